// The state directory: a saved machine reads back as it was written, a missing file means
// "learn", and every file that cannot be trusted is refused with its name and the reason.
#include "daemon/machine_state_store.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <cstdlib>
#include <filesystem>
#include <fstream>

namespace gearpath::daemon {
namespace {

class MachineStateStoreTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = std::filesystem::temp_directory_path() /
           ("gearpathd_state_" + std::to_string(getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    std::filesystem::remove_all(dir_);
  }
  void TearDown() override {
    std::error_code ec;
    std::filesystem::permissions(dir_, std::filesystem::perms::owner_all, ec);
    std::filesystem::remove_all(dir_, ec);
  }

  static SavedMachine Sample(const std::string& id) {
    SavedMachine m;
    m.machine_id = id;
    m.saved_at_ns = 1'700'000'000'123'456'789;
    m.counters.received = 12;
    m.counters.processed = 10;
    m.counters.rejected = 2;
    m.counters.lost = 1;
    m.counters.rejected_by_reason["non_finite"] = 2;
    m.counters.not_judged[static_cast<std::size_t>(NotJudgedCause::kSpeedOutside)] = 4;
    LearnedState& s = m.learned;
    s.fingerprint = 0xfedcba9876543210ULL;
    s.learning = false;
    s.indicator_baseline.blocks = 3;
    s.indicator_baseline.indicators = 2;
    s.indicator_baseline.count = 3;
    s.indicator_baseline.relative_floor = 0.05;
    s.indicator_baseline.absolute_floor = 1e-12;
    s.indicator_baseline.log_value_floor = 1e-300;
    s.indicator_baseline.median = {0.1 + 0.2, -690.7755278982137};  // not exact in decimal
    s.indicator_baseline.scale = {1.0 / 3.0, 0.048790164169432};
    s.indicator_baseline.log_transform = {true, false};
    s.alarm.state = FaultState::kAlarm;
    s.alarm.exceed_bits = 0b10110;
    s.alarm.votes = {2, 2, 1};
    s.group_excess_sum = {3.5, 0.0};
    s.mesh_evidence_sum = {0.0, 0.0, 0.0, 0.0, 1.25, 0.75, 0.0, 0.0};
    return m;
  }

  std::filesystem::path dir_;
};

TEST_F(MachineStateStoreTest, ASavedMachineReadsBackBitForBit) {
  auto store = MachineStateStore::Open(dir_.string());
  ASSERT_TRUE(store.ok()) << store.error();
  const SavedMachine saved = Sample("gb-1");
  ASSERT_TRUE(store->Save(saved).ok());
  auto loaded = store->Load("gb-1");
  ASSERT_TRUE(loaded.ok()) << loaded.error();
  ASSERT_TRUE(loaded->has_value());
  const SavedMachine& m = **loaded;
  EXPECT_EQ(m.saved_at_ns, saved.saved_at_ns);
  EXPECT_EQ(m.counters.processed, 10u);
  EXPECT_EQ(m.counters.rejected_by_reason.at("non_finite"), 2u);
  EXPECT_EQ(m.counters.not_judged, saved.counters.not_judged);
  EXPECT_EQ(m.learned.fingerprint, saved.learned.fingerprint);
  EXPECT_EQ(m.learned.indicator_baseline.median, saved.learned.indicator_baseline.median);
  EXPECT_EQ(m.learned.indicator_baseline.scale, saved.learned.indicator_baseline.scale);
  EXPECT_EQ(m.learned.alarm.state, FaultState::kAlarm);
  EXPECT_EQ(m.learned.alarm.exceed_bits, 0b10110u);
  EXPECT_EQ(m.learned.alarm.votes, (std::vector<int>{2, 2, 1}));
  EXPECT_EQ(m.learned.group_excess_sum, saved.learned.group_excess_sum);
  EXPECT_EQ(m.learned.mesh_evidence_sum, saved.learned.mesh_evidence_sum);
  // No temporary file is left behind.
  int files = 0;
  for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir_)) ++files;
  EXPECT_EQ(files, 1);
}

TEST_F(MachineStateStoreTest, AMachineWithoutAFileHasNothingToResume) {
  auto store = MachineStateStore::Open(dir_.string());
  ASSERT_TRUE(store.ok());
  auto loaded = store->Load("never-saved");
  ASSERT_TRUE(loaded.ok()) << loaded.error();
  EXPECT_FALSE(loaded->has_value());
}

TEST_F(MachineStateStoreTest, IdsThatAreNotFileNamesStayInsideTheDirectory) {
  auto store = MachineStateStore::Open(dir_.string());
  ASSERT_TRUE(store.ok());
  for (const std::string id : {"../../etc/passwd", ".hidden", "a/b", "plant 3: gb#2"}) {
    const std::filesystem::path p = store->PathOf(id);
    EXPECT_EQ(p.parent_path(), dir_) << id;
    EXPECT_NE(p.filename().string().front(), '.') << id;
    ASSERT_TRUE(store->Save(Sample(id)).ok()) << id;
    auto loaded = store->Load(id);
    ASSERT_TRUE(loaded.ok() && loaded->has_value()) << id;
    EXPECT_EQ((*loaded)->machine_id, id);
  }
  EXPECT_NE(store->PathOf("a/b"), store->PathOf("a%2Fb"));
}

TEST_F(MachineStateStoreTest, FilesThatCannotBeTrustedAreRefusedWithTheirName) {
  auto store = MachineStateStore::Open(dir_.string());
  ASSERT_TRUE(store.ok());
  const std::string path = store->PathOf("gb");
  auto refused = [&](const std::string& text, const std::string& why) {
    std::ofstream(path, std::ios::trunc) << text;
    auto loaded = store->Load("gb");
    ASSERT_FALSE(loaded.ok()) << text;
    EXPECT_NE(loaded.error().find(path), std::string::npos) << loaded.error();
    EXPECT_NE(loaded.error().find(why), std::string::npos) << loaded.error();
  };
  refused("{\"format\": \"gearpathd-machine-state\", \"vers", "line 1");  // torn
  refused("[1, 2]", "not a gearpathd machine state");
  refused(R"({"format": "gearpathd-machine-state", "version": 99})", "version 99");
  ASSERT_TRUE(store->Save(Sample("other")).ok());
  std::filesystem::copy_file(store->PathOf("other"), path,
                             std::filesystem::copy_options::overwrite_existing);
  refused(std::string(std::istreambuf_iterator<char>(std::ifstream(path).rdbuf()), {}),
          "holds machine \"other\"");
  refused(std::string(100'000, '[') + std::string(100'000, ']'), "line 1");  // nesting bomb
}

// The not-judged counts came after the first states were saved: a file without them loads
// with none, a cause this build does not know is dropped, and a count that is no count is
// refused by name.
TEST_F(MachineStateStoreTest, NotJudgedCountsAreOptionalButMustBeCounts) {
  auto store = MachineStateStore::Open(dir_.string());
  ASSERT_TRUE(store.ok());
  ASSERT_TRUE(store->Save(Sample("gb")).ok());
  const std::string path = store->PathOf("gb");
  const auto good = nlohmann::json::parse(std::ifstream(path));
  ASSERT_EQ(good["counters"]["not_judged"], nlohmann::json::parse(R"({"speed_outside": 4})"));
  auto load_with = [&](const nlohmann::json& j) {
    std::ofstream(path, std::ios::trunc) << j.dump();
    return store->Load("gb");
  };
  auto older = good;
  older["counters"].erase("not_judged");
  auto loaded = load_with(older);
  ASSERT_TRUE(loaded.ok()) << loaded.error();
  EXPECT_EQ((*loaded)->counters.not_judged, (decltype((*loaded)->counters.not_judged){}));
  auto later = good;
  later["counters"]["not_judged"]["torque_sensor_failed"] = 9;
  loaded = load_with(later);
  ASSERT_TRUE(loaded.ok()) << loaded.error();
  EXPECT_EQ((*loaded)->counters.not_judged[static_cast<std::size_t>(NotJudgedCause::kSpeedOutside)],
            4u);
  auto bad = good;
  bad["counters"]["not_judged"]["load_outside"] = -1;
  loaded = load_with(bad);
  ASSERT_FALSE(loaded.ok());
  EXPECT_NE(loaded.error().find("load_outside: not a count"), std::string::npos) << loaded.error();
}

TEST_F(MachineStateStoreTest, ADirectoryThatCannotBeWrittenIsRefusedAtOpen) {
  if (geteuid() == 0) {
    // root writes anywhere; a file where the directory should be is refused for everyone.
    std::filesystem::create_directories(dir_.parent_path());
    std::ofstream(dir_.string()) << "x";
    auto store = MachineStateStore::Open(dir_.string());
    ASSERT_FALSE(store.ok());
    EXPECT_NE(store.error().find(dir_.string()), std::string::npos) << store.error();
    std::filesystem::remove(dir_);
    return;
  }
  std::filesystem::create_directories(dir_);
  std::filesystem::permissions(dir_, std::filesystem::perms::owner_read);
  auto store = MachineStateStore::Open(dir_.string());
  ASSERT_FALSE(store.ok());
  EXPECT_NE(store.error().find("not writable"), std::string::npos) << store.error();
}

TEST(ResolveStateDirectoryTest, ConfigurationFirstThenTheFirstSystemdDirectory) {
  DaemonConfig config;
  ::setenv("STATE_DIRECTORY", "/var/lib/gearpathd:/var/lib/other", 1);
  EXPECT_EQ(ResolveStateDirectory(config), "/var/lib/gearpathd");
  config.state_directory = "/srv/state";
  EXPECT_EQ(ResolveStateDirectory(config), "/srv/state");
  ::unsetenv("STATE_DIRECTORY");
  config.state_directory.clear();
  EXPECT_EQ(ResolveStateDirectory(config), "");
}

}  // namespace
}  // namespace gearpath::daemon

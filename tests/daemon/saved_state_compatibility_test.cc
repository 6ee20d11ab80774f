// A machine state file outlives the build that saved it: a state saved before the learned
// state's fingerprint moved to version 2 (core/pipeline/learned_state.h) still resumes, and is
// saved again under version 2. The truth is a file an earlier build wrote, not a fingerprint
// this build computes: tests/data/state/fingerprint_v1.state.json, a frozen copy of the seed that
// fuzz_machine_state saved on 2026-11-29 (the seeds themselves may be made again by a later
// build; this copy must not be).
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>

#include "core/pipeline/block_processor.h"
#include "daemon/daemon_config.h"
#include "daemon/machine_setup_builder.h"
#include "daemon/machine_state_store.h"
#include "tests/fuzz/machine_state_machine.h"

namespace gearpath::daemon {
namespace {

namespace fs = std::filesystem;

class SavedStateCompatibility : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("gearpathd_compat_" + std::to_string(getpid()));
    fs::remove_all(dir_);
    auto config = ParseDaemonConfig(kMachineStateConfig, "test");
    ASSERT_TRUE(config.ok()) << config.error();
    auto setup = BuildMachineSetup(config->machines.front());
    ASSERT_TRUE(setup.ok()) << setup.error();
    auto processor = BlockProcessor::Create(std::move(setup.value()));
    ASSERT_TRUE(processor.ok()) << processor.error();
    processor_.emplace(std::move(processor.value()));
    auto store = MachineStateStore::Open(dir_.string());
    ASSERT_TRUE(store.ok()) << store.error();
    store_.emplace(std::move(store.value()));
  }
  void TearDown() override { fs::remove_all(dir_); }

  // The seed file as the earlier build saved it, read as gearpathd reads it at a start.
  SavedMachine SavedByTheEarlierBuild() {
    fs::copy_file(fs::path(GEARPATH_TEST_DATA_DIR) / "state/fingerprint_v1.state.json",
                  store_->PathOf("fuzz"), fs::copy_options::overwrite_existing);
    auto saved = store_->Load("fuzz");
    EXPECT_TRUE(saved.ok()) << saved.error();
    EXPECT_TRUE(saved.ok() && saved.value().has_value());
    return saved.ok() && saved.value() ? *saved.value() : SavedMachine{};
  }

  fs::path dir_;
  std::optional<BlockProcessor> processor_;
  std::optional<MachineStateStore> store_;
};

TEST_F(SavedStateCompatibility,
       AStateSavedUnderTheFirstFingerprintResumesAndIsSavedUnderTheSecond) {
  const SavedMachine saved = SavedByTheEarlierBuild();
  // The earlier build's fingerprint is not this build's ...
  ASSERT_NE(saved.learned.fingerprint, processor_->learned_state_fingerprint());
  // ... and the baseline it vouches for is resumed all the same.
  const Status imported = processor_->ImportLearnedState(saved.learned);
  ASSERT_TRUE(imported.ok()) << imported.error();
  EXPECT_EQ(processor_->baseline_blocks_learned(), 3);
  const LearnedState again = processor_->ExportLearnedState();
  EXPECT_EQ(again.fingerprint, processor_->learned_state_fingerprint());
  auto fresh = BlockProcessor::Create(processor_->setup());
  ASSERT_TRUE(fresh.ok()) << fresh.error();
  EXPECT_TRUE(fresh->ImportLearnedState(again).ok());
}

TEST_F(SavedStateCompatibility, AStateWhoseFingerprintIsNeitherVersionIsRefused) {
  SavedMachine saved = SavedByTheEarlierBuild();
  saved.learned.fingerprint ^= 1;  // one bit of a re-measured FRF set, say
  const Status imported = processor_->ImportLearnedState(saved.learned);
  ASSERT_FALSE(imported.ok());
  EXPECT_NE(imported.error().find("measured something else"), std::string::npos)
      << imported.error();
  EXPECT_EQ(processor_->baseline_blocks_learned(), 0);
}

}  // namespace
}  // namespace gearpath::daemon

// Machines on one FRF set share its matrix and per-shape operators (SharedFrfOperators), and
// judge exactly as machines that own theirs.
#include "core/pipeline/shared_frf_operators.h"

#include <gtest/gtest.h>

#include <memory>
#include <thread>
#include <vector>

#include "tests/core/pipeline/simulated_machine.h"

namespace gearpath {
namespace {
using namespace gearpath::testing;

std::shared_ptr<SharedFrfOperators> SharedOf(const Machine& m) {
  return std::make_shared<SharedFrfOperators>(std::make_shared<const FrfMatrix>(m.frf.decoupled));
}

BlockProcessor Make(const Machine& m, std::shared_ptr<SharedFrfOperators> shared) {
  MachineSetup s = MakeSetup(m);
  s.shared_frf = std::move(shared);
  auto p = BlockProcessor::Create(std::move(s));
  EXPECT_TRUE(p.ok()) << p.error();
  return std::move(p.value());
}

TEST(SharedFrfOperatorsTest, TwoMachinesOnOneSetShareOneOperatorAndJudgeAsAPrivateOne) {
  const Machine& m = Table1Machine();
  auto shared = SharedOf(m);
  BlockProcessor a = Make(m, shared);
  BlockProcessor b = Make(m, shared);
  BlockProcessor own = Make(m, nullptr);
  ASSERT_TRUE(a.Prepare(kBlock));
  ASSERT_TRUE(b.Prepare(kBlock));
  EXPECT_EQ(shared->mappings_built(), 1u);
  EXPECT_EQ(shared->operators_built(), 1u);
  EXPECT_EQ(a.setup().shared_frf.get(), b.setup().shared_frf.get());
  EXPECT_EQ(a.setup().frf_set.decoupled.bins(), 0);  // the machine's own copy is gone
  // Learning, then a fracture on G1 that the alarm model must name, through all three.
  GearboxSimulator healthy = MakeSimulator(m, FaultType::kNone, "", 7);
  GearboxSimulator faulty = MakeSimulator(m, FaultType::kToothFracture, "G1", 5);
  AccelBlock block;
  BlockResult ra, rb, ro;
  for (int i = 0; i < kBaselineBlocks + 5; ++i) {
    (i < kBaselineBlocks ? healthy : faulty).NextBlock(block);
    block.sequence = static_cast<std::uint64_t>(i);
    ASSERT_TRUE(a.Process(block.view(), ra).accepted());
    ASSERT_TRUE(b.Process(block.view(), rb).accepted());
    ASSERT_TRUE(own.Process(block.view(), ro).accepted());
    ExpectSameResult(ra, ro);
    ExpectSameResult(rb, ro);
  }
  EXPECT_EQ(ro.verdict.state, FaultState::kAlarm);
  EXPECT_EQ(shared->operators_built(), 1u);
}

TEST(SharedFrfOperatorsTest, MachinesOnOneSetAndShapeHoldOneFrfPowerTable) {
  // The |H|^2 and H tables of the identification pass, the path energies and the
  // contributions (paths x channels x in-range bins) depend only on the set and the block
  // shape: built once, held by every machine (23 MB each at the reference workload otherwise).
  const Machine& m = Table1Machine();
  auto shared = SharedOf(m);
  BlockProcessor a = Make(m, shared);
  BlockProcessor b = Make(m, shared);
  ASSERT_TRUE(a.Prepare(kBlock));
  ASSERT_TRUE(b.Prepare(kBlock));
  EXPECT_EQ(shared->power_tables_built(), 1u);
  auto table = shared->Power(kBlock, kFs);
  ASSERT_TRUE(table.ok()) << table.error();
  EXPECT_EQ(shared->power_tables_built(), 1u);
  // Held by the shared entry, both machines' workspaces and this test: one instance.
  EXPECT_EQ(table->use_count(), 4);
  const FrfPowerTable& t = **table;
  EXPECT_EQ(t.paths, 3u);
  EXPECT_EQ(t.channels, 3u);
  EXPECT_EQ(t.power.size(), t.paths * t.channels * t.bins);
  EXPECT_EQ(t.response.size(), t.paths * t.channels * t.bins);
  // Another block shape is another table.
  ASSERT_TRUE(a.Prepare(kBlock / 2));
  EXPECT_EQ(shared->power_tables_built(), 2u);
}

TEST(SharedFrfOperatorsTest, OtherIdentificationOptionsGetTheirOwnOperator) {
  const Machine& m = Table1Machine();
  auto shared = SharedOf(m);
  MachineSetup s = MakeSetup(m);
  s.shared_frf = shared;
  s.options.identification.iterations = 3;
  auto other = BlockProcessor::Create(std::move(s));
  ASSERT_TRUE(other.ok()) << other.error();
  BlockProcessor a = Make(m, shared);
  ASSERT_TRUE(a.Prepare(kBlock));
  ASSERT_TRUE(other->Prepare(kBlock));
  EXPECT_EQ(shared->mappings_built(), 1u);  // the grid mapping does not depend on them
  EXPECT_EQ(shared->operators_built(), 2u);
}

TEST(SharedFrfOperatorsTest, ASetupWhoseMatrixIsNotTheSharedOneIsRefused) {
  const Machine& m = Table1Machine();
  MachineSetup s = MakeSetup(m);
  s.shared_frf = SharedOf(m);
  s.frf_set.decoupled.at[3](0, 0) += Complex(1e-9, 0.0);
  const auto p = BlockProcessor::Create(std::move(s));
  ASSERT_FALSE(p.ok());
  EXPECT_EQ(p.error(),
            "machine 'sim': the shared FRF operators were built from another decoupled FRF "
            "matrix");
}

TEST(SharedFrfOperatorsTest, MachinesPreparedAndRunOnSeveralThreadsBuildTheOperatorOnce) {
  // What the daemon does: prepare in parallel, then process on worker threads (TSan target).
  const Machine& m = Table1Machine();
  auto shared = SharedOf(m);
  std::vector<BlockProcessor> machines;
  for (int i = 0; i < 4; ++i) machines.push_back(Make(m, shared));
  std::vector<std::thread> threads;
  std::vector<BlockResult> last(machines.size());
  for (std::size_t i = 0; i < machines.size(); ++i) {
    threads.emplace_back([&, i] {
      EXPECT_TRUE(machines[i].Prepare(kBlock));
      GearboxSimulator sim = MakeSimulator(m, FaultType::kNone, "", 11);
      AccelBlock block;
      for (std::uint64_t k = 0; k < 3; ++k) {
        sim.NextBlock(block);
        block.sequence = k;
        EXPECT_TRUE(machines[i].Process(block.view(), last[i]).accepted());
      }
    });
  }
  for (auto& t : threads) t.join();
  EXPECT_EQ(shared->operators_built(), 1u);
  for (std::size_t i = 1; i < machines.size(); ++i) ExpectSameResult(last[i], last[0]);
}

}  // namespace
}  // namespace gearpath

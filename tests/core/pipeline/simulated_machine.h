// The simulated Table-1 gearbox of the pipeline tests: model, gear train, its model FRF set on
// the block's bin grid, a processor set-up and block helpers.
#pragma once

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <utility>

#include "core/diagnosis/train_layout.h"
#include "core/model/gear_train.h"
#include "core/model/lumped_gearbox_model.h"
#include "core/pipeline/block_processor.h"
#include "core/simulation/gearbox_simulator.h"
#include "core/simulation/model_frf_set.h"

namespace gearpath::testing {

constexpr std::uint32_t kBlock = 8192;
constexpr double kFs = 8000.0;
constexpr int kBaselineBlocks = 6;

struct Machine {
  LumpedGearboxModel model;
  GearTrain train;
  FrfSet frf;
};

// Table 1 (distinct = false) or a variant whose G3 has 30 teeth, so the output shaft turns at
// 10 * 28/40 * 30/34 = 6.18 Hz and no two gears share both a mesh and a shaft rate.
inline Machine MakeMachine(bool distinct) {
  GearboxParameters p = Table1Parameters();
  GearTrain train = GearTrain::Table1();
  if (distinct) {
    p.stages[1].z_driver = 30;
    for (GearSpec& g : train.gears) {
      if (g.name == "G3") g.teeth = 30;
    }
  }
  auto model = LumpedGearboxModel::Create(p);
  EXPECT_TRUE(model.ok()) << model.error();
  // FRF grid = the block's bins 1..N/2 (the mapping is then a copy; interpolation is tested
  // in frf_grid_mapping_test.cc).
  Eigen::VectorXd f(kBlock / 2);
  for (Eigen::Index k = 0; k < f.size(); ++k) f[k] = static_cast<double>(k + 1) * kFs / kBlock;
  auto set = MakeModelFrfSet(model.value(), train, f);
  EXPECT_TRUE(set.ok()) << set.error();
  return {std::move(model.value()), train, std::move(set.value())};
}

inline MachineSetup MakeSetup(const Machine& m) {
  MachineSetup s;
  s.machine_id = "sim";
  s.frf_set = m.frf;
  auto layout = TrainLayoutFromGearTrain(m.train);
  EXPECT_TRUE(layout.ok()) << layout.error();
  s.train = layout.value();
  s.options.sample_rate_hz = kFs;
  s.options.nominal_speed_hz = 10.0;
  s.options.baseline_blocks = kBaselineBlocks;
  return s;
}

inline GearboxSimulator MakeSimulator(const Machine& m, FaultType type, const std::string& gear,
                               std::uint64_t seed, bool report_speed = true,
                               std::uint32_t block_length = kBlock,
                               double input_speed_hz = 10.0) {
  SimulatorConfig c;
  c.machine_id = "sim";
  c.fault.type = type;
  c.fault.gear = gear;
  c.sample_rate_hz = kFs;
  c.block_length = block_length;
  c.input_speed_hz = input_speed_hz;
  c.noise_relative = 0.05;
  c.seed = seed;
  c.report_speed = report_speed;
  c.include_housing_channel = false;  // channels p1..p3 = the Eq. 22 FRF rows
  auto sim = GearboxSimulator::Create(m.model, m.train, c);
  EXPECT_TRUE(sim.ok()) << sim.error();
  return std::move(sim.value());
}

// Feeds `count` blocks; returns the last result.
inline BlockResult RunBlocks(BlockProcessor& p, GearboxSimulator& sim, int count,
                             std::uint64_t& sequence, double load = 0.0) {
  AccelBlock block;
  BlockResult result;
  for (int i = 0; i < count; ++i) {
    sim.NextBlock(block);
    block.sequence = sequence++;
    block.load = load;  // AccelBlock::load; 0: not carried
    const ProcessOutcome o = p.Process(block.view(), result);
    EXPECT_TRUE(o.accepted()) << o.message.view();
  }
  return result;
}

inline BlockProcessor LearnedProcessor(const Machine& m, std::uint64_t& sequence,
                                      bool transient_gate = true) {
  MachineSetup setup = MakeSetup(m);
  setup.options.transient_gate = transient_gate;
  auto p = BlockProcessor::Create(setup);
  EXPECT_TRUE(p.ok()) << p.error();
  GearboxSimulator healthy = MakeSimulator(m, FaultType::kNone, "", 7);
  const BlockResult r = RunBlocks(p.value(), healthy, kBaselineBlocks, sequence);
  EXPECT_EQ(r.verdict.state, FaultState::kLearning);
  EXPECT_EQ(p->baseline_blocks_learned(), kBaselineBlocks);
  return std::move(p.value());
}

inline const Machine& Table1Machine() {
  static const Machine m = MakeMachine(false);
  return m;
}

// Every published figure of two results, exactly (same inputs, same operations: the same bits).
inline void ExpectSameResult(const BlockResult& a, const BlockResult& b,
                             const std::string& where = "") {
  SCOPED_TRACE(where);
  EXPECT_EQ(a.sequence, b.sequence);
  EXPECT_EQ(a.speed_hz, b.speed_hz);
  EXPECT_EQ(a.dominant_path, b.dominant_path);
  EXPECT_EQ(a.indicator_channel, b.indicator_channel);
  ASSERT_EQ(a.paths.size(), b.paths.size());
  for (std::size_t i = 0; i < a.paths.size(); ++i) {
    EXPECT_EQ(a.paths[i].energy, b.paths[i].energy) << "path " << i;
    EXPECT_EQ(a.paths[i].share, b.paths[i].share) << "path " << i;
    EXPECT_EQ(a.paths[i].criterion, b.paths[i].criterion) << "path " << i;
  }
  for (const auto& [x, y] : {std::pair{&a.raw_band, &b.raw_band},
                             std::pair{&a.reconstructed_band, &b.reconstructed_band}}) {
    EXPECT_EQ(x->centre_hz, y->centre_hz);
    EXPECT_EQ(x->width_hz, y->width_hz);
    EXPECT_EQ(x->level, y->level);
    EXPECT_EQ(x->kurtosis, y->kurtosis);
    EXPECT_EQ(x->significant, y->significant);
  }
  ASSERT_EQ(a.shafts.size(), b.shafts.size());
  for (std::size_t i = 0; i < a.shafts.size(); ++i) {
    EXPECT_EQ(a.shafts[i].raw, b.shafts[i].raw) << "shaft " << i;
    EXPECT_EQ(a.shafts[i].reconstructed, b.shafts[i].reconstructed) << "shaft " << i;
    EXPECT_EQ(a.shafts[i].raw_harmonics, b.shafts[i].raw_harmonics) << "shaft " << i;
    EXPECT_EQ(a.shafts[i].reconstructed_harmonics, b.shafts[i].reconstructed_harmonics);
    EXPECT_EQ(a.shafts[i].raw_threshold, b.shafts[i].raw_threshold) << "shaft " << i;
  }
  ASSERT_EQ(a.condition.size(), b.condition.size());
  for (std::size_t i = 0; i < a.condition.size(); ++i) {
    const BlockConditionIndicators& x = a.condition[i];
    const BlockConditionIndicators& y = b.condition[i];
    EXPECT_EQ(x.revolutions, y.revolutions) << "set " << i;
    EXPECT_EQ(x.score, y.score) << "set " << i;
    ASSERT_EQ(x.value.size(), y.value.size());
    for (std::size_t k = 0; k < x.value.size(); ++k) {
      EXPECT_EQ(x.value[k], y.value[k]) << "set " << i << " value " << k;
      EXPECT_EQ(x.z[k], y.z[k]) << "set " << i << " z " << k;
    }
  }
  EXPECT_EQ(a.score.score, b.score.score);
  EXPECT_EQ(a.score.limit_z, b.score.limit_z);
  EXPECT_EQ(a.score.exceed_count, b.score.exceed_count);
  EXPECT_EQ(a.localisation.group, b.localisation.group);
  EXPECT_EQ(a.localisation.shaft_evidence, b.localisation.shaft_evidence);
  EXPECT_EQ(a.localisation.shaft_evidence_accumulated, b.localisation.shaft_evidence_accumulated);
  EXPECT_EQ(a.localisation.mesh_evidence, b.localisation.mesh_evidence);
  EXPECT_EQ(a.localisation.signature_excess, b.localisation.signature_excess);
  EXPECT_EQ(a.verdict.state, b.verdict.state);
  EXPECT_EQ(a.verdict.gear, b.verdict.gear);
  EXPECT_EQ(a.verdict.gear_name, b.verdict.gear_name);
  EXPECT_EQ(a.verdict.confidence, b.verdict.confidence);
  EXPECT_EQ(a.verdict.candidates, b.verdict.candidates);
  EXPECT_EQ(a.regularisation.alpha_median, b.regularisation.alpha_median);
  EXPECT_EQ(a.regularisation.condition_max, b.regularisation.condition_max);
  EXPECT_EQ(a.regularisation.relative_residual, b.regularisation.relative_residual);
}

}  // namespace gearpath::testing

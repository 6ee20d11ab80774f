// PlantSimulator against independent truth: lines where the kinematics put them, the response
// equal to the plant's transfer times the TE spectrum computed here from the excitation, fault
// content on the faulty shaft's harmonics, steady state across blocks, determinism.
#include "core/evaluation/plant_simulator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include "core/dsp/fft_plan.h"
#include "core/evaluation/plant_family.h"

namespace gearpath {
namespace {

constexpr double kFs = 8000.0;
constexpr std::uint32_t kBlock = 8000;  // 1 Hz bins: every line at 10 Hz input falls on a bin
constexpr double kSpeedHz = 10.0;

// One-sided complex spectrum (amplitude-scaled: a cosine of amplitude A gives |X| = A).
std::vector<std::complex<double>> Spectrum(const Eigen::VectorXd& x) {
  const std::size_t n = static_cast<std::size_t>(x.size());
  Result<FftPlan> plan = FftPlan::Create(FftKind::kRealToComplex, n);
  EXPECT_TRUE(plan.ok());
  for (std::size_t i = 0; i < n; ++i) plan->real_in()[i] = x[static_cast<Eigen::Index>(i)];
  plan->Execute();
  std::vector<std::complex<double>> out(n / 2 + 1);
  for (std::size_t k = 0; k < out.size(); ++k) {
    out[k] = plan->complex_out()[k] * (k == 0 ? 1.0 : 2.0) / static_cast<double>(n);
  }
  return out;
}

// The same, only at the requested bins (a direct DFT: independent of the simulator's FFTW).
std::complex<double> Bin(const Eigen::VectorXd& x, int k) {
  const auto n = static_cast<double>(x.size());
  std::complex<double> acc = 0.0;
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    acc += x[i] * std::polar(1.0, -2.0 * std::numbers::pi * k * static_cast<double>(i) / n);
  }
  return acc * 2.0 / n;
}

struct Rig {
  Plant plant;
  PlantSimulator sim;
};

Rig MakeRig(PlantFamily family, PlantFaultKind fault, const std::string& gear,
            double eccentricity = 0.0, std::uint64_t seed = 3) {
  Result<Plant> plant =
      MakePlant({family, TrainVariant::kTable1, ChannelSet::kSeatsAndHousing, seed});
  EXPECT_TRUE(plant.ok()) << plant.error();
  PlantExcitationConfig ec;
  ec.fault = fault;
  ec.faulty_gear = gear;
  ec.seed = seed;
  ec.eccentricity_depth = eccentricity;
  Result<PlantExcitation> ex = PlantExcitation::Create(plant->train, ec);
  EXPECT_TRUE(ex.ok()) << ex.error();
  PlantSimulatorConfig sc;
  sc.sample_rate_hz = kFs;
  sc.block_length = kBlock;
  sc.input_speed_hz = kSpeedHz;
  sc.noise_relative = 0.0;
  sc.seed = seed;
  Result<PlantSimulator> sim =
      PlantSimulator::Create(plant->dynamics, plant->channels, std::move(ex).value(), sc);
  EXPECT_TRUE(sim.ok()) << sim.error();
  return {std::move(plant).value(), std::move(sim).value()};
}

bool MeshHarmonicBin(int k) {
  for (int h = 1; h <= 4; ++h) {
    if (k == 280 * h || k == 238 * h) return true;
  }
  return false;
}

// Fraction of the energy of `x` at bins that are multiples of `step` Hz.
double EnergyOnGrid(const std::vector<std::complex<double>>& x, int step) {
  double on = 0.0, all = 0.0;
  for (std::size_t k = 1; k < x.size(); ++k) {
    const double e = std::norm(x[k]);
    all += e;
    if (k % static_cast<std::size_t>(step) == 0) on += e;
  }
  return all > 0.0 ? on / all : 0.0;
}

TEST(PlantSimulator, HealthyNoiseFreeHasLinesOnlyAtTheMeshHarmonics) {
  for (PlantFamily family : {PlantFamily::kLumpedPerturbed, PlantFamily::kModalHousing}) {
    Rig rig = MakeRig(family, PlantFaultKind::kNone, "");
    Eigen::MatrixXd a, b;
    rig.sim.NoiseFree(5 * kBlock, false, a);
    rig.sim.NoiseFree(6 * kBlock, false, b);
    for (Eigen::Index c = 0; c < a.cols(); ++c) {
      const auto sa = Spectrum(a.col(c));
      const auto sb = Spectrum(b.col(c));
      double on = 0.0, off = 0.0;
      for (std::size_t k = 1; k < sa.size(); ++k) {
        (MeshHarmonicBin(static_cast<int>(k)) ? on : off) += std::norm(sa[k]);
      }
      EXPECT_LT(off, 1e-12 * on) << PlantFamilyName(family) << " channel " << c;
      // Steady state: the next block has identical lines (a whole number of mesh periods).
      for (int k : {280, 238, 560, 476}) {
        EXPECT_NEAR(std::abs(sb[k]), std::abs(sa[k]), 1e-9 * std::abs(sa[k]) + 1e-15);
      }
    }
  }
}

TEST(PlantSimulator, ResponseIsThePlantTransferTimesTheTeSpectrum) {
  for (PlantFamily family : {PlantFamily::kLumpedTorsional, PlantFamily::kModalHousing}) {
    Rig rig = MakeRig(family, PlantFaultKind::kNone, "", 0.04);
    const std::int64_t first = 3 * kBlock;
    Eigen::MatrixXd acc;
    rig.sim.NoiseFree(first, false, acc);
    // TE of each stage sampled here from the excitation, at the same instants.
    const PlantExcitation& ex = rig.sim.excitation();
    Eigen::MatrixXd te(kBlock, ex.stage_count());
    for (int s = 0; s < ex.stage_count(); ++s) {
      for (std::uint32_t i = 0; i < kBlock; ++i) {
        te(i, s) = ex.Te(s, rig.sim.InputRevs(static_cast<double>(first + i)), false);
      }
    }
    for (int k : {280, 290, 238, 231, 245, 560, 476, 840, 952}) {
      Eigen::VectorXd f(1);
      f[0] = k;
      Result<FrfMatrix> t = rig.plant.dynamics->TeTransfer(f);
      ASSERT_TRUE(t.ok()) << t.error();
      Eigen::VectorXcd e(ex.stage_count());
      for (int s = 0; s < ex.stage_count(); ++s) e[s] = Bin(te.col(s), k);
      const Eigen::VectorXcd expected = t->at[0] * e;
      for (Eigen::Index c = 0; c < acc.cols(); ++c) {
        const std::complex<double> got = Bin(acc.col(c), k);
        EXPECT_LT(std::abs(got - expected[c]), 1e-7 * expected.norm())
            << PlantFamilyName(family) << " bin " << k << " channel " << c;
      }
    }
  }
}

TEST(PlantSimulator, TePulseAddsLinesAtTheFaultyShaftHarmonics) {
  // G1 turns at 10 Hz, G2 at 7 Hz: the fault's added content sits on that shaft's comb.
  for (const auto& [gear, rate] : {std::pair<std::string, int>{"G1", 10}, {"G2", 7}}) {
    Rig rig = MakeRig(PlantFamily::kLumpedPerturbed, PlantFaultKind::kTePulse, gear);
    Eigen::MatrixXd healthy, faulty;
    rig.sim.NoiseFree(2 * kBlock, false, healthy);
    rig.sim.NoiseFree(2 * kBlock, true, faulty);
    for (Eigen::Index c = 0; c < healthy.cols(); ++c) {
      const auto d = Spectrum(faulty.col(c) - healthy.col(c));
      // 1e-5: what folds back from above 4 fs (the TE is oversampled 4x, then band-limited);
      // sampling the sharp pulse at fs put 3 % of the energy off the 7 Hz comb.
      EXPECT_GT(EnergyOnGrid(d, rate), 1.0 - 1e-5) << gear << " channel " << c;
      // And it is not just the mesh lines: most of it lies off the mesh harmonics.
      double off_mesh = 0.0, total = 0.0;
      for (std::size_t k = 1; k < d.size(); ++k) {
        total += std::norm(d[k]);
        if (!MeshHarmonicBin(static_cast<int>(k))) off_mesh += std::norm(d[k]);
      }
      EXPECT_GT(off_mesh, 0.5 * total) << gear << " channel " << c;
    }
  }
}

TEST(PlantSimulator, MeshAmPutsSidebandsAroundItsOwnMeshAtTheFaultyShaftRate) {
  // Fault on G1 (stage 0, mesh 280 Hz, shaft 10 Hz), one mesh harmonic, no eccentricity, so
  // the healthy TE of stage 0 is the single line A cos(2 pi 280 t + phi) = Re(X e^{j 2 pi 280 t}),
  // X = its one-sided complex amplitude. A gain loss d w(t) repeating at 10 Hz, with Fourier
  // coefficients c_k = mean(w e^{-j 2 pi 10 k t}), puts on line 280 + 10 k the amplitude
  // -d (c_k X + c_{k + 56} conj(X)) (the second term: the negative-frequency half of the
  // carrier). Checked for k = +/-1, +/-2, and nothing on the other stage.
  PlantExcitationConfig ec;
  ec.fault = PlantFaultKind::kMeshAm;
  ec.faulty_gear = "G1";
  ec.seed = 3;
  ec.eccentricity_depth = 0.0;
  ec.mesh_harmonics = 1;
  Result<PlantExcitation> ex = PlantExcitation::Create(GearTrain::Table1(), ec);
  ASSERT_TRUE(ex.ok());
  const PlantFaultSeverity& sv = ex->severity();
  Eigen::VectorXd te_h(kBlock), te_f(kBlock), w(kBlock);
  for (std::uint32_t i = 0; i < kBlock; ++i) {
    const double revs = kSpeedHz * i / kFs;
    te_h[i] = ex->Te(0, revs, false);
    te_f[i] = ex->Te(0, revs, true);
    EXPECT_EQ(ex->Te(1, revs, true), ex->Te(1, revs, false));
    double u = revs - ex->fault_onset_revs();
    u -= std::floor(u);
    w[i] = TaperedWindow(28.0 * u, sv.am_length_periods, sv.am_taper);
  }
  auto coefficient = [&w](int k) { return 0.5 * Bin(w, 10 * k); };  // two-sided c_k
  const std::complex<double> x = Bin(te_h, 280);
  EXPECT_LT(std::abs(Bin(te_h, 290)), 1e-9 * std::abs(x));  // no healthy sideband
  for (int k : {-2, -1, 1, 2}) {
    const std::complex<double> c_k = k > 0 ? coefficient(k) : std::conj(coefficient(-k));
    const std::complex<double> expected =
        -sv.am_depth * (c_k * x + coefficient(k + 56) * std::conj(x));
    const std::complex<double> got = Bin(te_f, 280 + 10 * k);
    EXPECT_LT(std::abs(got - expected), 1e-6 * std::abs(expected)) << k;
    EXPECT_GT(std::abs(got), 0.003 * std::abs(x)) << k;  // a real sideband, ~1 % of the carrier
  }

  // Through the plant (all harmonics): the added content lies entirely on the 10 Hz comb.
  Rig rig = MakeRig(PlantFamily::kLumpedPerturbed, PlantFaultKind::kMeshAm, "G1");
  Eigen::MatrixXd healthy, faulty;
  rig.sim.NoiseFree(0, false, healthy);
  rig.sim.NoiseFree(0, true, faulty);
  for (Eigen::Index c = 0; c < healthy.cols(); ++c) {
    EXPECT_GT(EnergyOnGrid(Spectrum(faulty.col(c) - healthy.col(c)), 10), 1.0 - 1e-9) << c;
  }
}

TEST(PlantSimulator, BlocksAreBitIdenticalForTheSameSeed) {
  auto run = [](std::uint64_t seed) {
    Result<Plant> plant = MakePlant(
        {PlantFamily::kLumpedTorsional, TrainVariant::kDistinct, ChannelSet::kSeats, seed});
    PlantExcitationConfig ec;
    ec.fault = PlantFaultKind::kCombined;
    ec.faulty_gear = "G4";
    ec.seed = seed;
    PlantSimulatorConfig sc;
    sc.block_length = 1024;
    sc.input_speed_hz = 7.5;
    sc.tones = sc.bursts = sc.speed_drift = true;
    sc.noise_relative = 0.05;
    sc.seed = seed;
    Result<PlantSimulator> sim = PlantSimulator::Create(
        plant->dynamics, plant->channels, *PlantExcitation::Create(plant->train, ec), sc);
    std::vector<float> all;
    AccelBlock block;
    for (int b = 0; b < 3; ++b) {
      sim->NextBlock(b == 2, block);
      all.insert(all.end(), block.samples.begin(), block.samples.end());
    }
    return all;
  };
  const std::vector<float> a = run(42), b = run(42), c = run(43);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
}

TEST(PlantSimulator, BlocksCarryTheMeanSpeedWhileItDrifts) {
  Result<Plant> plant =
      MakePlant({PlantFamily::kLumpedPerturbed, TrainVariant::kTable1, ChannelSet::kSeats, 1});
  ASSERT_TRUE(plant.ok());
  PlantSimulatorConfig sc;
  sc.input_speed_hz = 5.0;
  sc.speed_drift = true;
  Result<PlantSimulator> sim = PlantSimulator::Create(
      plant->dynamics, plant->channels, *PlantExcitation::Create(plant->train, {}), sc);
  ASSERT_TRUE(sim.ok()) << sim.error();
  const double b = sc.block_length;
  for (int k = 0; k < 4; ++k) {
    // Whole-block mean speed = the reported speed.
    EXPECT_NEAR(sim->InputRevs((k + 1) * b) - sim->InputRevs(k * b), 5.0 * b / sc.sample_rate_hz,
                1e-9);
  }
  double lo = 1e9, hi = 0.0;
  for (int i = 0; i < 8192; i += 16) {
    const double speed = (sim->InputRevs(i + 1) - sim->InputRevs(i)) * sc.sample_rate_hz;
    lo = std::min(lo, speed);
    hi = std::max(hi, speed);
  }
  EXPECT_NEAR(hi / 5.0 - 1.0, 0.003, 2e-4);
  EXPECT_NEAR(lo / 5.0 - 1.0, -0.003, 2e-4);
  AccelBlock block;
  sim->NextBlock(false, block);
  EXPECT_EQ(block.speed_hz, 5.0);
  EXPECT_EQ(block.speed_source, SpeedSource::kAcquisition);
  EXPECT_EQ(block.channels.size(), 3u);
  EXPECT_EQ(block.channels[0].sensor, "p1");
}

TEST(PlantSimulator, NoiseHasTheRequestedLevel) {
  Result<Plant> plant =
      MakePlant({PlantFamily::kModalHousing, TrainVariant::kTable1, ChannelSet::kSeats, 9});
  PlantSimulatorConfig sc;
  sc.noise_relative = 0.10;
  sc.seed = 9;
  Result<PlantSimulator> sim = PlantSimulator::Create(
      plant->dynamics, plant->channels, *PlantExcitation::Create(plant->train, {}), sc);
  ASSERT_TRUE(sim.ok());
  Eigen::MatrixXd clean;
  sim->NoiseFree(0, false, clean);
  AccelBlock block;
  sim->NextBlock(false, block);
  for (Eigen::Index c = 0; c < clean.cols(); ++c) {
    double e = 0.0;
    for (std::uint32_t i = 0; i < sc.block_length; ++i) {
      const double d = block.samples[c * sc.block_length + i] - clean(i, c);
      e += d * d;
    }
    const double std = std::sqrt(e / sc.block_length);
    EXPECT_NEAR(std / sim->reference_rms()[c], 0.10, 0.005) << c;
  }
}

TEST(PlantSimulator, RejectsBadConfigByName) {
  Result<Plant> plant =
      MakePlant({PlantFamily::kLumpedPerturbed, TrainVariant::kTable1, ChannelSet::kSeats, 1});
  PlantSimulatorConfig sc;
  sc.segment_factor = 1;
  Result<PlantSimulator> sim = PlantSimulator::Create(
      plant->dynamics, plant->channels, *PlantExcitation::Create(plant->train, {}), sc);
  ASSERT_FALSE(sim.ok());
  EXPECT_NE(sim.error().find("segment_factor"), std::string::npos) << sim.error();
  sc = PlantSimulatorConfig{};
  sc.input_speed_hz = -1.0;
  sim = PlantSimulator::Create(plant->dynamics, plant->channels,
                               *PlantExcitation::Create(plant->train, {}), sc);
  ASSERT_FALSE(sim.ok());
  EXPECT_NE(sim.error().find("input_speed_hz"), std::string::npos) << sim.error();
}

}  // namespace
}  // namespace gearpath

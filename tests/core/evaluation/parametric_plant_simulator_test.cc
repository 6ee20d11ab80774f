// ParametricPlantSimulator (the parametric_plate family's time-domain stream), signal level:
// healthy lines at the mesh harmonics, and without eccentricity nowhere but on the meshes'
// grid; every tooth fault repeats once per revolution of its own gear's shaft; a crack adds sidebands at its gear's shaft rate around
// its mesh's harmonics, over many orders; missing material adds a comb of the shaft rate;
// severity normalisation reaches the target RMS change (or the caps); bit-identical streams;
// no jump at block boundaries; no blow-up at any matrix speed; the speed drift drives the
// input angle; cost per scenario.
#include "core/evaluation/parametric_plant_simulator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <map>
#include <numbers>

#include "core/dsp/fft_plan.h"
#include "core/evaluation/evaluation_runner.h"
#include "core/evaluation/parametric_plate_plant.h"
#include "core/evaluation/plant_family.h"
#include "core/evaluation/plant_simulator.h"
#include "core/evaluation/scenario_matrix.h"

namespace gearpath {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

struct Rig {
  ParametricPlatePlant plant;
  std::unique_ptr<ParametricPlantSimulator> sim;
};

// eccentric = false: every gear's runout and wobble removed (then the only periodicities are
// the meshes' and the fault's).
Rig MakeRig(std::uint64_t seed, PlantFaultKind kind, const std::string& gear,
            ParametricSimulatorConfig c, bool eccentric = true,
            const GearTrain& train = GearTrain::Table1()) {
  Result<ParametricPlatePlant> plant = DrawParametricPlatePlant(train, true, seed);
  EXPECT_TRUE(plant.ok()) << plant.error();
  if (!eccentric) {
    ParametricGearboxParameters p = plant->truth->parameters();
    for (MeshStage& st : p.stages) st.mesh.driver = st.mesh.driven = GearEccentricity{};
    plant->truth = std::make_shared<const ParametricGearbox>(ParametricGearbox::Create(p).value());
  }
  Result<ToothFault> fault = DrawToothFault(*plant, train, kind, gear, seed);
  EXPECT_TRUE(fault.ok()) << fault.error();
  Result<ParametricPlantSimulator> sim = ParametricPlantSimulator::Create(
      plant->truth, plant->channel_points, {{"p1"}, {"p2"}, {"p3"}, {"m1"}}, *fault, c);
  EXPECT_TRUE(sim.ok()) << sim.error();
  return {std::move(plant).value(),
          std::make_unique<ParametricPlantSimulator>(std::move(sim).value())};
}

// 10 Hz input, 8000-sample blocks: 1 Hz bins, every line of the Table 1 train on a bin (shafts
// 10 / 7 / 7 Hz, meshes 280 / 238 Hz).
ParametricSimulatorConfig OneHertzBins() {
  ParametricSimulatorConfig c;
  c.block_length = 8000;
  c.input_speed_hz = 10.0;
  c.noise_relative = 0.0;
  return c;
}

// Power per bin, one-sided (|X_k|^2 of amplitude-scaled X).
std::vector<double> Power(const Eigen::VectorXd& x) {
  const auto n = static_cast<std::size_t>(x.size());
  Result<FftPlan> plan = FftPlan::Create(FftKind::kRealToComplex, n);
  EXPECT_TRUE(plan.ok()) << plan.error();
  std::copy(x.data(), x.data() + x.size(), plan->real_in().begin());
  plan->Execute();
  std::vector<double> p(n / 2 + 1);
  for (std::size_t k = 0; k < p.size(); ++k) {
    p[k] = std::norm(plan->complex_out()[k] * 2.0 / static_cast<double>(n));
  }
  return p;
}

bool MeshHarmonic(std::size_t k) { return k > 0 && (k % 280 == 0 || k % 238 == 0); }

TEST(ParametricPlantSimulator, HealthyRunShowsLinesAtTheMeshHarmonics) {
  Rig rig = MakeRig(3, PlantFaultKind::kNone, "", OneHertzBins());
  Eigen::MatrixXd x;
  rig.sim->NoiseFreeNext(false, x);
  for (Eigen::Index c = 0; c < x.cols(); ++c) {
    const std::vector<double> p = Power(x.col(c));
    double total = 0.0, mesh = 0.0;
    std::size_t top = 1;
    for (std::size_t k = 1; k < p.size(); ++k) {
      total += p[k];
      if (MeshHarmonic(k)) mesh += p[k];
      if (p[k] > p[top]) top = k;
    }
    EXPECT_TRUE(MeshHarmonic(top)) << "channel " << c << ": largest line at " << top << " Hz";
    EXPECT_GT(mesh / total, 0.5) << c;
    // Eccentricity: first-order shaft-rate sidebands, small against the carrier.
    for (std::size_t k : {270u, 290u, 273u, 287u}) {
      EXPECT_GT(p[k], 1e-8 * p[280]) << c << " " << k;
      EXPECT_LT(p[k], 1e-2 * p[280]) << c << " " << k;
    }
  }
}

// Without eccentricity a healthy gearbox has two periodic excitations only, the meshes (280
// and 238 Hz at 10 Hz input): its steady state lies on a x 280 + b x 238 Hz, i.e. on the 14 Hz
// grid (their gcd), mostly on the meshes' own harmonics (the rest is their intermodulation
// through the shared intermediate shaft), and carries nothing at the shaft rates off that grid
// (10 Hz input, 7 Hz intermediate and output). What leaves the grid is the integrator's time
// discretisation (the stiffness sampled every step, off any common period): ~2e-8 of the
// energy at 8x oversampling, 1e-2 of that at 16x. With the eccentricity back on, the
// shaft-rate lines appear (~1e-2 of the energy): the check can see them.
double OffGridShare(bool eccentric, std::uint32_t oversampling, double* mesh_share) {
  ParametricSimulatorConfig c = OneHertzBins();
  c.oversampling = oversampling;
  Rig rig = MakeRig(3, PlantFaultKind::kNone, "", c, eccentric);
  AccelBlock first;
  rig.sim->NextBlock(false, first);  // the second block: 1.5 s after the start at rest
  Eigen::MatrixXd x;
  rig.sim->NoiseFreeNext(false, x);
  double worst = 0.0;
  *mesh_share = 1.0;
  for (Eigen::Index ch = 0; ch < x.cols(); ++ch) {
    const std::vector<double> p = Power(x.col(ch));
    double total = 0.0, off = 0.0, mesh = 0.0;
    for (std::size_t k = 1; k < p.size(); ++k) {
      total += p[k];
      if (k % 14 != 0) off += p[k];
      if (MeshHarmonic(k)) mesh += p[k];
    }
    if (!eccentric) {
      for (std::size_t k : {7u, 10u, 20u, 231u, 245u, 270u, 273u, 287u, 290u}) {
        EXPECT_LT(p[k], 1e-10 * p[280]) << "channel " << ch << ", " << k << " Hz";
      }
    }
    worst = std::max(worst, off / total);
    *mesh_share = std::min(*mesh_share, mesh / total);
  }
  return worst;
}

TEST(ParametricPlantSimulator, HealthySteadyStateWithoutEccentricityLiesOnTheMeshGridOnly) {
  double mesh8 = 0.0, mesh16 = 0.0, mesh_eccentric = 0.0;
  const double off8 = OffGridShare(false, 8, &mesh8);
  const double off16 = OffGridShare(false, 16, &mesh16);
  const double eccentric = OffGridShare(true, 8, &mesh_eccentric);
  std::printf("healthy energy off the 14 Hz mesh grid: %.2e (8x), %.2e (16x) without "
              "eccentricity, %.2e with; on the mesh harmonics >= %.3f\n",
              off8, off16, eccentric, mesh8);
  EXPECT_LT(off8, 1e-7);
  EXPECT_LT(off16, 0.1 * off8);  // discretisation error: falls with the step
  EXPECT_GT(mesh8, 0.7);
  EXPECT_GT(eccentric, 1e-4);
}

// Share of x's energy that is periodic with `period` samples (its synchronous average over
// the whole revolutions at the end of x, extended periodically).
double SynchronousShare(const Eigen::VectorXd& x, Eigen::Index period) {
  const Eigen::Index revs = x.size() / period;
  const Eigen::Index start = x.size() - revs * period;
  Eigen::VectorXd mean = Eigen::VectorXd::Zero(period);
  for (Eigen::Index r = 0; r < revs; ++r) mean += x.segment(start + r * period, period);
  mean /= static_cast<double>(revs);
  return static_cast<double>(revs) * mean.squaredNorm() /
         x.segment(start, revs * period).squaredNorm();
}

// A tooth fault changes its gear's shaft's revolution, once per revolution: what it adds to
// the response (faulty - healthy, same plant, steady state) is periodic with the faulty
// gear's shaft and not with the other shafts. Distinct train (every shaft rate different) at
// an input of fs / 833 (576 r/min): shaft periods of 833 (input), 1190 (intermediate) and
// 1015 (output) samples exactly, so the synchronous averages are exact comb filters.
TEST(ParametricPlantSimulator, ToothFaultRepeatsOncePerRevolutionOfItsOwnShaft) {
  const GearTrain train = MakeTrain(TrainVariant::kDistinct);
  const std::map<std::string, int> shaft_of = {{"G1", 0}, {"G2", 1}, {"G3", 1}, {"G4", 2}};
  const Eigen::Index periods[3] = {833, 1190, 1015};
  ParametricSimulatorConfig c;
  c.block_length = 16660;  // 20 input revolutions, 14 and 16.4 of the others
  c.input_speed_hz = 8000.0 / 833.0;
  c.noise_relative = 0.0;
  for (int eccentric = 0; eccentric < 2; ++eccentric) {
    Rig healthy_rig = MakeRig(7, PlantFaultKind::kNone, "", c, eccentric == 1, train);
    AccelBlock block;
    healthy_rig.sim->NextBlock(false, block);
    Eigen::MatrixXd healthy;
    healthy_rig.sim->NoiseFreeNext(false, healthy);
    for (PlantFaultKind kind : {PlantFaultKind::kTePulse, PlantFaultKind::kMeshAm,
                                PlantFaultKind::kWearDip, PlantFaultKind::kCombined}) {
      for (const auto& [gear, own] : shaft_of) {
        Rig rig = MakeRig(7, kind, gear, c, eccentric == 1, train);
        rig.sim->ScaleFaultSeverity(2.0);
        rig.sim->NextBlock(true, block);  // the fault's onset transient dies out in this block
        Eigen::MatrixXd faulty;
        rig.sim->NoiseFreeNext(true, faulty);
        const Eigen::MatrixXd d = faulty - healthy;
        // The most affected channel.
        Eigen::Index ch = 0;
        for (Eigen::Index k = 1; k < d.cols(); ++k) {
          if (d.col(k).norm() / healthy.col(k).norm() > d.col(ch).norm() / healthy.col(ch).norm()) {
            ch = k;
          }
        }
        double share[3];
        for (int s = 0; s < 3; ++s) share[s] = SynchronousShare(d.col(ch), periods[s]);
        const std::string what = std::string(PlantFaultKindName(kind)) + " on " + gear +
                                 (eccentric ? ", eccentric" : "");
        EXPECT_GT(share[own], 0.5) << what;
        for (int s = 0; s < 3; ++s) {
          if (s != own) {
            EXPECT_LT(share[s], 0.5 * share[own]) << what << ", shaft " << s;
          }
        }
        std::printf("%-30s synchronous share on shafts 1..3: %.3f %.3f %.3f\n", what.c_str(),
                    share[0], share[1], share[2]);
      }
    }
  }
}

// Energy of the fault's added content (faulty - healthy from the same state) by family of lines.
struct FaultContent {
  double on_comb = 0.0;       // on the faulty shaft's comb (multiples of its rate)
  double on_grid = 0.0;       // on a x rate + b x 238 Hz (with the other stage's mesh)
  double off_mesh = 0.0;      // off the mesh harmonics
  double wide_sidebands = 0.0;   // |order| 2..5 around 280 and 560 Hz
  double healthy_wide = 0.0;     // the same bins, healthy
};

// Steady states: the same plant healthy and with the fault on since t = 0, second block (the
// fault's onset transient, which is no line, has died out).
FaultContent Content(PlantFaultKind kind, const std::string& gear, std::size_t rate,
                     bool eccentric) {
  Rig healthy_rig = MakeRig(3, kind, gear, OneHertzBins(), eccentric);
  Rig faulty_rig = MakeRig(3, kind, gear, OneHertzBins(), eccentric);
  faulty_rig.sim->ScaleFaultSeverity(2.0);
  AccelBlock first;
  healthy_rig.sim->NextBlock(false, first);
  faulty_rig.sim->NextBlock(true, first);
  Eigen::MatrixXd healthy, faulty;
  healthy_rig.sim->NoiseFreeNext(false, healthy);
  faulty_rig.sim->NoiseFreeNext(true, faulty);
  FaultContent fc;
  double total = 0.0;
  for (Eigen::Index c = 0; c < healthy.cols(); ++c) {
    const std::vector<double> d = Power(faulty.col(c) - healthy.col(c));
    const std::vector<double> h = Power(healthy.col(c));
    for (std::size_t k = 1; k < d.size(); ++k) {
      total += d[k];
      if (k % rate == 0) fc.on_comb += d[k];
      for (long b = -3; b <= 3; ++b) {
        const long rest = static_cast<long>(k) - 238 * b;
        if (rest >= 0 && rest % static_cast<long>(rate) == 0) {
          fc.on_grid += d[k];
          break;
        }
      }
      if (!MeshHarmonic(k)) fc.off_mesh += d[k];
    }
    for (std::size_t carrier : {280u, 560u}) {
      for (std::size_t order = 2; order <= 5; ++order) {
        for (std::size_t k : {carrier - order * rate, carrier + order * rate}) {
          fc.wide_sidebands += d[k];
          fc.healthy_wide += h[k];
        }
      }
    }
  }
  fc.on_comb /= total;
  fc.on_grid /= total;
  fc.off_mesh /= total;
  return fc;
}

// Without eccentricity the fault's content is exactly on its lines. G1: input shaft 10 Hz,
// mesh 280 Hz: the 10 Hz comb, plus what the other mesh (238 Hz, not a multiple of 10)
// intermodulates: a x 10 + b x 238. G2: intermediate shaft 7 Hz (both meshes are multiples of
// 7 Hz on Table 1): the 7 Hz comb. With eccentricity (the real plant), the fault's sidebands
// spread over many orders, where the healthy (eccentricity) sidebands are first order only.
TEST(ParametricPlantSimulator, CrackAddsShaftRateSidebandsAroundItsMeshOverManyOrders) {
  const FaultContent g1 = Content(PlantFaultKind::kMeshAm, "G1", 10, false);
  EXPECT_GT(g1.on_comb, 0.5);
  EXPECT_GT(g1.on_grid, 1.0 - 1e-6);
  const FaultContent g2 = Content(PlantFaultKind::kMeshAm, "G2", 7, false);
  EXPECT_GT(g2.on_comb, 1.0 - 1e-6);
  const FaultContent g1e = Content(PlantFaultKind::kMeshAm, "G1", 10, true);
  const FaultContent g2e = Content(PlantFaultKind::kMeshAm, "G2", 7, true);
  EXPECT_GT(g1e.wide_sidebands, 20.0 * g1e.healthy_wide);
  EXPECT_GT(g2e.wide_sidebands, 20.0 * g2e.healthy_wide);
  std::printf("crack: G1 comb %.3f grid %.9f; G2 comb %.9f; sidebands of orders 2..5: %.0fx, "
              "%.0fx the healthy ones\n",
              g1.on_comb, g1.on_grid, g2.on_comb, g1e.wide_sidebands / g1e.healthy_wide,
              g2e.wide_sidebands / g2e.healthy_wide);
}

TEST(ParametricPlantSimulator, MissingMaterialAddsACombOfTheShaftRate) {
  for (const auto& [gear, rate] : {std::pair<std::string, std::size_t>{"G1", 10}, {"G4", 7}}) {
    const FaultContent fc = Content(PlantFaultKind::kTePulse, gear, rate, false);
    EXPECT_GT(fc.on_grid, 1.0 - 1e-6) << gear;
    EXPECT_GT(fc.on_comb, 0.5) << gear;
    EXPECT_GT(fc.off_mesh, 0.5) << gear;  // a comb, not the mesh lines
    const FaultContent fe = Content(PlantFaultKind::kTePulse, gear, rate, true);
    EXPECT_GT(fe.wide_sidebands, 20.0 * fe.healthy_wide) << gear;
    std::printf("missing material on %s: comb %.3f grid %.9f off-mesh %.3f\n", gear.c_str(),
                fc.on_comb, fc.on_grid, fc.off_mesh);
  }
}

TEST(ParametricPlantSimulator, SeverityReachesTheTargetRmsChangeOrTheCaps) {
  for (PlantFaultKind kind : {PlantFaultKind::kTePulse, PlantFaultKind::kMeshAm,
                              PlantFaultKind::kWearDip, PlantFaultKind::kCombined}) {
    ParametricSimulatorConfig c;
    c.input_speed_hz = 7.5;
    c.noise_relative = 0.0;
    Rig rig = MakeRig(17, kind, "G3", c);
    AccelBlock block;
    rig.sim->NextBlock(false, block);
    const SeverityFit fit = rig.sim->NormaliseSeverity(0.03);
    const PlantFaultSeverity& sv = rig.sim->severity();
    const bool capped = fit.scale >= rig.sim->CapFactor() - 1e-12;
    if (capped) {
      EXPECT_LT(std::abs(fit.rms_change), 0.03) << PlantFaultKindName(kind);
    } else {
      EXPECT_NEAR(std::abs(fit.rms_change), 0.03, 0.0003) << PlantFaultKindName(kind);
    }
    EXPECT_LE(fit.evaluations, 8);
    EXPECT_LE(sv.pulse_depth_m, sv.max_pulse_depth_m);
    EXPECT_LE(sv.am_depth, sv.max_am_depth);
    EXPECT_LE(sv.dip_depth_m, sv.max_dip_depth_m);
    // The change is what the next faulty block shows, from the stream's state.
    Eigen::MatrixXd healthy, faulty;
    rig.sim->NoiseFreeNext(false, healthy);
    rig.sim->NoiseFreeNext(true, faulty);
    double best = 0.0;
    for (Eigen::Index ch = 0; ch < healthy.cols(); ++ch) {
      const double change = faulty.col(ch).norm() / healthy.col(ch).norm() - 1.0;
      if (std::abs(change) > std::abs(best)) best = change;
    }
    EXPECT_NEAR(best, fit.rms_change, 1e-12) << PlantFaultKindName(kind);
    std::printf("%s on G3: scale %.3f, RMS change %.4f%s, %d evaluations\n",
                std::string(PlantFaultKindName(kind)).c_str(), fit.scale, fit.rms_change,
                capped ? " (capped)" : "", fit.evaluations);
  }
}

std::vector<float> Stream(std::uint64_t seed, std::uint32_t block_length, int blocks,
                          bool disturbed, int fault_from) {
  ParametricSimulatorConfig c;
  c.block_length = block_length;
  c.input_speed_hz = 12.5;
  c.noise_relative = disturbed ? 0.05 : 0.0;
  c.tones = c.bursts = c.speed_drift = disturbed;
  c.seed = seed;
  Rig rig = MakeRig(seed, PlantFaultKind::kCombined, "G4", c);
  std::vector<float> all;
  AccelBlock block;
  for (int b = 0; b < blocks; ++b) {
    rig.sim->NextBlock(b >= fault_from, block);
    EXPECT_EQ(block.sequence, static_cast<std::uint64_t>(b));
    // Channel-major within a block: re-interleave to one time series per channel.
    for (std::uint32_t i = 0; i < block_length; ++i) {
      for (std::size_t ch = 0; ch < 4; ++ch) all.push_back(block.samples[ch * block_length + i]);
    }
  }
  return all;
}

TEST(ParametricPlantSimulator, BlocksAreBitIdenticalForTheSameSeed) {
  const std::vector<float> a = Stream(42, 2048, 3, true, 2);
  const std::vector<float> b = Stream(42, 2048, 3, true, 2);
  const std::vector<float> c = Stream(43, 2048, 3, true, 2);
  EXPECT_EQ(a, b);
  EXPECT_NE(a, c);
}

TEST(ParametricPlantSimulator, BlocksAreContinuousAcrossBlockBoundaries) {
  // The same noise-free stream cut into blocks of 2048 or of 4096 samples is the same signal:
  // a block boundary changes nothing (state carried, no restart, no jump).
  const std::vector<float> small = Stream(5, 2048, 4, false, 99);
  const std::vector<float> large = Stream(5, 4096, 2, false, 99);
  ASSERT_EQ(small.size(), large.size());
  EXPECT_EQ(small, large);
  // And no jump at a boundary: the step across it is an ordinary step.
  double largest_step = 0.0;
  for (std::size_t i = 4; i < small.size(); ++i) {
    largest_step = std::max(largest_step, static_cast<double>(std::abs(small[i] - small[i - 4])));
  }
  for (std::size_t boundary : {2048u, 4096u, 6144u}) {
    for (std::size_t ch = 0; ch < 4; ++ch) {
      const std::size_t i = boundary * 4 + ch;
      EXPECT_LE(std::abs(small[i] - small[i - 4]), largest_step);
    }
  }
}

TEST(ParametricPlantSimulator, LongStreamsStayBoundedAtEveryMatrixSpeed) {
  for (double rpm : kMatrixSpeedsRpm) {
    ParametricSimulatorConfig c;
    c.input_speed_hz = rpm / 60.0;
    c.noise_relative = 0.0;
    Rig rig = MakeRig(23, PlantFaultKind::kNone, "", c);
    AccelBlock block;
    Eigen::VectorXd first;
    for (int b = 0; b < kBaselineBlocks + kEvaluationBlocks; ++b) {
      rig.sim->NextBlock(false, block);
      Eigen::VectorXd rms = Eigen::VectorXd::Zero(4);
      for (std::size_t ch = 0; ch < 4; ++ch) {
        for (std::uint32_t i = 0; i < c.block_length; ++i) {
          const double v = block.samples[ch * c.block_length + i];
          ASSERT_TRUE(std::isfinite(v)) << rpm << " block " << b;
          rms[static_cast<Eigen::Index>(ch)] += v * v;
        }
      }
      rms = (rms / c.block_length).cwiseSqrt();
      if (b == 0) first = rms;
      for (Eigen::Index ch = 0; ch < 4; ++ch) {
        // Constant speed: a steady state, block after block.
        EXPECT_NEAR(rms[ch] / first[ch], 1.0, 0.02) << rpm << " r/min, block " << b;
      }
    }
    EXPECT_GT(first.minCoeff(), 0.0);
  }
}

// The drift moves the motor angle: an input speed f0 (1 + a sin(2 pi t / T + psi)) phase-
// modulates a mesh line by beta = z f0 a T / (2 pi) x 2 pi = z f0 a T rad, whose carrier keeps
// J0(beta)^2 of its power (T = the block: the sidebands fall on neighbouring bins). The drift is
// the one PlantSimulator applies (same seed, same profile).
TEST(ParametricPlantSimulator, SpeedDriftDrivesTheInputAngle) {
  const double f0 = 287.0 * 8000.0 / (8192.0 * 28.0);  // stage-0 mesh on bin 287 of 8192
  double carrier[2];
  for (int drift = 0; drift < 2; ++drift) {
    Result<ParametricPlatePlant> plant = DrawParametricPlatePlant(GearTrain::Table1(), true, 8);
    ASSERT_TRUE(plant.ok());
    ParametricGearboxParameters p = plant->truth->parameters();
    for (std::size_t s = 0; s < 2; ++s) {
      p.stages[s].mesh.driver = p.stages[s].mesh.driven = GearEccentricity{};
      p.stages[s].mesh.profile_amplitude_m = {s == 0 ? 1e-6 : 0.0};
      p.stages[s].mesh.profile_phase = {0.0};
    }
    auto gearbox = std::make_shared<const ParametricGearbox>(ParametricGearbox::Create(p).value());
    ParametricSimulatorConfig c;
    c.input_speed_hz = f0;
    c.noise_relative = 0.0;
    c.speed_drift = drift == 1;
    c.constant_stiffness = true;  // one line only: the stage-0 profile error's
    c.seed = 8;
    // Three channels, as the linear families' seat set: the drift phase is drawn after the
    // per-channel gains of the unmodelled sources.
    Result<ParametricPlantSimulator> sim = ParametricPlantSimulator::Create(
        gearbox, {0, 1, 2}, {{"p1"}, {"p2"}, {"p3"}}, ToothFault{}, c);
    ASSERT_TRUE(sim.ok()) << sim.error();
    Eigen::MatrixXd x;
    sim->NoiseFreeNext(false, x);
    std::complex<double> acc = 0.0;
    for (Eigen::Index i = 0; i < x.rows(); ++i) {
      acc += x(i, 0) * std::polar(1.0, -kTwoPi * 287.0 * static_cast<double>(i) / 8192.0);
    }
    carrier[drift] = std::norm(acc);
    if (drift == 1) {
      // The same profile as the frequency-domain families' simulator draws for this seed.
      Result<Plant> linear =
          MakePlant({PlantFamily::kLumpedPerturbed, TrainVariant::kTable1, ChannelSet::kSeats, 1});
      ASSERT_TRUE(linear.ok());
      PlantSimulatorConfig lc;
      lc.input_speed_hz = f0;
      lc.speed_drift = true;
      lc.seed = 8;
      Result<PlantSimulator> ls = PlantSimulator::Create(
          linear->dynamics, linear->channels, *PlantExcitation::Create(linear->train, {}), lc);
      ASSERT_TRUE(ls.ok());
      for (double sample : {0.0, 1234.5, 8191.0, 20000.0}) {
        EXPECT_EQ(sim->speed().Revs(sample / 8000.0), ls->InputRevs(sample));
      }
    }
  }
  const double beta = 28.0 * f0 * 0.003 * 8192.0 / 8000.0;
  const double j0 = std::cyl_bessel_j(0.0, beta);
  EXPECT_NEAR(carrier[1] / carrier[0], j0 * j0, 0.03) << "beta " << beta;
  EXPECT_LT(carrier[1] / carrier[0], 0.8);
}

TEST(ParametricPlantSimulator, RejectsBadConfigByName) {
  ParametricSimulatorConfig c;
  c.oversampling = 4;
  const GearTrain train = GearTrain::Table1();
  Result<ParametricPlatePlant> plant = DrawParametricPlatePlant(train, false, 1);
  ASSERT_TRUE(plant.ok());
  Result<ParametricPlantSimulator> sim = ParametricPlantSimulator::Create(
      plant->truth, plant->channel_points, {{"p1"}, {"p2"}, {"p3"}}, ToothFault{}, c);
  ASSERT_FALSE(sim.ok());
  EXPECT_NE(sim.error().find("oversampling"), std::string::npos) << sim.error();
  c = ParametricSimulatorConfig{};
  c.input_speed_hz = 80.0;  // mesh 2240 Hz: too few harmonics below fs / 2
  sim = ParametricPlantSimulator::Create(plant->truth, plant->channel_points,
                                         {{"p1"}, {"p2"}, {"p3"}}, ToothFault{}, c);
  ASSERT_FALSE(sim.ok());
  EXPECT_NE(sim.error().find("input_speed_hz"), std::string::npos) << sim.error();
  c = ParametricSimulatorConfig{};
  sim = ParametricPlantSimulator::Create(plant->truth, {0, 1, 9}, {{"p1"}, {"p2"}, {"p3"}},
                                         ToothFault{}, c);
  EXPECT_FALSE(sim.ok());
}

}  // namespace
}  // namespace gearpath

#include "core/simulation/gearbox_simulator.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include "core/dsp/fft_plan.h"

namespace gearpath {
namespace {

using Complex = std::complex<double>;

const LumpedGearboxModel& Table1Model() {
  static const LumpedGearboxModel model = [] {
    Result<LumpedGearboxModel> m = LumpedGearboxModel::Create(Table1Parameters());
    EXPECT_TRUE(m.ok()) << m.error();
    return std::move(m).value();
  }();
  return model;
}

GearboxSimulator MakeSimulator(const SimulatorConfig& config) {
  Result<GearboxSimulator> s = GearboxSimulator::Create(Table1Model(), GearTrain::Table1(), config);
  EXPECT_TRUE(s.ok()) << s.error();
  return std::move(s).value();
}

SimulatorConfig FaultyConfig(FaultType type = FaultType::kToothFracture, const char* gear = "G1") {
  SimulatorConfig c;
  c.fault = {type, gear, 1.0};
  c.seed = 42;
  return c;
}

// Direct DFT of x at integer bin k (X[k] = sum x[n] e^{-2 pi j k n / N}).
Complex Dft(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Index k) {
  Complex acc = 0.0;
  const auto n = static_cast<double>(x.size());
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    const double phase = -2.0 * std::numbers::pi * static_cast<double>(k * i % x.size()) / n;
    acc += x(i) * Complex(std::cos(phase), std::sin(phase));
  }
  return acc;
}

// All one-sided bins of x by FFT.
Eigen::VectorXcd Spectrum(const Eigen::Ref<const Eigen::VectorXd>& x) {
  Result<FftPlan> plan =
      FftPlan::Create(FftKind::kRealToComplex, static_cast<std::size_t>(x.size()));
  EXPECT_TRUE(plan.ok());
  std::copy(x.data(), x.data() + x.size(), plan->real_in().begin());
  plan->Execute();
  const std::span<Complex> out = plan->complex_out();
  return Eigen::Map<const Eigen::VectorXcd>(out.data(), static_cast<Eigen::Index>(out.size()));
}

TEST(GearboxSimulatorTest, PeriodIsOneSecondForTable1At600Rpm) {
  const GearboxSimulator sim = MakeSimulator(FaultyConfig());
  EXPECT_EQ(sim.period_samples(), 8000u);
  EXPECT_EQ(sim.speed_hz(), 10.0);
  EXPECT_EQ(sim.channels().size(), 4u);
  EXPECT_EQ(sim.seat_count(), 3);
}

TEST(GearboxSimulatorTest, NoiseFreeAccelerationsEqualTheModelsForcedResponseAtEveryTestedBin) {
  // Independent path: TE spectrum by direct DFT of the excitation, response by the model's
  // frequency-domain RespondToTransmissionError, compared with the DFT of the synthesized
  // time signals. Bins: mesh 1 and 2, a sideband, fault lines of G1 (multiples of 10 Hz),
  // and one near each of two housing modes.
  const GearboxSimulator sim = MakeSimulator(FaultyConfig());
  const Eigen::Index n = static_cast<Eigen::Index>(sim.period_samples());
  const LumpedGearboxModel& model = Table1Model();
  // Round-off floor: 1e-12 of the channel's largest line (the mesh lines).
  std::vector<double> floor_x, floor_f;
  for (int c = 0; c < 4; ++c) {
    floor_x.push_back(1e-12 * std::max(std::abs(Dft(sim.periodic_acceleration().col(c), 280)),
                                       std::abs(Dft(sim.periodic_acceleration().col(c), 238))));
  }
  for (int b = 0; b < 3; ++b) {
    floor_f.push_back(1e-12 * std::max(std::abs(Dft(sim.periodic_bearing_force().col(b), 280)),
                                       std::abs(Dft(sim.periodic_bearing_force().col(b), 238))));
  }
  for (Eigen::Index k : {280, 238, 290, 10, 130, 1010, 1230, 1710, 2500}) {
    Eigen::VectorXcd te(2);
    for (int s = 0; s < 2; ++s) {
      Eigen::VectorXd e(n);
      for (Eigen::Index i = 0; i < n; ++i) {
        e(i) = sim.excitation().Total(s, static_cast<double>(i) / 8000.0);
      }
      te(s) = Dft(e, k);
    }
    const double f = static_cast<double>(k) * 8000.0 / static_cast<double>(n);
    Result<ForcedResponse> r = model.RespondToTransmissionError(f, te);
    ASSERT_TRUE(r.ok()) << r.error();
    for (int seat = 0; seat < 3; ++seat) {
      const Complex want = r->acceleration(model.SeatDof(seat));
      const Complex got = Dft(sim.periodic_acceleration().col(seat), k);
      EXPECT_LE(std::abs(got - want),
                1e-9 * std::abs(want) + floor_x[static_cast<std::size_t>(seat)])
          << f << " Hz seat " << seat;
      const Complex want_f = r->bearing_force(seat);
      const Complex got_f = Dft(sim.periodic_bearing_force().col(seat), k);
      EXPECT_LE(std::abs(got_f - want_f),
                1e-9 * std::abs(want_f) + floor_f[static_cast<std::size_t>(seat)])
          << f << " Hz force";
    }
    const Complex want_m = r->acceleration(model.HousingDof());
    const Complex got_m = Dft(sim.periodic_acceleration().col(3), k);
    EXPECT_LE(std::abs(got_m - want_m), 1e-9 * std::abs(want_m) + floor_x[3]) << f << " Hz housing";
  }
}

TEST(GearboxSimulatorTest, TrueBearingForcesSatisfyTheHousingFrfIdentityAtEveryBin) {
  // x_p = H_d,pp F and x_m = H_d,mp F (housing alone, seed Eqs. 7 and 45) at every bin.
  // Physical accelerance -w^2 (K_h - w^2 M_h + j w C_h)^-1 from the model's housing
  // matrices, independent of the simulator's transfer path.
  const GearboxSimulator sim = MakeSimulator(FaultyConfig(FaultType::kChippedTooth, "G3"));
  const LumpedGearboxModel& model = Table1Model();
  const Eigen::Index n = static_cast<Eigen::Index>(sim.period_samples());
  std::vector<Eigen::VectorXcd> x, f;
  for (int c = 0; c < 4; ++c) x.push_back(Spectrum(sim.periodic_acceleration().col(c)));
  for (int b = 0; b < 3; ++b) f.push_back(Spectrum(sim.periodic_bearing_force().col(b)));
  double largest = 0.0;  // round-off floor: 1e-12 of the largest response line
  for (int c = 0; c < 4; ++c)
    largest = std::max(largest, x[static_cast<std::size_t>(c)].cwiseAbs().maxCoeff());
  double worst = 0.0;
  for (Eigen::Index k = 1; k < n / 2; ++k) {
    const double w =
        2.0 * std::numbers::pi * static_cast<double>(k) * 8000.0 / static_cast<double>(n);
    const Eigen::MatrixXcd dyn = model.housing_stiffness().cast<Complex>() -
                                 w * w * model.housing_mass().cast<Complex>() +
                                 Complex(0.0, w) * model.housing_damping().cast<Complex>();
    const Eigen::MatrixXcd h = -w * w * dyn.inverse();  // 4 x 4: seats then housing mass
    Eigen::VectorXcd fk(3), xk(4);
    for (int b = 0; b < 3; ++b) fk(b) = f[static_cast<std::size_t>(b)](k);
    for (int c = 0; c < 4; ++c) xk(c) = x[static_cast<std::size_t>(c)](k);
    const Eigen::VectorXcd predicted = h.leftCols(3) * fk;
    const double scale = xk.norm() + h.leftCols(3).norm() * fk.norm() + largest;
    worst = std::max(worst, (predicted - xk).norm() / scale);
  }
  EXPECT_LT(worst, 1e-12);  // 1e-12 relative per bin, floor 1e-12 of the largest line
}

TEST(GearboxSimulatorTest, BlocksAcrossTheChunkSeamAreContinuous) {
  SimulatorConfig c = FaultyConfig();
  c.block_length = 3000;  // blocks 2 and 5 straddle the 8000-sample seams
  GearboxSimulator sim = MakeSimulator(c);
  std::vector<float> stream;
  AccelBlock block;
  for (int b = 0; b < 6; ++b) {
    sim.NextBlock(block);
    stream.insert(stream.end(), block.samples.begin(), block.samples.begin() + 3000);  // p1
  }
  const Eigen::MatrixXd& p = sim.periodic_acceleration();
  for (std::size_t i = 0; i < stream.size(); ++i) {
    ASSERT_EQ(stream[i], static_cast<float>(p(static_cast<Eigen::Index>(i % 8000), 0))) << i;
  }
  for (std::size_t seam : {std::size_t{8000}, std::size_t{16000}}) {
    double local = 0.0;
    for (std::size_t i = seam - 40; i < seam + 40; ++i) {
      if (i == seam - 1) continue;
      local = std::max(local, std::abs(static_cast<double>(stream[i + 1]) - stream[i]));
    }
    const double jump = std::abs(static_cast<double>(stream[seam]) - stream[seam - 1]);
    EXPECT_LE(jump, local) << "seam at " << seam;
  }
}

TEST(GearboxSimulatorTest, BlocksAreBitReproducibleForTheSameSeed) {
  SimulatorConfig c = FaultyConfig(FaultType::kLocalizedWear, "G2");
  c.noise_relative = 0.1;
  c.block_length = 4096;
  GearboxSimulator a = MakeSimulator(c);
  GearboxSimulator b = MakeSimulator(c);
  c.seed = 43;
  GearboxSimulator other = MakeSimulator(c);
  AccelBlock ba, bb, bo;
  std::vector<AccelBlock> first;
  for (int i = 0; i < 4; ++i) {
    a.NextBlock(ba);
    b.NextBlock(bb);
    other.NextBlock(bo);
    ASSERT_EQ(ba.samples, bb.samples) << "block " << i;
    ASSERT_NE(ba.samples, bo.samples) << "block " << i;
    first.push_back(ba);
  }
  a.Rewind();
  for (int i = 0; i < 4; ++i) {
    a.NextBlock(ba);
    ASSERT_EQ(ba.samples, first[static_cast<std::size_t>(i)].samples);
    ASSERT_EQ(ba.sequence, first[static_cast<std::size_t>(i)].sequence);
  }
}

TEST(GearboxSimulatorTest, NoiseHasTheRequestedLevelRelativeToEachChannel) {
  SimulatorConfig c = FaultyConfig();
  c.noise_relative = 0.2;
  c.block_length = 8000;
  GearboxSimulator sim = MakeSimulator(c);
  AccelBlock block;
  sim.NextBlock(block);
  for (Eigen::Index ch = 0; ch < 4; ++ch) {
    double sum2 = 0.0;
    const Eigen::VectorXd clean = sim.periodic_acceleration().col(ch);
    for (Eigen::Index i = 0; i < 8000; ++i) {
      const double d = block.samples[static_cast<std::size_t>(ch * 8000 + i)] - clean(i);
      sum2 += d * d;
    }
    const double rms_clean = std::sqrt(clean.squaredNorm() / 8000.0);
    // 8000 Gaussian samples: the std estimate is within ~1.6 % (2 sigma); allow 5 %.
    EXPECT_NEAR(std::sqrt(sum2 / 8000.0), 0.2 * rms_clean, 0.05 * 0.2 * rms_clean) << ch;
  }
}

TEST(GearboxSimulatorTest, BlocksCarryMetadataSequenceTimeAndSpeed) {
  SimulatorConfig c = FaultyConfig();
  c.machine_id = "gb-7";
  c.block_length = 1000;
  c.start_time_ns = 1'700'000'000'000'000'000;
  c.first_sequence = 5;
  GearboxSimulator sim = MakeSimulator(c);
  AccelBlock block;
  std::vector<double> forces;
  for (std::uint64_t i = 0; i < 3; ++i) {
    sim.NextBlock(block, &forces);
    EXPECT_EQ(block.machine_id, "gb-7");
    EXPECT_EQ(block.sequence, 5 + i);
    EXPECT_EQ(block.t0_ns, c.start_time_ns + static_cast<std::int64_t>(i) * 125'000'000);
    EXPECT_EQ(block.sample_rate_hz, 8000.0);
    EXPECT_EQ(block.speed_hz, 10.0);
    EXPECT_EQ(block.speed_source, SpeedSource::kAcquisition);
    EXPECT_EQ(block.samples_per_channel, 1000u);
    EXPECT_EQ(block.samples.size(), 4000u);
    ASSERT_EQ(forces.size(), 3000u);
    EXPECT_EQ(forces[2 * 1000 + 17],
              sim.periodic_bearing_force()(static_cast<Eigen::Index>(i * 1000 + 17), 2));
  }
  const char* names[] = {"p1", "p2", "p3", "m1"};
  for (int ch = 0; ch < 4; ++ch) {
    EXPECT_EQ(block.channels[static_cast<std::size_t>(ch)].sensor, names[ch]);
    EXPECT_EQ(block.channels[static_cast<std::size_t>(ch)].axis, Axis::kX);
  }
  c.report_speed = false;
  c.include_housing_channel = false;
  GearboxSimulator quiet = MakeSimulator(c);
  quiet.NextBlock(block);
  EXPECT_EQ(block.speed_hz, 0.0);
  EXPECT_EQ(block.speed_source, SpeedSource::kUnknown);
  EXPECT_EQ(block.channels.size(), 3u);
  EXPECT_EQ(block.samples.size(), 3000u);
}

TEST(GearboxSimulatorTest, SpeedIsSnappedSoTheCommonPeriodIsWholeSamples) {
  SimulatorConfig c;
  c.input_speed_hz = 10.1;
  const GearboxSimulator sim = MakeSimulator(c);
  const double n = static_cast<double>(sim.period_samples());
  EXPECT_EQ(sim.period_samples(), 7921u);  // 10 revolutions / 10.1 Hz * 8000 Hz = 7920.79
  EXPECT_DOUBLE_EQ(sim.speed_hz(), 10.0 * 8000.0 / n);
  EXPECT_LE(std::abs(sim.speed_hz() - 10.1) / 10.1, 0.5 / n);
  // Seed speeds need no snapping: 500 r/min -> 1.2 s = 9600 samples.
  c.input_speed_hz = RpmToHz(500.0);
  EXPECT_EQ(MakeSimulator(c).period_samples(), 9600u);
}

TEST(GearboxSimulatorTest, FaultAddsShaftRateLinesThatHealthyLacksButMeshLinesDominate) {
  SimulatorConfig healthy_config = FaultyConfig(FaultType::kNone, "");
  const GearboxSimulator healthy = MakeSimulator(healthy_config);
  for (FaultType type :
       {FaultType::kChippedTooth, FaultType::kLocalizedWear, FaultType::kToothFracture}) {
    const GearboxSimulator faulty = MakeSimulator(FaultyConfig(type, "G1"));
    for (int ch = 0; ch < 4; ++ch) {
      const Eigen::VectorXcd xf = Spectrum(faulty.periodic_acceleration().col(ch));
      const Eigen::VectorXcd xh = Spectrum(healthy.periodic_acceleration().col(ch));
      // 1010 Hz: a multiple of the G1 shaft rate (10 Hz) far from every mesh harmonic and
      // its shaft sidebands (840 +- 10/7, 952 +- 7, 1120 +- 10/7).
      EXPECT_LT(std::abs(xh(1010)), 1e-12 * xh.cwiseAbs().maxCoeff());
      EXPECT_GT(std::abs(xf(1010)), 1e-6 * xf.cwiseAbs().maxCoeff()) << FaultTypeName(type);
      // The largest line is still a mesh harmonic (or one of its sidebands).
      Eigen::Index peak = 0;
      xf.cwiseAbs().maxCoeff(&peak);
      const bool near_mesh = [&] {
        for (int h = 1; h <= 3; ++h) {
          if (std::abs(static_cast<double>(peak) - 280.0 * h) <= 10.0) return true;
          if (std::abs(static_cast<double>(peak) - 238.0 * h) <= 7.0) return true;
        }
        return false;
      }();
      EXPECT_TRUE(near_mesh) << FaultTypeName(type) << " channel " << ch << ": peak at " << peak
                             << " Hz";
    }
  }
}

TEST(GearboxSimulatorTest, FaultRaisesKurtosisInSeverityOrderWithoutDominatingTheLevel) {
  // Realism contract of the default fault shapes (fault_excitation.h): at the G1 seat the
  // fracture is more impulsive than the chipped tooth, both more than healthy, and no fault
  // raises the RMS by more than 50 %.
  const auto moments = [](FaultType type) {
    const GearboxSimulator sim = MakeSimulator(FaultyConfig(type, "G1"));
    const Eigen::ArrayXd x = sim.periodic_acceleration().col(0).array();
    const double m2 = x.square().mean();
    return std::pair<double, double>{std::sqrt(m2), x.pow(4).mean() / (m2 * m2)};
  };
  const auto [rms_h, kurt_h] = moments(FaultType::kNone);
  const auto [rms_w, kurt_w] = moments(FaultType::kLocalizedWear);
  const auto [rms_c, kurt_c] = moments(FaultType::kChippedTooth);
  const auto [rms_f, kurt_f] = moments(FaultType::kToothFracture);
  EXPECT_GT(kurt_f, kurt_c);
  EXPECT_GT(kurt_c, kurt_h);
  EXPECT_GE(kurt_w, 0.99 * kurt_h);
  for (double rms : {rms_w, rms_c, rms_f}) {
    EXPECT_GE(rms, 0.99 * rms_h);
    EXPECT_LT(rms, 1.5 * rms_h);
  }
}

TEST(GearboxSimulatorValidationTest, RejectsBadConfigurationNamingTheField) {
  const LumpedGearboxModel& model = Table1Model();
  const GearTrain train = GearTrain::Table1();
  SimulatorConfig c;
  c.sample_rate_hz = 0.0;
  Result<GearboxSimulator> r = GearboxSimulator::Create(model, train, c);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error(), "simulator: sample_rate_hz must be finite and > 0, got 0");
  c = {};
  c.block_length = 0;
  r = GearboxSimulator::Create(model, train, c);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error(), "simulator: block_length must be >= 1, got 0");
  c = {};
  c.noise_relative = -0.1;
  r = GearboxSimulator::Create(model, train, c);
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error(), "simulator: noise_relative must be finite and >= 0, got -0.1");
  c = {};
  c.max_period_samples = 4000;
  r = GearboxSimulator::Create(model, train, c);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("exceeds max_period_samples (4000)"), std::string::npos) << r.error();
  c = {};
  c.fault = {FaultType::kToothFracture, "G7", 1.0};
  r = GearboxSimulator::Create(model, train, c);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("fault gear 'G7'"), std::string::npos) << r.error();
}

TEST(GearboxSimulatorValidationTest, RejectsATrainThatDoesNotDescribeTheModel) {
  const LumpedGearboxModel& model = Table1Model();
  GearTrain t = GearTrain::Table1();
  t.gears[1].teeth = 41;
  EXPECT_EQ(CheckTrainMatchesModel(model, t).error(),
            "gear train: stages[0] (G1->G2): tooth counts 28/41 differ from the model's 28/40");
  t = GearTrain::Table1();
  t.bearings.pop_back();
  EXPECT_EQ(CheckTrainMatchesModel(model, t).error(),
            "gear train: has 2 bearings but the model has 3 bearing seats (one per rotor)");
  t = GearTrain::Table1();
  std::swap(t.bearings[0].shaft, t.bearings[1].shaft);
  EXPECT_EQ(CheckTrainMatchesModel(model, t).error(),
            "gear train: bearings[0] (B1) must support shaft 'input' (model seat 0), got "
            "'intermediate'");
  t = GearTrain::Table1();
  std::swap(t.shafts[1], t.shafts[2]);
  EXPECT_NE(CheckTrainMatchesModel(model, t).error().find("must drive from shaft 0 to shaft 1"),
            std::string::npos);
  EXPECT_TRUE(CheckTrainMatchesModel(model, GearTrain::Table1()).ok());
}

}  // namespace
}  // namespace gearpath

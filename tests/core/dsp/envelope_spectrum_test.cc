#include "core/dsp/envelope_spectrum.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "tests/core/dsp/test_signals.h"

namespace gearpath {
namespace {

using dsp_test::kTwoPi;

constexpr double kFs = 8000.0;
constexpr std::size_t kN = 16000;  // 0.5 Hz bins: every line below is on a bin

// (1 + m cos 2 pi fm t) cos 2 pi fc t.
std::vector<double> AmCarrier(double m, double fm, double fc, double gain = 1.0) {
  std::vector<double> x(kN);
  for (std::size_t i = 0; i < kN; ++i) {
    const double t = static_cast<double>(i) / kFs;
    x[i] = gain * (1.0 + m * std::cos(kTwoPi * fm * t)) * std::cos(kTwoPi * fc * t);
  }
  return x;
}

std::vector<double> Ses(const std::vector<double>& x) {
  auto ses = EnvelopeSpectrum::Create(kN, kFs).value();
  std::vector<double> out(ses.bin_count());
  EXPECT_TRUE(ses.Process(x, out).ok());
  return out;
}

TEST(EnvelopeSpectrum, AmCarrierShowsFmAndTwiceFmAtTheAnalyticalHeights) {
  // Squared envelope: (1 + m cos wt)^2 = 1 + 2m cos wt + m^2 cos^2 wt
  //                 = (1 + m^2/2) + 2m cos wt + (m^2/2) cos 2wt.
  // Its mean is 1 + m^2/2; the one-sided amplitudes of the rest are 2m at fm and m^2/2 at 2fm.
  // Normalised by the mean: SES(fm) = 2m / (1 + m^2/2), SES(2fm) = (m^2/2) / (1 + m^2/2),
  // e.g. 4/3 and 1/3 for m = 1. Everything else, DC included, is 0.
  const double fm = 10.0;
  const double bin_hz = kFs / kN;
  for (double m : {1.0, 0.5, 0.1}) {
    const auto ses = Ses(AmCarrier(m, fm, 1500.0));
    const double mean = 1.0 + m * m / 2.0;
    const auto k1 = static_cast<std::size_t>(fm / bin_hz);
    EXPECT_NEAR(ses[k1], 2.0 * m / mean, 1e-10) << "m = " << m;
    EXPECT_NEAR(ses[2 * k1], m * m / 2.0 / mean, 1e-10) << "m = " << m;
    for (std::size_t k = 0; k < ses.size(); ++k) {
      if (k != k1 && k != 2 * k1) {
        EXPECT_NEAR(ses[k], 0.0, 1e-10) << "m = " << m << " bin " << k;
      }
    }
  }
}

TEST(EnvelopeSpectrum, IsIndependentOfTheSignalsGain) {
  const auto a = Ses(AmCarrier(0.4, 12.5, 2000.0));
  const auto b = Ses(AmCarrier(0.4, 12.5, 2000.0, 250.0));
  for (std::size_t k = 0; k < a.size(); ++k) EXPECT_NEAR(a[k], b[k], 1e-10);
}

TEST(EnvelopeSpectrum, UnmodulatedCarrierAndSilenceGiveAZeroSpectrum) {
  for (const auto& x : {AmCarrier(0.0, 10.0, 1500.0), std::vector<double>(kN, 0.0)}) {
    for (double v : Ses(x)) EXPECT_NEAR(v, 0.0, 1e-10);
  }
}

TEST(EnvelopeSpectrum, ReportsTheMeanSquaredEnvelopeItNormalisedBy) {
  auto ses = EnvelopeSpectrum::Create(kN, kFs).value();
  std::vector<double> out(ses.bin_count());
  ASSERT_TRUE(ses.Process(AmCarrier(1.0, 10.0, 1500.0, 2.0), out).ok());
  EXPECT_NEAR(ses.mean_squared_envelope(), 4.0 * 1.5, 1e-10);  // gain^2 (1 + m^2/2)
  EXPECT_DOUBLE_EQ(ses.bin_hz(), 0.5);
}

TEST(EnvelopeSpectrum, RejectsBadConfigurationAndBadBlocks) {
  auto rate = EnvelopeSpectrum::Create(kN, std::numeric_limits<double>::infinity());
  ASSERT_FALSE(rate.ok());
  EXPECT_NE(rate.error().find("sample rate"), std::string::npos) << rate.error();
  EXPECT_FALSE(EnvelopeSpectrum::Create(0, kFs).ok());

  auto ses = EnvelopeSpectrum::Create(128, kFs).value();
  std::vector<double> out(65);
  Status empty = ses.Process({}, out);
  ASSERT_FALSE(empty.ok());
  EXPECT_NE(empty.error().find("empty"), std::string::npos) << empty.error();
  std::vector<double> x(128, 1.0);
  std::vector<double> wrong_out(64);
  Status mismatched = ses.Process(x, wrong_out);
  ASSERT_FALSE(mismatched.ok());
  EXPECT_NE(mismatched.error().find("64 values, configured for 65"), std::string::npos)
      << mismatched.error();
  x[3] = std::numeric_limits<double>::quiet_NaN();
  Status nan = ses.Process(x, out);
  ASSERT_FALSE(nan.ok());
  EXPECT_NE(nan.error().find("non-finite value at index 3"), std::string::npos) << nan.error();
}

}  // namespace
}  // namespace gearpath

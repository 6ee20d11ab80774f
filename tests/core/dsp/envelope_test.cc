#include "core/dsp/envelope.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <limits>
#include <string>
#include <vector>

#include "tests/core/dsp/test_signals.h"

namespace gearpath {
namespace {

using dsp_test::Cosine;
using dsp_test::kTwoPi;

constexpr double kFs = 1000.0;

TEST(Envelope, AnalyticSignalOfACosineIsTheComplexExponential) {
  for (std::size_t n : {256u, 255u}) {
    const double f = 37.0 * kFs / static_cast<double>(n);
    const auto x = Cosine(n, kFs, f, 1.5, 0.25);
    auto envelope = Envelope::Create(n).value();
    std::vector<std::complex<double>> z(n);
    ASSERT_TRUE(envelope.ProcessAnalytic(x, z).ok());
    for (std::size_t i = 0; i < n; ++i) {
      const auto expected = std::polar(1.5, kTwoPi * f * static_cast<double>(i) / kFs + 0.25);
      EXPECT_NEAR(std::abs(z[i] - expected), 0.0, 1e-12) << n << " " << i;
    }
  }
}

TEST(Envelope, RealPartOfTheAnalyticSignalIsTheSignal) {
  for (std::size_t n : {512u, 511u}) {
    const auto x = dsp_test::WhiteNoise(n, 1.0, 3);
    auto envelope = Envelope::Create(n).value();
    std::vector<std::complex<double>> z(n);
    ASSERT_TRUE(envelope.ProcessAnalytic(x, z).ok());
    for (std::size_t i = 0; i < n; ++i) EXPECT_NEAR(z[i].real(), x[i], 1e-12);
  }
}

TEST(Envelope, SquaredEnvelopeOfAnAmCarrierIsTheSquaredModulation) {
  // x = (1 + m cos w_m t) cos w_c t with both lines on bins: |z|^2 = (1 + m cos w_m t)^2.
  const std::size_t n = 2000;
  const double fc = 200.0;
  const double fm = 7.0;
  const double m = 0.6;
  std::vector<double> x(n);
  std::vector<double> expected(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) / kFs;
    const double a = 1.0 + m * std::cos(kTwoPi * fm * t);
    x[i] = a * std::cos(kTwoPi * fc * t);
    expected[i] = a * a;
  }
  auto envelope = Envelope::Create(n).value();
  std::vector<double> e2(n);
  ASSERT_TRUE(envelope.ProcessSquared(x, e2).ok());
  for (std::size_t i = 0; i < n; ++i) EXPECT_NEAR(e2[i], expected[i], 1e-10);
}

TEST(Envelope, SilentBlockHasZeroEnvelope) {
  auto envelope = Envelope::Create(64).value();
  std::vector<double> e2(64, 1.0);
  ASSERT_TRUE(envelope.ProcessSquared(std::vector<double>(64, 0.0), e2).ok());
  for (double v : e2) EXPECT_EQ(v, 0.0);
}

TEST(Envelope, RejectsBadLengthsAndNonFiniteSamples) {
  EXPECT_FALSE(Envelope::Create(1).ok());
  auto envelope = Envelope::Create(64).value();
  std::vector<double> e2(64);
  Status empty = envelope.ProcessSquared({}, e2);
  ASSERT_FALSE(empty.ok());
  EXPECT_NE(empty.error().find("input block is empty"), std::string::npos) << empty.error();
  std::vector<double> x(64, 0.0);
  std::vector<double> short_out(63);
  Status out = envelope.ProcessSquared(x, short_out);
  ASSERT_FALSE(out.ok());
  EXPECT_NE(out.error().find("63 values, configured for 64"), std::string::npos) << out.error();
  std::vector<std::complex<double>> z(65);
  EXPECT_FALSE(envelope.ProcessAnalytic(x, z).ok());
  x[63] = -std::numeric_limits<double>::infinity();
  Status inf = envelope.ProcessSquared(x, e2);
  ASSERT_FALSE(inf.ok());
  EXPECT_NE(inf.error().find("index 63"), std::string::npos) << inf.error();
}

}  // namespace
}  // namespace gearpath

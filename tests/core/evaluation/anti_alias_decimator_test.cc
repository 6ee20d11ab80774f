// AntiAliasDecimator: 64 kHz -> 8 kHz as the parametric simulator uses it. A tone in the pass
// band comes out at the output rate with its amplitude and phase (zero phase: output n is the
// input at 8 n); tones that would fold onto 0..4 kHz are gone; channels are independent.
#include "core/evaluation/anti_alias_decimator.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace gearpath {
namespace {

constexpr double kIn = 64000.0;
constexpr double kOut = 8000.0;

// Decimates cos(2 pi f t + phase) (t = i / kIn, i = 0..) on channel 0 and sin(...) on
// channel 1; returns the outputs from output index `skip` on (n outputs, two columns).
Eigen::MatrixXd Decimate(AntiAliasDecimator& d, double f, double phase, int skip, int n) {
  Eigen::MatrixXd out(n, 2);
  int produced = 0;
  double frame[2], y[2];
  for (long long i = 0; produced < n; ++i) {
    const double t = static_cast<double>(i) / kIn;
    frame[0] = std::cos(2.0 * std::numbers::pi * f * t + phase);
    frame[1] = std::sin(2.0 * std::numbers::pi * f * t + phase);
    if (!d.Push(frame, y)) continue;  // output k (counted from 0) is the input at 8 k
    if (skip > 0) {
      --skip;
      continue;
    }
    out(produced, 0) = y[0];
    out(produced, 1) = y[1];
    ++produced;
  }
  return out;
}

TEST(AntiAliasDecimator, PassBandToneKeepsAmplitudeAndPhaseAtTheOutputInstants) {
  const int skip = 200;  // past the start-up (zeros before the first input)
  for (double f : {37.0, 1234.5, 3100.0, 3550.0}) {
    Result<AntiAliasDecimator> d = AntiAliasDecimator::Create(kIn, kOut, 3600.0, 100.0, 2);
    ASSERT_TRUE(d.ok()) << d.error();
    EXPECT_EQ(d->factor(), 8);
    EXPECT_EQ(d->stage_count(), 3);
    EXPECT_GT(d->lookahead(), 0);
    const Eigen::MatrixXd y = Decimate(*d, f, 0.3, skip, 400);
    double worst = 0.0;
    for (int n = 0; n < y.rows(); ++n) {
      const double t = static_cast<double>(n + skip) / kOut;  // output n <-> input 8 n
      worst = std::max(worst, std::abs(y(n, 0) - std::cos(2.0 * std::numbers::pi * f * t + 0.3)));
      worst = std::max(worst, std::abs(y(n, 1) - std::sin(2.0 * std::numbers::pi * f * t + 0.3)));
    }
    EXPECT_LT(worst, 1e-4) << f << " Hz";  // pass-band ripple of a 100 dB Kaiser design
  }
}

TEST(AntiAliasDecimator, TonesThatWouldFoldOntoTheBandAreRemoved) {
  // 4.0 kHz and above would alias into 0..4 kHz at 8 kHz; 30 kHz into the first stage's band.
  for (double f : {4000.0, 4500.0, 7000.0, 12345.0, 30000.0}) {
    Result<AntiAliasDecimator> d = AntiAliasDecimator::Create(kIn, kOut, 3600.0, 100.0, 2);
    ASSERT_TRUE(d.ok());
    const Eigen::MatrixXd y = Decimate(*d, f, 0.0, 200, 400);
    EXPECT_LT(y.cwiseAbs().maxCoeff(), 3e-5) << f << " Hz";  // ~ -90 dB or better
  }
}

TEST(AntiAliasDecimator, DesignFollowsKaiser) {
  // Kaiser's formula: A = 100 dB over a transition of 400 Hz at 16 kHz -> ~257 taps.
  EXPECT_NEAR(KaiserLength(100.0, 400.0 / 16000.0), 257, 2);
  EXPECT_NEAR(KaiserBeta(100.0), 0.1102 * 91.3, 1e-12);
  const std::vector<double> h = KaiserLowPass(31, 0.2, 6.0);
  double sum = 0.0;
  for (std::size_t i = 0; i < h.size(); ++i) {
    sum += h[i];
    EXPECT_DOUBLE_EQ(h[i], h[h.size() - 1 - i]);  // symmetric: linear (here zero) phase
  }
  EXPECT_NEAR(sum, 1.0, 1e-12);
}

TEST(AntiAliasDecimator, RejectsBadRates) {
  EXPECT_FALSE(AntiAliasDecimator::Create(64000.0, 6000.0, 2000.0, 100.0, 1).ok());
  EXPECT_FALSE(AntiAliasDecimator::Create(64000.0, 8000.0, 4100.0, 100.0, 1).ok());
  EXPECT_FALSE(AntiAliasDecimator::Create(64000.0, 8000.0, 3600.0, 100.0, 0).ok());
}

}  // namespace
}  // namespace gearpath

#include "core/dsp/spectrum.h"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <limits>
#include <vector>

#include "tests/core/dsp/test_signals.h"

namespace gearpath {
namespace {

using dsp_test::Cosine;

constexpr double kFs = 1000.0;

std::vector<std::complex<double>> SpectrumOf(const std::vector<double>& x, std::size_t channels) {
  auto spectrum = Spectrum::Create(x.size() / channels, channels, kFs).value();
  std::vector<std::complex<double>> s(spectrum.bin_count() * channels);
  EXPECT_TRUE(spectrum.Process(x, s).ok());
  return s;
}

class SpectrumOfLength : public ::testing::TestWithParam<std::size_t> {};

TEST_P(SpectrumOfLength, SinusoidOnAnInteriorBinGivesItsComplexAmplitude) {
  const std::size_t n = GetParam();
  const std::size_t k0 = n / 3;
  const double amplitude = 2.5;
  const double phase = 0.7;
  const auto x =
      Cosine(n, kFs, static_cast<double>(k0) * kFs / static_cast<double>(n), amplitude, phase);
  const auto s = SpectrumOf(x, 1);
  ASSERT_EQ(s.size(), n / 2 + 1);
  EXPECT_NEAR(std::abs(s[k0] - std::polar(amplitude, phase)), 0.0, 1e-12);
  for (std::size_t k = 0; k < s.size(); ++k) {
    if (k != k0) {
      EXPECT_NEAR(std::abs(s[k]), 0.0, 1e-12) << "bin " << k;
    }
  }
}

TEST_P(SpectrumOfLength, ConstantGivesItsValueAtDc) {
  const std::size_t n = GetParam();
  const auto s = SpectrumOf(std::vector<double>(n, -1.25), 1);
  EXPECT_NEAR(std::abs(s[0] - (-1.25)), 0.0, 1e-13);
  for (std::size_t k = 1; k < s.size(); ++k) EXPECT_NEAR(std::abs(s[k]), 0.0, 1e-13);
}

TEST(Spectrum, LastBinOfAnOddLengthIsAnInteriorBin) {
  for (std::size_t n : {17u, 1001u}) {
    const std::size_t k0 = (n - 1) / 2;
    const auto x =
        Cosine(n, kFs, static_cast<double>(k0) * kFs / static_cast<double>(n), 1.5, -2.0);
    const auto s = SpectrumOf(x, 1);
    EXPECT_NEAR(std::abs(s.back() - std::polar(1.5, -2.0)), 0.0, 1e-12) << n;
  }
}

TEST_P(SpectrumOfLength, InverseReproducesTheBlock) {
  const std::size_t n = GetParam();
  const std::size_t channels = 3;
  const auto x = dsp_test::WhiteNoise(n * channels, 1.0, 7);
  const auto s = SpectrumOf(x, channels);
  auto inverse = InverseSpectrum::Create(n, channels).value();
  std::vector<double> y(n * channels);
  ASSERT_TRUE(inverse.Process(s, y).ok());
  for (std::size_t i = 0; i < y.size(); ++i) EXPECT_NEAR(y[i], x[i], 1e-12);
}

INSTANTIATE_TEST_SUITE_P(OddAndEven, SpectrumOfLength, ::testing::Values(16, 17, 1000, 1001));

TEST(Spectrum, NyquistSinusoidGivesAmplitudeTimesCosineOfItsPhase) {
  const std::size_t n = 64;
  const auto x = Cosine(n, kFs, kFs / 2.0, 3.0, 0.4);
  const auto s = SpectrumOf(x, 1);
  EXPECT_NEAR(s.back().real(), 3.0 * std::cos(0.4), 1e-12);
  EXPECT_EQ(s.back().imag(), 0.0);
}

TEST(Spectrum, FrequencyAxisIsKTimesFsOverN) {
  auto spectrum = Spectrum::Create(10, 1, 1000.0).value();
  ASSERT_EQ(spectrum.frequencies_hz().size(), 6u);
  for (std::size_t k = 0; k < 6; ++k) {
    EXPECT_DOUBLE_EQ(spectrum.frequencies_hz()[k], 100.0 * static_cast<double>(k));
  }
}

TEST(Spectrum, ChannelsArePlanarAndIndependent) {
  const std::size_t n = 32;
  std::vector<double> x = Cosine(n, kFs, 4.0 * kFs / n, 1.0, 0.0);
  const auto second = Cosine(n, kFs, 9.0 * kFs / n, 2.0, 1.0);
  x.insert(x.end(), second.begin(), second.end());
  const auto s = SpectrumOf(x, 2);
  const std::size_t bins = n / 2 + 1;
  EXPECT_NEAR(std::abs(s[4] - 1.0), 0.0, 1e-12);
  EXPECT_NEAR(std::abs(s[9]), 0.0, 1e-12);
  EXPECT_NEAR(std::abs(s[bins + 9] - std::polar(2.0, 1.0)), 0.0, 1e-12);
  EXPECT_NEAR(std::abs(s[bins + 4]), 0.0, 1e-12);
}

TEST(Spectrum, InverseOfASingleLineIsTheSinusoid) {
  // Path-contribution use: a one-sided line A e^{j phi} at bin k back to A cos(...).
  const std::size_t n = 40;
  std::vector<std::complex<double>> s(n / 2 + 1, 0.0);
  s[5] = std::polar(0.8, -1.1);
  s[0] = 0.3;
  auto inverse = InverseSpectrum::Create(n, 1).value();
  std::vector<double> y(n);
  ASSERT_TRUE(inverse.Process(s, y).ok());
  const auto expected = Cosine(n, kFs, 5.0 * kFs / n, 0.8, -1.1);
  for (std::size_t i = 0; i < n; ++i) EXPECT_NEAR(y[i], expected[i] + 0.3, 1e-13);
}

TEST(Spectrum, RejectsBadConfiguration) {
  auto short_block = Spectrum::Create(1, 1, kFs);
  ASSERT_FALSE(short_block.ok());
  EXPECT_NE(short_block.error().find("block length 1"), std::string::npos);
  auto no_channels = Spectrum::Create(8, 0, kFs);
  ASSERT_FALSE(no_channels.ok());
  EXPECT_NE(no_channels.error().find("channel count"), std::string::npos);
  auto bad_rate = Spectrum::Create(8, 1, std::numeric_limits<double>::quiet_NaN());
  ASSERT_FALSE(bad_rate.ok());
  EXPECT_NE(bad_rate.error().find("sample rate"), std::string::npos);
  EXPECT_FALSE(InverseSpectrum::Create(0, 1).ok());
}

TEST(Spectrum, RejectsEmptyMismatchedAndNonFiniteBlocks) {
  auto spectrum = Spectrum::Create(16, 2, kFs).value();
  std::vector<std::complex<double>> s(18);
  Status empty = spectrum.Process({}, s);
  ASSERT_FALSE(empty.ok());
  EXPECT_NE(empty.error().find("sample block is empty"), std::string::npos) << empty.error();
  std::vector<double> x(31, 0.0);
  Status mismatched = spectrum.Process(x, s);
  ASSERT_FALSE(mismatched.ok());
  EXPECT_NE(mismatched.error().find("31 values, configured for 32"), std::string::npos)
      << mismatched.error();
  x.resize(32, 0.0);
  x[20] = std::numeric_limits<double>::infinity();
  Status non_finite = spectrum.Process(x, s);
  ASSERT_FALSE(non_finite.ok());
  EXPECT_NE(non_finite.error().find("non-finite value at index 20"), std::string::npos)
      << non_finite.error();
  x[20] = 0.0;
  std::vector<std::complex<double>> short_out(17);
  EXPECT_FALSE(spectrum.Process(x, short_out).ok());

  auto inverse = InverseSpectrum::Create(16, 1).value();
  std::vector<double> y(16);
  std::vector<std::complex<double>> line(9, 0.0);
  line[3] = {std::numeric_limits<double>::quiet_NaN(), 0.0};
  Status nan_bin = inverse.Process(line, y);
  ASSERT_FALSE(nan_bin.ok());
  EXPECT_NE(nan_bin.error().find("index 3"), std::string::npos) << nan_bin.error();
  EXPECT_FALSE(inverse.Process(std::span<const std::complex<double>>(line).first(8), y).ok());
}

}  // namespace
}  // namespace gearpath

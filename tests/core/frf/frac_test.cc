#include "core/frf/frac.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

namespace gearpath {
namespace {

Eigen::VectorXd Grid(int n) { return Eigen::VectorXd::LinSpaced(n, 0.0, n - 1.0); }

// A single-DOF accelerance, a shape with a resonance (complex, frequency dependent).
Eigen::VectorXcd Resonance(const Eigen::VectorXd& f, double fn, double zeta) {
  Eigen::VectorXcd h(f.size());
  for (Eigen::Index k = 0; k < f.size(); ++k) {
    const double r = f[k] / fn;
    h[k] = -r * r / Complex(1.0 - r * r, 2.0 * zeta * r);
  }
  return h;
}

TEST(Frac, IsOneForIdenticalFrfs) {
  const Eigen::VectorXd f = Grid(200);
  const Eigen::VectorXcd h = Resonance(f, 80.0, 0.03);
  const Result<double> frac = Frac(f, h, h, 1.0, 199.0);
  ASSERT_TRUE(frac.ok()) << frac.error();
  EXPECT_NEAR(*frac, 1.0, 1e-14);
}

TEST(Frac, IsOneForAComplexScaledCopy) {
  const Eigen::VectorXd f = Grid(200);
  const Eigen::VectorXcd h = Resonance(f, 80.0, 0.03);
  const Eigen::VectorXcd g = Complex(-3.0, 7.5) * h;
  EXPECT_NEAR(*Frac(f, h, g, 0.0, 199.0), 1.0, 1e-14);
}

TEST(Frac, IsZeroForOrthogonalFrfs) {
  // Disjoint support, and a sign pattern orthogonal over the band.
  const Eigen::VectorXd f = Grid(4);
  Eigen::VectorXcd a(4), b(4);
  a << 1.0, 0.0, 2.0, 0.0;
  b << 0.0, Complex(0.0, 5.0), 0.0, -1.0;
  EXPECT_EQ(*Frac(f, a, b, 0.0, 3.0), 0.0);
  a << 1.0, 1.0, 1.0, 1.0;
  b << Complex(0, 1), Complex(0, -1), Complex(0, 1), Complex(0, -1);
  EXPECT_NEAR(*Frac(f, a, b, 0.0, 3.0), 0.0, 1e-30);
}

TEST(Frac, MatchesTheHandValueForTwoBins) {
  // a = (1, 1), b = (1, 0): |1|^2 / (2 * 1) = 0.5.
  const Eigen::VectorXd f = Grid(2);
  Eigen::VectorXcd a(2), b(2);
  a << 1.0, 1.0;
  b << 1.0, 0.0;
  EXPECT_DOUBLE_EQ(*Frac(f, a, b, 0.0, 1.0), 0.5);
}

TEST(Frac, StaysWithinZeroAndOneByCauchySchwarz) {
  const Eigen::VectorXd f = Grid(64);
  std::srand(7);
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::VectorXcd a = Eigen::VectorXcd::Random(64);
    const Eigen::VectorXcd b = Eigen::VectorXcd::Random(64);
    const double frac = *Frac(f, a, b, 3.0, 50.0);
    EXPECT_GE(frac, 0.0);
    EXPECT_LE(frac, 1.0 + 1e-15);
  }
}

TEST(Frac, BandIsInclusiveByFrequency) {
  // Only bins 2 and 3 are in [2, 3]: there a == b, elsewhere they differ.
  const Eigen::VectorXd f = Grid(6);
  Eigen::VectorXcd a(6), b(6);
  a << 1.0, 2.0, 3.0, 4.0, 5.0, 6.0;
  b << -9.0, 1.0, 3.0, 4.0, 0.0, 2.0;
  EXPECT_NEAR(*Frac(f, a, b, 2.0, 3.0), 1.0, 1e-15);
  EXPECT_LT(*Frac(f, a, b, 1.0, 3.0), 0.99);
}

TEST(Frac, RejectsBadInputWithAMessage) {
  const Eigen::VectorXd f = Grid(10);
  const Eigen::VectorXcd h = Resonance(f, 4.0, 0.05);
  Result<double> r = Frac(f, h, h.head(9), 0.0, 9.0);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("size mismatch"), std::string::npos) << r.error();
  r = Frac(f, h, h, 20.0, 30.0);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("no frequency bin lies in the band [20, 30] Hz"), std::string::npos)
      << r.error();
  r = Frac(f, h, h, 5.0, 2.0);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("f_lo <= f_hi"), std::string::npos) << r.error();
  r = Frac(f, h, Eigen::VectorXcd::Zero(10), 0.0, 9.0);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("second FRF is zero"), std::string::npos) << r.error();
  Eigen::VectorXcd bad = h;
  bad[3] = Complex(std::nan(""), 0.0);
  r = Frac(f, bad, h, 0.0, 9.0);
  ASSERT_FALSE(r.ok());
  EXPECT_NE(r.error().find("non-finite FRF value at 3 Hz"), std::string::npos) << r.error();
}

TEST(Frac, PerEntryComparesMatricesEntryByEntry) {
  FrfMatrix a, b;
  a.frequency_hz = Grid(50);
  b.frequency_hz = a.frequency_hz;
  const Eigen::VectorXcd h1 = Resonance(a.frequency_hz, 10.0, 0.05);
  const Eigen::VectorXcd h2 = Resonance(a.frequency_hz, 30.0, 0.05);
  for (Eigen::Index k = 0; k < 50; ++k) {
    Eigen::MatrixXcd m(1, 2);
    m << h1[k], h2[k];
    a.at.push_back(m);
    Eigen::MatrixXcd n(1, 2);
    n << 2.0 * h1[k], h1[k];  // entry (0, 0) same shape, entry (0, 1) different
    b.at.push_back(n);
  }
  const Result<Eigen::MatrixXd> frac = FracPerEntry(a, b, 0.0, 49.0);
  ASSERT_TRUE(frac.ok()) << frac.error();
  EXPECT_NEAR((*frac)(0, 0), 1.0, 1e-14);
  EXPECT_LT((*frac)(0, 1), 0.9);
  b.frequency_hz[3] += 0.5;
  const Result<Eigen::MatrixXd> bad = FracPerEntry(a, b, 0.0, 49.0);
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().find("different frequency axes"), std::string::npos) << bad.error();
}

}  // namespace
}  // namespace gearpath

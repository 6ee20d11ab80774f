// The per-bin operators of IdentificationOperator against an independent reference computed
// here: G = D V diag(phi / sigma) U^H from Eigen::JacobiSVD (what Configure used before issue
// 9), with D, the parameter and phi written out from their definitions (mwi.h,
// regularisation_rule.h). Stated tolerances, relative Frobenius error of G per bin:
//   MWI and Tikhonov with the noise-floor rule (eta = 1e-3): 1e-11 at any condition number
//     (the filter bounds the gain; measured <= 1e-12 up to condition 1e6, where the two
//     SVDs' own errors against a long-double SVD are both ~1e-11);
//   least squares: 100 * eps * condition(H) (a pseudo-inverse is that sensitive whatever SVD).
// Figures: condition numbers as condition_number_test.cc says; ranks equal.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>
#include <limits>
#include <numbers>
#include <random>
#include <string>

#include "core/inverse/condition_number.h"
#include "core/inverse/identification_operator.h"
#include "tests/core/inverse/random_system.h"

namespace gearpath {
namespace {

using testing::RandomSystems;

constexpr double kEps = std::numeric_limits<double>::epsilon();

struct Reference {
  Eigen::MatrixXcd g;
  double condition_h = 0.0;
  double condition_weighted = 0.0;
  Eigen::Index rank = 0;
};

Reference ReferenceOperator(const Eigen::MatrixXcd& h, const IdentificationOptions& o) {
  const Eigen::Index m = h.rows();
  const Eigen::Index n = h.cols();
  Eigen::VectorXd d = Eigen::VectorXd::Ones(n);
  if (o.method == InverseMethod::kMwi) {  // W = diag(1 / ||row_i(H^H H)||), Eq. 40
    const Eigen::MatrixXcd a = h.adjoint() * h;
    for (Eigen::Index i = 0; i < n; ++i) {
      const double norm = a.row(i).norm();
      d(i) = norm > 0.0 ? 1.0 / std::sqrt(norm) : 0.0;  // zero column: force unobservable
    }
  }
  const Eigen::JacobiSVD<Eigen::MatrixXcd> svd(h * d.asDiagonal(),
                                               Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::VectorXd& s = svd.singularValues();
  const double cutoff = o.regularisation.relative_noise * s(0);
  const double ls_cutoff = s(0) * static_cast<double>(std::max(m, n)) * kEps;
  const double parameter = o.method == InverseMethod::kMwi
                               ? cutoff * cutoff / (std::pow(2.0, 1.0 / o.iterations) - 1.0)
                               : cutoff * cutoff;
  const long double k = o.iterations;
  Eigen::VectorXd gain(s.size());
  for (Eigen::Index i = 0; i < s.size(); ++i) {
    // In long double: 1 - r^K in double loses ~K eps absolutely where phi is small, which
    // alone would put ~1e-11 into G at condition 1e6.
    const long double s2 = static_cast<long double>(s(i)) * s(i);
    const long double p = parameter;
    const long double phi = o.method == InverseMethod::kMwi ? 1.0L - std::pow(p / (s2 + p), k)
                            : o.method == InverseMethod::kTikhonov
                                ? s2 / (s2 + p)
                                : (s(i) > ls_cutoff ? 1.0L : 0.0L);
    gain(i) = s(i) > 0.0 ? static_cast<double>(phi / s(i)) : 0.0;
  }
  Reference r;
  r.g = d.asDiagonal() * svd.matrixV() * gain.asDiagonal() * svd.matrixU().adjoint();
  const Eigen::VectorXd sh = Eigen::JacobiSVD<Eigen::MatrixXcd>(h).singularValues();
  r.condition_h = sh(0) / sh(sh.size() - 1);
  r.condition_weighted = s(0) / s(s.size() - 1);
  // Both rules count sigma above sigma_1 * max(m, n) * eps (least squares: its default cutoff).
  r.rank = (s.array() > ls_cutoff).count();
  return r;
}

// Column j of G is the forces for the unit response e_j.
Eigen::MatrixXcd OperatorOf(IdentificationOperator& op, Eigen::Index bin) {
  Eigen::MatrixXcd g(op.paths(), op.channels());
  Eigen::VectorXcd forces(op.paths());
  for (Eigen::Index j = 0; j < op.channels(); ++j) {
    const Eigen::VectorXcd unit = Eigen::VectorXcd::Unit(op.channels(), j);
    EXPECT_EQ(op.Identify(bin, unit, forces), IdentifyStatus::kOk);
    g.col(j) = forces;
  }
  return g;
}

// A housing-like FRF set: per channel-path pair three lightly damped modes plus a direct term
// on the "own" path, 0 .. 4000 Hz.
FrfMatrix ModalFrf(Eigen::Index channels, Eigen::Index paths, int bins, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> natural(300.0, 3500.0), damping(0.01, 0.04),
      gain(-1.0, 1.0);
  std::vector<Eigen::Vector3d> modes(static_cast<std::size_t>(channels * paths * 3));
  for (Eigen::Vector3d& mode : modes) mode = {natural(rng), damping(rng), gain(rng)};
  FrfMatrix frf;
  frf.frequency_hz = Eigen::VectorXd::LinSpaced(bins, 0.0, 4000.0);
  for (int k = 0; k < bins; ++k) {
    const double w = 2.0 * std::numbers::pi * frf.frequency_hz(k);
    Eigen::MatrixXcd h(channels, paths);
    for (Eigen::Index c = 0; c < channels; ++c) {
      for (Eigen::Index p = 0; p < paths; ++p) {
        std::complex<double> v = c % paths == p ? 1e-3 : 0.0;
        for (int i = 0; i < 3; ++i) {
          const Eigen::Vector3d& mode = modes[static_cast<std::size_t>((c * paths + p) * 3 + i)];
          const double wn = 2.0 * std::numbers::pi * mode(0);
          v += 1e-3 * mode(2) * w * w /
               std::complex<double>(wn * wn - w * w, 2.0 * mode(1) * wn * w);
        }
        h(c, p) = v;
      }
    }
    frf.at.push_back(h);
  }
  return frf;
}

FrfMatrix IllConditionedFrf(Eigen::Index channels, Eigen::Index paths, double condition) {
  RandomSystems rnd(111);
  FrfMatrix frf;
  frf.frequency_hz = Eigen::VectorXd::LinSpaced(6, 10.0, 60.0);
  for (int k = 0; k < 6; ++k) frf.at.push_back(rnd.Conditioned(channels, paths, condition, 20.0));
  return frf;
}

IdentificationOptions NoiseFloor(InverseMethod method) {
  IdentificationOptions o;
  o.method = method;
  o.iterations = 50;  // the reference workload's K
  o.regularisation.rule = RegularisationRule::kNoiseFloor;
  o.regularisation.relative_noise = 1e-3;
  return o;
}

void ExpectMatchesReference(const FrfMatrix& frf, const std::string& name) {
  for (InverseMethod method :
       {InverseMethod::kMwi, InverseMethod::kTikhonov, InverseMethod::kLeastSquares}) {
    const IdentificationOptions o = NoiseFloor(method);
    Result<IdentificationOperator> op = IdentificationOperator::Create(frf, o);
    ASSERT_TRUE(op.ok()) << op.error();
    double worst = 0.0;
    for (Eigen::Index k = 0; k < frf.bins(); ++k) {
      const Eigen::MatrixXcd& h = frf.at[static_cast<std::size_t>(k)];
      const Reference ref = ReferenceOperator(h, o);
      const std::string where = name + " " + std::string(ToString(method)) + " bin " +
                                std::to_string(k) + " condition " + std::to_string(ref.condition_h);
      const double error = (OperatorOf(*op, k) - ref.g).norm() / ref.g.norm();
      worst = std::max(worst, error);
      const double tolerance =
          method == InverseMethod::kLeastSquares ? 100.0 * kEps * ref.condition_weighted : 1e-11;
      EXPECT_LE(error, tolerance) << where;
      const BinFigures figures = op->StaticFigures(k);
      EXPECT_NEAR(figures.condition_weighted / ref.condition_weighted, 1.0,
                  1e3 * kEps * ref.condition_weighted)
          << where;
      EXPECT_EQ(figures.rank, ref.rank) << where;
    }
    char worst_text[32];
    std::snprintf(worst_text, sizeof worst_text, "%.2e", worst);
    ::testing::Test::RecordProperty(name + " " + std::string(ToString(method)) + " worst error",
                                    worst_text);
  }
}

TEST(IdentificationOperatorReference, ModalFrfSetsMatchTheJacobiSvdOperators) {
  ExpectMatchesReference(ModalFrf(12, 12, 161, 42), "modal 12x12");
  ExpectMatchesReference(ModalFrf(18, 12, 81, 43), "modal 18x12");
  ExpectMatchesReference(ModalFrf(6, 9, 81, 44), "modal 6x9");
}

TEST(IdentificationOperatorReference, IllConditionedBinsMatchTheJacobiSvdOperators) {
  for (const double condition : {1e3, 1e6}) {
    const std::string name = "condition " + std::to_string(static_cast<int>(condition));
    ExpectMatchesReference(IllConditionedFrf(12, 12, condition), name + " 12x12");
    ExpectMatchesReference(IllConditionedFrf(18, 12, condition), name + " 18x12");
  }
}

TEST(IdentificationOperatorReference, OperatorsAreBitIdenticalForAnyThreadCount) {
  const FrfMatrix frf = ModalFrf(12, 12, 200, 45);
  for (const IdentificationOptions& o :
       {NoiseFloor(InverseMethod::kMwi), NoiseFloor(InverseMethod::kLeastSquares)}) {
    Result<IdentificationOperator> one = IdentificationOperator::Create(frf, o, 1);
    Result<IdentificationOperator> three = IdentificationOperator::Create(frf, o, 3);
    ASSERT_TRUE(one.ok() && three.ok());
    for (Eigen::Index k = 0; k < frf.bins(); ++k) {
      EXPECT_TRUE(OperatorOf(*one, k) == OperatorOf(*three, k)) << "bin " << k;
      const BinFigures a = one->StaticFigures(k);
      const BinFigures b = three->StaticFigures(k);
      EXPECT_EQ(a.condition_weighted, b.condition_weighted) << k;
      EXPECT_EQ(a.parameter, b.parameter) << k;
      EXPECT_EQ(a.rank, b.rank) << k;
    }
  }
}

}  // namespace
}  // namespace gearpath

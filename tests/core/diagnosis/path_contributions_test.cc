#include "core/diagnosis/path_contributions.h"

#include <gtest/gtest.h>

#include <random>
#include <vector>

#include "core/model/lumped_gearbox_model.h"

namespace gearpath {
namespace {

using Complex = std::complex<double>;

struct RandomCase {
  std::vector<Eigen::MatrixXcd> h;
  Eigen::MatrixXcd forces;
};

RandomCase MakeRandom(Eigen::Index channels, Eigen::Index paths, Eigen::Index bins, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> n(0.0, 1.0);
  RandomCase r;
  for (Eigen::Index k = 0; k < bins; ++k) {
    Eigen::MatrixXcd hk(channels, paths);
    for (Eigen::Index i = 0; i < hk.size(); ++i) hk.data()[i] = Complex(n(rng), n(rng)) * 1e3;
    r.h.push_back(hk);
  }
  r.forces.resize(paths, bins);
  for (Eigen::Index i = 0; i < r.forces.size(); ++i) r.forces.data()[i] = Complex(n(rng), n(rng));
  return r;
}

PathContributions MakeContributions(Eigen::Index channels, Eigen::Index paths, Eigen::Index bins) {
  Result<PathContributions> c = PathContributions::Create(channels, paths, bins);
  EXPECT_TRUE(c.ok()) << c.error();
  return std::move(c).value();
}

TEST(PathContributionsTest, ContributionsSumToTheResponseOnRandomData) {
  const Eigen::Index channels = 6, paths = 12, bins = 257;
  const RandomCase r = MakeRandom(channels, paths, bins, 1);
  PathContributions pc = MakeContributions(channels, paths, bins);
  ASSERT_EQ(pc.Compute(r.h, r.forces), ContributionStatus::kOk);
  for (Eigen::Index k = 0; k < bins; ++k) {
    const Eigen::VectorXcd x = r.h[static_cast<std::size_t>(k)] * r.forces.col(k);  // H F
    for (Eigen::Index c = 0; c < channels; ++c) {
      Complex sum = 0.0;
      for (Eigen::Index i = 0; i < paths; ++i) {
        sum += pc.Contribution(i, c)[static_cast<std::size_t>(k)];
      }
      ASSERT_LE(std::abs(sum - x(c)), 1e-12 * x.norm()) << "bin " << k << " channel " << c;
      ASSERT_LE(std::abs(pc.Response(c)[static_cast<std::size_t>(k)] - x(c)), 1e-12 * x.norm());
    }
  }
}

TEST(PathContributionsTest, EachContributionIsOneFrfColumnTimesItsForce) {
  const RandomCase r = MakeRandom(3, 4, 5, 2);
  PathContributions pc = MakeContributions(3, 4, 5);
  ASSERT_EQ(pc.Compute(r.h, r.forces), ContributionStatus::kOk);
  for (Eigen::Index k = 0; k < 5; ++k) {
    for (Eigen::Index i = 0; i < 4; ++i) {
      for (Eigen::Index c = 0; c < 3; ++c) {
        EXPECT_EQ(pc.Contribution(i, c)[static_cast<std::size_t>(k)],
                  r.h[static_cast<std::size_t>(k)](c, i) * r.forces(i, k));
      }
    }
  }
}

TEST(PathContributionsTest, SharesAndProjectionSharesSumToOne) {
  const RandomCase r = MakeRandom(4, 5, 64, 3);
  PathContributions pc = MakeContributions(4, 5, 64);
  ASSERT_EQ(pc.Compute(r.h, r.forces), ContributionStatus::kOk);
  PathEnergy e = pc.MakeEnergy();
  for (Eigen::Index channel : {Eigen::Index{-1}, Eigen::Index{0}, Eigen::Index{3}}) {
    ASSERT_EQ(pc.Energy(10, 40, channel, e), ContributionStatus::kOk);
    EXPECT_NEAR(e.share.sum(), 1.0, 1e-12);
    EXPECT_NEAR(e.projection_share.sum(), 1.0, 1e-12);
    EXPECT_GE(e.share.minCoeff(), 0.0);
    // Independent energies from the definitions.
    double response = 0.0;
    for (Eigen::Index k = 10; k < 40; ++k) {
      const Eigen::VectorXcd x = r.h[static_cast<std::size_t>(k)] * r.forces.col(k);
      response += channel < 0 ? x.squaredNorm() : std::norm(x(channel));
    }
    EXPECT_NEAR(e.response_energy, response, 1e-12 * response);
    Eigen::Index argmax = 0;
    e.share.maxCoeff(&argmax);
    EXPECT_EQ(e.dominant_path, argmax);
  }
}

TEST(PathContributionsTest, OnePathCarriesTheWholeResponse) {
  // Trivial case: a single path's contribution is the response, its share 1.
  const RandomCase r = MakeRandom(2, 1, 8, 4);
  PathContributions pc = MakeContributions(2, 1, 8);
  ASSERT_EQ(pc.Compute(r.h, r.forces), ContributionStatus::kOk);
  PathEnergy e = pc.MakeEnergy();
  ASSERT_EQ(pc.Energy(0, 8, -1, e), ContributionStatus::kOk);
  EXPECT_DOUBLE_EQ(e.share(0), 1.0);
  EXPECT_NEAR(e.projection_share(0), 1.0, 1e-14);
  EXPECT_NEAR(e.response_energy, e.path_energy_sum, 1e-12 * e.response_energy);
  EXPECT_EQ(e.dominant_path, 0);
}

TEST(PathContributionsTest, CancellingPathsShowTheCrossTermAndZeroProjection) {
  // Analytical case: two paths with C_2 = -C_1 everywhere. The response is 0, each path alone
  // carries half the incoherent energy, and the cross term is -(E_1 + E_2).
  std::vector<Eigen::MatrixXcd> h(3, Eigen::MatrixXcd::Ones(1, 2));
  Eigen::MatrixXcd f(2, 3);
  f << Complex(1, 2), Complex(3, -1), Complex(0, 1),  //
      -Complex(1, 2), -Complex(3, -1), -Complex(0, 1);
  PathContributions pc = MakeContributions(1, 2, 3);
  ASSERT_EQ(pc.Compute(h, f), ContributionStatus::kOk);
  PathEnergy e = pc.MakeEnergy();
  ASSERT_EQ(pc.Energy(0, 3, -1, e), ContributionStatus::kOk);
  EXPECT_EQ(e.response_energy, 0.0);
  EXPECT_DOUBLE_EQ(e.energy(0), 5.0 + 10.0 + 1.0);
  EXPECT_DOUBLE_EQ(e.share(0), 0.5);
  EXPECT_DOUBLE_EQ(e.share(1), 0.5);
  EXPECT_DOUBLE_EQ(e.response_energy - e.path_energy_sum, -32.0);
  EXPECT_EQ(e.projection_share, Eigen::VectorXd::Zero(2));
}

TEST(PathContributionsTest, ZeroForcesGiveZeroSharesAndNoDominantPath) {
  std::vector<Eigen::MatrixXcd> h(4, Eigen::MatrixXcd::Ones(2, 3));
  PathContributions pc = MakeContributions(2, 3, 4);
  ASSERT_EQ(pc.Compute(h, Eigen::MatrixXcd::Zero(3, 4)), ContributionStatus::kOk);
  PathEnergy e = pc.MakeEnergy();
  ASSERT_EQ(pc.Energy(0, 4, -1, e), ContributionStatus::kOk);
  EXPECT_EQ(e.share, Eigen::VectorXd::Zero(3));
  EXPECT_EQ(e.dominant_path, -1);
}

TEST(PathContributionsTest, ContributionsOfTheTable1ModelReproduceTheCoupledSeatResponse) {
  // Physical identity on the lumped model (seed Eqs. 6, 7, 45): the seat response of the
  // coupled gearbox driven by mesh TE, H_coupled g, equals the housing-alone FRF H_d,pp times
  // the bearing forces. Both FRFs come from the model's accelerance functions (one sign
  // convention), the forces from its forced response.
  Result<LumpedGearboxModel> model = LumpedGearboxModel::Create(Table1Parameters());
  ASSERT_TRUE(model.ok()) << model.error();
  Eigen::VectorXd freq = Eigen::VectorXd::LinSpaced(200, 5.0, 3980.0);
  Result<FrfMatrix> hpp = model->PhysicalDecoupledPp(freq);
  ASSERT_TRUE(hpp.ok()) << hpp.error();
  const Eigen::Index seats = model->rotor_count();
  Eigen::MatrixXcd forces(seats, freq.size());
  Eigen::MatrixXcd seat_response(seats, freq.size());
  Eigen::VectorXcd te(model->stage_count());
  te << Complex(1e-6, 0.0), Complex(0.2e-6, -0.3e-6);
  for (Eigen::Index k = 0; k < freq.size(); ++k) {
    Result<ForcedResponse> r = model->RespondToTransmissionError(freq(k), te);
    Result<Eigen::MatrixXcd> h = model->Accelerance(freq(k));
    Result<Eigen::VectorXcd> g = model->MeshForce(freq(k), te);
    ASSERT_TRUE(r.ok() && h.ok() && g.ok());
    forces.col(k) = r->bearing_force;
    const Eigen::VectorXcd x = *h * *g;
    for (Eigen::Index s = 0; s < seats; ++s) {
      seat_response(s, k) = x(model->SeatDof(static_cast<int>(s)));
    }
  }
  PathContributions pc = MakeContributions(seats, seats, freq.size());
  ASSERT_EQ(pc.Compute(hpp->at, forces), ContributionStatus::kOk);
  for (Eigen::Index k = 0; k < freq.size(); ++k) {
    for (Eigen::Index c = 0; c < seats; ++c) {
      EXPECT_LE(std::abs(pc.Response(c)[static_cast<std::size_t>(k)] - seat_response(c, k)),
                1e-9 * seat_response.col(k).norm())
          << freq(k) << " Hz, seat " << c;
    }
  }
  PathEnergy e = pc.MakeEnergy();
  ASSERT_EQ(pc.Energy(0, freq.size(), -1, e), ContributionStatus::kOk);
  EXPECT_NEAR(e.share.sum(), 1.0, 1e-12);
  EXPECT_NEAR(e.projection_share.sum(), 1.0, 1e-12);
}

TEST(PathContributionsValidationTest, RejectsEmptyShapes) {
  Result<PathContributions> c = PathContributions::Create(3, 0, 10);
  ASSERT_FALSE(c.ok());
  EXPECT_EQ(c.error(), "path contributions: paths must be >= 1, got 0");
  c = PathContributions::Create(-1, 2, 10);
  ASSERT_FALSE(c.ok());
  EXPECT_EQ(c.error(), "path contributions: channels must be >= 1, got -1");
}

TEST(PathContributionsValidationTest, RejectsInputsOfTheWrongShape) {
  const RandomCase r = MakeRandom(3, 4, 5, 5);
  PathContributions pc = MakeContributions(3, 4, 5);
  std::vector<Eigen::MatrixXcd> short_h(r.h.begin(), r.h.end() - 1);
  EXPECT_EQ(pc.Compute(short_h, r.forces), ContributionStatus::kShapeMismatch);
  std::vector<Eigen::MatrixXcd> bad_h = r.h;
  bad_h[2] = Eigen::MatrixXcd::Zero(4, 3);  // transposed
  EXPECT_EQ(pc.Compute(bad_h, r.forces), ContributionStatus::kShapeMismatch);
  EXPECT_EQ(pc.Compute(r.h, r.forces.transpose()), ContributionStatus::kShapeMismatch);
  ASSERT_EQ(pc.Compute(r.h, r.forces), ContributionStatus::kOk);
  PathEnergy e = pc.MakeEnergy();
  EXPECT_EQ(pc.Energy(3, 3, -1, e), ContributionStatus::kBadBinRange);
  EXPECT_EQ(pc.Energy(0, 6, -1, e), ContributionStatus::kBadBinRange);
  EXPECT_EQ(pc.Energy(0, 5, 3, e), ContributionStatus::kBadChannel);
  PathEnergy wrong;
  EXPECT_EQ(pc.Energy(0, 5, -1, wrong), ContributionStatus::kShapeMismatch);
  EXPECT_TRUE(pc.Contribution(4, 0).empty());
  EXPECT_TRUE(pc.Response(3).empty());
  EXPECT_EQ(ToString(ContributionStatus::kShapeMismatch),
            "FRF or force shape differs from the configured channels x paths x bins");
}

}  // namespace
}  // namespace gearpath

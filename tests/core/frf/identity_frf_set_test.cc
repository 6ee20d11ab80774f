// MakeIdentityFrfSet: one path per sensor channel, H = I at every frequency, and validation
// that names the offending argument.
#include "core/frf/identity_frf_set.h"

#include <gtest/gtest.h>

#include <limits>

namespace gearpath {
namespace {

std::vector<ResponseChannel> ThreeChannels() { return {{"A1", "x"}, {"A1", "z"}, {"A2", "y"}}; }
std::vector<std::vector<std::string>> ThreeGearLists() { return {{"G1"}, {"G1", "G2"}, {"G3"}}; }
Eigen::VectorXd Grid() { return Eigen::VectorXd::LinSpaced(5, 1.0, 4000.0); }

TEST(IdentityFrfSet, EverySensorChannelIsItsOwnPathWithTheGearsItSitsNear) {
  auto set = MakeIdentityFrfSet(ThreeChannels(), ThreeGearLists(), Grid());
  ASSERT_TRUE(set.ok()) << set.error();
  EXPECT_EQ(set->decoupling, "identity");
  ASSERT_EQ(set->channels.size(), 3u);
  ASSERT_EQ(set->paths.size(), 3u);
  EXPECT_EQ(set->paths[0].name, "A1/x");
  EXPECT_EQ(set->paths[1].name, "A1/z");
  EXPECT_EQ(set->paths[2].name, "A2/y");
  EXPECT_EQ(set->paths[1].direction, "z");
  EXPECT_EQ(set->paths[1].gears, (std::vector<std::string>{"G1", "G2"}));
  EXPECT_EQ(set->channels[2].sensor, "A2");
  EXPECT_FALSE(set->coupled.has_value());
}

TEST(IdentityFrfSet, TheDecoupledMatrixIsTheIdentityAtEveryFrequencyOfTheGrid) {
  const Eigen::VectorXd grid = Grid();
  auto set = MakeIdentityFrfSet(ThreeChannels(), ThreeGearLists(), grid);
  ASSERT_TRUE(set.ok()) << set.error();
  const FrfMatrix& h = set->decoupled;
  ASSERT_EQ(h.bins(), grid.size());
  EXPECT_EQ(h.frequency_hz, grid);
  EXPECT_EQ(h.outputs(), 3);
  EXPECT_EQ(h.inputs(), 3);
  for (const Eigen::MatrixXcd& m : h.at) {
    EXPECT_TRUE(m.isApprox(Eigen::MatrixXcd::Identity(3, 3), 0.0)) << m;
    EXPECT_EQ((m * m.adjoint() - Eigen::MatrixXcd::Identity(3, 3)).norm(), 0.0);
  }
}

TEST(IdentityFrfSet, ASingleChannelAndASinglePointAreEnough) {
  Eigen::VectorXd one(1);
  one << 10.0;
  auto set = MakeIdentityFrfSet({{"S", "x"}}, {{"G"}}, one);
  ASSERT_TRUE(set.ok()) << set.error();
  EXPECT_EQ(set->decoupled.at.size(), 1u);
  EXPECT_EQ(set->decoupled.at[0](0, 0), Complex(1.0, 0.0));
}

// The error must start with the argument (and index) it is about.
void ExpectError(const Result<FrfSet>& r, const std::string& prefix) {
  ASSERT_FALSE(r.ok());
  EXPECT_EQ(r.error().rfind(prefix, 0), 0u) << r.error();
}

TEST(IdentityFrfSet, BadChannelsAreRefusedNamingTheChannel) {
  ExpectError(MakeIdentityFrfSet({}, {}, Grid()), "channels: empty");
  ExpectError(MakeIdentityFrfSet({{"", "x"}}, {{"G1"}}, Grid()), "channels[0].sensor: empty");
  ExpectError(MakeIdentityFrfSet({{"A1", "x"}, {"A1", "w"}}, {{"G1"}, {"G1"}}, Grid()),
              "channels[1].axis: expected x, y or z");
  ExpectError(MakeIdentityFrfSet({{"A1", "x"}, {"A1", "x"}}, {{"G1"}, {"G2"}}, Grid()),
              "channels[1]: sensor A1 axis x is listed twice");
}

TEST(IdentityFrfSet, BadGearListsAreRefusedNamingTheList) {
  ExpectError(MakeIdentityFrfSet(ThreeChannels(), {{"G1"}}, Grid()),
              "gears_per_channel: 1 entries for 3 channels");
  ExpectError(MakeIdentityFrfSet(ThreeChannels(), {{"G1"}, {}, {"G3"}}, Grid()),
              "gears_per_channel[1]: no gear named");
  ExpectError(MakeIdentityFrfSet(ThreeChannels(), {{"G1"}, {"G2", ""}, {"G3"}}, Grid()),
              "gears_per_channel[1][1]: empty");
  ExpectError(MakeIdentityFrfSet(ThreeChannels(), {{"G1"}, {"G2", "G2"}, {"G3"}}, Grid()),
              "gears_per_channel[1][1]: gear \"G2\" is named twice");
}

TEST(IdentityFrfSet, ABadGridIsRefusedNamingTheFrequency) {
  ExpectError(MakeIdentityFrfSet(ThreeChannels(), ThreeGearLists(), Eigen::VectorXd()),
              "frequency_hz: empty");
  Eigen::VectorXd down(3);
  down << 1.0, 3.0, 2.0;
  ExpectError(MakeIdentityFrfSet(ThreeChannels(), ThreeGearLists(), down),
              "frequency_hz[2]: 2 Hz does not exceed");
  Eigen::VectorXd nan(2);
  nan << 1.0, std::numeric_limits<double>::quiet_NaN();
  ExpectError(MakeIdentityFrfSet(ThreeChannels(), ThreeGearLists(), nan), "frequency_hz[1]:");
  Eigen::VectorXd negative(2);
  negative << -1.0, 1.0;
  ExpectError(MakeIdentityFrfSet(ThreeChannels(), ThreeGearLists(), negative),
              "frequency_hz[0]:");
}

}  // namespace
}  // namespace gearpath

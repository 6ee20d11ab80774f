// ToothMesh: single and double tooth contact alternate at the mesh frequency with the contact
// ratio's duty cycle; the mean stiffness is the pair shape's integral; a crack lowers only the
// pairs that hold the damaged tooth, once per revolution of its gear; missing material acts only
// while that tooth is in contact; wear is smooth; the profile error is its harmonics.
#include "core/evaluation/tooth_mesh.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace gearpath {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

ToothMeshParameters Plain() {
  ToothMeshParameters p;
  p.z_driver = 28;
  p.z_driven = 40;
  p.contact_ratio = 1.62;
  p.pair_stiffness_n_per_m = 2.2e8;
  p.ramp_periods = 0.08;
  p.crown = 0.2;
  p.base_pitch_m = std::numbers::pi * 3e-3 * std::cos(20.0 * std::numbers::pi / 180.0);
  p.mesh_phase = 0.0;
  return p;
}

// Driver shaft at `revs` input revolutions with ratio 1, driven at 28 / 40.
MeshSample At(const ToothMesh& mesh, double driver_revs, const ToothFault* fault = nullptr) {
  MeshSample s;
  mesh.Evaluate(MakeShaftPhase(driver_revs, 10.0), MakeShaftPhase(driver_revs * 0.7, 7.0), fault,
                false, s);
  return s;
}

TEST(ToothMesh, SingleAndDoubleContactAlternateWithTheContactRatio) {
  Result<ToothMesh> mesh = ToothMesh::Create(Plain());
  ASSERT_TRUE(mesh.ok()) << mesh.error();
  // Over one mesh period (1/28 driver revolution): double contact for eps - 1 = 0.62 of it.
  int doubles = 0;
  const int n = 10000;
  double k_single_mid = 0.0, k_double_mid = 0.0;
  for (int i = 0; i < n; ++i) {
    const double u = (i + 0.5) / n;  // mesh cycles
    const MeshSample s = At(*mesh, u / 28.0);
    EXPECT_EQ(s.pairs, u < 0.62 ? 2 : 1) << u;
    doubles += s.pairs == 2;
    if (std::abs(u - 0.31) < 0.5 / n) k_double_mid = s.TotalStiffness();
    if (std::abs(u - 0.81) < 0.5 / n) k_single_mid = s.TotalStiffness();
  }
  EXPECT_EQ(doubles, 6200);
  EXPECT_GT(k_double_mid / k_single_mid, 1.5);
  EXPECT_LT(k_double_mid / k_single_mid, 1.9);
  // Single contact, mid-path: one pair at u = 0.81 of a 1.62 path: full shape (no crown loss).
  EXPECT_NEAR(k_single_mid, 2.2e8, 1e-6 * 2.2e8);
  // Mean: the integral of one pair's shape (one pair engages per period).
  double integral = 0.0;
  for (int i = 0; i < 100000; ++i) integral += mesh->PairShape((i + 0.5) * 1.62 / 100000) * 1.62 / 100000;
  EXPECT_NEAR(mesh->mean_stiffness(), 2.2e8 * integral, 1e-4 * mesh->mean_stiffness());
  EXPECT_GT(mesh->max_stiffness(), mesh->mean_stiffness());
  // Smooth engagement: the shape rises from 0 over the ramp.
  EXPECT_EQ(mesh->PairShape(0.0), 0.0);
  EXPECT_NEAR(mesh->PairShape(0.04), 0.5 * (1.0 - 0.2 * std::pow(2 * 0.04 / 1.62 - 1, 2)), 1e-12);
  EXPECT_EQ(mesh->PairShape(1.62), 0.0);
}

TEST(ToothMesh, ProfileErrorIsItsHarmonicsAndItsRate) {
  ToothMeshParameters p = Plain();
  p.profile_amplitude_m = {1e-6, 0.3e-6};
  p.profile_phase = {0.4, -1.1};
  Result<ToothMesh> mesh = ToothMesh::Create(p);
  ASSERT_TRUE(mesh.ok());
  for (double revs : {0.0123, 0.5, 3.2777}) {
    const MeshSample s = At(*mesh, revs);
    const double m = 28.0 * revs;
    const double e = 1e-6 * std::cos(kTwoPi * m + 0.4) + 0.3e-6 * std::cos(2 * kTwoPi * m - 1.1);
    const double rate = -(1e-6 * kTwoPi * std::sin(kTwoPi * m + 0.4) +
                          0.3e-6 * 2 * kTwoPi * std::sin(2 * kTwoPi * m - 1.1)) *
                        280.0;
    EXPECT_NEAR(s.ErrorForce(), s.TotalStiffness() * e, 1e-9 * s.TotalStiffness() * 1e-6);
    for (int j = 0; j < s.pairs; ++j) EXPECT_NEAR(s.gap[j], e, 1e-18);
    EXPECT_NEAR(s.error_rate, rate, 1e-9 * std::abs(rate) + 1e-12);
  }
}

TEST(ToothMesh, CrackLowersOnlyThePairsOfTheDamagedToothOncePerRevolution) {
  ToothMeshParameters p = Plain();
  p.driver_tooth_offset = 5;
  Result<ToothMesh> mesh = ToothMesh::Create(p);
  ASSERT_TRUE(mesh.ok());
  ToothFault crack;
  crack.kind = PlantFaultKind::kMeshAm;
  crack.stage = 0;
  crack.on_driver = true;
  crack.tooth = 9;  // pairs j with (j + 5) mod 28 == 9: j = 4, 32, ...
  crack.severity.am_depth = 0.3;
  ASSERT_TRUE(mesh->CheckFault(crack).ok());
  const int n = 28 * 400;
  for (int i = 0; i < 2 * n; ++i) {
    const double m = (i + 0.5) / 400.0;  // mesh cycles over two revolutions
    const MeshSample h = At(*mesh, m / 28.0);
    const MeshSample f = At(*mesh, m / 28.0, &crack);
    const double within = std::fmod(m, 28.0);
    const bool tooth_in_contact = within >= 4.0 && within < 4.0 + 1.62;
    if (!tooth_in_contact) {
      EXPECT_EQ(f.TotalStiffness(), h.TotalStiffness()) << m;
    } else {
      // The damaged pair's share, 0.3 of it, is gone.
      const double pair = 2.2e8 * mesh->PairShape(within - 4.0);
      EXPECT_NEAR(f.TotalStiffness(), h.TotalStiffness() - 0.3 * pair, 1e-6 * h.TotalStiffness())
          << m;
    }
    for (int j = 0; j < f.pairs; ++j) EXPECT_EQ(f.gap[j], h.gap[j]);  // no profile change
    EXPECT_EQ(f.error_rate, h.error_rate);
  }
}

TEST(ToothMesh, MissingMaterialActsOnlyDuringTheToothsContactWithSharpEdges) {
  ToothMeshParameters p = Plain();
  p.driven_tooth_offset = 11;
  Result<ToothMesh> mesh = ToothMesh::Create(p);
  ASSERT_TRUE(mesh.ok());
  ToothFault spall;
  spall.kind = PlantFaultKind::kTePulse;
  spall.stage = 0;
  spall.on_driver = false;  // on the 40-tooth gear
  spall.tooth = 3;          // pairs j with (j + 11) mod 40 == 3: j = 32, 72, ...
  spall.spall_start = 0.5;
  spall.severity.pulse_depth_m = 2e-6;
  spall.severity.pulse_length_periods = 0.6;
  spall.severity.pulse_taper = 0.08;
  ASSERT_TRUE(mesh->CheckFault(spall).ok());
  for (int i = 0; i < 40 * 200; ++i) {
    const double m = (i + 0.5) / 200.0;
    const MeshSample h = At(*mesh, m / 28.0);
    const MeshSample f = At(*mesh, m / 28.0, &spall);
    EXPECT_EQ(f.TotalStiffness(), h.TotalStiffness());
    const double u = m - 32.0;  // path position of the damaged pair
    const double expected = u >= 0.0 && u < 1.62 ? 2e-6 * TaperedWindow(u - 0.5, 0.6, 0.08) : 0.0;
    // The damaged pair is the older one (slot 1) once a newer pair has engaged.
    double extra = 0.0;
    for (int j = 0; j < f.pairs; ++j) extra += f.gap[j] - h.gap[j];
    EXPECT_NEAR(extra, expected, 1e-15) << m;
  }
}

TEST(ToothMesh, WearIsASmoothWornFlankOnTheToothAndLessOnItsNeighbours) {
  Result<ToothMesh> mesh = ToothMesh::Create(Plain());
  ASSERT_TRUE(mesh.ok());
  ToothFault wear;
  wear.kind = PlantFaultKind::kWearDip;
  wear.stage = 0;
  wear.on_driver = true;
  wear.tooth = 0;  // offset 0: pair j holds driver tooth j mod 28; tooth 0 meshes at m in [0, 1.62)
  wear.wear_length = 3.0;
  wear.severity.dip_depth_m = 1e-6;
  ASSERT_TRUE(mesh->CheckFault(wear).ok());
  double peak = 0.0, peak_m = 0.0;
  for (int i = -3000; i < 4000; ++i) {
    const double m = (i + 0.5) / 1000.0;
    const double revs = (m < 0 ? m + 28.0 : m) / 28.0;
    const MeshSample h = At(*mesh, revs);
    const MeshSample f = At(*mesh, revs, &wear);
    ASSERT_EQ(f.pairs, h.pairs);
    for (int j = 0; j < f.pairs; ++j) {
      // Slot j holds pair floor(m) - j, at path position u = frac(m) + j.
      const double u = m - std::floor(m) + j;
      const int tooth = static_cast<int>(std::floor(m)) - j;  // -1 = tooth 27, 1 = tooth 1
      const double across = std::abs(tooth) <= 1 ? std::pow(std::cos(std::numbers::pi * tooth / 3.0), 2) : 0.0;
      const double expected = 1e-6 * across * std::pow(std::sin(std::numbers::pi * u / 1.62), 2);
      EXPECT_NEAR(f.gap[j] - h.gap[j], expected, 1e-15) << m << " slot " << j;
      EXPECT_EQ(f.stiffness[j], h.stiffness[j]);
      if (f.gap[j] - h.gap[j] > peak) {
        peak = f.gap[j] - h.gap[j];
        peak_m = m;
      }
    }
  }
  EXPECT_NEAR(peak, 1e-6, 1e-9);
  EXPECT_NEAR(peak_m, 0.81, 2e-3);  // the worn tooth, mid-path
}

TEST(ToothMesh, RejectsBadParametersAndFaultsByName) {
  ToothMeshParameters p = Plain();
  p.contact_ratio = 2.1;
  Result<ToothMesh> bad = ToothMesh::Create(p);
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().find("contact_ratio"), std::string::npos);
  p = Plain();
  p.profile_amplitude_m = {1e-6};
  EXPECT_FALSE(ToothMesh::Create(p).ok());
  Result<ToothMesh> mesh = ToothMesh::Create(Plain());
  ToothFault f;
  f.kind = PlantFaultKind::kTePulse;
  f.tooth = 28;  // a 28-tooth driver has teeth 0..27
  EXPECT_FALSE(mesh->CheckFault(f).ok());
  f.tooth = 3;
  f.spall_start = 1.5;  // + 1.0 long: beyond the 1.62 contact path
  EXPECT_FALSE(mesh->CheckFault(f).ok());
}

}  // namespace
}  // namespace gearpath

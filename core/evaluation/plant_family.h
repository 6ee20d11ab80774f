// Plant families of the evaluation: the "true" gearbox (its dynamics, PlantDynamics) and the
// FRF set the daemon is given for it (a MODEL of the plant, never the truth itself).
//
//  lumped_perturbed  the plant is the lumped model (core/model) with every mass, stiffness and
//                    damping value scaled independently by a factor drawn in [0.7, 1.3]: seat
//                    masses, housing mass, gear density (rotor masses), bearing, seat, ground
//                    and mesh stiffnesses, bearing, seat and ground dampings, mesh damping
//                    ratio. The daemon's FRF set is the NOMINAL model's (MakeModelFrfSet):
//                    Eq. 22 at the seats p1..pN+1; for the 4-channel set the Eq. 24 row m1 is
//                    stacked under it (channels p1..pN+1, m1 x paths B1x..).
//  lumped_torsional  as lumped_perturbed, plus torsional couplings of the input and output
//                    rotors to ground (motor / load, 2e3..2e4 N m / rad) and a mesh damping
//                    ratio of 0.05..0.10: rotor-side physics the FRF model does not know.
//  modal_housing     a tuning family since 2026-11-27 (held out until parametric_plate came;
//                    docs/evaluation.md). Not the lumped
//                    model at all: the housing is a random modal model, 6..12 modes between
//                    300 Hz and 3.5 kHz (log-uniform), damping 1..4 %, modal masses 5..30 kg,
//                    random mode shapes at the bearing seats p1..pN+1 and the point m1:
//                      H_true(f)[c, b] = sum_r phi_r(c) phi_r(b) (-w^2)
//                                        / (w_r^2 - w^2 + 2 j z_r w_r w).
//                    Bearing forces come straight from the mesh excitation: stage s pushes with
//                    k_s R_s(f) TE_s(f) (k_s: the nominal mesh stiffness x U(0.8, 1.2); R_s a
//                    single-DOF rotor resonance in 1.2..3 kHz, 5 % damping) on bearing s with
//                    lever fraction lambda_s in [0.35, 0.65] and on bearing s + 1 with
//                    -(1 - lambda_s); responses = H_true F. The daemon gets H_model: the same
//                    modes with frequencies shifted by up to +/- 5 % and dampings changed by up
//                    to +/- 30 %.
//  parametric_plate  HELD OUT. A different physics in excitation, rotors and housing: a
//                    time-domain simulation of the two-stage train with time-varying mesh
//                    stiffness (tooth pairs in contact, parametric excitation), profile errors,
//                    eccentricity, torsional and lateral rotor DOFs on bearings standing on a
//                    simply supported plate (analytic modes up to 5 kHz, two-way coupled);
//                    tooth faults of its own physics (crack = stiffness loss of the tooth's
//                    pairs, missing material, wear). The daemon gets the plate's FRFs from a
//                    model with modes above ~2.5 kHz missing, thickness / modulus off by a few
//                    percent and damping off by up to 30 % (parametric_plate_plant.h).
// Trains (TrainVariant): Table 1 (28 / 40 / 34 / 34: G3 and G4 are inseparable) or a variant
// with distinct counts on every gear (output gear 29 teeth). One bearing per shaft (B1..).
// The FRF sets cover bins 1..4096 of an 8192-sample block at 8 kHz (0.98 Hz .. 4 kHz).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string_view>
#include <vector>

#include "core/common/accel_block.h"
#include "core/common/result.h"
#include "core/evaluation/plant_simulator.h"
#include "core/frf/frf_set.h"
#include "core/model/gear_train.h"
#include "core/model/lumped_gearbox_model.h"

namespace gearpath {

enum class PlantFamily : std::uint8_t {
  kLumpedPerturbed,
  kLumpedTorsional,
  kModalHousing,
  kParametricPlate
};
inline constexpr PlantFamily kAllPlantFamilies[] = {
    PlantFamily::kLumpedPerturbed, PlantFamily::kLumpedTorsional, PlantFamily::kModalHousing,
    PlantFamily::kParametricPlate};
std::string_view PlantFamilyName(PlantFamily family) noexcept;
std::optional<PlantFamily> ParsePlantFamily(std::string_view name) noexcept;
// The families no tuning decision may see (any number of them; moving a family to the tuning
// side is removing it from this list).
inline constexpr PlantFamily kHeldOutFamilies[] = {PlantFamily::kParametricPlate};
constexpr bool IsHeldOut(PlantFamily family) noexcept {
  for (PlantFamily held_out : kHeldOutFamilies) {
    if (held_out == family) return true;
  }
  return false;
}

enum class TrainVariant : std::uint8_t { kTable1, kDistinct };
std::string_view TrainVariantName(TrainVariant variant) noexcept;  // "table1", "distinct"
GearTrain MakeTrain(TrainVariant variant);

enum class ChannelSet : std::uint8_t { kSeats, kSeatsAndHousing };
std::string_view ChannelSetName(ChannelSet set) noexcept;  // "p", "p+m"

struct PlantSpec {
  PlantFamily family = PlantFamily::kLumpedPerturbed;
  TrainVariant variant = TrainVariant::kTable1;
  ChannelSet channels = ChannelSet::kSeats;
  std::uint64_t seed = 1;
};

struct ParametricPlatePlant;  // parametric_plate_plant.h

// The truth is either a linear TE -> response transfer (`dynamics`, synthesised in the frequency
// domain by PlantSimulator) or a time-domain model (`parametric`, ParametricPlantSimulator);
// exactly one is set. MakePlantStream (plant_stream.h) picks the simulator.
struct Plant {
  PlantSpec spec;
  GearTrain train;
  std::vector<ChannelInfo> channels;              // block channels, FRF row order
  FrfSet model_frf;                               // what the daemon is given
  std::shared_ptr<const PlantDynamics> dynamics;  // the truth (linear families)
  std::shared_ptr<const ParametricPlatePlant> parametric;  // the truth (parametric_plate)
};

// The FRF grid of the daemon's sets: bins 1..4096 of 8192 samples at 8 kHz.
Eigen::VectorXd EvaluationFrfGrid();

Result<Plant> MakePlant(const PlantSpec& spec);

// --- Building blocks, public for the tests ---

// Nominal lumped parameters of a train (Table 1 values, the train's tooth counts).
GearboxParameters NominalParameters(const GearTrain& train);
// The lumped families' plant parameters (perturbation drawn from `seed`).
GearboxParameters PerturbedParameters(const GearboxParameters& nominal, bool torsional,
                                      std::uint64_t seed);

// A lumped model as a plant: rows = seats (p1..), then the housing mass (m1) if asked.
class LumpedPlantDynamics final : public PlantDynamics {
 public:
  LumpedPlantDynamics(LumpedGearboxModel model, bool include_housing)
      : model_(std::move(model)), include_housing_(include_housing) {}
  int channel_count() const override { return model_.rotor_count() + (include_housing_ ? 1 : 0); }
  int stage_count() const override { return model_.stage_count(); }
  Result<FrfMatrix> TeTransfer(const Eigen::VectorXd& frequency_hz) const override;
  const LumpedGearboxModel& model() const { return model_; }

 private:
  LumpedGearboxModel model_;
  bool include_housing_;
};

struct HousingMode {
  double frequency_hz = 0.0;
  double damping_ratio = 0.0;
  Eigen::VectorXd shape;  // one entry per point: seats p1..pN+1, then m1
};

// The held-out family's housing + rotor-side force model.
class ModalHousingDynamics final : public PlantDynamics {
 public:
  struct MeshSource {
    double stiffness_n_per_m = 0.0;
    double rotor_hz = 0.0;  // single-DOF rotor resonance
    double rotor_damping = 0.05;
    double lever = 0.5;  // fraction on the driver's bearing; -(1 - lever) on the driven one
  };
  // Draws modes and sources from the seed (see the file comment).
  static ModalHousingDynamics Random(const GearTrain& train, bool include_housing,
                                     std::uint64_t seed);
  int channel_count() const override { return channels_; }
  int stage_count() const override { return static_cast<int>(sources_.size()); }
  Result<FrfMatrix> TeTransfer(const Eigen::VectorXd& frequency_hz) const override;
  // H (channels x seats) of a mode set at one frequency; the truth uses modes().
  Eigen::MatrixXcd Accelerance(const std::vector<HousingMode>& modes, double frequency_hz) const;
  // Bearing forces per unit TE (seats x stages) at one frequency.
  Eigen::MatrixXcd ForceTransfer(double frequency_hz) const;
  const std::vector<HousingMode>& modes() const { return modes_; }
  // The modes the daemon's FRF set is made from (shifted frequencies, changed dampings).
  const std::vector<HousingMode>& model_modes() const { return model_modes_; }

 private:
  int seats_ = 0;
  int channels_ = 0;
  std::vector<HousingMode> modes_, model_modes_;
  std::vector<MeshSource> sources_;
};

}  // namespace gearpath

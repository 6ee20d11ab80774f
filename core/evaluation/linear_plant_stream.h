// LinearPlantStream: the PlantStream of the families whose truth is a linear TE -> response
// transfer (PlantSimulator, frequency-domain synthesis).
//
// Severity: every fault model of PlantExcitation is linear in its depths (TE_f = (1 - s d w)
// TE_h + s p), and so is the plant: with all depths scaled by s the faulty block is H + s G,
// G = F(1) - H. The smallest s > 0 at which some channel's RMS reaches (1 +/- target) x its
// healthy RMS solves, per channel, |G|^2 s^2 + 2 <H, G> s + |H|^2 (1 - (1 +/- target)^2) = 0:
// exact, one healthy and one faulty noise-free block.
#pragma once

#include "core/evaluation/plant_simulator.h"
#include "core/evaluation/plant_stream.h"

namespace gearpath {

class LinearPlantStream final : public PlantStream {
 public:
  explicit LinearPlantStream(PlantSimulator simulator) : sim_(std::move(simulator)) {}

  SeverityFit NormaliseSeverity(double target) override;
  PlantFaultSeverity severity() const override { return sim_.excitation().severity(); }
  void NextBlock(bool fault_on, AccelBlock& block) override { sim_.NextBlock(fault_on, block); }

  PlantSimulator& simulator() noexcept { return sim_; }

 private:
  PlantSimulator sim_;
};

// The exact factor (see the file comment) for the block starting at first_sample; 0 = no
// s > 0 reaches the target.
double SeverityScaleForRmsChange(PlantSimulator& sim, std::int64_t first_sample, double target);
// Signed raw RMS change of the channel whose RMS changes most, faulty vs healthy, noise-free.
double MaxRmsChange(PlantSimulator& sim, std::int64_t first_sample);

}  // namespace gearpath

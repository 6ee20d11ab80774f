// The mesh evidence harmonic by harmonic (docs/diagnosis.md sections 11 and 13, sixteenth
// session): each mesh harmonic's neighbourhood gets its own robust z, so the harmonic the
// housing transmits most loudly no longer outvotes the others inside one mesh's evidence.
#include <gtest/gtest.h>

#include "core/evaluation/evaluation_runner.h"
#include "core/evaluation/scenario_matrix.h"
#include "tests/core/evaluation/scenario_of.h"

namespace gearpath {
namespace {

// Tuning-matrix scenarios, one per family, each a fault on the intermediate shaft, which
// carries one gear on each mesh. With one z of the three harmonics' summed energies each named
// the gear on the other mesh in most of its alarmed blocks (`gearpath evaluate --matrix full
// --sample 400` at 3c13fa9); with a z per harmonic each names its own gear.
TEST(MeshEvidencePerHarmonic, NamesTheFaultyGearsMeshWhereSummedEnergiesNamedTheOther) {
  const Scenario scenarios[] = {
      testing::ScenarioOf(PlantFamily::kLumpedTorsional, TrainVariant::kTable1,
                          PlantFaultKind::kWearDip, "G3", 450.0, 0.10,
                          ChannelSet::kSeatsAndHousing, false),
      testing::ScenarioOf(PlantFamily::kLumpedPerturbed, TrainVariant::kDistinct,
                          PlantFaultKind::kTePulse, "G3", 200.0, 0.05,
                          ChannelSet::kSeatsAndHousing, true),
      testing::ScenarioOf(PlantFamily::kModalHousing, TrainVariant::kDistinct,
                          PlantFaultKind::kCombined, "G2", 900.0, 0.05, ChannelSet::kSeats,
                          true),
  };
  for (const Scenario& s : scenarios) {
    SCOPED_TRACE(s.Key());
    const ScenarioOutcome out = testing::RunExpectingRightGear(s);
    const testing::NamedShaftBlocks n = testing::CountNamedShaft(out, "intermediate");
    EXPECT_EQ(n.naming, n.alarmed) << "alarmed blocks naming the intermediate shaft";
  }
}

}  // namespace
}  // namespace gearpath

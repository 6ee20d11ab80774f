// MachineContext: everything about one machine that is fixed once its setup is validated (the
// FRF set, the channel mapping, the gear train's kinematics and the verdict's topology, the
// analysis band, the block expectations). Built once by BlockProcessor::Create; read-only for
// every stage afterwards, so one instance can serve every block shape of the machine.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "core/common/result.h"
#include "core/diagnosis/dominant_path.h"
#include "core/diagnosis/gear_verdict.h"
#include "core/pipeline/block_processor.h"
#include "core/pipeline/block_validation.h"

namespace gearpath {

// Shafts turning at the same rate (within the harmonic tolerance) form one rate group: their
// synchronous averages are identical, so every rate-based indicator is computed once per group.
struct RateGroup {
  double ratio = 0.0;             // group rate / input-shaft rate
  std::vector<int> shafts;        // TrainLayout shaft indices
  std::vector<int> gears;         // gears keyed on those shafts
  std::vector<int> gear_teeth;    // their tooth counts = their mesh orders on this group's TSA
  std::vector<int> gear_meshes;   // their mesh indices (-1: in no mesh)
  std::vector<int> meshes;        // distinct meshes of those gears
  std::vector<int> mesh_orders;   // each one's order on this group's synchronous average
  // Names of one condition-indicator set at this rate: the core indicators, the per-mesh
  // sideband energies ("sideband_<mesh name>"), the exclusive residual.
  std::vector<std::string> indicator_names;
  // Each one's power of the signal's amplitude (AmplitudePower; the energies 2).
  std::vector<int> indicator_powers;
};

// One signal whose condition indicators are computed at every rate group.
struct ConditionSignal {
  ConditionSource source = ConditionSource::kMeasured;
  int index = -1;    // FRF row (measured) or path
  std::string name;  // "A1/x" or the path name
};

// Where one (signal, group) set of condition indicators sits in the machine's indicator
// vector (the vector the healthy baseline learns).
struct ConditionSlot {
  std::size_t signal = 0;  // index into MachineContext::condition_signals
  std::size_t group = 0;   // index into MachineContext::rate_groups
  std::size_t offset = 0;  // first entry in the indicator vector
  std::size_t count = 0;   // entries: rate_groups[group].indicator_names.size()
};

// Where one mesh's transfer signature (core/diagnosis/mesh_signature.h) at one rate group,
// over one sensor array (the measured channels or the identified forces), sits in the
// indicator vector: two entries, the parallel and the orthogonal sideband energy.
struct SignatureSlot {
  std::size_t group = 0;
  bool forces = false;     // false: measured channels; true: identified bearing forces
  std::size_t mesh = 0;    // index into rate_groups[group].meshes
  std::size_t offset = 0;  // first of the two entries
  // Measured slots: the localisation's entries, a parallel / orthogonal pair per mesh harmonic
  // (2 x kSignatureHarmonics, harmonic by harmonic), from order-tracked averages when the
  // machine is tracked (MachineContext::tracked_offset); 0 for the forces' slots. One pair per
  // harmonic, so that each neighbourhood's rise is judged in its own healthy spread.
  std::size_t tracked_offset = 0;
};

// Meshes a train may have (MachineContext::Create refuses more).
inline constexpr std::size_t kMaxTrainMeshes = 32;

// Sidebands and mesh harmonics the transfer signature looks at.
inline constexpr int kSignatureSidebands = 3;   // k = 1..3 around each harmonic
inline constexpr int kSignatureHarmonics = 3;   // h = 1..3

struct MachineContext {
  MachineSetup setup;  // options normalised (speed search range filled in)
  BlockExpectations expect;
  std::vector<int> block_to_row;  // block channel -> FRF row
  std::size_t channels = 0;       // FRF rows
  std::size_t paths = 0;          // FRF columns

  std::vector<double> shaft_ratio;     // per shaft: rate / input rate
  double max_ratio = 1.0;              // highest shaft ratio
  std::vector<MeshLines> unit_meshes;  // at 1 Hz input speed
  std::vector<double> mesh_orders;     // mesh frequency / input rate, per mesh
  std::vector<RateGroup> rate_groups;  // in order of first shaft
  std::vector<int> shaft_group;        // per shaft: its rate group
  VerdictTopology topology;

  // Condition indicators: signals (every measured channel, every path's contribution and
  // force), slots signal-major, then the envelope indicators (raw, reconstructed per shaft).
  std::vector<ConditionSignal> condition_signals;
  std::vector<ConditionSlot> condition_slots;
  std::vector<SignatureSlot> signature_slots;
  std::vector<std::string> signature_names;  // one per entry, from signature_slots.front()
  std::size_t signature_offset = 0;
  std::size_t envelope_offset = 0;     // first envelope entry in the indicator vector
  // Then, per measured slot s (s < channels x rate groups), the exclusive residual of the
  // order-tracked average at tracked_offset + s (the same value when the block is not tracked):
  // the localisation's shaft evidence, never scored; then the measured signature slots'
  // per-harmonic entries (SignatureSlot::tracked_offset), the localisation's mesh evidence.
  std::size_t tracked_offset = 0;
  std::size_t indicator_count = 0;     // length of the indicator vector
  std::size_t scored_indicator_count = 0;  // entries that can raise the block's score
  std::vector<std::string> envelope_names;  // "envelope_raw_<shaft>", "envelope_rec_<shaft>"

  double band_lo = 0.0;       // analysis band, Hz
  double band_hi = 0.0;
  double max_speed_hz = 0.0;  // upper bound on the input speed (bandwidth, search range)

  // Validates `setup` and derives everything above. Errors name the offending field.
  static Result<MachineContext> Create(MachineSetup setup);
};

}  // namespace gearpath

// BlockWorkspace: the buffers one machine's stages share, for one block shape (samples per
// channel). Sized once by BlockWorkspace::Create and the stages' Configure(); every buffer is
// reused block after block, so processing allocates nothing. Only what a block leaves for later
// (the forces, which PathSignal / ForceAmplitude / DominantPathSignal read after Process) or
// what is small lives here, per machine; the block's time signals, spectra and every other
// per-call buffer are scratch lent by the caller (ShapeScratch, shape_scratch.h).
//
// Layouts: time signals are FRF-row major (row r occupies [r n, (r + 1) n)); spectra are
// FRF-row major over bins (n/2 + 1 per row); forces are paths x in-range bins, row-major (each
// path's force contiguous over the bins).
#pragma once

#include <Eigen/Dense>
#include <array>
#include <complex>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "core/common/accel_block.h"
#include "core/diagnosis/dominant_path.h"
#include "core/dsp/spectrum.h"
#include "core/pipeline/frf_grid_mapping.h"
#include "core/pipeline/frf_power_table.h"
#include "core/pipeline/machine_context.h"

namespace gearpath {

struct ShapeScratch;  // shape_scratch.h

struct BlockWorkspace {
  using Cd = std::complex<double>;

  // --- Shape ---
  std::size_t n = 0;     // samples per channel
  std::size_t bins = 0;  // n/2 + 1
  double bin_hz = 0.0;
  FrfGridMapping map;  // the FRF set on this shape's bin grid (in-range bins only)
  // |H|^2 and H per (path, channel) over the in-range bins; shared by every machine on a shared
  // FRF set (SharedFrfOperators::Power).
  std::shared_ptr<const FrfPowerTable> frf_table;

  // --- Filled stage by stage (the time signals and spectra: ShapeScratch::time, ::spec) ---
  double speed_hz = 0.0;     // input-shaft speed of this block; 0 = unknown
  SpeedSource speed_source = SpeedSource::kUnknown;
  std::vector<MeshLines> meshes;  // every mesh at this block's speed

  // paths x in-range bins: identified bearing forces.
  Eigen::Matrix<Cd, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> forces;

  std::vector<std::uint8_t> band_mask;      // bins: analysis band and inside the FRF range
  std::vector<std::uint8_t> sideband_mask;  // bins: mesh sideband lines (criterion)
  std::vector<std::uint8_t> mesh_mask;      // bins: mesh harmonics

  // Filled in the identification pass: per (path, FRF row), path-major, the contribution
  // energy over the analysis band; per path, its energy on the mesh sideband lines (summed
  // over the rows).
  std::vector<double> path_channel_energy;
  std::vector<double> path_sideband_energy;

  std::vector<double> path_energy;     // per path: analysis-band contribution energy
  std::vector<double> path_share;      // per path: energy share
  std::vector<double> path_criterion;  // per path: dominant-path criterion (after excess)
  std::vector<int> best_channel;       // per path: FRF row where its contribution is largest

  int dominant = -1;                 // dominant path; -1 = none
  std::size_t indicator_channel = 0;  // FRF row of the raw / reconstructed indicator
  // The dominant path's contribution in time at one FRF row is made only when asked for
  // (BlockProcessor::DominantPathSignal; no stage reads it): DominantTime(). One row, not every
  // row, in the processor's own scratch: the daemon never asks, and the 12 rows of the
  // reference workload held 1.5 MB per machine (issue 9's memory bar).
  std::size_t dominant_time_row = kNoRow;  // the row made; reset by each block
  static constexpr std::size_t kNoRow = static_cast<std::size_t>(-1);

  // Condition indicators (machine.condition_slots layout, then the envelope indicators).
  std::vector<double> indicators;          // machine.indicator_count values
  std::vector<double> z;                   // their robust z-scores (0 while learning)
  std::vector<double> excess;              // value - healthy median, >= 0 (0 while learning)
  std::vector<std::uint8_t> slot_valid;    // per slot: computed this block
  std::vector<double> slot_shaft_hz;       // per slot: the rate averaged at
  std::vector<int> slot_revolutions;       // per slot: revolutions averaged
  std::vector<int> slot_transient_samples;  // per slot: samples the transient gate took out
  std::vector<double> slot_residual_variance;  // per slot: for NA4's healthy reference
  std::vector<double> slot_score;          // per slot: largest directional z / limit
  // Lines around each mesh harmonic for the transfer signature: per signature slot, per
  // harmonic, sensors x (2 kSignatureSidebands + 1), sensor-major.
  std::vector<Cd> signature_lines;
  std::size_t signature_stride = 0;       // values per signature slot
  std::size_t signature_sensors = 0;      // max(channels, paths)
  std::vector<double> group_score;         // per rate group: largest slot score

  // Localisation of this block (LocalisationStage), read by the alarm stage.
  struct Localisation {
    int group = -1;                 // rate group whose indicators carry the anomaly
    std::uint32_t gear_mask = 0;    // candidate gears (bit g = gear g); 0 = none
    int best_gear = -1;             // the most likely of them (on the best-evidenced mesh)
    int mesh = -1;                  // the one mesh chosen; -1 = none or several
    double mesh_evidence = 0.0;     // best mesh's transfer-signature evidence (fraction)
    double other_evidence = 0.0;    // best other mesh's evidence (fraction)
    int mesh_count = 0;             // meshes the group's gears sit on
  } localisation;

  // Sizes every buffer for `machine` and n samples per channel and maps the FRF set onto the
  // grid.
  static Result<BlockWorkspace> Create(const MachineContext& machine, std::size_t n);

  // Contribution spectrum of `path` at FRF row `channel`: H_cp F_p on in-range bins, 0
  // elsewhere (seed Eq. 45). noexcept, allocation-free.
  void Contribution(std::size_t path, std::size_t channel, std::span<Cd> out) const noexcept;

  // The dominant path's contribution in time at FRF row `row` (< channels), in
  // scratch.dominant_time (`scratch` of this shape, the same one every call), made on the first
  // call for that row after a block (a contribution and an inverse FFT, which no stage needs);
  // valid until the next block or a call for another row. noexcept, allocation-free.
  std::span<const double> DominantTime(std::size_t row, ShapeScratch& scratch) noexcept;
};

}  // namespace gearpath

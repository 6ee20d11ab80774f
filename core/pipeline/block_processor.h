// BlockProcessor: one machine's per-block diagnosis engine (the whole data flow of DESIGN.md),
// a chain of stages (core/pipeline/pipeline_stage.h), top to bottom:
//   spectra -> speed -> bearing forces (seed Eqs. 40-43 MWI; Tikhonov or least squares) ->
//   path energies (contributions C_ij = H_d,ij F_j, seed Eq. 45) -> dominant path ->
//   envelope indicators (seed Algorithm 2: kurtogram band, SES, five shaft harmonics) ->
//   condition indicators (synchronous average per shaft rate of every measured channel, path
//   contribution and force: FM0, FM4, NA4, M6A, M8A, ER, SLF, mesh harmonics, residual
//   energies, per-mesh sidebands, transfer signatures) -> scoring against the machine's robust
//   healthy baseline -> localisation (shaft group, mesh, gears) -> alarm model (persistence,
//   hysteresis, clear delay) -> verdict.
// docs/diagnosis.md explains each decision and the evaluation behind it.
//
// Configure once, process per block:
//  - Create() validates the setup and builds everything that depends only on the FRFs and the
//    gear train (MachineContext). Errors come back as Result, naming the offending field.
//  - The first block of a new shape (samples_per_channel; the sample rate is fixed per machine)
//    configures every stage: FFT plans, the FRF set brought onto the block's bin grid ONCE
//    (linear interpolation in real and imaginary parts; bins outside the FRF's frequency range
//    get zero force and are excluded and counted), the per-bin identification operators,
//    kurtogram and synchronous-average plans, buffers. That block allocates; Prepare(n) does
//    it ahead of time. Later blocks of a configured shape allocate nothing. Up to kMaxShapes
//    shapes are kept; a further new shape replaces the least recently used.
//  - Process() is noexcept. It never throws on data: a bad block comes back as a typed
//    RejectReason with a one-line message and leaves the BlockResult untouched.
//  - The first baseline_blocks accepted blocks with a known speed are the machine's healthy
//    baseline (the verdict is kLearning meanwhile; ResetBaseline() relearns).
//
//  - Scratch: what lives only within one Process() call (the block's time signals and spectra,
//    FFT plans, the envelope and condition-indicator stages' grids and buffers; ~13 MB for the
//    reference workload) is a BlockScratch (block_scratch.h) the caller lends:
//    Process(block, out, scratch). A worker thread keeps one and lends it to every machine it
//    runs; Prepare(n, scratch) makes the scratch ready for this machine's shape too. What a
//    block leaves behind (the forces read by PathSignal / ForceAmplitude / DominantPathSignal,
//    the learned state) stays in the processor. Process(block, out) and Prepare(n) use a
//    scratch of the processor's own, made when first needed.
//
// Thread-safety: one BlockProcessor per machine; Process() mutates internal buffers and must
// not be called concurrently on the same instance. One BlockScratch is used by one thread at a
// time: two processors may run concurrently only on different scratch objects. Different
// instances share nothing but FFTW's planner, which core/dsp's FftPlan guards with one mutex
// (configuration of different machines' processors may run concurrently).
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "core/common/accel_block.h"
#include "core/common/result.h"
#include "core/diagnosis/fixed_text.h"
#include "core/diagnosis/gear_verdict.h"
#include "core/diagnosis/train_layout.h"
#include "core/dsp/harmonic_indicator.h"  // kIndicatorHarmonics (5, seed Sec. 4.3)
#include "core/frf/frf_set.h"
#include "core/inverse/identification_operator.h"
#include "core/pipeline/block_validation.h"
#include "core/pipeline/learned_state.h"

namespace gearpath {

inline constexpr std::size_t kMaxShapes = 4;

class SharedFrfOperators;  // core/pipeline/shared_frf_operators.h
class BlockScratch;        // core/pipeline/block_scratch.h

struct AnalysisOptions {
  // --- Bearing-force identification (core/inverse): method (MWI default, Tikhonov, least
  // squares), regularisation rule (default: noise floor, eta = 1e-3, fixed per FRF set so the
  // per-bin operator is precomputed), MWI iterations K. See identification_operator.h.
  IdentificationOptions identification;

  // --- Block expectations ---
  double sample_rate_hz = 0.0;          // required (> 0)
  double sample_rate_tolerance = 1e-4;  // relative
  std::uint32_t min_samples_per_channel = 1024;
  std::uint32_t max_samples_per_channel = 1u << 18;

  // --- Speed ---
  double nominal_speed_hz = 0.0;  // input-shaft speed from configuration; 0 = none
  // Mesh-frequency tracking searches input speeds in [lo, hi]; 0 = +/-20 % around nominal
  // (or 1..100 Hz when there is no nominal).
  double speed_search_lo_hz = 0.0;
  double speed_search_hi_hz = 0.0;
  // Track the speed's variation within each block from the mesh tones (the median of the warps
  // of the first mesh harmonics, condition_indicator_stage.cc) and average the shafts at the
  // tracked angle (core/dsp/order_tracker.h); off = constant speed per block. A machine whose
  // first block gains nothing from it is not tracked (MachineState::order_tracking_mode).
  // On by default since the tracker keeps the block's mean speed (docs/diagnosis.md, 9a).
  bool order_tracking = true;
  // Track it for the shaft localisation only (when order_tracking is off): the exclusive
  // residual that names the shaft is taken from tracked averages, every scored indicator from
  // constant-speed ones. Drift smears a shaft's high orders into its neighbours' and named the
  // wrong shaft in most drifting tuning scenarios; the scores keep the held-out family's figures
  // (docs/diagnosis.md, section 11).
  bool localisation_tracking = true;
  // Take the transients that no shaft explains (broadband bursts, knocks) out of each measured
  // channel before its synchronous averages (core/dsp/transient_gate.h): an average keeps 1/R
  // of a burst in one revolution, which the peak indicators read as a fault and which widens
  // the healthy limits (docs/diagnosis.md, section 13).
  bool transient_gate = true;

  // --- Dominant path ---
  enum class DominantCriterion : std::uint8_t {
    kSidebandEnergy,  // default: energy at mesh-harmonic sidebands h*fm +/- k*fs (docs)
    kBandEnergy,      // energy in the analysis band
    kIndicator,       // max over shafts of the fault indicator of each path's contribution
  };
  DominantCriterion criterion = DominantCriterion::kSidebandEnergy;
  // Judge the criterion by its EXCESS over the path's healthy level (learned with the
  // baseline; a healthy mesh already has sidebands from eccentricity and mesh beating):
  // criterion = max(0, value - healthy mean). Falls back to the plain value while learning,
  // when thresholds are configured, or when no path exceeds its healthy level.
  bool criterion_over_baseline = true;
  double analysis_band_lo_hz = 0.0;  // 0 / 0 = the FRF set's frequency range
  double analysis_band_hi_hz = 0.0;
  int sideband_orders = 6;  // k = 1..sideband_orders around each mesh harmonic

  // Indicator channel (row of the FRF set) used for the raw and the reconstructed signal;
  // -1 = the channel where the dominant path's contribution is largest.
  int indicator_channel = -1;

  // --- Envelope analysis (core/dsp) ---
  int kurtogram_max_level = 6;
  // Minimum envelope band width; 0 = automatic: 2 * kIndicatorHarmonics * highest shaft rate
  // (the band must hold the modulation it is meant to show, DESIGN.md).
  double min_band_width_hz = 0.0;
  // Comb-remove the mesh harmonics (+/- 1 bin) before the kurtogram and the SES. Off by
  // default: removing the carrier but not its deterministic shaft-rate sidebands (every real
  // mesh has them) turns them into a fully modulated envelope and RAISES the healthy indicator
  // (measured on the Table-1 simulation: healthy thresholds 4-10x higher). The learned healthy
  // baseline is what handles mesh beating; the kurtogram pre-whitens against mesh tones.
  bool remove_mesh_tones = false;
  double harmonic_tolerance = 0.02;  // relative tolerance on harmonic positions (speed drift)

  // --- Envelope thresholds (published with the envelope indicators) ---
  // Per-shaft thresholds of the raw and of the reconstructed indicator (same order as the
  // train's shafts); both empty = learn them from the first baseline_blocks accepted blocks.
  std::vector<double> raw_thresholds;
  std::vector<double> reconstructed_thresholds;
  int baseline_blocks = 20;       // healthy blocks the baselines are learned from (>= 3)
  double baseline_k_sigma = 4.0;  // published envelope threshold = mean + k * sigma

  // --- Condition indicators and their healthy baseline (docs/diagnosis.md) ---
  // Target rate of healthy blocks in which ANY indicator exceeds its limit; the limit in
  // robust z units follows from it, the number of indicators and baseline_blocks
  // (RobustBaseline::ZForFalseAlarmRate). The alarm model's persistence lowers the rate of
  // flagged blocks well below it.
  double false_alarm_rate = 0.01;
  double scale_floor = 0.05;  // relative floor of every indicator's healthy scale (5 %)
  // Tail guard (core/diagnosis/robust_baseline.h): every indicator's healthy scale is at least
  // its largest deviation over the baseline blocks / 3, so no healthy baseline block would have
  // scored above z = 3 (about half the limit). Off = median, robust scale and the floor only.
  bool tail_guard = true;
  // Operating speed: a block is judged only when its input speed lies within the speeds the
  // baseline was learned at, widened by this fraction either way (the speed reading's own
  // jitter); outside them the block is not scored and the state is held (docs/diagnosis.md
  // section 10). Why: the baseline holds the machine's response at those speeds. On the tuning
  // families a healthy machine learned at one constant speed and judged after a step of 1 %
  // is over its limit in 55 % of its blocks, after a step of 0.01 % in 5 % (59 % and 12 %
  // before the baseline's floor became the amplitude's); the default is the largest step that
  // raised no block when it was chosen (0.001 %), rounded up.
  double speed_tolerance = 2e-5;
  // Operating load (AccelBlock::load): when every block the baseline learned from carried a
  // load, a block that carries one is judged only within those loads widened by this fraction
  // either way; outside them the state is held, as for a speed (docs/diagnosis.md section 10).
  // Why: the amplitudes and energies grow with the load, and a baseline learned at one load
  // cannot tell a higher level from a fault that raises it. On the tuning quick matrix a
  // healthy machine judged after a load step of +10 % raises no block, after +15 % 7.5 % of
  // them (`gearpath evaluate --match /none/ --load-step L --no-load-reading`); the default is
  // the largest step that raised none. 1 judges every load. Blocks without a load are judged.
  double load_tolerance = 0.1;
  // Operating bands (docs/diagnosis.md section 10): how many baselines, each at its own band of
  // speed and load, the machine may learn, in [1, kMaxOperatingBands]. 1: the first baseline
  // only, and a block outside its speeds or loads is not judged. More: such a block is judged
  // against the band that learned at its speed and load; when none did and no fault is
  // suspected, a new band learns there (the verdict holds meanwhile). Why not by
  // default: a band learned at a new operating point while a fault develops there takes the
  // fault for healthy, so a plant turns it on where its operating points are known to recur.
  int operating_bands = 1;
  // A label of the healthy baseline (baseline.epoch): part of the learned state's fingerprint
  // when not empty, so that changing it (after maintenance: a gear replaced) makes this machine
  // refuse the baseline it has and learn a new one, on a reload as at a start, while every other
  // machine keeps its own. Empty adds nothing, so states saved before the key existed stay valid.
  std::string baseline_epoch;  // printable, at most kMaxBaselineEpochBytes
  // Persistence (k of the last n blocks), hysteresis and clear delay (core/diagnosis/
  // alarm_model.h): suspected after suspect_k exceedances, alarm after alarm_k, cleared after
  // clear_blocks blocks under clear_level x the limit.
  int alarm_window = 5;
  int suspect_k = 2;
  int alarm_k = 3;
  double clear_level = 0.7;
  int clear_blocks = 3;
  // Mesh decision: the best mesh's evidence must exceed the next one's by this factor, else
  // both meshes' gears are reported as candidates. 1 (since 2026-11-29; 1.1 before): the
  // leading mesh whenever any evidence rose, its lead shown in the confidence
  // (docs/diagnosis.md section 13).
  double mesh_separation = 1.0;
};

struct MachineSetup {
  std::string machine_id;
  FrfSet frf_set;     // must carry `decoupled` (channels x paths)
  TrainLayout train;  // gear names must match the names in frf_set.paths[i].gears
  // Block channel c is accelerometer block_channels[c]; it is matched to the FRF row with the
  // same sensor id and axis. Empty = the FRF set's channels, in their order. Every FRF row
  // must be present; block channels without an FRF row are rejected at Create().
  std::vector<ExpectedChannel> block_channels;
  AnalysisOptions options;
  // Optional: the FRF set's decoupled matrix and its per-shape operators, shared with other
  // machines. It must hold frf_set.decoupled; Create() checks that and drops this setup's own
  // copy of the matrix (setup().frf_set.decoupled is then empty). Null: everything is private.
  std::shared_ptr<SharedFrfOperators> shared_frf;
};

struct BlockPathShare {
  std::string_view name;     // FrfSet path name, e.g. "B5x"
  std::string_view bearing;  // FrfSet bearing description
  double energy = 0.0;       // sum over channels and analysis-band bins of |C_ij|^2
  double share = 0.0;        // energy / sum of energies, in [0, 1]
  double criterion = 0.0;    // value of the dominant-path criterion for this path (the
                             // excess over its healthy level when that is in use)
};

struct BlockEnvelopeBand {
  double centre_hz = 0.0;
  double width_hz = 0.0;
  int level = 0;             // kurtogram level (may be fractional-tree level / 1-3 split)
  double kurtosis = 0.0;     // spectral kurtosis of the selected band
  bool significant = false;  // false: no band stood out; the default band was used
};

struct BlockShaftIndicator {
  std::string_view shaft;                // TrainLayout shaft name
  double characteristic_hz = 0.0;        // shaft rate at this block's speed
  double raw = 0.0;                      // sum of the five SES harmonic amplitudes, raw signal
  double reconstructed = 0.0;            // same, dominant-path contribution
  double enhancement_percent = 0.0;      // 100 * reconstructed / raw (0 when raw == 0)
  double raw_threshold = 0.0;            // thresholds the indicators are judged against (learned
  double reconstructed_threshold = 0.0;  // or configured; 0 while learning)
  std::array<double, kIndicatorHarmonics> raw_harmonics{};
  std::array<double, kIndicatorHarmonics> reconstructed_harmonics{};
};

// Where a condition-indicator signal comes from.
enum class ConditionSource : std::uint8_t {
  kMeasured,      // a measured channel (FRF row)
  kContribution,  // one path's contribution at its indicator channel
  kForce,         // one path's identified bearing force
};
std::string_view ToString(ConditionSource source) noexcept;

// Condition indicators of one signal at one shaft rate (core/diagnosis/
// gear_condition_indicators.h), judged against the machine's healthy baseline.
struct BlockConditionIndicators {
  ConditionSource source = ConditionSource::kMeasured;
  int index = -1;                  // FRF row (measured) or path (contribution, force)
  std::string_view signal;         // channel "A1/x" or path name
  std::string_view shaft;          // first shaft of the rate group
  double shaft_hz = 0.0;           // the rate the synchronous average was taken at
  int revolutions = 0;             // revolutions averaged (0: not computed this block)
  // Samples the transient gate took out of a measured channel before its averages (0: none,
  // or a contribution or force, which keep their transients).
  int transient_samples = 0;
  std::span<const double> value;   // indicator values (names: ConditionIndicatorNames())
  std::span<const double> z;       // robust z-score of each against the baseline (0 learning)
  double score = 0.0;              // largest directional two-block z / its limit over this set
};

// Why a machine past learning did not judge a block (it holds the state meanwhile). A plant
// watches these: a machine that runs away from the speeds or loads it learned at is blind.
enum class NotJudgedCause : std::uint8_t {
  kNone,          // judged, or still learning
  kSpeedUnknown,  // no input speed (not in the block, not configured, nothing to track)
  kSpeedOutside,  // the speed is outside the baseline's range (speed_tolerance)
  kLoadOutside,   // the load is outside the baseline's range (load_tolerance)
  // A new operating band learns its baseline at this block's speed and load (operating_bands)
  kLearningBand,
};
inline constexpr NotJudgedCause kLastNotJudgedCause = NotJudgedCause::kLearningBand;
// "speed_unknown", "speed_outside", "load_outside", "learning_band" ("none" for kNone).
std::string_view ToString(NotJudgedCause cause) noexcept;

// The block's anomaly score and the limits it was judged by.
struct BlockScore {
  double limit_z = 0.0;        // z limit in force (0 while learning)
  double clear_level = 0.0;    // hysteresis level, in units of the limit
  double score = 0.0;          // largest indicator z over this and the previous block / limit
  std::string_view indicator;  // which indicator gave it
  std::string_view signal;     // on which signal
  std::string_view shaft;      // at which shaft rate
  int exceed_count = 0;        // exceedances in the alarm window (after this block)
  int window = 0;              // alarm window length, blocks
  int baseline_blocks_learned = 0;
  int baseline_blocks_needed = 0;
  // Scored against the baseline: learned, the speed known and within the baseline's speed
  // range (AnalysisOptions::speed_tolerance). A block that is not judged holds the state.
  bool judged = false;
  double baseline_speed_lo_hz = 0.0;  // input speeds the baseline was learned at (0 while
  double baseline_speed_hi_hz = 0.0;  // learning, or unknown for a state saved before them)
  double baseline_load_lo = 0.0;      // loads the baseline was learned at (0 while learning,
  double baseline_load_hi = 0.0;      // or when a baseline block carried no load)
  NotJudgedCause not_judged = NotJudgedCause::kNone;
  // The operating band in force (AnalysisOptions::operating_bands): its id (0 the machine's
  // first baseline, then in order of creation) and how many bands the machine has.
  int operating_band = 0;
  int operating_bands = 1;
};

struct BlockRegularisation {
  double alpha_median = 0.0;      // regularisation parameter over in-range bins
  double condition_median = 0.0;  // condition number of the inverted operator per bin
  double condition_max = 0.0;
  double relative_residual = 0.0;      // ||x - H F|| / ||x|| over the analysis band, all channels
  std::uint32_t bins_used = 0;         // bins inside the FRF range
  std::uint32_t bins_outside_frf = 0;  // bins with forces set to zero (outside FRF range)
};

// What the localisation stood on this block (docs/diagnosis.md section 11). Fixed sizes: no
// allocation per block. Zero while learning or without a speed.
struct BlockLocalisation {
  static constexpr std::size_t kMaxGroups = 8;
  static constexpr std::size_t kMaxMeshes = 4;
  int group = -1;       // rate group chosen (index into the machine's rate groups)
  int group_count = 0;  // rate groups of the machine (up to kMaxGroups recorded)
  // Per rate group: this block's locked exclusive-residual rise over healthy, summed over the
  // measured channels (units^2), and the value accumulated over the fault's blocks.
  std::array<double, kMaxGroups> shaft_evidence{};
  std::array<double, kMaxGroups> shaft_evidence_accumulated{};
  int mesh_count = 0;  // meshes of the chosen group
  // Per mesh of the chosen group (its order): the transfer-signature evidence accumulated over
  // the fault's blocks, as fractions (the mesh decision's input).
  std::array<double, kMaxMeshes> mesh_evidence{};
  // Per rate group and mesh of that group: the transfer signatures' rise over healthy
  // (units^2): measured channels parallel, orthogonal (each mesh harmonic's rise over its own
  // healthy median, summed over the harmonics); identified forces parallel, orthogonal.
  std::array<std::array<std::array<double, 4>, kMaxMeshes>, kMaxGroups> signature_excess{};
};

// The names in a BlockResult (paths, bearings, shafts, dominant path) are string_views into
// the BlockProcessor that filled it (no allocation per block): keep the processor alive as
// long as the result is read, and copy a name to keep it longer.
struct BlockResult {
  std::uint64_t sequence = 0;
  std::int64_t t0_ns = 0;
  std::uint64_t sequence_gap = 0;  // blocks missing just before this one (0 = none)
  bool sequence_restarted = false;

  double speed_hz = 0.0;  // input-shaft speed used
  SpeedSource speed_source = SpeedSource::kUnknown;

  int dominant_path = -1;
  std::string_view dominant_path_name;
  AnalysisOptions::DominantCriterion criterion =
      AnalysisOptions::DominantCriterion::kSidebandEnergy;
  double analysis_band_lo_hz = 0.0;
  double analysis_band_hi_hz = 0.0;
  std::vector<BlockPathShare> paths;  // every path, FrfSet order
  int indicator_channel = -1;         // FRF row used for raw / reconstructed indicators

  BlockEnvelopeBand raw_band;               // kurtogram band of the raw signal
  BlockEnvelopeBand reconstructed_band;     // kurtogram band of the dominant-path signal
  std::vector<BlockShaftIndicator> shafts;  // TrainLayout order

  // Condition indicators: every (signal, rate group), signal-major; and the block's score.
  std::vector<BlockConditionIndicators> condition;
  BlockScore score;
  BlockLocalisation localisation;

  GearVerdict verdict;
  BlockRegularisation regularisation;
};

// Wall time (steady_clock) of one part of Process(), for benchmarks and diagnostics
// (BlockProcessor::set_stage_timing). The parts, in order: "validation" (block checks and the
// sequence), "configure" (the first block of a new shape only), then one entry per stage
// ("spectra", "speed", "identification", ..., "alarm"; pipeline_stage.h).
struct StageTime {
  std::string_view stage;
  std::uint64_t blocks = 0;  // times this part ran since the last reset
  double last_s = 0.0;       // its time in the last block that ran it
  double total_s = 0.0;      // summed over those blocks
};

struct ProcessOutcome {
  RejectReason reason = RejectReason::kNone;
  MessageText message;  // empty when accepted
  bool accepted() const noexcept { return reason == RejectReason::kNone; }
};

class BlockProcessor {
 public:
  // Validates `setup` (FRF set, channel mapping, train layout vs path gears, options) and
  // builds the shape-independent parts. Errors name the offending field.
  static Result<BlockProcessor> Create(MachineSetup setup);

  BlockProcessor(BlockProcessor&&) noexcept;
  BlockProcessor& operator=(BlockProcessor&&) noexcept;
  ~BlockProcessor();

  // Configures for blocks of `samples_per_channel` samples ahead of the first such block, and
  // the processor's own scratch (used by the two-argument Process()).
  Status Prepare(std::uint32_t samples_per_channel);
  // The same, readying `scratch` (instead of the own one) for this machine's blocks of that
  // length: a later Process(block, out, scratch) of such a block allocates nothing. Scratch
  // already ready for a machine of the same shape is reused as it is. `scratch` must not be in
  // use by another thread meanwhile.
  Status Prepare(std::uint32_t samples_per_channel, BlockScratch& scratch);
  // True when blocks of this length are configured (Prepare() or an earlier block).
  bool configured_for(std::uint32_t samples_per_channel) const noexcept;

  // Validates and analyses one block. On acceptance `out` is filled; pass the same
  // BlockResult every time (its vectors are sized once and reused, so nothing is allocated
  // once the shape is configured). On rejection `out` is left untouched; the
  // outcome carries the reason and message. The block must stay alive only during the call.
  // Works in the processor's own scratch.
  ProcessOutcome Process(const AccelBlockView& block, BlockResult& out) noexcept;
  // The same, working in `scratch` (lent for the call; nothing in it is read from an earlier
  // call, so it may serve any number of processors, one call at a time). The first block of a
  // shape that `scratch` has not served allocates there.
  ProcessOutcome Process(const AccelBlockView& block, BlockResult& out,
                         BlockScratch& scratch) noexcept;

  // Time signal (length samples_per_channel of the last accepted block) of the dominant
  // path's contribution at FRF row `channel`, from the last accepted block. Empty before the
  // first accepted block or for an invalid channel. Valid until the next Process() or a call
  // for another channel (one channel's signal is kept, made on the first call for it after a
  // block: no stage needs them, Process() does not); like Process(), not to be called
  // concurrently on one instance. Made in the processor's own scratch: allocation-free once
  // that has served the shape (Prepare(n) or the two-argument Process()); a processor that ran
  // only on lent scratch makes it on the first call.
  std::span<const double> DominantPathSignal(std::size_t channel) const noexcept;

  // Time signal of any path's contribution at FRF row `channel` for the last accepted block,
  // written into `out` (size samples_per_channel). Allocation-free as DominantPathSignal (its
  // inverse FFT is the own scratch's); false on bad indices or size.
  bool PathSignal(std::size_t path, std::size_t channel, std::span<double> out) noexcept;

  // Amplitude |F| of path `path`'s identified bearing force at every block bin of the last
  // accepted block (the spectra's amplitude scaling; N for FRFs in (m/s^2)/N), written into
  // `out` (size samples_per_channel / 2 + 1); 0 at bins outside the FRF range. Read-only,
  // allocation-free; false on a bad index or size or before the first accepted block.
  bool ForceAmplitude(std::size_t path, std::span<double> out) const noexcept;

  // Healthy baseline: number of blocks learned so far / needed (0 needed when configured).
  int baseline_blocks_learned() const noexcept;
  int baseline_blocks_needed() const noexcept;
  // Forget the learned baseline (e.g. after maintenance) and learn again.
  void ResetBaseline() noexcept;

  // What this machine has learned (core/pipeline/learned_state.h), to persist it or carry it
  // over a reload. Allocates; call between blocks.
  LearnedState ExportLearnedState() const;
  // Resumes from `state`, or refuses and changes nothing: a fingerprint that is not this
  // processor's (the message says the baseline measured something else) or an inconsistent
  // part (the message names it). Alarm options that differ restart the alarm model only.
  // A state with more operating bands than AnalysisOptions::operating_bands allows keeps its
  // learned bands first, as many as fit; operating_bands_dropped() counts the rest.
  Status ImportLearnedState(const LearnedState& state);
  std::size_t operating_bands_dropped() const noexcept;
  std::uint64_t learned_state_fingerprint() const noexcept;

  // Names of the entries of BlockConditionIndicators::value of rate group `group` (the
  // indicators, then the group's per-mesh sideband energies, then the exclusive residual).
  std::span<const std::string> ConditionIndicatorNames(std::size_t group) const noexcept;

  const MachineSetup& setup() const noexcept;
  const BlockExpectations& expectations() const noexcept;

  // Per-stage timing of Process(): off by default (no clock is read). On, every Process() reads
  // steady_clock once per part (StageTime) and allocates nothing. stage_times() lists every part
  // in pipeline order; ResetStageTimes() zeroes the counts and sums.
  void set_stage_timing(bool on) noexcept;
  bool stage_timing() const noexcept;
  std::span<const StageTime> stage_times() const noexcept;
  void ResetStageTimes() noexcept;

 private:
  struct Impl;
  explicit BlockProcessor(std::unique_ptr<Impl> impl) noexcept;
  std::unique_ptr<Impl> impl_;
};

}  // namespace gearpath

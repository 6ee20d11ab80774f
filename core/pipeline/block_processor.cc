#include "core/pipeline/block_processor.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <memory>
#include <optional>
#include <tuple>
#include <utility>
#include <vector>

#include "core/diagnosis/gear_condition_indicators.h"
#include "core/pipeline/alarm_stage.h"
#include "core/pipeline/block_scratch.h"
#include "core/pipeline/block_workspace.h"
#include "core/pipeline/condition_indicator_stage.h"
#include "core/pipeline/dominant_path_stage.h"
#include "core/pipeline/envelope_stage.h"
#include "core/pipeline/identification_stage.h"
#include "core/pipeline/indicator_scoring_stage.h"
#include "core/pipeline/localisation_stage.h"
#include "core/pipeline/machine_context.h"
#include "core/pipeline/machine_state.h"
#include "core/pipeline/operating_band_stage.h"
#include "core/pipeline/path_energy_stage.h"
#include "core/pipeline/pipeline_stage.h"
#include "core/pipeline/shape_scratch.h"
#include "core/pipeline/shared_frf_operators.h"
#include "core/pipeline/spectra_stage.h"
#include "core/pipeline/speed_stage.h"

namespace gearpath {
namespace {

// The data flow of DESIGN.md, top to bottom: one stage per arrow.
std::vector<std::unique_ptr<PipelineStage>> MakeStages() {
  std::vector<std::unique_ptr<PipelineStage>> stages;
  stages.push_back(std::make_unique<SpectraStage>());
  stages.push_back(std::make_unique<SpeedStage>());
  stages.push_back(std::make_unique<OperatingBandStage>());
  stages.push_back(std::make_unique<IdentificationStage>());
  stages.push_back(std::make_unique<PathEnergyStage>());
  stages.push_back(std::make_unique<DominantPathStage>());
  stages.push_back(std::make_unique<EnvelopeStage>());
  stages.push_back(std::make_unique<ConditionIndicatorStage>());
  stages.push_back(std::make_unique<IndicatorScoringStage>());
  stages.push_back(std::make_unique<LocalisationStage>());
  stages.push_back(std::make_unique<AlarmStage>());
  return stages;
}

// The healthy baseline of the envelope indicators: configured thresholds or learned.
Result<HealthyBaseline> MakeEnvelopeBaseline(const MachineContext& m) {
  const AnalysisOptions& o = m.setup.options;
  const std::size_t shafts = m.shaft_ratio.size();
  const std::string at = "machine '" + m.setup.machine_id + "': ";
  if (!o.raw_thresholds.empty() || !o.reconstructed_thresholds.empty()) {
    if (o.raw_thresholds.size() != shafts || o.reconstructed_thresholds.size() != shafts) {
      return Error{at + fmt::format("options.raw_thresholds and reconstructed_thresholds need {} "
                                    "values each (one per shaft), got {} and {}",
                                    shafts, o.raw_thresholds.size(),
                                    o.reconstructed_thresholds.size())};
    }
    std::vector<double> all(o.raw_thresholds);
    all.insert(all.end(), o.reconstructed_thresholds.begin(), o.reconstructed_thresholds.end());
    auto b = HealthyBaseline::Configured(all);
    if (!b) return Error{at + "options thresholds: " + b.error()};
    return b;
  }
  BaselineOptions bo;
  bo.blocks = o.baseline_blocks;
  bo.k_sigma = o.baseline_k_sigma;
  auto b = HealthyBaseline::Create(2 * shafts, bo);
  if (!b) return Error{at + "options.baseline: " + b.error()};
  return b;
}

// What the machine learns: the indicator baseline and its z limit, the alarm model, the
// per-path healthy levels.
Status InitialiseState(const MachineContext& m, MachineState& st) {
  const AnalysisOptions& o = m.setup.options;
  const std::string at = "machine '" + m.setup.machine_id + "': ";
  auto envelope = MakeEnvelopeBaseline(m);
  if (!envelope) return Error{envelope.error()};
  st.envelope_baseline.emplace(std::move(envelope.value()));
  RobustBaselineOptions bo;
  bo.blocks = o.baseline_blocks;
  bo.relative_floor = o.scale_floor;
  bo.log_transform.assign(m.indicator_count, true);  // every indicator is a positive ratio
  // The relative floor is the amplitude's: an energy's is twice as wide on the log scale, NA4's
  // four times, so that a level change (a load, a gain) moves none past the floor sooner.
  bo.floor_power.assign(m.indicator_count, 1.0);
  for (const ConditionSlot& cs : m.condition_slots) {
    const std::vector<int>& powers = m.rate_groups[cs.group].indicator_powers;
    for (std::size_t k = 0; k < powers.size() && k < cs.count; ++k) {
      bo.floor_power[cs.offset + k] = std::max(1.0, static_cast<double>(powers[k]));
    }
  }
  for (const SignatureSlot& ss : m.signature_slots) {  // parallel and orthogonal energies
    bo.floor_power[ss.offset] = 2.0;
    bo.floor_power[ss.offset + 1] = 2.0;
  }
  st.limit_z = RobustBaseline::ZForFalseAlarmRate(
      o.false_alarm_rate, static_cast<int>(m.scored_indicator_count), o.baseline_blocks);
  if (!(st.limit_z > 0.0)) {
    return Error{at + fmt::format("options.false_alarm_rate {} gives no z limit (needs 0 < rate "
                                  "< 1 and baseline_blocks >= 3)",
                                  o.false_alarm_rate)};
  }
  st.window_limit_z = RobustBaseline::ZForFalseAlarmRate(
      o.false_alarm_rate, static_cast<int>(m.scored_indicator_count), o.baseline_blocks, 2);
  st.previous_z.assign(m.indicator_count, 0.0);
  st.previous_scored = false;
  // Tail guard at z = 3: no healthy baseline block would have scored above 3 (about half the
  // limit). A Gaussian indicator's largest of 20 deviations passes 3 sigma in ~5 % of baselines,
  // so the guard seldom binds there; a heavy-tailed one (M6A, M8A under bursts) gets the spread
  // its tail shows. At clear_level x limit (~4) it left 3.0 % of the healthy evaluation blocks
  // of 400 tuning scenarios over the limit; at 3, 2.3 % (docs/diagnosis.md section 10).
  constexpr double kTailGuardZ = 3.0;
  bo.tail_z = o.tail_guard ? kTailGuardZ : 0.0;
  auto baseline = RobustBaseline::Create(m.indicator_count, bo);
  if (!baseline) return Error{at + "options.baseline: " + baseline.error()};
  st.band.indicator_baseline.emplace(std::move(baseline.value()));
  AlarmOptions ao;
  ao.n = o.alarm_window;
  ao.suspect_k = o.suspect_k;
  ao.alarm_k = o.alarm_k;
  ao.clear_level = o.clear_level;
  ao.clear_blocks = o.clear_blocks;
  auto alarm = AlarmModel::Create(ao);
  if (!alarm) return Error{at + "options alarm model: " + alarm.error()};
  st.alarm.emplace(std::move(alarm.value()));
  st.learning = true;
  st.band.residual_variance_healthy.mean.assign(m.condition_slots.size(), 0.0);
  st.band.criterion_healthy.mean.assign(m.paths, 0.0);
  st.band.id = 0;
  // The other bands' slots, empty copies of the first: made here, so that a new band costs no
  // allocation on the processing path.
  st.parked_bands.assign(static_cast<std::size_t>(o.operating_bands - 1), st.band);
  st.parked_count = 0;
  st.group_excess_sum.assign(m.rate_groups.size(), 0.0);
  st.mesh_evidence_sum.assign(m.rate_groups.size() * kMaxMeshesPerShaft, 0.0);
  return Status::Ok();
}

}  // namespace

std::string_view ToString(NotJudgedCause cause) noexcept {
  switch (cause) {
    case NotJudgedCause::kNone:
      return "none";
    case NotJudgedCause::kSpeedUnknown:
      return "speed_unknown";
    case NotJudgedCause::kSpeedOutside:
      return "speed_outside";
    case NotJudgedCause::kLoadOutside:
      return "load_outside";
    case NotJudgedCause::kLearningBand:
      return "learning_band";
  }
  return "unknown";
}

std::string_view ToString(ConditionSource source) noexcept {
  switch (source) {
    case ConditionSource::kMeasured:
      return "measured";
    case ConditionSource::kContribution:
      return "contribution";
    case ConditionSource::kForce:
      return "force";
  }
  return "unknown";
}

// One block shape of one machine: what the machine keeps for it (its workspace and its
// configured stages) and the key of the scratch area it runs in.
struct Shape {
  BlockWorkspace work;
  std::vector<std::unique_ptr<PipelineStage>> stages;
  ShapeScratchKey scratch_key;
  std::uint64_t last_used = 0;
};

// Entries of BlockProcessor::stage_times() before the stages' own.
constexpr std::size_t kValidationTime = 0;
constexpr std::size_t kConfigureTime = 1;
constexpr std::size_t kFirstStageTime = 2;
constexpr std::size_t kMaxStageTimes = 16;

// The optional per-part timing of Process() (BlockProcessor::set_stage_timing).
class StageClock {
 public:
  using Clock = std::chrono::steady_clock;
  explicit StageClock(std::array<StageTime, kMaxStageTimes>* times) noexcept
      : times_(times), last_(times ? Clock::now() : Clock::time_point{}) {}
  // Charges the time since the previous lap (or the start) to entry `i`; `more` adds it to the
  // entry's time in this block instead of counting a new block.
  void Lap(std::size_t i, bool more = false) noexcept {
    if (times_ == nullptr) return;
    const Clock::time_point now = Clock::now();
    const double s = std::chrono::duration<double>(now - last_).count();
    StageTime& t = (*times_)[i];
    if (more) {
      t.last_s += s;
    } else {
      ++t.blocks;
      t.last_s = s;
    }
    t.total_s += s;
    last_ = now;
  }

 private:
  std::array<StageTime, kMaxStageTimes>* times_;
  Clock::time_point last_;
};

struct BlockProcessor::Impl {
  MachineContext machine;
  MachineState state;
  std::uint64_t fingerprint = 0;
  std::vector<std::unique_ptr<Shape>> shapes;  // at most kMaxShapes
  Shape* last_shape = nullptr;                 // shape of the last accepted block
  std::uint64_t use_counter = 0;
  bool timing = false;
  std::array<StageTime, kMaxStageTimes> times{};
  std::size_t time_entries = 0;
  std::size_t parked_bands_dropped = 0;  // by the last ImportLearnedState
  // The scratch of the two-argument Process() and of DominantPathSignal() / PathSignal(),
  // made when first needed: a processor that only ever runs on lent scratch has none.
  std::unique_ptr<BlockScratch> own_scratch;

  Shape* FindShape(std::size_t n) const noexcept {
    for (const auto& s : shapes) {
      if (s->work.n == n) return s.get();
    }
    return nullptr;
  }
  Status Configure(std::size_t n);
  // The own scratch, made when first needed (allocates once); null when memory runs out.
  BlockScratch* OwnScratch() noexcept;
  // The own scratch's area for the last accepted block's shape, made when missing (allocates
  // once); null when it cannot be made.
  ShapeScratch* OwnAreaForLastShape() noexcept;
  void ResetLearning() noexcept;
};

Status BlockProcessor::Impl::Configure(std::size_t n) {
  if (FindShape(n) != nullptr) return Status::Ok();
  auto work = BlockWorkspace::Create(machine, n);
  if (!work) return Error{work.error()};
  auto key = ShapeScratchKey::Of(machine, n);
  if (!key) return Error{key.error()};
  auto shape = std::make_unique<Shape>();
  shape->work = std::move(work.value());
  shape->scratch_key = key.value();
  shape->stages = MakeStages();
  for (auto& stage : shape->stages) {
    Status st = stage->Configure(machine, shape->work);
    if (!st) return Error{fmt::format("{} stage: {}", stage->name(), st.error())};
  }
  if (shapes.size() >= kMaxShapes) {
    // Replace the least recently used shape (the last-block pointer may dangle: reset it).
    auto oldest = std::min_element(shapes.begin(), shapes.end(), [](const auto& a, const auto& b) {
      return a->last_used < b->last_used;
    });
    shapes.erase(oldest);
    last_shape = nullptr;
  }
  shapes.push_back(std::move(shape));
  return Status::Ok();
}

BlockScratch* BlockProcessor::Impl::OwnScratch() noexcept {
  try {
    if (!own_scratch) own_scratch = std::make_unique<BlockScratch>();
  } catch (const std::exception&) {
    return nullptr;
  }
  return own_scratch.get();
}

ShapeScratch* BlockProcessor::Impl::OwnAreaForLastShape() noexcept {
  if (last_shape == nullptr) return nullptr;
  BlockScratch* own = OwnScratch();
  if (own == nullptr) return nullptr;
  try {
    auto area = own->Provide(last_shape->scratch_key, machine);
    return area ? area.value() : nullptr;
  } catch (const std::exception&) {
    return nullptr;
  }
}

void BlockProcessor::Impl::ResetLearning() noexcept {
  state.envelope_baseline->Reset();
  state.band.Reset();
  state.band.id = 0;
  for (OperatingBand& b : state.parked_bands) b.Reset();
  state.parked_count = 0;
  state.alarm->Reset();
  state.learning = true;
  state.previous_scored = false;
  std::fill(state.group_excess_sum.begin(), state.group_excess_sum.end(), 0.0);
  std::fill(state.mesh_evidence_sum.begin(), state.mesh_evidence_sum.end(), 0.0);
  state.order_tracking_mode = -1;
}

BlockProcessor::BlockProcessor(std::unique_ptr<Impl> impl) noexcept : impl_(std::move(impl)) {}
BlockProcessor::BlockProcessor(BlockProcessor&&) noexcept = default;
BlockProcessor& BlockProcessor::operator=(BlockProcessor&&) noexcept = default;
BlockProcessor::~BlockProcessor() = default;

Result<BlockProcessor> BlockProcessor::Create(MachineSetup setup) {
  auto machine = MachineContext::Create(std::move(setup));
  if (!machine) return Error{machine.error()};
  auto impl = std::make_unique<Impl>();
  impl->machine = std::move(machine.value());
  if (Status st = InitialiseState(impl->machine, impl->state); !st) return Error{st.error()};
  impl->fingerprint = LearnedStateFingerprint(impl->machine);
  if (Status st = DropOwnDecoupledCopy(impl->machine.setup); !st) return Error{st.error()};
  impl->shapes.reserve(kMaxShapes);
  impl->times[kValidationTime].stage = "validation";
  impl->times[kConfigureTime].stage = "configure";
  impl->time_entries = kFirstStageTime;
  for (const auto& stage : MakeStages()) {  // names are string literals: the views stay valid
    if (impl->time_entries == kMaxStageTimes) break;
    impl->times[impl->time_entries++].stage = stage->name();
  }
  return BlockProcessor(std::move(impl));
}

Status BlockProcessor::Prepare(std::uint32_t samples_per_channel) {
  BlockScratch* own = impl_->OwnScratch();
  if (own == nullptr) {
    return Error{fmt::format("machine '{}': no memory for the processor's scratch",
                             impl_->machine.expect.machine_id)};
  }
  return Prepare(samples_per_channel, *own);
}

Status BlockProcessor::Prepare(std::uint32_t samples_per_channel, BlockScratch& scratch) {
  const BlockExpectations& e = impl_->machine.expect;
  if (samples_per_channel < e.min_samples_per_channel ||
      samples_per_channel > e.max_samples_per_channel) {
    return Error{fmt::format("machine '{}': {} samples per channel is outside {}..{}", e.machine_id,
                             samples_per_channel, e.min_samples_per_channel,
                             e.max_samples_per_channel)};
  }
  try {
    if (Status st = impl_->Configure(samples_per_channel); !st) return st;
    const Shape* shape = impl_->FindShape(samples_per_channel);
    auto area = scratch.Provide(shape->scratch_key, impl_->machine);
    if (!area) return Error{fmt::format("machine '{}': {}", e.machine_id, area.error())};
    return Status::Ok();
  } catch (const std::exception& ex) {
    return Error{fmt::format("machine '{}': configuring for {} samples failed: {}", e.machine_id,
                             samples_per_channel, ex.what())};
  }
}

bool BlockProcessor::configured_for(std::uint32_t samples_per_channel) const noexcept {
  return impl_->FindShape(samples_per_channel) != nullptr;
}

ProcessOutcome BlockProcessor::Process(const AccelBlockView& block, BlockResult& out) noexcept {
  BlockScratch* own = impl_->OwnScratch();
  if (own == nullptr) {
    ProcessOutcome outcome;
    outcome.reason = RejectReason::kNotConfigured;
    outcome.message.Assign("no memory for the processor's scratch");
    return outcome;
  }
  return Process(block, out, *own);
}

ProcessOutcome BlockProcessor::Process(const AccelBlockView& block, BlockResult& out,
                                       BlockScratch& scratch) noexcept {
  ProcessOutcome outcome;
  Impl& im = *impl_;
  StageClock clock(im.timing ? &im.times : nullptr);
  outcome.reason = ValidateBlock(block, im.machine.expect, outcome.message);
  clock.Lap(kValidationTime);
  if (!outcome.accepted()) return outcome;

  // The first block of a new length configures its shape (Prepare() does it ahead of time).
  const std::size_t n = block.samples_per_channel;
  Shape* shape = im.FindShape(n);
  bool configured = false;
  if (shape == nullptr) {
    Status st = Status::Ok();
    try {
      st = im.Configure(n);
    } catch (const std::exception& e) {
      outcome.reason = RejectReason::kNotConfigured;
      outcome.message.Format("configuring for %zu samples per channel failed: %s", n, e.what());
      return outcome;
    }
    if (!st) {
      outcome.reason = RejectReason::kNotConfigured;
      outcome.message.Format("cannot configure for %zu samples per channel: %s", n,
                             st.error().c_str());
      return outcome;
    }
    shape = im.FindShape(n);
    configured = true;
  }
  // The scratch area for this shape: made by the first block that needs it in this scratch
  // (Prepare(n, scratch) does it ahead of time).
  ShapeScratch* area = scratch.Find(shape->scratch_key, im.machine);
  if (area == nullptr) {
    try {
      auto provided = scratch.Provide(shape->scratch_key, im.machine);
      if (!provided) {
        outcome.reason = RejectReason::kNotConfigured;
        outcome.message.Format("cannot configure for %zu samples per channel: %s", n,
                               provided.error().c_str());
        return outcome;
      }
      area = provided.value();
    } catch (const std::exception& e) {
      outcome.reason = RejectReason::kNotConfigured;
      outcome.message.Format("configuring for %zu samples per channel failed: %s", n, e.what());
      return outcome;
    }
    configured = true;
  }
  if (configured) clock.Lap(kConfigureTime);
  const SequenceTracker::Verdict seq =
      im.state.tracker.Observe(block.sequence, im.machine.expect.machine_id, outcome.message);
  if (seq.reason != RejectReason::kNone) {
    outcome.reason = seq.reason;
    return outcome;
  }
  shape->last_used = ++im.use_counter;

  // Result bookkeeping (vectors keep their capacity across blocks).
  const MachineContext& m = im.machine;
  out.sequence = block.sequence;
  out.t0_ns = block.t0_ns;
  out.sequence_gap = seq.gap;
  out.sequence_restarted = seq.restarted;
  out.paths.resize(m.paths);
  out.shafts.resize(m.shaft_ratio.size());
  if (out.verdict.candidates.capacity() < m.topology.gear_names.size()) {
    m.topology.Reserve(out.verdict);  // first use of this BlockResult only
  }
  out.criterion = m.setup.options.criterion;
  out.analysis_band_lo_hz = m.band_lo;
  out.analysis_band_hi_hz = m.band_hi;
  clock.Lap(kValidationTime, /*more=*/true);  // the sequence and the result's bookkeeping

  StageContext ctx{m, im.state, shape->work, *area, block, out, outcome.message};
  for (std::size_t i = 0; i < shape->stages.size(); ++i) {
    const RejectReason reason = shape->stages[i]->Process(ctx);
    if (kFirstStageTime + i < kMaxStageTimes) clock.Lap(kFirstStageTime + i);
    if (reason != RejectReason::kNone) {
      outcome.reason = reason;
      return outcome;
    }
  }
  im.last_shape = shape;
  return outcome;
}

std::span<const double> BlockProcessor::DominantPathSignal(std::size_t channel) const noexcept {
  Impl& im = *impl_;
  if (im.last_shape == nullptr || im.last_shape->work.dominant < 0 ||
      channel >= im.machine.channels) {
    return {};
  }
  ShapeScratch* own = im.OwnAreaForLastShape();
  if (own == nullptr) return {};
  return im.last_shape->work.DominantTime(channel, *own);  // made on the first call for it
}

bool BlockProcessor::PathSignal(std::size_t path, std::size_t channel,
                                std::span<double> out) noexcept {
  Impl& im = *impl_;
  if (im.last_shape == nullptr || path >= im.machine.paths || channel >= im.machine.channels) {
    return false;
  }
  BlockWorkspace& w = im.last_shape->work;
  if (out.size() != w.n) return false;
  ShapeScratch* own = im.OwnAreaForLastShape();
  if (own == nullptr) return false;
  w.Contribution(path, channel, own->one_spec);
  return own->inverse->Process(own->one_spec, out).ok();
}

bool BlockProcessor::ForceAmplitude(std::size_t path, std::span<double> out) const noexcept {
  const Impl& im = *impl_;
  if (im.last_shape == nullptr || path >= im.machine.paths) return false;
  const BlockWorkspace& w = im.last_shape->work;
  const auto row = static_cast<Eigen::Index>(path);
  if (out.size() != w.bins || row >= w.forces.rows()) return false;
  std::fill(out.begin(), out.end(), 0.0);
  for (Eigen::Index i = 0; i < w.forces.cols(); ++i) {
    const std::size_t bin = w.map.first_bin + static_cast<std::size_t>(i);
    if (bin < out.size()) out[bin] = std::abs(w.forces(row, i));
  }
  return true;
}

int BlockProcessor::baseline_blocks_learned() const noexcept {
  return impl_->state.band.indicator_baseline->blocks_seen();
}
int BlockProcessor::baseline_blocks_needed() const noexcept {
  return impl_->state.band.indicator_baseline->blocks_needed();
}
std::span<const std::string> BlockProcessor::ConditionIndicatorNames(
    std::size_t group) const noexcept {
  const auto& groups = impl_->machine.rate_groups;
  return group < groups.size() ? std::span<const std::string>(groups[group].indicator_names)
                               : std::span<const std::string>{};
}
void BlockProcessor::ResetBaseline() noexcept { impl_->ResetLearning(); }

namespace {

// The speeds and loads a band learned at, between a band and its saved form (the fields have
// the same names in both).
template <typename From, typename To>
void CopyRanges(const From& from, To& to) noexcept {
  to.baseline_speed_lo_hz = from.baseline_speed_lo_hz;
  to.baseline_speed_hi_hz = from.baseline_speed_hi_hz;
  to.baseline_load_lo = from.baseline_load_lo;
  to.baseline_load_hi = from.baseline_load_hi;
  to.baseline_load_partial = from.baseline_load_partial;
}

LearnedBand ExportBand(const OperatingBand& b) {
  LearnedBand s;
  s.band_id = b.id;
  s.indicator_baseline = b.indicator_baseline->State();
  s.residual_variance_healthy = b.residual_variance_healthy.mean;
  s.residual_variance_blocks = b.residual_variance_healthy.blocks;
  s.criterion_healthy = b.criterion_healthy.mean;
  s.criterion_blocks = b.criterion_healthy.blocks;
  CopyRanges(b, s);
  return s;
}

// A saved band checked against this machine's empty one (`now`: sizes and the baseline's
// configuration), into a band ready to use.
Result<OperatingBand> ImportBand(const LearnedBand& s, const OperatingBand& now) {
  auto size_check = [](const char* what, std::size_t want, std::size_t got) -> Status {
    if (want == got) return Status::Ok();
    return Error{fmt::format("{} has {} entries, this machine {}", what, got, want)};
  };
  for (Status st :
       {size_check("residual_variance_healthy", now.residual_variance_healthy.mean.size(),
                   s.residual_variance_healthy.size()),
        size_check("criterion_healthy", now.criterion_healthy.mean.size(),
                   s.criterion_healthy.size()),
        size_check("indicator_baseline", now.indicator_baseline->indicators(),
                   static_cast<std::size_t>(s.indicator_baseline.indicators))}) {
    if (!st) return Error{st.error()};
  }
  auto indicator = RobustBaseline::FromState(s.indicator_baseline);
  if (!indicator) return Error{indicator.error()};
  // Configuration, not state (the fingerprint vouches that it is the one it learned under).
  indicator->set_tail_z(now.indicator_baseline->tail_z());
  indicator->set_floor_power(now.indicator_baseline->floor_power());
  for (const auto* v : {&s.residual_variance_healthy, &s.criterion_healthy}) {
    for (double x : *v) {
      if (!std::isfinite(x)) return Error{"a healthy level is not finite"};
    }
  }
  if (s.residual_variance_blocks < 0 || s.criterion_blocks < 0) {
    return Error{"negative block counts"};
  }
  // Each learned range: both 0 (none, or saved before it existed) or 0 < lo <= hi, finite.
  for (const auto& [what, lo, hi] :
       {std::tuple{"speed range", s.baseline_speed_lo_hz, s.baseline_speed_hi_hz},
        std::tuple{"load range", s.baseline_load_lo, s.baseline_load_hi}}) {
    if (!(lo == 0.0 && hi == 0.0) && !(lo > 0.0 && lo <= hi && std::isfinite(hi))) {
      return Error{fmt::format("baseline {} {}-{} is not 0 < low <= high", what, lo, hi)};
    }
  }
  if (s.band_id < 0 || s.band_id >= kMaxOperatingBands) {
    return Error{
        fmt::format("operating band id {} is not in [0, {})", s.band_id, kMaxOperatingBands)};
  }
  OperatingBand b;
  b.id = s.band_id;
  b.indicator_baseline.emplace(std::move(indicator.value()));
  b.residual_variance_healthy.mean = s.residual_variance_healthy;
  b.residual_variance_healthy.blocks = s.residual_variance_blocks;
  b.criterion_healthy.mean = s.criterion_healthy;
  b.criterion_healthy.blocks = s.criterion_blocks;
  CopyRanges(s, b);
  return b;
}

}  // namespace

LearnedState BlockProcessor::ExportLearnedState() const {
  const MachineState& st = impl_->state;
  LearnedState s;
  static_cast<LearnedBand&>(s) = ExportBand(st.band);
  s.fingerprint = impl_->fingerprint;
  s.learning = st.learning;
  HealthyBaselineState envelope = st.envelope_baseline->State();
  if (!envelope.configured) s.envelope_baseline = std::move(envelope);
  s.alarm = st.alarm->State();
  s.group_excess_sum = st.group_excess_sum;
  s.mesh_evidence_sum = st.mesh_evidence_sum;
  s.order_tracking_mode = st.order_tracking_mode;
  for (std::size_t i = 0; i < st.parked_count; ++i) {
    s.parked_bands.push_back(ExportBand(st.parked_bands[i]));
  }
  s.baseline_epoch = impl_->machine.setup.options.baseline_epoch;
  return s;
}

Status BlockProcessor::ImportLearnedState(const LearnedState& s) {
  const Impl& im = *impl_;
  const MachineState& now = im.state;
  const std::string& epoch = im.machine.setup.options.baseline_epoch;
  if (s.baseline_epoch && *s.baseline_epoch != epoch) {
    return Error{
        fmt::format("the saved baseline was learned under baseline epoch \"{}\", this "
                    "configuration's is \"{}\"",
                    *s.baseline_epoch, epoch)};
  }
  // A state saved before the fingerprint's version 2 carries version 1, computed only then.
  if (s.fingerprint != im.fingerprint &&
      s.fingerprint != LegacyLearnedStateFingerprint(im.machine)) {
    return Error{
        fmt::format("the saved baseline measured something else (fingerprint {:016x}, "
                    "this configuration {:016x}: FRF set, channels, gear train, "
                    "indicator options or baseline epoch changed)",
                    s.fingerprint, im.fingerprint)};
  }
  auto size_check = [](const char* what, std::size_t want, std::size_t got) -> Status {
    if (want == got) return Status::Ok();
    return Error{fmt::format("{} has {} entries, this machine {}", what, got, want)};
  };
  for (Status st :
       {size_check("group_excess_sum", now.group_excess_sum.size(), s.group_excess_sum.size()),
        // Empty in states saved before the mesh evidence accumulated.
        s.mesh_evidence_sum.empty() ? Status::Ok()
                                    : size_check("mesh_evidence_sum", now.mesh_evidence_sum.size(),
                                                 s.mesh_evidence_sum.size())}) {
    if (!st) return st;
  }
  auto in_use = ImportBand(s, now.band);
  if (!in_use) return Error{in_use.error()};
  if (s.learning == in_use->learned()) {
    return Error{"learning flag contradicts the indicator baseline"};
  }
  // The band in use first, the parked ones after it, learned bands before learning ones: a
  // configuration with fewer bands than the state keeps the learned ones it has room for
  // (parked_bands_dropped() counts the others), and a machine that was learning an added band
  // resumes judging at a learned one.
  std::vector<OperatingBand> bands;
  bands.push_back(std::move(in_use.value()));
  for (const LearnedBand& saved : s.parked_bands) {
    auto b = ImportBand(saved, now.band);
    if (!b) return Error{fmt::format("operating band {}: {}", saved.band_id, b.error())};
    bands.push_back(std::move(b.value()));
  }
  std::stable_partition(bands.begin(), bands.end(),
                        [](const OperatingBand& b) { return b.learned(); });
  const std::size_t keep = std::min(bands.size(), now.parked_bands.size() + 1);
  const std::size_t dropped = bands.size() - keep;
  std::optional<HealthyBaseline> envelope;
  if (s.envelope_baseline) {
    auto e = HealthyBaseline::FromState(*s.envelope_baseline);
    if (!e) return Error{e.error()};
    if (e->thresholds().size() != now.envelope_baseline->thresholds().size()) {
      return Error{"envelope baseline size differs"};
    }
    envelope.emplace(std::move(e.value()));
  }
  // Alarm options from the configuration in force win: a changed window or k restarts the
  // alarm model (the baseline is kept).
  std::optional<AlarmModel> alarm;
  if (s.alarm.options == now.alarm->options()) {
    auto a = AlarmModel::FromState(s.alarm);
    if (!a) return Error{a.error()};
    alarm.emplace(std::move(a.value()));
  }
  for (const auto* v : {&s.group_excess_sum, &s.mesh_evidence_sum}) {
    for (double x : *v) {
      if (!std::isfinite(x)) return Error{"an evidence sum is not finite"};
    }
  }
  // Everything checked: commit. The parked slots keep their size (no allocation later).
  MachineState& st = impl_->state;
  for (std::size_t i = 0; i < st.parked_bands.size(); ++i) {
    if (i + 1 < keep) {
      st.parked_bands[i] = std::move(bands[i + 1]);
    } else {
      st.parked_bands[i].Reset();
    }
  }
  st.parked_count = keep - 1;
  impl_->parked_bands_dropped = dropped;
  st.band = std::move(bands.front());
  if (envelope) st.envelope_baseline.emplace(std::move(*envelope));
  if (alarm) {
    st.alarm.emplace(std::move(*alarm));
  } else {
    st.alarm->Reset();
  }
  st.learning = !st.band.learned();
  st.previous_scored = false;  // a restored machine starts a new two-block window
  st.group_excess_sum = s.group_excess_sum;
  if (s.mesh_evidence_sum.empty()) {
    std::fill(st.mesh_evidence_sum.begin(), st.mesh_evidence_sum.end(), 0.0);
  } else {
    st.mesh_evidence_sum = s.mesh_evidence_sum;
  }
  st.order_tracking_mode = s.order_tracking_mode;
  return Status::Ok();
}

std::size_t BlockProcessor::operating_bands_dropped() const noexcept {
  return impl_->parked_bands_dropped;
}

std::uint64_t BlockProcessor::learned_state_fingerprint() const noexcept {
  return impl_->fingerprint;
}
const MachineSetup& BlockProcessor::setup() const noexcept { return impl_->machine.setup; }
const BlockExpectations& BlockProcessor::expectations() const noexcept {
  return impl_->machine.expect;
}

void BlockProcessor::set_stage_timing(bool on) noexcept { impl_->timing = on; }
bool BlockProcessor::stage_timing() const noexcept { return impl_->timing; }
std::span<const StageTime> BlockProcessor::stage_times() const noexcept {
  return {impl_->times.data(), impl_->time_entries};
}
void BlockProcessor::ResetStageTimes() noexcept {
  for (StageTime& t : impl_->times) {
    t.blocks = 0;
    t.last_s = 0.0;
    t.total_s = 0.0;
  }
}

}  // namespace gearpath

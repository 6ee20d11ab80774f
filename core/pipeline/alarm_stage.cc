#include "core/pipeline/alarm_stage.h"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <limits>

#include "core/pipeline/block_workspace.h"
#include "core/pipeline/machine_context.h"
#include "core/pipeline/machine_state.h"

namespace gearpath {
namespace {

double Clamp01(double v) noexcept { return v < 0.0 ? 0.0 : (v > 1.0 ? 1.0 : v); }

// Appends ", "-separated names of the gears in `mask` to buf[pos..cap).
std::size_t AppendGears(char* buf, std::size_t cap, std::size_t pos, const VerdictTopology& t,
                        std::uint32_t mask) noexcept {
  bool first = true;
  for (std::size_t g = 0; g < t.gear_names.size() && pos + 1 < cap; ++g) {
    if (!(mask >> g & 1u)) continue;
    const int n = std::snprintf(buf + pos, cap - pos, "%s%s", first ? "" : ", ",
                                t.gear_names[g].c_str());
    if (n > 0) pos = std::min(cap - 1, pos + static_cast<std::size_t>(n));
    first = false;
  }
  return pos;
}

// Appends printf-style text to buf[pos..cap) (truncated at cap); a function rather than a lambda
// so that the compiler checks each format against its arguments.
__attribute__((format(printf, 4, 5))) std::size_t AppendFormat(char* buf, std::size_t cap,
                                                               std::size_t pos, const char* format,
                                                               ...) noexcept {
  if (pos + 1 >= cap) return pos;
  std::va_list args;
  va_start(args, format);
  const int n = std::vsnprintf(buf + pos, cap - pos, format, args);
  va_end(args);
  return n > 0 ? std::min(cap - 1, pos + static_cast<std::size_t>(n)) : pos;
}

}  // namespace

Status AlarmStage::Configure(const MachineContext&, BlockWorkspace&) { return Status::Ok(); }

RejectReason AlarmStage::Process(StageContext& ctx) noexcept {
  BlockWorkspace& w = ctx.work;
  const MachineContext& m = ctx.machine;
  MachineState& st = ctx.state;
  const VerdictTopology& t = m.topology;
  GearVerdict& v = ctx.out.verdict;
  const bool scored = ctx.out.score.limit_z > 0.0;
  AlarmEvidence evidence;
  // An added operating band that learns is not the machine learning: its verdict holds.
  evidence.learning = !scored && st.learning && !st.parked_band_learned();
  // A block that was not judged (no speed, or a speed the baseline did not learn at) is no
  // evidence either way: the alarm model holds its state.
  evidence.score =
      ctx.out.score.judged ? ctx.out.score.score : std::numeric_limits<double>::quiet_NaN();
  evidence.gear_vote =
      w.localisation.gear_mask != 0 ? static_cast<int>(w.localisation.gear_mask) : -1;
  const AlarmStatus& a = st.alarm->Update(evidence);
  ctx.out.score.exceed_count = a.exceed_count;
  ctx.out.score.window = a.window;

  v.state = a.state;
  v.gear = -1;
  v.gear_name = {};
  v.shaft = -1;
  v.shaft_name = {};
  v.characteristic_hz = 0.0;
  v.confidence = 0.0;
  v.mesh = -1;
  v.candidates.clear();
  v.candidate_names.clear();
  v.reason.Clear();
  if (a.state == FaultState::kLearning && !scored) {  // a block of the baseline
    v.reason.Format("learning the healthy baseline (%d of %d blocks); no verdict yet",
                    ctx.out.score.baseline_blocks_learned, ctx.out.score.baseline_blocks_needed);
    return RejectReason::kNone;
  }
  const bool judged = ctx.out.score.judged;
  char buf[256];
  std::size_t pos = 0;
  if (!judged) {
    switch (ctx.out.score.not_judged) {
      case NotJudgedCause::kSpeedOutside:
        pos = AppendFormat(
            buf, sizeof buf, pos,
            "input speed %.4g Hz outside the %.4g-%.4g Hz the healthy baseline was learned at "
            "(+/- %.2g %%): not judged, state held",
            w.speed_hz, ctx.out.score.baseline_speed_lo_hz, ctx.out.score.baseline_speed_hi_hz,
            100.0 * m.setup.options.speed_tolerance);
        break;
      case NotJudgedCause::kLoadOutside:
        pos = AppendFormat(
            buf, sizeof buf, pos,
            "load %.4g outside the %.4g-%.4g the healthy baseline was learned at (+/- %.2g %%): "
            "not judged, state held",
            ctx.block.load, ctx.out.score.baseline_load_lo, ctx.out.score.baseline_load_hi,
            100.0 * m.setup.options.load_tolerance);
        break;
      case NotJudgedCause::kLearningBand:
        pos = AppendFormat(
            buf, sizeof buf, pos,
            "learning the healthy baseline of operating band %d (of up to %d) at input speed "
            "%.4g Hz, load %.4g (%d of %d blocks): not judged, state held",
            ctx.out.score.operating_band, m.setup.options.operating_bands, w.speed_hz,
            ctx.block.load, ctx.out.score.baseline_blocks_learned,
            ctx.out.score.baseline_blocks_needed);
        break;
      case NotJudgedCause::kSpeedUnknown:
      case NotJudgedCause::kNone:  // not reached: a learned machine's unjudged block has a cause
        pos = AppendFormat(
            buf, sizeof buf, pos,
            "input speed unknown (not in the block, not configured, no mesh lines to track): "
            "indicators not computed, state held");
        break;
    }
    // No fault, or no verdict yet (learned, but no block judged since).
    if (a.state == FaultState::kNoFault || a.state == FaultState::kLearning) {
      v.reason.Assign(std::string_view(buf, pos));
      return RejectReason::kNone;
    }
  }
  const double score = ctx.out.score.score;
  if (a.state == FaultState::kNoFault) {  // judged
    v.confidence = Clamp01(1.0 - score);
    v.reason.Format("every indicator within the healthy baseline (highest: %.*s of %.*s at "
                    "%.0f %% of its limit)",
                    static_cast<int>(ctx.out.score.indicator.size()),
                    ctx.out.score.indicator.data(), static_cast<int>(ctx.out.score.signal.size()),
                    ctx.out.score.signal.data(), 100.0 * score);
    return RejectReason::kNone;
  }

  // Suspected or alarm: the latched localisation (most voted among the recent exceedances).
  const std::uint32_t mask =
      a.latched_vote > 0 ? static_cast<std::uint32_t>(a.latched_vote) : w.localisation.gear_mask;
  for (std::size_t g = 0; g < t.gear_names.size(); ++g) {
    if (!(mask >> g & 1u)) continue;
    v.candidates.push_back(static_cast<int>(g));
    v.candidate_names.push_back(t.gear_names[g]);
  }
  if (!v.candidates.empty()) {
    const int best = w.localisation.best_gear;
    v.gear = best >= 0 && (mask >> best & 1u) ? best : v.candidates.front();
    v.gear_name = t.gear_names[static_cast<std::size_t>(v.gear)];
    v.shaft = t.gear_shaft[static_cast<std::size_t>(v.gear)];
    v.shaft_name = t.shaft_names[static_cast<std::size_t>(v.shaft)];
    v.characteristic_hz = t.shaft_ratio[static_cast<std::size_t>(v.shaft)] * w.speed_hz;
    int mesh = t.gear_mesh[static_cast<std::size_t>(v.gear)];
    for (int g : v.candidates) {
      if (t.gear_mesh[static_cast<std::size_t>(g)] != mesh) mesh = -1;
    }
    v.mesh = mesh;
  }
  if (!judged) {  // the gears named while the state was raised; no confidence from this block
    pos = AppendFormat(buf, sizeof buf, pos, " -> ");
    pos = AppendGears(buf, sizeof buf, pos, t, mask);
    v.reason.Assign(std::string_view(buf, pos));
    return RejectReason::kNone;
  }
  // Confidence that the fault is among the candidates: how far over the limit the recent
  // blocks are, times how clearly the mesh was separated (1 when only one mesh was possible).
  const BlockWorkspace::Localisation& loc = w.localisation;
  const double strength = Clamp01(1.0 - 1.0 / std::max(score, 1.0));
  const double persistence =
      a.window > 0 ? static_cast<double>(a.exceed_count) / static_cast<double>(a.window) : 0.0;
  const double separation =
      loc.mesh_count > 1 && loc.mesh_evidence > 0.0
          ? Clamp01(1.0 - loc.other_evidence / loc.mesh_evidence)
          : 1.0;
  v.confidence = Clamp01((0.5 * strength + 0.5 * persistence) * (0.5 + 0.5 * separation));

  pos =
      AppendFormat(buf, sizeof buf, pos,
                   "%.*s of %.*s at %.1fx its limit at shaft rate %.3g Hz (%d of %d blocks)",
                   static_cast<int>(ctx.out.score.indicator.size()), ctx.out.score.indicator.data(),
                   static_cast<int>(ctx.out.score.signal.size()), ctx.out.score.signal.data(),
                   score, v.characteristic_hz, a.exceed_count, a.window);
  if (loc.mesh_count > 1) {
    pos = AppendFormat(
        buf, sizeof buf, pos,
        loc.mesh >= 0 ? "; mesh %s by its transfer signature (%.0f %% vs %.0f %%)"
                      : "; meshes not separated by their transfer signatures (%s%.0f %% vs "
                        "%.0f %%)",
        loc.mesh >= 0 ? t.mesh_names[static_cast<std::size_t>(loc.mesh)].c_str() : "",
        100.0 * loc.mesh_evidence, 100.0 * loc.other_evidence);
  }
  if (v.candidates.size() == 1) {
    pos = AppendFormat(buf, sizeof buf, pos, " -> gear ");
  } else if (v.candidates.size() > 1) {
    pos = AppendFormat(buf, sizeof buf, pos, " -> candidates ");
  }
  pos = AppendGears(buf, sizeof buf, pos, t, mask);
  if (v.candidates.size() > 1 && v.mesh >= 0) {
    pos = AppendFormat(buf, sizeof buf, pos, ": same mesh and shaft rate, inseparable");
  }
  v.reason.Assign(std::string_view(buf, pos));
  return RejectReason::kNone;
}

}  // namespace gearpath

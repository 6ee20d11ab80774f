#include "core/diagnosis/gear_verdict.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

namespace gearpath {
namespace {

constexpr double kMeshAmbiguity = 0.2;  // mesh separation under this keeps both meshes

double Clamp01(double v) noexcept { return v < 0.0 ? 0.0 : (v > 1.0 ? 1.0 : v); }

// Appends "G3, G4" style names of `gears` to buf[pos...]; returns the new length.
std::size_t AppendNames(char* buf, std::size_t cap, std::size_t pos, const VerdictTopology& t,
                        std::span<const int> gears) noexcept {
  for (std::size_t i = 0; i < gears.size() && pos + 1 < cap; ++i) {
    const int n = std::snprintf(buf + pos, cap - pos, "%s%s", i == 0 ? "" : ", ",
                                t.gear_names[gears[i]].c_str());
    if (n < 0) break;
    pos = std::min(cap - 1, pos + static_cast<std::size_t>(n));
  }
  return pos;
}

}  // namespace

std::string_view ToString(FaultState state) noexcept {
  switch (state) {
    case FaultState::kLearning:
      return "learning";
    case FaultState::kNoFault:
      return "no_fault";
    case FaultState::kSuspected:
      return "suspected";
    case FaultState::kAlarm:
      return "alarm";
  }
  return "unknown";
}

void VerdictTopology::Reserve(GearVerdict& verdict) const {
  verdict.candidates.reserve(gear_names.size());
  verdict.candidate_names.reserve(gear_names.size());
}

void DecideGearVerdict(const VerdictTopology& t, const VerdictInputs& in,
                       GearVerdict& out) noexcept {
  out.gear = -1;
  out.gear_name = {};
  out.shaft = -1;
  out.shaft_name = {};
  out.characteristic_hz = 0.0;
  out.confidence = 0.0;
  out.mesh = -1;
  out.candidates.clear();
  out.candidate_names.clear();
  out.reason.Clear();

  const std::size_t shafts = t.shaft_names.size();
  const std::size_t paths = t.path_meshes.size();
  const std::size_t meshes = t.mesh_names.size();
  if (in.raw.size() != shafts || in.reconstructed.size() != shafts ||
      in.raw_threshold.size() != shafts || in.reconstructed_threshold.size() != shafts ||
      in.path_criterion.size() != paths || meshes > 32) {
    out.state = FaultState::kNoFault;
    out.reason.Format("verdict inputs do not match the machine (%zu shafts, %zu paths expected)",
                      shafts, paths);
    return;
  }
  if (in.learning) {
    out.state = FaultState::kLearning;
    out.reason.Assign("learning the healthy baseline; no verdict yet");
    return;
  }

  // Exceedance per shaft.
  int best = -1;
  double e_max = -1.0;
  for (std::size_t s = 0; s < shafts; ++s) {
    const double er = in.raw_threshold[s] > 0.0 ? in.raw[s] / in.raw_threshold[s] : 0.0;
    const double ec = in.reconstructed_threshold[s] > 0.0
                          ? in.reconstructed[s] / in.reconstructed_threshold[s]
                          : 0.0;
    const double e = std::max(er, ec);
    if (e > e_max) {
      e_max = e;
      best = static_cast<int>(s);
    }
  }
  if (best < 0 || !(e_max >= 1.0)) {
    out.state = FaultState::kNoFault;
    out.confidence = Clamp01(1.0 - std::max(e_max, 0.0));
    if (best >= 0) {
      out.reason.Format(
          "every shaft indicator under its threshold (highest: shaft '%s' at %.0f %%)",
          t.shaft_names[best].c_str(), 100.0 * e_max);
    } else {
      out.reason.Assign("no shaft to judge");
    }
    return;
  }
  out.state = e_max >= in.alarm_factor ? FaultState::kAlarm : FaultState::kSuspected;
  out.shaft = best;
  out.shaft_name = t.shaft_names[best];
  out.characteristic_hz = t.shaft_ratio[best] * in.input_speed_hz;

  // Shaft group: every shaft at the same rate (the envelope cannot separate them).
  const double rate = t.shaft_ratio[best];
  const auto in_group = [&](int s) {
    return std::abs(t.shaft_ratio[s] - rate) <= t.rate_tolerance * rate;
  };
  double e_other = 0.0;
  for (std::size_t s = 0; s < shafts; ++s) {
    if (in_group(static_cast<int>(s))) continue;
    const double er = in.raw_threshold[s] > 0.0 ? in.raw[s] / in.raw_threshold[s] : 0.0;
    const double ec = in.reconstructed_threshold[s] > 0.0
                          ? in.reconstructed[s] / in.reconstructed_threshold[s]
                          : 0.0;
    e_other = std::max({e_other, er, ec});
  }

  // Mesh scores from the path criteria; candidate meshes from the shaft group's gears.
  std::array<double, 32> score{};
  for (std::size_t p = 0; p < paths; ++p) {
    const auto& seen = t.path_meshes[p];
    if (seen.empty()) continue;
    const double w = std::max(in.path_criterion[p], 0.0) / static_cast<double>(seen.size());
    for (int m : seen) score[m] += w;
  }
  if (in.mesh_evidence.size() == meshes) {
    double total = 0.0;
    for (double v : in.mesh_evidence) total += std::isfinite(v) && v > 0.0 ? v : 0.0;
    if (total > 0.0) {
      for (std::size_t m = 0; m < meshes; ++m) {
        const double v = in.mesh_evidence[m];
        score[m] = std::isfinite(v) && v > 0.0 ? v : 0.0;
      }
    }
  }
  std::uint32_t candidate_meshes = 0;  // bit set
  for (std::size_t g = 0; g < t.gear_names.size(); ++g) {
    if (in_group(t.gear_shaft[g]) && t.gear_mesh[g] >= 0) candidate_meshes |= 1u << t.gear_mesh[g];
  }
  std::uint32_t dominant_meshes = 0;
  if (in.dominant_path >= 0 && static_cast<std::size_t>(in.dominant_path) < paths) {
    for (int m : t.path_meshes[in.dominant_path]) dominant_meshes |= 1u << m;
  }
  dominant_meshes &= candidate_meshes;
  const bool dominant_consistent = dominant_meshes != 0;
  const std::uint32_t pool = dominant_consistent ? dominant_meshes : candidate_meshes;

  // Best and second-best mesh inside the pool (by score); separation vs the best OTHER
  // candidate mesh.
  int m1 = -1;
  for (std::size_t m = 0; m < meshes; ++m) {
    if ((pool >> m & 1u) && (m1 < 0 || score[m] > score[m1])) m1 = static_cast<int>(m);
  }
  double sep = 1.0;
  std::uint32_t chosen = 0;
  if (m1 >= 0) {
    chosen = 1u << m1;
    double s2 = 0.0;
    for (std::size_t m = 0; m < meshes; ++m) {
      if (static_cast<int>(m) == m1 || !(candidate_meshes >> m & 1u)) continue;
      s2 = std::max(s2, score[m]);
    }
    sep = score[m1] > 0.0 ? Clamp01(1.0 - s2 / score[m1]) : 0.0;
    if (sep < kMeshAmbiguity) {
      // Too close to call: keep every pool mesh scoring within the ambiguity of the best.
      for (std::size_t m = 0; m < meshes; ++m) {
        if ((pool >> m & 1u) && score[m] >= (1.0 - kMeshAmbiguity) * score[m1]) {
          chosen |= 1u << m;
        }
      }
    }
    if (!dominant_consistent) sep *= 0.5;
  }
  int chosen_count = 0;
  for (std::size_t m = 0; m < meshes; ++m) chosen_count += (chosen >> m & 1u) ? 1 : 0;
  if (chosen_count == 1) out.mesh = m1;

  // Candidates: gears of the shaft group on a chosen mesh (all of the group if no mesh info).
  for (std::size_t g = 0; g < t.gear_names.size(); ++g) {
    if (!in_group(t.gear_shaft[g])) continue;
    const int m = t.gear_mesh[g];
    if (chosen != 0 && (m < 0 || !(chosen >> m & 1u))) continue;
    out.candidates.push_back(static_cast<int>(g));
  }
  // Best candidate: prefer a gear on the shaft with the highest exceedance.
  for (int g : out.candidates) {
    if (out.gear < 0 || (t.gear_shaft[g] == best && t.gear_shaft[out.gear] != best)) out.gear = g;
  }
  for (int g : out.candidates) out.candidate_names.push_back(t.gear_names[g]);
  if (out.gear >= 0) out.gear_name = t.gear_names[out.gear];

  const double strength = Clamp01(1.0 - 1.0 / e_max);
  const double shaft_sep = Clamp01(1.0 - e_other / e_max);
  out.confidence = Clamp01(strength * shaft_sep * sep);

  // Reason, in one line.
  char buf[256];
  std::size_t pos = 0;
  const auto add = [&](const char* format, auto... args) {
    if (pos + 1 >= sizeof buf) return;
    const int n = std::snprintf(buf + pos, sizeof buf - pos, format, args...);
    if (n > 0) pos = std::min(sizeof buf - 1, pos + static_cast<std::size_t>(n));
  };
  add("shaft '%s' (%.3g Hz) at %.1fx threshold", t.shaft_names[best].c_str(), out.characteristic_hz,
      e_max);
  if (m1 >= 0 && in.dominant_path >= 0) {
    const auto dp = static_cast<std::size_t>(in.dominant_path);
    char index[24];
    std::snprintf(index, sizeof index, "%d", in.dominant_path);
    const char* path_name = dp < t.path_names.size() ? t.path_names[dp].c_str() : index;
    add(dominant_consistent ? "; dominant path %s points at mesh %s"
                            : "; dominant path %s sees no mesh of that shaft, mesh %s by path "
                              "weights",
        path_name, t.mesh_names[m1].c_str());
  }
  if (out.candidates.size() == 1) {
    add(" -> gear %s", t.gear_names[out.gear].c_str());
  } else if (out.candidates.size() > 1) {
    bool same_mesh = true;
    bool same_rate = true;
    for (int g : out.candidates) {
      same_mesh = same_mesh && t.gear_mesh[g] == t.gear_mesh[out.candidates[0]];
      same_rate = same_rate && in_group(t.gear_shaft[g]);
    }
    add(" -> candidates ");
    pos = AppendNames(buf, sizeof buf, pos, t, out.candidates);
    if (same_mesh && same_rate && t.gear_mesh[out.candidates[0]] >= 0) {
      add(": they share mesh %s and shaft rate %.3g Hz, the envelope and the paths cannot "
          "tell them apart",
          t.mesh_names[t.gear_mesh[out.candidates[0]]].c_str(), out.characteristic_hz);
    } else {
      add(": the path evidence does not separate their meshes");
    }
  }
  out.reason.Assign(std::string_view(buf, pos));
}

}  // namespace gearpath

#include "daemon/latest_indicators.h"

#include <algorithm>

namespace gearpath::daemon {

void CaptureLatestIndicators(const BlockResult& r, LatestIndicators& out) noexcept {
  out.valid = true;
  out.score = r.score.score;
  out.limit_z = r.score.limit_z;
  out.exceed_count = r.score.exceed_count;
  out.baseline_blocks_learned = r.score.baseline_blocks_learned;
  out.baseline_blocks_needed = r.score.baseline_blocks_needed;
  out.dominant_path.Assign(r.dominant_path_name);
  const bool has_dominant =
      r.dominant_path >= 0 && static_cast<std::size_t>(r.dominant_path) < r.paths.size();
  out.dominant_path_share = has_dominant ? r.paths[r.dominant_path].share : 0.0;
  out.speed_hz = r.speed_hz;
  out.shaft_count = std::min(r.shafts.size(), kLatestMaxShafts);
  for (std::size_t i = 0; i < out.shaft_count; ++i) {
    const BlockShaftIndicator& s = r.shafts[i];
    LatestShaftIndicators& o = out.shafts[i];
    o.shaft.Assign(s.shaft);
    o.raw = s.raw;
    o.reconstructed = s.reconstructed;
    o.raw_threshold = s.raw_threshold;
    o.reconstructed_threshold = s.reconstructed_threshold;
  }
}

}  // namespace gearpath::daemon

// LatestIndicators: what the metrics endpoint shows of a machine's last accepted block.
//
// A fixed-size copy of a few BlockResult figures (the score against its limit, the dominant
// path and its share, the envelope indicators per shaft and their thresholds, the speed),
// taken by the worker after each accepted block under the lane's counters_mutex. Names are
// copied into fixed buffers (FixedText), so the capture allocates nothing; the HTTP thread
// never touches the processor or its BlockResult. The shaft count is bounded by the IDL's
// MAX_SHAFTS (16), which bounds the metric series per machine.
#pragma once

#include <array>
#include <cstdint>

#include "core/diagnosis/fixed_text.h"
#include "core/pipeline/block_processor.h"

namespace gearpath::daemon {

inline constexpr std::size_t kLatestMaxShafts = 16;  // IDL MAX_SHAFTS
using LatestName = FixedText<64>;                    // IDL ID_LENGTH

struct LatestShaftIndicators {
  LatestName shaft;
  double raw = 0.0;                      // SES harmonic sum, measured signal
  double reconstructed = 0.0;            // same, dominant path's contribution
  double raw_threshold = 0.0;            // 0 while learning
  double reconstructed_threshold = 0.0;
};

struct LatestIndicators {
  bool valid = false;      // false until a block has been accepted (since start or reload)
  double score = 0.0;      // largest indicator z / limit z: 1 is the limit
  double limit_z = 0.0;    // 0 while learning
  int exceed_count = 0;    // exceedances in the alarm window
  int baseline_blocks_learned = 0;
  int baseline_blocks_needed = 0;
  LatestName dominant_path;
  double dominant_path_share = 0.0;  // its band-energy share, [0, 1]
  double speed_hz = 0.0;
  std::array<LatestShaftIndicators, kLatestMaxShafts> shafts{};
  std::size_t shaft_count = 0;
};

// Copies the figures of an accepted block's result; allocation-free, noexcept.
void CaptureLatestIndicators(const BlockResult& result, LatestIndicators& out) noexcept;

}  // namespace gearpath::daemon

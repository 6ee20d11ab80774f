// Block validation: is this AccelBlock something the machine it claims to come from can have
// produced? Checked before any numerics touch the data, each failure a typed reason plus a
// one-line message naming the expected and the received value, e.g.
//   "sample rate 8192 Hz does not match machine 'gb1' (expects 8000 Hz +/- 0.01 %)".
// Bad input never crashes the daemon and never silently disappears (DESIGN.md ground rules):
// the daemon counts rejections by reason and reports them on its status topic.
//
// Order of the checks (the first failure wins, cheapest and most fundamental first):
//   machine id, oversize cap, empty, channel count, channel layout, sample rate, speed,
//   length, finiteness, flat channel. Sequence numbers are judged separately by
//   SequenceTracker, only for blocks that passed everything else, so a rejected block never
//   advances the tracker.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "core/common/accel_block.h"
#include "core/diagnosis/fixed_text.h"

namespace gearpath {

enum class RejectReason : std::uint8_t {
  kNone,                // accepted
  kUnknownMachine,      // machine id is not the one this processor watches
  kOversized,           // more samples than the hard cap (checked before reading any sample)
  kEmpty,               // no channels or no samples
  kWrongChannelCount,   // channel count differs from the machine's layout
  kWrongChannelLayout,  // a channel's (sensor, axis) differs from the layout at that index
  kWrongSampleRate,     // sample rate outside the machine's rate +/- tolerance
  kBadLength,           // samples per channel too short / too long / samples.size() inconsistent
  kNonFinite,           // NaN or Inf sample
  kDuplicateSequence,   // same sequence number as the last accepted block
  kOutOfOrderSequence,  // sequence number below the last accepted block
  kNotConfigured,       // processor could not configure for this block shape (see message)
  kImplausibleSpeed,    // speed_hz not finite, negative, or outside the machine's plausible range
  kFlatChannel,         // every sample of a channel is the same value (zero: sensor/bridge dead)
  kNoSignalInBand,      // no transfer path carries energy in the analysis band (path energy)
  kImplausibleLoad,     // load not finite or negative
};

// Stable snake_case name, e.g. "wrong_sample_rate" (used as the status topic's counter key).
std::string_view ToString(RejectReason reason) noexcept;

// One expected block channel: accelerometer `sensor`, axis `axis`.
struct ExpectedChannel {
  std::string sensor;
  Axis axis = Axis::kX;
};

struct BlockExpectations {
  std::string machine_id;
  std::vector<ExpectedChannel> channels;  // exact order of the block's channels
  double sample_rate_hz = 0.0;            // > 0
  double sample_rate_tolerance = 1e-4;    // relative (1e-4 = 0.01 %)
  std::uint32_t min_samples_per_channel = 256;
  std::uint32_t max_samples_per_channel = 1u << 20;
  std::size_t max_total_samples = std::size_t{1} << 26;  // hard cap, any layout
  // Plausible input-shaft speed of a block that carries one; 0 = no bound on that side.
  // speed_hz = 0 means "unknown" (the pipeline takes the nominal speed or estimates it) and
  // is always accepted; NaN, infinity and negative speeds never are.
  double min_speed_hz = 0.0;
  double max_speed_hz = 0.0;
};

// Fills `message` and returns the reason (kNone and an empty message when the block is valid).
// noexcept and allocation-free.
RejectReason ValidateBlock(const AccelBlockView& block, const BlockExpectations& expected,
                           MessageText& message) noexcept;

// SequenceTracker: per-machine sequence bookkeeping, pure (no clock, no I/O).
//
// Policy (documented in docs/diagnosis.md):
//  - first block: accepted whatever its number;
//  - seq == last accepted: rejected kDuplicateSequence;
//  - last - reorder_window <= seq < last: rejected kOutOfOrderSequence, UNLESS it is the
//    `resync_after`-th block of a contiguous run of such backward blocks (a publisher
//    restart): then accepted and `restarted` is set;
//  - seq < last - reorder_window: accepted at once as a publisher restart (`restarted`, no
//    gap): a block that far behind is no late block, and waiting would drop good blocks;
//  - last + 1 < seq <= last + 1 + max_gap: ACCEPTED, and the number of missing blocks is
//    reported in `gap` (a lost block does not make the next one wrong; the loss is counted,
//    not hidden);
//  - seq > last + 1 + max_gap: accepted as a restart (`restarted`, no gap): a jump of more
//    than max_gap blocks is a renumbering or a corrupt number (2^64 - 1), not a loss, and
//    must not add ~2^64 to the lost counter.
// Plain unsigned arithmetic, no wrap-around: a uint64 counter at 10^6 blocks/s wraps after
// 584 000 years, so 2^64 - 1 followed by 0 is a restart (far backward), not a gap of 0.
class SequenceTracker {
 public:
  // Largest forward jump counted as lost blocks (2^24: 194 days at one block per second).
  static constexpr std::uint64_t kDefaultMaxGap = std::uint64_t{1} << 24;
  // Deepest backward jump still treated as a late block rather than a restart.
  static constexpr std::uint64_t kDefaultReorderWindow = 1024;

  struct Verdict {
    RejectReason reason = RejectReason::kNone;  // kNone, kDuplicateSequence, kOutOfOrderSequence
    std::uint64_t gap = 0;                      // blocks missing before this one (accepted only)
    bool restarted = false;                     // accepted as a publisher restart
  };

  explicit SequenceTracker(std::uint32_t resync_after = 3, std::uint64_t max_gap = kDefaultMaxGap,
                           std::uint64_t reorder_window = kDefaultReorderWindow) noexcept
      : resync_after_(resync_after == 0 ? 1 : resync_after),
        max_gap_(max_gap),
        reorder_window_(reorder_window) {}

  // Judges `sequence` and, when accepted, makes it the last accepted one. Fills `message`
  // for rejections (names the machine, the received and the last accepted number).
  Verdict Observe(std::uint64_t sequence, std::string_view machine_id,
                  MessageText& message) noexcept;

  bool has_last() const noexcept { return has_last_; }
  std::uint64_t last() const noexcept { return last_; }
  std::uint64_t total_gap() const noexcept { return total_gap_; }
  void Reset() noexcept;

 private:
  std::uint32_t resync_after_;
  std::uint64_t max_gap_;
  std::uint64_t reorder_window_;
  bool has_last_ = false;
  std::uint64_t last_ = 0;
  std::uint64_t total_gap_ = 0;
  // Run of contiguous backward blocks (candidate restart).
  std::uint32_t backward_run_ = 0;
  std::uint64_t backward_last_ = 0;
};

}  // namespace gearpath

// AlarmModel: the per-machine alarm state machine that turns per-block anomaly scores into a
// steady FaultState, with persistence (k of the last n blocks), hysteresis (a lower clear
// level) and a clear delay, plus a latched localisation that does not flicker.
//
// Input per block: the score in units of the alarm threshold (score >= 1: the block exceeds)
// and an opaque gear vote (>= 0; -1 = none). Why: a single block over the threshold is
// usually noise (with K indicators at a 1 % per-block false-alarm rate a healthy machine
// exceeds once every 100 blocks); demanding k exceedances among the last n turns a per-block
// probability p into ~C(n, k) p^k for a window and delays detection by about k blocks; a clear
// level under 1 and a clear delay stop a fault that hovers around its threshold from
// flickering (DIAGNOSTICS.md, "Judging indicators against a healthy baseline").
//
// Transitions (evaluated once per block, in this order; n, suspect_k, alarm_k, clear_level,
// clear_blocks = c from AlarmOptions):
//   learning block          -> kLearning; window, votes and quiet run emptied (fresh start).
//   score NaN               -> no evidence: state, window and run held (blocks_in_state + 1).
//   Otherwise let active = state in {kSuspected, kAlarm}; the block EXCEEDS when
//   score >= (active ? clear_level : 1) (hysteresis) and is QUIET when score < clear_level.
//   The exceedance enters the window of the last n blocks (count = exceedances in it), the
//   vote of an exceeding block enters the vote ring, quiet run = consecutive quiet blocks.
//   kLearning/kNoFault: exceeds and count >= alarm_k   -> kAlarm
//                       exceeds and count >= suspect_k -> kSuspected
//                       else                           -> kNoFault
//   kSuspected:         quiet run >= c                 -> kNoFault (clear)
//                       exceeds and count >= alarm_k   -> kAlarm
//                       else                           -> kSuspected
//   kAlarm:             quiet run >= c                 -> kNoFault (clear)
//                       else                           -> kAlarm
//   A clear empties the window and the votes: the c quiet blocks have just shown the machine
//   back under clear_level, so older exceedances must not re-raise it on the next block.
// Consequences: every escalation happens on an exceeding block (the count only grows by the
// current block). kAlarm never falls back to kSuspected and leaves only through c consecutive
// quiet blocks; the clear empties the window, so kAlarm needs alarm_k new exceedances again
// and kAlarm -> kNoFault -> kAlarm takes at least c + alarm_k blocks (5 with the defaults).
// Hence a steady fault shows more than one state change in 5 consecutive blocks only around a
// clear, i.e. after c consecutive quiet blocks: probability ~u^c per block when the faulty
// score falls under clear_level with probability u (u = 0.04, c = 3: 6e-5), while one under 1
// alone (20 % of the blocks for a fault exceeding in 80 %) changes nothing.
//
// Healthy stream, per-block exceedance probability p = P(score >= 1) and q = P(score >=
// clear_level) >= p, independent blocks. For suspect_k = 1, alarm_k = 2, c <= n - 1 (the
// defaults) the model is a renewal process and the fractions of blocks are exact:
//   s = 1 - q,  E[S] = c s^c + q sum_{j=1..c} j s^(j-1)   (blocks in kSuspected per episode),
//   P(escalate) = 1 - s^c,  E[A] = (1 - s^c) / (q s^c)   (blocks in kAlarm per alarm),
//   L = 1/p + E[S] + (1 - s^c) E[A]                       (blocks per cycle),
//   fraction kAlarm = (1 - s^c)^2 / (q s^c) / L  ~  c^2 p q,   fraction kSuspected = E[S] / L.
// (The leading term: an exceedance (p) is followed within c blocks by a block over the clear
// level (~c q), and the alarm then lasts ~c blocks.) Without hysteresis (q = p) the alarm
// fraction is ~c^2 p^2, comparable to the window probability C(n, 2) p^2 = 10 p^2 for n = 5.
// ExpectedHealthyFractions() evaluates the exact expression.
//
// Latched localisation: the votes of the last n exceeding blocks (votes -1 are not kept);
// latched_vote = the most frequent, ties to the most recent; -1 when none. Emptied on a clear.
// Per-block Update is noexcept and allocation-free (fixed arrays, n <= kMaxAlarmWindow).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/common/result.h"
#include "core/diagnosis/gear_verdict.h"

namespace gearpath {

inline constexpr int kMaxAlarmWindow = 64;

struct AlarmOptions {
  int n = 5;                 // window length in blocks, [1, kMaxAlarmWindow]
  int suspect_k = 1;         // exceedances in the window for kSuspected, [1, alarm_k]
  int alarm_k = 2;           // exceedances in the window for kAlarm, [suspect_k, n]
  double clear_level = 0.7;  // hysteresis level in threshold units, (0, 1]
  int clear_blocks = 3;      // consecutive quiet blocks to clear, >= 1
  bool operator==(const AlarmOptions&) const = default;
};

struct AlarmEvidence {
  bool learning = false;  // the baseline is still being learned
  double score = 0.0;     // this block's anomaly score in units of the alarm threshold
  int gear_vote = -1;     // this block's localisation (opaque, >= 0); -1 = none
};

struct AlarmStatus {
  FaultState state = FaultState::kLearning;
  int exceed_count = 0;     // exceedances among the last `window` blocks (after this block)
  int window = 0;           // n
  double score = 0.0;       // this block's score
  int latched_vote = -1;    // most frequent vote of the recent exceeding blocks; -1 = none
  int blocks_in_state = 0;  // consecutive blocks in `state`, this one included
};

// Everything needed to resume after a restart (written to disk elsewhere).
struct AlarmModelState {
  AlarmOptions options;
  FaultState state = FaultState::kLearning;
  std::uint64_t exceed_bits = 0;  // bit j = the block j blocks ago exceeded (j < n)
  int quiet_run = 0;
  int blocks_in_state = 0;
  std::vector<int> votes;  // kept votes, oldest first (at most n, each >= 0)
};

struct AlarmFractions {
  double suspected = 0.0;  // fraction of healthy blocks reported kSuspected
  double alarm = 0.0;      // fraction of healthy blocks reported kAlarm
};

class AlarmModel {
 public:
  // Validates the options; messages name the field.
  static Result<AlarmModel> Create(const AlarmOptions& options);
  // Validates options and state (sizes, ranges, enum); messages name the field.
  static Result<AlarmModel> FromState(const AlarmModelState& state);
  AlarmModelState State() const;

  // One block. noexcept, no allocation.
  const AlarmStatus& Update(const AlarmEvidence& evidence) noexcept;
  const AlarmStatus& status() const noexcept { return status_; }
  const AlarmOptions& options() const noexcept { return options_; }
  void Reset() noexcept;  // back to kLearning with everything emptied

  // The exact healthy-stream fractions of the header comment, for exceedance probability p
  // (score >= 1) and q (score >= clear_level), 0 < p <= q < 1. Valid for suspect_k = 1,
  // alarm_k = 2, clear_blocks <= n - 1; NaN otherwise.
  static AlarmFractions ExpectedHealthyFractions(double p, double q, const AlarmOptions& options);

 private:
  AlarmModel() = default;
  void Clear() noexcept;  // empties window, votes and quiet run
  void PushVote(int vote) noexcept;
  int LatchedVote() const noexcept;

  AlarmOptions options_;
  AlarmStatus status_;
  std::uint64_t exceed_bits_ = 0;
  std::uint64_t window_mask_ = 0;
  int quiet_run_ = 0;
  std::array<int, kMaxAlarmWindow> votes_{};  // ring, oldest at votes_head_
  int votes_head_ = 0;
  int votes_size_ = 0;
};

}  // namespace gearpath

#include "core/diagnosis/alarm_model.h"

#include <bit>
#include <cmath>
#include <limits>
#include <string>

namespace gearpath {
namespace {

std::uint64_t WindowMask(int n) {
  return n >= 64 ? ~std::uint64_t{0} : (std::uint64_t{1} << n) - 1;
}

std::string ValidateOptions(const AlarmOptions& o) {
  if (o.n < 1 || o.n > kMaxAlarmWindow) {
    return "alarm model: n must be in [1, " + std::to_string(kMaxAlarmWindow) + "], got " +
           std::to_string(o.n);
  }
  if (o.alarm_k < 1 || o.alarm_k > o.n) {
    return "alarm model: alarm_k must be in [1, n = " + std::to_string(o.n) + "], got " +
           std::to_string(o.alarm_k);
  }
  if (o.suspect_k < 1 || o.suspect_k > o.alarm_k) {
    return "alarm model: suspect_k must be in [1, alarm_k = " + std::to_string(o.alarm_k) +
           "], got " + std::to_string(o.suspect_k);
  }
  if (!(o.clear_level > 0.0 && o.clear_level <= 1.0)) {
    return "alarm model: clear_level must be in (0, 1], got " + std::to_string(o.clear_level);
  }
  if (o.clear_blocks < 1) {
    return "alarm model: clear_blocks must be >= 1, got " + std::to_string(o.clear_blocks);
  }
  return {};
}

}  // namespace

Result<AlarmModel> AlarmModel::Create(const AlarmOptions& options) {
  if (std::string e = ValidateOptions(options); !e.empty()) return Error{std::move(e)};
  AlarmModel m;
  m.options_ = options;
  m.window_mask_ = WindowMask(options.n);
  m.Reset();
  return m;
}

Result<AlarmModel> AlarmModel::FromState(const AlarmModelState& state) {
  if (std::string e = ValidateOptions(state.options); !e.empty()) {
    return Error{"alarm model state: options." + e.substr(std::string("alarm model: ").size())};
  }
  Result<AlarmModel> made = Create(state.options);
  AlarmModel& m = made.value();
  const auto raw_state = static_cast<int>(state.state);
  if (raw_state < static_cast<int>(FaultState::kLearning) ||
      raw_state > static_cast<int>(FaultState::kAlarm)) {
    return Error{"alarm model state: state is not a FaultState, got " + std::to_string(raw_state)};
  }
  if ((state.exceed_bits & ~m.window_mask_) != 0) {
    return Error{"alarm model state: exceed_bits has bits beyond the window n = " +
                 std::to_string(state.options.n)};
  }
  if (state.quiet_run < 0) {
    return Error{"alarm model state: quiet_run must be >= 0, got " +
                 std::to_string(state.quiet_run)};
  }
  if (state.blocks_in_state < 0) {
    return Error{"alarm model state: blocks_in_state must be >= 0, got " +
                 std::to_string(state.blocks_in_state)};
  }
  if (state.votes.size() > static_cast<std::size_t>(state.options.n)) {
    return Error{
        "alarm model state: votes must hold at most n = " + std::to_string(state.options.n) +
        " entries, got " + std::to_string(state.votes.size())};
  }
  for (std::size_t i = 0; i < state.votes.size(); ++i) {
    if (state.votes[i] < 0) {
      return Error{"alarm model state: votes[" + std::to_string(i) + "] must be >= 0, got " +
                   std::to_string(state.votes[i])};
    }
  }
  m.exceed_bits_ = state.exceed_bits;
  m.quiet_run_ = state.quiet_run;
  for (int v : state.votes) m.PushVote(v);
  m.status_.state = state.state;
  m.status_.blocks_in_state = state.blocks_in_state;
  m.status_.exceed_count = std::popcount(m.exceed_bits_);
  m.status_.latched_vote = m.LatchedVote();
  return made;
}

AlarmModelState AlarmModel::State() const {
  AlarmModelState s;
  s.options = options_;
  s.state = status_.state;
  s.exceed_bits = exceed_bits_;
  s.quiet_run = quiet_run_;
  s.blocks_in_state = status_.blocks_in_state;
  s.votes.reserve(static_cast<std::size_t>(votes_size_));
  for (int i = 0; i < votes_size_; ++i) s.votes.push_back(votes_[(votes_head_ + i) % options_.n]);
  return s;
}

void AlarmModel::Clear() noexcept {
  exceed_bits_ = 0;
  quiet_run_ = 0;
  votes_head_ = 0;
  votes_size_ = 0;
}

void AlarmModel::Reset() noexcept {
  Clear();
  status_ = AlarmStatus{};
  status_.window = options_.n;
}

void AlarmModel::PushVote(int vote) noexcept {
  const int n = options_.n;
  if (votes_size_ < n) {
    votes_[(votes_head_ + votes_size_) % n] = vote;
    ++votes_size_;
  } else {  // full: overwrite the oldest
    votes_[votes_head_] = vote;
    votes_head_ = (votes_head_ + 1) % n;
  }
}

int AlarmModel::LatchedVote() const noexcept {
  const int n = options_.n;
  int best = -1;
  int best_count = 0;
  // From the most recent back, so on a tie the vote met first (the most recent) stays.
  for (int i = votes_size_ - 1; i >= 0; --i) {
    const int v = votes_[(votes_head_ + i) % n];
    int c = 0;
    for (int j = 0; j < votes_size_; ++j) c += votes_[(votes_head_ + j) % n] == v ? 1 : 0;
    if (c > best_count) {
      best = v;
      best_count = c;
    }
  }
  return best;
}

const AlarmStatus& AlarmModel::Update(const AlarmEvidence& evidence) noexcept {
  status_.score = evidence.score;
  if (evidence.learning) {
    Clear();
    status_.blocks_in_state =
        status_.state == FaultState::kLearning ? status_.blocks_in_state + 1 : 1;
    status_.state = FaultState::kLearning;
    status_.exceed_count = 0;
    status_.latched_vote = -1;
    return status_;
  }
  if (std::isnan(evidence.score)) {  // no evidence: hold everything
    ++status_.blocks_in_state;
    return status_;
  }

  const FaultState before = status_.state;
  const bool active = before == FaultState::kSuspected || before == FaultState::kAlarm;
  const bool exceeds = evidence.score >= (active ? options_.clear_level : 1.0);
  const bool quiet = evidence.score < options_.clear_level;

  exceed_bits_ = ((exceed_bits_ << 1) | (exceeds ? 1u : 0u)) & window_mask_;
  quiet_run_ = quiet ? quiet_run_ + 1 : 0;
  bool votes_changed = false;
  if (exceeds && evidence.gear_vote >= 0) {
    PushVote(evidence.gear_vote);
    votes_changed = true;
  }
  const int count = std::popcount(exceed_bits_);

  FaultState next = before;
  switch (before) {
    case FaultState::kLearning:
    case FaultState::kNoFault:
      if (exceeds && count >= options_.alarm_k) {
        next = FaultState::kAlarm;
      } else if (exceeds && count >= options_.suspect_k) {
        next = FaultState::kSuspected;
      } else {
        next = FaultState::kNoFault;
      }
      break;
    case FaultState::kSuspected:
      if (quiet_run_ >= options_.clear_blocks) {
        next = FaultState::kNoFault;
      } else if (exceeds && count >= options_.alarm_k) {
        next = FaultState::kAlarm;
      }
      break;
    case FaultState::kAlarm:
      if (quiet_run_ >= options_.clear_blocks) next = FaultState::kNoFault;
      break;
  }
  if (active && next == FaultState::kNoFault) {
    Clear();
    votes_changed = true;
  }

  status_.blocks_in_state = next == before ? status_.blocks_in_state + 1 : 1;
  status_.state = next;
  status_.exceed_count = std::popcount(exceed_bits_);
  if (votes_changed) status_.latched_vote = LatchedVote();
  return status_;
}

AlarmFractions AlarmModel::ExpectedHealthyFractions(double p, double q,
                                                    const AlarmOptions& options) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  if (!ValidateOptions(options).empty() || options.suspect_k != 1 || options.alarm_k != 2 ||
      options.clear_blocks > options.n - 1 || !(p > 0.0 && p <= q && q < 1.0)) {
    return {kNaN, kNaN};
  }
  const int c = options.clear_blocks;
  const double s = 1.0 - q;
  const double sc = std::pow(s, c);
  double suspected = c * sc;  // E[S]
  for (int j = 1; j <= c; ++j) suspected += q * j * std::pow(s, j - 1);
  const double escalate = 1.0 - sc;
  const double alarm_blocks = escalate / (q * sc);  // E[A]
  const double cycle = 1.0 / p + suspected + escalate * alarm_blocks;
  return {suspected / cycle, escalate * alarm_blocks / cycle};
}

}  // namespace gearpath

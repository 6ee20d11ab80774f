#include "core/pipeline/block_validation.h"

#include <cmath>

namespace gearpath {
namespace {

const char* AxisName(Axis axis) noexcept {
  switch (axis) {
    case Axis::kX:
      return "x";
    case Axis::kY:
      return "y";
    case Axis::kZ:
      return "z";
  }
  return "?";
}

// Prints a string_view that is not NUL-terminated through "%.*s".
int Len(std::string_view s) noexcept { return static_cast<int>(s.size()); }

}  // namespace

std::string_view ToString(RejectReason reason) noexcept {
  switch (reason) {
    case RejectReason::kNone:
      return "none";
    case RejectReason::kUnknownMachine:
      return "unknown_machine";
    case RejectReason::kOversized:
      return "oversized";
    case RejectReason::kEmpty:
      return "empty";
    case RejectReason::kWrongChannelCount:
      return "wrong_channel_count";
    case RejectReason::kWrongChannelLayout:
      return "wrong_channel_layout";
    case RejectReason::kWrongSampleRate:
      return "wrong_sample_rate";
    case RejectReason::kBadLength:
      return "bad_length";
    case RejectReason::kNonFinite:
      return "non_finite";
    case RejectReason::kDuplicateSequence:
      return "duplicate_sequence";
    case RejectReason::kOutOfOrderSequence:
      return "out_of_order_sequence";
    case RejectReason::kNotConfigured:
      return "not_configured";
    case RejectReason::kImplausibleSpeed:
      return "implausible_speed";
    case RejectReason::kFlatChannel:
      return "flat_channel";
    case RejectReason::kNoSignalInBand:
      return "no_signal_in_band";
    case RejectReason::kImplausibleLoad:
      return "implausible_load";
  }
  return "unknown";
}

RejectReason ValidateBlock(const AccelBlockView& block, const BlockExpectations& expected,
                           MessageText& message) noexcept {
  message.Clear();
  const std::string_view machine = expected.machine_id;
  if (block.machine_id != machine) {
    message.Format("block is for machine '%.*s' but this processor watches machine '%.*s'",
                   Len(block.machine_id), block.machine_id.data(), Len(machine), machine.data());
    return RejectReason::kUnknownMachine;
  }
  if (block.samples.size() > expected.max_total_samples) {
    message.Format("block of machine '%.*s' carries %zu samples, over the cap of %zu", Len(machine),
                   machine.data(), block.samples.size(), expected.max_total_samples);
    return RejectReason::kOversized;
  }
  if (block.channels.empty() || block.samples.empty() || block.samples_per_channel == 0) {
    message.Format(
        "block %llu of machine '%.*s' is empty (%zu channels, %u samples per channel, "
        "%zu samples)",
        static_cast<unsigned long long>(block.sequence), Len(machine), machine.data(),
        block.channels.size(), block.samples_per_channel, block.samples.size());
    return RejectReason::kEmpty;
  }
  if (block.channels.size() != expected.channels.size()) {
    message.Format("block has %zu channels but machine '%.*s' has %zu", block.channels.size(),
                   Len(machine), machine.data(), expected.channels.size());
    return RejectReason::kWrongChannelCount;
  }
  for (std::size_t c = 0; c < block.channels.size(); ++c) {
    const ChannelInfo& got = block.channels[c];
    const ExpectedChannel& want = expected.channels[c];
    if (got.sensor != want.sensor || got.axis != want.axis) {
      message.Format("channel %zu is %s/%s but machine '%.*s' expects %s/%s there", c,
                     got.sensor.c_str(), AxisName(got.axis), Len(machine), machine.data(),
                     want.sensor.c_str(), AxisName(want.axis));
      return RejectReason::kWrongChannelLayout;
    }
  }
  const double rate = block.sample_rate_hz;
  const double want_rate = expected.sample_rate_hz;
  if (!std::isfinite(rate) ||
      std::abs(rate - want_rate) > expected.sample_rate_tolerance * want_rate) {
    message.Format("sample rate %g Hz does not match machine '%.*s' (expects %g Hz +/- %g %%)",
                   rate, Len(machine), machine.data(), want_rate,
                   expected.sample_rate_tolerance * 100.0);
    return RejectReason::kWrongSampleRate;
  }
  // A speed is trusted by every later stage (shaft rates, orders, envelope harmonics): a
  // non-finite one, or one far outside what the machine can do (1e300 Hz, rpm sent as Hz), is
  // a broken tachometer or publisher, not a reading. 0 stays "unknown".
  const double speed = block.speed_hz;
  if (speed != 0.0) {
    if (!std::isfinite(speed) || speed < 0.0) {
      message.Format(
          "speed %g Hz of block %llu is not a shaft speed (finite and > 0 Hz, or 0 "
          "when unknown)",
          speed, static_cast<unsigned long long>(block.sequence));
      return RejectReason::kImplausibleSpeed;
    }
    if ((expected.min_speed_hz > 0.0 && speed < expected.min_speed_hz) ||
        (expected.max_speed_hz > 0.0 && speed > expected.max_speed_hz)) {
      message.Format(
          "speed %g Hz of block %llu is outside the plausible range of machine "
          "'%.*s' (%g..%g Hz)",
          speed, static_cast<unsigned long long>(block.sequence), Len(machine), machine.data(),
          expected.min_speed_hz, expected.max_speed_hz);
      return RejectReason::kImplausibleSpeed;
    }
  }
  // The load only selects whether the baseline judges the block: any finite non-negative value
  // is a reading (0: not carried); a NaN or a negative load is a broken publisher.
  if (!std::isfinite(block.load) || block.load < 0.0) {
    message.Format("load %g of block %llu is not a load (finite and > 0, or 0 when unknown)",
                   block.load, static_cast<unsigned long long>(block.sequence));
    return RejectReason::kImplausibleLoad;
  }
  const std::size_t n = block.samples_per_channel;
  if (block.samples.size() != block.channels.size() * n) {
    message.Format("block carries %zu samples but %zu channels x %zu samples per channel = %zu",
                   block.samples.size(), block.channels.size(), n, block.channels.size() * n);
    return RejectReason::kBadLength;
  }
  if (n < expected.min_samples_per_channel) {
    message.Format(
        "block has %zu samples per channel, too short for machine '%.*s' "
        "(at least %u)",
        n, Len(machine), machine.data(), expected.min_samples_per_channel);
    return RejectReason::kBadLength;
  }
  if (n > expected.max_samples_per_channel) {
    message.Format(
        "block has %zu samples per channel, too long for machine '%.*s' "
        "(at most %u)",
        n, Len(machine), machine.data(), expected.max_samples_per_channel);
    return RejectReason::kBadLength;
  }
  for (std::size_t i = 0; i < block.samples.size(); ++i) {
    if (!std::isfinite(block.samples[i])) {
      const std::size_t c = i / n;
      message.Format("sample %zu of channel %zu (%s/%s) is %s", i % n, c,
                     block.channels[c].sensor.c_str(), AxisName(block.channels[c].axis),
                     std::isnan(block.samples[i]) ? "NaN" : "infinite");
      return RejectReason::kNonFinite;
    }
  }
  // A channel holding one value throughout (all zero: an unpowered sensor or bridge; a
  // constant: a stuck or saturated input) carries no vibration. Processed, it would be fitted
  // as real silence (an all-zero block gave a dominant path with no name); rejected, it shows
  // on the status topic. A live channel differs from its first sample within a few samples.
  std::size_t flat = 0;
  std::size_t first_flat = 0;
  for (std::size_t c = 0; c < block.channels.size(); ++c) {
    const float* x = block.samples.data() + c * n;
    std::size_t i = 1;
    while (i < n && x[i] == x[0]) ++i;
    if (i == n) {
      if (flat == 0) first_flat = c;
      ++flat;
    }
  }
  if (flat == block.channels.size() && block.samples[0] == 0.0f) {
    bool all_zero = true;
    for (std::size_t c = 0; c < block.channels.size(); ++c) {
      all_zero = all_zero && block.samples[c * n] == 0.0f;
    }
    if (all_zero) {
      message.Format("every sample of all %zu channels is zero: sensors or bridge dead?",
                     block.channels.size());
      return RejectReason::kFlatChannel;
    }
  }
  if (flat > 0) {
    const float value = block.samples[first_flat * n];
    const ChannelInfo& ch = block.channels[first_flat];
    if (value == 0.0f) {
      message.Format("every sample of channel %zu (%s/%s) is zero: sensor or bridge dead?%s",
                     first_flat, ch.sensor.c_str(), AxisName(ch.axis),
                     flat > 1 ? " (and other channels are flat too)" : "");
    } else {
      message.Format(
          "every sample of channel %zu (%s/%s) is %g: a flat signal, sensor stuck "
          "or saturated?%s",
          first_flat, ch.sensor.c_str(), AxisName(ch.axis), static_cast<double>(value),
          flat > 1 ? " (and other channels are flat too)" : "");
    }
    return RejectReason::kFlatChannel;
  }
  return RejectReason::kNone;
}

SequenceTracker::Verdict SequenceTracker::Observe(std::uint64_t sequence,
                                                  std::string_view machine_id,
                                                  MessageText& message) noexcept {
  message.Clear();
  Verdict verdict;
  const auto accept = [&](std::uint64_t gap) {
    verdict.gap = gap;
    total_gap_ += gap;
    has_last_ = true;
    last_ = sequence;
    backward_run_ = 0;
  };
  if (!has_last_) {
    accept(0);
    return verdict;
  }
  if (sequence == last_) {
    message.Format("block %llu of machine '%.*s' repeats the last accepted sequence number",
                   static_cast<unsigned long long>(sequence), Len(machine_id), machine_id.data());
    verdict.reason = RejectReason::kDuplicateSequence;
    return verdict;
  }
  if (sequence > last_) {
    const std::uint64_t gap = sequence - last_ - 1;
    if (gap > max_gap_) {  // a renumbering or a corrupt number, not 2^64 lost blocks
      accept(0);
      verdict.restarted = true;
      return verdict;
    }
    accept(gap);
    return verdict;
  }
  if (last_ - sequence > reorder_window_) {  // too far back for a late block: a restart
    accept(0);
    verdict.restarted = true;
    return verdict;
  }
  // Backward: a late block, or a publisher that restarted its numbering.
  if (backward_run_ > 0 && sequence == backward_last_ + 1) {
    ++backward_run_;
  } else {
    backward_run_ = 1;
  }
  backward_last_ = sequence;
  if (backward_run_ >= resync_after_) {
    accept(0);
    verdict.restarted = true;
    return verdict;
  }
  message.Format("block %llu of machine '%.*s' arrived after block %llu (out of order)",
                 static_cast<unsigned long long>(sequence), Len(machine_id), machine_id.data(),
                 static_cast<unsigned long long>(last_));
  verdict.reason = RejectReason::kOutOfOrderSequence;
  return verdict;
}

void SequenceTracker::Reset() noexcept {
  has_last_ = false;
  last_ = 0;
  total_gap_ = 0;
  backward_run_ = 0;
  backward_last_ = 0;
}

}  // namespace gearpath

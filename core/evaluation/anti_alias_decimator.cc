#include "core/evaluation/anti_alias_decimator.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace gearpath {
namespace {

// Modified Bessel function of the first kind, order 0 (power series).
double BesselI0(double x) noexcept {
  double sum = 1.0, term = 1.0;
  const double q = 0.25 * x * x;
  for (int k = 1; k < 500; ++k) {
    term *= q / (static_cast<double>(k) * static_cast<double>(k));
    sum += term;
    if (term < 1e-17 * sum) break;
  }
  return sum;
}

}  // namespace

int KaiserLength(double attenuation_db, double width_cycles) noexcept {
  const double n = (attenuation_db - 7.95) / (2.285 * 2.0 * std::numbers::pi * width_cycles);
  int length = static_cast<int>(std::ceil(n)) + 1;
  if (length % 2 == 0) ++length;
  return length < 3 ? 3 : length;
}

double KaiserBeta(double attenuation_db) noexcept {
  if (attenuation_db > 50.0) return 0.1102 * (attenuation_db - 8.7);
  if (attenuation_db >= 21.0) {
    return 0.5842 * std::pow(attenuation_db - 21.0, 0.4) + 0.07886 * (attenuation_db - 21.0);
  }
  return 0.0;
}

std::vector<double> KaiserLowPass(int length, double cutoff, double beta) {
  std::vector<double> h(static_cast<std::size_t>(length));
  const double mid = 0.5 * static_cast<double>(length - 1);
  const double i0b = BesselI0(beta);
  double sum = 0.0;
  for (int n = 0; n < length; ++n) {
    const double t = static_cast<double>(n) - mid;
    const double arg = 2.0 * cutoff * t;
    const double sinc =
        t == 0.0 ? 1.0 : std::sin(std::numbers::pi * arg) / (std::numbers::pi * arg);
    const double r = mid > 0.0 ? t / mid : 0.0;
    const double w = BesselI0(beta * std::sqrt(std::max(0.0, 1.0 - r * r))) / i0b;
    h[static_cast<std::size_t>(n)] = 2.0 * cutoff * sinc * w;
    sum += h[static_cast<std::size_t>(n)];
  }
  for (double& v : h) v /= sum;
  return h;
}

Result<AntiAliasDecimator> AntiAliasDecimator::Create(double input_rate_hz,
                                                      double output_rate_hz, double pass_hz,
                                                      double attenuation_db, int channels) {
  if (!(input_rate_hz > 0.0) || !(output_rate_hz > 0.0)) {
    return Error{"anti-alias decimator: rates must be > 0"};
  }
  const double ratio = input_rate_hz / output_rate_hz;
  const int stages = static_cast<int>(std::lround(std::log2(ratio)));
  if (stages < 1 || stages > 6 || std::abs(ratio - std::ldexp(1.0, stages)) > 1e-9 * ratio) {
    return Error{fmt::format(
        "anti-alias decimator: input / output rate must be 2^K, K in 1..6, got {} / {}",
        input_rate_hz, output_rate_hz)};
  }
  if (!(pass_hz > 0.0 && pass_hz < 0.5 * output_rate_hz)) {
    return Error{fmt::format("anti-alias decimator: pass_hz must be in (0, {}), got {}",
                             0.5 * output_rate_hz, pass_hz)};
  }
  if (!(attenuation_db >= 40.0 && attenuation_db <= 160.0) || channels < 1) {
    return Error{fmt::format(
        "anti-alias decimator: attenuation_db must be in [40, 160] and channels >= 1, got {} "
        "and {}",
        attenuation_db, channels)};
  }
  AntiAliasDecimator d;
  d.factor_ = 1 << stages;
  d.channels_ = channels;
  const double beta = KaiserBeta(attenuation_db);
  double rate = input_rate_hz;
  int scale = 1;
  for (int k = 0; k < stages; ++k) {
    const bool last = k + 1 == stages;
    const double pass = last ? pass_hz : 0.5 * output_rate_hz;
    const double stop = last ? 0.5 * output_rate_hz : 0.5 * rate - 0.5 * output_rate_hz;
    Stage st;
    const int length = KaiserLength(attenuation_db, (stop - pass) / rate);
    st.taps = KaiserLowPass(length, 0.5 * (pass + stop) / rate, beta);
    st.half = (length - 1) / 2;
    st.ring.assign(static_cast<std::size_t>(2 * length * channels), 0.0);
    d.lookahead_ += st.half * scale;
    d.stages_.push_back(std::move(st));
    rate *= 0.5;
    scale *= 2;
  }
  d.scratch_.assign(static_cast<std::size_t>(stages * channels), 0.0);
  return d;
}

bool AntiAliasDecimator::PushStage(int k, const double* frame, double* out) noexcept {
  Stage& st = stages_[static_cast<std::size_t>(k)];
  const int length = static_cast<int>(st.taps.size());
  for (int c = 0; c < channels_; ++c) {
    double* ring = st.ring.data() + static_cast<std::size_t>(2 * length * c);
    ring[st.pos] = frame[c];
    ring[st.pos + length] = frame[c];
  }
  const long long i = st.count++;
  const int newest = st.pos;
  st.pos = st.pos + 1 == length ? 0 : st.pos + 1;
  if (i < st.half || ((i - st.half) & 1) != 0) return false;
  // Window oldest .. newest = ring[newest + 1 .. newest + length]; the taps are symmetric, so
  // each pair of samples at equal distance from the middle shares a multiply.
  const double* h = st.taps.data();
  const int half = st.half;
  for (int c = 0; c < channels_; ++c) {
    const double* x = st.ring.data() + static_cast<std::size_t>(2 * length * c + newest + 1);
    double acc0 = h[half] * x[half], acc1 = 0.0;
    int j = 0;
    for (; j + 1 < half; j += 2) {
      acc0 += h[j] * (x[j] + x[length - 1 - j]);
      acc1 += h[j + 1] * (x[j + 1] + x[length - 2 - j]);
    }
    for (; j < half; ++j) acc0 += h[j] * (x[j] + x[length - 1 - j]);
    out[c] = acc0 + acc1;
  }
  return true;
}

bool AntiAliasDecimator::Push(const double* frame, double* out) noexcept {
  const double* in = frame;
  const int stages = stage_count();
  for (int k = 0; k < stages; ++k) {
    double* dst = k + 1 == stages ? out : scratch_.data() + static_cast<std::size_t>(k * channels_);
    if (!PushStage(k, in, dst)) return false;
    in = dst;
  }
  return true;
}

}  // namespace gearpath

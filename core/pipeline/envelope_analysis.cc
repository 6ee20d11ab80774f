#include "core/pipeline/envelope_analysis.h"

#include <fmt/format.h>

#include <algorithm>
#include <utility>

#include "core/pipeline/machine_context.h"

namespace gearpath {

Result<EnvelopeSettings> EnvelopeSettings::Of(const MachineContext& machine, std::size_t n) {
  const AnalysisOptions& o = machine.setup.options;
  const double fs = o.sample_rate_hz;
  KurtogramOptions ko;
  ko.depth = o.kurtogram_max_level;
  ko.min_bandwidth_hz = o.min_band_width_hz > 0.0
                            ? o.min_band_width_hz
                            : 2.0 * kIndicatorHarmonics * machine.max_ratio * machine.max_speed_hz;
  if (ko.min_bandwidth_hz >= fs / 2.0) {
    return Error{
        fmt::format("envelope band: minimum width {} Hz (2 x {} harmonics x highest "
                    "shaft rate) does not fit below Nyquist {} Hz",
                    ko.min_bandwidth_hz, kIndicatorHarmonics, fs / 2.0)};
  }
  EnvelopeSettings s;
  s.n = n;
  s.sample_rate_hz = fs;
  s.kurtogram = ko;
  return s;
}

Result<EnvelopeAnalysis> EnvelopeAnalysis::Create(const EnvelopeSettings& settings) {
  const std::size_t n = settings.n;
  const double fs = settings.sample_rate_hz;
  const KurtogramOptions& ko = settings.kurtogram;
  EnvelopeAnalysis e;
  e.settings_ = settings;
  e.bin_hz_ = fs / static_cast<double>(n);
  auto kurtogram = Kurtogram::Create(n, fs, ko);
  if (!kurtogram) return Error{"kurtogram: " + kurtogram.error()};
  e.kurtogram_.emplace(std::move(kurtogram.value()));
  auto band_pass = BandPass::Create(n, fs, 0.1 * ko.min_bandwidth_hz);
  if (!band_pass) return Error{"band-pass: " + band_pass.error()};
  e.band_pass_.emplace(std::move(band_pass.value()));
  auto ses = EnvelopeSpectrum::Create(n, fs);
  if (!ses) return Error{"envelope spectrum: " + ses.error()};
  e.ses_.emplace(std::move(ses.value()));
  e.filtered_.assign(n, 0.0);
  e.ses_buf_.assign(n / 2 + 1, 0.0);
  return e;
}

void EnvelopeAnalysis::Process(
    const MachineContext& m, std::span<const double> signal, double speed_hz,
    BlockEnvelopeBand& band, std::span<double> indicator,
    std::span<std::array<double, kIndicatorHarmonics>> harmonics) noexcept {
  band = BlockEnvelopeBand{};
  const double nyquist = m.setup.options.sample_rate_hz / 2.0;
  double lo = m.band_lo;
  double hi = std::min(m.band_hi, nyquist);
  auto k = kurtogram_->Process(signal);
  if (k.ok()) {
    const KurtogramBand& kb = k.value();
    band.kurtosis = kb.kurtosis;
    band.level = kb.node.level;
    band.significant = kb.significant;
    if (kb.significant) {
      lo = kb.low_hz;
      hi = kb.high_hz;
    }
  }
  band.centre_hz = 0.5 * (lo + hi);
  band.width_hz = hi - lo;
  const bool filtered = band_pass_->Process(signal, lo, hi, filtered_).ok();
  const bool have_ses = filtered && ses_->Process(filtered_, ses_buf_).ok();
  HarmonicSearch search;
  search.relative_tolerance = m.setup.options.harmonic_tolerance;
  for (std::size_t s = 0; s < indicator.size(); ++s) {
    const double fc = m.shaft_ratio[s] * speed_hz;
    harmonics[s].fill(0.0);
    indicator[s] = 0.0;
    if (!have_ses || !(fc > 0.0)) continue;
    auto ind = ComputeHarmonicIndicator(ses_buf_, bin_hz_, fc, search);
    if (!ind.ok()) continue;
    for (std::size_t h = 0; h < harmonics[s].size(); ++h) {
      harmonics[s][h] = ind->harmonics[h].amplitude;
    }
    indicator[s] = ind->sum;
  }
}

}  // namespace gearpath

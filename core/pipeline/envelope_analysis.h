// EnvelopeAnalysis: the seed's fault feature enhancement (Algorithm 2) applied to one time
// signal: fast kurtogram band (core/dsp/kurtogram.h, significance-gated; the whole analysis
// band when no band stands out) -> frequency-domain band-pass -> normalised squared envelope
// spectrum -> per shaft, the sum of the SES amplitudes at the first five harmonics of its rate
// (seed Sec. 4.3). Used by the envelope stage (raw and reconstructed signals) and by the
// dominant-path stage's `indicator` criterion. Configure once per shape; Process allocates
// nothing.
//
// Per-call scratch (core/pipeline/shape_scratch.h): it holds plans and buffers only, nothing
// of a machine, so one instance serves every machine whose EnvelopeSettings are equal (the
// machine is passed to Process()).
#pragma once

#include <optional>
#include <span>
#include <vector>

#include "core/common/result.h"
#include "core/dsp/band_pass.h"
#include "core/dsp/envelope_spectrum.h"
#include "core/dsp/harmonic_indicator.h"
#include "core/dsp/kurtogram.h"
#include "core/pipeline/block_processor.h"

namespace gearpath {

struct MachineContext;

// Everything the plans and buffers depend on: machines with equal settings share one analysis.
struct EnvelopeSettings {
  std::size_t n = 0;  // samples per channel
  double sample_rate_hz = 0.0;
  KurtogramOptions kurtogram;
  bool operator==(const EnvelopeSettings&) const = default;

  // A machine's settings for blocks of n samples; errors name the option (a minimum band
  // width that does not fit below Nyquist).
  static Result<EnvelopeSettings> Of(const MachineContext& machine, std::size_t n);
};

class EnvelopeAnalysis {
 public:
  static Result<EnvelopeAnalysis> Create(const EnvelopeSettings& settings);

  const EnvelopeSettings& settings() const noexcept { return settings_; }

  // Fills `band`, and per shaft `indicator[s]` and `harmonics[s]` (amplitudes at 1x..5x of
  // shaft s's rate at `speed_hz`) for `machine` (whose settings these must be).
  // noexcept, allocation-free.
  void Process(const MachineContext& machine, std::span<const double> signal, double speed_hz,
               BlockEnvelopeBand& band, std::span<double> indicator,
               std::span<std::array<double, kIndicatorHarmonics>> harmonics) noexcept;

 private:
  EnvelopeAnalysis() = default;
  EnvelopeSettings settings_;
  double bin_hz_ = 0.0;
  std::optional<Kurtogram> kurtogram_;
  std::optional<BandPass> band_pass_;
  std::optional<EnvelopeSpectrum> ses_;
  std::vector<double> filtered_;  // n
  std::vector<double> ses_buf_;   // bins
};

}  // namespace gearpath

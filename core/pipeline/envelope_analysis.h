// EnvelopeAnalysis: the seed's fault feature enhancement (Algorithm 2) applied to one time
// signal: fast kurtogram band (core/dsp/kurtogram.h, significance-gated; the whole analysis
// band when no band stands out) -> frequency-domain band-pass -> normalised squared envelope
// spectrum -> per shaft, the sum of the SES amplitudes at the first five harmonics of its rate
// (seed Sec. 4.3). Used by the envelope stage (raw and reconstructed signals) and by the
// dominant-path stage's `indicator` criterion. Configure once per shape; Process allocates
// nothing.
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

class EnvelopeAnalysis {
 public:
  static Result<EnvelopeAnalysis> Create(const MachineContext& machine, std::size_t n);

  // Fills `band`, and per shaft `indicator[s]` and `harmonics[s]` (amplitudes at 1x..5x of
  // shaft s's rate at `speed_hz`). noexcept, allocation-free.
  void Process(std::span<const double> signal, double speed_hz, BlockEnvelopeBand& band,
               std::span<double> indicator,
               std::span<std::array<double, kIndicatorHarmonics>> harmonics) noexcept;

 private:
  EnvelopeAnalysis() = default;
  const MachineContext* machine_ = nullptr;
  double bin_hz_ = 0.0;
  std::optional<Kurtogram> kurtogram_;
  std::optional<BandPass> band_pass_;
  std::optional<EnvelopeSpectrum> ses_;
  std::vector<double> filtered_;  // n
  std::vector<double> ses_buf_;   // bins
};

}  // namespace gearpath

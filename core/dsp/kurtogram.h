// Fast kurtogram: the spectral-kurtosis band selection of Algorithm 2 step 5 (seed Sect. 4.3),
// after J. Antoni, "Fast computation of the kurtogram for the detection of transient faults",
// Mech. Syst. Signal Process. 21 (2007) 108-124.
//
// What it computes. The 1/3-binary tree of Antoni: levels 0, 1, 1.6, 2, 2.6, ..., depth. A
// binary level k splits [0, fs/2] into 2^k equal bands; the ternary level "k.6" (k >= 1, the
// .6 standing for log2 3 - 1 = 0.585) into 3 * 2^(k-1). Nodes are integers (level k, ternary
// flag, band index): no floating level arithmetic. In every band it takes the complex envelope
// c(t) of the block restricted to that band and its spectral kurtosis
//     SK = <|c|^4> / <|c|^2>^2 - 2,
// which is 0 for a Gaussian envelope, -1 for a pure tone and large for sparse transients. The
// band of largest SK is returned with the whole map (rows x bands) for plots.
//
// How (a documented deviation from Antoni's FIR tree, same band partition): a frequency-domain
// filter bank. One real FFT of the block; the positive-frequency bins 1..floor(N/2) are split
// exactly into the bands of each row (bin k belongs to band floor(2 L k / N), integer maths,
// the Nyquist bin to the last band); the DC bin is dropped (the mean carries no transient).
// Each band's bins are moved to baseband and inverse-transformed with a zero-padded FFT of at
// least twice the band's bin count, so <|c|^2> and <|c|^4> are the exact moments of the
// band-limited periodic envelope (|c|^2 has twice c's bandwidth). Brick-wall bands have no
// overlap or gap, unlike the quasi-analytic FIRs, at the price of circular sinc ringing in time;
// a linear filter keeps Gaussian noise Gaussian, so the SK = 0 reference is unbiased. Plans
// and buffers are made at configuration; Process allocates nothing.
//
// The block edges. An FFT treats the block as periodic; a tone that is not periodic in the
// block jumps at the wrap point, and that single jump is a broadband transient with enormous SK
// in every band away from the tone. So the block is tapered by a Tukey window (cosine tapers
// on options.taper_fraction of it, half at each end) and each SK is corrected for the taper:
// a Gaussian (or constant) envelope times a slow window w has <|c|^4>/<|c|^2>^2 multiplied by
// r = <w^4>/<w^2>^2, so SK = (SK_tapered + 2) / r - 2, exact for Gaussian noise (0) and for a
// tone (-1) when the band is wide compared with 1/(taper duration).
//
// Known traps (DESIGN.md) and what this does about them:
// - Mesh tones drive SK negative and hide a transient band: optional pre-whitening by linear
//   prediction (autoregressive, as Sawalhi & Randall use before the kurtogram): an AR model of
//   options.ar_order fitted to the block (biased autocorrelation, Levinson-Durbin, so the
//   predictor is stable) and the block replaced by its prediction error. Tones are predictable
//   and vanish; transients are not and stay. Within a narrow band the whitening filter is
//   nearly a constant gain, which SK ignores, so the transient band keeps its SK. The order
//   must exceed twice the number of strong tones (each tone takes a pole pair). The first
//   ar_order samples (no full history) are set to zero. Phase-only (cepstral) pre-whitening
//   was tried and rejected: it raises the leakage skirts of strong tones to the level of
//   everything else, and their coherent phase turns the block edges into a transient.
// - No impulsive content: every band scores about 0 and the argmax is arbitrary. The result
//   carries sigma = 2 / sqrt(n), the standard deviation of the SK estimate of a circular
//   Gaussian envelope from n independent samples (delta method: Var|c|^2 = 1, Var|c|^4 = 20,
//   Cov = 4 for unit power, giving (20 + 16 - 32)/n = 4/n); n is the band's bin count, the
//   number of independent envelope samples in the block (the taper makes the true spread a few
//   per cent larger: 1/r of the samples carry the weight). `significant` = SK > k sigma
//   (options.significance_sigmas, default 5: the maximum is taken over up to a few hundred
//   correlated cells, so 3 sigma would fire on noise).
// - The envelope band must hold the modulation it is meant to show: options.min_bandwidth_hz
//   (set it to 2 x the highest modulation frequency sought, e.g. 10 x the shaft rate for five
//   harmonics) removes every row whose bands are narrower; rows also stop when a band would
//   hold fewer than kMinBinsPerBand bins.
#pragma once

#include <complex>
#include <cstddef>
#include <span>
#include <utility>
#include <vector>

#include "core/common/result.h"
#include "core/dsp/fft_plan.h"

namespace gearpath {

enum class KurtogramWhitening {
  kNone,            // SK of the block as it is
  kAutoregressive,  // SK of the AR prediction error (removes discrete tones)
};

struct KurtogramOptions {
  int depth = 6;                  // deepest binary level, 0..12 (rows 0, 1, 1.6, ..., depth)
  double min_bandwidth_hz = 0.0;  // narrowest band allowed; caps the depth
  KurtogramWhitening whitening = KurtogramWhitening::kAutoregressive;
  int ar_order = 64;                 // AR whitening order, 1..block_length/4
  double taper_fraction = 0.1;       // Tukey taper share of the block, [0, 1]
  double significance_sigmas = 5.0;  // SK must exceed this many sigma to be `significant`
  bool operator==(const KurtogramOptions&) const = default;
};

// A node of the 1/3-binary tree: binary level k has 2^k bands, ternary level k.6 (k >= 1) has
// 3 * 2^(k-1). index counts bands from 0 Hz.
struct KurtogramNode {
  int level = 0;
  bool ternary = false;
  int index = 0;

  int BandCount() const noexcept { return ternary ? 3 << (level - 1) : 1 << level; }
  // Antoni's plotting level: k, or k + log2(3) - 1 for ternary rows. For display only.
  double DisplayLevel() const noexcept;
};

struct KurtogramBand {
  KurtogramNode node;
  double low_hz = 0.0;
  double high_hz = 0.0;
  double centre_hz = 0.0;
  double bandwidth_hz = 0.0;
  double kurtosis = 0.0;  // spectral kurtosis of the band's complex envelope (0 = Gaussian)
  double sigma = 0.0;     // standard deviation of that estimate for Gaussian noise, 2/sqrt(n)
  bool significant = false;
};

class Kurtogram {
 public:
  static constexpr std::size_t kMinBinsPerBand = 8;

  // Configures for real blocks of `block_length` samples at `sample_rate_hz`. Errors name the
  // offending option (depth out of range, bandwidth above fs/2, block too short).
  static Result<Kurtogram> Create(std::size_t block_length, double sample_rate_hz,
                                  const KurtogramOptions& options = {});

  // Computes the kurtogram of one block and returns its best band. Rejects a block of the
  // wrong length or with non-finite samples. A silent block scores 0 everywhere.
  Result<KurtogramBand> Process(std::span<const double> block) noexcept;

  // The map of the last processed block, rows in tree order 0, 1, 1.6, 2, ... (row_node(r)
  // says which); row r has row_node(r).BandCount() values, band 0 (lowest frequency) first.
  std::size_t row_count() const noexcept { return rows_.size(); }
  KurtogramNode row_node(std::size_t row) const noexcept { return rows_[row].node; }
  double row_bandwidth_hz(std::size_t row) const noexcept;
  std::span<const double> map_row(std::size_t row) const noexcept;
  // The band of a given node (frequencies, sigma); kurtosis from the last block.
  KurtogramBand Band(const KurtogramNode& node) const noexcept;

  std::size_t block_length() const noexcept { return block_length_; }
  double sample_rate_hz() const noexcept { return sample_rate_hz_; }
  const KurtogramOptions& options() const noexcept { return options_; }

 private:
  struct Row {
    KurtogramNode node;    // index unused
    std::size_t plan = 0;  // index into envelope_plans_
  };

  explicit Kurtogram(FftPlan forward) : forward_(std::move(forward)) {}
  std::size_t BandFirstBin(int bands, int index) const noexcept;
  double BandKurtosis(std::size_t plan_index, std::size_t first_bin,
                      std::size_t end_bin) noexcept;

  void Whiten() noexcept;  // AR prediction error of forward_.real_in(), in place

  FftPlan forward_;
  std::vector<FftPlan> envelope_plans_;
  std::vector<std::size_t> plan_written_;  // per plan: leading inputs that may be non-zero
  std::vector<double> taper_;    // Tukey window, block_length
  double taper_ratio_ = 1.0;     // <w^4> / <w^2>^2
  std::vector<double> ar_work_;  // autocorrelation, coefficients, Levinson scratch
  std::vector<double> history_;  // whitening input copy, then reversed: 2 block_length
  std::vector<Row> rows_;
  std::vector<double> map_;  // rows x max_bands_, NaN where a row has fewer bands
  std::size_t max_bands_ = 0;
  std::size_t block_length_ = 0;
  double sample_rate_hz_ = 0.0;
  KurtogramOptions options_;
};

}  // namespace gearpath

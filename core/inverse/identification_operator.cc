#include "core/inverse/identification_operator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <utility>

#include "core/inverse/condition_number.h"
#include "core/inverse/least_squares.h"
#include "core/inverse/parallel_ranges.h"
#include "core/inverse/small_svd.h"
#include "core/inverse/validation.h"
#include "core/common/simd_clones.h"

namespace gearpath {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// A bin costs tens of microseconds, a thread start about as much as one bin: below this many
// bins per thread the split is not worth it (and small test sets stay single-threaded).
constexpr std::size_t kMinBinsPerThread = 32;

// Eq. 40 with the zero-column convention of the header (weight 0: force unobservable);
// a = H^H H.
Eigen::VectorXd WeightsOrZero(const Eigen::MatrixXcd& a) {
  Eigen::VectorXd w(a.rows());
  for (Eigen::Index i = 0; i < a.rows(); ++i) {
    const double norm = a.row(i).norm();
    w(i) = norm > 0.0 ? 1.0 / norm : 0.0;
  }
  return w;
}

// F = G x over one chunk of the layout (identification_operator.h): per path, the channels'
// contributions summed over the chunk's bins, which the compiler vectorises. Built for the
// baseline and, where the CPU has them, AVX2 and AVX-512 (simd_clones.h).
GEARPATH_SIMD_CLONES
void ApplyChunk(const double* __restrict g, std::size_t paths, std::size_t channels,
                const double* __restrict x_re, const double* __restrict x_im,
                double* __restrict f_re, double* __restrict f_im) noexcept {
  constexpr std::size_t kBins = IdentificationOperator::kChunkBins;
  for (std::size_t p = 0; p < paths; ++p) {
    double re[kBins] = {};
    double im[kBins] = {};
    for (std::size_t c = 0; c < channels; ++c) {
      const double* gr = g + (p * channels + c) * 2 * kBins;
      const double* gi = gr + kBins;
      const double* xr = x_re + c * kBins;
      const double* xi = x_im + c * kBins;
      for (std::size_t j = 0; j < kBins; ++j) {
        re[j] += gr[j] * xr[j] - gi[j] * xi[j];
        im[j] += gr[j] * xi[j] + gi[j] * xr[j];
      }
    }
    std::copy_n(re, kBins, f_re + p * kBins);
    std::copy_n(im, kBins, f_im + p * kBins);
  }
}

std::string BinName(const FrfMatrix& frf, Eigen::Index k) {
  return "frf.at[" + std::to_string(k) + "] (" + FormatNumber(frf.frequency_hz(k)) + " Hz)";
}

}  // namespace

std::string_view ToString(IdentifyStatus status) noexcept {
  switch (status) {
    case IdentifyStatus::kOk:
      return "ok";
    case IdentifyStatus::kBinOutOfRange:
      return "bin index out of range";
    case IdentifyStatus::kShapeMismatch:
      return "response or force length does not match the FRF matrix";
    case IdentifyStatus::kNonFiniteResponse:
      return "response contains a non-finite value";
  }
  return "unknown";
}

Status ValidateIdentificationOptions(const IdentificationOptions& options) {
  if (options.method == InverseMethod::kLeastSquares) {
    if (!std::isfinite(options.rank_tolerance) || options.rank_tolerance >= 1.0) {
      return Error{"rank_tolerance: must be finite and < 1 (<= 0 selects max(m, n) * eps), got " +
                   FormatNumber(options.rank_tolerance)};
    }
    return Status::Ok();
  }
  if (options.method == InverseMethod::kMwi && options.iterations < 1) {
    return Error{"iterations: MWI needs K >= 1 iterations, got " +
                 std::to_string(options.iterations)};
  }
  const RegularisationSettings& r = options.regularisation;
  const std::string parameter_name = options.method == InverseMethod::kMwi ? "alpha" : "lambda";
  switch (r.rule) {
    case RegularisationRule::kFixed:
      if (!std::isfinite(r.parameter) || !(r.parameter > 0.0)) {
        return Error{parameter_name + ": the fixed regularisation parameter must be finite and "
                     "> 0, got " + FormatNumber(r.parameter)};
      }
      break;
    case RegularisationRule::kNoiseFloor:
    case RegularisationRule::kGcv:
      if (!std::isfinite(r.relative_noise) || !(r.relative_noise > 0.0) ||
          !(r.relative_noise < 1.0)) {
        return Error{"relative_noise: eta must lie in (0, 1), got " +
                     FormatNumber(r.relative_noise)};
      }
      break;
    case RegularisationRule::kDiscrepancy:
      if (!std::isfinite(r.noise_rms) || !(r.noise_rms > 0.0)) {
        return Error{"noise_rms: the discrepancy principle needs the noise RMS, finite and > 0, "
                     "got " + FormatNumber(r.noise_rms)};
      }
      if (!std::isfinite(r.discrepancy_factor) || !(r.discrepancy_factor >= 1.0)) {
        return Error{"discrepancy_factor: tau must be finite and >= 1, got " +
                     FormatNumber(r.discrepancy_factor)};
      }
      break;
  }
  return Status::Ok();
}

Result<IdentificationOperator> IdentificationOperator::Create(
    const FrfMatrix& frf, const IdentificationOptions& options, unsigned threads) {
  if (Status s = ValidateIdentificationOptions(options); !s) return Error{s.error()};
  if (frf.at.empty()) return Error{"frf: FRF matrix has no frequency bins"};
  if (frf.frequency_hz.size() != static_cast<Eigen::Index>(frf.at.size())) {
    return Error{"frf: " + std::to_string(frf.frequency_hz.size()) + " frequencies but " +
                 std::to_string(frf.at.size()) + " matrices"};
  }
  const Eigen::Index m = frf.at.front().rows();
  const Eigen::Index n = frf.at.front().cols();
  // Every bin is checked before any is decomposed, so the error names the first bad bin.
  for (Eigen::Index k = 0; k < frf.bins(); ++k) {
    const Eigen::MatrixXcd& h = frf.at[static_cast<std::size_t>(k)];
    // The bin's name is formatted only for the message (8001 names would cost milliseconds).
    if (h.size() == 0 || !h.allFinite()) {
      if (Status s = ValidateOperator(h, BinName(frf, k)); !s) return Error{s.error()};
    }
    if (h.rows() != m || h.cols() != n) {
      return Error{BinName(frf, k) + ": shape " + std::to_string(h.rows()) + " x " +
                   std::to_string(h.cols()) + " differs from the first bin's " +
                   std::to_string(m) + " x " + std::to_string(n)};
    }
  }
  IdentificationOperator op;
  op.options_ = options;
  op.channels_ = m;
  op.paths_ = n;
  const RegularisationRule rule = options.regularisation.rule;
  op.precomputed_ = options.method == InverseMethod::kLeastSquares ||
                    rule == RegularisationRule::kFixed || rule == RegularisationRule::kNoiseFloor;
  const std::size_t count = frf.at.size();
  auto bins = std::make_shared<std::vector<Bin>>(count);
  auto layout = std::make_shared<Layout>();
  const std::size_t chunks = (count + kChunkBins - 1) / kChunkBins;
  const auto paths = static_cast<std::size_t>(n);
  const auto channels = static_cast<std::size_t>(m);
  const std::size_t chunk_size = paths * channels * 2 * kChunkBins;
  layout->g.assign(chunks * chunk_size, 0.0);
  layout->outside = m > std::min(m, n);
  std::vector<BinOperator> residual_rows(count);
  // Each bin depends on its own H only and writes only its own slots of the layout, so the
  // split over threads cannot change any result.
  ForEachRangeInParallel(
      count, ThreadsForRanges(count, kMinBinsPerThread, threads),
      [&](std::size_t begin, std::size_t end) {
        for (std::size_t k = begin; k < end; ++k) {
          BinOperator& bo = residual_rows[k];
          (*bins)[k] = BuildBin(frf.at[k], options, op.precomputed_, &bo);
          if (!(*bins)[k].has_g) continue;
          double* g = layout->g.data() + (k / kChunkBins) * chunk_size + k % kChunkBins;
          for (std::size_t p = 0; p < paths; ++p) {
            for (std::size_t c = 0; c < channels; ++c) {
              const Complex v = bo.g(static_cast<Eigen::Index>(p), static_cast<Eigen::Index>(c));
              double* at = g + (p * channels + c) * 2 * kChunkBins;
              at[0] = v.real();
              at[kChunkBins] = v.imag();
            }
          }
          bo.g.resize(0, 0);
        }
      });
  // The residual rows, bin after bin.
  std::size_t rows = 0;
  for (const BinOperator& bo : residual_rows) rows += static_cast<std::size_t>(bo.rows.rows());
  const std::size_t row_size = 1 + 2 * channels;
  layout->rows.reserve(rows * row_size);
  layout->row_begin.reserve(count + 1);
  layout->row_begin.push_back(0);
  for (BinOperator& bo : residual_rows) {
    for (Eigen::Index i = 0; i < bo.rows.rows(); ++i) {
      layout->rows.push_back(bo.damping(i));
      for (Eigen::Index c = 0; c < m; ++c) {
        layout->rows.push_back(bo.rows(i, c).real());
        layout->rows.push_back(bo.rows(i, c).imag());
      }
    }
    layout->row_begin.push_back(static_cast<std::uint32_t>(layout->rows.size() / row_size));
    bo = BinOperator{};
  }
  op.bins_ = std::move(bins);
  op.layout_ = std::move(layout);
  const Eigen::Index r = std::min(m, n);
  op.beta_.resize(r);
  op.beta2_.resize(r);
  op.coefficients_.resize(r);
  op.channel_work_.resize(m);
  op.path_work_.resize(n);
  return op;
}

IdentificationOperator::Bin IdentificationOperator::BuildBin(
    const Eigen::MatrixXcd& h, const IdentificationOptions& options, bool precomputed,
    BinOperator* op) {
  const Eigen::Index m = h.rows();
  const Eigen::Index n = h.cols();
  const RegularisationRule rule = options.regularisation.rule;
  const bool mwi = options.method == InverseMethod::kMwi;
  Bin bin;
  if (mwi) {
    // MWI inverts B = H W^{1/2}; H^H H, formed for the weights, also starts B's SVD.
    const Eigen::MatrixXcd gram = GramMatrix(h);
    bin.svd = DecomposeScaled(h, WeightsOrZero(gram).cwiseSqrt(), &gram);
  } else {
    // Tikhonov and least squares invert H itself.
    bin.svd = DecomposeScaled(h, Eigen::VectorXd::Ones(n));
  }
  bin.condition_weighted = ConditionFromSingularValues(bin.svd.sigma);
  const double sigma_max = bin.svd.sigma.size() > 0 ? bin.svd.sigma(0) : 0.0;
  const double cutoff = options.method == InverseMethod::kLeastSquares
                            ? LeastSquaresCutoff(sigma_max, m, n, options.rank_tolerance)
                            : DefaultRankCutoff(sigma_max, m, n);
  bin.rank = (bin.svd.sigma.array() > cutoff).count();
  if (!(sigma_max > 0.0)) {
    bin.outcome = RuleOutcome::kZeroOperator;
    bin.parameter = options.method == InverseMethod::kLeastSquares ? 0.0 : kInfinity;
  } else if (options.method == InverseMethod::kLeastSquares) {
    bin.outcome = RuleOutcome::kNoParameter;
  } else if (rule == RegularisationRule::kFixed) {
    bin.parameter = options.regularisation.parameter;
  } else if (rule == RegularisationRule::kNoiseFloor ||
             (rule == RegularisationRule::kGcv && m <= bin.rank)) {
    bin.parameter = NoiseFloorParameter(options.method, sigma_max,
                                        options.regularisation.relative_noise,
                                        options.iterations);
    if (rule == RegularisationRule::kGcv) bin.outcome = RuleOutcome::kGcvFellBackToNoiseFloor;
  }
  if (precomputed || bin.outcome == RuleOutcome::kGcvFellBackToNoiseFloor) {
    // G = D V diag(phi / sigma) U^H; the residual rows: u_i^H where 1 - phi_i is not
    // negligible (every one when rows > r, for ||x||^2 - ||U^H x||^2).
    const Eigen::Index r = bin.svd.sigma.size();
    const bool outside = m > r;
    Eigen::VectorXd gain(r);
    Eigen::VectorXd damping(r);
    Eigen::Index kept = 0;
    for (Eigen::Index i = 0; i < r; ++i) {
      const double s = bin.svd.sigma(i);
      const double phi = FilterFactor(options.method, s, bin.parameter, options.iterations,
                                      cutoff);
      gain(i) = phi > 0.0 ? phi / s : 0.0;
      damping(i) = 1.0 - phi;
      if (outside || damping(i) > kResidualDamping) ++kept;
    }
    op->g = bin.svd.column_scale.asDiagonal() * bin.svd.v * gain.asDiagonal() *
            bin.svd.u.adjoint();
    op->damping.resize(kept);
    op->rows.resize(kept, m);
    for (Eigen::Index i = 0, j = 0; i < r; ++i) {
      if (!(outside || damping(i) > kResidualDamping)) continue;
      op->damping(j) = damping(i);
      op->rows.row(j++) = bin.svd.u.col(i).adjoint();
    }
    bin.has_g = true;
    // Identify uses G alone from here on; U and V would only hold memory (2 x 2.3 kB per
    // 12 x 12 bin). sigma stays for the figures.
    bin.svd.u.resize(0, 0);
    bin.svd.v.resize(0, 0);
  }
  return bin;
}

BinFigures IdentificationOperator::StaticFigures(Eigen::Index bin) const {
  const Bin& b = bins_->at(static_cast<std::size_t>(bin));
  BinFigures f;
  f.parameter = b.parameter;
  f.condition_weighted = b.condition_weighted;
  f.rank = b.rank;
  f.outcome = b.outcome;
  return f;
}

double IdentificationOperator::ChooseParameter(const Bin& bin, double outside2,
                                               RuleOutcome* outcome) noexcept {
  const RegularisationSettings& r = options_.regularisation;
  if (r.rule == RegularisationRule::kGcv) {
    *outcome = RuleOutcome::kAsConfigured;
    return GcvParameter(options_.method, bin.svd.sigma, beta2_, outside2, channels_,
                        options_.iterations);
  }
  const double target = r.discrepancy_factor * r.noise_rms;
  const ParameterChoice choice =
      DiscrepancyParameter(options_.method, bin.svd.sigma, beta2_, outside2,
                           target * target * static_cast<double>(channels_),
                           options_.iterations);
  *outcome = choice.outcome;
  return choice.parameter;
}

IdentifyStatus IdentificationOperator::Identify(Eigen::Index bin,
                                                const Eigen::Ref<const Eigen::VectorXcd>& x,
                                                Eigen::Ref<Eigen::VectorXcd> forces,
                                                BinFigures* figures) noexcept {
  if (bin < 0 || bin >= bins()) return IdentifyStatus::kBinOutOfRange;
  if (x.size() != channels_ || forces.size() != paths_) return IdentifyStatus::kShapeMismatch;
  if (!x.allFinite()) return IdentifyStatus::kNonFiniteResponse;
  const Bin& b = (*bins_)[static_cast<std::size_t>(bin)];
  double parameter = b.parameter;
  RuleOutcome outcome = b.outcome;
  double residual2 = 0.0;
  // x as split planes with stride 2 (a complex is re, im).
  const auto* x_re = reinterpret_cast<const double*>(x.data());
  if (b.has_g) {
    const auto k = static_cast<std::size_t>(bin);
    const auto channels = static_cast<std::size_t>(channels_);
    const double* g = layout_->g.data() +
                      (k / kChunkBins) * static_cast<std::size_t>(paths_) * channels * 2 *
                          kChunkBins +
                      k % kChunkBins;
    for (Eigen::Index p = 0; p < paths_; ++p) {
      Complex sum(0.0, 0.0);
      for (std::size_t c = 0; c < channels; ++c) {
        const double* at = g + (static_cast<std::size_t>(p) * channels + c) * 2 * kChunkBins;
        sum += Complex(at[0], at[kChunkBins]) * x(static_cast<Eigen::Index>(c));
      }
      forces(p) = sum;
    }
    if (figures != nullptr) residual2 = Residual2(bin, x_re, x_re + 1, 2);
  } else if (outcome == RuleOutcome::kZeroOperator) {
    forces.setZero();
    residual2 = x.squaredNorm();
  } else {
    beta_.noalias() = b.svd.u.adjoint() * x;
    channel_work_ = x;
    channel_work_.noalias() -= b.svd.u * beta_;
    const double outside2 = channel_work_.squaredNorm();
    beta2_ = beta_.cwiseAbs2();
    parameter = ChooseParameter(b, outside2, &outcome);
    for (Eigen::Index i = 0; i < beta_.size(); ++i) {
      const double s = b.svd.sigma(i);
      const double phi = FilterFactor(options_.method, s, parameter, options_.iterations, 0.0);
      coefficients_(i) = phi > 0.0 ? beta_(i) * (phi / s) : Complex(0.0, 0.0);
    }
    path_work_.noalias() = b.svd.v * coefficients_;
    for (Eigen::Index j = 0; j < paths_; ++j) forces(j) = b.svd.column_scale(j) * path_work_(j);
    residual2 = ResidualNorm2(options_.method, b.svd.sigma, beta2_, outside2, parameter,
                              options_.iterations);
  }
  if (figures != nullptr) {
    figures->parameter = parameter;
    figures->condition_weighted = b.condition_weighted;
    figures->rank = b.rank;
    figures->outcome = outcome;
    const double x_norm = x.norm();
    figures->relative_residual = x_norm > 0.0 ? std::sqrt(residual2) / x_norm : 0.0;
  }
  return IdentifyStatus::kOk;
}

std::size_t IdentificationOperator::chunks() const noexcept {
  return bins_ ? (bins_->size() + kChunkBins - 1) / kChunkBins : 0;
}

bool IdentificationOperator::has_operator(Eigen::Index bin) const noexcept {
  return bin >= 0 && bin < bins() && (*bins_)[static_cast<std::size_t>(bin)].has_g;
}

void IdentificationOperator::ForcesOfChunk(std::size_t chunk, const double* x_re,
                                           const double* x_im, double* f_re,
                                           double* f_im) const noexcept {
  const auto paths = static_cast<std::size_t>(paths_);
  const auto channels = static_cast<std::size_t>(channels_);
  ApplyChunk(layout_->g.data() + chunk * paths * channels * 2 * kChunkBins, paths, channels,
             x_re, x_im, f_re, f_im);
}

double IdentificationOperator::Residual2(Eigen::Index bin, const double* x_re,
                                         const double* x_im, std::size_t stride) noexcept {
  const Layout& l = *layout_;
  const auto channels = static_cast<std::size_t>(channels_);
  const std::size_t row_size = 1 + 2 * channels;
  const auto k = static_cast<std::size_t>(bin);
  // With more channels than singular values, e = x - U U^H x, the part of x no force explains,
  // accumulated as x minus each row's projection (as a vector, not ||x||^2 - ||U^H x||^2,
  // which would cancel down to sqrt(eps) when x lies nearly in the range of H).
  const bool outside = l.outside;
  Complex* e = channel_work_.data();  // this copy's workspace, channels long
  if (outside) {
    for (std::size_t c = 0; c < channels; ++c) e[c] = Complex(x_re[c * stride], x_im[c * stride]);
  }
  double sum = 0.0;
  for (std::size_t r = l.row_begin[k]; r < l.row_begin[k + 1]; ++r) {
    const double* row = l.rows.data() + r * row_size;
    double re = 0.0;
    double im = 0.0;
    for (std::size_t c = 0; c < channels; ++c) {
      const double ur = row[1 + 2 * c];
      const double ui = row[2 + 2 * c];
      const double xr = x_re[c * stride];
      const double xi = x_im[c * stride];
      re += ur * xr - ui * xi;
      im += ur * xi + ui * xr;
    }
    sum += row[0] * row[0] * (re * re + im * im);
    if (outside) {
      // e -= beta u, with u = conj(row): (re + i im)(ur - i ui).
      for (std::size_t c = 0; c < channels; ++c) {
        const double ur = row[1 + 2 * c];
        const double ui = row[2 + 2 * c];
        e[c] -= Complex(re * ur + im * ui, im * ur - re * ui);
      }
    }
  }
  if (outside) {
    for (std::size_t c = 0; c < channels; ++c) sum += std::norm(e[c]);
  }
  return sum;
}

IdentifyStatus IdentificationOperator::IdentifyAll(const Eigen::Ref<const Eigen::MatrixXcd>& x,
                                                   Eigen::Ref<Eigen::MatrixXcd> forces,
                                                   std::span<BinFigures> figures) noexcept {
  if (x.rows() != channels_ || x.cols() != bins() || forces.rows() != paths_ ||
      forces.cols() != bins() ||
      (!figures.empty() && static_cast<Eigen::Index>(figures.size()) != bins())) {
    return IdentifyStatus::kShapeMismatch;
  }
  for (Eigen::Index k = 0; k < bins(); ++k) {
    const IdentifyStatus s = Identify(k, x.col(k), forces.col(k),
                                      figures.empty() ? nullptr : &figures[static_cast<std::size_t>(k)]);
    if (s != IdentifyStatus::kOk) return s;
  }
  return IdentifyStatus::kOk;
}

}  // namespace gearpath

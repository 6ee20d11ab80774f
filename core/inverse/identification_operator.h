// IdentificationOperator: bearing-force identification for every bin of one FRF matrix, with
// everything that depends only on the FRFs computed once (configure) and a per-block step
// that allocates nothing (process).
//
// Per bin k the model is x = H_k F (seed Sect. 2.3; x: channel responses, F: one force per
// transfer path, H_k the decoupled FRF matrix, channels x paths, any shape). Configure, per
// bin: the MWI weights W (Eq. 40), the thin SVD of the inverted operator B = H W^{1/2} (MWI)
// or H (Tikhonov, least squares; this SVD also gives the condition number of H), the
// condition numbers (MWI: H's from H^H H, condition_number.h) and, when the parameter does not
// depend on x (rules kFixed and kNoiseFloor, and least squares), the complete operator
// G_k = D V diag(phi/sigma) U^H (paths x channels), so a block costs one mat-vec per bin.
// With kGcv or kDiscrepancy the parameter is chosen per block from U^H x (no allocation).
// Solver forms: spectral_filter.h; rules and why they are well posed: regularisation_rule.h.
//
// Layout (issue 9: the per-block pass at memory speed). The G_k of every bin sit in one
// contiguous array, kChunkBins bins at a time, real and imaginary parts split and the bins
// innermost: G[chunk][path][channel][re|im][bin of the chunk]. ForcesOfChunk() applies a chunk
// with loops the compiler vectorises across bins (no per-bin dynamic matrices, no temporaries).
// The residual needs no mat-vec with H: with B = H D = U diag(sigma) V^H and F = G x,
// x - H F = U diag(1 - phi) U^H x + (I - U U^H) x, two orthogonal parts, so
//   ||x - H F||^2 = sum_i (1 - phi_i)^2 |u_i^H x|^2 + ||x - U U^H x||^2,
// the second term only when there are more channels than singular values (r = min(m, n) < m;
// then every u_i is kept and x - U U^H x is formed as a vector, without the cancellation of
// ||x||^2 - ||U^H x||^2). Otherwise only the components whose 1 - phi_i exceeds
// kResidualDamping carry a row u_i^H (under noise-floor MWI a few per bin): the others add less
// than kResidualDamping^2 ||x||^2, below the rounding of ||x||^2. It is the residual of F = G x
// in exact arithmetic; the former x - H (G x) differed from it by the rounding of G x.
//
// MWI weight at a bin where a column of H is zero (e.g. accelerance at 0 Hz): the path has no
// effect there, its force is unobservable and is set to 0 (weight 0), instead of W = 1/0.
//
// Thread safety: Identify uses a workspace owned by the operator; one operator per thread.
// A copy shares the per-bin factorisations (read-only once built) and gets its own workspace,
// so machines on one FRF set hold the operators once and each identifies on its own copy.
#pragma once

#include <Eigen/Dense>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <span>
#include <string_view>
#include <vector>

#include "core/common/frf_matrix.h"
#include "core/common/result.h"
#include "core/inverse/regularisation_rule.h"
#include "core/inverse/spectral_filter.h"

namespace gearpath {

struct IdentificationOptions {
  InverseMethod method = InverseMethod::kMwi;
  RegularisationSettings regularisation;  // ignored by least squares
  int iterations = 10;                    // MWI K >= 1
  double rank_tolerance = 0.0;            // least squares: <= 0 default, else relative cutoff
};

// Checks every option the chosen method and rule use; messages name the option.
Status ValidateIdentificationOptions(const IdentificationOptions& options);

struct BinFigures {
  double parameter = 0.0;             // alpha (MWI) or lambda (Tikhonov) used; 0 for LS,
                                      // +infinity where the forces were set to 0
  // sigma_max / sigma_min (+inf if singular) of the operator inverted: H W^{1/2} for MWI, H
  // otherwise. H's own is not computed (nothing on the processing path read it, and for MWI it
  // took one more eigen-decomposition per bin, a fifth of the precompute).
  double condition_weighted = 0.0;
  double relative_residual = 0.0;     // ||x - H F|| / ||x|| (0 for x = 0)
  Eigen::Index rank = 0;              // numerical rank of the inverted operator
  RuleOutcome outcome = RuleOutcome::kAsConfigured;
};

enum class IdentifyStatus { kOk, kBinOutOfRange, kShapeMismatch, kNonFiniteResponse };
std::string_view ToString(IdentifyStatus status) noexcept;

class IdentificationOperator {
 public:
  // Validates the FRF matrix (non-empty, one matrix per frequency, equal shapes, finite) and
  // the options; builds the per-bin factorisations, split over `threads` threads (0: one per
  // hardware thread; small sets use fewer). Every bin is built from its own H alone, so the
  // operator is bit-identical for any thread count.
  static Result<IdentificationOperator> Create(const FrfMatrix& frf,
                                               const IdentificationOptions& options,
                                               unsigned threads = 0);

  Eigen::Index bins() const noexcept {
    return bins_ ? static_cast<Eigen::Index>(bins_->size()) : 0;
  }
  Eigen::Index channels() const noexcept { return channels_; }
  Eigen::Index paths() const noexcept { return paths_; }
  const IdentificationOptions& options() const noexcept { return options_; }
  // True when the per-bin operators G_k are precomputed (parameter independent of x).
  bool precomputed() const noexcept { return precomputed_; }

  // Forces at one bin. forces must have paths() entries, x channels() entries. figures may be
  // null. noexcept, no heap allocation.
  IdentifyStatus Identify(Eigen::Index bin, const Eigen::Ref<const Eigen::VectorXcd>& x,
                          Eigen::Ref<Eigen::VectorXcd> forces,
                          BinFigures* figures = nullptr) noexcept;

  // All bins at once: x is channels x bins, forces paths x bins, figures empty or bins long.
  IdentifyStatus IdentifyAll(const Eigen::Ref<const Eigen::MatrixXcd>& x,
                             Eigen::Ref<Eigen::MatrixXcd> forces,
                             std::span<BinFigures> figures = {}) noexcept;

  // The figures of a bin that do not depend on x (parameter for precomputed rules).
  BinFigures StaticFigures(Eigen::Index bin) const;

  // --- The per-block pass over every bin (bins whose G_k is precomputed; all of them when
  // precomputed()). Bins go kChunkBins at a time; the chunk's responses and forces are split
  // into real and imaginary planes with the bins innermost: x_re[c * kChunkBins + j] is channel
  // c at bin chunk * kChunkBins + j, f_re[p * kChunkBins + j] path p's force there. The last
  // chunk's bins past bins() read zero and give zero force. noexcept, no allocation.
  static constexpr std::size_t kChunkBins = 16;
  // 1 - phi_i below which a component carries no residual row (see Layout).
  static constexpr double kResidualDamping = 1e-9;
  std::size_t chunks() const noexcept;
  // F = G x for one chunk (reads the shared operator only).
  void ForcesOfChunk(std::size_t chunk, const double* x_re, const double* x_im, double* f_re,
                     double* f_im) const noexcept;
  // ||x - H G x||^2 at one bin with a precomputed G (Layout), x read as x_re[c * stride].
  // Uses this copy's workspace (one thread per copy, as Identify).
  double Residual2(Eigen::Index bin, const double* x_re, const double* x_im,
                   std::size_t stride) noexcept;
  // True when bin's G is precomputed (always when precomputed(); with kGcv, where it fell back).
  bool has_operator(Eigen::Index bin) const noexcept;

 private:
  struct Bin {
    ScaledSvd svd;  // u and v are released where G is precomputed (Identify uses G alone)
    double parameter = 0.0;
    double condition_weighted = 0.0;
    Eigen::Index rank = 0;
    RuleOutcome outcome = RuleOutcome::kAsConfigured;
    bool has_g = false;  // G of this bin is in Layout::g
  };
  // What a bin's build hands to the layout (then dropped).
  struct BinOperator {
    Eigen::MatrixXcd g;         // paths x channels; empty when not precomputed
    Eigen::VectorXd damping;    // 1 - phi_i of the residual rows
    Eigen::MatrixXcd rows;      // their u_i^H, one per row (rows x channels)
  };
  // The contiguous per-block data (see Layout in the header comment).
  struct Layout {
    std::vector<double> g;  // chunks x paths x channels x 2 x kChunkBins
    // Residual rows of bin k: row_begin[k] .. row_begin[k + 1], each 1 + 2 channels doubles
    // (1 - phi_i, then u_i^H as re, im per channel).
    std::vector<std::uint32_t> row_begin;
    std::vector<double> rows;
    bool outside = false;  // channels > min(channels, paths): add ||x||^2 - ||U^H x||^2
  };

  IdentificationOperator() = default;
  // Everything Create computes for one bin: one SVD of the inverted operator. Depends on h and
  // the options only.
  static Bin BuildBin(const Eigen::MatrixXcd& h, const IdentificationOptions& options,
                      bool precomputed, BinOperator* op);
  double ChooseParameter(const Bin& bin, double outside2, RuleOutcome* outcome) noexcept;

  IdentificationOptions options_;
  Eigen::Index channels_ = 0;
  Eigen::Index paths_ = 0;
  bool precomputed_ = false;
  // Shared between copies, never written after Create (see Thread safety).
  std::shared_ptr<const std::vector<Bin>> bins_;
  std::shared_ptr<const Layout> layout_;
  // Per-block workspace, sized once; each copy has its own.
  Eigen::VectorXcd beta_;
  Eigen::VectorXd beta2_;
  Eigen::VectorXcd coefficients_;
  Eigen::VectorXcd channel_work_;
  Eigen::VectorXcd path_work_;
};

}  // namespace gearpath

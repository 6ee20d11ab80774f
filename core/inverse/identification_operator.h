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
// MWI weight at a bin where a column of H is zero (e.g. accelerance at 0 Hz): the path has no
// effect there, its force is unobservable and is set to 0 (weight 0), instead of W = 1/0.
//
// Thread safety: Identify uses a workspace owned by the operator; one operator per thread.
// A copy shares the per-bin factorisations (read-only once built) and gets its own workspace,
// so machines on one FRF set hold the operators once and each identifies on its own copy.
#pragma once

#include <Eigen/Dense>
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
  double condition_h = 0.0;           // sigma_max / sigma_min of H (+inf if singular)
  double condition_weighted = 0.0;    // the same for H W^{1/2} (MWI); = condition_h otherwise
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

 private:
  struct Bin {
    Eigen::MatrixXcd h;
    ScaledSvd svd;       // u and v are released where g is built (Identify uses g alone)
    Eigen::MatrixXcd g;  // paths x channels, only when precomputed_
    double parameter = 0.0;
    double condition_h = 0.0;
    double condition_weighted = 0.0;
    Eigen::Index rank = 0;
    RuleOutcome outcome = RuleOutcome::kAsConfigured;
  };

  IdentificationOperator() = default;
  // Everything Create computes for one bin: one SVD of the inverted operator and, for MWI,
  // H's condition number from H^H H. Depends on h and the options only.
  static Bin BuildBin(const Eigen::MatrixXcd& h, const IdentificationOptions& options,
                      bool precomputed);
  double ChooseParameter(const Bin& bin, double outside2, RuleOutcome* outcome) noexcept;

  IdentificationOptions options_;
  Eigen::Index channels_ = 0;
  Eigen::Index paths_ = 0;
  bool precomputed_ = false;
  // Shared between copies, never written after Create (see Thread safety).
  std::shared_ptr<const std::vector<Bin>> bins_;
  // Per-block workspace, sized once; each copy has its own.
  Eigen::VectorXcd beta_;
  Eigen::VectorXd beta2_;
  Eigen::VectorXcd coefficients_;
  Eigen::VectorXcd channel_work_;
  Eigen::VectorXcd path_work_;
};

}  // namespace gearpath

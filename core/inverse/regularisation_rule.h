// How the regularisation parameter (MWI alpha, Tikhonov lambda) is chosen per frequency bin.
//
// The seed picks alpha "by GCV or the L-curve" (Sect. 2.3, Algorithm 1, line 5). Per bin,
// GCV(p) = ||x - H F_p||^2 / (m - sum_i phi_i(p))^2 is exact through the SVD of the inverted
// operator (its trace term is sum phi_i for Tikhonov and MWI alike). But on a square or
// underdetermined bin (m <= rank) both numerator and denominator go to 0 as p -> 0: the
// minimiser is the unregularised solution or is undefined, whatever the noise. So GCV is only
// used where it is well posed, m > rank (the denominator stays >= m - rank > 0), and the
// other rules below are offered:
//
//  kNoiseFloor (default): filter the singular components that sit below the relative noise
//    level eta of the data: p = ParameterForCutoff(eta * sigma_1), i.e. phi = 1/2 exactly at
//    sigma = eta * sigma_1 (lambda = (eta sigma_1)^2 for Tikhonov; alpha = (eta sigma_1)^2 /
//    (2^{1/K} - 1) for MWI, equal for K = 1). Well posed on every shape: p is finite and > 0
//    whenever H != 0, does not depend on x, is scale-covariant in H, and bounds the gain of
//    the filtered inverse by about 1/(eta sigma_1). Because it depends only on H, the whole
//    per-bin operator is precomputed and a block costs one mat-vec per bin. Default
//    eta = 1e-3: an impact-hammer FRF is rarely better than 0.1 %, so components weaker than
//    that relative to the strongest are noise, not force.
//  kFixed: p given (> 0). Precomputed too.
//  kDiscrepancy (Morozov): p such that ||x - H F_p|| = tau * noise_rms * sqrt(m) (noise_rms is
//    the known per-channel noise RMS in the unit of x, tau >= 1). The residual grows
//    monotonically with p from the least-squares residual to ||x||, so a root exists and is
//    unique whenever LS residual < target < ||x|| (solved by bisection on log p, no
//    allocation). Outside that range the rule reports it: target >= ||x|| gives F = 0 (the
//    response is indistinguishable from noise); target <= LS residual gives the smallest
//    parameter of the search range (the data are more consistent than the noise claims).
//  kGcv: minimise GCV(p) over p (grid on log cutoff, then golden section) where m > rank;
//    elsewhere falls back to kNoiseFloor with the configured eta and reports that it did.
//
// Least squares has no parameter; the rule is ignored for it.
//
// The functions below work on one bin's spectrum for one response: sigma (descending), beta2
// = |u_i^H x|^2, and outside2 = ||x - U U^H x||^2 (the part of x no force can explain).
// They are noexcept and allocate nothing (per-block path).
#pragma once

#include <Eigen/Dense>
#include <string_view>

#include "core/inverse/spectral_filter.h"

namespace gearpath {

enum class RegularisationRule { kFixed, kNoiseFloor, kDiscrepancy, kGcv };

// What a rule did at one bin, reported per bin so that a fallback never goes unnoticed.
enum class RuleOutcome {
  kAsConfigured,
  kNoParameter,                          // least squares
  kGcvFellBackToNoiseFloor,              // m <= rank: GCV is degenerate there
  kDiscrepancyBelowLeastSquaresResidual, // target <= LS residual: smallest parameter used
  kDiscrepancyAboveResponse,             // target >= ||x||: F = 0
  kZeroOperator,                         // H = 0 at this bin (e.g. accelerance at 0 Hz): F = 0
};

std::string_view ToString(RegularisationRule rule) noexcept;
std::string_view ToString(RuleOutcome outcome) noexcept;

struct RegularisationSettings {
  RegularisationRule rule = RegularisationRule::kNoiseFloor;
  double parameter = 0.0;           // kFixed: alpha (MWI) or lambda (Tikhonov), finite, > 0
  double relative_noise = 1e-3;     // kNoiseFloor and the kGcv fallback: eta in (0, 1)
  double noise_rms = 0.0;           // kDiscrepancy: per-channel noise RMS (unit of x), > 0
  double discrepancy_factor = 1.0;  // kDiscrepancy: tau >= 1
};

// The parameter search range, as cutoff / sigma_1 (see ParameterForCutoff).
inline constexpr double kMinRelativeCutoff = 1e-12;
inline constexpr double kMaxRelativeCutoff = 1e3;

double NoiseFloorParameter(InverseMethod method, double sigma_max, double relative_noise,
                           int iterations) noexcept;

// ||x - H F_p||^2 = sum (1 - phi_i)^2 beta2_i + outside2.
double ResidualNorm2(InverseMethod method, const Eigen::Ref<const Eigen::VectorXd>& sigma,
                     const Eigen::Ref<const Eigen::VectorXd>& beta2, double outside2,
                     double parameter, int iterations) noexcept;

// GCV(p); +infinity where the denominator m - sum phi is not positive.
double GcvFunction(InverseMethod method, const Eigen::Ref<const Eigen::VectorXd>& sigma,
                   const Eigen::Ref<const Eigen::VectorXd>& beta2, double outside2,
                   Eigen::Index rows, double parameter, int iterations) noexcept;

// argmin of GCV over the search range. Meaningful only where rows > rank (see above).
double GcvParameter(InverseMethod method, const Eigen::Ref<const Eigen::VectorXd>& sigma,
                    const Eigen::Ref<const Eigen::VectorXd>& beta2, double outside2,
                    Eigen::Index rows, int iterations) noexcept;

struct ParameterChoice {
  double parameter = 0.0;  // +infinity means F = 0
  RuleOutcome outcome = RuleOutcome::kAsConfigured;
};

// Morozov's discrepancy principle: ||x - H F_p||^2 = target2.
ParameterChoice DiscrepancyParameter(InverseMethod method,
                                     const Eigen::Ref<const Eigen::VectorXd>& sigma,
                                     const Eigen::Ref<const Eigen::VectorXd>& beta2,
                                     double outside2, double target2, int iterations) noexcept;

}  // namespace gearpath

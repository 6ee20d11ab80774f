#include "core/inverse/identification_operator.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <complex>
#include <cstdlib>
#include <vector>

#include "core/inverse/least_squares.h"
#include "core/inverse/mwi.h"
#include "core/inverse/tikhonov.h"
#include "tests/core/inverse/random_system.h"

// Allocation counter for this test executable. What the per-block test must catch is above all
// Eigen heap storage (a temporary, a resize), and Eigen takes it from std::malloc, not from
// operator new (Eigen/src/Core/util/Memory.h, aligned_malloc), so counting operator new
// (tests/core/counting_operator_new.h) would not see it: the counter has to sit on malloc.
//
// Normal build: glibc's malloc is replaced by a forwarder to __libc_malloc that counts calls
// while armed. Eigen's dynamic storage and operator new both end in malloc, so a zero count
// proves the per-block path allocates nothing. Forwarding keeps free/realloc of glibc valid for
// these blocks.
//
// ASan/TSan build: the sanitizer owns malloc and free, so a replaced malloc would hand glibc
// memory to the sanitizer's free ("attempting free on address which was not malloc()-ed").
// There the count comes from the sanitizer allocator's own hook, which it runs after every
// allocation it serves (malloc, calloc, realloc, posix_memalign, every operator new): the same
// coverage, with no replacement. (Not EIGEN_RUNTIME_NO_MALLOC: it would have to be defined for
// the library's translation units too, and its check is an eigen_assert, gone under NDEBUG.)
#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define GEARPATH_TEST_SANITIZER_ALLOCATOR 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer)
#define GEARPATH_TEST_SANITIZER_ALLOCATOR 1
#endif
#endif

namespace {
std::atomic<bool> g_count_allocations{false};
std::atomic<long> g_allocations{0};
// Keeps a test allocation observable, so the compiler cannot drop the malloc/free pair.
void* volatile g_allocation_sink = nullptr;
}  // namespace

#ifdef GEARPATH_TEST_SANITIZER_ALLOCATOR
// From <sanitizer/allocator_interface.h> (compiler-rt; GCC does not ship that header, libasan
// and libtsan export the function).
extern "C" int __sanitizer_install_malloc_and_free_hooks(  // NOLINT
    void (*malloc_hook)(const volatile void*, std::size_t), void (*free_hook)(const volatile void*));
namespace {
void CountingMallocHook(const volatile void*, std::size_t) {
  if (g_count_allocations.load(std::memory_order_relaxed)) {
    g_allocations.fetch_add(1, std::memory_order_relaxed);
  }
}
void IgnoreFree(const volatile void*) {}
// Installs the hook once (before any counting; the sanitizer allows a few hook pairs).
bool InstallAllocationCounter() {
  static const bool installed =
      __sanitizer_install_malloc_and_free_hooks(CountingMallocHook, IgnoreFree) != 0;
  return installed;
}
}  // namespace
#else
extern "C" void* __libc_malloc(std::size_t size);  // NOLINT
extern "C" void* malloc(std::size_t size) {  // NOLINT
  if (g_count_allocations.load(std::memory_order_relaxed)) {
    g_allocations.fetch_add(1, std::memory_order_relaxed);
  }
  return __libc_malloc(size);
}
namespace {
bool InstallAllocationCounter() { return true; }
}  // namespace
#endif

namespace gearpath {
namespace {

using testing::RandomSystems;
using testing::RelativeError;

FrfMatrix RandomFrf(RandomSystems& rnd, Eigen::Index rows, Eigen::Index cols, int bins,
                    double condition) {
  FrfMatrix frf;
  frf.frequency_hz = Eigen::VectorXd::LinSpaced(bins, 10.0, 10.0 * bins);
  for (int k = 0; k < bins; ++k) frf.at.push_back(rnd.Conditioned(rows, cols, condition, 20.0));
  return frf;
}

IdentificationOptions Fixed(InverseMethod method, double parameter, int k = 10) {
  IdentificationOptions o;
  o.method = method;
  o.iterations = k;
  o.regularisation.rule = RegularisationRule::kFixed;
  o.regularisation.parameter = parameter;
  return o;
}

TEST(IdentificationOperator, EqualsTheSingleBinSolversForEveryMethodAndShape) {
  RandomSystems rnd(71);
  for (const auto& [rows, cols] : {std::pair{7, 3}, std::pair{4, 4}, std::pair{3, 5}}) {
    const FrfMatrix frf = RandomFrf(rnd, rows, cols, 5, 300.0);
    const Eigen::MatrixXcd x = rnd.Matrix(rows, 5);
    for (InverseMethod method :
         {InverseMethod::kMwi, InverseMethod::kTikhonov, InverseMethod::kLeastSquares}) {
      Result<IdentificationOperator> op = IdentificationOperator::Create(frf, Fixed(method, 1e-3, 7));
      ASSERT_TRUE(op.ok()) << op.error();
      EXPECT_TRUE(op->precomputed());
      Eigen::MatrixXcd forces(cols, 5);
      ASSERT_EQ(op->IdentifyAll(x, forces), IdentifyStatus::kOk);
      for (int k = 0; k < 5; ++k) {
        const Eigen::VectorXcd xk = x.col(k);
        Result<Eigen::VectorXcd> expected =
            method == InverseMethod::kMwi        ? SolveMwi(frf.at[k], xk, 1e-3, 7)
            : method == InverseMethod::kTikhonov ? SolveTikhonov(frf.at[k], xk, 1e-3)
                                                 : SolveLeastSquares(frf.at[k], xk);
        ASSERT_TRUE(expected.ok());
        EXPECT_LT(RelativeError(forces.col(k), *expected), 1e-12)
            << ToString(method) << " " << rows << "x" << cols << " bin " << k;
      }
    }
  }
}

TEST(IdentificationOperator, ChunkedPassGivesTheSingleBinForcesAndTheExplicitResidual) {
  // The per-block pass (ForcesOfChunk over kChunkBins bins at a time, Residual2 from the SVD
  // rows) against the textbook: forces of the single-bin solvers, and ||x - H F||^2 formed from
  // H itself. 37 bins: two full chunks and a partial one; more channels than paths, square,
  // fewer channels than paths.
  constexpr std::size_t kChunk = IdentificationOperator::kChunkBins;
  RandomSystems rnd(76);
  for (const auto& [rows, cols] : {std::pair{7, 3}, std::pair{4, 4}, std::pair{3, 5}}) {
    const int bins = 37;
    const FrfMatrix frf = RandomFrf(rnd, rows, cols, bins, 300.0);
    const Eigen::MatrixXcd x = rnd.Matrix(rows, bins);
    for (InverseMethod method : {InverseMethod::kMwi, InverseMethod::kTikhonov}) {
      Result<IdentificationOperator> op = IdentificationOperator::Create(frf, Fixed(method, 1e-3, 7));
      ASSERT_TRUE(op.ok()) << op.error();
      ASSERT_EQ(op->chunks(), 3u);
      const auto m = static_cast<std::size_t>(rows);
      const auto n = static_cast<std::size_t>(cols);
      std::vector<double> x_re(m * kChunk), x_im(m * kChunk), f_re(n * kChunk), f_im(n * kChunk);
      for (std::size_t chunk = 0; chunk < op->chunks(); ++chunk) {
        for (std::size_t c = 0; c < m; ++c) {
          for (std::size_t j = 0; j < kChunk; ++j) {
            const std::size_t k = chunk * kChunk + j;
            const std::complex<double> v =
                k < static_cast<std::size_t>(bins)
                    ? x(static_cast<Eigen::Index>(c), static_cast<Eigen::Index>(k))
                    : std::complex<double>{};
            x_re[c * kChunk + j] = v.real();
            x_im[c * kChunk + j] = v.imag();
          }
        }
        op->ForcesOfChunk(chunk, x_re.data(), x_im.data(), f_re.data(), f_im.data());
        for (std::size_t j = 0; j < kChunk; ++j) {
          const std::size_t k = chunk * kChunk + j;
          if (k >= static_cast<std::size_t>(bins)) {  // past the last bin: zero force
            for (std::size_t p = 0; p < n; ++p) {
              EXPECT_EQ(f_re[p * kChunk + j], 0.0);
              EXPECT_EQ(f_im[p * kChunk + j], 0.0);
            }
            continue;
          }
          const auto ki = static_cast<Eigen::Index>(k);
          const Eigen::VectorXcd xk = x.col(ki);
          Eigen::VectorXcd fk(cols);
          for (std::size_t p = 0; p < n; ++p) {
            fk(static_cast<Eigen::Index>(p)) = {f_re[p * kChunk + j], f_im[p * kChunk + j]};
          }
          Result<Eigen::VectorXcd> expected = method == InverseMethod::kMwi
                                                  ? SolveMwi(frf.at[k], xk, 1e-3, 7)
                                                  : SolveTikhonov(frf.at[k], xk, 1e-3);
          ASSERT_TRUE(expected.ok());
          EXPECT_LT(RelativeError(fk, *expected), 1e-12)
              << ToString(method) << " " << rows << "x" << cols << " bin " << k;
          const double explicit_residual = (xk - frf.at[k] * fk).norm();
          const double residual =
              std::sqrt(op->Residual2(ki, x_re.data() + j, x_im.data() + j, kChunk));
          EXPECT_NEAR(residual, explicit_residual, 1e-9 * xk.norm())
              << ToString(method) << " " << rows << "x" << cols << " bin " << k;
        }
      }
    }
  }
}

TEST(IdentificationOperator, RecoversKnownForcesNoiseFreeWithConvergedMwi) {
  RandomSystems rnd(72);
  const FrfMatrix frf = RandomFrf(rnd, 6, 3, 4, 100.0);
  Result<IdentificationOperator> op =
      IdentificationOperator::Create(frf, Fixed(InverseMethod::kMwi, 1e-6, 100000));
  ASSERT_TRUE(op.ok());
  for (int k = 0; k < 4; ++k) {
    const Eigen::VectorXcd f = rnd.Vector(3);
    Eigen::VectorXcd fhat(3);
    BinFigures figures;
    ASSERT_EQ(op->Identify(k, frf.at[k] * f, fhat, &figures), IdentifyStatus::kOk);
    EXPECT_LT(RelativeError(fhat, f), 1e-10);
    EXPECT_LT(figures.relative_residual, 1e-12);
    EXPECT_EQ(figures.rank, 3);
    EXPECT_EQ(figures.parameter, 1e-6);
    const Eigen::VectorXd sv = Eigen::BDCSVD<Eigen::MatrixXcd>(frf.at[k]).singularValues();
    EXPECT_LT(figures.condition_weighted, sv(0) / sv(2));  // column spread 20 removed
  }
}

TEST(IdentificationOperator, NoiseFloorRuleFiltersComponentsBelowEtaTimesSigmaMax) {
  // Diagonal H: Tikhonov with lambda = (eta sigma_1)^2 is sigma / (sigma^2 + lambda) per entry.
  FrfMatrix frf;
  frf.frequency_hz = Eigen::VectorXd::Constant(1, 100.0);
  Eigen::MatrixXcd h = Eigen::MatrixXcd::Zero(3, 3);
  h(0, 0) = 2.0;
  h(1, 1) = Complex(0.0, 2e-2);
  h(2, 2) = 2e-6;
  frf.at.push_back(h);
  IdentificationOptions o;
  o.method = InverseMethod::kTikhonov;
  o.regularisation.relative_noise = 1e-3;
  Result<IdentificationOperator> op = IdentificationOperator::Create(frf, o);
  ASSERT_TRUE(op.ok());
  const double lambda = 4e-6;
  Eigen::VectorXcd x(3);
  x << 1.0, 1.0, 1.0;
  Eigen::VectorXcd fhat(3);
  BinFigures figures;
  ASSERT_EQ(op->Identify(0, x, fhat, &figures), IdentifyStatus::kOk);
  EXPECT_NEAR(figures.parameter / lambda, 1.0, 1e-12);
  EXPECT_NEAR(std::abs(fhat(0) - 2.0 / (4.0 + lambda)), 0.0, 1e-14);
  EXPECT_NEAR(std::abs(fhat(1) - Complex(0.0, -2e-2) / (4e-4 + lambda)), 0.0, 1e-12);
  EXPECT_NEAR(std::abs(fhat(2) - 2e-6 / (4e-12 + lambda)), 0.0, 1e-14);
}

TEST(IdentificationOperator, GcvFallsBackOnSquareAndUnderdeterminedBinsAndSaysSo) {
  RandomSystems rnd(73);
  for (const auto& [rows, cols] : {std::pair{4, 4}, std::pair{3, 6}}) {
    const FrfMatrix frf = RandomFrf(rnd, rows, cols, 2, 1e3);
    IdentificationOptions o;
    o.regularisation.rule = RegularisationRule::kGcv;
    Result<IdentificationOperator> op = IdentificationOperator::Create(frf, o);
    ASSERT_TRUE(op.ok());
    Eigen::VectorXcd fhat(cols);
    BinFigures figures;
    ASSERT_EQ(op->Identify(1, rnd.Vector(rows), fhat, &figures), IdentifyStatus::kOk);
    EXPECT_EQ(figures.outcome, RuleOutcome::kGcvFellBackToNoiseFloor);
    EXPECT_TRUE(std::isfinite(figures.parameter) && figures.parameter > 0.0);
    EXPECT_TRUE(fhat.allFinite());
  }
}

TEST(IdentificationOperator, GcvAndDiscrepancyRunPerBlockOnOverdeterminedBins) {
  RandomSystems rnd(74);
  const FrfMatrix frf = RandomFrf(rnd, 12, 4, 3, 1e4);
  for (RegularisationRule rule : {RegularisationRule::kGcv, RegularisationRule::kDiscrepancy}) {
    IdentificationOptions o;
    o.method = InverseMethod::kTikhonov;
    o.regularisation.rule = rule;
    o.regularisation.noise_rms = 1e-3;
    Result<IdentificationOperator> op = IdentificationOperator::Create(frf, o);
    ASSERT_TRUE(op.ok());
    EXPECT_FALSE(op->precomputed());
    const Eigen::VectorXcd x = frf.at[0] * rnd.Vector(4) + 1e-3 * rnd.Vector(12) / std::sqrt(2.0);
    Eigen::VectorXcd fhat(4);
    BinFigures figures;
    ASSERT_EQ(op->Identify(0, x, fhat, &figures), IdentifyStatus::kOk);
    EXPECT_EQ(figures.outcome, RuleOutcome::kAsConfigured) << ToString(rule);
    EXPECT_TRUE(std::isfinite(figures.parameter) && figures.parameter > 0.0);
    Result<Eigen::VectorXcd> same = SolveTikhonov(frf.at[0], x, figures.parameter);
    EXPECT_LT(RelativeError(fhat, *same), 1e-10);
    if (rule == RegularisationRule::kDiscrepancy) {
      EXPECT_NEAR(figures.relative_residual * x.norm() / (1e-3 * std::sqrt(12.0)), 1.0, 1e-8);
    }
  }
}

TEST(IdentificationOperator, ZeroFrfBinGivesZeroForcesAndSaysSo) {
  FrfMatrix frf;
  frf.frequency_hz = Eigen::VectorXd::LinSpaced(2, 0.0, 10.0);
  frf.at.push_back(Eigen::MatrixXcd::Zero(3, 2));  // accelerance at 0 Hz
  frf.at.push_back(Eigen::MatrixXcd::Identity(3, 2));
  for (InverseMethod method :
       {InverseMethod::kMwi, InverseMethod::kTikhonov, InverseMethod::kLeastSquares}) {
    IdentificationOptions o;
    o.method = method;
    Result<IdentificationOperator> op = IdentificationOperator::Create(frf, o);
    ASSERT_TRUE(op.ok()) << op.error();
    Eigen::VectorXcd fhat(2);
    BinFigures figures;
    ASSERT_EQ(op->Identify(0, Eigen::VectorXcd::Ones(3), fhat, &figures), IdentifyStatus::kOk);
    EXPECT_EQ(fhat.norm(), 0.0);
    EXPECT_EQ(figures.outcome, RuleOutcome::kZeroOperator);
    EXPECT_TRUE(std::isinf(figures.condition_weighted));
  }
}

TEST(IdentificationOperator, PerBlockCallAllocatesNothing) {
  ASSERT_TRUE(InstallAllocationCounter());
  RandomSystems rnd(75);
  const FrfMatrix frf = RandomFrf(rnd, 8, 4, 6, 1e3);
  const Eigen::MatrixXcd x = rnd.Matrix(8, 6);
  for (RegularisationRule rule : {RegularisationRule::kNoiseFloor, RegularisationRule::kGcv,
                                  RegularisationRule::kDiscrepancy}) {
    IdentificationOptions o;
    o.regularisation.rule = rule;
    o.regularisation.noise_rms = 0.1;
    Result<IdentificationOperator> op = IdentificationOperator::Create(frf, o);
    ASSERT_TRUE(op.ok());
    Eigen::MatrixXcd forces(4, 6);
    std::vector<BinFigures> figures(6);
    Eigen::VectorXcd one(4);
    g_allocations = 0;
    g_count_allocations = true;
    const IdentifyStatus all = op->IdentifyAll(x, forces, figures);
    const IdentifyStatus single = op->Identify(2, x.col(2), one, &figures[2]);
    g_count_allocations = false;
    EXPECT_EQ(all, IdentifyStatus::kOk);
    EXPECT_EQ(single, IdentifyStatus::kOk);
    EXPECT_EQ(g_allocations.load(), 0) << ToString(rule);
  }
  // The counter does count, on both paths: Eigen's dynamic storage (malloc) and operator new.
  g_allocations = 0;
  g_count_allocations = true;
  {
    Eigen::VectorXcd v(100);
    g_allocation_sink = v.data();
  }
  g_count_allocations = false;
  EXPECT_GE(g_allocations.load(), 1) << "an Eigen heap vector was not counted";
  g_allocations = 0;
  g_count_allocations = true;
  std::vector<double>* w = new std::vector<double>();
  g_allocation_sink = w;
  g_count_allocations = false;
  delete w;
  EXPECT_GE(g_allocations.load(), 1) << "an operator new was not counted";
  g_allocation_sink = nullptr;
}

TEST(IdentificationOperator, PerBlockCallRejectsBadShapesAndNonFiniteResponses) {
  RandomSystems rnd(76);
  const FrfMatrix frf = RandomFrf(rnd, 4, 2, 3, 10.0);
  Result<IdentificationOperator> op = IdentificationOperator::Create(frf, IdentificationOptions{});
  ASSERT_TRUE(op.ok());
  Eigen::VectorXcd f(2);
  EXPECT_EQ(op->Identify(3, rnd.Vector(4), f), IdentifyStatus::kBinOutOfRange);
  EXPECT_EQ(op->Identify(0, rnd.Vector(5), f), IdentifyStatus::kShapeMismatch);
  Eigen::VectorXcd x = rnd.Vector(4);
  x(2) = Complex(INFINITY, 0.0);
  EXPECT_EQ(op->Identify(0, x, f), IdentifyStatus::kNonFiniteResponse);
  Eigen::MatrixXcd forces(2, 2);
  EXPECT_EQ(op->IdentifyAll(rnd.Matrix(4, 3), forces), IdentifyStatus::kShapeMismatch);
}

TEST(IdentificationOperator, ConstructionRejectsInvalidOptionsAndFrfsNamingTheCulprit) {
  RandomSystems rnd(77);
  const FrfMatrix good = RandomFrf(rnd, 4, 2, 3, 10.0);
  auto error_of = [](const FrfMatrix& frf, const IdentificationOptions& o) {
    Result<IdentificationOperator> op = IdentificationOperator::Create(frf, o);
    return op.ok() ? std::string("ok") : op.error();
  };
  EXPECT_NE(error_of(good, Fixed(InverseMethod::kMwi, 0.0)).find("alpha: the fixed"),
            std::string::npos);
  EXPECT_NE(error_of(good, Fixed(InverseMethod::kTikhonov, -1.0)).find("lambda: the fixed"),
            std::string::npos);
  EXPECT_NE(error_of(good, Fixed(InverseMethod::kMwi, 1.0, 0)).find("iterations: MWI needs K >= 1"),
            std::string::npos);
  IdentificationOptions o;
  o.regularisation.relative_noise = 1.5;
  EXPECT_NE(error_of(good, o).find("relative_noise"), std::string::npos);
  o = IdentificationOptions{};
  o.regularisation.rule = RegularisationRule::kDiscrepancy;
  EXPECT_NE(error_of(good, o).find("noise_rms"), std::string::npos);
  o.regularisation.noise_rms = 1.0;
  o.regularisation.discrepancy_factor = 0.5;
  EXPECT_NE(error_of(good, o).find("discrepancy_factor"), std::string::npos);

  EXPECT_NE(error_of(FrfMatrix{}, IdentificationOptions{}).find("no frequency bins"),
            std::string::npos);
  FrfMatrix mismatched = good;
  mismatched.at[2] = rnd.Matrix(4, 3);
  EXPECT_NE(error_of(mismatched, IdentificationOptions{}).find("frf.at[2] (30 Hz): shape 4 x 3"),
            std::string::npos)
      << error_of(mismatched, IdentificationOptions{});
  FrfMatrix non_finite = good;
  non_finite.at[1](3, 1) = Complex(0.0, std::nan(""));
  EXPECT_NE(error_of(non_finite, IdentificationOptions{}).find("frf.at[1] (20 Hz): entry (3, 1)"),
            std::string::npos);
  FrfMatrix short_axis = good;
  short_axis.frequency_hz.resize(2);
  EXPECT_NE(error_of(short_axis, IdentificationOptions{}).find("2 frequencies but 3 matrices"),
            std::string::npos);
}

}  // namespace
}  // namespace gearpath

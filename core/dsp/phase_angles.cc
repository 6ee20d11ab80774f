#include "core/dsp/phase_angles.h"

#include <algorithm>
#include <cstddef>

#if defined(GEARPATH_HAVE_LIBMVEC) && defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
// libmvec's atan2 under the x86-64 vector function ABI: 2 (SSE) or 4 (AVX2) (y, x) pairs per
// call, each dispatched inside glibc to the CPU's best implementation.
// NOLINTBEGIN(readability-identifier-naming)
extern "C" __m128d _ZGVbN2vv_atan2(__m128d y, __m128d x);
#define GEARPATH_VECTOR_ATAN2 1
#if !defined(__clang__)
// Not with clang (the sanitizer and fuzz builds): clang 14 passes these __m256d arguments in
// memory instead of in ymm registers as the vector ABI requires (test PhaseAngles caught it).
extern "C" __attribute__((target("avx2"))) __m256d _ZGVdN4vv_atan2(__m256d y, __m256d x);
#define GEARPATH_VECTOR_ATAN2_AVX2 1
#endif
// NOLINTEND(readability-identifier-naming)
#endif

namespace gearpath {
namespace {

#ifdef GEARPATH_VECTOR_ATAN2_AVX2
// The first count - count % 4 angles, four per call; returns how many.
__attribute__((target("avx2"))) std::size_t FourAtATime(const double* v, std::size_t count,
                                                       double* angle) noexcept {
  std::size_t i = 0;
  for (; i + 4 <= count; i += 4) {
    // (re0 im0 re1 im1), (re2 im2 re3 im3): unpacked within 128-bit lanes, re and im come out
    // in the order 0 2 1 3, which the permute undoes.
    const __m256d first = _mm256_loadu_pd(v + 2 * i);
    const __m256d second = _mm256_loadu_pd(v + 2 * i + 4);
    const __m256d a =
        _ZGVdN4vv_atan2(_mm256_unpackhi_pd(first, second), _mm256_unpacklo_pd(first, second));
    _mm256_storeu_pd(angle + i, _mm256_permute4x64_pd(a, 0xd8));
  }
  return i;
}
#endif

}  // namespace

void PhaseAngles(std::span<const std::complex<double>> z, std::span<double> angle) noexcept {
  const std::size_t count = std::min(z.size(), angle.size());
#ifdef GEARPATH_VECTOR_ATAN2
  // (re, im) pairs: the array layout [complex.numbers.general] guarantees.
  const double* v = reinterpret_cast<const double*>(z.data());
  double* out = angle.data();
  std::size_t i = 0;
#ifdef GEARPATH_VECTOR_ATAN2_AVX2
  static const bool avx2 = __builtin_cpu_supports("avx2");
  if (avx2) i = FourAtATime(v, count, out);
#endif
  for (; i + 2 <= count; i += 2) {
    const __m128d first = _mm_loadu_pd(v + 2 * i);
    const __m128d second = _mm_loadu_pd(v + 2 * i + 2);
    _mm_storeu_pd(out + i, _ZGVbN2vv_atan2(_mm_unpackhi_pd(first, second),
                                           _mm_unpacklo_pd(first, second)));
  }
  if (i < count) {  // an odd last value, through the same function as the others
    const __m128d last = _mm_loadu_pd(v + 2 * i);
    out[i] = _mm_cvtsd_f64(_ZGVbN2vv_atan2(_mm_unpackhi_pd(last, last),
                                           _mm_unpacklo_pd(last, last)));
  }
#else
  for (std::size_t i = 0; i < count; ++i) angle[i] = std::arg(z[i]);
#endif
}

}  // namespace gearpath

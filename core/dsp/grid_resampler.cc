#include "core/dsp/grid_resampler.h"

#include <algorithm>
#include <cstdint>

#include "core/common/simd_clones.h"

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#endif

namespace gearpath {
namespace {

struct Job {
  const double* x;
  std::size_t n;
  CubicGridView grid;  // already advanced to the first point of the job
  std::size_t count;
  double* out;
  bool add;
};

inline double PointAt(const Job& j, std::size_t p) noexcept {
  const double* s = j.x + j.grid.first[p];
  // The same terms in the same order as ApplyCubicStencil.
  return j.grid.w0[p] * s[0] + j.grid.w1[p] * s[1] - j.grid.w2[p] * s[2] + j.grid.w3[p] * s[3];
}

inline void PointsFrom(const Job& j, std::size_t from, std::size_t to) noexcept {
  for (std::size_t m = from; m < to; ++m) {
    const double v = PointAt(j, m);
    j.out[m] = j.add ? j.out[m] + v : v;
  }
}

#if defined(__x86_64__) && defined(__GNUC__) && !defined(GEARPATH_NO_SIMD_CLONES)
#define GEARPATH_RESAMPLE_WIDE 1

// Eight points at a time from one 16-sample window: consecutive grid points lie at most a sample
// apart (M >= fs / f upsamples), so eight points read one short stretch of the signal, and two
// loads and four two-register permutes replace 32 loads. Groups that do not fit (a warp
// stretching the grid, the block's end) go point by point.
__attribute__((target("avx512f"))) void ResampleAvx512(const Job& j) noexcept {
  const __m512i one = _mm512_set1_epi64(1);
  const __m512i last_in_window = _mm512_set1_epi64(15);
  std::size_t m = 0;
  for (; m + 8 <= j.count; m += 8) {
    const std::uint32_t f0 = j.grid.first[m];
    const __m256i f = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(j.grid.first + m));
    const __m512i i0 = _mm512_maskz_cvtepu32_epi64(
        0xFF, _mm256_sub_epi32(f, _mm256_set1_epi32(static_cast<int>(f0))));
    const __m512i i1 = _mm512_add_epi64(i0, one);
    const __m512i i2 = _mm512_add_epi64(i1, one);
    const __m512i i3 = _mm512_add_epi64(i2, one);
    // Every stencil inside the window (a point before f0 wraps to a huge index), and the window
    // inside the block.
    if (_mm512_cmpgt_epu64_mask(i3, last_in_window) != 0 || f0 + 16 > j.n) {
      PointsFrom(j, m, m + 8);
      continue;
    }
    const __m512d lo = _mm512_loadu_pd(j.x + f0);
    const __m512d hi = _mm512_loadu_pd(j.x + f0 + 8);
    const __m512d s0 = _mm512_permutex2var_pd(lo, i0, hi);
    const __m512d s1 = _mm512_permutex2var_pd(lo, i1, hi);
    const __m512d s2 = _mm512_permutex2var_pd(lo, i2, hi);
    const __m512d s3 = _mm512_permutex2var_pd(lo, i3, hi);
    // w0 s0 + w1 s1 - w2 s2 + w3 s3, left to right, no fused multiply-add: the scalar bits.
    __m512d v = _mm512_add_pd(_mm512_mul_pd(_mm512_loadu_pd(j.grid.w0 + m), s0),
                              _mm512_mul_pd(_mm512_loadu_pd(j.grid.w1 + m), s1));
    v = _mm512_sub_pd(v, _mm512_mul_pd(_mm512_loadu_pd(j.grid.w2 + m), s2));
    v = _mm512_add_pd(v, _mm512_mul_pd(_mm512_loadu_pd(j.grid.w3 + m), s3));
    if (j.add) v = _mm512_add_pd(_mm512_loadu_pd(j.out + m), v);
    _mm512_storeu_pd(j.out + m, v);
  }
  PointsFrom(j, m, j.count);
}

// Four points at a time, each point's four samples one unaligned load (its stencil always lies
// inside the block), transposed in registers so that tap t of the four points is one vector.
// Unlike a window shared by the group, this needs no fit test and no scalar fallback, and a
// 4 x 4 transpose is eight shuffles where picking taps from a window with AVX2's 32-bit permutes
// took twelve and their index arithmetic.
__attribute__((target("avx2"))) void ResampleAvx2(const Job& j) noexcept {
  // Locals, so that the stores to out are not taken to move the job's pointers.
  const double* const x = j.x;
  const std::uint32_t* const first = j.grid.first;
  const double* const w0 = j.grid.w0;
  const double* const w1 = j.grid.w1;
  const double* const w2 = j.grid.w2;
  const double* const w3 = j.grid.w3;
  double* const out = j.out;
  const bool add = j.add;
  std::size_t m = 0;
  for (; m + 4 <= j.count; m += 4) {
    const __m256d a = _mm256_loadu_pd(x + first[m]);
    const __m256d b = _mm256_loadu_pd(x + first[m + 1]);
    const __m256d c = _mm256_loadu_pd(x + first[m + 2]);
    const __m256d d = _mm256_loadu_pd(x + first[m + 3]);
    const __m256d ab_even = _mm256_unpacklo_pd(a, b);  // a0 b0 a2 b2
    const __m256d ab_odd = _mm256_unpackhi_pd(a, b);   // a1 b1 a3 b3
    const __m256d cd_even = _mm256_unpacklo_pd(c, d);  // c0 d0 c2 d2
    const __m256d cd_odd = _mm256_unpackhi_pd(c, d);   // c1 d1 c3 d3
    const __m256d s0 = _mm256_permute2f128_pd(ab_even, cd_even, 0x20);
    const __m256d s1 = _mm256_permute2f128_pd(ab_odd, cd_odd, 0x20);
    const __m256d s2 = _mm256_permute2f128_pd(ab_even, cd_even, 0x31);
    const __m256d s3 = _mm256_permute2f128_pd(ab_odd, cd_odd, 0x31);
    // w0 s0 + w1 s1 - w2 s2 + w3 s3, left to right, no fused multiply-add: the scalar bits.
    __m256d v = _mm256_add_pd(_mm256_mul_pd(_mm256_loadu_pd(w0 + m), s0),
                              _mm256_mul_pd(_mm256_loadu_pd(w1 + m), s1));
    v = _mm256_sub_pd(v, _mm256_mul_pd(_mm256_loadu_pd(w2 + m), s2));
    v = _mm256_add_pd(v, _mm256_mul_pd(_mm256_loadu_pd(w3 + m), s3));
    if (add) v = _mm256_add_pd(_mm256_loadu_pd(out + m), v);
    _mm256_storeu_pd(out + m, v);
  }
  PointsFrom(j, m, j.count);
}

enum class Wide { kNone, kAvx2, kAvx512 };

Wide WidestSupported() noexcept {
  static const Wide wide = __builtin_cpu_supports("avx512f") ? Wide::kAvx512
                           : __builtin_cpu_supports("avx2")  ? Wide::kAvx2
                                                             : Wide::kNone;
  return wide;
}
#endif

// MakeCubicStencil's arithmetic on arrays (its terms in its order, no fused multiply-add), in
// 32-bit indices, which the vector units convert to and from doubles; clamped like the callers'
// std::clamp (NaN aside, which no caller passes).
GEARPATH_SIMD_CLONES
void Stencils(std::int32_t n, const double* __restrict position, std::size_t count,
              std::uint32_t* __restrict first, double* __restrict w0, double* __restrict w1,
              double* __restrict w2, double* __restrict w3) noexcept {
  const double last = static_cast<double>(n - 1);
  for (std::size_t k = 0; k < count; ++k) {
    const double u = std::min(std::max(position[k], 0.0), last);
    const auto i = static_cast<std::int32_t>(u);  // floor, u >= 0
    const std::int32_t f = std::min(std::max(i - 1, 0), n - 4);
    const double t = u - static_cast<double>(f);
    const double a = t - 1.0;
    const double b = t - 2.0;
    const double c = t - 3.0;
    first[k] = static_cast<std::uint32_t>(f);
    w0[k] = -a * b * c / 6.0;
    w1[k] = t * b * c / 2.0;
    w2[k] = t * a * c / 2.0;
    w3[k] = t * a * b / 6.0;
  }
}

}  // namespace

void SetCubicStencils(std::size_t n, const double* position, std::size_t count, CubicGrid& grid,
                      std::size_t begin) noexcept {
  Stencils(static_cast<std::int32_t>(n), position, count, grid.first.data() + begin,
           grid.w0.data() + begin, grid.w1.data() + begin, grid.w2.data() + begin,
           grid.w3.data() + begin);
}

void ResampleOnGrid(const double* x, std::size_t n, const CubicGridView& grid, std::size_t begin,
                    std::size_t count, double* out, bool add) noexcept {
  const Job j{
      x,
      n,
      {grid.first + begin, grid.w0 + begin, grid.w1 + begin, grid.w2 + begin, grid.w3 + begin},
      count,
      out,
      add};
#ifdef GEARPATH_RESAMPLE_WIDE
  switch (WidestSupported()) {
    case Wide::kAvx512:
      ResampleAvx512(j);
      return;
    case Wide::kAvx2:
      ResampleAvx2(j);
      return;
    case Wide::kNone:
      break;
  }
#endif
  PointsFrom(j, 0, count);
}

}  // namespace gearpath

// GEARPATH_SIMD_CLONES: marks a hot kernel (a loop the compiler vectorises) to be built three
// times, for baseline x86-64 (SSE2), x86-64-v3 (AVX2, FMA) and x86-64-v4 (AVX-512), the best
// one that the CPU runs being chosen once at load time (GCC target_clones, an ifunc). The
// package keeps running on any x86-64 while the few loops that dominate a block use the wide
// vectors where they exist (docs/performance.md, "Build").
//
// Results do not depend on the clone: the project builds with -ffp-contract=off (no fused
// multiply-add unless written), and the kernels marked with it vectorise element-wise work
// only, never a floating-point reduction (whose order vectorising would change), so every
// clone rounds exactly as the baseline one.
//
// Empty (one build for the configured target) with other compilers or architectures, and in
// sanitizer and fuzz builds (GEARPATH_NO_SIMD_CLONES), whose runtimes start after ifunc
// resolvers run.
#pragma once

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && \
    !defined(GEARPATH_NO_SIMD_CLONES)
#define GEARPATH_SIMD_CLONES \
  __attribute__((target_clones("default", "arch=x86-64-v3", "arch=x86-64-v4")))
#else
#define GEARPATH_SIMD_CLONES
#endif

#pragma once
// GBL_SIMD_CLONES: compile a hot loop twice, for x86-64-v3 (AVX2) and for the baseline, and pick
// one at load time (GCC target_clones, an ifunc). The build targets baseline x86-64 (SSE2), which
// has no vector floor (ROUNDPS is SSE4.1), so without this the quantise loops stay scalar.
// Results are identical in both clones: only IEEE-exact operations (+ - * / sqrt floor, integer
// ops) are vectorised, and -ffp-contract=off forbids FMA contraction in the AVX2 clone too.
// GCC vectorises floor and sqrt only under -fno-trapping-math -fno-math-errno (CMakeLists.txt sets
// them for the files that use this; no value changes). Off under AddressSanitizer (that build is
// for correctness: the baseline path alone, no ifunc resolvers running before the sanitizer
// runtime) and off other compilers and architectures, where the loops build for the baseline.
//
// GBL_CLONE_INLINE marks the helpers such a function calls: a helper that is not inlined is
// compiled once, for the baseline, and its loops would run without AVX2 in the AVX2 clone.
//
// GCC 12 drops `restrict` in target_clones clones: a loop that stores through a pointer and also
// reads a table (sRGB) is then not vectorised; such loops write to a local array first.
//
// GBL_SIMD_CLONES_AVX512 adds a third clone for x86-64-v4 (AVX-512 F/BW/DQ/VL; GCC still prefers
// 256-bit vectors for the generic tuning, but gains unsigned float/int conversions, masks and
// ternary logic). Used by the CPU codec's encode loops, where it saved 5-15 % of the CPU time per
// image on the AMD Zen 4 benchmark machine (bench/RESULTS.md); the same IEEE-exact operations, so
// the same codes (tests/codec/cpu_codec_test.cpp runs whichever clone the machine picks).
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && !defined(__SANITIZE_ADDRESS__)
#define GBL_SIMD_CLONES __attribute__((target_clones("arch=x86-64-v3", "default")))
#define GBL_SIMD_CLONES_AVX512 __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define GBL_SIMD_CLONES
#define GBL_SIMD_CLONES_AVX512
#endif
#if defined(__GNUC__)
#define GBL_CLONE_INLINE [[gnu::always_inline]] inline
#else
#define GBL_CLONE_INLINE inline
#endif

#pragma once
// The CPU cut's hot code (render/tile_cuts.cpp, render/far_field.cpp) runs in a copy compiled
// for AVX2 on x86-64 CPUs that have it: GCC's target_clones builds both copies and the dynamic
// loader picks one. The results are the same bit for bit: AVX2 brings no fused multiply-add,
// and none of this code reassociates. The helpers it calls are inlined (MANYLIGHT_INLINE), so
// that each copy has its own; a call would leave the AVX2 copy for the plain code. Off under
// clang (the sanitizer and fuzzer builds) and on other CPUs.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define MANYLIGHT_AVX2_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define MANYLIGHT_AVX2_CLONES
#endif
#if defined(__GNUC__)
#define MANYLIGHT_INLINE __attribute__((always_inline))
#else
#define MANYLIGHT_INLINE
#endif

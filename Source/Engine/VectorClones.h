#pragma once
// SNARESIM_VECTOR_CLONES: build a hot loop twice, for x86-64-v3 (AVX2 + FMA) and for the
// baseline x86-64, and let the loader pick the one the CPU runs. Shipped binaries stay generic
// (no -march=native) and still use the wide vectors where the CPU has them.

//
// SNARESIM_WIDE_VECTOR_CLONES: the same with an x86-64-v4 (AVX-512) build first, for the air
// box's loops, which stream far more data than the drum's others, and the heads' rows (eq. 22),
// 12 % faster on the batter at Quality 1 with it (BENCHMARKS.md).

#if defined(__x86_64__) && defined(__GNUC__) && ! defined(__clang__)
#define SNARESIM_VECTOR_CLONES __attribute__((target_clones("arch=x86-64-v3", "default")))
#define SNARESIM_WIDE_VECTOR_CLONES __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define SNARESIM_VECTOR_CLONES
#define SNARESIM_WIDE_VECTOR_CLONES
#endif

#pragma once

#include <cstddef>  // Defines __GLIBC__ where glibc is the C library.

/**
 * Marks a loop kernel to be compiled twice, for AVX2 and for the baseline x86-64 (SSE2), and chosen
 * once at load time by the CPU it runs on (GCC's function multiversioning, an ifunc). The packages
 * are built for any x86-64, so without this the kernels would never use 256-bit vectors; on the
 * real-data benchmark the AVX2 clones make MRS's query about a fifth faster. Elementwise loops give
 * the same floats in either clone (no FMA contraction: AVX2 alone does not enable FMA).
 *
 * Only GCC on x86-64 with glibc: other compilers and targets get the plain function.
 */
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__GLIBC__)
#define MRS_VPR_VECTOR_KERNEL __attribute__((target_clones("avx2", "default")))
#else
#define MRS_VPR_VECTOR_KERNEL
#endif

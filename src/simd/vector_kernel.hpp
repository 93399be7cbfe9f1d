#pragma once

#include <cstddef>  // Defines __GLIBC__ where glibc is the C library.

/**
 * Marks a loop kernel to be compiled twice, for AVX2 and for the baseline x86-64 (SSE2), and chosen
 * once at load time by the CPU it runs on (GCC's function multiversioning, an ifunc). The packages
 * are built for any x86-64, so without this the kernels would never use 256-bit vectors; on the
 * real-data benchmark the AVX2 clones make an MRS query about a quarter faster (AVX-512 clones
 * added nothing measurable). The core is built with -ffp-contract=off, so that both clones compute
 * the same floats: elementwise loops, no fused multiply-adds.
 *
 * Only GCC on x86-64 with glibc: other compilers and targets get the plain function. So do builds
 * under ThreadSanitizer, which instruments the ifunc's resolver: run by the dynamic loader before the
 * sanitizer's runtime is ready, it crashed every program before main().
 */
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && defined(__GLIBC__) && \
    !defined(__SANITIZE_THREAD__)
#define MRS_VPR_VECTOR_KERNEL __attribute__((target_clones("avx2", "default")))
#else
#define MRS_VPR_VECTOR_KERNEL
#endif

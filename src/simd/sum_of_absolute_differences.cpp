#include "simd/sum_of_absolute_differences.hpp"

#include <cstdlib>

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define MRS_VPR_HAVE_AVX2_KERNEL 1
#endif

namespace mrs_vpr {
namespace simd {
namespace {

int plainSum(const std::uint8_t* __restrict a, const std::uint8_t* __restrict b, int size) {
  int sum = 0;
  for (int i = 0; i < size; ++i) sum += std::abs(static_cast<int>(a[i]) - static_cast<int>(b[i]));
  return sum;
}

void plainKernel(const std::uint8_t* query, const std::uint8_t* cells, std::ptrdiff_t pitch, int count, int size,
                 float scale, float* out) {
  for (int i = 0; i < count; ++i) out[i] = static_cast<float>(plainSum(query, cells + i * pitch, size)) * scale;
}

#ifdef MRS_VPR_HAVE_AVX2_KERNEL

/// The four 64-bit lanes of each of a, b, c, d summed: {sum a, sum b, sum c, sum d} as 32-bit
/// integers (a lane of sums of absolute byte differences fits in 32 bits).
__attribute__((target("avx2"))) __m128i sumLanes(__m256i a, __m256i b, __m256i c, __m256i d) {
  // Dwords [a0 b0 a1 b1 | a2 b2 a3 b3] and [c0 d0 c1 d1 | ...].
  const __m256i ab = _mm256_blend_epi32(a, _mm256_slli_epi64(b, 32), 0xAA);
  const __m256i cd = _mm256_blend_epi32(c, _mm256_slli_epi64(d, 32), 0xAA);
  // [a0 b0 c0 d0 | a2 b2 c2 d2] + [a1 b1 c1 d1 | a3 b3 c3 d3].
  const __m256i halves = _mm256_add_epi32(_mm256_unpacklo_epi64(ab, cd), _mm256_unpackhi_epi64(ab, cd));
  return _mm_add_epi32(_mm256_castsi256_si128(halves), _mm256_extracti128_si256(halves, 1));
}

/// The sum of absolute differences of `query` and the 32 bytes at `cell`, both masked by `mask`.
__attribute__((target("avx2"))) inline __m256i maskedSad(__m256i query, const std::uint8_t* cell, __m256i mask) {
  return _mm256_sad_epu8(query, _mm256_and_si256(mask, _mm256_loadu_si256(reinterpret_cast<const __m256i*>(cell))));
}

__attribute__((target("avx2"))) void avx2Kernel(const std::uint8_t* query, const std::uint8_t* cells,
                                                std::ptrdiff_t pitch, int count, int size, float scale, float* out) {
  const __m128 scales = _mm_set1_ps(scale);
  const int whole = size & ~31;  // Bytes in whole 32-byte vectors from the start.
  const int tail = size - whole;
  // The tail is read as the row's last 32 bytes, whose first 32 - tail were summed already: the mask
  // zeroes them in both rows, so that they add nothing.
  const __m256i positions = _mm256_setr_epi8(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19,
                                             20, 21, 22, 23, 24, 25, 26, 27, 28, 29, 30, 31);
  const __m256i tail_mask = _mm256_cmpgt_epi8(positions, _mm256_set1_epi8(static_cast<char>(31 - tail)));
  const int last = size - 32;
  const __m256i query_tail =
      _mm256_and_si256(tail_mask, _mm256_loadu_si256(reinterpret_cast<const __m256i*>(query + last)));
  int i = 0;
  for (; i + 4 <= count; i += 4) {
    const std::uint8_t* c0 = cells + i * pitch;
    const std::uint8_t* c1 = c0 + pitch;
    const std::uint8_t* c2 = c1 + pitch;
    const std::uint8_t* c3 = c2 + pitch;
    __m256i s0 = _mm256_setzero_si256();
    __m256i s1 = s0;
    __m256i s2 = s0;
    __m256i s3 = s0;
    for (int b = 0; b < whole; b += 32) {
      const __m256i q = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(query + b));
      s0 = _mm256_add_epi64(s0, _mm256_sad_epu8(q, _mm256_loadu_si256(reinterpret_cast<const __m256i*>(c0 + b))));
      s1 = _mm256_add_epi64(s1, _mm256_sad_epu8(q, _mm256_loadu_si256(reinterpret_cast<const __m256i*>(c1 + b))));
      s2 = _mm256_add_epi64(s2, _mm256_sad_epu8(q, _mm256_loadu_si256(reinterpret_cast<const __m256i*>(c2 + b))));
      s3 = _mm256_add_epi64(s3, _mm256_sad_epu8(q, _mm256_loadu_si256(reinterpret_cast<const __m256i*>(c3 + b))));
    }
    if (tail > 0) {
      s0 = _mm256_add_epi64(s0, maskedSad(query_tail, c0 + last, tail_mask));
      s1 = _mm256_add_epi64(s1, maskedSad(query_tail, c1 + last, tail_mask));
      s2 = _mm256_add_epi64(s2, maskedSad(query_tail, c2 + last, tail_mask));
      s3 = _mm256_add_epi64(s3, maskedSad(query_tail, c3 + last, tail_mask));
    }
    _mm_storeu_ps(out + i, _mm_mul_ps(_mm_cvtepi32_ps(sumLanes(s0, s1, s2, s3)), scales));
  }
  plainKernel(query, cells + i * pitch, pitch, count - i, size, scale, out + i);
}

bool hasAvx2() {
  static const bool avx2 = __builtin_cpu_supports("avx2");
  return avx2;
}

#endif

}  // namespace

void sumsOfAbsoluteDifferences(const std::uint8_t* query, const std::uint8_t* cells, std::ptrdiff_t pitch, int count,
                               int size, float scale, float* out) {
#ifdef MRS_VPR_HAVE_AVX2_KERNEL
  if (size >= 32 && hasAvx2()) {
    avx2Kernel(query, cells, pitch, count, size, scale, out);
    return;
  }
#endif
  plainKernel(query, cells, pitch, count, size, scale, out);
}

}  // namespace simd
}  // namespace mrs_vpr

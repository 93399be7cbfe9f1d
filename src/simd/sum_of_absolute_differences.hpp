#pragma once

#include <cstddef>
#include <cstdint>

namespace mrs_vpr {
namespace simd {

/**
 * out[i] = scale * (sum of |query[b] - cell_i[b]| over the `size` bytes), cell_i = cells + i * pitch,
 * for i in [0, count): one short row (a compact coarse cell) against consecutive cells.
 *
 * With AVX2 and at least 32 bytes, four cells are compared at once against the query held in
 * registers, 32 bytes at a time (the last size % 32 bytes in one masked vector), and their four sums
 * are reduced together; the per-pair reduction is what dominates a 96-byte comparison otherwise. Other CPUs and
 * shorter rows take a plain loop that the compiler vectorises. Both give the same integers, so the
 * same floats.
 */
void sumsOfAbsoluteDifferences(const std::uint8_t* query, const std::uint8_t* cells, std::ptrdiff_t pitch, int count,
                               int size, float scale, float* out);

}  // namespace simd
}  // namespace mrs_vpr

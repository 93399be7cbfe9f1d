#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <random>
#include <vector>

#include "mrs_vpr/descriptor.hpp"
#include "mrs_vpr/difference_matrix.hpp"

namespace mrs_vpr {
namespace {

/// The definition: mean absolute byte difference in patch standard deviations.
float expectedDifference(const std::uint8_t* a, const std::uint8_t* b, int size) {
  long sum = 0;
  for (int i = 0; i < size; ++i) sum += std::abs(static_cast<int>(a[i]) - static_cast<int>(b[i]));
  return static_cast<float>(sum) * (1.0F / (static_cast<float>(size) * DescriptorExtractor::kLevelsPerStd));
}

std::vector<std::uint8_t> randomBytes(std::size_t count, unsigned seed) {
  std::mt19937 generator(seed);
  std::uniform_int_distribution<int> byte(0, 255);
  std::vector<std::uint8_t> bytes(count);
  for (std::uint8_t& value : bytes) value = static_cast<std::uint8_t>(byte(generator));
  return bytes;
}

// Sizes on and off the 32-byte blocks of the vector kernel, counts on and off its groups of four,
// cells packed and spaced: every path gives the definition's value exactly.
TEST(DescriptorDifferences, EqualTheDefinitionForEverySizeCountAndPitch) {
  for (int size : {1, 31, 32, 64, 96, 100, 128, 992, 1024, 2048}) {
    for (int spacing : {0, 7, 32}) {
      const std::ptrdiff_t pitch = size + spacing;
      for (int count : {0, 1, 3, 4, 5, 8, 9}) {
        const std::vector<std::uint8_t> query = randomBytes(static_cast<std::size_t>(size), 1U);
        const std::vector<std::uint8_t> cells = randomBytes(static_cast<std::size_t>(pitch) * 9, 2U + size);
        std::vector<float> out(static_cast<std::size_t>(count) + 1, -1.0F);
        descriptorDifferences(query.data(), cells.data(), pitch, count, size, out.data());
        for (int i = 0; i < count; ++i) {
          const std::uint8_t* cell = cells.data() + i * pitch;
          EXPECT_EQ(out[static_cast<std::size_t>(i)], expectedDifference(query.data(), cell, size))
              << "size " << size << ", pitch " << pitch << ", cell " << i << " of " << count;
          EXPECT_EQ(out[static_cast<std::size_t>(i)], descriptorDifference(query.data(), cell, size));
        }
        EXPECT_EQ(out[static_cast<std::size_t>(count)], -1.0F) << "wrote past the cells";
      }
    }
  }
}

TEST(DescriptorDifferences, ExtremeBytesDoNotOverflow) {
  const std::vector<std::uint8_t> zeros(992, 0);
  const std::vector<std::uint8_t> full(992 * 4, 255);
  std::vector<float> out(4);
  descriptorDifferences(zeros.data(), full.data(), 992, 4, 992, out.data());
  for (float value : out) EXPECT_FLOAT_EQ(value, 255.0F / DescriptorExtractor::kLevelsPerStd);
}

}  // namespace
}  // namespace mrs_vpr

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "mrs_vpr/descriptor_regions.hpp"
#include "support/front_ends.hpp"

namespace mrs_vpr {
namespace {

class DescriptorRegionsTest : public ::testing::TestWithParam<DescriptorParams> {};

TEST_P(DescriptorRegionsTest, TheMedianRegionDecidesSoAFewChangedRegionsChangeNothing) {
  const DescriptorRegions regions(GetParam());
  const auto size = static_cast<std::size_t>(GetParam().descriptorSize());
  std::vector<std::uint8_t> a(size, 100);
  std::vector<std::uint8_t> b(size, 104);  // every byte 4 apart
  EXPECT_DOUBLE_EQ(regions.difference(a.data(), a.data()), 0.0);
  EXPECT_DOUBLE_EQ(regions.difference(a.data(), b.data()), 4.0);
  // A descriptor and a mean of descriptors with the same values differ alike.
  const std::vector<float> b_as_mean(b.begin(), b.end());
  EXPECT_DOUBLE_EQ(regions.difference(a.data(), b_as_mean.data()), 4.0);
  // A passer-by: the first tenth of the bytes (a few regions) changes by 200; the median does not.
  for (std::size_t i = 0; i < size / 10; ++i) b[i] = 255;
  EXPECT_DOUBLE_EQ(regions.difference(a.data(), b.data()), 4.0);
}

INSTANTIATE_TEST_SUITE_P(FrontEnds, DescriptorRegionsTest,
                         ::testing::Values(DescriptorParams{}, testing_support::thumbnailParams()),
                         [](const auto& info) { return info.param.type; });

}  // namespace
}  // namespace mrs_vpr

#include "mrs_vpr/descriptor_regions.hpp"

#include <cmath>
#include <cstddef>
#include <cstdlib>

#include "mrs_vpr/median.hpp"

namespace mrs_vpr {

DescriptorRegions::DescriptorRegions(const DescriptorParams& front_end) {
  front_end.validate();
  const int size = front_end.descriptorSize();
  region_of_.resize(static_cast<std::size_t>(size));
  int regions = 0;
  if (front_end.isHog()) {
    const int block = 4 * front_end.hog_bins;
    for (int i = 0; i < size; ++i) region_of_[static_cast<std::size_t>(i)] = i / block;
    regions = size / block;
  } else {
    const int side = front_end.patch_size;
    const int across = front_end.image_width / side;
    for (int i = 0; i < size; ++i) {
      region_of_[static_cast<std::size_t>(i)] =
          (i / front_end.image_width / side) * across + (i % front_end.image_width) / side;
    }
    regions = across * (front_end.image_height / side);
  }
  region_size_.assign(static_cast<std::size_t>(regions), 0.0);
  for (int region : region_of_) region_size_[static_cast<std::size_t>(region)] += 1.0;
  for (int i = 0; i < size; ++i) {
    if (i == 0 || region_of_[static_cast<std::size_t>(i)] != region_of_[static_cast<std::size_t>(i - 1)]) {
      runs_.push_back({i, i + 1, region_of_[static_cast<std::size_t>(i)]});
    } else {
      runs_.back().end = i + 1;
    }
  }
}

template <typename Value>
double DescriptorRegions::medianRegionDifference(const std::uint8_t* a, const Value* b) const {
  thread_local std::vector<double> means;
  means.assign(region_size_.size(), 0.0);
  for (std::size_t i = 0; i < region_of_.size(); ++i) {
    means[static_cast<std::size_t>(region_of_[i])] += std::fabs(static_cast<double>(a[i]) - b[i]);
  }
  for (std::size_t r = 0; r < means.size(); ++r) means[r] /= region_size_[r];
  return upperMedian(means);
}

double DescriptorRegions::difference(const std::uint8_t* a, const float* b) const {
  return medianRegionDifference(a, b);
}

double DescriptorRegions::difference(const std::uint8_t* a, const std::uint8_t* b) const {
  // As medianRegionDifference, in whole numbers (the same sums, exactly) over runs of one region's bytes,
  // which the compiler vectorises: the rules that compare keyframes make hundreds of these a question.
  thread_local std::vector<int> sums;
  sums.assign(region_size_.size(), 0);
  for (const Run& run : runs_) {
    int sum = 0;
    for (int i = run.begin; i < run.end; ++i) sum += std::abs(static_cast<int>(a[i]) - static_cast<int>(b[i]));
    sums[static_cast<std::size_t>(run.region)] += sum;
  }
  thread_local std::vector<double> means;
  means.resize(sums.size());
  for (std::size_t r = 0; r < sums.size(); ++r) means[r] = sums[r] / region_size_[r];
  return upperMedian(means);
}

}  // namespace mrs_vpr

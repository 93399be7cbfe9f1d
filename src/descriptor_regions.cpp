#include "mrs_vpr/descriptor_regions.hpp"

#include <cmath>
#include <cstddef>
#include <cstdlib>

#include "mrs_vpr/median.hpp"

namespace mrs_vpr {

DescriptorRegions::DescriptorRegions(const DescriptorParams& front_end) {
  front_end.validate();
  const int size = front_end.descriptorSize();
  std::vector<int> region_of(static_cast<std::size_t>(size));  // per descriptor byte, its region
  int regions = 0;
  if (front_end.isHog()) {
    const int block = 4 * front_end.hog_bins;
    for (int i = 0; i < size; ++i) region_of[static_cast<std::size_t>(i)] = i / block;
    regions = size / block;
  } else {
    const int side = front_end.patch_size;
    const int across = front_end.image_width / side;
    for (int i = 0; i < size; ++i) {
      region_of[static_cast<std::size_t>(i)] =
          (i / front_end.image_width / side) * across + (i % front_end.image_width) / side;
    }
    regions = across * (front_end.image_height / side);
  }
  region_size_.assign(static_cast<std::size_t>(regions), 0.0);
  for (int region : region_of) region_size_[static_cast<std::size_t>(region)] += 1.0;
  for (int i = 0; i < size; ++i) {
    const int region = region_of[static_cast<std::size_t>(i)];
    if (runs_.empty() || runs_.back().region != region) {
      runs_.push_back({i, i + 1, region});
    } else {
      runs_.back().end = i + 1;
    }
  }
}

double DescriptorRegions::medianRegionMean(std::vector<double>& sums) const {
  for (std::size_t r = 0; r < sums.size(); ++r) sums[r] /= region_size_[r];
  return upperMedian(sums);
}

double DescriptorRegions::difference(const std::uint8_t* a, const float* b) const {
  thread_local std::vector<double> sums;
  sums.assign(region_size_.size(), 0.0);
  for (const Run& run : runs_) {
    double& sum = sums[static_cast<std::size_t>(run.region)];
    for (int i = run.begin; i < run.end; ++i) sum += std::fabs(static_cast<double>(a[i]) - b[i]);
  }
  return medianRegionMean(sums);
}

double DescriptorRegions::difference(const std::uint8_t* a, const std::uint8_t* b) const {
  // In whole numbers (the same sums, exactly), which the compiler vectorises over a run: the rules that
  // compare keyframes make hundreds of these a question.
  thread_local std::vector<double> sums;
  sums.assign(region_size_.size(), 0.0);
  for (const Run& run : runs_) {
    int sum = 0;
    for (int i = run.begin; i < run.end; ++i) sum += std::abs(static_cast<int>(a[i]) - static_cast<int>(b[i]));
    sums[static_cast<std::size_t>(run.region)] += sum;
  }
  return medianRegionMean(sums);
}

}  // namespace mrs_vpr

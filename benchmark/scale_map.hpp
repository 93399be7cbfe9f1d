#pragma once

// The map-scale benchmark's maps: the Nordland summer half, as the true places, at a seeded position
// among distractors made of the shared real frames, each segment changed by its own look.

#include <cstdint>
#include <random>
#include <string>

#include <opencv2/core.hpp>

#include "map_scale_options.hpp"

namespace mrs_vpr {
namespace benchmark {

/// A changed frame: turned (upside down, or by 180 degrees) or not, and moved by a shift, gain,
/// offset and noise.
class Augmenter {
 public:
  explicit Augmenter(std::uint64_t seed) : rng_(seed) {}

  struct Look {
    int flip = 2;  ///< cv::flip's code (0 upside down, -1 both axes), or 2 for none.
    double dx = 0, dy = 0, gain = 1, offset = 0;
  };

  /// A seeded look with `flip` (see Look::flip).
  Look nextLook(int flip);
  /// `image` changed by `look`, with seeded noise.
  cv::Mat apply(const cv::Mat& image, const Look& look);

 private:
  std::mt19937_64 rng_;
};

/// Writes the map of `frames` frames to `path` + ".part" (renamed by the caller once complete): the
/// summer frames at a seeded offset, among distractor segments of 200 to 800 frames of the shared
/// data, each played forwards or backwards with its own look. Winter, the queries' season, is left
/// out, and Nordland distractors are turned, so that no distractor shows a query's place. Returns the
/// index of the first true place.
long long writeScaleMap(const std::string& path, long long frames, const MapScaleOptions& options);

}  // namespace benchmark
}  // namespace mrs_vpr

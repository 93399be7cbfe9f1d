#pragma once

#include <cstdint>
#include <vector>

#include <opencv2/core.hpp>

namespace mrs_vpr {

/// Settings of a generated route; defaults give a small, quick route.
struct SyntheticRouteParams {
  int reference_frames = 400;   ///< Frames of the first traversal (speed 1 place per frame).
  int query_frames = 300;       ///< Frames of the second traversal.
  int image_width = 128;        ///< Size of the generated bgr8 frames [px].
  int image_height = 64;
  double speed_min = 0.8;       ///< The second traversal's speed varies in [speed_min, speed_max]
  double speed_max = 1.2;       ///< places per frame, smoothly.
  double start_place = 0.0;     ///< Place where the second traversal starts.
  double noise_std = 6.0;       ///< Gaussian pixel noise of the second traversal [grey levels].
  std::uint64_t seed = 7;       ///< Same seed, same route.

  /// Throws std::invalid_argument naming the bounds when a count, a size or the speeds are out of them.
  void validate() const;
};

/// Two traversals of one route with known alignment; the second has another appearance.
struct SyntheticRoute {
  std::vector<cv::Mat> reference;         ///< bgr8 frames.
  std::vector<cv::Mat> query;             ///< bgr8 frames: illumination, contrast, blur, noise, shifts.
  std::vector<int> query_to_reference;    ///< Reference frame showing the place of each query frame.
};

/// Throws std::invalid_argument when the second traversal would leave the route or sizes are invalid.
SyntheticRoute generateSyntheticRoute(const SyntheticRouteParams& params);

}  // namespace mrs_vpr

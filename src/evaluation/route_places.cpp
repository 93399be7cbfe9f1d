#include "mrs_vpr/evaluation/route_places.hpp"

#include <stdexcept>
#include <string>

#include "mrs_vpr/descriptor.hpp"
#include "mrs_vpr/evaluation/evaluation.hpp"

namespace mrs_vpr {
namespace {

/// A route image in grey (the types toGrey takes): a header that shares the converted data, if any.
cv::Mat grey(const cv::Mat& image) {
  cv::Mat buffer;
  return toGrey(image, ChannelOrder::kBgr, buffer);
}

/// Mean absolute grey-level difference of each pair of consecutive images.
std::vector<double> steps(const std::vector<cv::Mat>& route) {
  std::vector<double> differences;
  cv::Mat previous = grey(route.front());
  for (std::size_t i = 1; i < route.size(); ++i) {
    if (route[i].size() != route.front().size()) {
      throw std::invalid_argument("route image " + std::to_string(i) + " differs in size from the first");
    }
    const cv::Mat current = grey(route[i]);
    differences.push_back(cv::norm(current, previous, cv::NORM_L1) / static_cast<double>(current.total()));
    previous = current;
  }
  return differences;
}

}  // namespace

std::vector<int> routePlaces(const std::vector<const std::vector<cv::Mat>*>& traversals, double standing_share) {
  if (!(standing_share >= 0.0 && standing_share < 1.0)) {
    throw std::invalid_argument("standing share must be in [0, 1), got " + std::to_string(standing_share));
  }
  if (traversals.empty() || traversals.front() == nullptr || traversals.front()->empty()) {
    throw std::invalid_argument("route places need at least one traversal with images");
  }
  const std::size_t length = traversals.front()->size();
  std::vector<bool> standing(length - 1, true);
  for (const std::vector<cv::Mat>* traversal : traversals) {
    if (traversal == nullptr || traversal->size() != length) {
      throw std::invalid_argument("every traversal must have the route's " + std::to_string(length) + " images");
    }
    if (length < 2) break;
    const std::vector<double> differences = steps(*traversal);
    const double threshold = standing_share * median(differences);
    for (std::size_t i = 0; i < differences.size(); ++i) standing[i] = standing[i] && differences[i] < threshold;
  }
  std::vector<int> places(length, 0);
  for (std::size_t i = 1; i < length; ++i) places[i] = places[i - 1] + (standing[i - 1] ? 0 : 1);
  return places;
}

std::vector<int> placesOf(const std::vector<int>& route_frames, const std::vector<int>& places) {
  std::vector<int> result;
  result.reserve(route_frames.size());
  for (const int frame : route_frames) {
    if (frame < 0 || frame >= static_cast<int>(places.size())) {
      throw std::out_of_range("route frame " + std::to_string(frame) + " is outside the route's " +
                              std::to_string(places.size()) + " frames");
    }
    result.push_back(places[static_cast<std::size_t>(frame)]);
  }
  return result;
}

}  // namespace mrs_vpr

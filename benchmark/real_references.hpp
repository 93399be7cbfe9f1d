#pragma once

// The real-data benchmark's maps: the shared data's frames, and references built from them whose
// every frame knows the route frame it shows (or that it is a distractor).

#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "mrs_vpr/descriptor.hpp"
#include "mrs_vpr/descriptor_sequence.hpp"

namespace mrs_vpr {
namespace benchmark {

/// Real frames of the route and of the corridor, as loaded (BGR or grayscale).
struct RealFrames {
  std::vector<cv::Mat> summer;
  std::vector<cv::Mat> winter;
  std::vector<cv::Mat> corridor;
};

/// Reads nordland/{summer,winter} and corridor/{ref,query} (both into `corridor`) from `data`.
RealFrames loadRealFrames(const std::string& data);

/// A reference: descriptors, and for each of its frames the route frame it shows (-1 for distractors).
struct Reference {
  std::string name;
  DescriptorSequence descriptors;
  std::vector<int> route_frame;
};

/// The summer frames [begin, end) as true places, then (with `distractors`, the "9k" reference) real
/// distractors derived from the same frames (both seasons mirrored, summer backwards, winter mirrored
/// and backwards) and the corridor frames. Shows its progress on stderr.
Reference buildReference(const RealFrames& frames, const DescriptorExtractor& extractor, int begin, int end,
                         bool distractors, const std::string& name);

/// Summer frames [begin, end) of `summer` as a map of their own, each the true place of its route frame.
Reference stretchOf(const DescriptorSequence& summer, int begin, int end);

/// The descriptors of `frames`, in order.
DescriptorSequence describe(const std::vector<cv::Mat>& frames, const DescriptorExtractor& extractor);

/// The reference indices showing route frame `frame`; empty when it is not in the map.
std::vector<int> truthOf(const Reference& reference, int frame);

}  // namespace benchmark
}  // namespace mrs_vpr

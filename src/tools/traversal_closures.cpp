#include "traversal_closures.hpp"

#include <algorithm>
#include <stdexcept>
#include <utility>

#include "mrs_vpr/parameters.hpp"

namespace mrs_vpr {
namespace tools {

namespace {

Parameters defaultsWith(const DescriptorParams& front_end) {
  Parameters params;
  params.descriptor = front_end;
  return params;
}

/// The node's defaults, with no cap on the map: a map too large for a node is still the user's map.
RecognizerParams unboundedKeyframedAt(double min_appearance_change) {
  RecognizerParams recognizer;
  recognizer.max_frames = 0;
  recognizer.min_appearance_change = min_appearance_change;
  return recognizer;
}

}  // namespace

TraversalClosures::TraversalClosures(const DescriptorParams& front_end, double min_appearance_change, int map_frames)
    : recognizer_(defaultsWith(front_end), unboundedKeyframedAt(min_appearance_change)),
      map_(recognizer_.prepareMap(map_frames)) {}

void TraversalClosures::addMapFrame(const cv::Mat& descriptor, Stamp stamp) {
  if (!map_) throw std::logic_error("TraversalClosures: the map's frames come before the traversal's");
  map_->append(descriptor, stamp);
}

void TraversalClosures::startTraversal(const std::vector<PlaceLink>& map_links, const std::vector<int>& drive_starts) {
  if (!map_) throw std::logic_error("TraversalClosures: the traversal has started already");
  map_->linkPlaces(map_links);
  map_->markDriveStarts(drive_starts);
  recognizer_.install(std::move(*map_));
  map_.reset();
  recognizer_.keepUnsavedLinks();
  beginDrive();  // The traversal's keyframes are another drive's.
}

void TraversalClosures::startDrive(const std::vector<PlaceLink>& links) {
  if (map_) throw std::logic_error("TraversalClosures: startTraversal() comes before the traversal's drives");
  recognizer_.linkPlaces(links);
  beginDrive();
}

void TraversalClosures::beginDrive() {
  recognizer_.markDriveStart(recognizer_.size());
  // As the node's continuous mode asks: once the map holds enough frames to search, and the test
  // sequence holds keyframes of this drive only.
  const int length = recognizer_.parameters().sequence.sequence_length;
  const long long after_drive_start = static_cast<long long>(recognizer_.size()) + length;
  first_question_size_ =
      static_cast<int>(std::max<long long>(recognizer_.fewestFramesForRecent(length), after_drive_start));
}

void TraversalClosures::addKeyframe(const cv::Mat& descriptor, Stamp stamp) {
  if (map_) throw std::logic_error("TraversalClosures: startTraversal() comes before the traversal's keyframes");
  recognizer_.addDescriptor(descriptor, stamp);
  recognizer_.flush();
  if (recognizer_.size() < first_question_size_) return;
  ++questions_;
  if (recognizer_.matchRecent(recognizer_.parameters().sequence.sequence_length).match.accepted) ++closures_;
}

}  // namespace tools
}  // namespace mrs_vpr

#pragma once

// Loop closures over a traversal that build_map writes into a map: the place links a node mapping
// the same frames in continuous mode would have made (place_links.hpp).

#include <optional>
#include <vector>

#include <opencv2/core.hpp>

#include "mrs_vpr/descriptor.hpp"
#include "mrs_vpr/place_links.hpp"
#include "mrs_vpr/place_recognizer.hpp"
#include "mrs_vpr/stamp.hpp"

namespace mrs_vpr {
namespace tools {

/**
 * Closes loops over a traversal as the node's continuous mode does at its defaults: after each new
 * keyframe, the newest `sequence_length` keyframes are matched against the map's older frames, and an
 * accepted answer links the keyframe it localised to the place it names.
 *
 * Without these links, a stretch held twice, by two traversals written one after the other, is its own
 * rival: a node serving the map refuses the next visit's right answers there (doc/limitations.md).
 *
 * The map's frames and links come first (addMapFrame(), then startTraversal()); a test sequence holds
 * keyframes of the traversal only, as the node's holds those of its own run. Holds the map in memory.
 */
class TraversalClosures {
 public:
  /// For a map of `map_frames` frames before the traversal, described by `front_end` and keyframed at
  /// `min_appearance_change` (the node's ~min_appearance_change, by which it also tells repeated views).
  TraversalClosures(const DescriptorParams& front_end, double min_appearance_change, int map_frames);

  /// A frame the map held before the traversal, in map order.
  void addMapFrame(const cv::Mat& descriptor, Stamp stamp);
  /// The map's own place links and drive starts (drive_starts.hpp), once its frames are added; the
  /// traversal's keyframes follow, as another drive.
  void startTraversal(const std::vector<PlaceLink>& map_links, const std::vector<int>& drive_starts);
  /// A keyframe of the traversal (in map order after the map's frames): asks where its newest
  /// keyframes are, once the map holds enough older frames to search.
  void addKeyframe(const cv::Mat& descriptor, Stamp stamp);
  /// Another drive begins with the next keyframe (a map's drives linked in one pass): its questions,
  /// like the traversal's first, wait for a whole test sequence of its own keyframes, and the place
  /// links known by then are `links`.
  void startDrive(const std::vector<PlaceLink>& links);

  /// The links accepted answers made since the last call, to store with the frames they name.
  std::vector<PlaceLink> takeLinks() { return recognizer_.takeUnsavedLinks(); }
  /// Questions asked and answers accepted so far.
  int questions() const { return questions_; }
  int closures() const { return closures_; }

 private:
  /// The next keyframe begins a drive: no question before a test sequence holds its keyframes only.
  void beginDrive();

  PlaceRecognizer recognizer_;
  std::optional<PlaceRecognizer::PreparedMap> map_;  // the map's frames, until startTraversal()
  int first_question_size_ = 0;  // the map's size at the traversal's first question
  int questions_ = 0;
  int closures_ = 0;
};

}  // namespace tools
}  // namespace mrs_vpr

#pragma once

// The real-data benchmark's camera drives: real frames replayed as a camera-only vehicle records them
// (evaluation/camera_drive.hpp), through the node's continuous mode at its defaults and through the
// evaluator's per-frame protocol.

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "mrs_vpr/evaluation/evaluation.hpp"
#include "mrs_vpr/parameters.hpp"

namespace mrs_vpr {
namespace benchmark {

/// What the drives are made of and how they are replayed.
struct CameraDriveInput {
  const std::vector<cv::Mat>* summer = nullptr;  ///< The map drive's route: summer frames [0, route_frames).
  const std::vector<cv::Mat>* winter = nullptr;  ///< The revisit's route: winter frames [part_begin, part_end).
  int route_frames = 0;
  int part_begin = 0;
  int part_end = 0;
  std::vector<std::string> methods;
  DescriptorParams descriptor;  ///< The front end.
  std::uint64_t seed = 42;      ///< The map drive's seed; the revisit's is seed + 1.
  SequenceParams sequence;      ///< The sequence search (the node's defaults unless set).
  /// Keyframes by appearance change (RecognizerParams::min_appearance_change; the node's default unless set).
  double min_appearance_change = RecognizerParams{}.min_appearance_change;
  /// Continuous mode localises every keyframe that came since its last question, as the node does;
  /// false: only the newest.
  bool each_keyframe = true;
};

/// A row of the evaluator's per-frame protocol: printed and kept as the benchmark's other rows are.
using PerFrameRow = std::function<void(const std::string& setting, const std::string& method,
                                       const EvaluationSummary& summary, int reference_frames, int sequence_length)>;

/**
 * The map drive (summer, whole route) at 30 Hz and the revisit (winter, the reported part) at 10 Hz,
 * each with make_drive's defaults (8 stops of 30-90 frames, a half- and a double-speed stretch of 100
 * route frames; stretches of a quarter of a route shorter than 400 frames), go
 * frame by frame into one PlaceRecognizer at the node's defaults but for the input's settings
 * (keyframes by appearance), which
 * every second, as the node's continuous mode, asks where its newest keyframes lie (matchRecent of
 * the node's continuous-mode length) when a keyframe came since the last question. Prints a table per
 * method and hands its rows to `add` for --json. Then the evaluator's per-frame protocol on the two
 * drives (mrs_vpr_eval --reference MAP --query REVISIT --ground-truth from make_drive), through `per_frame`.
 */
void runCameraDrives(const CameraDriveInput& input, const std::function<void(const std::vector<nlohmann::json>&)>& add,
                     const PerFrameRow& per_frame);

}  // namespace benchmark
}  // namespace mrs_vpr

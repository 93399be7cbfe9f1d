#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "mrs_vpr/evaluation/evaluation.hpp"

namespace mrs_vpr {

/**
 * How a camera-only vehicle drives a route: where it stops and for how long, where it goes at half and
 * at double speed, and what a standing camera adds to a view. Noise, vibration and the passer-by are
 * given at the 64 px width of OpenSeqSLAM's thumbnails and scaled with the width of the images.
 */
struct CameraDriveSettings {
  std::uint64_t seed = 1;    ///< Same seed, same drive: places, lengths, noise, passers-by.
  int stops = 8;             ///< Stops along the route (none inside the speed stretches).
  int stop_frames_min = 30;  ///< Frames of the shortest stop, after the frame where the vehicle stops.
  int stop_frames_max = 90;  ///< Frames of the longest stop.
  int slow_frames = 100;     ///< Route frames of the half-speed stretch (each shown twice); 0 = none.
  int fast_frames = 100;     ///< Route frames of the double-speed stretch (every other left out); 0 = none.
  double noise_std = 0.5;    ///< Sensor noise of a standing camera [grey levels at 64 px width].
  double vibration = 0.5;    ///< Largest shift of a standing camera [px at 64 px width], in x and in y.
  double gain = 0.02;        ///< Largest change of a standing camera's gain (0.02: within +-2%).

  /// Throws std::invalid_argument naming the first setting out of range.
  void validate() const;
};

/// What a drive frame shows.
enum class DriveFrameKind {
  kMoving,    ///< The route frame itself.
  kStopped,   ///< The vehicle stands: the route frame with noise, vibration, gain and a passer-by.
  kSlowCopy,  ///< Half speed: the route frame again, with noise, vibration and gain.
};

/// "moving", "stopped", "slow".
std::string toString(DriveFrameKind kind);
/// Parses toString's words; throws std::invalid_argument otherwise.
DriveFrameKind parseDriveFrameKind(const std::string& text);

/// One frame of a drive.
struct DriveFrame {
  int route_frame = 0;  ///< The route frame it shows.
  DriveFrameKind kind = DriveFrameKind::kMoving;
  int stop = -1;        ///< Stopped frames: which stop (0-based, in drive order); else -1.
  int stop_frame = 0;   ///< Stopped frames: index within the stop, 0 .. stop_length - 1.
  int stop_length = 0;  ///< Stopped frames: frames of the stop.
};

/**
 * A drive of a route of `route_frames` frames (in route order), planned from the settings' seed:
 * every route frame in order, except that
 *   - after each of `stops` route frames (one in each equal share of the frames outside the speed
 *     stretches) the vehicle stands for stop_frames_min..stop_frames_max frames;
 *   - in the half-speed stretch each route frame is followed by a noisy copy of itself;
 *   - in the double-speed stretch every other route frame is left out.
 * The two stretches lie at seeded places that do not overlap. render() draws a frame from its route
 * frame's image; a stopped or slow frame is never an exact copy of it.
 *
 * A passer-by (a dark upright figure, 1/10 of the width and 1/2 of the height of the view) crosses
 * each stop's view from one side to the other, entering at its first frame and leaving after its last.
 */
class CameraDrive {
 public:
  /// Throws std::invalid_argument when a setting is out of range or the route is too short for the
  /// stretches and stops.
  CameraDrive(int route_frames, const CameraDriveSettings& settings = CameraDriveSettings{});

  const std::vector<DriveFrame>& frames() const { return frames_; }
  int size() const { return static_cast<int>(frames_.size()); }
  /// Frames of the route it drives.
  int routeLength() const { return route_frames_; }
  /// First route frame of the half-speed and of the double-speed stretch (-1 when there is none).
  int slowBegin() const { return slow_begin_; }
  int fastBegin() const { return fast_begin_; }
  const CameraDriveSettings& settings() const { return settings_; }

  /**
   * Drive frame `index` drawn from `route_image`, the image of its route frame (8-bit, 1, 3 or 4
   * channels). Deterministic: the same frame of the same drive is the same image whenever it is drawn.
   * Throws std::invalid_argument for another image type and std::out_of_range for a bad index.
   */
  cv::Mat render(int index, const cv::Mat& route_image) const;

 private:
  /// Where a stop's passer-by is and how it looks.
  struct PasserBy {
    bool left_to_right = true;
    double darkness = 0.0;  ///< Its grey level as a fraction of white.
    double foot = 1.0;      ///< Where its feet are, as a fraction of the height from the top.
  };

  CameraDriveSettings settings_;
  std::vector<DriveFrame> frames_;
  std::vector<PasserBy> passers_by_;  ///< One per stop.
  int route_frames_ = 0;
  int slow_begin_ = -1;
  int fast_begin_ = -1;
};

/// The route frame of each of `frames`.
std::vector<int> routeFramesOf(const std::vector<DriveFrame>& frames);

/// Every frame of a drive of `route` (the route's images, in route order; see CameraDrive::render).
std::vector<cv::Mat> renderDrive(const CameraDrive& drive, const std::vector<cv::Mat>& route);

/**
 * Ground truth between two drives of one route, for mrs_vpr_eval: query drive frame i -> the reference
 * drive frames whose route frame is within `route_tolerance` route frames of its own. A route frame
 * that the reference drive left out (double speed) is then still found beside it.
 * Throws std::invalid_argument when route_tolerance < 0.
 */
GroundTruth driveGroundTruth(const std::vector<int>& reference_route_frames,
                             const std::vector<int>& query_route_frames, int route_tolerance);

}  // namespace mrs_vpr

// The node's frames: image and compressed-image callbacks, their stamps, the keyframe policies (time,
// stride, travel on tf, appearance change), the counts of frames skipped, dropped or missing, and a silent camera.

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <mutex>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>

#include "mrs_vpr/node/compressed_image.hpp"
#include "mrs_vpr/node/image_conversion.hpp"
#include "mrs_vpr/node/place_recognition_node.hpp"
#include "mrs_vpr/node/robot_position.hpp"
#include "mrs_vpr/node/ros_stamp.hpp"
#include "node_warnings.hpp"

namespace mrs_vpr {
namespace node {
namespace {

/// Shortest pause [s] between one image callback's end and the next one's start that is taken for
/// an idle node, however short the callbacks: roscpp dispatches a queued message within microseconds.
constexpr double kQueueDispatch = 0.001;

/// Runs `action` when the scope it guards ends, by any return or exception.
template <typename Action>
class ScopeExit {
 public:
  explicit ScopeExit(Action action) : action_(std::move(action)) {}
  ~ScopeExit() { action_(); }
  ScopeExit(const ScopeExit&) = delete;
  ScopeExit& operator=(const ScopeExit&) = delete;

 private:
  Action action_;
};

}  // namespace

void PlaceRecognitionNode::imageCallback(const sensor_msgs::ImageConstPtr& message) {
  addFrame(message->header, [&] { return fromImageMessage(*message, message); },
           [&] {
             return std::to_string(message->width) + " x " + std::to_string(message->height) + ", " +
                    message->encoding;
           });
}

void PlaceRecognitionNode::compressedImageCallback(const sensor_msgs::CompressedImageConstPtr& message) {
  addFrame(
      message->header, [&] { return decodeCompressedImage(*message); },
      [&] { return "format " + inQuotes(message->format) + ", " + std::to_string(message->data.size()) + " bytes"; });
}

template <typename Convert, typename Summary>
void PlaceRecognitionNode::addFrame(const std_msgs::Header& header, const Convert& convert, const Summary& summary) {
  ++frames_received_;
  const double callback_start = steadySeconds();
  camera_silence_.imageArrived(callback_start);
  countMissingFrames(header.seq, header.stamp.toSec(), callback_start);
  // Whatever path this frame takes, the next callback must know when this one began and ended.
  const ScopeExit ended([this, callback_start] {
    std::lock_guard<std::mutex> lock(state_mutex_);
    image_callback_start_ = callback_start;
    image_callback_end_ = steadySeconds();
  });
  const std::optional<Stamp> stamp = frameStamp(header);
  if (!stamp) return;
  // The keyframe policies compare intervals, for which seconds in a double are precise enough.
  const double seconds = stamp->seconds();
  std::optional<Eigen::Vector3d> position;
  if (!wantedByPolicies(header, seconds, position)) return;

  // The expensive part runs without any lock.
  const auto start = std::chrono::steady_clock::now();
  cv::Mat descriptor;
  try {
    const ImageFrame frame = convert();
    descriptor = recognizer_.describe(frame.image(), frame.order);
  } catch (const std::exception& error) {  // std::invalid_argument, and cv::Exception or bad_alloc
    ++frames_failed_;
    {
      std::lock_guard<std::mutex> lock(state_mutex_);
      keyframe_policy_.skip(seconds);
    }
    // Each kind of problem once a period: a second kind within it would be hidden by a throttle.
    if (frame_failure_warning_.allows(kindOf(error.what()), steadySeconds())) {
      ROS_WARN("mrs_vpr: dropping a frame from %s (%s): %s", imageTopic().c_str(), summary().c_str(), error.what());
    }
    return;
  }
  if (!admit(descriptor, *stamp, header, seconds)) return;

  ++map_version_;
  std::optional<double> stepped_back_from;
  {
    std::lock_guard<std::mutex> lock(state_mutex_);
    stepped_back_from = keyframe_policy_.steppedBackFrom(seconds);
    keyframe_policy_.keep(seconds);
    standing_frames_.keyframe(*stamp);
    if (position) travel_policy_.keep(*position);
    camera_frame_id_ = header.frame_id;
    const double elapsed_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    frame_time_total_ms_ += elapsed_ms;
    ++frames_timed_;
    frame_time_max_ms_ = std::max(frame_time_max_ms_, elapsed_ms);
  }
  if (stepped_back_from && !params_.fixedMap()) {
    // Not refused: the frames are real, and a clock may be reset. But a bag played twice maps its route
    // twice, and the second pass then finds the first as loop closures.
    ROS_WARN_THROTTLE(kWarningPeriod,
                      "mrs_vpr: image stamps went back from %.3f to %.3f s (a bag played again, a clock reset): "
                      "the new keyframes join the map after the others, and closures to frames recorded at the "
                      "same time are not accepted; call ~reset first to map anew",
                      *stepped_back_from, seconds);
  }
}

std::optional<Stamp> PlaceRecognitionNode::frameStamp(const std_msgs::Header& header) {
  Stamp stamp;
  try {
    stamp = stampOf(header.stamp);  // Exact: a double cannot hold every ROS time.
  } catch (const std::invalid_argument& error) {  // an unnormalised stamp beyond ROS's range
    ++frames_failed_;
    ROS_WARN_THROTTLE(kWarningPeriod, "mrs_vpr: dropping a frame from %s: header.stamp %u s + %u ns: %s",
                      imageTopic().c_str(), header.stamp.sec, header.stamp.nsec, error.what());
    return std::nullopt;
  }
  if (stamp.isZero()) {
    stamp = stampOf(ros::Time::now());  // unstamped camera: the arrival time is the best we have
  }
  if (stamp.isZero()) {
    // Simulated time before the first /clock message: a keyframe of no time would join every closure
    // to stamp 0, which ~loop_closure_stamps cannot send and a SLAM back end cannot place.
    ++frames_failed_;
    ROS_WARN_THROTTLE(kWarningPeriod,
                      "mrs_vpr: dropping a frame from %s: it has no stamp (header.stamp 0), and the clock has not "
                      "started (/use_sim_time is true and nothing has published /clock yet)",
                      imageTopic().c_str());
    return std::nullopt;
  }
  return stamp;
}

bool PlaceRecognitionNode::wantedByPolicies(const std_msgs::Header& header, double seconds,
                                            std::optional<Eigen::Vector3d>& position) {
  {
    std::lock_guard<std::mutex> lock(state_mutex_);
    if (!keyframe_policy_.wants(seconds)) {
      keyframe_policy_.skip(seconds);
      ++frames_skipped_;
      return false;
    }
  }
  if (!travel_policy_.enabled()) return true;
  std::string error;
  position = robotPosition(header.stamp, error);
  bool travelled = false;
  {
    std::lock_guard<std::mutex> lock(state_mutex_);
    travelled = position && travel_policy_.wants(*position);
    if (!travelled) keyframe_policy_.skip(seconds);
  }
  if (!position) {
    ++frames_without_pose_;
    ROS_WARN_THROTTLE(kWarningPeriod, "mrs_vpr: skipping a frame from %s: no pose of %s in %s at its stamp (%s)",
                      imageTopic().c_str(), params_.base_frame.c_str(), params_.odom_frame.c_str(), error.c_str());
    return false;
  }
  if (!travelled) ++frames_skipped_;
  return travelled;
}

bool PlaceRecognitionNode::admit(const cv::Mat& descriptor, Stamp stamp, const std_msgs::Header& header,
                                 double seconds) {
  // Keyframes by travel are chosen before; otherwise the recognizer keeps a frame whose view has changed.
  // A fixed map stays as it is: the keyframes join the recognizer's trail, which questions ask about.
  FrameAdmission admission = FrameAdmission::kAdmitted;
  try {
    if (params_.fixedMap()) {
      admission = travel_policy_.enabled() ? recognizer_.addToTrail(descriptor, stamp)
                                           : recognizer_.offerToTrail(descriptor, stamp);
    } else {
      admission = travel_policy_.enabled() ? map_->add(descriptor, stamp, header.frame_id, header.seq)
                                           : map_->offer(descriptor, stamp, header.frame_id, header.seq);
    }
  } catch (const std::exception& error) {  // std::bad_alloc: no memory left for the map
    ++frames_dropped_;
    ROS_ERROR_THROTTLE(kWarningPeriod, "mrs_vpr: could not add a keyframe to the map (%s); dropping frames",
                       error.what());
    return false;
  }
  switch (admission) {
    case FrameAdmission::kTooSimilar:
    case FrameAdmission::kSeenRecently: {
      ++frames_too_similar_;
      std::lock_guard<std::mutex> lock(state_mutex_);
      keyframe_policy_.skip(seconds);
      // Only the newest keyframe's own view stands at its place; one like an older keyframe, or one on its
      // way from the newest, may not.
      if (admission == FrameAdmission::kTooSimilar && recognizer_.lastFrameStood()) standing_frames_.tooSimilar(stamp);
      return false;
    }
    case FrameAdmission::kMapFull:
      ++frames_dropped_;
      // Continuous mode asks about new map keyframes only: once the map is full it asks nothing more.
      ROS_WARN_THROTTLE(kWarningPeriod,
                        "mrs_vpr: the reference map is full (~max_frames = %d); dropping frames%s",
                        params_.recognizer.max_frames,
                        params_.auto_query_period > 0.0 ? ", and continuous mode localises no new frame" : "");
      return false;
    case FrameAdmission::kPendingFull:
      ++frames_dropped_;
      ROS_WARN_THROTTLE(kWarningPeriod,
                        "mrs_vpr: %d keyframes wait for a long query (~max_pending_frames); dropping frames",
                        params_.recognizer.max_pending_frames);
      return false;
    case FrameAdmission::kAdmitted:
      break;
  }
  return true;
}

std::string PlaceRecognitionNode::unknownTfFrame() const {
  for (const std::string* frame : {&params_.odom_frame, &params_.base_frame}) {
    if (!tf_buffer_->_frameExists(*frame)) return *frame;
  }
  return "";
}

std::optional<Eigen::Vector3d> PlaceRecognitionNode::robotPosition(const ros::Time& stamp, std::string& error) const {
  // A frame that no transform has named is waited for once, as tf may start after the camera. While
  // it stays unknown, later frames fail at once: waiting ~tf_timeout for each would overflow the
  // image queue and hide the real problem behind lost frames.
  const std::string unknown = unknownTfFrame();
  const auto noSuchFrame = [&](const std::string& frame) {
    return "frame '" + frame + "' does not exist: no transform on /tf or /tf_static has named it (~odom_frame " +
           params_.odom_frame + ", ~base_frame " + params_.base_frame + ")";
  };
  if (!unknown.empty() && waited_for_unknown_tf_frame_) {
    error = noSuchFrame(unknown);
    return std::nullopt;
  }
  // A zero stamp (an unstamped camera) asks for the newest pose.
  std::optional<Eigen::Vector3d> position = robotPositionFrom(
      [&] {
        return tf_buffer_->lookupTransform(params_.odom_frame, params_.base_frame, stamp,
                                           ros::Duration(params_.tf_timeout));
      },
      error);
  const std::string still_unknown = position ? "" : unknownTfFrame();
  if (!still_unknown.empty()) {
    waited_for_unknown_tf_frame_ = true;
    error = noSuchFrame(still_unknown);
  }
  return position;
}

void PlaceRecognitionNode::countMissingFrames(std::uint32_t seq, double stamp, double callback_start) {
  std::uint64_t missing = 0;
  {
    std::lock_guard<std::mutex> lock(state_mutex_);
    // roscpp hands a queued message to the callback at once. A node that keeps up waits for each
    // message longer than it works on one; a node that falls behind finds the next one waiting,
    // after no more than freeing the last (which for a large image takes a millisecond or two).
    const double pause = callback_start - image_callback_end_;
    const double work = image_callback_end_ - image_callback_start_;
    const bool waited = image_callback_end_ > 0.0 && pause < std::max(kQueueDispatch, work);
    missing = sequence_gaps_.record(seq, stamp, waited);
  }
  if (missing == 0) {
    return;
  }
  // Lost before this callback, where nothing else would count them: received, and failed.
  frames_received_ += missing;
  frames_failed_ += missing;
  ROS_WARN_THROTTLE(kWarningPeriod,
                    "mrs_vpr: %llu frames of %s never reached the node (header.seq jumped to %u): the "
                    "subscriber queue (~image_queue_size = %d) overflowed while frames were described%s, or the "
                    "publisher dropped or skipped them; counted as failed",
                    static_cast<unsigned long long>(missing), imageTopic().c_str(), seq, params_.image_queue_size,
                    travel_policy_.enabled() ? " or waited for the robot's pose (~tf_timeout)" : "");
}

std::string PlaceRecognitionNode::imageTopic() const {
  return compressed_image_sub_ ? compressed_image_sub_.getTopic() : image_sub_.getTopic();
}

void PlaceRecognitionNode::cameraWatchCallback(const ros::WallTimerEvent&) {
  const double now = steadySeconds();
  switch (camera_silence_.check(now)) {
    case CameraSilence::Change::kSilent:
      ROS_WARN("%s", cameraSilenceWarning(now).c_str());
      break;
    case CameraSilence::Change::kImagesBack:
      ROS_INFO("mrs_vpr: images arrive on %s now", imageTopic().c_str());
      break;
    case CameraSilence::Change::kNone:
      break;
  }
}

std::string PlaceRecognitionNode::cameraSilenceWarning(double now) const {
  const std::string topic = imageTopic();
  const std::string seconds = std::to_string(std::lround(camera_silence_.silentFor(now)));
  const bool came_before = camera_silence_.anyImage();
  const std::string warning =
      "mrs_vpr: no image has arrived on " + topic +
      (came_before ? " for " + seconds + " s" : " in the " + seconds + " s since the node subscribed to it");
  const std::uint32_t publishers =
      compressed_image_sub_ ? compressed_image_sub_.getNumPublishers() : image_sub_.getNumPublishers();
  if (publishers > 0) {
    return warning + ": " + std::to_string(publishers) +
           (publishers == 1 ? " publisher is connected but sends" : " publishers are connected but send") +
           " nothing (check with `rostopic hz " + topic + "`)";
  }
  if (came_before) {
    return warning + ": its publisher has gone (a camera driver that stopped, or a bag that ended)";
  }
  return warning + ": no node publishes it (check the name with `rostopic list`, and the launch file's image:= "
                   "argument); the map grows, and continuous mode asks, only as images come (a node that only "
                   "answers ~query about the images sent with it can ignore this)";
}

}  // namespace node
}  // namespace mrs_vpr

#include "mrs_vpr/node/place_recognition_node.hpp"

#include <algorithm>
#include <chrono>
#include <exception>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "mrs_vpr/LoopClosure.h"
#include "mrs_vpr/acceptance.hpp"
#include "mrs_vpr/node/compressed_image.hpp"
#include "mrs_vpr/node/continuous_queries.hpp"
#include "mrs_vpr/node/image_conversion.hpp"
#include "mrs_vpr/node/loop_closure_stamps.hpp"
#include "mrs_vpr/node/robot_position.hpp"
#include "mrs_vpr/node/ros_stamp.hpp"

namespace mrs_vpr {
namespace node {
namespace {

constexpr double kWarningPeriod = 5.0;  // [s] between repeated warnings about bad frames
// Answers a publisher holds while the transport sends them. Continuous mode may localise every keyframe
// of a period at once, and restate up to 100 answers for a stop: a short queue would drop the oldest.
constexpr int kAnswerQueue = 1000;

std::string inQuotes(const std::string& text) { return "'" + text + "'"; }

}  // namespace

PlaceRecognitionNode::PlaceRecognitionNode(const ros::NodeHandle& nh, const ros::NodeHandle& private_nh,
                                           const NodeParameters& params)
    : params_(params),
      recognizer_(params.core, params.recognizer),
      keyframe_policy_(params.min_frame_interval, params.frame_stride),
      travel_policy_(params.min_travel),
      standing_frames_(params.auto_query_period),
      nh_(nh),
      private_nh_(private_nh),
      query_nh_(private_nh),
      image_transport_(nh) {
  openMap();  // First: a map database that cannot be used stops the node before it offers anything.
  // Everything that may wait for the map (queries, reset, timers) lives on its own queue and thread.
  query_nh_.setCallbackQueue(&query_queue_);
  loop_closure_pub_ = private_nh_.advertise<LoopClosure>("loop_closure", kAnswerQueue);
  loop_closure_stamps_pub_ = private_nh_.advertise<std_msgs::Float64MultiArray>("loop_closure_stamps", kAnswerQueue);
  map_info_pub_ = private_nh_.advertise<MapInfo>("map_info", 1, /*latch=*/true);
  debug_image_ = std::make_unique<DebugImagePublisher>(private_nh_);
  query_srv_ = query_nh_.advertiseService("query", &PlaceRecognitionNode::queryCallback, this);
  reset_srv_ = query_nh_.advertiseService("reset", &PlaceRecognitionNode::resetCallback, this);
  save_map_srv_ = query_nh_.advertiseService("save_map", &PlaceRecognitionNode::saveMapCallback, this);
  load_map_srv_ = query_nh_.advertiseService("load_map", &PlaceRecognitionNode::loadMapCallback, this);
  map_info_timer_ = query_nh_.createTimer(ros::Duration(1.0 / params_.map_info_rate),
                                          &PlaceRecognitionNode::mapInfoCallback, this);
  if (params_.auto_query_period > 0.0) {
    auto_query_timer_ = query_nh_.createTimer(ros::Duration(params_.auto_query_period),
                                              &PlaceRecognitionNode::autoQueryCallback, this);
  }
  if (travel_policy_.enabled()) {
    tf_buffer_ = std::make_unique<tf2_ros::Buffer>();
    tf_listener_ = std::make_unique<tf2_ros::TransformListener>(*tf_buffer_);
  }
  recognizer_.reserveAhead();
  publishMapInfoIfChanged();

  // The transport ("raw", "compressed", ...) comes from ~image_transport. Debian 12 ships no
  // `compressed` plugin, so the node decodes that transport itself, on the topic and with the format
  // strings of image_transport's plugin (doc/compressed_images.md); others go through image_transport.
  const image_transport::TransportHints hints("raw", ros::TransportHints(), private_nh_);
  const auto queue_size = static_cast<std::uint32_t>(params_.image_queue_size);
  if (hints.getTransport() == "compressed") {
    compressed_image_sub_ = nh_.subscribe(nh_.resolveName("image") + "/compressed", queue_size,
                                          &PlaceRecognitionNode::compressedImageCallback, this);
  } else {
    image_sub_ = image_transport_.subscribe("image", queue_size, &PlaceRecognitionNode::imageCallback, this, hints);
  }

  query_spinner_ = std::make_unique<ros::AsyncSpinner>(1, &query_queue_);
  query_spinner_->start();
  master_watch_ = std::make_unique<MasterWatch>();  // Last: it re-registers what is advertised above.

  ROS_INFO("mrs_vpr: listening on %s (transport %s); front end %s, default method %s%s", imageTopic().c_str(),
           hints.getTransport().c_str(), params_.core.descriptor.describe().c_str(),
           params_.recognizer.default_method.c_str(), params_.auto_query_period > 0.0 ? ", continuous mode on" : "");
}

std::unique_ptr<PlaceRecognitionNode> PlaceRecognitionNode::start(const ros::NodeHandle& nh,
                                                                 const ros::NodeHandle& private_nh) {
  const NodeParameters params = loadParameters(private_nh);
  for (const auto& name : unknownParameters(private_nh)) {
    ROS_WARN("mrs_vpr: unknown parameter %s (ignored; see mrs_vpr_node --help)", name.c_str());
  }
  return std::make_unique<PlaceRecognitionNode>(nh, private_nh, params);
}

PlaceRecognitionNode::~PlaceRecognitionNode() {
  // Stop feeding callbacks first, then join the query thread, so no callback outlives the members.
  image_sub_.shutdown();
  compressed_image_sub_.shutdown();
  auto_query_timer_.stop();
  map_info_timer_.stop();
  query_srv_.shutdown();
  reset_srv_.shutdown();
  save_map_srv_.shutdown();
  load_map_srv_.shutdown();
  if (query_spinner_) {
    query_spinner_->stop();
  }
}

// ---------------------------------------------------------------------------------------------------
// Frames

void PlaceRecognitionNode::imageCallback(const sensor_msgs::ImageConstPtr& message) {
  addFrame(message->header, [&] { return fromImageMessage(*message, message); },
           [&] {
             return std::to_string(message->width) + " x " + std::to_string(message->height) + ", " +
                    message->encoding;
           });
}

void PlaceRecognitionNode::compressedImageCallback(const sensor_msgs::CompressedImageConstPtr& message) {
  addFrame(message->header, [&] { return decodeCompressedImage(*message); },
           [&] { return "format " + inQuotes(message->format) + ", " + std::to_string(message->data.size()) + " bytes"; });
}

template <typename Convert, typename Summary>
void PlaceRecognitionNode::addFrame(const std_msgs::Header& header, const Convert& convert, const Summary& summary) {
  ++frames_received_;
  countMissingFrames(header.seq);
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
    ROS_WARN_THROTTLE(kWarningPeriod, "mrs_vpr: dropping a frame from %s (%s): %s", imageTopic().c_str(),
                      summary().c_str(), error.what());
    return;
  }
  if (!admit(descriptor, *stamp, header, seconds)) return;

  ++map_version_;
  std::lock_guard<std::mutex> lock(state_mutex_);
  keyframe_policy_.keep(seconds);
  standing_frames_.keyframe(*stamp);
  if (position) travel_policy_.keep(*position);
  camera_frame_id_ = header.frame_id;
  const double elapsed_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  frame_time_total_ms_ += elapsed_ms;
  ++frames_timed_;
  frame_time_max_ms_ = std::max(frame_time_max_ms_, elapsed_ms);
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
  const FrameAdmission admission = travel_policy_.enabled() ? map_->add(descriptor, stamp, header.frame_id, header.seq)
                                                            : map_->offer(descriptor, stamp, header.frame_id, header.seq);
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
      ROS_WARN_THROTTLE(kWarningPeriod, "mrs_vpr: the reference map is full (~max_frames = %d); dropping frames",
                        params_.recognizer.max_frames);
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

void PlaceRecognitionNode::countMissingFrames(std::uint32_t seq) {
  std::uint64_t missing = 0;
  {
    std::lock_guard<std::mutex> lock(state_mutex_);
    missing = sequence_gaps_.record(seq);
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
                    "publisher dropped them; counted as failed",
                    static_cast<unsigned long long>(missing), imageTopic().c_str(), seq, params_.image_queue_size,
                    travel_policy_.enabled() ? " or waited for the robot's pose (~tf_timeout)" : "");
}

std::string PlaceRecognitionNode::imageTopic() const {
  return compressed_image_sub_ ? compressed_image_sub_.getTopic() : image_sub_.getTopic();
}

// ---------------------------------------------------------------------------------------------------
// Queries

bool PlaceRecognitionNode::queryCallback(QuerySequence::Request& request, QuerySequence::Response& response) {
  const auto start = std::chrono::steady_clock::now();
  response.success = false;
  response.reference_index = -1;
  QueryInput input;
  input.method = request.method;  // Empty: the recognizer's default method.
  PlaceAnswer answered;
  try {
    if (!request.images.empty()) {
      if (request.recent_frames > 0) {
        throw std::invalid_argument("give either images or recent_frames, not both (got " +
                                    std::to_string(request.images.size()) + " images and recent_frames " +
                                    std::to_string(request.recent_frames) + ")");
      }
      if (request.images.size() < 2) {
        throw std::invalid_argument("a test sequence needs at least 2 images, got 1");
      }
      input.images = std::make_unique<DescriptorSequence>(recognizer_.extractor().size());
      input.images->reserve(static_cast<int>(request.images.size()));
      for (std::size_t i = 0; i < request.images.size(); ++i) {
        const sensor_msgs::Image& image = request.images[i];
        try {
          input.images->append(describeImage(recognizer_.extractor(), image), stampOf(image.header.stamp));
        } catch (const std::exception& error) {
          throw std::invalid_argument("images[" + std::to_string(i) + "] (" + std::to_string(image.width) +
                                      " x " + std::to_string(image.height) + ", encoding " +
                                      inQuotes(image.encoding) + "): " + error.what());
        }
      }
      for (const sensor_msgs::Image& image : request.images) input.image_headers.push_back(image.header);
    } else if (request.recent_frames == 0) {
      throw std::invalid_argument(
          "empty request: give the test sequence as images, or set recent_frames >= 2 to use the "
          "newest map frames");
    } else {
      input.recent_frames = request.recent_frames;
    }
    answered = answer(input, response);
    response.success = true;
  } catch (const std::exception& error) {
    response.success = false;
    response.message = error.what();
    response.reference_index = -1;
    response.accepted = false;
  }
  response.elapsed_ms = std::chrono::duration<float, std::milli>(std::chrono::steady_clock::now() - start).count();
  if (response.success) {
    const std::string unpublished = publishLoopClosure(input.header, answered, response, input.header.stamp);
    if (!unpublished.empty()) response.message += "; " + unpublished;
    if (!input.images) publishStandingClosures(input.header, answered, response);
    ROS_DEBUG("mrs_vpr: query (%s, %d frames) -> %d, confidence %.3f, %.1f ms", answered.method.c_str(),
              answered.query_length, response.reference_index, response.confidence, response.elapsed_ms);
  } else {
    ROS_WARN_THROTTLE(1.0, "mrs_vpr: query failed: %s", response.message.c_str());
  }
  return true;  // failures are reported in the response, never as "service call failed"
}

PlaceAnswer PlaceRecognitionNode::answer(QueryInput& input, QuerySequence::Response& response) {
  // The search may take a while; frames arriving meanwhile wait in the recognizer's pending buffer.
  // The answer is explained (for ~debug_image) only while someone watches.
  MatchExplanation explanation;
  MatchExplanation* const explain = debug_image_->wanted() ? &explanation : nullptr;
  // Images at the camera's rate are spaced as the map is: keyframed by appearance as its frames were
  // (with keyframes by travel, the images are taken as keyframes already).
  PlaceAnswer answered =
      !input.images               ? recognizer_.matchRecent(input.recent_frames, input.method, explain, input.end)
      : travel_policy_.enabled()  ? recognizer_.match(*input.images, input.method, explain)
                                  : recognizer_.matchKeyframesOf(*input.images, input.method, explain);
  if (input.images) {
    input.header = input.image_headers.at(static_cast<std::size_t>(answered.localised_row));
  } else {
    input.header.stamp = rosTimeOf(answered.localised_stamp);
    std::lock_guard<std::mutex> lock(state_mutex_);
    input.header.frame_id = camera_frame_id_;
  }
  if (explain != nullptr) {
    // What keyframing left out, so that a stop shows as frames skipped rather than as missing answers.
    const std::string map_status = std::to_string(frames_too_similar_.load()) +
                                   " frames skipped as too similar to the last keyframe; " +
                                   std::to_string(frames_skipped_.load()) + " skipped by the keyframe policy";
    debug_image_->publish(input.header, answered, explanation, map_status);
  }
  const Match& match = answered.match;
  response.reference_index = match.reference_index;
  response.score = match.score;
  response.confidence = match.confidence;
  response.reference_stamp = rosTimeOf(answered.reference_stamp);
  response.localised_stamp = input.header.stamp;
  response.accepted = match.accepted;
  response.message = acceptanceVerdict(match, params_.core.sequence);
  return answered;
}

std::string PlaceRecognitionNode::publishLoopClosure(const std_msgs::Header& header, const PlaceAnswer& answer,
                                                     const QuerySequence::Response& response,
                                                     const ros::Time& localised_keyframe_stamp) {
  LoopClosure message;
  message.header = header;
  message.localised_keyframe_stamp = localised_keyframe_stamp;
  message.reference_index = response.reference_index;
  message.reference_stamp = response.reference_stamp;
  message.query_length = static_cast<std::uint32_t>(answer.query_length);
  message.score = response.score;
  message.confidence = response.confidence;
  message.accepted = response.accepted;
  message.method = answer.method;
  loop_closure_pub_.publish(message);

  std::string why;
  if (const auto stamps = loopClosureStamps(message, why)) {
    loop_closure_stamps_pub_.publish(*stamps);
    return "";
  }
  if (why.empty()) return "";  // not accepted: nothing to publish
  const std::string unpublished = "not published on " + loop_closure_stamps_pub_.getTopic() + ": " + why;
  ROS_WARN_THROTTLE(kWarningPeriod, "mrs_vpr: an accepted loop closure was %s", unpublished.c_str());
  return unpublished;
}

void PlaceRecognitionNode::publishStandingClosures(const std_msgs::Header& header, const PlaceAnswer& answer,
                                                   const QuerySequence::Response& response) {
  if (!response.accepted || params_.auto_query_period <= 0.0) return;
  std::vector<Stamp> standing;
  {
    std::lock_guard<std::mutex> lock(state_mutex_);
    standing = standing_frames_.of(answer.localised_stamp);
  }
  for (const Stamp stamp : standing) {
    std_msgs::Header restated = header;
    restated.stamp = rosTimeOf(stamp);
    publishLoopClosure(restated, answer, response, header.stamp);
  }
}

void PlaceRecognitionNode::autoQueryCallback(const ros::TimerEvent&) {
  recognizer_.flush();
  const std::uint64_t version = map_version_.load();
  if (version == auto_query_version_) {
    return;  // nothing new since the last answer
  }
  const int recent = params_.autoQueryFrames();
  const int first_size = 2 * recent + params_.recognizer.recent_exclusion;
  const int size = recognizer_.size();
  if (size < first_size) {
    return;  // too early: not enough older frames to search yet
  }
  auto_query_version_ = version;
  // Each keyframe since the last question is localised once (continuous_queries.hpp), within
  // kContinuousShare of the period by the last question's time.
  const std::vector<int> ends = continuousQueryEnds(auto_query_size_, size, first_size,
                                                    affordableQueries(params_.auto_query_period, auto_query_ms_));
  auto_query_size_ = size;
  for (const int end : ends) {
    QueryInput input;
    input.recent_frames = recent;
    input.end = end;
    QuerySequence::Response response;
    const auto start = std::chrono::steady_clock::now();
    try {
      const PlaceAnswer answered = answer(input, response);
      publishLoopClosure(input.header, answered, response, input.header.stamp);  // warns itself when stamps cannot go out
      publishStandingClosures(input.header, answered, response);
    } catch (const std::exception& error) {
      ROS_WARN_THROTTLE(kWarningPeriod, "mrs_vpr: continuous query failed: %s", error.what());
      return;
    }
    auto_query_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  }
}

// ---------------------------------------------------------------------------------------------------
// Housekeeping

MapInfo PlaceRecognitionNode::makeMapInfo() {
  MapInfo info;
  const PlaceRecognizer::MapState state = recognizer_.state();
  info.frames = static_cast<std::uint32_t>(state.frames);
  info.memory_bytes = state.memory_bytes;
  info.descriptor_size = static_cast<std::uint32_t>(state.descriptor_size);
  if (state.frames > 0) {
    info.first_stamp = rosTimeOf(state.first_stamp);
    info.last_stamp = rosTimeOf(state.last_stamp);
  }
  info.max_frames = static_cast<std::uint32_t>(params_.recognizer.max_frames);
  info.frames_pending = static_cast<std::uint32_t>(state.pending);
  info.frames_persisted = map_->persisted();
  {
    std::lock_guard<std::mutex> lock(state_mutex_);
    info.frame_time_mean_ms =
        frames_timed_ > 0 ? static_cast<float>(frame_time_total_ms_ / static_cast<double>(frames_timed_)) : 0.0F;
    info.frame_time_max_ms = static_cast<float>(frame_time_max_ms_);
  }
  info.frames_received = frames_received_.load();
  info.frames_skipped = frames_skipped_.load();
  info.frames_too_similar = frames_too_similar_.load();
  info.frames_without_pose = frames_without_pose_.load();
  info.frames_dropped = frames_dropped_.load();
  info.frames_failed = frames_failed_.load();
  info.debug_images = debug_image_->rendered();
  return info;
}

void PlaceRecognitionNode::publishMapInfoIfChanged() {
  MapInfo info = makeMapInfo();
  // Republish only when the map or a counter changed; the header and timings alone do not count.
  MapInfo comparable = info;
  comparable.header = last_map_info_.header;
  comparable.frame_time_mean_ms = last_map_info_.frame_time_mean_ms;
  comparable.frame_time_max_ms = last_map_info_.frame_time_max_ms;
  if (map_info_published_ && comparable == last_map_info_) {
    return;
  }
  info.header.stamp = ros::Time::now();
  map_info_pub_.publish(info);
  last_map_info_ = info;
  map_info_published_ = true;
  std::lock_guard<std::mutex> lock(state_mutex_);
  frame_time_max_ms_ = 0.0;
}

void PlaceRecognitionNode::mapInfoCallback(const ros::TimerEvent&) {
  recognizer_.flush();  // frames parked during a query show up even when no new image arrives
  recognizer_.reserveAhead();
  publishMapInfoIfChanged();
  reportWriteErrors();
}

}  // namespace node
}  // namespace mrs_vpr

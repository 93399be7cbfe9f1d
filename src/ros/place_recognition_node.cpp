#include "mrs_vpr/ros/place_recognition_node.hpp"

#include <algorithm>
#include <chrono>
#include <exception>
#include <stdexcept>
#include <utility>

#include "mrs_vpr/LoopClosure.h"
#include "mrs_vpr/ros/image_conversion.hpp"

namespace mrs_vpr {
namespace node {
namespace {

constexpr double kWarningPeriod = 5.0;  // [s] between repeated warnings about bad frames

std::string inQuotes(const std::string& text) { return "'" + text + "'"; }

ros::Time toRosTime(double seconds) { return seconds > 0.0 ? ros::Time(seconds) : ros::Time(); }

}  // namespace

PlaceRecognitionNode::PlaceRecognitionNode(const ros::NodeHandle& nh, const ros::NodeHandle& private_nh,
                                           const NodeParameters& params)
    : params_(params),
      extractor_(params.core.descriptor),
      map_(extractor_.size()),
      keyframe_policy_(params.min_frame_interval, params.frame_stride),
      nh_(nh),
      private_nh_(private_nh),
      query_nh_(private_nh),
      image_transport_(nh) {
  for (const char* method : {"mrs", "seqslam"}) {
    matchers_[method] = makeMatcher(method, params_.core);
  }
  // The map keeps MRS's pooled coarse levels up to date as frames arrive, so that a query does not
  // pool the whole map again.
  map_.keepPooledCells(params_.core.mrs.levels, params_.core.mrs.pixel_pooling);

  // Everything that may wait for the map (queries, reset, timers) lives on its own queue and thread.
  query_nh_.setCallbackQueue(&query_queue_);
  loop_closure_pub_ = private_nh_.advertise<LoopClosure>("loop_closure", 10);
  map_info_pub_ = private_nh_.advertise<MapInfo>("map_info", 1, /*latch=*/true);
  query_srv_ = query_nh_.advertiseService("query", &PlaceRecognitionNode::queryCallback, this);
  reset_srv_ = query_nh_.advertiseService("reset", &PlaceRecognitionNode::resetCallback, this);
  map_info_timer_ = query_nh_.createTimer(ros::Duration(1.0 / params_.map_info_rate),
                                          &PlaceRecognitionNode::mapInfoCallback, this);
  if (params_.auto_query_period > 0.0) {
    auto_query_timer_ = query_nh_.createTimer(ros::Duration(params_.auto_query_period),
                                              &PlaceRecognitionNode::autoQueryCallback, this);
  }
  reserveAhead();
  publishMapInfoIfChanged();

  // The transport ("raw", "compressed", ...) comes from ~image_transport.
  const image_transport::TransportHints hints("raw", ros::TransportHints(), private_nh_);
  image_sub_ = image_transport_.subscribe("image", static_cast<std::uint32_t>(params_.image_queue_size),
                                          &PlaceRecognitionNode::imageCallback, this, hints);

  query_spinner_ = std::make_unique<ros::AsyncSpinner>(1, &query_queue_);
  query_spinner_->start();

  ROS_INFO("mrs_vpr: listening on %s (transport %s); descriptor %d x %d, default method %s%s",
           image_sub_.getTopic().c_str(), image_sub_.getTransport().c_str(),
           params_.core.descriptor.image_width, params_.core.descriptor.image_height,
           params_.default_method.c_str(), params_.auto_query_period > 0.0 ? ", continuous mode on" : "");
}

PlaceRecognitionNode::~PlaceRecognitionNode() {
  // Stop feeding callbacks first, then join the query thread, so no callback outlives the members.
  image_sub_.shutdown();
  auto_query_timer_.stop();
  map_info_timer_.stop();
  query_srv_.shutdown();
  reset_srv_.shutdown();
  if (query_spinner_) {
    query_spinner_->stop();
  }
}

// ---------------------------------------------------------------------------------------------------
// Frames

void PlaceRecognitionNode::imageCallback(const sensor_msgs::ImageConstPtr& message) {
  ++frames_received_;
  double stamp = message->header.stamp.toSec();
  if (stamp <= 0.0) {
    stamp = ros::Time::now().toSec();  // unstamped camera: the arrival time is the best we have
  }
  {
    std::lock_guard<std::mutex> lock(pending_mutex_);
    if (!keyframe_policy_.wants(stamp)) {
      keyframe_policy_.skip();
      ++frames_skipped_;
      return;
    }
  }

  // The expensive part runs without any lock.
  const auto start = std::chrono::steady_clock::now();
  cv::Mat descriptor;
  try {
    descriptor = describeImage(extractor_, *message, message);
  } catch (const std::exception& error) {
    ++frames_failed_;
    {
      std::lock_guard<std::mutex> lock(pending_mutex_);
      keyframe_policy_.skip();
    }
    ROS_WARN_THROTTLE(kWarningPeriod, "mrs_vpr: dropping a frame from %s (%u x %u, %s): %s",
                      image_sub_.getTopic().c_str(), message->width, message->height,
                      message->encoding.c_str(), error.what());
    return;
  }

  {
    std::lock_guard<std::mutex> lock(pending_mutex_);
    if (params_.max_frames > 0 && frames_admitted_ >= params_.max_frames) {
      ++frames_dropped_;
      ROS_WARN_THROTTLE(kWarningPeriod, "mrs_vpr: the reference map is full (~max_frames = %d); dropping frames",
                        params_.max_frames);
      return;
    }
    if (static_cast<int>(pending_.size()) >= params_.max_pending_frames) {
      ++frames_dropped_;
      ROS_WARN_THROTTLE(kWarningPeriod,
                        "mrs_vpr: %zu keyframes wait for a long query (~max_pending_frames); dropping frames",
                        pending_.size());
      return;
    }
    pending_.push_back({descriptor, stamp});
    ++frames_admitted_;
    keyframe_policy_.keep(stamp);
    camera_frame_id_ = message->header.frame_id;
    const double elapsed_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    frame_time_total_ms_ += elapsed_ms;
    ++frames_timed_;
    frame_time_max_ms_ = std::max(frame_time_max_ms_, elapsed_ms);
  }

  // Never wait for a query: if one holds the map, the frame stays pending until the map is free.
  std::unique_lock<std::shared_mutex> map_lock(map_mutex_, std::try_to_lock);
  if (map_lock.owns_lock()) {
    flushPendingLocked();
  }
}

void PlaceRecognitionNode::flushPendingLocked() {
  std::vector<PendingFrame> frames;
  {
    std::lock_guard<std::mutex> lock(pending_mutex_);
    frames.swap(pending_);
  }
  if (frames.empty()) {
    return;
  }
  for (const auto& frame : frames) {
    map_.append(frame.descriptor, frame.stamp);
  }
  map_frames_ = map_.size();
  ++map_version_;
}

void PlaceRecognitionNode::flushPending() {
  std::unique_lock<std::shared_mutex> map_lock(map_mutex_);
  flushPendingLocked();
}

void PlaceRecognitionNode::reserveAhead() {
  constexpr int kMinimumReserve = 4096;  // frames: over two minutes of a 30 Hz camera
  const int frames = map_frames_.load();
  if (frames < reserved_frames_ - reserved_frames_ / 4) {
    return;
  }
  int target = std::max(kMinimumReserve, 2 * std::max(reserved_frames_, frames));
  if (params_.max_frames > 0) {
    target = std::min(target, params_.max_frames);
  }
  if (target <= reserved_frames_) {
    return;
  }
  // Copying a large map takes a while; meanwhile the image callback parks frames in pending_.
  std::unique_lock<std::shared_mutex> map_lock(map_mutex_);
  map_.reserve(target);
  reserved_frames_ = target;
}

// ---------------------------------------------------------------------------------------------------
// Queries

bool PlaceRecognitionNode::queryCallback(QuerySequence::Request& request, QuerySequence::Response& response) {
  const auto start = std::chrono::steady_clock::now();
  response.success = false;
  response.reference_index = -1;
  QueryInput input;
  input.method = request.method.empty() ? params_.default_method : request.method;
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
      input.images = std::make_unique<DescriptorSequence>(extractor_.size());
      input.images->reserve(static_cast<int>(request.images.size()));
      for (std::size_t i = 0; i < request.images.size(); ++i) {
        const sensor_msgs::Image& image = request.images[i];
        try {
          input.images->append(describeImage(extractor_, image), image.header.stamp.toSec());
        } catch (const std::exception& error) {
          throw std::invalid_argument("images[" + std::to_string(i) + "] (" + std::to_string(image.width) +
                                      " x " + std::to_string(image.height) + ", encoding " +
                                      inQuotes(image.encoding) + "): " + error.what());
        }
      }
      input.header = request.images.back().header;
    } else if (request.recent_frames == 0) {
      throw std::invalid_argument(
          "empty request: give the test sequence as images, or set recent_frames >= 2 to use the "
          "newest map frames");
    } else {
      input.recent_frames = static_cast<int>(std::min<std::uint32_t>(request.recent_frames, 1U << 30U));
    }
    answer(input, response);
    response.success = true;
  } catch (const std::exception& error) {
    response.success = false;
    response.message = error.what();
    response.reference_index = -1;
    response.accepted = false;
  }
  response.elapsed_ms = std::chrono::duration<float, std::milli>(std::chrono::steady_clock::now() - start).count();
  if (response.success) {
    const int length = input.images ? input.images->size() : input.recent_frames;
    publishLoopClosure(input.header, length, input.method, response);
    ROS_DEBUG("mrs_vpr: query (%s, %d frames) -> %d, confidence %.3f, %.1f ms", input.method.c_str(), length,
              response.reference_index, response.confidence, response.elapsed_ms);
  } else {
    ROS_WARN_THROTTLE(1.0, "mrs_vpr: query failed: %s", response.message.c_str());
  }
  return true;  // failures are reported in the response, never as "service call failed"
}

void PlaceRecognitionNode::answer(QueryInput& input, QuerySequence::Response& response) {
  const auto matcher = matchers_.find(input.method);
  if (matcher == matchers_.end()) {
    throw std::invalid_argument("unknown method " + inQuotes(input.method) + ": use 'mrs' or 'seqslam'");
  }
  if (input.recent_frames > 0) {
    flushPending();  // the newest frames must be in the map before they can be the test sequence
  }

  {
    std::shared_lock<std::shared_mutex> map_lock(map_mutex_);
    const int frames = map_.size();
    if (frames == 0) {
      throw std::invalid_argument("the reference map is empty: publish images on " + image_sub_.getTopic() +
                                  " first");
    }
    SequenceView reference;
    SequenceView query;
    if (input.images) {
      if (input.images->size() > frames) {
        throw std::invalid_argument("the test sequence has " + std::to_string(input.images->size()) +
                                    " images but the reference map only " + std::to_string(frames) +
                                    " frames");
      }
      reference = map_.view();
      query = input.images->view();
    } else {
      const int recent = input.recent_frames;
      if (recent < 2) {
        throw std::invalid_argument("recent_frames must be at least 2, got " + std::to_string(recent));
      }
      if (recent > frames) {
        throw std::invalid_argument("recent_frames " + std::to_string(recent) + " is more than the " +
                                    std::to_string(frames) + " frames in the reference map");
      }
      const int searchable = frames - recent - params_.recent_exclusion;
      if (searchable < recent) {
        throw std::invalid_argument(
            "recent_frames " + std::to_string(recent) + " leaves " + std::to_string(std::max(searchable, 0)) +
            " searchable frames (map " + std::to_string(frames) + " - recent " + std::to_string(recent) +
            " - ~recent_exclusion " + std::to_string(params_.recent_exclusion) + "); the search needs at least " +
            std::to_string(recent));
      }
      reference = map_.view(0, searchable);
      query = map_.view(frames - recent, frames);
      input.header.stamp = toRosTime(map_.stamp(frames - 1));
      std::lock_guard<std::mutex> lock(pending_mutex_);
      input.header.frame_id = camera_frame_id_;
    }

    // The search may take a while; frames arriving meanwhile wait in the pending buffer.
    const Match match = matcher->second->match(reference, query);
    response.reference_index = match.reference_index;
    response.score = match.score;
    response.confidence = match.confidence;
    response.reference_stamp =
        match.reference_index >= 0 ? toRosTime(map_.stamp(match.reference_index)) : ros::Time();
    response.accepted = match.accepted;
    response.message = match.reference_index >= 0
                           ? (response.accepted ? "accepted" : "not accepted: confidence below ~sequence/accept_threshold")
                           : "no match found";
  }
  flushPending();
}

void PlaceRecognitionNode::publishLoopClosure(const std_msgs::Header& header, int query_length,
                                              const std::string& method,
                                              const QuerySequence::Response& response) {
  LoopClosure message;
  message.header = header;
  message.reference_index = response.reference_index;
  message.reference_stamp = response.reference_stamp;
  message.query_length = static_cast<std::uint32_t>(query_length);
  message.score = response.score;
  message.confidence = response.confidence;
  message.accepted = response.accepted;
  message.method = method;
  loop_closure_pub_.publish(message);
}

void PlaceRecognitionNode::autoQueryCallback(const ros::TimerEvent&) {
  flushPending();
  const std::uint64_t version = map_version_.load();
  if (version == auto_query_version_) {
    return;  // nothing new since the last answer
  }
  const int recent = params_.autoQueryFrames();
  if (map_frames_.load() < 2 * recent + params_.recent_exclusion) {
    return;  // too early: not enough older frames to search yet
  }
  auto_query_version_ = version;
  QueryInput input;
  input.recent_frames = recent;
  input.method = params_.default_method;
  QuerySequence::Response response;
  try {
    answer(input, response);
  } catch (const std::exception& error) {
    ROS_WARN_THROTTLE(kWarningPeriod, "mrs_vpr: continuous query failed: %s", error.what());
    return;
  }
  publishLoopClosure(input.header, recent, input.method, response);
}

// ---------------------------------------------------------------------------------------------------
// Housekeeping

bool PlaceRecognitionNode::resetCallback(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& response) {
  int cleared = 0;
  {
    std::unique_lock<std::shared_mutex> map_lock(map_mutex_);
    std::lock_guard<std::mutex> lock(pending_mutex_);
    cleared = map_.size() + static_cast<int>(pending_.size());
    pending_.clear();
    map_.clear();
    keyframe_policy_.reset();
    map_frames_ = 0;
    frames_admitted_ = 0;
    reserved_frames_ = 0;
    ++map_version_;
  }
  response.success = true;
  response.message = "cleared " + std::to_string(cleared) + " frames";
  ROS_INFO("mrs_vpr: reference map reset (%s)", response.message.c_str());
  publishMapInfoIfChanged();
  return true;
}

MapInfo PlaceRecognitionNode::makeMapInfo() {
  MapInfo info;
  {
    std::shared_lock<std::shared_mutex> map_lock(map_mutex_);
    info.frames = static_cast<std::uint32_t>(map_.size());
    info.memory_bytes = map_.memoryBytes();
    info.descriptor_size = static_cast<std::uint32_t>(map_.descriptorSize());
    if (!map_.empty()) {
      info.first_stamp = toRosTime(map_.stamp(0));
      info.last_stamp = toRosTime(map_.stamp(map_.size() - 1));
    }
  }
  info.max_frames = static_cast<std::uint32_t>(params_.max_frames);
  {
    std::lock_guard<std::mutex> lock(pending_mutex_);
    info.frames_pending = static_cast<std::uint32_t>(pending_.size());
    info.frame_time_mean_ms =
        frames_timed_ > 0 ? static_cast<float>(frame_time_total_ms_ / static_cast<double>(frames_timed_)) : 0.0F;
    info.frame_time_max_ms = static_cast<float>(frame_time_max_ms_);
  }
  info.frames_received = frames_received_.load();
  info.frames_skipped = frames_skipped_.load();
  info.frames_dropped = frames_dropped_.load();
  info.frames_failed = frames_failed_.load();
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
  std::lock_guard<std::mutex> lock(pending_mutex_);
  frame_time_max_ms_ = 0.0;
}

void PlaceRecognitionNode::mapInfoCallback(const ros::TimerEvent&) {
  flushPending();  // frames parked during a query show up even when no new image arrives
  reserveAhead();
  publishMapInfoIfChanged();
}

}  // namespace node
}  // namespace mrs_vpr

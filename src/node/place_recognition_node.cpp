// The node's life: what it advertises and subscribes to at start-up, its shutdown, and ~map_info.
// Its frames are in frame_intake.cpp, its answers in place_queries.cpp, its map in map_services.cpp.

#include "mrs_vpr/node/place_recognition_node.hpp"

#include <algorithm>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>

#include <opencv2/core/utility.hpp>
#include <std_msgs/Float64MultiArray.h>

#include "mrs_vpr/LoopClosure.h"
#include "mrs_vpr/node/ros_stamp.hpp"
#include "mrs_vpr/number_text.hpp"
#include "node_warnings.hpp"

namespace mrs_vpr {
namespace node {
namespace {

// Answers a publisher holds while the transport sends them. Continuous mode may localise every keyframe
// of a period at once, and restate up to 100 answers for a stop: a short queue would drop the oldest.
constexpr int kAnswerQueue = 1000;

}  // namespace

PlaceRecognitionNode::PlaceRecognitionNode(const ros::NodeHandle& nh, const ros::NodeHandle& private_nh,
                                           const NodeParameters& params)
    : params_(params),
      recognizer_(params.core, params.recognizer),
      keyframe_policy_(params.min_frame_interval, params.frame_stride),
      travel_policy_(params.min_travel),
      frame_failure_warning_(kWarningPeriod),
      standing_frames_(params.auto_query_period),
      nh_(nh),
      private_nh_(private_nh),
      query_nh_(private_nh),
      info_nh_(private_nh),
      image_transport_(nh) {
  // Before anything runs in parallel: loading the map does.
  if (params_.threads > 0) cv::setNumThreads(params_.threads);
  openMap();  // First: a map database that cannot be used stops the node before it offers anything.
  // Everything that may wait for the map (queries, reset, timers) lives on its own queue and thread.
  query_nh_.setCallbackQueue(&query_queue_);
  // ~map_info on a third: it reports frames parked by a long query while that query runs.
  info_nh_.setCallbackQueue(&info_queue_);
  loop_closure_pub_ = private_nh_.advertise<LoopClosure>("loop_closure", kAnswerQueue);
  loop_closure_stamps_pub_ = private_nh_.advertise<std_msgs::Float64MultiArray>("loop_closure_stamps", kAnswerQueue);
  map_info_pub_ = private_nh_.advertise<MapInfo>("map_info", 1, /*latch=*/true);
  debug_image_ = std::make_unique<DebugImagePublisher>(private_nh_);
  query_srv_ = query_nh_.advertiseService("query", &PlaceRecognitionNode::queryCallback, this);
  reset_srv_ = query_nh_.advertiseService("reset", &PlaceRecognitionNode::resetCallback, this);
  save_map_srv_ = query_nh_.advertiseService("save_map", &PlaceRecognitionNode::saveMapCallback, this);
  load_map_srv_ = query_nh_.advertiseService("load_map", &PlaceRecognitionNode::loadMapCallback, this);
  reject_closure_srv_ =
      query_nh_.advertiseService("reject_closure", &PlaceRecognitionNode::rejectClosureCallback, this);
  // Wall-clock timers: they pace the node's own work, which goes on under use_sim_time whether or not
  // a /clock runs (before one starts, and after a replayed bag's clock stops, ROS time stands still).
  map_info_timer_ = info_nh_.createWallTimer(ros::WallDuration(1.0 / params_.map_info_rate),
                                             &PlaceRecognitionNode::mapInfoCallback, this);
  if (params_.auto_query_period > 0.0) {
    auto_query_timer_ = query_nh_.createWallTimer(ros::WallDuration(params_.auto_query_period),
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
  camera_silence_.listenFrom(steadySeconds());  // After the map: loading a large one takes a while.
  camera_watch_timer_ =
      info_nh_.createWallTimer(ros::WallDuration(1.0), &PlaceRecognitionNode::cameraWatchCallback, this);

  query_spinner_ = std::make_unique<ros::AsyncSpinner>(1, &query_queue_);
  query_spinner_->start();
  info_spinner_ = std::make_unique<ros::AsyncSpinner>(1, &info_queue_);
  info_spinner_->start();
  master_watch_ = std::make_unique<MasterWatch>();  // Last: it re-registers what is advertised above.

  // Said either way: a parameter file of one's own that leaves auto_query_period out turns
  // continuous mode off, and the node would otherwise publish nothing without a word.
  const std::string continuous =
      params_.auto_query_period > 0.0
          ? "continuous mode every " + numberText(params_.auto_query_period) + " s"
          : "continuous mode off (~auto_query_period 0): ~loop_closure answers ~query calls only";
  ROS_INFO("mrs_vpr: listening on %s (transport %s); front end %s, default method %s; %s", imageTopic().c_str(),
           hints.getTransport().c_str(), params_.core.descriptor.describe().c_str(),
           params_.recognizer.default_method.c_str(), continuous.c_str());
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
  // A running question ends at once (its caller is told that the node is shutting down): joining
  // the query thread below would wait for it, and a brute-force one on a large map can take longer
  // than roslaunch's 15 s before SIGTERM. Then stop feeding callbacks, and join the query thread, so
  // that no callback outlives the members.
  recognizer_.stopQueries();
  camera_watch_timer_.stop();  // First: it asks the subscribers below how many publishers they have.
  image_sub_.shutdown();
  compressed_image_sub_.shutdown();
  auto_query_timer_.stop();
  map_info_timer_.stop();
  query_srv_.shutdown();
  reset_srv_.shutdown();
  save_map_srv_.shutdown();
  load_map_srv_.shutdown();
  reject_closure_srv_.shutdown();
  if (info_spinner_) {
    info_spinner_->stop();
  }
  if (query_spinner_) {
    query_spinner_->stop();
  }
  // The last commit now, while a failure can still be said: the frames it leaves out are lost.
  if (map_ && map_->persistent()) {
    const std::size_t lost = map_->close();
    if (lost > 0) {
      ROS_ERROR("mrs_vpr: %zu keyframes of the map are lost: the last commit to ~database failed (%s)", lost,
                map_->writeError().c_str());
    }
  }
}

// ---------------------------------------------------------------------------------------------------
// Housekeeping

MapInfo PlaceRecognitionNode::makeMapInfo() {
  MapInfo info;
  // Persisted first, then capped at the frames read after it (pending ones included: a keyframe is
  // queued for the database when admitted, before it may leave the pending buffer for the map): a
  // commit, ~reset or ~load_map between the two reads never makes the database hold more than the map.
  const std::uint64_t persisted = map_->persisted();
  const PlaceRecognizer::MapState state = recognizer_.state();
  info.frames = static_cast<std::uint32_t>(state.frames);
  info.memory_bytes = state.memory_bytes + map_->labelBytes();
  info.descriptor_size = static_cast<std::uint32_t>(state.descriptor_size);
  if (state.frames > 0) {
    info.first_stamp = rosTimeOf(state.first_stamp);
    info.last_stamp = rosTimeOf(state.last_stamp);
  }
  info.max_frames = static_cast<std::uint32_t>(params_.recognizer.max_frames);
  info.frames_pending = static_cast<std::uint32_t>(state.pending);
  info.frames_persisted = std::min<std::uint64_t>(persisted, state.frames + state.pending);
  info.frames_linked = static_cast<std::uint32_t>(state.linked_frames);
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
  std::lock_guard<std::mutex> map_info_lock(map_info_mutex_);
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

bool PlaceRecognitionNode::flushWaitingKeyframes(bool wait) {
  try {
    if (!wait) return recognizer_.tryFlush();
    recognizer_.flush();
    return true;
  } catch (const std::exception& error) {  // std::bad_alloc
    ROS_ERROR_THROTTLE(kWarningPeriod, "mrs_vpr: could not move waiting keyframes into the map (they wait): %s",
                       error.what());
    return false;
  }
}

void PlaceRecognitionNode::mapInfoCallback(const ros::WallTimerEvent&) {
  // Frames parked during a query join the map even when no new image arrives; reserveAhead gives up by
  // itself when memory runs out.
  // Not waiting for a running query (tryFlush reserves ahead too): its parked frames are counted as
  // pending until it ends.
  flushWaitingKeyframes(/*wait=*/false);
  publishMapInfoIfChanged();
  reportWriteErrors();
}

}  // namespace node
}  // namespace mrs_vpr

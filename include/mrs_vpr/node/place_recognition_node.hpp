#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include <image_transport/image_transport.h>
#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <sensor_msgs/CompressedImage.h>
#include <sensor_msgs/Image.h>
#include <std_srvs/Trigger.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include "mrs_vpr/LoadMap.h"
#include "mrs_vpr/MapInfo.h"
#include "mrs_vpr/QuerySequence.h"
#include "mrs_vpr/RejectClosure.h"
#include "mrs_vpr/SaveMap.h"
#include "mrs_vpr/descriptor_sequence.hpp"
#include "mrs_vpr/node/camera_silence.hpp"
#include "mrs_vpr/node/debug_image_publisher.hpp"
#include "mrs_vpr/place_recognizer.hpp"
#include "mrs_vpr/node/keyframe_policy.hpp"
#include "mrs_vpr/node/master_watch.hpp"
#include "mrs_vpr/node/node_parameters.hpp"
#include "mrs_vpr/node/kind_throttle.hpp"
#include "mrs_vpr/node/sequence_gaps.hpp"
#include "mrs_vpr/node/standing_frames.hpp"
#include "mrs_vpr/node/travel_policy.hpp"
#include "mrs_vpr/store/persistent_map.hpp"

namespace mrs_vpr {
namespace node {

/**
 * The ROS face of the place recogniser: subscribes `image`, keeps keyframe descriptors in a reference
 * map, answers `~query` (mrs_vpr/QuerySequence), publishes `~loop_closure`, the stamps of accepted
 * ones on `~loop_closure_stamps` (LIO-SAM's convention, see loop_closure_stamps.hpp) and the latched
 * `~map_info`, offers `~reset`, `~save_map` and `~load_map`, keeps the map in `~database` when one
 * is set, and optionally queries on its own every `~auto_query_period` seconds.
 *
 * Threading: image callbacks run on the queue of `nh` (the caller spins it: ros::spin() in the node,
 * the manager's single-threaded queue in the nodelet). Services and timers run on private callback
 * queues served by this object's own spinner threads (one for queries and the map services, one for
 * ~map_info, which never waits for a query), so a query that takes seconds never delays a camera
 * frame. The map, its locking and the search are the ROS-free PlaceRecognizer's: a query
 * reads the map under a shared lock, and a new keyframe never waits for one (it is parked in a small
 * pending buffer that the next writer moves into the map).
 */
class PlaceRecognitionNode {
 public:
  /// `nh` subscribes the image topic; `private_nh` advertises services and publishers and supplies the
  /// image transport hints. Parameters must already be validated (see loadParameters).
  PlaceRecognitionNode(const ros::NodeHandle& nh, const ros::NodeHandle& private_nh,
                       const NodeParameters& params);
  ~PlaceRecognitionNode();

  /**
   * The one start-up path of the node and the nodelet: reads and validates the parameters under
   * `private_nh`, warns about parameters it does not know, and starts the node. Throws
   * std::invalid_argument naming the parameter when one is invalid.
   */
  static std::unique_ptr<PlaceRecognitionNode> start(const ros::NodeHandle& nh, const ros::NodeHandle& private_nh);

  PlaceRecognitionNode(const PlaceRecognitionNode&) = delete;
  PlaceRecognitionNode& operator=(const PlaceRecognitionNode&) = delete;

 private:
  /// What a query needs besides the map: the test sequence, when given explicitly.
  struct QueryInput {
    std::unique_ptr<DescriptorSequence> images;  ///< Explicit test sequence, or null.
    long long recent_frames = 0;                 ///< Otherwise the map's newest frames ...
    int end = -1;                                ///< ... before map frame `end` (-1: the newest).
    std::string method;
    std::vector<std_msgs::Header> image_headers;  ///< The header of each frame of `images`.
    std_msgs::Header header;  ///< Stamp and frame of the test frame the answer localises (set by answer()).
  };

  void imageCallback(const sensor_msgs::ImageConstPtr& message);
  /// The `compressed` transport (jpeg, png), decoded by the node itself: Debian 12 has no plugin for it.
  void compressedImageCallback(const sensor_msgs::CompressedImageConstPtr& message);
  /// The image path of both callbacks: keyframe policy, conversion (`convert` returns an ImageFrame),
  /// description, admission and counters. `summary` describes the message for a warning.
  template <typename Convert, typename Summary>
  void addFrame(const std_msgs::Header& header, const Convert& convert, const Summary& summary);
  /// The frame's exact stamp (its arrival time when the camera leaves it 0), or nothing when the stamp
  /// lies beyond ROS's range or neither it nor the clock gives a time (simulated time before /clock):
  /// counted as failed and reported.
  std::optional<Stamp> frameStamp(const std_msgs::Header& header);
  /// Whether the keyframe policies (interval, stride, then travel by tf) want the frame taken at
  /// `seconds`; `position` gets the robot's position when ~min_travel is set. What they refuse is
  /// counted and reported.
  bool wantedByPolicies(const std_msgs::Header& header, double seconds, std::optional<Eigen::Vector3d>& position);
  /// Offers the frame's descriptor to the map (added when chosen by travel, else kept if its view has
  /// changed); counts what is refused. Whether it became a keyframe.
  bool admit(const cv::Mat& descriptor, Stamp stamp, const std_msgs::Header& header, double seconds);
  /// Where ~base_frame was in ~odom_frame at `stamp` (waiting up to ~tf_timeout for tf), or nothing
  /// with the reason in `error`. Fails at once, naming the frame, while ~odom_frame or ~base_frame
  /// is unknown to tf and a first wait for it has been in vain.
  std::optional<Eigen::Vector3d> robotPosition(const ros::Time& stamp, std::string& error) const;
  /// ~odom_frame or ~base_frame when no transform received has named it yet, else "".
  std::string unknownTfFrame() const;
  /// Counts (received and failed) and reports the frames missing before the one numbered `seq`,
  /// whose callback began at steady time `callback_start`.
  void countMissingFrames(std::uint32_t seq, double stamp, double callback_start);
  /// The topic the camera frames come from, for messages.
  std::string imageTopic() const;
  bool queryCallback(QuerySequence::Request& request, QuerySequence::Response& response);
  // The map and its database (map_services.cpp).
  /// Opens ~database and loads its map, or keeps the map in memory; throws MapDatabaseError.
  void openMap();
  /// keyframingMismatch() of the map opened or loaded against the node's keyframing; empty if none.
  std::string keyframingMismatchOfMap() const;
  /// Warns of keyframingMismatchOfMap(), naming ~database.
  void warnOfKeyframingMismatch() const;
  bool resetCallback(std_srvs::Trigger::Request& request, std_srvs::Trigger::Response& response);
  bool saveMapCallback(SaveMap::Request& request, SaveMap::Response& response);
  bool rejectClosureCallback(RejectClosure::Request& request, RejectClosure::Response& response);
  bool loadMapCallback(LoadMap::Request& request, LoadMap::Response& response);
  /// After ~reset or ~load_map: the keyframe policies, the standing frames and continuous mode start over.
  /// Continuous mode asks about the keyframes after the new map's `map_frames` (those added while a
  /// load rewrote the database too).
  void startOverOnNewMap(int map_frames);
  /// Marks the map's first `map_frames` as loaded (continuous mode's sequences hold none of them) and
  /// warns when ~max_frames leaves too little room after them for continuous mode to ever ask.
  void startSession(int map_frames);
  /// Logs (throttled) why commits to ~database fail, while they do.
  void reportWriteErrors();
  void autoQueryCallback(const ros::WallTimerEvent& event);
  void mapInfoCallback(const ros::WallTimerEvent& event);
  /// Warns once when no image has arrived for a while (camera_silence.hpp), and says when images come again.
  void cameraWatchCallback(const ros::WallTimerEvent& event);
  /// The warning of a silence at `now`: how long, and what the topic's publishers suggest.
  std::string cameraSilenceWarning(double now) const;
  /// Moves the keyframes parked during a query into the map; false, logged, when memory ran out (a
  /// timer callback must not throw: roscpp would end the node). Without `wait`, also false at once
  /// while a query holds the map (the frames then wait for the next flush).
  bool flushWaitingKeyframes(bool wait = true);

  /// Answers a query; throws std::invalid_argument with a user-facing message on bad input.
  PlaceAnswer answer(QueryInput& input, QuerySequence::Response& response);
  /// Publishes the answer on ~loop_closure, for the frame of `header` (the keyframe localised, or a
  /// frame it stands for), and, when it is an accepted match, its stamps on ~loop_closure_stamps;
  /// returns why an accepted match could not go there (empty otherwise).
  std::string publishLoopClosure(const std_msgs::Header& header, const PlaceAnswer& answer,
                                 const QuerySequence::Response& response, const ros::Time& localised_keyframe_stamp);
  /// An accepted answer of continuous mode becomes the one restated for the frames its localised
  /// keyframe stands for (standing_frames.hpp), and those it has are restated now.
  void publishStandingClosures(const std_msgs::Header& header, const PlaceAnswer& answer,
                               const QuerySequence::Response& response);
  /// Restates the last accepted answer for the standing frames its keyframe gained since.
  void restateLastClosure();
  /// The closure of `keyframe` to `reference_index` was rejected: when it is the one restated, stops
  /// restating it. Returns whether it was.
  bool stopRestating(Stamp keyframe, int reference_index);
  MapInfo makeMapInfo();
  void publishMapInfoIfChanged();

  NodeParameters params_;
  PlaceRecognizer recognizer_;  ///< The map and both methods; thread-safe.
  /// recognizer_'s map and ~database: every keyframe goes through it. Thread-safe.
  std::unique_ptr<PersistentMap> map_;

  // The keyframe policies, the camera's frame id and the frame timings, under state_mutex_, which is
  // only ever held for a few instructions.
  std::mutex state_mutex_;
  KeyframePolicy keyframe_policy_;
  TravelPolicy travel_policy_;
  SequenceGaps sequence_gaps_;  // frames lost before the image callback
  double image_callback_start_ = 0.0;  // steady seconds when the last image callback began,
  double image_callback_end_ = 0.0;    // and returned; 0 before the first
  CameraSilence camera_silence_;  // thread-safe: outside state_mutex_
  KindThrottle query_failure_warning_{1.0};  // thread-safe; each kind of failed ~query once a second
  KindThrottle frame_failure_warning_;  // thread-safe; each kind of dropped frame once a kWarningPeriod
  StandingFrames standing_frames_;  // frames too similar to a recent keyframe, one per ~auto_query_period
  std::string camera_frame_id_;
  double frame_time_total_ms_ = 0.0;  // image callback cost of the keyframes, for ~map_info
  std::uint64_t frames_timed_ = 0;
  double frame_time_max_ms_ = 0.0;    // since the last ~map_info

  std::atomic<std::uint64_t> frames_received_{0};
  std::atomic<std::uint64_t> frames_skipped_{0};
  std::atomic<std::uint64_t> frames_too_similar_{0};  ///< Views too similar to a recent keyframe's.
  std::atomic<std::uint64_t> frames_without_pose_{0};
  std::atomic<std::uint64_t> frames_dropped_{0};
  std::atomic<std::uint64_t> frames_failed_{0};
  std::atomic<std::uint64_t> map_version_{0};  // bumped whenever frames are added or the map is reset
  std::uint64_t auto_query_version_ = 0;      // map_version_ at the last continuous-mode query
  int auto_query_size_ = 0;                   // map frames at the last continuous-mode query
  int session_start_size_ = 0;  // map frames before the camera's of this run: a map loaded at start-up or by ~load_map
  double auto_query_ms_ = 0.0;                // what its last query took
  /// Continuous mode's last accepted answer and its stamp, restated for its keyframe's standing frames
  /// (query thread only; the frames under state_mutex_).
  struct AcceptedClosure {
    std_msgs::Header header;
    PlaceAnswer answer;
    QuerySequence::Response response;
  };
  std::optional<AcceptedClosure> last_closure_;
  PendingRestatements pending_restatements_;
  // Held while ~map_info is composed and published: its timer's thread and the map services both do.
  std::mutex map_info_mutex_;
  MapInfo last_map_info_;
  bool map_info_published_ = false;

  // The robot's poses, for ~min_travel only (null otherwise: no /tf subscription).
  std::unique_ptr<tf2_ros::Buffer> tf_buffer_;
  std::unique_ptr<tf2_ros::TransformListener> tf_listener_;
  // A frame unknown to tf has been waited for ~tf_timeout once already (image callbacks only).
  mutable std::atomic<bool> waited_for_unknown_tf_frame_{false};

  ros::NodeHandle nh_;
  ros::NodeHandle private_nh_;
  ros::CallbackQueue query_queue_;
  ros::NodeHandle query_nh_;  // private_nh_ bound to query_queue_
  ros::CallbackQueue info_queue_;
  ros::NodeHandle info_nh_;  // private_nh_ bound to info_queue_: ~map_info, never waiting for a query
  image_transport::ImageTransport image_transport_;
  image_transport::Subscriber image_sub_;       // every transport but `compressed`
  ros::Subscriber compressed_image_sub_;         // `compressed`
  ros::Publisher loop_closure_pub_;
  ros::Publisher loop_closure_stamps_pub_;  // LIO-SAM's external loop closures: accepted ones only
  ros::Publisher map_info_pub_;
  std::unique_ptr<DebugImagePublisher> debug_image_;  // ~debug_image, drawn only while subscribed
  ros::ServiceServer query_srv_;
  ros::ServiceServer reset_srv_;
  ros::ServiceServer save_map_srv_;
  ros::ServiceServer reject_closure_srv_;
  ros::ServiceServer load_map_srv_;
  ros::WallTimer auto_query_timer_;
  ros::WallTimer map_info_timer_;
  ros::WallTimer camera_watch_timer_;
  std::unique_ptr<ros::AsyncSpinner> query_spinner_;
  std::unique_ptr<ros::AsyncSpinner> info_spinner_;
  std::unique_ptr<MasterWatch> master_watch_;  // re-registers everything above with a restarted master
};

}  // namespace node
}  // namespace mrs_vpr

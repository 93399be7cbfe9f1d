// The node's answers: ~query, and continuous mode's loop closures (with the closures restated for a
// stop), published on ~loop_closure and ~loop_closure_stamps.

#include <algorithm>
#include <chrono>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <limits>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/core/utility.hpp>

#include "mrs_vpr/LoopClosure.h"
#include "mrs_vpr/node/continuous_queries.hpp"
#include "mrs_vpr/node/image_conversion.hpp"
#include "mrs_vpr/node/loop_closure_stamps.hpp"
#include "mrs_vpr/node/place_recognition_node.hpp"
#include "mrs_vpr/node/ros_stamp.hpp"
#include "node_warnings.hpp"

namespace mrs_vpr {
namespace node {

bool PlaceRecognitionNode::queryCallback(QuerySequence::Request& request, QuerySequence::Response& response) {
  const auto start = std::chrono::steady_clock::now();
  response.success = false;
  response.reference_index = -1;
  QueryInput input;
  input.method = request.method;  // Empty: the recognizer's default method.
  PlaceAnswer answered;
  bool stopped = false;  // by the node's shutdown: said in the response, not warned about
  try {
    recognizer_.requireMethod(request.method);  // Before any image is described.
    if (!request.images.empty()) {
      if (request.recent_frames > 0) {
        throw std::invalid_argument("give either images or recent_frames, not both (got " +
                                    std::to_string(request.images.size()) + " images and recent_frames " +
                                    std::to_string(request.recent_frames) + ")");
      }
      if (request.images.size() < static_cast<std::size_t>(kMinSequenceFrames)) {  // Before any is described.
        throw std::invalid_argument("a test sequence needs at least " + std::to_string(kMinSequenceFrames) +
                                    " images, got " + std::to_string(request.images.size()));
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
    stopped = dynamic_cast<const QueryStopped*>(&error) != nullptr;
    response.message = stopped ? "the node is shutting down: the query was stopped" : error.what();
    response.reference_index = -1;
    response.accepted = false;
  }
  response.elapsed_ms = std::chrono::duration<float, std::milli>(std::chrono::steady_clock::now() - start).count();
  response.threads = static_cast<std::uint32_t>(std::max(1, cv::getNumThreads()));
  if (response.success) {
    const std::string unpublished = publishLoopClosure(input.header, answered, response, input.header.stamp);
    if (!unpublished.empty()) response.message += "; " + unpublished;
    if (!input.images) publishStandingClosures(input.header, answered, response);
    ROS_DEBUG("mrs_vpr: query (%s, %d frames) -> %d, confidence %.3f, %.1f ms", answered.method.c_str(),
              answered.query_length, response.reference_index, response.confidence, response.elapsed_ms);
  } else if (!stopped && query_failure_warning_.allows(kindOf(response.message), steadySeconds())) {
    ROS_WARN("mrs_vpr: query failed: %s", response.message.c_str());
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
      !input.images && params_.fixedMap()
          ? recognizer_.matchTrail(input.recent_frames, input.method, explain, input.end)
      : !input.images             ? recognizer_.matchRecent(input.recent_frames, input.method, explain, input.end)
      : travel_policy_.enabled()  ? recognizer_.match(*input.images, input.method, explain)
                                  : recognizer_.matchKeyframesOf(*input.images, input.method, explain);
  if (input.images) {
    input.header = input.image_headers.at(static_cast<std::size_t>(answered.localised_row));
  } else {
    // The map frame's own camera frame, as its image said (a loaded map's too); the camera's newest
    // for a frame that said none.
    input.header.stamp = rosTimeOf(answered.localised_stamp);
    input.header.frame_id = map_->frameIdOf(answered.localised_frame);
    if (input.header.frame_id.empty()) {
      std::lock_guard<std::mutex> lock(state_mutex_);
      input.header.frame_id = camera_frame_id_;
    }
  }
  if (explain != nullptr) {
    // What keyframing left out, so that a stop shows as frames skipped rather than as missing answers.
    // Short enough for the picture's 512 px.
    const std::string map_status = "skipped: " + std::to_string(frames_too_similar_.load()) + " too similar, " +
                                   std::to_string(frames_skipped_.load()) + " by keyframe policy";
    debug_image_->publish(input.header, answered, explanation, map_status);
  }
  const Match& match = answered.match;
  response.reference_index = match.reference_index;
  response.score = match.score;
  response.confidence = match.confidence;
  response.reference_stamp = rosTimeOf(answered.reference_stamp);
  response.localised_stamp = input.header.stamp;
  response.accepted = match.accepted;
  response.message = answered.verdict;
  response.method = answered.method;
  response.query_length = static_cast<std::uint32_t>(answered.query_length);
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
  last_closure_ = AcceptedClosure{header, answer, response};
  {
    std::lock_guard<std::mutex> lock(state_mutex_);
    pending_restatements_.accepted(answer.localised_stamp);
  }
  restateLastClosure();
}

void PlaceRecognitionNode::restateLastClosure() {
  if (!last_closure_) return;
  std::vector<Stamp> standing;
  {
    std::lock_guard<std::mutex> lock(state_mutex_);
    standing = pending_restatements_.take(standing_frames_);
  }
  for (const Stamp stamp : standing) {
    std_msgs::Header restated = last_closure_->header;
    restated.stamp = rosTimeOf(stamp);
    publishLoopClosure(restated, last_closure_->answer, last_closure_->response, last_closure_->header.stamp);
  }
}

bool PlaceRecognitionNode::stopRestating(Stamp keyframe, int reference_index) {
  if (!last_closure_ || last_closure_->answer.match.reference_index != reference_index) return false;
  {
    std::lock_guard<std::mutex> lock(state_mutex_);
    if (!pending_restatements_.reject(keyframe)) return false;
  }
  last_closure_.reset();
  return true;
}

void PlaceRecognitionNode::autoQueryCallback(const ros::WallTimerEvent&) {
  if (!flushWaitingKeyframes()) return;
  restateLastClosure();  // A stop at the keyframe it localised adds no keyframe, so no new question.
  const std::uint64_t version = map_version_.load();
  if (version == auto_query_version_) {
    return;  // nothing new since the last answer
  }
  const int recent = params_.autoQueryFrames();
  // A test sequence holds the camera's keyframes of this run only: one reaching back into a loaded
  // map would join two drives, and its centre could be a keyframe of the file. A fixed map's are
  // the trail's, all of this run, and the whole map is searched.
  long long first_size =
      std::max(recognizer_.fewestFramesForRecent(recent), static_cast<long long>(session_start_size_) + recent);
  int size = recognizer_.size();
  if (params_.fixedMap()) {
    if (recognizer_.size() < recent) return;  // nothing to localise in (yet: a map may be loaded)
    first_size = recent;
    size = static_cast<int>(std::min<std::int64_t>(recognizer_.trailSize(), std::numeric_limits<int>::max()));
    // Keyframes of a long pause (no map to localise in) that the trail no longer holds are not asked about.
    if (auto_query_size_ < size - kTrailKeyframes + recent) auto_query_size_ = 0;
  }
  if (size < first_size) {
    return;  // too early: not enough older frames to search yet
  }
  auto_query_version_ = version;
  // Each keyframe since the last question is localised once (continuous_queries.hpp), within
  // kContinuousShare of the period by the last question's time.
  // first_size <= size here, so it fits an int.
  const std::vector<int> ends = continuousQueryEnds(auto_query_size_, size, static_cast<int>(first_size),
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
      publishLoopClosure(input.header, answered, response,
                         input.header.stamp);  // warns itself when stamps cannot go out
      publishStandingClosures(input.header, answered, response);
    } catch (const QueryStopped&) {
      return;  // The node is shutting down.
    } catch (const std::exception& error) {
      // Each keyframe's question stands alone: the next ones are still asked.
      ROS_WARN_THROTTLE(kWarningPeriod, "mrs_vpr: continuous query failed: %s", error.what());
      continue;
    }
    auto_query_ms_ = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  }
}

}  // namespace node
}  // namespace mrs_vpr

// The node's map and its database: opening ~database at start-up, ~reset, ~save_map, ~load_map,
// ~reject_closure.

#include <algorithm>
#include <exception>
#include <filesystem>
#include <string>

#include "mrs_vpr/node/place_recognition_node.hpp"
#include "mrs_vpr/node/ros_stamp.hpp"
#include "mrs_vpr/store/map_traversal.hpp"
#include "../store/map_path.hpp"

namespace mrs_vpr {
namespace node {
namespace {

constexpr double kWriteErrorPeriod = 10.0;  // [s] between repeated errors about failing commits

/// `path` from the root: a relative one is the node's working directory's (~/.ros under roslaunch).
std::string absolutePath(const std::string& path) {
  std::error_code ignored;
  const std::filesystem::path absolute = std::filesystem::absolute(path, ignored);
  return absolute.empty() ? path : absolute.lexically_normal().string();
}

/// For a message about `path`: where a relative path led, which under roslaunch is ~/.ros, not the
/// folder the user typed it in; empty for an absolute path, an empty one or one of ~ (said otherwise).
std::string relativePathNote(const std::string& path) {
  if (path.empty() || path.front() == '/' || beginsWithHome(path) || path.find('\0') != std::string::npos) return "";
  return " ('" + path + "' is relative to the node's working folder: it names '" + absolutePath(path) + "')";
}

}  // namespace

void PlaceRecognitionNode::openMap() {
  // A database that cannot be read throws MapDatabaseError naming the file and the problem: the node
  // then exits rather than starting empty over a map it could not read.
  if (params_.fixedMap()) {
    // Read only, and not held: the map must exist (a mistyped path is an error, not a new empty map),
    // may be a file nobody may write, and other nodes may serve it too. ~reset and ~load_map change
    // the map in memory only.
    map_ = std::make_unique<PersistentMap>(recognizer_);
    if (!params_.database.empty()) {
      map_->load(params_.database);
      ROS_INFO("mrs_vpr: map database '%s': %d frames loaded, read only (~map_mode fixed: the map stays as "
               "loaded, and the camera's keyframes only localise in it)",
               absolutePath(params_.database).c_str(), recognizer_.size());
      warnOfKeyframingMismatch();
    }
    if (recognizer_.size() == 0) {
      ROS_WARN("mrs_vpr: ~map_mode is fixed and the map is empty: nothing is localised until a map is loaded "
               "(~load_map; or start with ~database)");
    }
    return;
  }
  if (params_.database.empty()) {
    map_ = std::make_unique<PersistentMap>(recognizer_);
    return;
  }
  map_ = std::make_unique<PersistentMap>(recognizer_, params_.database, params_.commit);
  startSession(recognizer_.size());
  ROS_INFO("mrs_vpr: map database '%s': %d frames loaded (%d linked to a place an earlier visit shows); keyframes "
           "are committed every %g s or %d frames",
           absolutePath(params_.database).c_str(), recognizer_.size(), recognizer_.state().linked_frames,
           params_.commit.period, params_.commit.frames);
  if (const int format = map_->convertedFromFormat()) {
    ROS_INFO("mrs_vpr: map database '%s': converted from format %d to %d (it now keeps the place links): releases "
             "before format %d cannot open it any more",
             absolutePath(params_.database).c_str(), format, MapDatabase::kFormatVersion, MapDatabase::kFormatVersion);
  }
  warnOfKeyframingMismatch();
}

void PlaceRecognitionNode::warnOfKeyframingMismatch() const {
  const std::string mismatch = keyframingMismatchOfMap();
  if (!mismatch.empty()) {
    ROS_WARN("mrs_vpr: map database '%s': %s", absolutePath(params_.database).c_str(), mismatch.c_str());
  }
}

std::string PlaceRecognitionNode::keyframingMismatchOfMap() const {
  // Keyframes by travel (odometry) are on the map's scale in metres, whatever its appearance change.
  if (params_.min_travel > 0.0) return "";
  return keyframingMismatch(map_->loadedTraversal(), recognizer_.recognizerParameters().min_appearance_change,
                            "~min_appearance_change");
}

bool PlaceRecognitionNode::resetCallback(std_srvs::Trigger::Request&, std_srvs::Trigger::Response& response) {
  try {
    const int cleared = map_->reset();
    startOverOnNewMap(0);
    response.success = true;
    const std::string where = map_->persistent() ? " from the map and from the database '" + map_->databasePath() + "'"
                              : params_.fixedMap() ? " from the map (~map_mode fixed: the map file is left as it is)"
                                                   : " (no ~database)";
    response.message = "cleared " + std::to_string(cleared) + " frames" + where;
    ROS_INFO("mrs_vpr: reference map reset (%s)", response.message.c_str());
  } catch (const std::exception& error) {
    response.success = false;
    response.message = std::string(error.what()) + "; the map is kept";
    ROS_ERROR("mrs_vpr: reset failed: %s", response.message.c_str());
  }
  publishMapInfoIfChanged();
  return true;  // Failures are reported in the response.
}

void PlaceRecognitionNode::startOverOnNewMap(int map_frames) {
  {
    std::lock_guard<std::mutex> lock(state_mutex_);
    keyframe_policy_.reset();
    travel_policy_.reset();
    standing_frames_.clear();
    pending_restatements_.clear();
  }
  last_closure_.reset();
  // Continuous mode's test sequences hold keyframes the camera added after the new map's frames only,
  // none of a loaded map's own. The services and continuous mode run on the query thread. The new version
  // makes its next period look, also at the frames a load held back, when no keyframe follows them. A
  // fixed map's questions are about the trail, which goes on: they go on where they were.
  if (params_.fixedMap()) {
    ++map_version_;
    return;
  }
  auto_query_size_ = map_frames;
  startSession(map_frames);
  ++map_version_;
}

void PlaceRecognitionNode::startSession(int map_frames) {
  session_start_size_ = map_frames;
  try {
    map_->startDrive(map_frames);  // The camera's keyframes are another drive than the map's.
  } catch (const std::exception& error) {  // The mark holds in memory; only the database lacks it.
    ROS_ERROR("mrs_vpr: could not record in the map database that the camera's keyframes begin another drive "
              "after the map's %d frames: %s", map_frames, error.what());
  }
  const int max_frames = params_.recognizer.max_frames;
  const int length = params_.autoQueryFrames();
  if (params_.auto_query_period <= 0.0 || max_frames <= 0 || max_frames - map_frames >= length) return;
  ROS_WARN("mrs_vpr: continuous mode asks with %d keyframes added after the map's %d frames, but ~max_frames (%d) "
           "leaves room for %d: it publishes nothing until ~reset, a smaller map is loaded or ~max_frames is raised",
           length, map_frames, max_frames, std::max(0, max_frames - map_frames));
}

bool PlaceRecognitionNode::saveMapCallback(SaveMap::Request& request, SaveMap::Response& response) {
  try {
    response.frames = static_cast<std::uint64_t>(map_->save(request.path));
    response.success = true;
    response.message = "saved " + std::to_string(response.frames) + " frames to '" + absolutePath(request.path) + "'";
    ROS_INFO("mrs_vpr: %s", response.message.c_str());
  } catch (const std::exception& error) {
    response.success = false;
    response.message = error.what() + relativePathNote(request.path);
    ROS_WARN("mrs_vpr: save_map failed: %s", response.message.c_str());
  }
  return true;
}

bool PlaceRecognitionNode::loadMapCallback(LoadMap::Request& request, LoadMap::Response& response) {
  try {
    if (request.path.empty()) throw std::invalid_argument("load_map needs a path");
    const int loaded = map_->load(request.path);
    startOverOnNewMap(loaded);
    response.frames = static_cast<std::uint64_t>(loaded);
    response.success = true;
    response.message = "loaded " + std::to_string(loaded) + " frames from '" + absolutePath(request.path) + "'" +
                       (map_->persistent() ? "; the database '" + map_->databasePath() + "' now holds them too"
                                           : "");
    const std::string mismatch = keyframingMismatchOfMap();
    if (mismatch.empty()) {
      ROS_INFO("mrs_vpr: %s", response.message.c_str());
    } else {
      response.message += "; warning: " + mismatch;
      ROS_WARN("mrs_vpr: %s", response.message.c_str());
    }
  } catch (const std::exception& error) {
    response.success = false;
    response.frames = static_cast<std::uint64_t>(recognizer_.size());
    response.message = error.what() + relativePathNote(request.path) + "; the current map is kept";
    ROS_WARN("mrs_vpr: load_map failed: %s", response.message.c_str());
  }
  publishMapInfoIfChanged();
  return true;
}

bool PlaceRecognitionNode::rejectClosureCallback(RejectClosure::Request& request, RejectClosure::Response& response) {
  std::string restating;  // Said whatever the links: a closure of a fixed map, say, links nothing.
  try {
    const Stamp stamp = stampOf(request.localised_keyframe_stamp);
    if (stamp.isZero()) {
      throw std::invalid_argument("localised_keyframe_stamp is 0: copy it from the closure's mrs_vpr/LoopClosure");
    }
    if (stopRestating(stamp, request.reference_index)) {
      restating = "; it is no longer restated for the frames of the stop at its keyframe";
    }
    const int frame = recognizer_.newestFrameStamped(stamp);
    if (frame < 0) {
      throw std::invalid_argument("no map keyframe has the stamp " + stamp.toString() +
                                  " (a closure of ~map_mode fixed localises a keyframe that is not in the map, and "
                                  "links nothing)");
    }
    const std::vector<PlaceLink> forgotten = map_->forgetClosure(frame, request.reference_index);
    response.success = true;
    response.links_forgotten = static_cast<std::uint32_t>(forgotten.size());
    response.message = "forgot the link of map frame " + std::to_string(frame) + " (stamp " + stamp.toString() +
                       ") to the place of map frame " + std::to_string(request.reference_index) +
                       (map_->persistent() ? ", in the map and its database" : "") + restating;
    ROS_INFO("mrs_vpr: %s", response.message.c_str());
  } catch (const std::exception& error) {
    response.success = false;
    response.message = std::string("reject_closure: ") + error.what() + "; the map's links are kept" + restating;
    ROS_WARN("mrs_vpr: %s", response.message.c_str());
  }
  response.frames_linked = static_cast<std::uint32_t>(recognizer_.state().linked_frames);
  publishMapInfoIfChanged();
  return true;
}

void PlaceRecognitionNode::reportWriteErrors() {
  const std::string error = map_->writeError();
  if (!error.empty()) {
    ROS_ERROR_THROTTLE(kWriteErrorPeriod, "mrs_vpr: keyframes cannot be committed to ~database (retrying): %s",
                       error.c_str());
  }
}

}  // namespace node
}  // namespace mrs_vpr

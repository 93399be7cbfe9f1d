#pragma once

#include <string>
#include <vector>

#include <ros/node_handle.h>

#include "mrs_vpr/node/travel_policy.hpp"
#include "mrs_vpr/parameters.hpp"
#include "mrs_vpr/store/map_writer.hpp"

namespace mrs_vpr {
namespace node {

/// Everything the node is configured with: the core's parameters plus the node's own. Each default
/// is written once, here or in mrs_vpr/parameters.hpp, and mirrored in config/default.yaml (a test
/// checks it). Allowed values are written once, in the tables of node_parameters.cpp and of the core.
struct NodeParameters {
  /// The core's parameters, read from ~descriptor/*, ~sequence/* and ~mrs/*.
  Parameters core;
  /// The map's capacity, its keyframes and how queries are answered: ~max_frames,
  /// ~max_pending_frames, ~min_appearance_change, ~recent_exclusion, ~default_method.
  RecognizerParams recognizer;

  double min_frame_interval = 0.0;  ///< Seconds between keyframes (by header stamp); 0 = off.
  int frame_stride = 1;             ///< Keep at most every n-th frame.
  double min_travel = 0.0;          ///< Metres travelled between keyframes (odometry by tf); 0 = off.
  std::string odom_frame = kDefaultOdomFrame;  ///< Fixed frame in which min_travel is measured.
  std::string base_frame = kDefaultBaseFrame;  ///< The robot's frame, whose travel is measured.
  double tf_timeout = 0.1;          ///< Longest wait for the robot's pose at a frame's stamp [s].
  int image_queue_size = 10;        ///< Subscriber queue of the image topic.
  double auto_query_period = 0.0;   ///< Continuous mode period [s]; 0 = off.
  int auto_query_frames = 0;        ///< Test sequence length in continuous mode; 0 = sequence/sequence_length.
  double map_info_rate = 1.0;       ///< Highest rate of ~map_info updates [Hz, wall-clock].
  int threads = 0;                  ///< Threads of a query's search (OpenCV's); 0 = one a core.
  std::string database;             ///< Map database path; empty = the map lives in memory only.
  std::string map_mode = "extend";  ///< "extend": keyframes join the map; "fixed": they only localise.
  CommitPolicy commit;              ///< ~commit_period, ~commit_frames: batching of the database's commits.

  /// Throws std::invalid_argument naming the first parameter out of range (as ~group/name) and the
  /// values it allows, in the words of `--help`.
  void validate() const;
  /// auto_query_frames, or sequence/sequence_length when it is 0.
  int autoQueryFrames() const;
  /// ~map_mode fixed: the map stays as it is, and the camera's keyframes join the recognizer's trail.
  bool fixedMap() const { return map_mode == "fixed"; }
};

/// The node's own parameters (the core's are in descriptorParameters(), sequenceParameters() and
/// mrsParameters()): each one's name, allowed values and meaning, written once.
const std::vector<ParameterSpec<NodeParameters>>& nodeParameters();
/// The batching of the map database's commits: ~commit_period and ~commit_frames.
const std::vector<ParameterSpec<CommitPolicy>>& commitParameters();

/**
 * Reads every parameter that is set under `private_nh` over the defaults (kiss-icp style: an unset
 * parameter keeps its default), then validates. Throws std::invalid_argument naming the parameter
 * (as ~group/name) when it has the wrong type or is out of range.
 */
NodeParameters loadParameters(const ros::NodeHandle& private_nh);

/// One line of the parameter reference printed by `mrs_vpr_node --help`.
struct ParameterDescription {
  std::string name;           ///< Private name, e.g. "mrs/tau".
  std::string type;           ///< "int", "double", "string".
  std::string default_value;  ///< As written in config/default.yaml.
  std::string range;          ///< Allowed values, as validate()'s messages give them.
  std::string meaning;
};

/// Every parameter with its default (taken from NodeParameters{}), range and meaning.
std::vector<ParameterDescription> describeParameters();

/// Parameters set under `private_nh` that the node does not know (typos), as "~name". Parameters of
/// image transport plugins are not reported.
std::vector<std::string> unknownParameters(const ros::NodeHandle& private_nh);

/// Of `names`, relative to the private namespace (e.g. "mrs/tau"), those the node does not know, as
/// "~name": neither in describeParameters() nor "image_transport" nor under the namespace of a known
/// image transport plugin (compressed/, compressedDepth/, theora/).
std::vector<std::string> unknownParameters(const std::vector<std::string>& names);

}  // namespace node
}  // namespace mrs_vpr

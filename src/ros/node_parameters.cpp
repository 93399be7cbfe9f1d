#include "mrs_vpr/ros/node_parameters.hpp"

#include <algorithm>
#include <cstdint>
#include <iomanip>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <XmlRpcValue.h>
#include <ros/param.h>

namespace mrs_vpr {
namespace node {
namespace {

/// Calls `visit(name, field, range, meaning)` for every parameter of `p`: the one list from which
/// the loader, the `--help` reference and the unknown-parameter check are built.
template <typename Params, typename Visitor>
void forEachParameter(Params& p, Visitor&& visit) {
  auto& d = p.core.descriptor;
  auto& s = p.core.sequence;
  auto& m = p.core.mrs;
  visit("descriptor/image_width", d.image_width, "4..1024", "Width the image is resized to [px].");
  visit("descriptor/image_height", d.image_height, "4..1024", "Height the image is resized to [px].");
  visit("descriptor/patch_size", d.patch_size, "divides width and height",
        "Side of the patch-normalisation patches [px].");
  visit("sequence/sequence_length", s.sequence_length, "2..10000",
        "Frames per test sequence in the per-frame protocol (continuous mode default).");
  visit("sequence/velocity_min", s.velocity_min, "(0, velocity_max]",
        "Slowest reference frames per test frame.");
  visit("sequence/velocity_max", s.velocity_max, "[velocity_min, 10]",
        "Fastest reference frames per test frame.");
  visit("sequence/velocity_step", s.velocity_step, "(0, 10), at most 1000 velocities",
        "Step between the velocities tried.");
  visit("sequence/contrast_window", s.contrast_window, "0 (off) or 2..1000",
        "Reference frames in the local contrast-enhancement window.");
  visit("sequence/match_exclusion", s.match_exclusion, "0..10000",
        "Frames around the best match excluded when looking for the runner-up.");
  visit("sequence/alignment", s.alignment, "causal, centred",
        "causal: the test sequence ends at the frame localised; centred: it is in the middle.");
  visit("sequence/accept_threshold", s.accept_threshold, "0..1000",
        "An answer is accepted when its confidence (distinctiveness, in standard deviations) reaches this.");
  visit("mrs/levels", m.levels, "0..8", "Coarsest temporal stride is 2^levels.");
  visit("mrs/min_coarse_frames", m.min_coarse_frames, "2..1000",
        "Fewer levels are used when the coarsest level would keep fewer test frames.");
  visit("mrs/pixel_pooling", m.pixel_pooling, "1..64, divides image_width * image_height",
        "Levels coarser than full resolution average runs of this many pixels.");
  visit("mrs/tau", m.tau, "1..16", "Particle overlap factor: initial particles = (M / N) * tau.");
  visit("mrs/index_shift", m.index_shift, "0..1000",
        "End-index search radius of a particle [frames of its level].");
  visit("mrs/coverage_threshold", m.coverage_threshold, "(0, 1)",
        "Go to the next level once particle coverage shrinks below this ratio.");
  visit("mrs/max_iterations", m.max_iterations, "1..1000", "Cap on particle iterations per level.");
  visit("mrs/resample_threshold", m.resample_threshold, "(0, 1]",
        "Resample when the effective particle count falls below this fraction.");
  visit("mrs/min_particles", m.min_particles, "1..100000", "Particles never drop below this.");
  visit("mrs/hypotheses", m.hypotheses, "2..1000",
        "Distinct minima of the coarsest level carried to the level below, which decides among them.");
  visit("mrs/seed", m.seed, "0..2147483647", "Seed of the particle search: same seed, same answer.");
  visit("min_frame_interval", p.min_frame_interval, ">= 0",
        "Seconds (by header stamp) between keyframes; 0 = no limit.");
  visit("frame_stride", p.frame_stride, "1..10000", "Keep at most every n-th image.");
  visit("max_frames", p.max_frames, "0 (unbounded) or >= 2",
        "Reference map capacity [frames]; further keyframes are dropped and counted.");
  visit("image_queue_size", p.image_queue_size, "1..10000", "Subscriber queue of the image topic.");
  visit("max_pending_frames", p.max_pending_frames, "1..1000000",
        "Keyframes buffered while a query holds the map; more are dropped and counted.");
  visit("recent_exclusion", p.recent_exclusion, "0..1000000",
        "Map frames just before a recent_frames test sequence that are not searched.");
  visit("default_method", p.default_method, "mrs, seqslam",
        "Method for requests with an empty method and for continuous mode.");
  visit("auto_query_period", p.auto_query_period, ">= 0",
        "Continuous mode: query with the newest frames every this many seconds; 0 = off.");
  visit("auto_query_frames", p.auto_query_frames, "0 or 2..1000000",
        "Test sequence length in continuous mode; 0 = sequence/sequence_length.");
  visit("map_info_rate", p.map_info_rate, "(0, 1000]", "Highest rate of ~map_info updates [Hz].");
}

std::string typeName(XmlRpc::XmlRpcValue::Type type) {
  switch (type) {
    case XmlRpc::XmlRpcValue::TypeBoolean: return "a boolean";
    case XmlRpc::XmlRpcValue::TypeInt: return "an integer";
    case XmlRpc::XmlRpcValue::TypeDouble: return "a number";
    case XmlRpc::XmlRpcValue::TypeString: return "a string";
    case XmlRpc::XmlRpcValue::TypeArray: return "a list";
    case XmlRpc::XmlRpcValue::TypeStruct: return "a dictionary";
    default: return "an invalid value";
  }
}

/// The value of ~name when it is set; throws when it is set but not of the expected type.
bool lookup(const ros::NodeHandle& nh, const std::string& name, XmlRpc::XmlRpcValue& value,
            XmlRpc::XmlRpcValue::Type expected, bool also_int = false) {
  if (!nh.getParam(name, value)) {
    return false;
  }
  if (value.getType() == expected || (also_int && value.getType() == XmlRpc::XmlRpcValue::TypeInt)) {
    return true;
  }
  // Silently keeping the default for `image_width: 64.0` or `tau: "2"` would hide the user's intent.
  throw std::invalid_argument("~" + name + " must be " + typeName(expected) + ", got " +
                              typeName(value.getType()));
}

void read(const ros::NodeHandle& nh, const std::string& name, int& field) {
  XmlRpc::XmlRpcValue value;
  if (lookup(nh, name, value, XmlRpc::XmlRpcValue::TypeInt)) {
    field = static_cast<int>(value);
  }
}

void read(const ros::NodeHandle& nh, const std::string& name, double& field) {
  XmlRpc::XmlRpcValue value;
  if (lookup(nh, name, value, XmlRpc::XmlRpcValue::TypeDouble, true)) {
    field = value.getType() == XmlRpc::XmlRpcValue::TypeInt ? static_cast<int>(value)
                                                             : static_cast<double>(value);
  }
}

void read(const ros::NodeHandle& nh, const std::string& name, std::string& field) {
  XmlRpc::XmlRpcValue value;
  if (lookup(nh, name, value, XmlRpc::XmlRpcValue::TypeString)) {
    field = static_cast<std::string>(value);
  }
}

void read(const ros::NodeHandle& nh, const std::string& name, std::uint64_t& field) {
  XmlRpc::XmlRpcValue value;
  if (lookup(nh, name, value, XmlRpc::XmlRpcValue::TypeInt)) {
    const int seed = static_cast<int>(value);
    if (seed < 0) {
      throw std::invalid_argument("~" + name + " must be in 0..2147483647, got " + std::to_string(seed));
    }
    field = static_cast<std::uint64_t>(seed);
  }
}

void read(const ros::NodeHandle& nh, const std::string& name, WindowAlignment& field) {
  XmlRpc::XmlRpcValue value;
  if (lookup(nh, name, value, XmlRpc::XmlRpcValue::TypeString)) {
    try {
      field = parseWindowAlignment(static_cast<std::string>(value));
    } catch (const std::invalid_argument&) {
      throw std::invalid_argument("~" + name + " must be causal or centred, got '" +
                                  static_cast<std::string>(value) + "'");
    }
  }
}

std::string format(int value) { return std::to_string(value); }
std::string format(std::uint64_t value) { return std::to_string(value); }
std::string format(const std::string& value) { return value.empty() ? "\"\"" : value; }
std::string format(WindowAlignment value) { return toString(value); }
std::string format(double value) {
  std::ostringstream out;
  out << value;
  std::string text = out.str();
  if (text.find_first_of(".e") == std::string::npos) {
    text += ".0";  // so that YAML reads it back as a float
  }
  return text;
}

std::string type(int) { return "int"; }
std::string type(std::uint64_t) { return "int"; }
std::string type(double) { return "double"; }
std::string type(const std::string&) { return "string"; }
std::string type(WindowAlignment) { return "string"; }

void require(bool condition, const std::string& name, const std::string& range, const std::string& got) {
  if (!condition) {
    throw std::invalid_argument("~" + name + " must be " + range + ", got " + got);
  }
}

}  // namespace

void NodeParameters::validate() const {
  // The core's messages already name the parameter as group/name with its range.
  core.validate();
  require(min_frame_interval >= 0.0, "min_frame_interval", ">= 0", format(min_frame_interval));
  require(frame_stride >= 1 && frame_stride <= 10000, "frame_stride", "in 1..10000", format(frame_stride));
  require(max_frames == 0 || max_frames >= 2, "max_frames", "0 (unbounded) or >= 2", format(max_frames));
  require(image_queue_size >= 1 && image_queue_size <= 10000, "image_queue_size", "in 1..10000",
          format(image_queue_size));
  require(max_pending_frames >= 1 && max_pending_frames <= 1000000, "max_pending_frames", "in 1..1000000",
          format(max_pending_frames));
  require(recent_exclusion >= 0 && recent_exclusion <= 1000000, "recent_exclusion", "in 0..1000000",
          format(recent_exclusion));
  require(default_method == "mrs" || default_method == "seqslam", "default_method", "mrs or seqslam",
          "'" + default_method + "'");
  require(auto_query_period >= 0.0, "auto_query_period", ">= 0 (0 = off)", format(auto_query_period));
  require(auto_query_frames == 0 || (auto_query_frames >= 2 && auto_query_frames <= 1000000),
          "auto_query_frames", "0 or 2..1000000", format(auto_query_frames));
  require(map_info_rate > 0.0 && map_info_rate <= 1000.0, "map_info_rate", "in (0, 1000]",
          format(map_info_rate));
}

int NodeParameters::autoQueryFrames() const {
  return auto_query_frames > 0 ? auto_query_frames : core.sequence.sequence_length;
}

NodeParameters loadParameters(const ros::NodeHandle& private_nh) {
  NodeParameters params;
  forEachParameter(params, [&](const char* name, auto& field, const char*, const char*) {
    read(private_nh, name, field);
  });
  params.validate();
  return params;
}

std::vector<ParameterDescription> describeParameters() {
  std::vector<ParameterDescription> descriptions;
  const NodeParameters defaults;
  forEachParameter(defaults, [&](const char* name, const auto& field, const char* range, const char* meaning) {
    descriptions.push_back({name, type(field), format(field), range, meaning});
  });
  return descriptions;
}

std::vector<std::string> unknownParameters(const ros::NodeHandle& private_nh) {
  std::vector<std::string> known;
  for (const auto& description : describeParameters()) {
    known.push_back(private_nh.resolveName(description.name));
  }
  const std::string prefix = private_nh.getNamespace() + "/";
  std::vector<std::string> names;
  std::vector<std::string> unknown;
  if (!ros::param::getParamNames(names)) {
    return unknown;
  }
  for (const auto& name : names) {
    if (name.compare(0, prefix.size(), prefix) != 0) {
      continue;
    }
    const std::string relative = name.substr(prefix.size());
    // Transport plugins read their own parameters (image_transport, compressed/..., theora/...).
    const bool core_group = relative.rfind("descriptor/", 0) == 0 || relative.rfind("sequence/", 0) == 0 ||
                            relative.rfind("mrs/", 0) == 0;
    const bool transport =
        relative == "image_transport" || (relative.find('/') != std::string::npos && !core_group);
    if (!transport && std::find(known.begin(), known.end(), name) == known.end()) {
      unknown.push_back("~" + relative);
    }
  }
  return unknown;
}

}  // namespace node
}  // namespace mrs_vpr

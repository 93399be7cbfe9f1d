#include "mrs_vpr/node/node_parameters.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <variant>

#include <XmlRpcValue.h>
#include <ros/param.h>

#include "mrs_vpr/node/travel_policy.hpp"
#include "mrs_vpr/parameter_binding.hpp"
#include "mrs_vpr/number_text.hpp"

namespace mrs_vpr {
namespace node {

const std::vector<ParameterSpec<NodeParameters>>& nodeParameters() {
  using P = NodeParameters;
  static const std::vector<ParameterSpec<P>> table = {
      {{"min_frame_interval", Range::closed(0, 86400), {}, "",
        "Seconds (by header stamp) between keyframes; 0 = no limit."},
       &P::min_frame_interval},
      {{"frame_stride", Range::closed(1, 10000), {}, "", "Keep at most every n-th image."}, &P::frame_stride},
      {{"min_travel", Range::atLeast(0), {}, "",
        "Metres the robot travels (~base_frame in ~odom_frame, by tf) between keyframes; 0 = off. For a "
        "robot that stops or changes speed."},
       &P::min_travel},
      {{"odom_frame", Range{}, {}, "a tf frame", "Fixed frame in which ~min_travel is measured."}, &P::odom_frame},
      {{"base_frame", Range{}, {}, "a tf frame", "The robot's frame, whose travel ~min_travel measures."},
       &P::base_frame},
      {{"tf_timeout", Range::openClosed(0, 10), {}, "",
        "Longest wait for the robot's pose at an image's stamp [s] (~min_travel > 0)."},
       &P::tf_timeout},
      {{"image_queue_size", Range::closed(1, 10000), {}, "", "Subscriber queue of the image topic."},
       &P::image_queue_size},
      {{"auto_query_period", Range::closed(0, 86400), {}, "",
        "Continuous mode: every this many seconds (wall-clock, also under use_sim_time), localise each "
        "keyframe that came since the last time (within a fifth of the period); 0 = off."},
       &P::auto_query_period},
      {{"auto_query_frames", Range::closed(kMinSequenceFrames, 1000000).orZero(), {}, "",
        "Test sequence length in continuous mode; 0 = sequence/sequence_length."},
       &P::auto_query_frames},
      {{"map_info_rate", Range::closed(0.001, 1000), {}, "", "Highest rate of ~map_info updates [Hz, wall-clock]."},
       &P::map_info_rate},
      {{"threads", Range::closed(0, 1024), {}, "",
        "Threads a query's search may use (OpenCV's); 0 = one a core. Process-wide: in a nodelet manager it "
        "sets every nodelet's OpenCV threads."},
       &P::threads},
      {{"database", Range{}, {}, "a file path; empty = memory only",
        "Map database (SQLite) loaded at start-up and extended with every keyframe, created when missing; with "
        "~map_mode fixed, only read at start-up (it must exist)."},
       &P::database},
      {{"map_mode", Range{}, {"extend", "fixed"}, "",
        "extend: every keyframe joins the map (and ~database), so that a drive closes loops with itself; fixed: "
        "the map stays as loaded (a map built earlier), and the camera's keyframes only localise in it "
        "(continuous mode and ~query {recent_frames} ask about them)."},
       &P::map_mode},
  };
  return table;
}

const std::vector<ParameterSpec<CommitPolicy>>& commitParameters() {
  using P = CommitPolicy;
  static const std::vector<ParameterSpec<P>> table = {
      {{"commit_period", Range::openClosed(0, 3600), {}, "",
        "Longest time a keyframe waits for its commit to ~database [s]."},
       &P::period},
      {{"commit_frames", Range::closed(1, 1000000), {}, "", "Most keyframes waiting for a commit to ~database."},
       &P::frames},
  };
  return table;
}

namespace {

/// One row of the node's table: the description, written once in a table above or in the core, and
/// where the value goes. The loader, `--help` and the unknown-parameter check are built from it.
using Entry = ParameterBinding<NodeParameters>;

const std::vector<Entry>& entries() {
  static const std::vector<Entry> table = [] {
    std::vector<Entry> all = coreParameterBindings<NodeParameters>();
    bindParameters(all, nodeParameters(), [](NodeParameters& p) -> NodeParameters& { return p; });
    bindParameters(all, commitParameters(), [](NodeParameters& p) -> CommitPolicy& { return p.commit; });
    return all;
  }();
  return table;
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

/// Throws when ~name holds a value other than the expected type.
void requireType(const std::string& name, const XmlRpc::XmlRpcValue& value, XmlRpc::XmlRpcValue::Type expected,
                 bool also_int = false) {
  if (value.getType() == expected || (also_int && value.getType() == XmlRpc::XmlRpcValue::TypeInt)) {
    return;
  }
  // Silently keeping the default for `image_width: 64.0` or `tau: "2"` would hide the user's intent.
  throw std::invalid_argument("~" + name + " must be " + typeName(expected) + ", got " + typeName(value.getType()));
}

/// The value of ~name when it is set; throws when it is set but not of the expected type.
bool lookup(const ros::NodeHandle& nh, const std::string& name, XmlRpc::XmlRpcValue& value,
            XmlRpc::XmlRpcValue::Type expected, bool also_int = false) {
  if (!nh.getParam(name, value)) {
    return false;
  }
  requireType(name, value, expected, also_int);
  return true;
}

/// Validation messages start with the parameter's name; the node's user knows it as ~name.
[[noreturn]] void throwPrivate(const std::invalid_argument& error) {
  throw std::invalid_argument("~" + std::string(error.what()));
}

/// The integer ~name when it is set. A whole number beyond 32 bits reaches the node as a double: it is
/// refused as out of the integer's range, which the message says, rather than as of another type.
bool lookupInteger(const ros::NodeHandle& nh, const ParameterInfo& info, int& number) {
  XmlRpc::XmlRpcValue value;
  if (!nh.getParam(info.name, value)) {
    return false;
  }
  if (value.getType() == XmlRpc::XmlRpcValue::TypeDouble) {
    const double whole = static_cast<double>(value);
    if (std::isfinite(whole) && whole == std::floor(whole) && std::abs(whole) > 2147483647.0) {
      throwPrivate(
          std::invalid_argument(info.rejection(numberText(whole), "a ROS parameter holds integers of 32 bits")));
    }
  }
  requireType(info.name, value, XmlRpc::XmlRpcValue::TypeInt);
  number = static_cast<int>(value);
  return true;
}

void read(const ros::NodeHandle& nh, const ParameterInfo& info, int& field) { lookupInteger(nh, info, field); }

void read(const ros::NodeHandle& nh, const ParameterInfo& info, double& field) {
  XmlRpc::XmlRpcValue value;
  if (lookup(nh, info.name, value, XmlRpc::XmlRpcValue::TypeDouble, true)) {
    field = value.getType() == XmlRpc::XmlRpcValue::TypeInt ? static_cast<int>(value)
                                                             : static_cast<double>(value);
  }
}

void read(const ros::NodeHandle& nh, const ParameterInfo& info, std::string& field) {
  XmlRpc::XmlRpcValue value;
  if (lookup(nh, info.name, value, XmlRpc::XmlRpcValue::TypeString)) {
    field = static_cast<std::string>(value);
  }
}

void read(const ros::NodeHandle& nh, const ParameterInfo& info, std::uint64_t& field) {
  int seed = 0;
  if (lookupInteger(nh, info, seed)) {
    try {
      info.require(seed);  // checked before the conversion, which would wrap a negative seed round
    } catch (const std::invalid_argument& error) {
      throwPrivate(error);
    }
    field = static_cast<std::uint64_t>(seed);
  }
}

void read(const ros::NodeHandle& nh, const ParameterInfo& info, WindowAlignment& field) {
  XmlRpc::XmlRpcValue value;
  if (lookup(nh, info.name, value, XmlRpc::XmlRpcValue::TypeString)) {
    try {
      field = parseWindowAlignment(static_cast<std::string>(value));
    } catch (const std::invalid_argument& error) {
      throwPrivate(error);
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

/// Namespaces of the image transport plugins of image_transport_plugins, which read their own
/// parameters under the subscriber's private namespace. Only these are let through: letting every
/// name with a '/' through hid typos such as ~sequnce/sequence_length.
const char* const kTransportNamespaces[] = {"compressed", "compressedDepth", "theora"};

bool isTransportParameter(const std::string& name) {
  if (name == "image_transport") {
    return true;  // the transport hint, read by image_transport itself
  }
  const std::string group = name.substr(0, name.find('/'));
  if (group == name) {
    return false;  // no namespace
  }
  return std::find(std::begin(kTransportNamespaces), std::end(kTransportNamespaces), group) !=
         std::end(kTransportNamespaces);
}

}  // namespace

void NodeParameters::validate() const {
  try {
    core.validate();
    recognizer.validate();
    requireInRange(nodeParameters(), *this);
    requireInRange(commitParameters(), commit);
  } catch (const std::invalid_argument& error) {
    throwPrivate(error);
  }
  if (min_travel > 0.0) {
    TravelPolicy::requireMeasurable(odom_frame, base_frame, "~odom_frame", "~base_frame", "~min_travel");
  }
}

int NodeParameters::autoQueryFrames() const {
  return auto_query_frames > 0 ? auto_query_frames : core.sequence.sequence_length;
}

NodeParameters loadParameters(const ros::NodeHandle& private_nh) {
  NodeParameters params;
  for (const auto& entry : entries()) {
    std::visit([&](auto* field) { read(private_nh, *entry.info, *field); }, entry.field(params));
  }
  // Read by image_transport, which takes any other type for "raw" without a word.
  XmlRpc::XmlRpcValue transport;
  lookup(private_nh, "image_transport", transport, XmlRpc::XmlRpcValue::TypeString);
  params.validate();
  return params;
}

std::vector<ParameterDescription> describeParameters() {
  std::vector<ParameterDescription> descriptions;
  NodeParameters defaults;
  for (const auto& entry : entries()) {
    std::visit(
        [&](auto* field) {
          descriptions.push_back(
              {entry.info->name, type(*field), format(*field), entry.info->allowed(), entry.info->meaning});
        },
        entry.field(defaults));
  }
  return descriptions;
}

std::vector<std::string> unknownParameters(const ros::NodeHandle& private_nh) {
  const std::string prefix = private_nh.getNamespace() + "/";
  std::vector<std::string> names;
  if (!ros::param::getParamNames(names)) {
    return {};
  }
  std::vector<std::string> relative;
  for (const auto& name : names) {
    if (name.compare(0, prefix.size(), prefix) == 0) {
      relative.push_back(name.substr(prefix.size()));
    }
  }
  return unknownParameters(relative);
}

std::vector<std::string> unknownParameters(const std::vector<std::string>& names) {
  std::vector<std::string> unknown;
  for (const auto& name : names) {
    const bool known = std::any_of(entries().begin(), entries().end(),
                                   [&](const Entry& entry) { return entry.info->name == name; });
    if (!known && !isTransportParameter(name)) {
      unknown.push_back("~" + name);
    }
  }
  return unknown;
}

}  // namespace node
}  // namespace mrs_vpr

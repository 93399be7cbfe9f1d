// query_bag: sends frames of a bag as a test sequence to the node's ~query service and prints the
// answer as one JSON object on stdout.

#include <chrono>
#include <cstdint>
#include <iostream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <boost/program_options.hpp>
#include <nlohmann/json.hpp>
#include <ros/console.h>
#include <ros/ros.h>

#include "mrs_vpr/QuerySequence.h"
#include "mrs_vpr/appearance_keyframes.hpp"
#include "mrs_vpr/descriptor.hpp"
#include "mrs_vpr/number_text.hpp"
#include "mrs_vpr/node/image_conversion.hpp"
#include "mrs_vpr/node/bag_images.hpp"
#include "mrs_vpr/node/bag_keyframes.hpp"
#include "mrs_vpr/node/node_parameters.hpp"
#include "descriptor_options.hpp"
#include "keyframing_options.hpp"
#include "interruption.hpp"
#include "tool_main.hpp"

namespace po = boost::program_options;
using json = nlohmann::ordered_json;  // Keeps fields in the documented order.

namespace {

constexpr const char* kUsage =
    "Usage: query_bag --bag B.bag --topic T [--start I] --count N [--min-travel M [--odom-frame F]\n"
    "                 [--base-frame B]] [--min-appearance-change C] [--method mrs|seqslam]\n"
    "                 [--service /mrs_vpr/query] [--timeout SEC]\n"
    "       query_bag --recent-frames K [--method mrs|seqslam] [--service /mrs_vpr/query]\n"
    "\n"
    "Calls the mrs_vpr node's query service (mrs_vpr/QuerySequence) with frames I..I+N-1 of topic T\n"
    "(oldest first), or with the node's own K most recent frames, and prints the response as JSON.\n"
    "With --min-travel, the test sequence is the N frames from I on that are M metres apart by the\n"
    "bag's own /tf (B in F), as the node's ~min_travel keeps them: a map spaced so is queried alike.\n"
    "Without it, the N frames are keyframes by appearance change, as the node keeps a camera's frames:\n"
    "by the node's own ~min_appearance_change and front end (read from its parameters, the namespace of\n"
    "--service), unless --min-appearance-change or front-end options are given (0: N consecutive frames).\n"
    "The node keyframes the images it gets as its camera's: query_length counts those it searched.\n"
    "Exit code 0 when the node answered with success, 1 otherwise, 130 on Ctrl-C.\n";

/// What --help shows as the default of an option whose default is the node's own setting.
constexpr const char* kTheNodes = "the node's";

/// Where the test sequence lies in a bag, and how its frames are chosen there.
struct BagSequence {
  std::string bag_path;
  std::string topic;
  int start = 0;
  int count = 0;
  mrs_vpr::bag::TravelSettings travel;
  double min_appearance_change = mrs_vpr::RecognizerParams{}.min_appearance_change;
  mrs_vpr::DescriptorParams front_end;
};

/// A ROS time in integer nanoseconds, exact where seconds in a double are not (4294967295.999999999 s).
std::int64_t exactNanoseconds(const ros::Time& time) { return static_cast<std::int64_t>(time.toNSec()); }

/// Keyframes as the node serving `service` keeps them: its front end and ~min_appearance_change, read
/// from its parameters as it read them at start-up (its private namespace is the service's). Options
/// given on the command line stay as given. Warns when the node keyframes by travel instead.
void keyframeAsTheNode(const std::string& service, const po::variables_map& variables, BagSequence& from_bag,
                       json& request) {
  const bool options_given =
      mrs_vpr::tools::descriptorOptionsGiven(variables) ||
      mrs_vpr::tools::givenOnCommandLine(variables, "min-appearance-change");
  // Without a master (checked first: a NodeHandle would wait for one) the service call fails anyway.
  if (from_bag.travel.min_travel != 0.0 || options_given || !ros::master::check()) {
    request["keyframing"] = "command line";
    return;
  }
  const std::string node = ros::names::parentNamespace(service);
  // Started by hand, now that the master answers (ros::start() would wait for one): started by the
  // NodeHandle below instead, roscpp would stop when it ends, before the service is called.
  ros::start();
  const mrs_vpr::node::NodeParameters params = mrs_vpr::node::loadParameters(ros::NodeHandle(node));
  from_bag.front_end = params.core.descriptor;
  from_bag.min_appearance_change = params.recognizer.min_appearance_change;
  request["keyframing"] = "the parameters of " + node;
  request["front_end"] = from_bag.front_end.describe();
  if (params.min_travel > 0.0) {
    std::cerr << "query_bag: warning: " << node << " keyframes by travel (~min_travel "
              << mrs_vpr::numberText(params.min_travel) << " m): give --min-travel to space the frames as its map's\n";
  }
}

/// The test sequence's images in the bag, chosen as the node would keep them; `request` records how.
std::vector<sensor_msgs::ImageConstPtr> readTestSequence(const BagSequence& from_bag, json& request) {
  const std::string& bag_path = from_bag.bag_path;
  const std::string& topic = from_bag.topic;
  const int start = from_bag.start;
  const int count = from_bag.count;
  const double min_appearance_change = from_bag.min_appearance_change;
  const mrs_vpr::bag::TravelSettings& travel = from_bag.travel;
  std::vector<sensor_msgs::ImageConstPtr> images;
  if (travel.min_travel == 0.0 && min_appearance_change > 0.0) {
    // As the node keeps a camera's frames without odometry: those whose view has changed.
    const mrs_vpr::DescriptorExtractor extractor(from_bag.front_end);
    mrs_vpr::AppearanceKeyframes keyframes(from_bag.front_end, min_appearance_change);
    int offered = 0;
    images = mrs_vpr::bag::readChosen(
        bag_path, topic, start, count,
        [&](const sensor_msgs::ImageConstPtr& image) {
          ++offered;
          cv::Mat descriptor;
          try {
            descriptor = mrs_vpr::node::describeImage(extractor, *image);
          } catch (const std::exception& error) {
            throw std::invalid_argument("message " + std::to_string(start + offered - 1) + " of topic '" + topic +
                                        "' in bag '" + bag_path + "': " + error.what());
          }
          return keyframes.offer(descriptor);
        },
        [&] { return std::to_string(offered) + " frames offered at --min-appearance-change " +
                     mrs_vpr::numberText(min_appearance_change); },
        mrs_vpr::tools::stopIfInterrupted);
    request["min_appearance_change"] = min_appearance_change;
    request["frames_read"] = offered;
  } else if (travel.min_travel == 0.0) {
    images = mrs_vpr::bag::readImages(bag_path, topic, start, count, mrs_vpr::tools::stopIfInterrupted);
  } else {
    mrs_vpr::bag::BagKeyframes keyframes(bag_path, travel, mrs_vpr::tools::stopIfInterrupted);
    images = mrs_vpr::bag::readKeyframes(bag_path, topic, start, count, keyframes, mrs_vpr::tools::stopIfInterrupted);
    request["min_travel"] = travel.min_travel;
    // Where the sequence ends in the bag: frames from --start on that were read to choose it.
    request["frames_read"] = keyframes.frames();
  }
  return images;
}

/// The node's answer as the JSON object printed, with the time the call took and what was asked.
json answerJson(const mrs_vpr::QuerySequence::Response& response, double round_trip_ms, const json& request) {
  return {{"success", static_cast<bool>(response.success)},
          {"message", response.message},
          {"reference_index", response.reference_index},
          {"reference_stamp", response.reference_stamp.toSec()},
          {"reference_stamp_ns", exactNanoseconds(response.reference_stamp)},
          {"localised_stamp", response.localised_stamp.toSec()},
          {"localised_stamp_ns", exactNanoseconds(response.localised_stamp)},
          {"score", response.score},
          {"confidence", response.confidence},
          {"accepted", static_cast<bool>(response.accepted)},
          {"method", response.method},
          {"query_length", response.query_length},
          {"elapsed_ms", response.elapsed_ms},
          {"threads", response.threads},
          {"round_trip_ms", round_trip_ms},
          {"request", request}};
}

/// Waits up to `timeout` seconds for `service` to be advertised; false when it is not. A Ctrl-C or
/// SIGTERM ends the wait (Interrupted), as roscpp's own wait would not before the node has started.
bool waitForQueryService(const std::string& service, double timeout) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout);
  for (;;) {
    mrs_vpr::tools::stopIfInterrupted();
    if (ros::service::exists(service, false)) return true;
    if (std::chrono::steady_clock::now() >= deadline) return false;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

int run(int argc, char** argv) {
  // Strips ROS remapping arguments (name:=value) before the options are parsed.
  // Ctrl-C is noted and acted on between the bag's messages and steps (a second one ends the tool at
  // once): roscpp's handler would only end its own waits, and only once the node has started.
  ros::init(argc, argv, "query_bag",
            ros::init_options::AnonymousName | ros::init_options::NoRosout | ros::init_options::NoSigintHandler);
  mrs_vpr::tools::catchInterruptions();
  // roscpp prints its informational messages (e.g. while waiting for the service) on stdout, which
  // must hold nothing but the JSON answer; warnings and errors go to stderr.
  if (ros::console::set_logger_level(ROSCONSOLE_ROOT_LOGGER_NAME, ros::console::levels::Warn)) {
    ros::console::notifyLoggerLevelsChanged();
  }

  BagSequence from_bag;
  std::string method;  // Empty: the node's ~default_method.
  std::string service = "/mrs_vpr/query";
  int recent_frames = 0;
  double timeout = 10.0;
  po::options_description description("Options");
  // clang-format off
  description.add_options()
      ("help,h", "print this help")
      ("bag", po::value(&from_bag.bag_path), "bag holding the test sequence")
      ("topic", po::value(&from_bag.topic), "image topic in the bag")
      ("start", po::value(&from_bag.start)->default_value(from_bag.start),
       "first frame (index among the topic's messages)")
      ("count", po::value(&from_bag.count), "frames in the test sequence");
  // clang-format on
  mrs_vpr::tools::addKeyframingOptions(
      description, from_bag.travel, from_bag.min_appearance_change,
      "metres between the sequence's frames, by the bag's /tf (0: keyframes by appearance change instead)",
      "without --min-travel: the sequence's frames are keyframes by appearance change, as the node's "
      "~min_appearance_change keeps them (0 = consecutive frames)",
      kTheNodes);
  // clang-format off
  description.add_options()
      ("recent-frames", po::value(&recent_frames), "instead of a bag: the node's own K most recent frames")
      ("method", po::value(&method), "mrs | seqslam (default: the node's ~default_method)")
      ("service", po::value(&service)->default_value(service), "the node's query service")
      ("timeout", po::value(&timeout)->default_value(timeout), "seconds to wait for the service, (0, 3600]");
  // clang-format on
  mrs_vpr::tools::addDescriptorOptions(description, from_bag.front_end, kTheNodes);
  po::variables_map variables;
  if (!mrs_vpr::tools::parseCommandLine(argc, argv, kUsage, description, variables)) return 0;
  mrs_vpr::tools::refuseEmptyPaths(variables, {"bag"});
  mrs_vpr::tools::refuseOtherFrontEndsOptions(variables, from_bag.front_end);
  mrs_vpr::RecognizerParams keyframing;
  keyframing.min_appearance_change = from_bag.min_appearance_change;
  keyframing.validate();
  // Checked now, not by the node after --timeout seconds of waiting for it ("": the node's default).
  if (!method.empty() && method != "mrs" && method != "seqslam") {
    throw std::invalid_argument("--method must be mrs or seqslam, got '" + method + "'");
  }
  std::string why;
  if (service.empty()) throw std::invalid_argument("--service must not be empty");
  if (!ros::names::validate(service, why)) {
    throw std::invalid_argument("--service '" + service + "' is not a valid ROS name: " + why);
  }
  // A negative duration would make roscpp wait for the service for ever.
  if (!(timeout > 0.0 && timeout <= 3600.0)) {
    throw std::invalid_argument("--timeout must be in (0, 3600] s, got " + mrs_vpr::numberText(timeout));
  }

  mrs_vpr::QuerySequence query;
  query.request.method = method;
  json request = {{"method", method}, {"service", service}};
  if (variables.count("recent-frames") > 0) {
    if (variables.count("bag") > 0) throw std::invalid_argument("give either --bag or --recent-frames, not both");
    if (from_bag.travel.min_travel != 0.0) {
      throw std::invalid_argument("--min-travel needs --bag, not --recent-frames");
    }
    if (recent_frames < mrs_vpr::kMinSequenceFrames) {
      throw std::invalid_argument("--recent-frames must be >= " + std::to_string(mrs_vpr::kMinSequenceFrames) +
                                  ", as ~query takes it");
    }
    query.request.recent_frames = static_cast<std::uint32_t>(recent_frames);
    request["recent_frames"] = recent_frames;
  } else {
    // Given empty (an unset shell variable), an option is named as such, not as missing.
    if (variables.count("topic") != 0 && !variables["topic"].defaulted() && from_bag.topic.empty()) {
      throw std::invalid_argument("--topic is empty: name the image topic of the bag (rosbag info BAG lists them)");
    }
    if (from_bag.bag_path.empty() || from_bag.topic.empty() || variables.count("count") == 0) {
      throw std::invalid_argument("--bag, --topic and --count are required (or --recent-frames)");
    }
    if (from_bag.start < 0) throw std::invalid_argument("--start must be >= 0");
    if (from_bag.count < mrs_vpr::kMinSequenceFrames) {
      throw std::invalid_argument("--count must be >= " + std::to_string(mrs_vpr::kMinSequenceFrames) +
                                  ", as ~query takes it");
    }
    request["bag"] = from_bag.bag_path;
    request["topic"] = from_bag.topic;
    request["start"] = from_bag.start;
    request["count"] = from_bag.count;
    keyframeAsTheNode(service, variables, from_bag, request);
    const std::vector<sensor_msgs::ImageConstPtr> images = readTestSequence(from_bag, request);
    mrs_vpr::tools::stopIfInterrupted();
    for (const sensor_msgs::ImageConstPtr& image : images) query.request.images.push_back(*image);
    const ros::Time& last = query.request.images.back().header.stamp;
    request["last_stamp"] = last.toSec();
    request["last_stamp_ns"] = exactNanoseconds(last);
  }

  if (!waitForQueryService(service, timeout)) {
    if (!ros::master::check()) {
      throw std::runtime_error("service " + service + " is not available after " + mrs_vpr::numberText(timeout) +
                               " s: no ROS master answers at ROS_MASTER_URI=" + ros::master::getURI() +
                               " (is roscore running?)");
    }
    throw std::runtime_error("service " + service + " is not available after " + mrs_vpr::numberText(timeout) +
                             " s (is the mrs_vpr node running? ROS_MASTER_URI=" + ros::master::getURI() + ")");
  }
  const auto sent = std::chrono::steady_clock::now();
  // A persistent connection: on a one-shot one, roscpp can fail a call whose answer was already sent
  // when it sees the server hang up before reading that answer (ros/ros_comm#1976).
  ros::NodeHandle nh;
  ros::ServiceClient client = nh.serviceClient<mrs_vpr::QuerySequence>(service, /*persistent=*/true);
  mrs_vpr::tools::stopIfInterrupted();
  if (!client.call(query)) {
    mrs_vpr::tools::stopIfInterrupted();
    throw std::runtime_error("calling " + service + " failed (the node may have died or the types differ)");
  }
  mrs_vpr::tools::stopIfInterrupted();  // A Ctrl-C while the node answered: the tool was stopped.
  const double round_trip_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - sent).count();

  const json answer = answerJson(query.response, round_trip_ms, request);
  std::cout << answer.dump(-1, ' ', false, json::error_handler_t::replace) << std::endl;  // Any bytes of a path.
  return query.response.success ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) { return mrs_vpr::tools::runTool("query_bag", run, argc, argv); }

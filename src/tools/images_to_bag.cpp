// images_to_bag: an image folder (file-name order) -> a bag of sensor_msgs/Image at a fixed rate.

#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <boost/program_options.hpp>
#include <ros/names.h>
#include <ros/time.h>
#include <rosbag/bag.h>

#include "mrs_vpr/evaluation/image_folder.hpp"
#include "mrs_vpr/evaluation/progress_line.hpp"
#include "mrs_vpr/node/bag_images.hpp"
#include "mrs_vpr/number_text.hpp"
#include "apart_from_inputs.hpp"
#include "output_in_progress.hpp"
#include "tool_main.hpp"

namespace po = boost::program_options;

namespace {

constexpr const char* kUsage =
    "Usage: images_to_bag --images DIR --bag OUT.bag --topic T --rate HZ [--encoding bgr8|mono8]\n"
    "                     [--start-time SEC] [--frame-id ID] [--force]\n"
    "\n"
    "Writes the images of DIR, in file-name order, as sensor_msgs/Image messages on topic T, one every\n"
    "1/HZ seconds from --start-time (Unix time; default: now). Header stamp and bag time are equal.\n"
    "The bag appears only once every image is in it: a bad image leaves no partial bag. An existing\n"
    "OUT.bag is replaced only with --force.\n";

int run(int argc, char** argv) {
  std::string images;
  std::string bag_path;
  std::string topic;
  std::string encoding = "bgr8";
  std::string frame_id = "camera";
  double rate = 0.0;
  double start_time = -1.0;
  bool force = false;
  po::options_description description("Options");
  // clang-format off
  description.add_options()
      ("help,h", "print this help")
      ("images", po::value(&images)->required(), "folder of images")
      ("bag", po::value(&bag_path)->required(), "bag to write")
      ("force", po::bool_switch(&force), "replace an existing bag")
      ("topic", po::value(&topic)->required(), "topic of the images, e.g. /camera/image_raw")
      ("rate", po::value(&rate)->required(), "frames per second [Hz], > 0 and at most 1e9")
      ("encoding", po::value(&encoding)->default_value(encoding), "bgr8 | mono8")
      ("start-time", po::value(&start_time), "stamp of the first frame [s since the Unix epoch] (default: now)")
      ("frame-id", po::value(&frame_id)->default_value(frame_id), "header.frame_id of the images");
  // clang-format on
  po::variables_map variables;
  if (!mrs_vpr::tools::parseCommandLine(argc, argv, kUsage, description, variables)) return 0;
  mrs_vpr::tools::refuseEmptyPaths(variables, {"images", "bag"});
  mrs_vpr::bag::requireFrameRate(rate);
  if (topic.empty()) throw std::invalid_argument("--topic must not be empty");
  std::string why;
  if (!ros::names::validate(topic, why)) {
    throw std::invalid_argument("--topic '" + topic + "' is not a valid ROS topic name: " + why);
  }
  // A link names the bag it points to, as build_map's --output does: that file is replaced, not the link.
  if (std::filesystem::is_symlink(bag_path)) bag_path = mrs_vpr::tools::linkTarget("--bag", bag_path);
  // Checked before any work: a folder would be found only when the finished bag is renamed.
  mrs_vpr::tools::requireApartFromInputs({"--bag", bag_path}, {{"--images", images}});
  if (std::filesystem::is_directory(bag_path)) {
    throw std::invalid_argument("'" + bag_path + "' is a folder; --bag names the bag file to write");
  }
  mrs_vpr::tools::requireNoSpecialFile("--bag", bag_path);
  if (std::filesystem::exists(bag_path) && !force) {
    throw std::invalid_argument("'" + bag_path + "' exists; use --force to replace it");
  }
  const std::filesystem::path folder = std::filesystem::path(bag_path).parent_path();
  if (!folder.empty() && !std::filesystem::is_directory(folder)) {
    throw std::invalid_argument("--bag '" + bag_path + "': there is no folder " + folder.string());
  }
  // rosbag's only word for this would be "Error opening file".
  const std::string bag_folder = folder.empty() ? "." : folder.string();
  if (::access(bag_folder.c_str(), W_OK | X_OK) != 0) {
    throw std::invalid_argument("--bag '" + bag_path + "': the folder " + bag_folder + " cannot be written to (" +
                                std::strerror(errno) + ")");
  }
  if (encoding != "bgr8" && encoding != "mono8") {
    throw std::invalid_argument("unknown encoding '" + encoding + "' (expected bgr8 or mono8)");
  }
  if (variables.count("start-time") == 0) {
    start_time = ros::WallTime::now().toSec();  // Wall-clock time: no ROS master, no /clock.
  }
  // A bag's earliest time is 1 ns (ros::TIME_MIN): a start that rounds to 0 would fail in rosbag.
  if (!(start_time >= 1e-9)) {
    throw std::invalid_argument("--start-time must be at least 1 ns (a bag cannot hold time 0), got " +
                                mrs_vpr::numberText(start_time));
  }

  // Read (and check) the folder before creating the bag, so that a bad folder leaves no empty bag.
  std::vector<std::string> left_out;
  const std::vector<std::string> files = mrs_vpr::listImageFiles(images, &left_out);
  for (const std::string& note : {mrs_vpr::leftOutNote(images, left_out), mrs_vpr::fractionOrderNote(files)}) {
    if (!note.empty()) std::cerr << "images_to_bag: " << note << "\n";
  }
  try {
    mrs_vpr::bag::frameStamp(start_time, static_cast<long long>(files.size()) - 1, rate);  // the latest stamp
  } catch (const std::invalid_argument& error) {
    throw std::invalid_argument(std::string("the images cannot all be stamped: ") + error.what() +
                                "; use a higher --rate or an earlier --start-time");
  }
  mrs_vpr::tools::catchInterruptions();
  mrs_vpr::tools::OutputInProgress output(bag_path);
  rosbag::Bag bag;
  bag.open(output.temporary(), rosbag::bagmode::Write);
  int written = 0;
  mrs_vpr::ProgressLine progress =
      mrs_vpr::ProgressLine::onStderr("  " + bag_path, "images", static_cast<long long>(files.size()));
  mrs_vpr::forEachImage(images, [&](int index, const std::string& path, const cv::Mat& image) {
    mrs_vpr::tools::stopIfInterrupted();
    // Stamps from the frame number, not accumulated, so they never drift.
    const ros::Time stamp = mrs_vpr::bag::frameStamp(start_time, index, rate);
    try {
      bag.write(topic, stamp, mrs_vpr::bag::toImageMessage(image, encoding, stamp, frame_id, static_cast<std::uint32_t>(index)));
    } catch (const std::invalid_argument& error) {
      throw std::runtime_error("image '" + path + "': " + error.what());
    }
    progress.update(++written);
  });
  progress.finish();
  bag.close();
  output.commit();
  std::cerr << "images_to_bag: wrote " << written << " images to " << bag_path << " on " << topic << " at " << rate
            << " Hz\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return mrs_vpr::tools::runTool("images_to_bag", run, argc, argv); }

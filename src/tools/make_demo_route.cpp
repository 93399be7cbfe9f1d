// make_demo_route: a generated route (two traversals with known alignment) as reference.bag,
// query.bag and ground_truth.csv, optionally also as image folders for mrs_vpr_eval.

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <boost/program_options.hpp>
#include <ros/names.h>
#include <ros/time.h>
#include <rosbag/bag.h>

#include "mrs_vpr/image_codecs.hpp"
#include "mrs_vpr/node/bag_images.hpp"
#include "mrs_vpr/synthetic_route.hpp"
#include "output_in_progress.hpp"
#include "tool_main.hpp"

namespace po = boost::program_options;
namespace fs = std::filesystem;

namespace {

constexpr const char* kUsage =
    "Usage: make_demo_route --output DIR [--reference-frames M] [--query-frames Q] [--topic T]\n"
    "                       [--rate HZ] [--start-time SEC] [--seed S] [--images] [--force]\n"
    "\n"
    "Generates two traversals of one synthetic route (the second one at 0.8..1.2 times the speed, with\n"
    "other illumination, contrast, blur, noise and small shifts) and writes DIR/reference.bag,\n"
    "DIR/query.bag (bgr8 sensor_msgs/Image on T) and DIR/ground_truth.csv (query_index,\n"
    "matching_ref_indices). Reference frame i is stamped start-time + i / rate; the query traversal\n"
    "starts one hour later. --images also writes DIR/reference/ and DIR/query/ as PNG folders. The\n"
    "files of an earlier route in DIR are replaced only with --force.\n";

void writeBag(const std::string& path, const std::string& topic, const std::vector<cv::Mat>& frames, double start,
              double rate) {
  rosbag::Bag bag;
  bag.open(path, rosbag::bagmode::Write);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    mrs_vpr::tools::stopIfInterrupted();
    const ros::Time stamp = mrs_vpr::bag::frameStamp(start, static_cast<long long>(i), rate);
    bag.write(topic, stamp, mrs_vpr::bag::toImageMessage(frames[i], "bgr8", stamp, "camera", static_cast<std::uint32_t>(i)));
  }
  bag.close();
}

/// The name of frame `index` in a traversal's folder.
std::string frameName(std::size_t index) {
  std::ostringstream name;
  name << std::setw(6) << std::setfill('0') << index << ".png";
  return name.str();
}

/// Throws unless `folder` is missing or holds only frames as writeFolder names them: an earlier
/// route's traversal, which --force may replace. Anything else in it is not the tool's to remove.
void requireEarlierFramesOnly(const fs::path& folder) {
  if (!fs::exists(folder)) return;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder)) {
    const std::string name = entry.path().filename().string();
    const bool frame = entry.is_regular_file() && name.size() == 10 && name.compare(6, 4, ".png") == 0 &&
                       std::all_of(name.begin(), name.begin() + 6, [](char c) { return c >= '0' && c <= '9'; });
    if (!frame) {
      throw std::invalid_argument("'" + folder.string() + "' holds '" + name +
                                  "', which make_demo_route did not write: it is not replaced");
    }
  }
}

void writeFolder(const fs::path& folder, const std::vector<cv::Mat>& frames) {
  for (std::size_t i = 0; i < frames.size(); ++i) {
    mrs_vpr::tools::stopIfInterrupted();
    const fs::path file = folder / frameName(i);
    if (!mrs_vpr::image_codecs::write(file.string(), frames[i])) {
      throw std::runtime_error("cannot write '" + file.string() + "'");
    }
  }
}

int run(int argc, char** argv) {
  mrs_vpr::SyntheticRouteParams route_params;
  route_params.reference_frames = 600;
  route_params.query_frames = 400;
  std::string output;
  std::string topic = "/camera/image_raw";
  double rate = 20.0;
  double start_time = 1.7e9;  // A fixed, plausible epoch time: same route, same bags.
  long long seed = static_cast<long long>(route_params.seed);
  po::options_description description("Options");
  // clang-format off
  description.add_options()
      ("help,h", "print this help")
      ("output", po::value(&output)->required(), "folder to write into (created)")
      ("reference-frames", po::value(&route_params.reference_frames)->default_value(route_params.reference_frames),
       "frames of the reference traversal")
      ("query-frames", po::value(&route_params.query_frames)->default_value(route_params.query_frames),
       "frames of the query traversal")
      ("topic", po::value(&topic)->default_value(topic), "image topic in the bags")
      ("rate", po::value(&rate)->default_value(rate), "frame rate of the stamps [Hz]")
      ("start-time", po::value(&start_time)->default_value(start_time), "stamp of the first reference frame [s]")
      ("seed", po::value(&seed)->default_value(seed), "seed of the route, >= 0")
      ("images", "also write the traversals as PNG folders")
      ("force", "replace the files of an earlier route in DIR");
  // clang-format on
  po::variables_map variables;
  if (!mrs_vpr::tools::parseCommandLine(argc, argv, kUsage, description, variables)) return 0;
  mrs_vpr::tools::refuseEmptyPaths(variables, {"output"});
  mrs_vpr::bag::requireFrameRate(rate);
  if (!(start_time > 0.0)) throw std::invalid_argument("--start-time must be > 0 s");
  if (seed < 0) throw std::invalid_argument("--seed must be >= 0, got " + std::to_string(seed));
  route_params.seed = static_cast<std::uint64_t>(seed);
  std::string why;
  if (topic.empty() || !ros::names::validate(topic, why)) {
    throw std::invalid_argument("--topic '" + topic + "' is not a valid ROS topic name" +
                                (why.empty() ? "" : ": " + why));
  }
  route_params.validate();  // Frame counts first: a stamp of frame -1 says nothing about them.
  // Both traversals' last stamps, before anything is written: the query one starts an hour later.
  try {
    mrs_vpr::bag::frameStamp(start_time, route_params.reference_frames - 1, rate);
    mrs_vpr::bag::frameStamp(start_time + 3600.0, route_params.query_frames - 1, rate);
  } catch (const std::invalid_argument& error) {
    throw std::invalid_argument(std::string("the traversals cannot all be stamped: ") + error.what());
  }

  const fs::path folder(output);
  if (variables.count("force") == 0) {
    for (const char* name : {"reference.bag", "query.bag", "ground_truth.csv", "reference", "query"}) {
      if (fs::exists(folder / name)) {
        throw std::invalid_argument("'" + (folder / name).string() +
                                    "' exists: use --force to replace an earlier route's files");
      }
    }
  }
  // Checked before anything is removed or written, with the folders an interrupted run left aside.
  const bool images = variables.count("images") > 0;
  const std::vector<std::string> traversals = {"reference", "query"};
  for (const std::string& traversal : traversals) {
    requireEarlierFramesOnly(folder / traversal);
    requireEarlierFramesOnly(folder / (traversal + ".part"));
  }
  const mrs_vpr::SyntheticRoute route = mrs_vpr::generateSyntheticRoute(route_params);
  mrs_vpr::tools::catchInterruptions();
  fs::create_directories(folder);
  // Every file of the route is written aside and takes its name only once all are complete: a failure
  // or Ctrl-C leaves an earlier route as it was, never half replaced.
  using mrs_vpr::tools::OutputInProgress;
  OutputInProgress reference_bag((folder / "reference.bag").string());
  OutputInProgress query_bag((folder / "query.bag").string());
  OutputInProgress truth_file((folder / "ground_truth.csv").string());
  writeBag(reference_bag.temporary(), topic, route.reference, start_time, rate);
  writeBag(query_bag.temporary(), topic, route.query, start_time + 3600.0, rate);
  {
    std::ofstream truth(truth_file.temporary());
    truth << "query_index,matching_ref_indices\n";
    for (std::size_t i = 0; i < route.query_to_reference.size(); ++i) {
      truth << i << "," << route.query_to_reference[i] << "\n";
    }
    if (!truth.flush()) throw std::runtime_error("cannot write '" + (folder / "ground_truth.csv").string() + "'");
  }
  std::vector<std::unique_ptr<OutputInProgress>> frame_folders;
  if (images) {
    for (const std::string& traversal : traversals) {
      frame_folders.push_back(std::make_unique<OutputInProgress>((folder / traversal).string()));
      // An interrupted earlier run's folder there is removed (requireEarlierFramesOnly checked it).
      writeFolder(frame_folders.back()->emptyFolder(), traversal == "reference" ? route.reference : route.query);
    }
  }
  // An earlier route's frames go with it: they would stay beside the new route's (or its bags). Checked
  // again: something may have been put there while the route was made.
  for (const std::string& traversal : traversals) requireEarlierFramesOnly(folder / traversal);
  mrs_vpr::tools::stopIfInterrupted();  // A signal from now on is only noted: the renames complete.
  for (const std::string& traversal : traversals) fs::remove_all(folder / traversal);
  for (OutputInProgress* output : {&reference_bag, &query_bag, &truth_file}) output->commit();
  for (const auto& output : frame_folders) output->commit();
  std::cerr << "make_demo_route: " << route.reference.size() << " reference and " << route.query.size()
            << " query frames of " << route_params.image_width << "x" << route_params.image_height << " px in "
            << output << "\n";
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return mrs_vpr::tools::runTool("make_demo_route", run, argc, argv); }

// make_drive: an image folder (a route, in file-name order) driven as a camera-only vehicle drives it,
// with stops, a slow and a fast stretch, written as an image folder with drive.csv; and the ground
// truth between two such drives, for mrs_vpr_eval --ground-truth.

#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <boost/algorithm/string.hpp>
#include <boost/program_options.hpp>
#include <opencv2/imgproc.hpp>

#include "mrs_vpr/descriptor.hpp"
#include "mrs_vpr/evaluation/camera_drive.hpp"
#include "mrs_vpr/evaluation/drive_file.hpp"
#include "mrs_vpr/evaluation/image_folder.hpp"
#include "mrs_vpr/evaluation/progress_line.hpp"
#include "mrs_vpr/evaluation/route_places.hpp"
#include "mrs_vpr/image_codecs.hpp"
#include "apart_from_inputs.hpp"
#include "output_in_progress.hpp"
#include "tool_main.hpp"

namespace po = boost::program_options;
namespace fs = std::filesystem;

namespace {

constexpr const char* kUsage =
    "Usage: make_drive --images DIR --output DRIVE [--begin F] [--end F] [--seed S] [--stops K]\n"
    "                  [--stop-frames-min N] [--stop-frames-max N] [--slow-frames N] [--fast-frames N]\n"
    "                  [--noise G] [--vibration PX] [--gain G] [--force]\n"
    "       make_drive --ground-truth FILE.csv --reference DRIVE_A --query DRIVE_B [--route-tolerance T]\n"
    "                  [--places-from DIR[,DIR...]] [--force]\n"
    "\n"
    "The first form drives the route of DIR's images [F, F_end) (file-name order) as a camera-only vehicle\n"
    "does: it stops K times (after a route frame, for N_min..N_max frames, the view with sensor noise,\n"
    "sub-pixel vibration, a gain change and a passer-by crossing it; never an exact copy), shows each frame\n"
    "of one stretch twice (half speed) and leaves out every other frame of another (double speed). It\n"
    "writes DRIVE/000000.png ... and DRIVE/drive.csv (drive_frame,route_frame,kind), route frames\n"
    "numbered as DIR's images. Noise, vibration and the figure are given at 64 px width and scaled with\n"
    "the images' width. The same seed gives the same drive.\n"
    "\n"
    "The second form writes the ground truth of two drives of one route (e.g. the same frame numbers in\n"
    "two seasons): query frame i matches the reference frames whose route frame is within T of its own.\n"
    "With --places-from (the route's image folders, e.g. both seasons), route frames where the recording\n"
    "camera stood in every folder count as one place, and T counts places: a station where the recording\n"
    "stood still is one place, not dozens of frames apart.\n"
    "Then: rosrun mrs_vpr mrs_vpr_eval --reference DRIVE_A --query DRIVE_B --ground-truth FILE.csv\n"
    "      --protocol per-frame\n";

struct Options {
  std::string images;
  std::string output;
  int begin = 0;
  int end = -1;  ///< -1: to the folder's end.
  mrs_vpr::CameraDriveSettings drive;
  std::string ground_truth;
  std::string reference;
  std::string query;
  int route_tolerance = 2;
  std::string places_from;  ///< Comma-separated route image folders; empty: every route frame a place.
  bool force = false;
};

/// The name of drive frame `index` among `count`: zero-padded to 6 digits or more, so that file-name
/// order is drive order.
std::string frameName(int index, int count) {
  const int digits = std::max(6, static_cast<int>(std::to_string(std::max(count - 1, 0)).size()));
  std::ostringstream name;
  name << std::setw(digits) << std::setfill('0') << index << ".png";
  return name.str();
}

/// Refuses an output that exists unless --force allows replacing it, and never replaces a folder that
/// is not a drive (one without drive.csv).
void checkOutputFolder(const std::string& output, bool force) {
  if (!fs::exists(output)) {
    mrs_vpr::tools::requireParentFolder("--output", output);
    return;
  }
  if (!fs::is_directory(output)) throw std::invalid_argument("'" + output + "' is a file; --output names a folder");
  if (fs::is_empty(output)) return;
  if (!force) throw std::invalid_argument("'" + output + "' exists and is not empty; use --force to replace a drive");
  if (!fs::exists(fs::path(output) / mrs_vpr::kDriveFileName)) {
    throw std::invalid_argument("'" + output + "' holds no " + std::string(mrs_vpr::kDriveFileName) +
                                ": --force replaces a drive only, not another folder");
  }
}

/// The drive of the route into OUTPUT.part, renamed to OUTPUT once complete.
void writeDrive(const Options& options) {
  mrs_vpr::tools::requireApartFromInputs({"--output", options.output}, {{"--images", options.images}});
  mrs_vpr::tools::requireNoInputInside({"--output", options.output}, {{"--images", options.images}});
  std::vector<std::string> left_out;
  const std::vector<std::string> files = mrs_vpr::listImageFiles(options.images, &left_out);
  for (const std::string& note : {mrs_vpr::leftOutNote(options.images, left_out), mrs_vpr::fractionOrderNote(files)}) {
    if (!note.empty()) std::cerr << "make_drive: " << note << "\n";
  }
  const int available = static_cast<int>(files.size());
  const int end = options.end < 0 ? available : options.end;
  if (options.begin < 0 || options.begin >= end || end > available) {
    throw std::invalid_argument("--begin " + std::to_string(options.begin) + " and --end " + std::to_string(end) +
                                " must satisfy 0 <= begin < end <= " + std::to_string(available) + " (the images of '" +
                                options.images + "')");
  }
  checkOutputFolder(options.output, options.force);
  const mrs_vpr::CameraDrive drive(end - options.begin, options.drive);

  mrs_vpr::tools::catchInterruptions();
  mrs_vpr::tools::OutputInProgress output(options.output);  // Removed on an error: no half-written drive.
  const fs::path part = output.emptyFolder();
  mrs_vpr::ProgressLine progress = mrs_vpr::ProgressLine::onStderr("  " + options.output, "frames", drive.size());
  int loaded = -1;  // The route frame whose image is in `route_image`: a stop draws it many times.
  cv::Mat route_image;
  cv::Size size;
  for (int i = 0; i < drive.size(); ++i) {
    mrs_vpr::tools::stopIfInterrupted();
    const int route_frame = drive.frames()[static_cast<std::size_t>(i)].route_frame;
    if (route_frame != loaded) {
      const std::string& file = files[static_cast<std::size_t>(options.begin + route_frame)];
      route_image = mrs_vpr::loadImage(file);
      // A drive's noise and gain are in 8-bit grey levels: 16-bit frames are drawn as their 8-bit
      // originals, as images_to_bag and the evaluator read them.
      if (route_image.depth() == CV_16U) route_image.convertTo(route_image, CV_8U, 1.0 / 257.0);
      if (size.empty()) size = route_image.size();
      if (route_image.size() != size) {
        throw std::runtime_error("image '" + file + "' is " + std::to_string(route_image.cols) + "x" +
                                 std::to_string(route_image.rows) + " but the first is " + std::to_string(size.width) +
                                 "x" + std::to_string(size.height) + ": all images of a route must have one size");
      }
      loaded = route_frame;
    }
    cv::Mat image;
    try {
      image = drive.render(i, route_image);
    } catch (const std::invalid_argument& error) {
      throw std::runtime_error("image '" + files[static_cast<std::size_t>(options.begin + route_frame)] +
                               "': " + error.what());
    }
    const std::string path = (part / frameName(i, drive.size())).string();
    if (!mrs_vpr::image_codecs::write(path, image)) throw std::runtime_error("cannot write '" + path + "'");
    progress.update(i + 1);
  }
  progress.finish();
  mrs_vpr::writeDriveFile((part / mrs_vpr::kDriveFileName).string(), drive.frames(), options.begin);
  fs::remove_all(options.output);  // checkOutputFolder allowed it: empty, or a drive and --force.
  output.commit();

  int stopped = 0;
  for (const mrs_vpr::DriveFrame& frame : drive.frames()) stopped += frame.kind == mrs_vpr::DriveFrameKind::kStopped;
  const auto stretch = [&](const char* speed, int begin) {
    return begin < 0 ? std::string(", no ") + speed + " stretch"
                     : std::string(", ") + speed + " from route frame " + std::to_string(options.begin + begin);
  };
  std::cerr << "make_drive: " << drive.size() << " frames of route frames " << options.begin << ".." << end - 1
            << " in " << options.output << ": " << options.drive.stops << " stops (" << stopped << " frames)"
            << stretch("half speed", drive.slowBegin()) << stretch("double speed", drive.fastBegin()) << "\n";
}

/// Every image of `folder` (file-name order) in grey, at most kPlacesWidth pixels wide: the steps of
/// a route are compared relative to its median step, which does not need the full resolution.
std::vector<cv::Mat> routeImages(const std::string& folder) {
  constexpr int kPlacesWidth = 64;
  std::vector<cv::Mat> images;
  for (const std::string& file : mrs_vpr::listImageFiles(folder)) {
    cv::Mat buffer;
    cv::Mat image = mrs_vpr::toGrey(mrs_vpr::loadImage(file), mrs_vpr::ChannelOrder::kBgr, buffer);
    if (image.cols > kPlacesWidth) {
      cv::resize(image, image, cv::Size(kPlacesWidth, std::max(1, image.rows * kPlacesWidth / image.cols)), 0, 0,
                 cv::INTER_AREA);
    }
    images.push_back(image);
  }
  return images;
}

/// The place of each route frame (evaluation/route_places.hpp) from comma-separated image folders.
std::vector<int> routePlacesOf(const std::string& folders) {
  std::vector<std::string> names;
  boost::split(names, folders, boost::is_any_of(","));
  std::vector<std::vector<cv::Mat>> traversals;
  for (const std::string& name : names) {
    traversals.push_back(routeImages(name));
    if (traversals.back().size() != traversals.front().size()) {
      throw std::invalid_argument("--places-from: '" + name + "' has " + std::to_string(traversals.back().size()) +
                                  " images but '" + names.front() + "' has " +
                                  std::to_string(traversals.front().size()) +
                                  ": the folders must show the same route frames");
    }
  }
  std::vector<const std::vector<cv::Mat>*> pointers;
  for (const std::vector<cv::Mat>& traversal : traversals) pointers.push_back(&traversal);
  return mrs_vpr::routePlaces(pointers);
}

/// The ground truth of two drives, as mrs_vpr_eval reads it.
void writeGroundTruth(const Options& options) {
  mrs_vpr::tools::requireApartFromInputs({"--ground-truth", options.ground_truth},
                                         {{"--reference", options.reference}, {"--query", options.query}});
  if (fs::is_directory(options.ground_truth)) {
    throw std::invalid_argument("'" + options.ground_truth +
                                "' is a folder; --ground-truth names the CSV file to write");
  }
  if (fs::exists(options.ground_truth) && !options.force) {
    throw std::invalid_argument("'" + options.ground_truth + "' exists; use --force to replace it");
  }
  const auto route_of = [](const std::string& drive) {
    return mrs_vpr::routeFramesOf(mrs_vpr::readDriveFile((fs::path(drive) / mrs_vpr::kDriveFileName).string()));
  };
  std::vector<int> reference = route_of(options.reference);
  std::vector<int> query = route_of(options.query);
  if (!options.places_from.empty()) {
    const std::vector<int> places = routePlacesOf(options.places_from);
    reference = mrs_vpr::placesOf(reference, places);
    query = mrs_vpr::placesOf(query, places);
  }
  const mrs_vpr::GroundTruth truth = mrs_vpr::driveGroundTruth(reference, query, options.route_tolerance);
  std::ofstream file(options.ground_truth);
  file << "query_index,matching_ref_indices\n";
  int without_truth = 0;
  for (const auto& [query_frame, matches] : truth) {
    file << query_frame << ",";
    for (std::size_t k = 0; k < matches.size(); ++k) file << (k > 0 ? " " : "") << matches[k];
    file << "\n";
    without_truth += matches.empty() ? 1 : 0;
  }
  if (!file) throw std::runtime_error("cannot write '" + options.ground_truth + "'");
  std::cerr << "make_drive: ground truth of " << query.size() << " query frames against " << reference.size()
            << " reference frames (route tolerance " << options.route_tolerance
            << (options.places_from.empty() ? " route frames" : " places") << ") in " << options.ground_truth;
  if (without_truth > 0) std::cerr << "; " << without_truth << " query frames show no reference frame's place";
  std::cerr << "\n";
}

int run(int argc, char** argv) {
  Options options;
  mrs_vpr::CameraDriveSettings& drive = options.drive;
  std::int64_t seed = static_cast<std::int64_t>(drive.seed);  // Signed, so that a negative seed is refused.
  po::options_description description("Options");
  // clang-format off
  description.add_options()
      ("help,h", "print this help")
      ("images", po::value(&options.images), "folder of the route's images (file-name order)")
      ("output", po::value(&options.output), "folder to write the drive into (created)")
      ("begin", po::value(&options.begin)->default_value(options.begin), "first route frame: index of an image of DIR")
      ("end", po::value(&options.end), "route frame after the last (default: DIR's image count)")
      ("seed", po::value(&seed)->default_value(seed), "seed of the stops, stretches, noise and passers-by")
      ("stops", po::value(&drive.stops)->default_value(drive.stops), "stops along the route")
      ("stop-frames-min", po::value(&drive.stop_frames_min)->default_value(drive.stop_frames_min),
       "frames of the shortest stop")
      ("stop-frames-max", po::value(&drive.stop_frames_max)->default_value(drive.stop_frames_max),
       "frames of the longest stop")
      ("slow-frames", po::value(&drive.slow_frames)->default_value(drive.slow_frames),
       "route frames of the half-speed stretch, 0 = none")
      ("fast-frames", po::value(&drive.fast_frames)->default_value(drive.fast_frames),
       "route frames of the double-speed stretch, 0 = none")
      ("noise", po::value(&drive.noise_std)->default_value(drive.noise_std),
       "sensor noise of a standing camera [grey levels at 64 px width]")
      ("vibration", po::value(&drive.vibration)->default_value(drive.vibration),
       "largest shift of a standing camera [px at 64 px width]")
      ("gain", po::value(&drive.gain)->default_value(drive.gain), "largest relative gain change of a standing camera")
      ("ground-truth", po::value(&options.ground_truth), "write the ground truth of --query against --reference here")
      ("reference", po::value(&options.reference), "reference drive (a folder make_drive wrote)")
      ("query", po::value(&options.query), "query drive (a folder make_drive wrote)")
      ("route-tolerance", po::value(&options.route_tolerance)->default_value(options.route_tolerance),
       "route frames (or places, with --places-from) apart that still show the same place")
      ("places-from", po::value(&options.places_from),
       "the route's image folders, comma-separated: route frames where the recording camera stood in all of them "
       "are one place")
      ("force", po::bool_switch(&options.force), "replace an existing drive or ground-truth file");
  // clang-format on
  po::variables_map variables;
  if (!mrs_vpr::tools::parseCommandLine(argc, argv, kUsage, description, variables)) return 0;
  mrs_vpr::tools::refuseEmptyPaths(variables,
                                   {"images", "output", "ground-truth", "reference", "query", "places-from"});
  if (seed < 0) throw std::invalid_argument("--seed must be >= 0, got " + std::to_string(seed));
  drive.seed = static_cast<std::uint64_t>(seed);

  const bool drives = !options.images.empty() || !options.output.empty();
  const bool truth = !options.ground_truth.empty() || !options.reference.empty() || !options.query.empty();
  if (drives == truth) {
    throw std::invalid_argument("give either --images and --output (a drive) or --ground-truth, --reference and "
                                "--query (the truth of two drives)");
  }
  if (drives) {
    if (options.images.empty() || options.output.empty())
      throw std::invalid_argument("a drive needs --images and --output");
    if (!options.places_from.empty()) throw std::invalid_argument("--places-from belongs to the ground truth's form");
    writeDrive(options);
  } else {
    if (options.ground_truth.empty() || options.reference.empty() || options.query.empty()) {
      throw std::invalid_argument("the ground truth needs --ground-truth, --reference and --query");
    }
    writeGroundTruth(options);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) { return mrs_vpr::tools::runTool("make_drive", run, argc, argv); }

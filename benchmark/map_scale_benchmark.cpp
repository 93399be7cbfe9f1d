// Map-scale benchmark: load time, resident memory and query time of maps of 10k to 1M real frames.
//
// Prints figures; it is not a test. For each size it writes a map database (once; reused on later
// runs) of real frames: the Nordland summer half, as the true places, at a seeded position among
// distractors made of the shared real frames (Nordland turned upside down or by 180 degrees, and the
// corridor), in
// segments of a few hundred frames, each played forwards or backwards with its own shift, gain,
// offset and noise, so that the map is never a repetition of itself. Then a fresh process (so that
// nothing of the writing is resident) loads the map into a PlaceRecognizer and answers winter
// queries of N frames with both methods, side by side.
//
// Then continuous mode: frames of the route in winter join the map as keyframes, a few per period,
// and matchRecent answers once a period; the row gives the CPU time of those queries per period.
// Last, service questions about the map's newest frames ("recent" rows), both methods on one map.
//
//   mrs_vpr_map_scale_benchmark --data DIR [--sizes 10k,100k,1M] [--dir /tmp/mrs_vpr_map_scale]
//                               [--lengths 10,50,100,300] [--queries 5] [--brute-queries 2] [--threads 1]
//                               [--periods 20] [--keyframes-per-period 3] [--seed 42] [--load-map]
//
// With --load-map, last: a node's persistent map of the same frames replaced by them (~load_map), and
// how far that raised the process's peak memory.

#include <malloc.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <istream>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "mrs_vpr/evaluation/image_folder.hpp"
#include "mrs_vpr/memory_reuse.hpp"
#include "mrs_vpr/mrs/recent_rows.hpp"
#include "mrs_vpr/place_recognizer.hpp"
#include "mrs_vpr/store/map_database.hpp"
#include "mrs_vpr/store/map_writer.hpp"
#include "mrs_vpr/store/persistent_map.hpp"
#include "tools/tool_main.hpp"
#include "map_scale_options.hpp"
#include "map_scale_rows.hpp"
#include "process_usage.hpp"
#include "scale_map.hpp"
#include "tools/stopwatch.hpp"

namespace mrs_vpr {
namespace benchmark {

using tools::Clock;
using tools::secondsSince;

namespace {

/// ~load_map's memory: a node's persistent map (a scratch database beside `path`) loads the map at
/// `path` (into an empty map), then again (replacing a map of the same frames, as ~load_map replaces a
/// node's map). Prints how far each raised the process's peak resident memory, and what stayed
/// resident after the first, per frame.
void measureLoadMap(const std::string& path, const mrs_vpr::DescriptorParams& descriptor) {
  const std::string scratch = path + ".load_map.db";
  const auto removeScratch = [&] {
    std::remove(scratch.c_str());
    mrs_vpr::MapDatabase::removeCompanions(scratch);
  };
  removeScratch();
  mrs_vpr::RecognizerParams limits;
  limits.max_frames = 0;
  mrs_vpr::PlaceRecognizer recognizer(paramsFor(10, descriptor), limits);
  {
    mrs_vpr::PersistentMap node_map(recognizer, scratch, mrs_vpr::CommitPolicy{});
    // Each load's peak over the resident memory before it [B a frame], and the seconds it took.
    const auto load = [&](double& peak_per_frame, double& seconds) {
      if (!resetPeakResident()) throw std::runtime_error("--load-map: this system cannot reset the peak memory");
      const auto before = residentBytes();
      const auto start = Clock::now();
      const int frames = node_map.load(path);
      seconds = secondsSince(start);
      peak_per_frame = static_cast<double>(residentBytes().second - before.first) / frames;
      return frames;
    };
    double first_peak = 0.0, first_s = 0.0, again_peak = 0.0, again_s = 0.0;
    malloc_trim(0);
    const long long resident_before = residentBytes().first;
    const int frames = load(first_peak, first_s);
    const double kept = static_cast<double>(residentBytes().first - resident_before) / frames;
    load(again_peak, again_s);
    std::printf("%9s  ~load_map of %d frames into a node's empty map: %.2f s, peak +%.0f B a frame, %.0f B a frame "
                "resident after; again, replacing them: %.2f s, peak +%.0f B a frame\n",
                sizeName(frames).c_str(), frames, first_s, first_peak, kept, again_s, again_peak);
  }
  removeScratch();
}

/// The child: loads one map and answers the queries; prints its rows.
int measure(const MapScaleOptions& options) {
  cv::setNumThreads(options.threads);
  const mrs_vpr::DescriptorParams descriptor =
      mrs_vpr::MapDatabase(options.measure, mrs_vpr::MapAccess::kReadOnly).descriptorParams();
  const auto before = residentBytes();
  const auto load_start = Clock::now();
  mrs_vpr::RecognizerParams limits;
  limits.max_frames = 0;  // Unbounded: the largest maps measured may exceed the default capacity.
  limits.min_appearance_change = 0.0;  // The map's frames are keyframes already.
  mrs_vpr::PlaceRecognizer recognizer(paramsFor(10, descriptor), limits);
  {
    const mrs_vpr::MapDatabase map(options.measure, descriptor);
    recognizer.reserve(static_cast<int>(map.size()));
    map.forEachFrame(
        [&](const mrs_vpr::StoredFrame& frame) { recognizer.addDescriptor(frame.descriptor, frame.stamp); });
    recognizer.flush();
  }
  const double load_s = secondsSince(load_start);
  const auto after = residentBytes();
  const int frames = recognizer.size();
  const double rss_per_frame = static_cast<double>(after.first - before.first) / frames;
  const double peak_per_frame = static_cast<double>(after.second) / frames;

  const std::vector<cv::Mat> winter = mrs_vpr::loadImageFolder(options.data + "/nordland/winter");
  const std::vector<cv::Mat> summer = mrs_vpr::loadImageFolder(options.data + "/nordland/summer");
  for (int length : options.lengths) {
    if (length >= 128) {
      // A recognizer with the long sequences' velocity step over the same frames (a view, not a copy,
      // is not offered by PlaceRecognizer: the map is loaded again into a second one).
      mrs_vpr::PlaceRecognizer fine(paramsFor(length, descriptor), limits);
      fine.reserve(frames);
      recognizer.visitFrames(0, frames, [&](const cv::Mat& d, mrs_vpr::Stamp stamp) { fine.addDescriptor(d, stamp); });
      fine.flush();
      measureLength(options, fine, length, load_s, rss_per_frame, peak_per_frame, winter, summer);
    } else {
      measureLength(options, recognizer, length, load_s, rss_per_frame, peak_per_frame, winter, summer);
    }
  }
  if (options.periods > 0) measureContinuous(options, recognizer, winter);
  // Past continuous mode's keyframes, with a gap of up to 100 places, so that no question finds those.
  const int continuous_frames = options.periods > 0 ? options.periods * options.keyframes_per_period +
                                                          recognizer.parameters().sequence.sequence_length
                                                    : 0;
  int recent_frames = 0;
  for (int length : options.lengths) {
    if (length < mrs_vpr::kMaxRecentRows) recent_frames += recentRouteFrames(options, length);
  }
  int next_route_frame = std::min(continuous_frames + kRouteGap, static_cast<int>(winter.size()) - recent_frames);
  if (next_route_frame < continuous_frames) {
    std::printf("%9s recent rows skipped: they need %d frames of the route in winter after continuous mode's %d, "
                "of %zu\n", sizeName(frames).c_str(), recent_frames, continuous_frames, winter.size());
    measureMapStream(recognizer, frames);
    if (options.load_map) measureLoadMap(options.measure, descriptor);
    return 0;
  }
  for (int length : options.lengths) {
    // Longer sequences take MRS's coarse levels, which keep nothing between queries.
    if (length < mrs_vpr::kMaxRecentRows) {
      measureRecent(options, recognizer, length, load_s, rss_per_frame, peak_per_frame, winter, next_route_frame);
    }
  }
  measureMapStream(recognizer, frames);
  if (options.load_map) measureLoadMap(options.measure, descriptor);
  return 0;
}

/// Whether the map written at `path` by an earlier run can be measured again: written from the same
/// data folder (its truth file says) and of the front end asked for (its database says). `truth_offset`
/// is then its truth offset.
bool cachedMapFits(const std::string& path, const std::string& truth_path, const MapScaleOptions& options,
                   long long& truth_offset) {
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0) return false;
  std::ifstream known(truth_path);
  std::string data;
  if (!(known >> truth_offset) || !(known >> std::ws && std::getline(known, data)) || data != options.data) {
    return false;
  }
  try {
    mrs_vpr::MapDatabase(path, options.descriptor, mrs_vpr::MapAccess::kReadOnly);
    return true;
  } catch (const mrs_vpr::MapDatabaseError&) {
    return false;  // another front end's parameters: written again
  }
}

int run(int argc, char** argv) {
  const std::optional<MapScaleOptions> parsed = parseMapScaleOptions(argc, argv);
  if (!parsed) return 0;
  const MapScaleOptions& options = *parsed;
  if (!options.measure.empty()) return measure(options);

  ::mkdir(options.dir.c_str(), 0755);
  std::string lengths;
  for (int length : options.lengths) lengths += (lengths.empty() ? "" : ",") + std::to_string(length);
  std::printf("Map-scale benchmark: real frames (Nordland summer as the true places among augmented real "
              "distractors), queries of N = %s, %d per map (%d for brute force), threads %d, seed %llu;\n"
              "the core's default parameters, velocity step 0.02 from N = 128 on\n",
              lengths.c_str(), options.queries, options.brute_queries, options.threads,
              static_cast<unsigned long long>(options.seed));
  std::printf("queries: winter = the route in winter; summer* = summer with a new shift, gain and noise; "
              "recent = the map's newest N frames (the route in winter, added as keyframes) after one new keyframe, "
              "recent= = again with none (a map that is not growing), recent* = after N. "
              "load = database to a queryable map;\nRSS/frame = resident growth of the load; peak = the process's "
              "peak RSS over frames; right = within 5 frames; wrong/acc = mrs answers accepted and wrong / accepted;\n"
              "same = queries where mrs and brute force gave the same frame / the same acceptance / of those both "
              "answered; dconf = largest confidence difference\n\n");
  std::printf("%9s %5s %8s %8s %9s %9s %8s %10s %10s %8s %10s %10s %10s %6s\n", "map", "N", "queries", "load[s]",
              "RSS/frame", "peak/fr", "mrs[ms]", "brute[ms]", "mrs right", "speed-up", "brute rt", "wrong/acc",
              "same", "dconf");
  std::fflush(stdout);
  for (const long long frames : options.sizes) {
    const std::string path = options.dir + "/map-" + sizeName(frames) + "-" + options.descriptor.type + "-seed" +
                             std::to_string(options.seed) + ".db";
    // Beside the map: its truth offset and the folder its frames came from.
    const std::string offset_path = path + ".truth";
    long long truth_offset = -1;
    if (!cachedMapFits(path, offset_path, options, truth_offset)) {
      truth_offset = writeScaleMap(path, frames, options);
      if (std::rename((path + ".part").c_str(), path.c_str()) != 0) throw std::runtime_error("cannot rename " + path);
      std::ofstream(offset_path) << truth_offset << "\n" << options.data << "\n";
    }
    std::printf("%9s map: %s\n", sizeName(frames).c_str(),
                mrs_vpr::MapDatabase(path, mrs_vpr::MapAccess::kReadOnly).descriptorParams().describe().c_str());
    std::fflush(stdout);  // before the child's rows
    // A fresh process, so that the figures hold only what loading and querying cost.
    const pid_t child = fork();
    if (child == 0) {
      const std::string exe = "/proc/self/exe";
      std::vector<std::string> args = {"mrs_vpr_map_scale_benchmark",
                                             "--data",
                                             options.data,
                                             "--measure",
                                             path,
                                             "--truth-offset",
                                             std::to_string(truth_offset),
                                             "--lengths",
                                             lengths,
                                             "--queries",
                                             std::to_string(options.queries),
                                             "--brute-queries",
                                             std::to_string(options.brute_queries),
                                             "--threads",
                                             std::to_string(options.threads),
                                             "--periods",
                                             std::to_string(options.periods),
                                             "--keyframes-per-period",
                                             std::to_string(options.keyframes_per_period),
                                             "--seed",
                                             std::to_string(options.seed)};  // The map records its front end.
      if (options.load_map) args.push_back("--load-map");
      std::vector<char*> argv_child;
      for (const std::string& arg : args) argv_child.push_back(const_cast<char*>(arg.c_str()));
      argv_child.push_back(nullptr);
      ::execv(exe.c_str(), argv_child.data());
      std::_Exit(127);
    }
    int status = 0;
    ::waitpid(child, &status, 0);
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) throw std::runtime_error("measuring " + path + " failed");
    std::fflush(stdout);
  }
  return 0;
}

}  // namespace
}  // namespace benchmark
}  // namespace mrs_vpr

int main(int argc, char** argv) {
  mrs_vpr::retainFreedMemory();  // As the node and the tools do.
  return mrs_vpr::tools::runTool("mrs_vpr_map_scale_benchmark", mrs_vpr::benchmark::run, argc, argv);
}

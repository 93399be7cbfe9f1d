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
//   mrs_vpr_map_scale_benchmark --data DIR [--sizes 10k,100k,1M] [--dir /tmp/mrs_vpr_map_scale]
//                               [--length 300] [--queries 5] [--brute-queries 2] [--threads 1]
//                               [--seed 42]

#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>
#include <sys/stat.h>
#include <sys/wait.h>
#include <vector>

#include <boost/program_options.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "mrs_vpr/evaluation/image_folder.hpp"
#include "mrs_vpr/memory_reuse.hpp"
#include "mrs_vpr/place_recognizer.hpp"
#include "mrs_vpr/store/map_database.hpp"
#include "tools/descriptor_options.hpp"
#include "tools/tool_main.hpp"
#include "list_option.hpp"

namespace po = boost::program_options;

namespace {

using Clock = std::chrono::steady_clock;

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

struct Options {
  std::string data;
  std::vector<long long> sizes = {10000, 100000, 1000000};
  std::string dir = "/tmp/mrs_vpr_map_scale";
  int length = 300;
  int queries = 5;
  int brute_queries = 2;
  int threads = 1;
  std::uint64_t seed = 42;
  // Internal: measure one map in this process (the parent runs one child per size).
  std::string measure;
  mrs_vpr::DescriptorParams descriptor;  ///< The front end of the maps written.
  long long truth_offset = -1;
};

/// A map size as written on the command line: frames, or thousands ("10k") or millions ("1M").
long long parseSize(const std::string& text) {
  const std::invalid_argument bad("--sizes: bad size '" + text + "' (e.g. 10k, 1M; >= 2k)");
  std::size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(text, &used);
  } catch (const std::logic_error&) {  // No number at all, or out of range.
    throw bad;
  }
  const std::string unit = text.substr(used);
  const double scale = unit.empty() ? 1 : unit == "k" ? 1e3 : unit == "M" ? 1e6 : -1;
  if (scale < 0 || !(value * scale >= 2000) || value * scale > 1e12) throw bad;
  return static_cast<long long>(value * scale);
}

std::string sizeName(long long frames) {
  if (frames % 1000000 == 0) return std::to_string(frames / 1000000) + "M";
  if (frames % 1000 == 0) return std::to_string(frames / 1000) + "k";
  return std::to_string(frames);
}

constexpr const char* kUsage =
    "Usage: mrs_vpr_map_scale_benchmark --data DIR [--sizes 10k,100k,1M] [--dir /tmp/mrs_vpr_map_scale]\n"
    "                                   [--length 300] [--queries 5] [--brute-queries 2] [--threads 1]\n"
    "                                   [--seed 42]\n"
    "Writes map databases of real frames (DIR: the shared data folder) once, then loads each in a fresh\n"
    "process and prints load time, resident bytes a frame and both methods' query times.\n";

/// Parses the command line; returns nothing after printing the help.
std::optional<Options> parse(int argc, char** argv) {
  Options options;
  std::vector<std::string> sizes;
  for (const long long frames : options.sizes) sizes.push_back(sizeName(frames));
  std::int64_t seed = static_cast<std::int64_t>(options.seed);  // Signed, so that a negative seed is refused.
  po::options_description description("Options");
  // clang-format off
  description.add_options()
      ("help,h", "print this help")
      ("data", po::value(&options.data)->required(), "the shared data folder (nordland/, corridor/)")
      ("sizes", mrs_vpr::benchmark::listValue(&sizes), "map sizes in frames, comma-separated (e.g. 10k, 1M; >= 2k)")
      ("dir", po::value(&options.dir)->default_value(options.dir), "folder of the map databases, kept between runs")
      ("length", po::value(&options.length)->default_value(options.length), "N: frames per test sequence")
      ("queries", po::value(&options.queries)->default_value(options.queries), "queries per map and kind (mrs)")
      ("brute-queries", po::value(&options.brute_queries)->default_value(options.brute_queries),
       "how many of them brute force answers too")
      ("threads", po::value(&options.threads)->default_value(options.threads), "threads of both methods")
      ("seed", po::value(&seed)->default_value(seed), "seed of the maps and of the queries")
      // The parent runs one child per map, with these two: the map to measure and where its true places are.
      ("measure", po::value(&options.measure), "internal: measure this map database in this process")
      ("truth-offset", po::value(&options.truth_offset)->default_value(options.truth_offset),
       "internal: index of the measured map's first true place");
  // clang-format on
  mrs_vpr::tools::addDescriptorOptions(description, options.descriptor);
  po::variables_map variables;
  if (!mrs_vpr::tools::parseCommandLine(argc, argv, kUsage, description, variables)) return std::nullopt;
  options.sizes.clear();
  for (const std::string& size : sizes) options.sizes.push_back(parseSize(size));
  if (seed < 0) throw std::invalid_argument("--seed must be >= 0");
  options.seed = static_cast<std::uint64_t>(seed);
  if (options.length < 10 || options.queries < 1 || options.brute_queries < 0 || options.threads < 1) {
    throw std::invalid_argument("--length >= 10, --queries >= 1, --brute-queries >= 0, --threads >= 1");
  }
  return options;
}

/// Resident and peak resident memory of this process [bytes], from /proc/self/status.
std::pair<long long, long long> residentBytes() {
  std::ifstream status("/proc/self/status");
  long long rss = 0;
  long long hwm = 0;
  for (std::string line; std::getline(status, line);) {
    if (line.rfind("VmRSS:", 0) == 0) rss = std::stoll(line.substr(6)) * 1024;
    if (line.rfind("VmHWM:", 0) == 0) hwm = std::stoll(line.substr(6)) * 1024;
  }
  return {rss, hwm};
}

/// A changed frame: turned (upside down, or by 180 degrees) or not, and moved by a shift, gain,
/// offset and noise.
class Augmenter {
 public:
  explicit Augmenter(std::uint64_t seed) : rng_(seed) {}

  struct Look {
    int flip = 2;  ///< cv::flip's code (0 upside down, -1 both axes), or 2 for none.
    double dx = 0, dy = 0, gain = 1, offset = 0;
  };

  Look nextLook(int flip) {
    std::uniform_real_distribution<double> shift_x(-6.0, 6.0);
    std::uniform_real_distribution<double> shift_y(-3.0, 3.0);
    std::uniform_real_distribution<double> gain(0.7, 1.3);
    std::uniform_real_distribution<double> offset(-30.0, 30.0);
    return {flip, shift_x(rng_), shift_y(rng_), gain(rng_), offset(rng_)};
  }

  cv::Mat apply(const cv::Mat& image, const Look& look) {
    cv::Mat source = image;  // Shares the pixels: flipped into a new image, never in place.
    if (look.flip != 2) {
      source = cv::Mat();
      cv::flip(image, source, look.flip);
    }
    const cv::Mat shift = (cv::Mat_<double>(2, 3) << 1, 0, look.dx, 0, 1, look.dy);
    cv::Mat moved;
    cv::warpAffine(source, moved, shift, source.size(), cv::INTER_LINEAR, cv::BORDER_REPLICATE);
    cv::Mat noise(moved.size(), CV_MAKETYPE(CV_16S, moved.channels()));
    cv::theRNG().state = rng_();
    cv::randn(noise, 0, 3);
    cv::Mat changed;
    moved.convertTo(changed, CV_16S, look.gain, look.offset);
    changed += noise;
    changed.convertTo(moved, image.type());
    return moved;
  }

 private:
  std::mt19937_64 rng_;
};

/// Writes the map of `frames` frames to `path`; returns the index of the first true place.
long long writeMap(const std::string& path, long long frames, const Options& options) {
  const mrs_vpr::DescriptorExtractor extractor(options.descriptor);
  const std::vector<cv::Mat> summer = mrs_vpr::loadImageFolder(options.data + "/nordland/summer");
  // Winter, the queries' season, is left out, and Nordland distractors are turned upside down (or by
  // 180 degrees), so that no distractor shows a query's place, not even mirrored: the truth is never
  // ambiguous, and a wrong answer is the search's fault.
  std::vector<std::vector<cv::Mat>> sources = {summer, mrs_vpr::loadImageFolder(options.data + "/corridor/ref")};
  for (const cv::Mat& image : mrs_vpr::loadImageFolder(options.data + "/corridor/query")) sources[1].push_back(image);
  const long long route = static_cast<long long>(summer.size());
  std::mt19937_64 rng(options.seed + static_cast<std::uint64_t>(frames));
  const long long truth_offset = std::uniform_int_distribution<long long>(0, frames - route)(rng);
  Augmenter augmenter(options.seed);

  const std::string aside = path + ".part";
  std::remove(aside.c_str());
  mrs_vpr::MapDatabase map(aside, options.descriptor);
  std::vector<mrs_vpr::StoredFrame> batch;
  const auto start = Clock::now();
  long long written = 0;
  auto add = [&](const cv::Mat& image) {
    mrs_vpr::StoredFrame frame;
    frame.descriptor = extractor.compute(image);
    frame.stamp = mrs_vpr::Stamp::fromNanoseconds(static_cast<std::int64_t>(written) * 100'000'000);
    frame.sequence = written++;
    batch.push_back(std::move(frame));
    if (batch.size() == 10000) {
      map.append(batch);
      batch.clear();
      std::fprintf(stderr, "\rwriting %s: %lld / %lld frames, %.0f frames/s ", path.c_str(), written, frames,
                   written / secondsSince(start));
    }
  };
  while (written < frames) {
    if (written == truth_offset) {
      for (const cv::Mat& image : summer) add(image);
      continue;
    }
    // A distractor segment that stops at the true places or the end of the map.
    const long long room = (written < truth_offset ? truth_offset : frames) - written;
    const int source_index = std::uniform_int_distribution<int>(0, 1)(rng);
    const auto& source = sources[static_cast<std::size_t>(source_index)];
    const long long length = std::min<long long>(room, std::uniform_int_distribution<long long>(200, 800)(rng));
    const long long begin = std::uniform_int_distribution<long long>(0, static_cast<long long>(source.size()) - 1)(rng);
    const bool backwards = std::uniform_int_distribution<int>(0, 1)(rng) == 1;
    const int flip = source_index == 0 ? (backwards ? -1 : 0) : 2;
    const Augmenter::Look look = augmenter.nextLook(flip);
    for (long long i = 0; i < length; ++i) {
      const long long step = backwards ? -i : i;
      const long long n = static_cast<long long>(source.size());
      add(augmenter.apply(source[static_cast<std::size_t>(((begin + step) % n + n) % n)], look));
    }
  }
  if (!batch.empty()) map.append(batch);
  std::fprintf(stderr, "\rwrote %s: %lld frames in %.1f s%20s\n", path.c_str(), written, secondsSince(start), "");
  return truth_offset;
}

double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

/// The child: loads one map and answers the queries; prints one row.
int measure(const Options& options) {
  cv::setNumThreads(options.threads);
  mrs_vpr::Parameters params;
  // As in mrs_vpr_real_benchmark: 0.1 leaves up to 15 frames of drift at N = 300.
  params.sequence.velocity_step = 0.02;
  params.validate();
  params.descriptor = mrs_vpr::MapDatabase(options.measure, mrs_vpr::MapAccess::kReadOnly).descriptorParams();
  const auto before = residentBytes();
  const auto load_start = Clock::now();
  mrs_vpr::RecognizerParams limits;
  limits.max_frames = 0;  // Unbounded: the default capacity (500k frames) is below the largest map.
  mrs_vpr::PlaceRecognizer recognizer(params, limits);
  {
    const mrs_vpr::MapDatabase map(options.measure, params.descriptor);
    recognizer.reserve(static_cast<int>(map.size()));
    map.forEachFrame([&](const mrs_vpr::StoredFrame& frame) { recognizer.addDescriptor(frame.descriptor, frame.stamp); });
    recognizer.flush();
  }
  const double load_s = secondsSince(load_start);
  const auto after = residentBytes();
  const int frames = recognizer.size();

  // Two kinds of test sequence: winter (across seasons, the benchmark's hard case) and summer seen
  // again with a new shift, gain and noise (unambiguous, so that speed is timed on right answers).
  const std::vector<cv::Mat> winter = mrs_vpr::loadImageFolder(options.data + "/nordland/winter");
  const std::vector<cv::Mat> summer = mrs_vpr::loadImageFolder(options.data + "/nordland/summer");
  Augmenter augmenter(options.seed + 1);
  for (const bool across_seasons : {true, false}) {
    std::mt19937_64 rng(options.seed);
    std::uniform_int_distribution<int> end_of(options.length - 1, static_cast<int>(winter.size()) - 1);
    std::vector<double> mrs_ms;
    std::vector<double> brute_ms;
    int mrs_right = 0;
    int mrs_accepted = 0;
    int mrs_accepted_wrong = 0;
    int brute_right = 0;
    for (int q = 0; q < options.queries; ++q) {
      const int end = end_of(rng);
      const Augmenter::Look look = augmenter.nextLook(2);
      mrs_vpr::DescriptorSequence query(recognizer.extractor().size());
      for (int i = end - options.length + 1; i <= end; ++i) {
        const auto frame = static_cast<std::size_t>(i);
        query.append(recognizer.describe(across_seasons ? winter[frame] : augmenter.apply(summer[frame], look)));
      }
      const long long truth = options.truth_offset + end;
      auto right = [&](const mrs_vpr::Match& match) { return std::llabs(match.reference_index - truth) <= 5; };
      auto start = Clock::now();
      const mrs_vpr::PlaceAnswer mrs = recognizer.match(query, "mrs");
      mrs_ms.push_back(secondsSince(start) * 1e3);
      mrs_right += right(mrs.match) ? 1 : 0;
      mrs_accepted += mrs.match.accepted ? 1 : 0;
      if (std::getenv("MRS_VPR_SHOW_ANSWERS") != nullptr) {
        std::fprintf(stderr, "%s query %d: truth %lld, mrs %d (confidence %.2f%s)\n", across_seasons ? "winter" : "summer*", q,
                     truth, mrs.match.reference_index, mrs.match.confidence, mrs.match.accepted ? ", accepted" : "");
      }
      mrs_accepted_wrong += mrs.match.accepted && !right(mrs.match) ? 1 : 0;
      if (q < options.brute_queries) {
        start = Clock::now();
        const mrs_vpr::PlaceAnswer brute = recognizer.match(query, "seqslam");
        brute_ms.push_back(secondsSince(start) * 1e3);
        brute_right += right(brute.match) ? 1 : 0;
      }
    }
    const double brute = median(brute_ms);
    const double fast = median(mrs_ms);
    const std::string speed_up = brute_ms.empty() ? "-" : std::to_string(static_cast<int>(brute / fast)) + "x";
    std::printf("%9s %8s %8.2f %9.0f %9.0f %8.1f %10.1f %6d/%-3d %8s %6d/%-3d %6d/%-3d\n", sizeName(frames).c_str(),
                across_seasons ? "winter" : "summer*", load_s, static_cast<double>(after.first - before.first) / frames,
                static_cast<double>(after.second) / frames, fast, brute, mrs_right, options.queries,
                speed_up.c_str(), brute_right, static_cast<int>(brute_ms.size()), mrs_accepted_wrong, mrs_accepted);
    std::fflush(stdout);
  }
  return 0;
}

int run(int argc, char** argv) {
  const std::optional<Options> parsed = parse(argc, argv);
  if (!parsed) return 0;
  const Options& options = *parsed;
  if (!options.measure.empty()) return measure(options);

  ::mkdir(options.dir.c_str(), 0755);
  std::printf("Map-scale benchmark: real frames (Nordland summer as the true places among augmented real "
              "distractors), queries of N = %d, %d per map (%d for brute force), threads %d, seed %llu\n",
              options.length, options.queries, options.brute_queries, options.threads,
              static_cast<unsigned long long>(options.seed));
  std::printf("queries: winter = the route in winter; summer* = summer with a new shift, gain and noise. "
              "load = database to a queryable map;\nRSS/frame = resident growth of the load; peak = the process's "
              "peak RSS over frames; right = within 5 frames; wrong/acc = mrs answers accepted and wrong / accepted\n\n");
  std::printf("%9s %8s %8s %9s %9s %8s %10s %10s %8s %10s %10s\n", "map", "queries", "load[s]", "RSS/frame",
              "peak/fr", "mrs[ms]", "brute[ms]", "mrs right", "speed-up", "brute rt", "wrong/acc");
  std::fflush(stdout);
  for (const long long frames : options.sizes) {
    const std::string path = options.dir + "/map-" + sizeName(frames) + "-" + options.descriptor.type + "-seed" +
                             std::to_string(options.seed) + ".db";
    const std::string offset_path = path + ".truth";
    long long truth_offset = -1;
    std::ifstream known(offset_path);
    struct stat info {};
    if (!(known >> truth_offset) || ::stat(path.c_str(), &info) != 0) {
      truth_offset = writeMap(path, frames, options);
      if (std::rename((path + ".part").c_str(), path.c_str()) != 0) throw std::runtime_error("cannot rename " + path);
      std::ofstream(offset_path) << truth_offset << "\n";
    }
    // A fresh process, so that the figures hold only what loading and querying cost.
    const pid_t child = fork();
    if (child == 0) {
      const std::string exe = "/proc/self/exe";
      const std::vector<std::string> args = {
          "mrs_vpr_map_scale_benchmark", "--data", options.data, "--measure", path, "--truth-offset",
          std::to_string(truth_offset), "--length", std::to_string(options.length), "--queries",
          std::to_string(options.queries), "--brute-queries", std::to_string(options.brute_queries), "--threads",
          std::to_string(options.threads), "--seed", std::to_string(options.seed)};  // The map records its front end.
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

int main(int argc, char** argv) {
  mrs_vpr::retainFreedMemory();  // As the node and the tools do.
  return mrs_vpr::tools::runTool("mrs_vpr_map_scale_benchmark", run, argc, argv);
}

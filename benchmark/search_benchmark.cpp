// Benchmark: MRS-VPR against this package's SIMD brute-force SeqSLAM on the same queries.
//
// Prints figures; it is not a test. Both methods answer the same seeded global-localisation queries
// (test sequences of N frames at random places of a generated route) and are timed side by side in
// one run, so the ratio holds on a loaded machine even when the absolute times do not. Short runs are
// repeated (see runQueries) so that a pause of the machine does not pass for a query's time.
//
//   mrs_vpr_benchmark [--reference-frames 9000] [--sequence-length 300] [--queries 40]
//                     [--velocity-step 0.02] [--tolerance 5] [--threads 1,2] [--seed 7]
//                     [--min-time 1]

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdint>
#include <cstdlib>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <boost/program_options.hpp>
#include <opencv2/core.hpp>

#include "mrs_vpr/descriptor.hpp"
#include "mrs_vpr/descriptor_sequence.hpp"
#include "mrs_vpr/evaluation/evaluation.hpp"
#include "mrs_vpr/memory_reuse.hpp"
#include "mrs_vpr/place_recognizer.hpp"
#include "mrs_vpr/synthetic_route.hpp"
#include "mrs_vpr/trajectory_search.hpp"
#include "tools/descriptor_options.hpp"
#include "tools/double_option.hpp"
#include "tools/tool_main.hpp"
#include "list_option.hpp"

namespace po = boost::program_options;

namespace {

struct Options {
  int reference_frames = 9000;
  int sequence_length = 300;
  int queries = 40;
  // At N = 300 a velocity step of 0.1 leaves up to 15 frames of drift at the oldest test frame, so
  // neither method can align a long sequence whose speed falls between two steps; 0.02 keeps it
  // within 3 frames. Both methods use the same grid.
  double velocity_step = 0.02;
  int tolerance = 5;
  std::vector<int> threads = {1, 2};
  std::uint64_t seed = 7;
  double min_time_s = 1.0;
  mrs_vpr::DescriptorParams descriptor;
};

/// Frames of the second traversal: it may run up to 1.2x faster, so it is kept inside the route.
int queryFrames(int reference_frames) {
  return static_cast<int>(reference_frames / mrs_vpr::SyntheticRouteParams{}.speed_max) - 10;
}

constexpr const char* kUsage =
    "Usage: mrs_vpr_benchmark [--reference-frames M] [--sequence-length N] [--queries K]\n"
    "                         [--velocity-step S] [--tolerance T] [--threads 1,2] [--seed S]\n"
    "                         [--min-time SECONDS] [--descriptor hog|thumbnail] [front-end options]\n"
    "\n"
    "Times MRS-VPR against brute-force SeqSLAM on the same seeded queries of a generated route, side by\n"
    "side for each thread count, and prints success, median time and comparisons a query.\n";

/// Parses the command line; returns nothing after printing the help.
std::optional<Options> parse(int argc, char** argv) {
  Options options;
  std::int64_t seed = static_cast<std::int64_t>(options.seed);  // Signed, so that a negative seed is refused.
  po::options_description description("Options");
  // clang-format off
  description.add_options()
      ("help,h", "print this help")
      ("reference-frames", po::value(&options.reference_frames)->default_value(options.reference_frames),
       "M: frames of the reference traversal")
      ("sequence-length", po::value(&options.sequence_length)->default_value(options.sequence_length),
       "N: frames per test sequence")
      ("queries", po::value(&options.queries)->default_value(options.queries), "K: test sequences")
      ("velocity-step", mrs_vpr::tools::doubleOption(&options.velocity_step),
       "step between the velocities tried, both methods")
      ("tolerance", po::value(&options.tolerance)->default_value(options.tolerance),
       "frames of error still counted a success")
      ("threads", mrs_vpr::benchmark::listValue(&options.threads), "thread counts to time, comma-separated")
      ("seed", po::value(&seed)->default_value(seed), "seed of the route and of the query positions")
      ("min-time", po::value(&options.min_time_s)->default_value(options.min_time_s),
       "seconds each method repeats the queries for, at least");
  // clang-format on
  mrs_vpr::tools::addDescriptorOptions(description, options.descriptor);
  po::variables_map variables;
  if (!mrs_vpr::tools::parseCommandLine(argc, argv, kUsage, description, variables)) return std::nullopt;
  mrs_vpr::tools::refuseOtherFrontEndsOptions(variables, options.descriptor);
  if (seed < 0) throw std::invalid_argument("--seed must be >= 0");
  options.seed = static_cast<std::uint64_t>(seed);
  if (options.reference_frames < 100) throw std::invalid_argument("--reference-frames must be >= 100");
  const int query_frames = queryFrames(options.reference_frames);
  if (options.sequence_length < 2 || options.sequence_length > query_frames) {
    throw std::invalid_argument("--sequence-length must be in 2.." + std::to_string(query_frames) +
                                " (the query traversal of " + std::to_string(options.reference_frames) + " frames)");
  }
  if (options.queries < 1) throw std::invalid_argument("--queries must be >= 1");
  if (options.tolerance < 0) throw std::invalid_argument("--tolerance must be >= 0");
  if (options.min_time_s < 0) throw std::invalid_argument("--min-time must be >= 0");
  for (const int threads : options.threads) {
    if (threads < 1) throw std::invalid_argument("--threads takes counts >= 1");
  }
  return options;
}

struct MethodResult {
  int successes = 0;
  std::vector<double> milliseconds;
  long long comparisons = 0;

  double median() const { return mrs_vpr::median(milliseconds); }
};

/// Every query with one method, in passes over all queries until the method has run for at least
/// options.min_time_s (as Google Benchmark repeats short runs): a query's time is the median of its
/// runs, so that a pause of the shared machine during a run of a millisecond does not count.
MethodResult runQueries(mrs_vpr::PlaceRecognizer& reference, const std::string& method,
                        const mrs_vpr::DescriptorSequence& query, const std::vector<int>& starts,
                        const std::vector<int>& truth, const Options& options) {
  const int anchor =
      mrs_vpr::wholeSequenceRows(options.sequence_length, reference.parameters().sequence.alignment).anchor;
  MethodResult result;
  std::vector<std::vector<double>> runs(starts.size());
  double elapsed_s = 0.0;
  for (int pass = 0; pass == 0 || elapsed_s < options.min_time_s; ++pass) {
    for (std::size_t q = 0; q < starts.size(); ++q) {
      const auto begin = std::chrono::steady_clock::now();
      const mrs_vpr::Match match =
          reference.match(query.view(starts[q], starts[q] + options.sequence_length), method).match;
      const auto end = std::chrono::steady_clock::now();
      runs[q].push_back(std::chrono::duration<double, std::milli>(end - begin).count());
      elapsed_s += runs[q].back() / 1000.0;
      if (pass > 0) continue;  // Runs repeat the same answer.
      result.comparisons += match.comparisons;
      // The answer names the reference frame of the test frame the sequence localises (its anchor:
      // the middle frame at the default sequence/alignment, the newest when causal).
      const int expected = truth[static_cast<std::size_t>(starts[q] + anchor)];
      if (match.reference_index >= 0 && std::abs(match.reference_index - expected) <= options.tolerance) {
        ++result.successes;
      }
    }
  }
  for (const std::vector<double>& query_runs : runs) result.milliseconds.push_back(mrs_vpr::median(query_runs));
  return result;
}

/// Runs the benchmark; returns the exit code.
int run(int argc, char** argv) {
  const std::optional<Options> parsed = parse(argc, argv);
  if (!parsed) return 0;
  const Options& options = *parsed;
  mrs_vpr::Parameters params;
  params.descriptor = options.descriptor;
  params.sequence.velocity_step = options.velocity_step;
  params.validate();

  mrs_vpr::SyntheticRouteParams route_params;
  route_params.reference_frames = options.reference_frames;
  route_params.query_frames = queryFrames(options.reference_frames);
  route_params.seed = options.seed;
  std::fprintf(stderr, "generating a route of %d + %d frames...\n", route_params.reference_frames,
               route_params.query_frames);
  const mrs_vpr::SyntheticRoute route = mrs_vpr::generateSyntheticRoute(route_params);

  mrs_vpr::RecognizerParams unbounded;
  unbounded.max_frames = 0;
  mrs_vpr::PlaceRecognizer reference(params, unbounded);
  mrs_vpr::DescriptorSequence query(reference.extractor().size());
  for (const cv::Mat& image : route.reference) reference.addDescriptor(reference.describe(image));  // Every frame.
  for (const cv::Mat& image : route.query) query.append(reference.describe(image));

  std::mt19937_64 rng(options.seed);
  std::uniform_int_distribution<int> start_at(0, query.size() - options.sequence_length);
  std::vector<int> starts;
  for (int i = 0; i < options.queries; ++i) starts.push_back(start_at(rng));

  std::printf("MRS-VPR vs brute-force SeqSLAM on the same %d queries (synthetic route, seed %llu)\n",
              options.queries, static_cast<unsigned long long>(options.seed));
  std::printf("M = %d reference frames, N = %d frame test sequences, velocity step %.2f, "
              "success = within %d frames\n",
              reference.size(), options.sequence_length, options.velocity_step, options.tolerance);
  std::printf("each method repeats the queries until it has run %.1f s; a query's time is the median of its runs\n\n",
              options.min_time_s);
  std::printf("%-8s %-8s %8s %14s %18s\n", "threads", "method", "success", "median ms/query",
              "comparisons/query");
  for (int threads : options.threads) {
    cv::setNumThreads(threads);
    const MethodResult brute = runQueries(reference, "seqslam", query, starts, route.query_to_reference, options);
    const MethodResult fast = runQueries(reference, "mrs", query, starts, route.query_to_reference, options);
    for (const auto& [name, result] : {std::pair{"seqslam", &brute}, std::pair{"mrs", &fast}}) {
      std::printf("%-8d %-8s %8.3f %14.3f %18lld\n", threads, name,
                  static_cast<double>(result->successes) / options.queries, result->median(),
                  result->comparisons / options.queries);
    }
    std::printf("%-8d speed-up of mrs over seqslam: %.1fx in median time, %.1fx in comparisons\n\n", threads,
                brute.median() / fast.median(),
                static_cast<double>(brute.comparisons) / static_cast<double>(std::max(1LL, fast.comparisons)));
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  mrs_vpr::retainFreedMemory();  // As the node and the tools do.
  return mrs_vpr::tools::runTool("mrs_vpr_benchmark", run, argc, argv);
}

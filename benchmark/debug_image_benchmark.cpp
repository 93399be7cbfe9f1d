// What ~debug_image costs an answered query: the same queries on real frames without and with the
// explanation and the drawing, side by side. Prints figures; it is not a test. With --output it also
// writes the picture of one query (doc/debug_image.png is made this way).
//
//   mrs_vpr_debug_image_benchmark --reference DIR --query DIR [--lengths 100,300] [--queries 20]
//                                 [--runs 3] [--methods mrs,seqslam] [--threads 1] [--output FILE.png]
//                                 [--picture-end I] [--picture-length N] [--picture-method mrs]

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <boost/program_options.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "mrs_vpr/descriptor_sequence.hpp"
#include "mrs_vpr/evaluation/image_folder.hpp"
#include "mrs_vpr/match_explanation.hpp"
#include "mrs_vpr/median.hpp"
#include "mrs_vpr/place_recognizer.hpp"
#include "mrs_vpr/visualization/match_image.hpp"
#include "tools/descriptor_options.hpp"
#include "tools/stopwatch.hpp"
#include "tools/tool_main.hpp"
#include "list_option.hpp"

namespace po = boost::program_options;
using mrs_vpr::tools::secondsSince;

namespace {

struct Options {
  std::string reference;
  std::string query;
  std::vector<int> lengths = {100, 300};
  int queries = 20;
  int runs = 3;  // per query and variant; the fastest counts
  std::vector<std::string> methods = {"mrs", "seqslam"};
  int threads = 1;
  std::string output;
  int picture_end = -1;  // -1: the middle of the query traversal
  int picture_length = 300;
  std::string picture_method = "mrs";
  mrs_vpr::DescriptorParams descriptor;
};

constexpr const char* kUsage =
    "Usage: mrs_vpr_debug_image_benchmark --reference DIR --query DIR [--lengths 100,300] [--queries K] [--runs R]\n"
    "                                     [--methods mrs,seqslam] [--threads T] [--output FILE.png]\n"
    "                                     [--picture-end I] [--picture-length N] [--picture-method mrs|seqslam]\n"
    "                                     [--descriptor hog|thumbnail] [front-end options]\n"
    "\n"
    "Times the same queries without and with the explanation and drawing of ~debug_image, side by side;\n"
    "with --output also writes the picture of one query. Query frame i is assumed to show reference\n"
    "frame i (as in the Nordland halves).\n";

bool isMethod(const std::string& method) { return method == "mrs" || method == "seqslam"; }

/// Parses the command line; returns nothing after printing the help.
std::optional<Options> parse(int argc, char** argv) {
  Options options;
  po::options_description description("Options");
  // clang-format off
  description.add_options()
      ("help,h", "print this help")
      ("reference", po::value(&options.reference)->required(), "reference image folder")
      ("query", po::value(&options.query)->required(), "query image folder")
      ("lengths", mrs_vpr::benchmark::listValue(&options.lengths), "N: frames per test sequence, comma-separated")
      ("queries", po::value(&options.queries)->default_value(options.queries), "queries per row, spread over the query")
      ("runs", po::value(&options.runs)->default_value(options.runs), "runs per query and variant; the fastest counts")
      ("methods", mrs_vpr::benchmark::listValue(&options.methods), "mrs and/or seqslam, comma-separated")
      ("threads", po::value(&options.threads)->default_value(options.threads), "threads of both methods")
      ("output", po::value(&options.output), "PNG file for the picture of one query")
      ("picture-end", po::value(&options.picture_end)->default_value(options.picture_end),
       "newest query frame of the picture; -1 = the middle of the query")
      ("picture-length", po::value(&options.picture_length)->default_value(options.picture_length),
       "frames of the picture's test sequence")
      ("picture-method", po::value(&options.picture_method)->default_value(options.picture_method),
       "mrs | seqslam: the method of the picture");
  // clang-format on
  mrs_vpr::tools::addDescriptorOptions(description, options.descriptor);
  po::variables_map variables;
  if (!mrs_vpr::tools::parseCommandLine(argc, argv, kUsage, description, variables)) return std::nullopt;
  mrs_vpr::tools::refuseOtherFrontEndsOptions(variables, options.descriptor);
  for (const int length : options.lengths) {
    if (length < 2) throw std::invalid_argument("--lengths takes sequence lengths >= 2");
  }
  for (const std::string& method : options.methods) {
    if (!isMethod(method)) {
      throw std::invalid_argument("--methods: unknown method '" + method + "' (expected mrs or seqslam)");
    }
  }
  if (!isMethod(options.picture_method)) {
    throw std::invalid_argument("--picture-method must be mrs or seqslam, not '" + options.picture_method + "'");
  }
  if (options.queries < 1) throw std::invalid_argument("--queries must be at least 1");
  if (options.runs < 1) throw std::invalid_argument("--runs must be at least 1");
  if (options.threads < 1) throw std::invalid_argument("--threads must be at least 1");
  if (options.picture_length < 2) throw std::invalid_argument("--picture-length must be at least 2");
  if (options.picture_end < -1) throw std::invalid_argument("--picture-end must be a frame index, or -1");
  return options;
}

/// The upper median (median.hpp), as the figures in doc/debug_image.md were taken.
double median(std::vector<double> values) { return mrs_vpr::upperMedian(values); }

double maximum(const std::vector<double>& values) { return *std::max_element(values.begin(), values.end()); }

void run(const Options& options) {
  cv::setNumThreads(options.threads);
  mrs_vpr::Parameters params;  // The node's defaults, but for the front end asked for.
  params.descriptor = options.descriptor;
  mrs_vpr::PlaceRecognizer recognizer(params);
  // A copy of the map's descriptors, to time the explanation on its own.
  mrs_vpr::DescriptorSequence reference(recognizer.extractor().size());
  mrs_vpr::forEachImage(options.reference, [&](int index, const std::string&, const cv::Mat& image) {
    const cv::Mat descriptor = recognizer.describe(image);
    const auto stamp = mrs_vpr::Stamp::fromSecondsAndNanoseconds(static_cast<std::uint32_t>(index), 0);
    recognizer.addDescriptor(descriptor, stamp);
    reference.append(descriptor, stamp);
  });
  mrs_vpr::DescriptorSequence query(recognizer.extractor().size());
  mrs_vpr::forEachImage(options.query, [&](int index, const std::string&, const cv::Mat& image) {
    query.append(recognizer.describe(image),
                 mrs_vpr::Stamp::fromSecondsAndNanoseconds(static_cast<std::uint32_t>(index), 0));
  });
  std::printf("reference %d frames, query %d frames, %d thread(s), %d queries per row\n", recognizer.size(),
              query.size(), options.threads, options.queries);
  std::printf("%-8s %5s | %10s | %14s %12s %10s | %10s %10s | %9s\n", "method", "N", "query [ms]",
              "explained [ms]", "explain [ms]", "drawn [ms]", "extra [ms]", "extra max", "accepted");

  for (const std::string& method : options.methods) {
    for (const int length : options.lengths) {
      if (length > query.size()) continue;
      std::vector<double> plain;
      std::vector<double> explained;
      std::vector<double> drawn;
      std::vector<double> extra;
      std::vector<double> explain_only;
      int accepted = 0;
      cv::Mat picture;  // Reused from query to query, as the node does.
      for (int q = 0; q < options.queries; ++q) {
        // Query ends spread evenly over the traversal.
        const int end = length - 1 + static_cast<int>(static_cast<long long>(q) * (query.size() - length) /
                                                      std::max(1, options.queries - 1));
        const mrs_vpr::SequenceView test = query.view(end - length + 1, end + 1);
        // The fastest of a few runs of each: the machine's other load is noise, not cost.
        double plain_ms = 1e300;
        double explained_ms = 1e300;
        double drawn_ms = 1e300;
        double explain_ms = 1e300;
        mrs_vpr::PlaceAnswer answer;
        mrs_vpr::PlaceAnswer explained_answer;
        for (int run = 0; run < options.runs; ++run) {
          auto start = std::chrono::steady_clock::now();
          answer = recognizer.match(test, method);
          plain_ms = std::min(plain_ms, 1e3 * secondsSince(start));
          mrs_vpr::MatchExplanation explanation;
          start = std::chrono::steady_clock::now();
          explained_answer = recognizer.match(test, method, &explanation);
          explained_ms = std::min(explained_ms, 1e3 * secondsSince(start));
          start = std::chrono::steady_clock::now();
          mrs_vpr::visualization::renderMatchImage(explanation, explained_answer, picture);
          drawn_ms = std::min(drawn_ms, 1e3 * secondsSince(start));
          start = std::chrono::steady_clock::now();
          mrs_vpr::explainMatch(reference.view(), test, explained_answer.match, recognizer.parameters().sequence,
                                recognizer.parameters().descriptor);
          explain_ms = std::min(explain_ms, 1e3 * secondsSince(start));
        }
        plain.push_back(plain_ms);
        explained.push_back(explained_ms);
        drawn.push_back(drawn_ms);
        explain_only.push_back(explain_ms);
        extra.push_back(explained_ms - plain_ms + drawn_ms);
        if (explained_answer.match.reference_index != answer.match.reference_index) {
          throw std::runtime_error("explaining changed the answer of the query ending at " + std::to_string(end));
        }
        accepted += answer.match.accepted ? 1 : 0;
      }
      std::printf("%-8s %5d | %10.2f | %14.2f %12.2f %10.2f | %10.2f %10.2f | %6d/%d\n", method.c_str(), length,
                  median(plain), median(explained), median(explain_only), median(drawn), median(extra),
                  maximum(extra), accepted, options.queries);
    }
  }
  std::puts("query: without explanation (no subscriber); explained: the same query filling a MatchExplanation\n"
            "(for mrs also recording its levels); explain: explainMatch alone; drawn: renderMatchImage;\n"
            "extra: explained - query + drawn, what a subscriber adds. Medians over the queries of the fastest\n"
            "of --runs runs each; extra max: the largest over the queries.");

  if (!options.output.empty()) {
    const int length = std::min(options.picture_length, query.size());
    const int end = options.picture_end >= 0 ? options.picture_end : query.size() / 2;
    if (end < length - 1 || end >= query.size()) throw std::invalid_argument("--picture-end out of range");
    mrs_vpr::MatchExplanation explanation;
    const mrs_vpr::PlaceAnswer answer =
        recognizer.match(query.view(end - length + 1, end + 1), options.picture_method, &explanation);
    const cv::Mat picture = mrs_vpr::visualization::renderMatchImage(explanation, answer);
    if (!cv::imwrite(options.output, picture, {cv::IMWRITE_PNG_COMPRESSION, 9})) {
      throw std::runtime_error("cannot write " + options.output);
    }
    std::printf("wrote %s (%d x %d): query frames %d..%d, %s, reference %d, confidence %.2f, %s\n",
                options.output.c_str(), picture.cols, picture.rows, end - length + 1, end, answer.method.c_str(),
                answer.match.reference_index, answer.match.confidence,
                answer.match.accepted ? "accepted" : "not accepted");
  }
}

}  // namespace

int main(int argc, char** argv) {
  return mrs_vpr::tools::runTool(
      "mrs_vpr_debug_image_benchmark",
      [](int count, char** arguments) {
        const std::optional<Options> options = parse(count, arguments);
        if (options) run(*options);
        return 0;
      },
      argc, argv);
}

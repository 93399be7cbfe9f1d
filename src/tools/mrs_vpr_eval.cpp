// mrs_vpr_eval: offline evaluation of `seqslam` and `mrs` on two traversals (image folders or bags)
// with either protocol of the paper notes: per-frame (SeqSLAM style) or global localisation.

#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <iostream>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

#include <boost/program_options.hpp>
#include <nlohmann/json.hpp>

#include "mrs_vpr/descriptor.hpp"
#include "mrs_vpr/descriptor_sequence.hpp"
#include "mrs_vpr/evaluation/evaluation.hpp"
#include "mrs_vpr/evaluation/image_folder.hpp"
#include "mrs_vpr/evaluation/progress_line.hpp"
#include "mrs_vpr/memory_reuse.hpp"
#include "mrs_vpr/node/bag_images.hpp"
#include "mrs_vpr/parameters.hpp"
#include "mrs_vpr/place_recognizer.hpp"
#include "mrs_vpr/store/map_database.hpp"
#include "evaluation_plots.hpp"
#include "descriptor_options.hpp"
#include "summary_json.hpp"
#include "tool_main.hpp"
#include "traversal_reader.hpp"

namespace po = boost::program_options;
using json = nlohmann::ordered_json;  // Keeps fields in the documented order.
using Clock = std::chrono::steady_clock;

namespace {

constexpr const char* kUsage =
    "Usage: mrs_vpr_eval --reference DIR|BAG|MAP.db --query DIR|BAG [--topic T] [--ground-truth FILE.csv]\n"
    "                    --protocol per-frame|global [--method mrs|seqslam] [--sequence-length N]\n"
    "                    [--min-appearance-change C] [--alignment causal|centred]\n"
    "                    [--queries K] [--tolerance T] [--seed S] [--output FILE.json]\n"
    "                    [--accept-threshold C] [--threads T] [--out-of-map] [--plots DIR]\n"
    "--method, --sequence-length, --min-appearance-change and --alignment default to the node's.\n"
    "\n"
    "Evaluates visual place recognition of a query traversal against a reference traversal.\n"
    "Image folders are read in file-name order; bags (*.bag) give the sensor_msgs/Image or\n"
    "CompressedImage messages of --topic. Without --ground-truth, query frame i matches reference\n"
    "frame i; a ground-truth CSV has the header query_index,matching_ref_indices and rows\n"
    "'i,a b c' (0-based). Protocols:\n"
    "  per-frame  every query frame with a full sequence of N frames (ending at it when causal);\n"
    "             PR curve over a threshold on confidence, PR-AUC, recall at 100% precision, top-1\n"
    "  global     K test sequences of N frames at random start positions (seeded); each returns\n"
    "             the reference frame of its newest frame (its middle when centred)\n"
    "A prediction is correct within --tolerance frames of a true index. Every answer is accepted or\n"
    "not by the core's acceptance rule (confidence >= --accept-threshold); with --out-of-map no query\n"
    "frame is in the reference, so every accepted answer is a false loop closure. The summary is\n"
    "printed on stdout; --output writes parameters, per-query records, summary and PR curve as JSON.\n"
    "--plots DIR writes that JSON (DIR/evaluation.json), pictures of the difference matrix, and the\n"
    "plots of mrs_vpr_plot (PR curve, difference matrix and band, error along the route) into DIR.\n";

/**
 * Creates `folder` when missing and writes and removes a file in it, so that results that could not
 * be written are found before the evaluation rather than after it (permissions, a read-only file
 * system, a file in the way). Throws std::runtime_error naming `option`, the folder and the reason.
 */
void requireWritableFolder(const std::string& folder, const std::string& option) {
  std::error_code error;
  std::filesystem::create_directories(folder, error);
  if (error) throw std::runtime_error(option + " '" + folder + "': cannot create the folder: " + error.message());
  std::string probe = (std::filesystem::path(folder) / ".mrs_vpr_eval_probe.XXXXXX").string();
  const int file = ::mkstemp(probe.data());
  if (file < 0) {
    throw std::runtime_error(option + " '" + folder + "': no file can be written in the folder: " +
                             std::strerror(errno));
  }
  ::close(file);
  std::filesystem::remove(probe, error);
}

double secondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

struct Options {
  std::string reference;
  std::string query;
  std::string topic;
  std::string ground_truth;
  std::string method;
  std::string protocol;
  std::string output;
  std::string plots;
  int queries = 200;
  int tolerance = 2;
  int threads = 0;
  bool out_of_map = false;
  std::int64_t seed = 42;  // Signed, so that a negative seed is seen and refused, not wrapped.
  mrs_vpr::Parameters params;
  bool descriptor_given = false;  ///< A descriptor option was set; else a map database's own front end is used.
  /// As the node's ~min_appearance_change: both traversals are keyframed as the node keyframes a camera.
  double min_appearance_change = mrs_vpr::RecognizerParams{}.min_appearance_change;
};

/// Parses the command line; returns nothing after printing the help.
std::optional<Options> parseOptions(int argc, char** argv) {
  Options options;
  mrs_vpr::Parameters& params = options.params;
  std::string alignment = mrs_vpr::toString(params.sequence.alignment);
  po::options_description description("Options");
  // clang-format off
  description.add_options()
      ("help,h", "print this help")
      ("reference", po::value(&options.reference)->required(), "reference traversal: image folder or .bag")
      ("query", po::value(&options.query)->required(), "query traversal: image folder or .bag")
      ("topic", po::value(&options.topic), "image topic of the bags")
      ("ground-truth", po::value(&options.ground_truth), "CSV query_index,matching_ref_indices (default: identity)")
      ("method", po::value(&options.method)->default_value(mrs_vpr::RecognizerParams{}.default_method),
       "mrs | seqslam (default: the node's)")
      ("protocol", po::value(&options.protocol)->required(), "per-frame | global")
      ("sequence-length", po::value(&params.sequence.sequence_length)->default_value(params.sequence.sequence_length),
       "N: keyframes per test sequence (ds of the per-frame protocol; default: the node's continuous mode)")
      ("min-appearance-change", po::value(&options.min_appearance_change)->default_value(options.min_appearance_change),
       "keyframes by appearance change, as the node's ~min_appearance_change; 0 = every frame")
      ("queries", po::value(&options.queries)->default_value(options.queries), "K: test sequences of the global protocol")
      ("tolerance", po::value(&options.tolerance)->default_value(options.tolerance), "frames of error still counted correct")
      ("seed", po::value(&options.seed)->default_value(options.seed), "seed of the global start positions and of mrs")
      ("output", po::value(&options.output), "JSON file with parameters, records, summary and PR curve")
      ("plots", po::value(&options.plots), "folder for the JSON, the difference pictures and the PNG plots")
      ("accept-threshold", po::value(&params.sequence.accept_threshold)->default_value(params.sequence.accept_threshold),
       "answers are accepted at this confidence (distinctiveness, in spreads of the query's end costs)")
      ("out-of-map", po::bool_switch(&options.out_of_map), "no query frame is in the reference (new ground)")
      ("threads", po::value(&options.threads)->default_value(options.threads), "threads of both methods; 0 = OpenCV's default")
      ("alignment", po::value(&alignment)->default_value(alignment), "causal | centred: where the localised frame sits")
      ("velocity-min", po::value(&params.sequence.velocity_min)->default_value(params.sequence.velocity_min),
       "slowest reference keyframes per test keyframe")
      ("velocity-max", po::value(&params.sequence.velocity_max)->default_value(params.sequence.velocity_max),
       "fastest reference keyframes per test keyframe")
      ("velocity-step", po::value(&params.sequence.velocity_step)->default_value(params.sequence.velocity_step),
       "step between the velocities tried (0.02 for sequences in the hundreds)")
      ("alignment-slack", po::value(&params.sequence.alignment_slack)->default_value(params.sequence.alignment_slack),
       "frames the path that places an answer may stray from the best straight trajectory; 0 = its end")
      ("levels", po::value(&params.mrs.levels)->default_value(params.mrs.levels), "mrs: l_max, coarsest stride 2^levels")
      ("tau", po::value(&params.mrs.tau)->default_value(params.mrs.tau), "mrs: particle overlap, P_init = M / N * tau");
  // clang-format on
  mrs_vpr::tools::addDescriptorOptions(description, params.descriptor);
  po::variables_map variables;
  if (!mrs_vpr::tools::parseCommandLine(argc, argv, kUsage, description, variables)) return std::nullopt;
  options.descriptor_given = mrs_vpr::tools::descriptorOptionsGiven(variables);

  if (options.method != "mrs" && options.method != "seqslam") {
    throw std::invalid_argument("unknown method '" + options.method + "' (expected mrs or seqslam)");
  }
  if (options.protocol != "per-frame" && options.protocol != "global") {
    throw std::invalid_argument("unknown protocol '" + options.protocol + "' (expected per-frame or global)");
  }
  if (options.tolerance < 0) throw std::invalid_argument("--tolerance must be >= 0");
  // Each test sequence keeps a record; a million of them took 1.7 GB.
  if (options.queries < 1 || options.queries > 100000) throw std::invalid_argument("--queries must be in 1..100000");
  if (options.threads < 0) throw std::invalid_argument("--threads must be >= 0");
  if (options.out_of_map && !options.ground_truth.empty()) {
    throw std::invalid_argument("--out-of-map and --ground-truth exclude each other");
  }
  if ((mrs_vpr::bag::isBagPath(options.reference) || mrs_vpr::bag::isBagPath(options.query)) &&
      options.topic.empty()) {
    throw std::invalid_argument("reading a bag needs --topic");
  }
  params.sequence.alignment = mrs_vpr::parseWindowAlignment(alignment);
  if (options.seed < 0) throw std::invalid_argument("--seed must be >= 0, got " + std::to_string(options.seed));
  params.mrs.seed = static_cast<std::uint64_t>(options.seed);
  params.validate();
  mrs_vpr::RecognizerParams keyframing;
  keyframing.min_appearance_change = options.min_appearance_change;
  keyframing.validate();
  if (!options.plots.empty()) requireWritableFolder(options.plots, "--plots");
  if (!options.output.empty()) {
    if (std::filesystem::is_directory(options.output)) {
      throw std::invalid_argument("--output '" + options.output + "' is a folder; give the JSON file to write");
    }
    const std::filesystem::path folder = std::filesystem::path(options.output).parent_path();
    if (!folder.empty() && !std::filesystem::is_directory(folder)) {
      throw std::invalid_argument("--output '" + options.output + "': there is no folder " + folder.string());
    }
    requireWritableFolder(folder.empty() ? "." : folder.string(), "--output");
  }
  return options;
}

/// The keyframes of both traversals: the records name frames, the search sees keyframes.
struct Keyframed {
  mrs_vpr::Keyframes reference;
  mrs_vpr::Keyframes query;
};

/// Per-frame protocol: one search per query frame with a full sequence, all in one call so that a
/// method can share work between frames (seqslam computes the difference matrix once). The time of
/// a query is therefore the call's time divided by the number of frames searched.
std::vector<mrs_vpr::QueryRecord> runPerFrame(mrs_vpr::PlaceRecognizer& reference, const std::string& method,
                                              const mrs_vpr::DescriptorSequence& query,
                                              const mrs_vpr::GroundTruth* truth,
                                              const mrs_vpr::SequenceParams& sequence, const Keyframed& keyframes) {
  const std::vector<int> frames = mrs_vpr::perFrameQueries(query.size(), sequence);
  if (frames.empty()) {
    throw std::invalid_argument("the query has " + std::to_string(query.size()) +
                                " frames, fewer than the sequence length " + std::to_string(sequence.sequence_length));
  }
  std::cerr << "  matching " << frames.size() << " query frames with " << method << "\n";
  const Clock::time_point start = Clock::now();
  const std::vector<mrs_vpr::Match> matches = reference.matchEveryFrame(query.view(), method);
  const double per_query_ms = 1000.0 * secondsSince(start) / static_cast<double>(frames.size());

  std::vector<mrs_vpr::QueryRecord> records;
  for (int keyframe : frames) {
    const int frame = keyframes.query.frames[static_cast<std::size_t>(keyframe)];
    const auto true_indices = mrs_vpr::truthFor(frame, truth, keyframes.reference.total);
    if (!true_indices) continue;
    records.push_back(mrs_vpr::keyframeRecordOf(frame, *true_indices, matches.at(static_cast<std::size_t>(keyframe)),
                                                keyframes.reference, per_query_ms));
  }
  return records;
}

/// Global localisation protocol: each test sequence is searched on its own and timed.
std::vector<mrs_vpr::QueryRecord> runGlobal(mrs_vpr::PlaceRecognizer& reference, const mrs_vpr::DescriptorSequence& query,
                                            const mrs_vpr::GroundTruth* truth, const Options& options,
                                            const Keyframed& keyframes) {
  const mrs_vpr::SequenceParams& sequence = options.params.sequence;
  if (sequence.sequence_length > query.size()) {
    throw std::invalid_argument("sequence length " + std::to_string(sequence.sequence_length) +
                                " is larger than the query of " + std::to_string(query.size()) + " frames");
  }
  const std::vector<mrs_vpr::TestSequence> tests = mrs_vpr::globalQueries(
      query.size(), sequence.sequence_length, options.queries, static_cast<std::uint64_t>(options.seed),
      sequence.alignment);
  std::vector<mrs_vpr::QueryRecord> records;
  int done = 0;
  int skipped = 0;
  mrs_vpr::ProgressLine progress =
      mrs_vpr::ProgressLine::onStderr("  " + options.method, "test sequences", static_cast<long long>(tests.size()));
  for (const mrs_vpr::TestSequence& test : tests) {
    progress.update(done++);
    const int frame = keyframes.query.frames[static_cast<std::size_t>(test.query_index)];
    const auto true_indices = mrs_vpr::truthFor(frame, truth, keyframes.reference.total);
    if (!true_indices) {
      ++skipped;
      continue;
    }
    const Clock::time_point start = Clock::now();
    const mrs_vpr::Match match =
        reference.match(query.view(test.start, test.start + test.length), options.method).match;
    records.push_back(mrs_vpr::keyframeRecordOf(frame, *true_indices, match, keyframes.reference,
                                                1000.0 * secondsSince(start)));
  }
  progress.update(done);
  progress.finish();
  if (skipped > 0) std::cerr << "  " << skipped << " test sequences skipped: their frame has no ground truth\n";
  return records;
}

/// A reference given as a map database (*.db) rather than as images.
bool isMapDatabase(const std::string& path) {
  return path.size() > 3 && path.compare(path.size() - 3, 3, ".db") == 0;
}

/// Every descriptor parameter, named as in the parameter reference without "descriptor/" ("type",
/// "image_width", "hog/cell_size", ...).
json descriptorJson(const mrs_vpr::DescriptorParams& descriptor) {
  json fields = json::object();
  for (const auto& spec : mrs_vpr::descriptorParameters()) {
    const std::string name = spec.info.name.substr(spec.info.name.find('/') + 1);
    std::visit(
        [&](auto member) {
          using Value = std::decay_t<decltype(descriptor.*member)>;
          if constexpr (std::is_same_v<Value, mrs_vpr::WindowAlignment>) {
            fields[name] = mrs_vpr::toString(descriptor.*member);
          } else {
            fields[name] = descriptor.*member;
          }
        },
        spec.member);
  }
  return fields;
}

/// The parameters of the run: those of the command line, with `p` as the parameters in effect (the
/// front end of a map database given as the reference).
json parametersToJson(const Options& options, const mrs_vpr::Parameters& p) {
  return {
      {"method", options.method},
      {"protocol", options.protocol},
      {"reference", options.reference},
      {"query", options.query},
      {"topic", options.topic.empty() ? json(nullptr) : json(options.topic)},
      {"ground_truth", options.ground_truth.empty() ? json(nullptr) : json(options.ground_truth)},
      {"sequence_length", p.sequence.sequence_length},
      {"min_appearance_change", options.min_appearance_change},
      {"queries", options.queries},
      {"tolerance", options.tolerance},
      {"seed", options.seed},
      {"threads", options.threads},
      {"out_of_map", options.out_of_map},
      {"descriptor", descriptorJson(p.descriptor)},
      {"sequence",
       {{"sequence_length", p.sequence.sequence_length},
        {"velocity_min", p.sequence.velocity_min},
        {"velocity_max", p.sequence.velocity_max},
        {"velocity_step", p.sequence.velocity_step},
        {"contrast_window", p.sequence.contrast_window},
        {"match_exclusion", p.sequence.match_exclusion},
        {"alignment", mrs_vpr::toString(p.sequence.alignment)},
        {"alignment_slack", p.sequence.alignment_slack},
        {"accept_threshold", p.sequence.accept_threshold}}},
      {"mrs",
       {{"levels", p.mrs.levels},
        {"min_coarse_frames", p.mrs.min_coarse_frames},
        {"tau", p.mrs.tau},
        {"index_shift", p.mrs.index_shift},
        {"coverage_threshold", p.mrs.coverage_threshold},
        {"max_iterations", p.mrs.max_iterations},
        {"resample_threshold", p.mrs.resample_threshold},
        {"min_particles", p.mrs.min_particles},
        {"hypotheses", p.mrs.hypotheses},
        {"seed", p.mrs.seed}}},
  };
}

json recordsToJson(const std::vector<mrs_vpr::QueryRecord>& records, int tolerance) {
  json list = json::array();
  for (const mrs_vpr::QueryRecord& record : records) {
    const int nearest = mrs_vpr::nearestTrueIndex(record);
    list.push_back({{"query_index", record.query_index},
                    {"true_index", nearest >= 0 ? json(nearest) : json(nullptr)},
                    {"true_indices", record.true_indices},
                    {"predicted_index", record.predicted_index},
                    {"predicted_last", record.predicted_last},
                    {"score", record.score},
                    {"confidence", record.confidence},
                    {"accepted", record.accepted},
                    {"rival_places", record.rival_places},
                    {"at_velocity_bound", record.at_velocity_bound},
                    {"repeated_view", record.repeated_view},
                    {"time_ms", record.time_ms},
                    {"correct", mrs_vpr::isCorrect(record, tolerance)}});
  }
  return list;
}

void writeJson(const json& document, const std::string& path) {
  std::ofstream file(path);
  if (!file) throw std::runtime_error("cannot write '" + path + "'");
  file << document.dump(2) << "\n";
  if (!file) throw std::runtime_error("cannot write '" + path + "'");
  std::cerr << "  wrote " << path << "\n";
}

int run(int argc, char** argv) {
  const Clock::time_point start = Clock::now();
  const std::optional<Options> parsed = parseOptions(argc, argv);
  if (!parsed) return 0;
  const Options& options = *parsed;
  const mrs_vpr::SequenceParams& sequence = options.params.sequence;

  if (options.threads > 0) cv::setNumThreads(options.threads);
  std::optional<mrs_vpr::GroundTruth> truth;
  if (!options.ground_truth.empty()) truth = mrs_vpr::readGroundTruthCsv(options.ground_truth);

  // A map built by build_map or the node holds descriptors already, of the front end it records.
  std::optional<mrs_vpr::MapDatabase> map;
  mrs_vpr::Parameters params = options.params;
  if (isMapDatabase(options.reference)) {
    if (options.descriptor_given) {
      map.emplace(options.reference, params.descriptor, mrs_vpr::MapAccess::kReadOnly);
    } else {
      map.emplace(options.reference, mrs_vpr::MapAccess::kReadOnly);
      params.descriptor = map->descriptorParams();
    }
  }
  // The reference is the recognizer's map, keyframed as the node keyframes a camera; unbounded, as an
  // offline traversal may be of any length.
  mrs_vpr::RecognizerParams map_params;
  map_params.max_frames = 0;
  map_params.min_appearance_change = options.min_appearance_change;
  mrs_vpr::PlaceRecognizer recognizer(params, map_params);
  const mrs_vpr::DescriptorExtractor& extractor = recognizer.extractor();
  std::cerr << "mrs_vpr_eval: " << options.method << ", " << options.protocol << " protocol, N = "
            << sequence.sequence_length << ", " << params.descriptor.describe() << ", keyframes at an appearance change of "
            << options.min_appearance_change << "\n";
  Keyframed keyframes;
  // The plots draw the difference matrix of every frame (the records name frames), which needs the
  // traversals' descriptors beside the map's keyframes.
  mrs_vpr::DescriptorSequence plotted_reference(extractor.size());
  mrs_vpr::DescriptorSequence plotted_query(extractor.size());
  const auto add_to_map = [&](const cv::Mat& descriptor, mrs_vpr::Stamp stamp) {
    const int frame = keyframes.reference.total++;
    if (!options.plots.empty()) plotted_reference.append(descriptor, stamp);
    // A map database holds keyframes already; a traversal is offered frame by frame.
    if ((map ? recognizer.addDescriptor(descriptor, stamp) : recognizer.offerDescriptor(descriptor, stamp)) !=
        mrs_vpr::FrameAdmission::kAdmitted) {
      return;
    }
    keyframes.reference.frames.push_back(frame);
  };
  mrs_vpr::tools::Traversal reference;
  if (map) {
    map->forEachFrame([&](const mrs_vpr::StoredFrame& frame) { add_to_map(frame.descriptor.clone(), frame.stamp); });
    reference.frames = recognizer.size();
    std::cerr << "  reference: " << reference.frames << " frames from the map database " << options.reference << "\n";
  } else {
    reference = mrs_vpr::tools::readTraversal(options.reference, options.topic, "reference", extractor, add_to_map);
    std::cerr << "  reference: " << recognizer.size() << " keyframes of " << reference.frames << " frames\n";
  }
  if (sequence.sequence_length > recognizer.size()) {
    throw std::invalid_argument("sequence length " + std::to_string(sequence.sequence_length) +
                                " is larger than the reference of " + std::to_string(recognizer.size()) + " keyframes");
  }
  // The query is keyframed as the node keyframes the camera after the map: on the map's scale.
  mrs_vpr::DescriptorSequence query_frames(extractor.size());
  const mrs_vpr::tools::Traversal query =
      mrs_vpr::tools::readTraversal(options.query, options.topic, "query", extractor,
                                    [&](const cv::Mat& descriptor, mrs_vpr::Stamp stamp) { query_frames.append(descriptor, stamp); });
  keyframes.query.total = query_frames.size();
  const mrs_vpr::DescriptorSequence query_descriptors = recognizer.keyframesOf(query_frames, &keyframes.query.frames);
  if (!options.plots.empty()) plotted_query = std::move(query_frames);
  std::cerr << "  query: " << query_descriptors.size() << " keyframes of " << query.frames << " frames\n";
  // A map database keeps descriptors, not images: there is no image size to compare.
  if (!isMapDatabase(options.reference) && query.image_size != reference.image_size) {
    throw std::invalid_argument(
        "query images are " + std::to_string(query.image_size.width) + "x" + std::to_string(query.image_size.height) +
        " but reference images are " + std::to_string(reference.image_size.width) + "x" +
        std::to_string(reference.image_size.height));
  }
  const double describe_s = secondsSince(start);

  if (truth) mrs_vpr::checkGroundTruth(*truth, query.frames, reference.frames);
  if (options.out_of_map) {
    truth.emplace();  // Every query frame, none of them in the reference.
    for (int frame = 0; frame < query.frames; ++frame) (*truth)[frame] = {};
  }
  const mrs_vpr::GroundTruth* truth_ptr = truth ? &*truth : nullptr;
  const Clock::time_point match_start = Clock::now();
  const std::vector<mrs_vpr::QueryRecord> records =
      options.protocol == "per-frame"
          ? runPerFrame(recognizer, options.method, query_descriptors, truth_ptr, sequence, keyframes)
          : runGlobal(recognizer, query_descriptors, truth_ptr, options, keyframes);
  const double match_s = secondsSince(match_start);
  if (records.empty()) throw std::invalid_argument("no query frame has ground truth: nothing to evaluate");

  mrs_vpr::EvaluationSummary summary = mrs_vpr::summarise(records, options.tolerance);
  summary.total_time_s = secondsSince(start);  // The whole evaluation: reading, describing, matching.

  if (!options.output.empty() || !options.plots.empty()) {
    json pr_curve = json::array();
    for (const mrs_vpr::PrPoint& point : mrs_vpr::precisionRecallCurve(records, options.tolerance)) {
      pr_curve.push_back({{"threshold", point.threshold}, {"precision", point.precision}, {"recall", point.recall}});
    }
    json document = {
        {"method", options.method},
        {"protocol", options.protocol},
        {"reference_frames", reference.frames},
        {"query_frames", query.frames},
        {"reference_keyframes", recognizer.size()},
        {"query_keyframes", query_descriptors.size()},
        {"parameters", parametersToJson(options, params)},
        {"summary", mrs_vpr::tools::summaryToJson(summary)},
        {"timing",
         {{"read_and_describe_s", describe_s},
          {"match_s", match_s},
          {"note", options.protocol == "per-frame"
                       ? "per-frame time_ms is the matching time of all frames divided by their number"
                       : "time_ms is the matching time of each test sequence"}}},
        {"records", recordsToJson(records, options.tolerance)},
        {"pr_curve", pr_curve},
    };
    if (!options.plots.empty()) {
      std::filesystem::create_directories(options.plots);
      document["difference_pictures"] = mrs_vpr::tools::writeDifferencePictures(
          options.plots, plotted_query.view(), plotted_reference.view(), records, sequence.contrast_window);
    }
    if (!options.output.empty()) writeJson(document, options.output);
    if (!options.plots.empty()) {
      const std::string evaluation = (std::filesystem::path(options.plots) / "evaluation.json").string();
      writeJson(document, evaluation);
      mrs_vpr::tools::runPlotTool({"eval", evaluation, "--directory", options.plots});
    }
  }
  std::cout << json{{"method", options.method}, {"protocol", options.protocol}, {"summary", mrs_vpr::tools::summaryToJson(summary)}}.dump(2)
            << std::endl;
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  mrs_vpr::retainFreedMemory();  // Each query reuses the memory the previous one freed.
  return mrs_vpr::tools::runTool("mrs_vpr_eval", run, argc, argv);
}

// mrs_vpr_eval: offline evaluation of `seqslam` and `mrs` on two traversals (image folders or bags)
// with either protocol of the paper notes: per-frame (SeqSLAM style) or global localisation.

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <iostream>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "eval_options.hpp"
#include "evaluation_json.hpp"
#include "evaluation_plots.hpp"
#include "mrs_vpr/descriptor.hpp"
#include "mrs_vpr/descriptor_sequence.hpp"
#include "mrs_vpr/evaluation/evaluation.hpp"
#include "mrs_vpr/evaluation/image_folder.hpp"
#include "mrs_vpr/evaluation/progress_line.hpp"
#include "mrs_vpr/memory_reuse.hpp"
#include "mrs_vpr/parameters.hpp"
#include "mrs_vpr/place_recognizer.hpp"
#include "mrs_vpr/store/map_database.hpp"
#include "mrs_vpr/store/map_traversal.hpp"
#include "stopwatch.hpp"
#include "summary_json.hpp"
#include "tool_main.hpp"
#include "traversal_reader.hpp"

namespace mrs_vpr {
namespace tools {
namespace {

using json = OrderedJson;

/// The keyframes of both traversals: the records name frames, the search sees keyframes.
struct Keyframed {
  Keyframes reference;
  Keyframes query;
};

/// The true reference frames of query frame `frame`; nullopt when it has no ground truth. By the
/// identity ground truth, a frame before the map's first keyframe shows a place the map does not hold
/// (a map database whose frames are numbered from later on): it is a query about a place outside the
/// map, not one the map should have answered.
std::optional<std::vector<int>> truthOfFrame(int frame, const GroundTruth* truth, const Keyframes& reference) {
  if (truth == nullptr && !reference.frames.empty() && frame >= 0 && frame < reference.frames.front()) {
    return std::vector<int>{};
  }
  return truthFor(frame, truth, reference.total);
}

/// The error of a query with fewer keyframes than a test sequence needs.
std::invalid_argument tooShortQuery(const Keyframes& query, int sequence_length) {
  const int kept = static_cast<int>(query.frames.size());
  return std::invalid_argument(
      "the query's " + std::to_string(query.total) + " frames hold " + std::to_string(kept) + " keyframes, fewer " +
      "than the sequence length " + std::to_string(sequence_length) +
      (kept < query.total ? ": its view hardly changes (a stop), or --min-appearance-change is too high for these "
                            "frames (0 keeps every frame)"
                          : ""));
}

/// Per-frame protocol: one search per query frame with a full sequence, all in one call so that a
/// method can share work between frames (seqslam computes the difference matrix once). The time of
/// a query is therefore the call's time divided by the number of frames searched.
std::vector<QueryRecord> runPerFrame(PlaceRecognizer& reference, const std::string& method,
                                     const DescriptorSequence& query, const GroundTruth* truth,
                                     const SequenceParams& sequence, const Keyframed& keyframes,
                                     int& without_rivals) {
  const std::vector<int> frames = perFrameQueries(query.size(), sequence);
  if (frames.empty()) throw tooShortQuery(keyframes.query, sequence.sequence_length);
  std::cerr << "  matching " << frames.size() << " query frames with " << method << "\n";
  const Clock::time_point start = Clock::now();
  const std::vector<Match> matches = reference.matchEveryFrame(query.view(), method);
  const double per_query_ms = 1000.0 * secondsSince(start) / static_cast<double>(frames.size());

  std::vector<QueryRecord> records;
  int skipped = 0;
  for (int keyframe : frames) {
    const int frame = keyframes.query.frames[static_cast<std::size_t>(keyframe)];
    const auto true_indices = truthOfFrame(frame, truth, keyframes.reference);
    if (!true_indices) {
      ++skipped;
      continue;
    }
    const Match& match = matches.at(static_cast<std::size_t>(keyframe));
    if (hasTooFewRivals(match)) ++without_rivals;
    records.push_back(keyframeRecordOf(frame, *true_indices, match, keyframes.reference, per_query_ms));
  }
  if (skipped > 0) std::cerr << "  " << skipped << " query frames skipped: they have no ground truth\n";
  return records;
}

/// Global localisation protocol: each test sequence is searched on its own and timed.
std::vector<QueryRecord> runGlobal(PlaceRecognizer& reference, const DescriptorSequence& query,
                                   const GroundTruth* truth, const EvalOptions& options, const Keyframed& keyframes,
                                   int& without_rivals) {
  const SequenceParams& sequence = options.params.sequence;
  if (sequence.sequence_length > query.size()) throw tooShortQuery(keyframes.query, sequence.sequence_length);
  const std::vector<TestSequence> tests = globalQueries(query.size(), sequence.sequence_length, options.queries,
                                                        static_cast<std::uint64_t>(options.seed), sequence.alignment);
  const std::string repeated = repeatedGlobalQueries(query.size(), sequence.sequence_length, options.queries);
  if (!repeated.empty()) std::cerr << "  " << repeated << "\n";
  std::vector<QueryRecord> records;
  int done = 0;
  int skipped = 0;
  ProgressLine progress =
      ProgressLine::onStderr("  " + options.method, "test sequences", static_cast<long long>(tests.size()));
  for (const TestSequence& test : tests) {
    progress.update(done++);
    const int frame = keyframes.query.frames[static_cast<std::size_t>(test.query_index)];
    const auto true_indices = truthOfFrame(frame, truth, keyframes.reference);
    if (!true_indices) {
      ++skipped;
      continue;
    }
    const Clock::time_point start = Clock::now();
    const Match match = reference.match(query.view(test.start, test.start + test.length), options.method).match;
    if (hasTooFewRivals(match)) ++without_rivals;
    records.push_back(keyframeRecordOf(frame, *true_indices, match, keyframes.reference, 1000.0 * secondsSince(start)));
  }
  progress.update(done);
  progress.finish();
  if (skipped > 0) std::cerr << "  " << skipped << " test sequences skipped: their frame has no ground truth\n";
  return records;
}

/// A reference given as a map database rather than as images: no folder, and named *.db (in any case) or
/// an SQLite file of another name.
bool isMapDatabase(const std::string& path) {
  if (std::filesystem::is_directory(path)) return false;
  std::string suffix = std::filesystem::path(path).extension().string();
  std::transform(suffix.begin(), suffix.end(), suffix.begin(), [](unsigned char c) { return std::tolower(c); });
  return suffix == ".db" || MapDatabase::isSqliteFile(path);
}

/// A map database's keyframes as frames of the traversal they were taken from, by the number each
/// stores (build_map stores the frame's index in its folder or bag), so that the ground truth names
/// the traversal's frames as it does for the folder itself; nullopt when a keyframe has no number or
/// the numbers do not increase.
std::optional<Keyframes> storedFrameNumbers(const std::vector<std::int64_t>& numbers) {
  Keyframes keyframes;
  for (const std::int64_t number : numbers) {
    const bool increasing = keyframes.frames.empty() || number > keyframes.frames.back();
    if (number < 0 || number >= std::numeric_limits<int>::max() || !increasing) return std::nullopt;
    keyframes.frames.push_back(static_cast<int>(number));
  }
  keyframes.total = keyframes.frames.empty() ? 0 : keyframes.frames.back() + 1;
  return keyframes;
}

/// Offers a map database's keyframes to `add_to_map` and numbers `keyframes` by the frames of the
/// traversal they were taken from, where the database stores increasing numbers (build_map's maps
/// do); gives the recognizer the map's place links and drive starts, as a node started on it has them; returns the
/// traversal they stand for.
Traversal readMapDatabase(MapDatabase& map, const EvalOptions& options, PlaceRecognizer& recognizer,
                          Keyframes& keyframes, const std::function<void(const cv::Mat&, Stamp)>& add_to_map) {
  std::vector<std::int64_t> stored_numbers;
  std::optional<MapTraversal> recorded;
  std::vector<PlaceLink> links;
  std::vector<int> drive_starts;
  // The frames and their record as the file holds them at one moment, whatever a node writes meanwhile.
  map.readAtOneMoment([&] {
    recorded = map.readTraversal();
    map.forEachFrame([&](const StoredFrame& frame) {
      const std::size_t kept = keyframes.frames.size();
      add_to_map(frame.descriptor.clone(), frame.stamp);
      if (keyframes.frames.size() > kept) stored_numbers.push_back(frame.sequence);
    });
    links = map.placeLinks();
    drive_starts = map.driveStarts();
  });
  if (recognizer.size() == 0) throw std::invalid_argument("the map database " + options.reference + " holds no frame");
  // Every frame of a map database joins the map (an unbounded one), so its links name the map's frames.
  recognizer.linkPlaces(links);
  for (const int start : drive_starts) {
    if (start <= recognizer.size()) recognizer.markDriveStart(start);  // as a node started on it has them
  }
  std::cerr << "  reference: " << recognizer.size() << " keyframes from the map database " << options.reference;
  if (!links.empty()) {
    std::cerr << " (" << recognizer.state().linked_frames << " of them linked by its loop closures to a place an "
              << "earlier visit shows)";
  }
  if (const std::optional<Keyframes> numbered = storedFrameNumbers(stored_numbers)) {
    keyframes = *numbered;
    // build_map records how many frames the traversal had: those after the last keyframe, which it
    // stands for, are frames of the reference too.
    if (recorded && recorded->frames > keyframes.total && recorded->frames <= std::numeric_limits<int>::max()) {
      keyframes.total = static_cast<int>(recorded->frames);
    }
    std::cerr << ", frames " << numbered->frames.front() << " to " << numbered->frames.back() << " of its traversal of "
              << keyframes.total << " frames by the numbers it stores\n";
    if (numbered->frames.front() > 0 && options.ground_truth.empty() && !options.out_of_map) {
      std::cerr << "  query frames 0 to " << numbered->frames.front() - 1
                << " show, by the identity ground truth, places before the map's first frame: places outside"
                << " the map\n";
    }
  } else {
    std::cerr << ", numbered 0 to " << recognizer.size() - 1 << " in order: it stores no increasing frame numbers"
              << " (build_map's maps do), so frame i of the ground truth is its i-th keyframe\n";
  }
  Traversal traversal;
  traversal.frames = keyframes.total;
  return traversal;
}

/// The query is keyframed as the map's frames were, where the map records how (keyframingMismatch).
void takeTheMapsKeyframing(const MapDatabase& map, EvalOptions& options) {
  const std::optional<MapTraversal>& traversal = map.traversal();
  if (!traversal || !traversal->min_appearance_change) return;
  if (!options.min_appearance_change_given) {
    options.min_appearance_change = *traversal->min_appearance_change;
    return;
  }
  const std::string mismatch =
      keyframingMismatch(traversal, options.min_appearance_change, "--min-appearance-change");
  if (!mismatch.empty()) {
    std::cerr << "mrs_vpr_eval: warning: " << mismatch << "; leave the option out to keyframe the query as the map\n";
  }
}

/// The precision-recall curve of `records` as JSON points.
json prCurveToJson(const std::vector<QueryRecord>& records, int tolerance) {
  json pr_curve = json::array();
  for (const PrPoint& point : precisionRecallCurve(records, tolerance)) {
    pr_curve.push_back({{"threshold", point.threshold}, {"precision", point.precision}, {"recall", point.recall}});
  }
  return pr_curve;
}

/// Writes the evaluation `document` to --output and, with --plots, its pictures and plots to that folder.
void writeEvaluation(json document, const EvalOptions& options, const DescriptorSequence& plotted_query,
                     const DescriptorSequence& plotted_reference, const std::vector<QueryRecord>& records) {
  if (!options.plots.empty()) {
    std::filesystem::create_directories(options.plots);
    document["difference_pictures"] =
        writeDifferencePictures(options.plots, plotted_query.view(), plotted_reference.view(), records,
                                options.params.sequence.contrast_window);
  }
  if (!options.output.empty()) {
    // Its pictures lie in the --plots folder, not beside it: named by their whole path there.
    json output = document;
    if (output.contains("difference_pictures")) {
      for (auto& [key, picture] : output["difference_pictures"].items()) {
        if (!picture.is_object()) continue;
        const std::filesystem::path file = std::filesystem::path(options.plots) / picture["file"].get<std::string>();
        picture["file"] = std::filesystem::absolute(file).lexically_normal().string();
      }
    }
    writeJson(output, options.output);
  }
  if (!options.plots.empty()) {
    const std::string evaluation = (std::filesystem::path(options.plots) / "evaluation.json").string();
    writeJson(document, evaluation);
    runPlotTool({"eval", evaluation, "--directory", options.plots});
  }
}

int run(int argc, char** argv) {
  const Clock::time_point start = Clock::now();
  const std::optional<EvalOptions> parsed = parseEvalOptions(argc, argv);
  if (!parsed) return 0;
  EvalOptions options = *parsed;
  const SequenceParams& sequence = options.params.sequence;

  if (options.threads > 0) cv::setNumThreads(options.threads);
  // The query's frames are counted before the reference is described: a mistyped query folder or bag
  // is named at once, and a ground truth of other traversals refused. A map database's frames are
  // known once it is read, before the query is described.
  if (std::filesystem::is_regular_file(options.query) && isMapDatabase(options.query)) {
    throw std::invalid_argument("--query '" + options.query + "' is a map database (named *.db or an SQLite " +
                                "file), which holds a map's keyframes; the query is a traversal to keyframe and " +
                                "match: a folder of images or a bag");
  }
  const int query_frame_count = countFrames(options.query, options.topic);
  std::optional<GroundTruth> truth;
  if (!options.ground_truth.empty()) {
    truth = readGroundTruthCsv(options.ground_truth);
    const int reference_frames = isMapDatabase(options.reference) ? std::numeric_limits<int>::max()
                                                                  : countFrames(options.reference, options.topic);
    checkGroundTruth(*truth, query_frame_count, reference_frames);
  }

  // A map built by build_map or the node holds descriptors already, of the front end it records.
  std::optional<MapDatabase> map;
  Parameters params = options.params;
  if (isMapDatabase(options.reference)) {
    if (options.descriptor_given) {
      map.emplace(options.reference, params.descriptor, MapAccess::kReadOnly);
    } else {
      map.emplace(options.reference, MapAccess::kReadOnly);
      params.descriptor = map->descriptorParams();
    }
  }
  if (map) takeTheMapsKeyframing(*map, options);
  // The reference is the recognizer's map, keyframed as the node keyframes a camera; unbounded, as an
  // offline traversal may be of any length.
  RecognizerParams map_params;
  map_params.max_frames = 0;
  map_params.min_appearance_change = options.min_appearance_change;
  PlaceRecognizer recognizer(params, map_params);
  const DescriptorExtractor& extractor = recognizer.extractor();
  std::cerr << "mrs_vpr_eval: " << options.method << ", " << options.protocol
            << " protocol, N = " << sequence.sequence_length << ", " << params.descriptor.describe()
            << ", keyframes at an appearance change of " << options.min_appearance_change << "\n";
  Keyframed keyframes;
  // The plots draw the difference matrix of every frame (the records name frames), which needs the
  // traversals' descriptors beside the map's keyframes.
  DescriptorSequence plotted_reference(extractor.size());
  DescriptorSequence plotted_query(extractor.size());
  const auto add_to_map = [&](const cv::Mat& descriptor, Stamp stamp) {
    const int frame = keyframes.reference.total++;
    if (!options.plots.empty()) plotted_reference.append(descriptor, stamp);
    // A map database holds keyframes already; a traversal is offered frame by frame.
    if ((map ? recognizer.addDescriptor(descriptor, stamp) : recognizer.offerDescriptor(descriptor, stamp)) !=
        FrameAdmission::kAdmitted) {
      return;
    }
    keyframes.reference.frames.push_back(frame);
  };
  Traversal reference;
  if (map) {
    reference = readMapDatabase(*map, options, recognizer, keyframes.reference, add_to_map);
    if (truth) checkGroundTruth(*truth, query_frame_count, reference.frames);
    if (!options.plots.empty() && plotted_reference.size() != reference.frames) {
      throw std::invalid_argument("--plots draws every frame of the reference, and the map database " +
                                  options.reference + " holds " + std::to_string(plotted_reference.size()) + " of " +
                                  std::to_string(reference.frames) + ": give its image folder or bag instead");
    }
  } else {
    reference = readTraversal(options.reference, options.topic, "reference", extractor, add_to_map);
    std::cerr << "  reference: " << recognizer.size() << " keyframes of " << reference.frames << " frames\n";
  }
  if (sequence.sequence_length > recognizer.size()) {
    throw std::invalid_argument("sequence length " + std::to_string(sequence.sequence_length) +
                                " is larger than the reference of " + std::to_string(recognizer.size()) + " keyframes");
  }
  // The query is keyframed as the node keyframes the camera after the map: on the map's scale.
  DescriptorSequence query_frames(extractor.size());
  const Traversal query =
      readTraversal(options.query, options.topic, "query", extractor,
                    [&](const cv::Mat& descriptor, Stamp stamp) { query_frames.append(descriptor, stamp); });
  keyframes.query.total = query_frames.size();
  const DescriptorSequence query_descriptors = recognizer.keyframesOf(query_frames, &keyframes.query.frames);
  if (!options.plots.empty()) plotted_query = std::move(query_frames);
  std::cerr << "  query: " << query_descriptors.size() << " keyframes of " << query.frames << " frames\n";
  // A map database keeps descriptors, not images: there is no image size to compare.
  if (!isMapDatabase(options.reference) && query.image_size != reference.image_size) {
    throw std::invalid_argument("query images are " + std::to_string(query.image_size.width) + "x" +
                                std::to_string(query.image_size.height) + " but reference images are " +
                                std::to_string(reference.image_size.width) + "x" +
                                std::to_string(reference.image_size.height));
  }
  const double describe_s = secondsSince(start);

  if (options.out_of_map) {
    truth.emplace();  // Every query frame, none of them in the reference.
    for (int frame = 0; frame < query.frames; ++frame) (*truth)[frame] = {};
  }
  const GroundTruth* truth_ptr = truth ? &*truth : nullptr;
  const Clock::time_point match_start = Clock::now();
  int without_rivals = 0;
  const std::vector<QueryRecord> records =
      options.protocol == "per-frame"
          ? runPerFrame(recognizer, options.method, query_descriptors, truth_ptr, sequence, keyframes, without_rivals)
          : runGlobal(recognizer, query_descriptors, truth_ptr, options, keyframes, without_rivals);
  const double match_s = secondsSince(match_start);
  if (records.empty()) throw std::invalid_argument("no query frame has ground truth: nothing to evaluate");
  const std::string rivals_note =
      tooFewRivalsNote(without_rivals, static_cast<int>(records.size()), recognizer.size());
  if (!rivals_note.empty()) std::cerr << "  " << rivals_note << "\n";

  EvaluationSummary summary = summarise(records, options.tolerance);
  summary.total_time_s = secondsSince(start);  // The whole evaluation: reading, describing, matching.

  if (!options.output.empty() || !options.plots.empty()) {
    json document = {
        {"method", options.method},
        {"protocol", options.protocol},
        {"reference_frames", reference.frames},
        {"query_frames", query.frames},
        {"reference_keyframes", recognizer.size()},
        {"query_keyframes", query_descriptors.size()},
        {"parameters", parametersToJson(options, params)},
        {"summary", summaryToJson(summary)},
        {"timing",
         {{"read_and_describe_s", describe_s},
          {"match_s", match_s},
          {"note", options.protocol == "per-frame"
                       ? "per-frame time_ms is the matching time of all frames divided by their number"
                       : "time_ms is the matching time of each test sequence"}}},
        {"records", recordsToJson(records, options.tolerance)},
        {"pr_curve", prCurveToJson(records, options.tolerance)},
    };
    writeEvaluation(std::move(document), options, plotted_query, plotted_reference, records);
  }
  std::cout
      << jsonText(
             json{{"method", options.method}, {"protocol", options.protocol}, {"summary", summaryToJson(summary)}}, 2)
      << std::endl;
  return 0;
}

}  // namespace
}  // namespace tools
}  // namespace mrs_vpr

int main(int argc, char** argv) {
  mrs_vpr::retainFreedMemory();  // Each query reuses the memory the previous one freed.
  return mrs_vpr::tools::runTool("mrs_vpr_eval", mrs_vpr::tools::run, argc, argv);
}

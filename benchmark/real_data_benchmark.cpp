// Real-data benchmark: MRS-VPR against this package's brute-force SeqSLAM on real frames.
//
// Prints figures; it is not a test. It reads the Nordland summer/winter halves and the corridor set
// from a data folder at run time and builds:
//   - references of M ~ 1.8k (summer) and M ~ 9k (summer plus real distractors: both seasons
//     mirrored, summer played backwards, winter mirrored and backwards, the corridor frames);
//   - known-ground queries from winter (global protocol, N = 100, 200, 300; per-frame, ds = 10, 50);
//   - out-of-map queries: winter frames of one half of the route against a reference built from the
//     other half only (its summer frames and the same kinds of distractors), so every accepted
//     answer is a false loop closure;
//   - small maps (20 to 300 frames, as a robot's map is when it starts), known ground and out of the map;
//   - the reported part's winter frames played backwards (places in the map that no trajectory follows);
//   - the node's continuous mode on one traversal (summer, then the part again in winter), its map
//     growing from empty;
//   - camera drives (camera_drive_rows.hpp): the summer frames and the part's winter frames replayed as
//     a camera-only vehicle records them, with noisy stops and slow and fast stretches, through the
//     node's continuous mode at its defaults and through the evaluator's per-frame protocol.
// The route is split in two parts, "tune" (first half) and "check" (second half): design choices are
// made on one and reported on the other (--part). Both methods answer the same queries in one run.
//
//   mrs_vpr_real_benchmark --data DIR [--part tune|check|all] [--queries 100] [--lengths 100,200,300]
//                          [--references 1.8k,9k] [--threads 1] [--tolerance 5] [--seed 42]
//                          [--skip-per-frame] [--skip-global] [--skip-drives] [--drive-length L]
//                          [--drive-alignment-slack S] [--drive-accept-threshold C] [--diagnose] [--json FILE]

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <boost/program_options.hpp>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>

#include "mrs_vpr/descriptor.hpp"
#include "mrs_vpr/descriptor_sequence.hpp"
#include "mrs_vpr/evaluation/evaluation.hpp"
#include "mrs_vpr/evaluation/image_folder.hpp"
#include "mrs_vpr/evaluation/progress_line.hpp"
#include "mrs_vpr/memory_reuse.hpp"
#include "mrs_vpr/acceptance.hpp"
#include "mrs_vpr/mrs/compact_cells.hpp"
#include "mrs_vpr/mrs/short_sequence_search.hpp"
#include "mrs_vpr/mrs_matcher.hpp"
#include "mrs_vpr/place_recognizer.hpp"
#include "mrs_vpr/sequence_matcher.hpp"
#include "tools/descriptor_options.hpp"
#include "tools/tool_main.hpp"
#include "camera_drive_rows.hpp"
#include "list_option.hpp"

namespace po = boost::program_options;

namespace {

using mrs_vpr::DescriptorSequence;
using mrs_vpr::QueryRecord;

struct Options {
  std::string data;
  std::string part = "check";
  int queries = 100;
  std::vector<int> lengths = {100, 200, 300};
  std::vector<std::string> references = {"1.8k", "9k"};
  int threads = 1;
  int tolerance = 5;
  std::uint64_t seed = 42;
  bool per_frame = true;
  bool global = true;
  bool drives = true;
  int drive_length = 0;
  int drive_alignment_slack = mrs_vpr::SequenceParams{}.alignment_slack;
  double drive_accept_threshold = mrs_vpr::SequenceParams{}.accept_threshold;
  double drive_min_appearance_change = mrs_vpr::RecognizerParams{}.min_appearance_change;
  std::string drive_alignment = mrs_vpr::toString(mrs_vpr::SequenceParams{}.alignment);
  std::string drive_queries = "each";  // as the node asks
  int drive_seeds = 1;                 // drives of seeds seed .. seed + drive_seeds - 1
  bool diagnose = false;
  std::string json;  ///< Every row of the tables also goes to this file (for mrs_vpr_plot benchmark).
  int hypotheses = mrs_vpr::MrsParams{}.hypotheses;
  int min_coarse_frames = mrs_vpr::MrsParams{}.min_coarse_frames;
  double velocity_min = mrs_vpr::SequenceParams{}.velocity_min;
  double velocity_max = mrs_vpr::SequenceParams{}.velocity_max;
  std::vector<std::string> methods = {"seqslam", "mrs"};
  mrs_vpr::DescriptorParams descriptor;
};

constexpr const char* kUsage =
    "Usage: mrs_vpr_real_benchmark --data DIR [--part tune|check|all] [--queries K] [--lengths 100,200,300]\n"
    "                              [--references 1.8k,9k] [--threads T] [--tolerance T] [--seed S]\n"
    "                              [--skip-per-frame] [--skip-global] [--skip-drives] [--drive-length L]\n"
    "                              [--drive-alignment-slack S] [--drive-accept-threshold C]\n"
    "                              [--drive-alignment causal|centred]\n"
    "                              [--drive-queries newest|each] [--drive-seeds K] [--diagnose]\n"
    "                              [--hypotheses K] [--min-coarse-frames F]   (mrs settings to explore)\n"
    "                              [--velocity-min V] [--velocity-max V]      (speeds to explore)\n"
    "                              [--methods seqslam,mrs,mrs-first-pass] [--json FILE]\n"
    "                              [--descriptor hog|thumbnail] [front-end options]\n"
    "\n"
    "Both methods on the same queries of real frames: Nordland winter against summer references of\n"
    "about 1.8k frames and 9k (with real distractors), known ground and out of the map, global and\n"
    "per-frame. DIR holds nordland/{summer,winter} and corridor/{ref,query}. mrs-first-pass is MRS's search\n"
    "for short sequences on large maps (mrs/short_sequence_search.hpp) on every map, whatever its size.\n";

/// Parses the command line; returns nothing after printing the help.
std::optional<Options> parse(int argc, char** argv) {
  Options options;
  std::int64_t seed = static_cast<std::int64_t>(options.seed);  // Signed, so that a negative seed is refused.
  bool skip_per_frame = false;
  bool skip_global = false;
  bool skip_drives = false;
  po::options_description description("Options");
  // clang-format off
  description.add_options()
      ("help,h", "print this help")
      ("data", po::value(&options.data)->required(), "the folder with nordland/ and corridor/")
      ("part", po::value(&options.part)->default_value(options.part),
       "tune (first half of the route) | check (second half) | all: the part whose queries are reported")
      ("queries", po::value(&options.queries)->default_value(options.queries), "K: test sequences of each global row")
      ("lengths", mrs_vpr::benchmark::listValue(&options.lengths), "N of the global rows, comma-separated")
      ("references", mrs_vpr::benchmark::listValue(&options.references), "1.8k and/or 9k, comma-separated")
      ("threads", po::value(&options.threads)->default_value(options.threads), "threads of both methods")
      ("tolerance", po::value(&options.tolerance)->default_value(options.tolerance),
       "frames of error still counted correct (global rows)")
      ("seed", po::value(&seed)->default_value(seed), "seed of the global query positions")
      ("skip-per-frame", po::bool_switch(&skip_per_frame), "no per-frame rows")
      ("skip-global", po::bool_switch(&skip_global), "no global rows")
      ("skip-drives", po::bool_switch(&skip_drives), "no camera-drive rows")
      ("drive-length", po::value(&options.drive_length)->default_value(options.drive_length),
       "keyframes per test sequence of the camera-drive rows; 0 = the node's default")
      ("drive-alignment-slack", po::value(&options.drive_alignment_slack)->default_value(options.drive_alignment_slack),
       "sequence/alignment_slack of the camera-drive rows")
      ("drive-accept-threshold",
       po::value(&options.drive_accept_threshold)->default_value(options.drive_accept_threshold),
       "sequence/accept_threshold of the camera-drive rows (the confidence an accepted answer needs)")
      ("drive-min-appearance-change",
       po::value(&options.drive_min_appearance_change)->default_value(options.drive_min_appearance_change),
       "min_appearance_change of the camera-drive rows (keyframes by appearance change)")
      ("drive-alignment", po::value(&options.drive_alignment)->default_value(options.drive_alignment),
       "sequence/alignment of the camera-drive rows: the keyframe an answer localises")
      ("drive-queries", po::value(&options.drive_queries)->default_value(options.drive_queries),
       "each | newest: continuous mode localises each keyframe since its last question (the node), or only the "
       "newest")
      ("drive-seeds", po::value(&options.drive_seeds)->default_value(options.drive_seeds),
       "camera drives of seeds S .. S + K - 1 (map drive seed s, revisit s + 1), then a summary over them")
      ("diagnose", po::bool_switch(&options.diagnose), "print where MRS kept the truth, level by level")
      ("hypotheses", po::value(&options.hypotheses)->default_value(options.hypotheses),
       "mrs: hypotheses carried down from the coarsest level")
      ("min-coarse-frames", po::value(&options.min_coarse_frames)->default_value(options.min_coarse_frames),
       "mrs: fewest rows of a coarse level")
      ("velocity-min", po::value(&options.velocity_min)->default_value(options.velocity_min),
       "slowest reference frames per query frame, every row")
      ("velocity-max", po::value(&options.velocity_max)->default_value(options.velocity_max),
       "fastest reference frames per query frame, every row")
      ("methods", mrs_vpr::benchmark::listValue(&options.methods), "seqslam and/or mrs, comma-separated")
      ("json", po::value(&options.json), "also write every row to this JSON file (for mrs_vpr_plot benchmark)");
  // clang-format on
  mrs_vpr::tools::addDescriptorOptions(description, options.descriptor);
  po::variables_map variables;
  if (!mrs_vpr::tools::parseCommandLine(argc, argv, kUsage, description, variables)) return std::nullopt;
  options.per_frame = !skip_per_frame;
  options.global = !skip_global;
  options.drives = !skip_drives;
  if (seed < 0) throw std::invalid_argument("--seed must be >= 0");
  options.seed = static_cast<std::uint64_t>(seed);
  if (options.part != "tune" && options.part != "check" && options.part != "all") {
    throw std::invalid_argument("--part must be tune, check or all");
  }
  mrs_vpr::SequenceParams drive_sequence;  // Checked now, not after the frames are read.
  drive_sequence.accept_threshold = options.drive_accept_threshold;
  drive_sequence.validate();
  if (options.queries < 1 || options.threads < 1 || options.tolerance < 0) {
    throw std::invalid_argument("--queries and --threads must be >= 1, --tolerance >= 0");
  }
  for (const int length : options.lengths) {
    if (length < 2) throw std::invalid_argument("--lengths takes sequence lengths >= 2");
  }
  for (const std::string& size : options.references) {
    if (size != "1.8k" && size != "9k") throw std::invalid_argument("--references takes 1.8k and/or 9k");
  }
  for (const std::string& method : options.methods) {
    if (method != "mrs" && method != "seqslam" && method != "mrs-first-pass") {
      throw std::invalid_argument("--methods: unknown method '" + method +
                                  "' (expected seqslam, mrs or mrs-first-pass)");
    }
  }
  return options;
}

/// MRS's search for short sequences (a first pass on compact cells at every end, the full descriptors
/// at its distinct minima) on any map, where MrsMatcher takes it only on maps large enough for it to
/// pay: its answers, confidences and acceptance can be compared with the brute force's on real frames.
class FirstPassMatcher : public mrs_vpr::SequenceMatcher {
 public:
  explicit FirstPassMatcher(const mrs_vpr::Parameters& params)
      : SequenceMatcher(params.sequence), compact_(mrs_vpr::makeCompactCells(params.descriptor)) {}

  mrs_vpr::Match match(mrs_vpr::SequenceView reference, mrs_vpr::SequenceView query) const override {
    return match(reference, query, nullptr);
  }
  /// The same, with the first pass traced into `trace` (one level, stride 1) when not null.
  mrs_vpr::Match match(mrs_vpr::SequenceView reference, mrs_vpr::SequenceView query,
                       std::vector<mrs_vpr::MrsLevelTrace>* trace) const {
    checkInputs(reference, query);
    mrs_vpr::MrsLevelTrace level;
    mrs_vpr::Match match = mrs_vpr::searchShortSequence(reference, query, sequence_, *compact_,
                                                        mrs_vpr::kShortSearchHypotheses, &level);
    if (trace != nullptr) trace->push_back(level);
    placeAnswer(match, reference, query, mrs_vpr::wholeSequenceRows(query.count, sequence_.alignment));
    mrs_vpr::applyAcceptance(match, sequence_);
    return match;
  }
  std::string name() const override { return "mrs-first-pass"; }

 private:
  std::shared_ptr<const mrs_vpr::CompactCells> compact_;
};

std::unique_ptr<mrs_vpr::SequenceMatcher> makeBenchMatcher(const std::string& method, const mrs_vpr::Parameters& params) {
  if (method == "mrs-first-pass") return std::make_unique<FirstPassMatcher>(params);
  return mrs_vpr::makeMatcher(method, params);
}

/// The images of a folder, as loaded (BGR or grayscale).
std::vector<cv::Mat> images(const std::string& folder) { return mrs_vpr::loadImageFolder(folder); }

cv::Mat mirrored(const cv::Mat& image) {
  cv::Mat flipped;
  cv::flip(image, flipped, 1);
  return flipped;
}

/// Real frames of the route and of the corridor, described once.
struct RealFrames {
  std::vector<cv::Mat> summer;
  std::vector<cv::Mat> winter;
  std::vector<cv::Mat> corridor;
};

/// A reference: descriptors, and for each of its frames the route frame it shows (-1 for distractors).
struct Reference {
  std::string name;
  DescriptorSequence descriptors;
  std::vector<int> route_frame;
};

/// Appends frames [begin, end) of `frames` (optionally mirrored, optionally backwards) as distractors.
void appendFrames(Reference& reference, const mrs_vpr::DescriptorExtractor& extractor, const std::vector<cv::Mat>& frames,
                  int begin, int end, bool mirror, bool backwards, bool true_place, mrs_vpr::ProgressLine& progress) {
  for (int i = 0; i < end - begin; ++i) {
    const int frame = backwards ? end - 1 - i : begin + i;
    const cv::Mat& image = frames[static_cast<std::size_t>(frame)];
    reference.descriptors.append(extractor.compute(mirror ? mirrored(image) : image));
    reference.route_frame.push_back(true_place ? frame : -1);
    progress.update(static_cast<long long>(reference.route_frame.size()));
  }
}

/// The summer frames [begin, end) as true places, then (for "9k") real distractors derived from the
/// same frames and from the corridor set.
Reference buildReference(const RealFrames& frames, const mrs_vpr::DescriptorExtractor& extractor, int begin, int end,
                         bool distractors, const std::string& name) {
  Reference reference{name, DescriptorSequence(extractor.size()), {}};
  const int corridor = static_cast<int>(frames.corridor.size());
  mrs_vpr::ProgressLine progress = mrs_vpr::ProgressLine::onStderr(
      "reference " + name, "frames", distractors ? 5LL * (end - begin) + corridor : end - begin);
  appendFrames(reference, extractor, frames.summer, begin, end, false, false, true, progress);
  if (distractors) {
    appendFrames(reference, extractor, frames.summer, begin, end, true, false, false, progress);
    appendFrames(reference, extractor, frames.winter, begin, end, true, false, false, progress);
    appendFrames(reference, extractor, frames.summer, begin, end, false, true, false, progress);
    appendFrames(reference, extractor, frames.winter, begin, end, true, true, false, progress);
    appendFrames(reference, extractor, frames.corridor, 0, corridor, false, false, false, progress);
  }
  progress.finish();
  return reference;
}

DescriptorSequence describe(const std::vector<cv::Mat>& frames, const mrs_vpr::DescriptorExtractor& extractor) {
  DescriptorSequence sequence(extractor.size());
  for (const cv::Mat& image : frames) sequence.append(extractor.compute(image));
  return sequence;
}

/// The reference index showing route frame `frame`, or -1 (out of map).
std::vector<int> truthOf(const Reference& reference, int frame) {
  std::vector<int> truth;
  for (std::size_t j = 0; j < reference.route_frame.size(); ++j) {
    if (reference.route_frame[j] == frame) truth.push_back(static_cast<int>(j));
  }
  return truth;
}

void printHeader() {
  std::printf("%-34s %-8s %7s %7s %7s %7s %9s %8s %8s %10s\n", "setting", "method", "queries", "success", "R@100P",
              "PR-AUC", "accepted", "acc.P", "acc.R", "median ms");
}

/// What a row of the tables measured, for the JSON output.
struct RowFacts {
  std::string protocol;  ///< "global" or "per-frame".
  bool out_of_map = false;
  int reference_frames = 0;
  int sequence_length = 0;
};

/// The tables: printed as they are measured, and kept for --json.
class Report {
 public:
  void row(const std::string& setting, const std::string& method, const mrs_vpr::EvaluationSummary& s,
           const RowFacts& facts) {
    std::printf("%-34s %-8s %7d %7.3f %7.3f %7.3f %9d %8.3f %8.3f %10.3f\n", setting.c_str(), method.c_str(), s.queries,
                s.top1, s.recall_at_100_precision, s.pr_auc, s.accepted, s.accepted_precision, s.accepted_recall,
                s.median_time_ms);
    std::fflush(stdout);
    // NaN (nothing accepted, nothing predicted) has no JSON spelling: null.
    const auto number = [](double value) { return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(); };
    rows_.push_back({{"setting", setting},
                     {"method", method},
                     {"protocol", facts.protocol},
                     {"out_of_map", facts.out_of_map},
                     {"reference_frames", facts.reference_frames},
                     {"sequence_length", facts.sequence_length},
                     {"summary",
                      {{"queries", s.queries},
                       {"top1", s.top1},
                       {"recall_at_100_precision", s.recall_at_100_precision},
                       {"pr_auc", s.pr_auc},
                       {"accepted", s.accepted},
                       {"accepted_precision", number(s.accepted_precision)},
                       {"accepted_recall", s.accepted_recall},
                       {"largest_wrong_accepted_error", number(s.largest_wrong_accepted_error)},
                       {"median_time_ms", number(s.median_time_ms)}}}});
  }

  /// Rows of another shape (printed by their maker), for the JSON output only.
  void add(const std::vector<nlohmann::json>& rows) { rows_.insert(rows_.end(), rows.begin(), rows.end()); }

  void write(const Options& options) const {
    if (options.json.empty()) return;
    const nlohmann::json document = {{"part", options.part}, {"threads", options.threads},
                                     {"tolerance", options.tolerance}, {"queries", options.queries},
                                     {"seed", options.seed}, {"rows", rows_}};
    std::ofstream file(options.json);
    file << document.dump(2) << "\n";
    if (!file) throw std::runtime_error("cannot write '" + options.json + "'");
    std::fprintf(stderr, "wrote %s\n", options.json.c_str());
  }

 private:
  std::vector<nlohmann::json> rows_;
};

/// Where MRS kept the truth: per level, how often a hypothesis lay within tolerance of it and at
/// which rank; for the coarsest level also the rank among the distinct minima of its table.
class Diagnosis {
 public:
  void add(const std::vector<mrs_vpr::MrsLevelTrace>& trace, const std::vector<int>& truth, int tolerance,
           double accept_threshold) {
    if (levels_.size() < trace.size()) levels_.resize(trace.size());
    for (std::size_t l = 0; l < trace.size(); ++l) {
      LevelCounts& counts = levels_[l];
      counts.stride = trace[l].stride;
      ++counts.queries;
      const int rank = rankOf(trace[l].candidates, truth, tolerance + trace[l].stride);
      counts.ranks[rank]++;
      if (l == 0) {
        const int table_rank = rankOf(trace[l].table_minima, truth, tolerance + trace[l].stride);
        counts.table_ranks[table_rank]++;
        // The coarse table alone would have accepted a wrong place: the finer levels had to catch it.
        if (table_rank != 1 && trace[l].table_confidence >= accept_threshold) ++confidently_wrong_;
      }
    }
  }

  void print(const std::string& setting) const {
    std::printf("  diagnose %-24s coarse table's lowest minimum wrong at an accepted confidence: %d queries\n",
                setting.c_str(), confidently_wrong_);
    for (const LevelCounts& counts : levels_) {
      std::printf("  diagnose %-24s stride %2d: truth among hypotheses at rank", setting.c_str(), counts.stride);
      printRanks(counts.ranks, counts.queries);
      if (!counts.table_ranks.empty()) {
        std::printf("  diagnose %-24s stride %2d: truth among the table's distinct minima at rank", setting.c_str(),
                    counts.stride);
        printRanks(counts.table_ranks, counts.queries);
      }
    }
  }

 private:
  struct LevelCounts {
    int stride = 1;
    int queries = 0;
    std::map<int, int> ranks;        ///< rank (1-based; 0 = lost) -> queries
    std::map<int, int> table_ranks;  ///< the same among the coarse table's minima
  };

  static int rankOf(const std::vector<int>& candidates, const std::vector<int>& truth, int tolerance) {
    for (std::size_t r = 0; r < candidates.size(); ++r) {
      for (int t : truth) {
        if (std::abs(candidates[r] - t) <= tolerance) return static_cast<int>(r) + 1;
      }
    }
    return 0;
  }

  static void printRanks(const std::map<int, int>& ranks, int queries) {
    int cumulative = 0;
    for (int top : {1, 2, 3, 5, 8, 20, 50}) {
      cumulative = 0;
      for (const auto& [rank, count] : ranks) {
        if (rank >= 1 && rank <= top) cumulative += count;
      }
      std::printf(" top%d %.2f", top, static_cast<double>(cumulative) / queries);
    }
    const auto lost = ranks.find(0);
    std::printf(" lost %.2f\n", lost == ranks.end() ? 0.0 : static_cast<double>(lost->second) / queries);
  }

  std::vector<LevelCounts> levels_;
  int confidently_wrong_ = 0;
};

/// One method's answers to the test sequences of `length` frames of `query` that end at `ends`, in
/// `map`; the sequence ending at frame e has the true places truth_of(e). With `diagnosis`, MRS's
/// levels are traced into it.
std::vector<QueryRecord> globalRecords(const mrs_vpr::SequenceMatcher& matcher, mrs_vpr::SequenceView map,
                                       const DescriptorSequence& query, const std::vector<int>& ends, int length,
                                       const std::function<std::vector<int>(int)>& truth_of, Diagnosis* diagnosis,
                                       int tolerance, double accept_threshold) {
  std::vector<QueryRecord> records;
  const auto* mrs = dynamic_cast<const mrs_vpr::MrsMatcher*>(&matcher);
  const auto* first_pass = dynamic_cast<const FirstPassMatcher*>(&matcher);
  for (int end : ends) {
    const mrs_vpr::SequenceView test = query.view(end - length + 1, end + 1);
    std::vector<mrs_vpr::MrsLevelTrace> trace;
    const auto start = std::chrono::steady_clock::now();
    const mrs_vpr::Match match = diagnosis == nullptr ? matcher.match(map, test)
                                 : mrs != nullptr     ? mrs->match(map, test, &trace)
                                 : first_pass != nullptr ? first_pass->match(map, test, &trace)
                                                         : matcher.match(map, test);
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    const QueryRecord& record = records.emplace_back(mrs_vpr::queryRecordOf(end, truth_of(end), match, ms));
    if (diagnosis != nullptr) diagnosis->add(trace, record.true_indices, tolerance, accept_threshold);
  }
  return records;
}

/// Runs one method on test sequences ending at the given frames of the route, in `reference`.
std::vector<QueryRecord> runGlobal(const mrs_vpr::SequenceMatcher& matcher, const Reference& reference,
                                   const DescriptorSequence& query, const std::vector<int>& ends, int length,
                                   bool out_of_map, Diagnosis* diagnosis, int tolerance, double accept_threshold) {
  const auto records = globalRecords(
      matcher, reference.descriptors.view(), query, ends, length,
      [&](int end) { return out_of_map ? std::vector<int>{} : truthOf(reference, end); },
      out_of_map ? nullptr : diagnosis, tolerance, accept_threshold);
  if (out_of_map && std::getenv("MRS_VPR_SHOW_FALSE") != nullptr) {
    for (const QueryRecord& record : records) {
      if (!record.accepted) continue;
      std::fprintf(stderr, "false closure: %s N=%d query end %d -> reference %d (route frame %d), confidence %.2f\n",
                   matcher.name().c_str(), length, record.query_index, record.predicted_index,
                   reference.route_frame[static_cast<std::size_t>(record.predicted_index)], record.confidence);
    }
  }
  return records;
}

/// `params` for the per-frame rows: sequences of `length` frames at OpenSeqSLAM's velocity step 0.1,
/// enough for short sequences.
mrs_vpr::Parameters perFrameParams(const mrs_vpr::Parameters& params, int length) {
  mrs_vpr::Parameters per_frame = params;
  per_frame.sequence.sequence_length = length;
  per_frame.sequence.velocity_step = 0.1;
  return per_frame;
}

/// The answers to every frame of `query` with a full sequence, in `map`; frame i's true places are
/// `truth_of(i)`.
std::vector<QueryRecord> perFrameRecords(const mrs_vpr::SequenceMatcher& matcher, mrs_vpr::SequenceView map,
                                         mrs_vpr::SequenceView query,
                                         const std::function<std::vector<int>(int)>& truth_of) {
  const auto start = std::chrono::steady_clock::now();
  const std::vector<mrs_vpr::Match> matches = matcher.matchEveryFrame(map, query);
  const double total_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  std::vector<QueryRecord> records;
  for (int i = 0; i < query.count; ++i) {
    const mrs_vpr::Match& match = matches[static_cast<std::size_t>(i)];
    if (match.reference_index < 0 && match.comparisons == 0) continue;  // No full sequence.
    records.push_back(mrs_vpr::queryRecordOf(i, truth_of(i), match, total_ms / query.count));
  }
  return records;
}

std::vector<QueryRecord> runPerFrame(const mrs_vpr::SequenceMatcher& matcher, const Reference& reference,
                                     const DescriptorSequence& query, int first, int last, bool out_of_map) {
  auto records = perFrameRecords(matcher, reference.descriptors.view(), query.view(first, last), [&](int i) {
    return out_of_map ? std::vector<int>{} : truthOf(reference, first + i);
  });
  for (QueryRecord& record : records) record.query_index += first;
  return records;
}

/// Summer frames [begin, end) as a map of their own, each the true place of its route frame.
Reference stretchOf(const DescriptorSequence& summer, int begin, int end) {
  Reference stretch{"stretch", DescriptorSequence(summer.descriptorSize()), {}};
  for (int frame = begin; frame < end; ++frame) {
    stretch.descriptors.append(summer.descriptorRow(frame));
    stretch.route_frame.push_back(frame);
  }
  return stretch;
}

/// Out-of-map queries from another world: the corridor's frames against a map of the Nordland summer
/// frames, and Nordland winter frames of the reported part against a map of the corridor.
void runOtherWorld(const RealFrames& frames, const DescriptorSequence& summer, const DescriptorSequence& winter,
                   const mrs_vpr::DescriptorExtractor& extractor, const mrs_vpr::Parameters& params,
                   const Options& options, int part_begin, int part_end, Report& report) {
  const Reference nordland = stretchOf(summer, 0, summer.size());
  Reference corridor{"corridor", describe(frames.corridor, extractor), {}};
  corridor.route_frame.assign(static_cast<std::size_t>(corridor.descriptors.size()), -1);
  for (int length : {10, 50}) {
    const mrs_vpr::Parameters per_frame = perFrameParams(params, length);
    for (const std::string& method : options.methods) {
      const auto matcher = makeBenchMatcher(method, per_frame);
      const int corridor_frames = corridor.descriptors.size();
      report.row("corridor in Nordland map ds=" + std::to_string(length), method,
                 mrs_vpr::summarise(runPerFrame(*matcher, nordland, corridor.descriptors, 0, corridor_frames, true), 2),
                 {"per-frame", true, nordland.descriptors.size(), length});
      report.row("Nordland in corridor map ds=" + std::to_string(length), method,
                 mrs_vpr::summarise(runPerFrame(*matcher, corridor, winter, part_begin, part_end, true), 2),
                 {"per-frame", true, corridor_frames, length});
    }
  }
}

/// Maps of a few to a few hundred frames: kStretches stretches of the summer frames of each size.
/// Known ground: stretches of the reported part, queried by the same stretch's winter frames. Out of
/// the map: stretches of the other part, queried by the whole reported part.
void runSmallMaps(const DescriptorSequence& summer, const DescriptorSequence& winter, const mrs_vpr::Parameters& params,
                  const Options& options, int part_begin, int part_end, int other_begin, int other_end,
                  bool out_of_map, Report& report) {
  constexpr int kStretches = 3;
  const auto stretchBegin = [](int low, int high, int size, int i) {
    return low + i * (high - low - size) / (kStretches - 1);
  };
  for (int length : {10, 50}) {
    const mrs_vpr::Parameters per_frame = perFrameParams(params, length);
    for (int size : {20, 50, 100, 150, 200, 300}) {
      if (size <= length) continue;
      const std::string setting = " M=" + std::to_string(size) + " ds=" + std::to_string(length);
      for (const std::string& method : options.methods) {
        const auto matcher = makeBenchMatcher(method, per_frame);
        std::vector<QueryRecord> known;
        std::vector<QueryRecord> unknown;
        for (int i = 0; i < kStretches; ++i) {
          const int begin = stretchBegin(part_begin, part_end, size, i);
          const auto records =
              runPerFrame(*matcher, stretchOf(summer, begin, begin + size), winter, begin, begin + size, false);
          known.insert(known.end(), records.begin(), records.end());
          if (!out_of_map) continue;
          const int other = stretchBegin(other_begin, other_end, size, i);
          const auto wrong =
              runPerFrame(*matcher, stretchOf(summer, other, other + size), winter, part_begin, part_end, true);
          unknown.insert(unknown.end(), wrong.begin(), wrong.end());
        }
        report.row("small maps" + setting, method, mrs_vpr::summarise(known, 2), {"per-frame", false, size, length});
        if (!out_of_map) continue;
        report.row("out-of-map small maps" + setting, method, mrs_vpr::summarise(unknown, 2),
                   {"per-frame", true, size, length});
      }
    }
  }
}

/// Seeded ends of test sequences of `length` frames that lie wholly inside frames [low, high], so that
/// out-of-map queries share no frame with the other part's reference.
std::vector<int> queryEnds(int low, int high, int length, int count, std::uint64_t seed) {
  const int first_end = low + length - 1;
  const std::vector<mrs_vpr::TestSequence> tests =
      mrs_vpr::globalQueries(high - first_end + 1, 1, count, seed);  // Positions in [0, span).
  std::vector<int> ends;
  for (const mrs_vpr::TestSequence& test : tests) ends.push_back(first_end + test.start);
  return ends;
}

/// The reported part's winter frames replayed at speeds the route was not driven at, against the
/// summer frames of the whole route: backwards, at twice the speed (every other frame), at half
/// (every frame twice), and stopping for kStopFrames frames (one second at 30 Hz) after every
/// kStopEvery. Every place is in the map, but the default velocities (0.8 to 1.2 map frames a query
/// frame) fit none of these, or a stop only in part. Per-frame rows at ds = 10 and 50, global rows
/// at the benchmark's lengths, scored against the true places: an accepted answer must still be right.
void runReplays(const DescriptorSequence& summer, const DescriptorSequence& winter, const mrs_vpr::Parameters& params,
                const Options& options, int part_begin, int part_end, Report& report) {
  struct Replay {
    std::string name;
    std::vector<int> frames;  ///< The winter frame of each replayed frame.
  };
  constexpr int kStopEvery = 100;
  constexpr int kStopFrames = 30;
  std::vector<Replay> replays{
      {"backwards", {}}, {"at twice the speed", {}}, {"at half the speed", {}}, {"with stops", {}}};
  for (int frame = part_end - 1; frame >= part_begin; --frame) replays[0].frames.push_back(frame);
  for (int frame = part_begin; frame < part_end; frame += 2) replays[1].frames.push_back(frame);
  for (int frame = part_begin; frame < part_end; ++frame) {
    replays[2].frames.insert(replays[2].frames.end(), 2, frame);
    const bool stop = (frame - part_begin) % kStopEvery == kStopEvery - 1;
    replays[3].frames.insert(replays[3].frames.end(), stop ? 1 + kStopFrames : 1, frame);
  }
  for (const Replay& replay : replays) {
    DescriptorSequence query(winter.descriptorSize());
    for (const int frame : replay.frames) query.append(winter.descriptorRow(frame));
    const auto truth_of = [&](int i) { return std::vector<int>{replay.frames[static_cast<std::size_t>(i)]}; };
    // Global queries, as a robot's ~query of N frames: the same seeded ends for both methods.
    for (int length : options.global ? options.lengths : std::vector<int>{}) {
      const std::vector<int> ends = queryEnds(0, query.size() - 1, length, options.queries, options.seed);
      for (const std::string& method : options.methods) {
        const auto matcher = makeBenchMatcher(method, params);
        const auto records = globalRecords(*matcher, summer.view(), query, ends, length, truth_of, nullptr,
                                           options.tolerance, params.sequence.accept_threshold);
        report.row("global winter " + replay.name + " N=" + std::to_string(length) + " M=" +
                       std::to_string(summer.size()),
                   method, mrs_vpr::summarise(records, options.tolerance), {"global", false, summer.size(), length});
      }
    }
    for (int length : options.per_frame ? std::vector<int>{10, 50} : std::vector<int>{}) {
      const mrs_vpr::Parameters per_frame = perFrameParams(params, length);
      for (const std::string& method : options.methods) {
        const auto matcher = makeBenchMatcher(method, per_frame);
        const auto records = perFrameRecords(*matcher, summer.view(), query.view(), truth_of);
        report.row("winter " + replay.name + " M=" + std::to_string(summer.size()) + " ds=" + std::to_string(length),
                   method, mrs_vpr::summarise(records, 2), {"per-frame", false, summer.size(), length});
      }
    }
  }
}

/// The node's continuous mode on one traversal: a robot drives the whole route in summer, then the
/// reported part again in winter, and after every frame asks where its newest `length` frames lie
/// among the older ones (PlaceRecognizer::matchRecent, the node's default recent_exclusion). On the
/// first traversal no place comes back, so every accepted answer is a false loop closure; on the
/// second, the summer frame of the same place is the truth. The map starts empty and grows.
void runContinuous(const DescriptorSequence& summer, const DescriptorSequence& winter,
                   const mrs_vpr::Parameters& params, const Options& options, int part_begin, int part_end,
                   Report& report) {
  constexpr int kLength = 10;  // The node's auto_query_frames default: sequence/sequence_length.
  const mrs_vpr::Parameters continuous = perFrameParams(params, kLength);
  const int route = summer.size();
  for (const std::string& method : options.methods) {
    if (method == "mrs-first-pass") continue;  // Not a method of PlaceRecognizer, whose mrs takes it where it pays.
    mrs_vpr::PlaceRecognizer recognizer(continuous);
    const int first_query = 2 * kLength + recognizer.recognizerParameters().recent_exclusion;
    std::vector<QueryRecord> first_traversal;
    std::vector<QueryRecord> revisit;
    const int frames = route + part_end - part_begin;
    for (int t = 0; t < frames; ++t) {
      const bool second = t >= route;
      const int route_frame = second ? part_begin + t - route : t;
      recognizer.addDescriptor((second ? winter : summer).descriptorRow(route_frame));
      if (t + 1 < first_query) continue;
      const auto start = std::chrono::steady_clock::now();
      const mrs_vpr::Match match = recognizer.matchRecent(kLength, method).match;
      const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
      // The summer frame of a place has the place's route index in the map.
      (second ? revisit : first_traversal)
          .push_back(mrs_vpr::queryRecordOf(t, second ? std::vector<int>{route_frame} : std::vector<int>{}, match, ms));
    }
    report.row("continuous, first traversal ds=10", method, mrs_vpr::summarise(first_traversal, 2),
               {"continuous", true, route, kLength});
    report.row("continuous, revisit in winter ds=10", method, mrs_vpr::summarise(revisit, 2),
               {"continuous", false, route, kLength});
  }
}

int run(int argc, char** argv) {
  const std::optional<Options> parsed = parse(argc, argv);
  if (!parsed) return 0;
  const Options& options = *parsed;
  cv::setNumThreads(options.threads);
  mrs_vpr::Parameters params;
  params.descriptor = options.descriptor;
  // Velocity step 0.02 for both methods: 0.1 leaves up to 15 frames of drift at N = 300, so neither
  // could align long sequences whose speed lies between two steps.
  params.sequence.velocity_step = 0.02;
  // The global and per-frame rows judge where a test sequence ends, as the paper does; the drive rows
  // localise what the node localises (--drive-alignment).
  params.sequence.alignment = mrs_vpr::WindowAlignment::kCausal;
  params.mrs.hypotheses = options.hypotheses;
  params.mrs.min_coarse_frames = options.min_coarse_frames;
  params.sequence.velocity_min = options.velocity_min;
  params.sequence.velocity_max = options.velocity_max;
  params.validate();
  const mrs_vpr::DescriptorExtractor extractor(params.descriptor);

  std::fprintf(stderr, "reading %s ...\n", options.data.c_str());
  RealFrames frames;
  frames.summer = images(options.data + "/nordland/summer");
  frames.winter = images(options.data + "/nordland/winter");
  frames.corridor = images(options.data + "/corridor/ref");
  for (const cv::Mat& image : images(options.data + "/corridor/query")) frames.corridor.push_back(image);
  const int route = static_cast<int>(std::min(frames.summer.size(), frames.winter.size()));
  const int half = route / 2;
  const DescriptorSequence winter = describe(frames.winter, extractor);

  // The part whose queries are reported; out-of-map references come from the other part. The whole
  // route (--part all) leaves no other part: then there are no out-of-map rows.
  const bool out_of_map = options.part != "all";
  const int part_begin = options.part == "check" ? half : 0;
  const int part_end = options.part == "tune" ? half : route;
  const int other_begin = options.part == "check" ? 0 : half;
  const int other_end = options.part == "check" ? half : route;

  std::printf("Real-data benchmark: Nordland summer (reference) / winter (query), corridor; part '%s' "
              "(route frames %d..%d of %d), front end %s, threads %d, tolerance %d, velocities %.2f..%.2f step %.2f, "
              "seed %llu\n",
              options.part.c_str(), part_begin, part_end - 1, route, params.descriptor.describe().c_str(),
              options.threads, options.tolerance,
              params.sequence.velocity_min, params.sequence.velocity_max, params.sequence.velocity_step,
              static_cast<unsigned long long>(options.seed));
  std::printf("success = top-1 within tolerance; accepted = the core's acceptance rule at its default (%.1f)\n\n",
              params.sequence.accept_threshold);
  if (!out_of_map) std::printf("no out-of-map rows: --part all leaves no part of the route outside the map\n\n");
  printHeader();
  Report report;

  std::vector<std::unique_ptr<mrs_vpr::SequenceMatcher>> matchers;
  for (const std::string& method : options.methods) matchers.push_back(makeBenchMatcher(method, params));
  for (const std::string& size : options.references) {
    const bool distractors = size == "9k";
    Reference known = buildReference(frames, extractor, 0, route, distractors, size);
    known.descriptors.keepCoarseCells(params.mrs.levels, params.descriptor);
    // The out-of-map reference: the other part of the route (with its own distractors), so that no
    // query frame of this part is in it.
    Reference unknown = buildReference(frames, extractor, other_begin, other_end, distractors, size + "-other");
    unknown.descriptors.keepCoarseCells(params.mrs.levels, params.descriptor);
    const std::string m = " M=" + std::to_string(known.descriptors.size());
    const std::string m_other = " M=" + std::to_string(unknown.descriptors.size());

    if (options.global) {
      for (int length : options.lengths) {
        const std::vector<int> ends = queryEnds(part_begin, part_end - 1, length, options.queries, options.seed);
        std::map<std::string, Diagnosis> diagnoses;  // One per traced method.
        for (const auto& matcher : matchers) {
          const bool diagnose = options.diagnose && matcher->name() != "seqslam";
          const auto records = runGlobal(*matcher, known, winter, ends, length, false,
                                         diagnose ? &diagnoses[matcher->name()] : nullptr, options.tolerance,
                                         params.sequence.accept_threshold);
          report.row("global N=" + std::to_string(length) + m, matcher->name(),
                     mrs_vpr::summarise(records, options.tolerance),
                     {"global", false, known.descriptors.size(), length});
        }
        for (const auto& [name, diagnosis] : diagnoses) {
          diagnosis.print("N=" + std::to_string(length) + m + (name == "mrs" ? "" : " " + name));
        }
        for (const auto& matcher : matchers) {
          if (!out_of_map) break;
          const auto records = runGlobal(*matcher, unknown, winter, ends, length, true, nullptr, options.tolerance,
                                         params.sequence.accept_threshold);
          report.row("out-of-map global N=" + std::to_string(length) + m_other, matcher->name(),
                     mrs_vpr::summarise(records, options.tolerance),
                     {"global", true, unknown.descriptors.size(), length});
        }
      }
    }
    if (options.per_frame) {
      for (int length : {10, 50}) {
        const mrs_vpr::Parameters per_frame = perFrameParams(params, length);
        for (const std::string& method : options.methods) {
          const auto matcher = makeBenchMatcher(method, per_frame);
          const auto known_records = runPerFrame(*matcher, known, winter, part_begin, part_end, false);
          report.row("per-frame ds=" + std::to_string(length) + m + " tol 2", method,
                     mrs_vpr::summarise(known_records, 2), {"per-frame", false, known.descriptors.size(), length});
          if (!out_of_map) continue;
          const auto unknown_records = runPerFrame(*matcher, unknown, winter, part_begin, part_end, true);
          report.row("out-of-map per-frame ds=" + std::to_string(length) + m_other, method,
                     mrs_vpr::summarise(unknown_records, 2), {"per-frame", true, unknown.descriptors.size(), length});
        }
      }
    }
  }
  const DescriptorSequence summer = describe(frames.summer, extractor);
  if (options.per_frame) {
    runOtherWorld(frames, summer, winter, extractor, params, options, part_begin, part_end, report);
    runSmallMaps(summer, winter, params, options, part_begin, part_end, other_begin, other_end, out_of_map, report);
  }
  runReplays(summer, winter, params, options, part_begin, part_end, report);
  if (options.per_frame) runContinuous(summer, winter, params, options, part_begin, part_end, report);
  if (options.drives) {
    mrs_vpr::benchmark::CameraDriveInput drives;
    drives.summer = &frames.summer;
    drives.winter = &frames.winter;
    drives.route_frames = route;
    drives.part_begin = part_begin;
    drives.part_end = part_end;
    drives.methods = options.methods;
    drives.descriptor = options.descriptor;
    if (options.drive_length > 0) drives.sequence.sequence_length = options.drive_length;
    drives.sequence.alignment_slack = options.drive_alignment_slack;
    drives.sequence.accept_threshold = options.drive_accept_threshold;
    drives.min_appearance_change = options.drive_min_appearance_change;
    drives.sequence.alignment = mrs_vpr::parseWindowAlignment(options.drive_alignment);
    if (options.drive_queries != "newest" && options.drive_queries != "each") {
      throw std::invalid_argument("--drive-queries must be newest or each, got '" + options.drive_queries + "'");
    }
    drives.each_keyframe = options.drive_queries == "each";
    drives.sequence.velocity_min = options.velocity_min;
    drives.sequence.velocity_max = options.velocity_max;
    if (options.drive_seeds < 1) {
      throw std::invalid_argument("--drive-seeds must be >= 1, got " + std::to_string(options.drive_seeds));
    }
    std::vector<nlohmann::json> continuous_rows;
    for (int k = 0; k < options.drive_seeds; ++k) {
      drives.seed = options.seed + static_cast<std::uint64_t>(k);
      mrs_vpr::benchmark::runCameraDrives(
          drives,
          [&](const std::vector<nlohmann::json>& rows) {
            for (nlohmann::json row : rows) {
              row["seed"] = drives.seed;
              continuous_rows.push_back(row);
              report.add({row});
            }
          },
          [&](const std::string& setting, const std::string& method, const mrs_vpr::EvaluationSummary& summary,
              int reference_frames, int sequence_length) {
            report.row(setting, method, summary, {"per-frame", false, reference_frames, sequence_length});
          });
    }
    if (options.drive_seeds > 1) mrs_vpr::benchmark::printDriveSeedSummary(continuous_rows);
  }
  report.write(options);
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  mrs_vpr::retainFreedMemory();  // As the node and the tools do.
  return mrs_vpr::tools::runTool("mrs_vpr_real_benchmark", run, argc, argv);
}

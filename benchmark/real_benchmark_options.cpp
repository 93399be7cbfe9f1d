#include "real_benchmark_options.hpp"

#include <stdexcept>
#include <string>

#include <boost/program_options.hpp>

#include "list_option.hpp"
#include "tools/descriptor_options.hpp"
#include "tools/double_option.hpp"
#include "tools/tool_main.hpp"

namespace po = boost::program_options;

namespace mrs_vpr {
namespace benchmark {
namespace {

constexpr const char* kUsage =
    "Usage: mrs_vpr_real_benchmark --data DIR [--part tune|check|all] [--queries K] [--lengths 100,200,300]\n"
    "                              [--per-frame-lengths 10,50] [--references 1.8k,9k] [--threads T] [--tolerance T] [--seed S]\n"
    "                              [--skip-per-frame] [--skip-global] [--skip-drives] [--drive-length L]\n"
    "                              [--drive-alignment-slack S] [--drive-accept-threshold C]\n"
    "                              [--drive-alignment causal|centred] [--drive-min-appearance-change M]\n"
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

}  // namespace

std::optional<RealBenchmarkOptions> parseRealBenchmarkOptions(int argc, char** argv) {
  RealBenchmarkOptions options;
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
      ("lengths", listValue(&options.lengths), "N of the global rows, comma-separated")
      ("per-frame-lengths", listValue(&options.per_frame_lengths), "ds of the per-frame rows, comma-separated")
      ("references", listValue(&options.references), "1.8k and/or 9k, comma-separated")
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
       tools::doubleOption(&options.drive_accept_threshold),
       "sequence/accept_threshold of the camera-drive rows (the confidence an accepted answer needs)")
      ("drive-min-appearance-change",
       tools::doubleOption(&options.drive_min_appearance_change),
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
      ("velocity-min", tools::doubleOption(&options.velocity_min),
       "slowest reference frames per query frame, every row")
      ("velocity-max", tools::doubleOption(&options.velocity_max),
       "fastest reference frames per query frame, every row")
      ("methods", listValue(&options.methods), "seqslam, mrs and/or mrs-first-pass, comma-separated")
      ("json", po::value(&options.json), "also write every row to this JSON file (for mrs_vpr_plot benchmark)");
  // clang-format on
  tools::addDescriptorOptions(description, options.descriptor);
  po::variables_map variables;
  if (!tools::parseCommandLine(argc, argv, kUsage, description, variables)) return std::nullopt;
  tools::refuseOtherFrontEndsOptions(variables, options.descriptor);
  options.per_frame = !skip_per_frame;
  options.global = !skip_global;
  options.drives = !skip_drives;
  if (seed < 0) throw std::invalid_argument("--seed must be >= 0");
  options.seed = static_cast<std::uint64_t>(seed);
  if (options.part != "tune" && options.part != "check" && options.part != "all") {
    throw std::invalid_argument("--part must be tune, check or all");
  }
  // The drive rows' settings are checked now, not after the frames are read.
  SequenceParams drive_sequence;
  drive_sequence.accept_threshold = options.drive_accept_threshold;
  drive_sequence.alignment_slack = options.drive_alignment_slack;
  if (options.drive_length > 0) drive_sequence.sequence_length = options.drive_length;
  drive_sequence.alignment = parseWindowAlignment(options.drive_alignment);
  drive_sequence.validate();
  if (options.drive_queries != "newest" && options.drive_queries != "each") {
    throw std::invalid_argument("--drive-queries must be newest or each, got '" + options.drive_queries + "'");
  }
  if (options.drive_seeds < 1) {
    throw std::invalid_argument("--drive-seeds must be >= 1, got " + std::to_string(options.drive_seeds));
  }
  if (options.queries < 1 || options.threads < 1 || options.tolerance < 0) {
    throw std::invalid_argument("--queries and --threads must be >= 1, --tolerance >= 0");
  }
  for (const int length : options.lengths) {
    if (length < 2) throw std::invalid_argument("--lengths takes sequence lengths >= 2");
  }
  for (const int length : options.per_frame_lengths) {
    if (length < 2) throw std::invalid_argument("--per-frame-lengths takes sequence lengths >= 2");
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

}  // namespace benchmark
}  // namespace mrs_vpr

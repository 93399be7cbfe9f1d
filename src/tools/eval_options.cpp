#include "eval_options.hpp"

#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>
#include <system_error>

#include <boost/program_options.hpp>

#include "apart_from_inputs.hpp"
#include "descriptor_options.hpp"
#include "double_option.hpp"
#include "mrs_vpr/node/bag_images.hpp"
#include "output_in_progress.hpp"
#include "tool_main.hpp"

namespace po = boost::program_options;

namespace mrs_vpr {
namespace tools {
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
    "plots of mrs_vpr_plot (PR curve, difference matrix and band, error along the route) into DIR;\n"
    "a picture or plot that an earlier run left there and this one does not make is removed.\n";

/**
 * Creates `folder` when missing and writes and removes a file in it, so that results that could not
 * be written are found before the evaluation rather than after it (permissions, a read-only file
 * system, a file in the way). Throws std::runtime_error naming `option`, the folder and the reason.
 */
void requireWritableFolder(const std::string& folder, const std::string& option) {
  requireParentFolder(option, folder);
  std::error_code error;
  const bool created = std::filesystem::create_directory(normalPath(folder), error);
  if (error) throw std::runtime_error(option + " '" + folder + "': cannot create the folder: " + error.message());
  // Made for the probe only: the results make it again, so that a run that fails leaves no empty folder.
  struct RemoveIfCreated {
    bool created;
    std::string folder;
    ~RemoveIfCreated() {
      std::error_code ignored;
      if (created) std::filesystem::remove(normalPath(folder), ignored);
    }
  } remove_after_probe{created, folder};
  std::string probe = (std::filesystem::path(folder) / ".mrs_vpr_eval_probe.XXXXXX").string();
  const int file = ::mkstemp(probe.data());
  if (file < 0) {
    throw std::runtime_error(option + " '" + folder + "': no file can be written in the folder: " +
                             std::strerror(errno));
  }
  ::close(file);
  std::filesystem::remove(probe, error);
}

}  // namespace

std::optional<EvalOptions> parseEvalOptions(int argc, char** argv) {
  EvalOptions options;
  Parameters& params = options.params;
  std::string alignment = toString(params.sequence.alignment);
  po::options_description description("Options");
  // clang-format off
  description.add_options()
      ("help,h", "print this help")
      ("reference", po::value(&options.reference)->required(),
       "reference traversal: image folder, .bag, or map database (.db) of the node or build_map")
      ("query", po::value(&options.query)->required(), "query traversal: image folder or .bag")
      ("topic", po::value(&options.topic), "image topic of the bags")
      ("ground-truth", po::value(&options.ground_truth), "CSV query_index,matching_ref_indices (default: identity)")
      ("method", po::value(&options.method)->default_value(RecognizerParams{}.default_method),
       "mrs | seqslam (default: the node's)")
      ("protocol", po::value(&options.protocol)->required(), "per-frame | global")
      ("sequence-length", po::value(&params.sequence.sequence_length)->default_value(params.sequence.sequence_length),
       "N: keyframes per test sequence (ds of the per-frame protocol; default: the node's continuous mode)")
      ("min-appearance-change", doubleOption(&options.min_appearance_change),
       "keyframes by appearance change, as the node's ~min_appearance_change (a map database's own where it "
       "records one); 0 = every frame")
      ("queries", po::value(&options.queries)->default_value(options.queries),
       "K: test sequences of the global protocol")
      ("tolerance", po::value(&options.tolerance)->default_value(options.tolerance),
       "frames of error still counted correct")
      ("seed", po::value(&options.seed)->default_value(options.seed), "seed of the global start positions and of mrs")
      ("output", po::value(&options.output), "JSON file with parameters, records, summary and PR curve")
      ("plots", po::value(&options.plots), "folder for the JSON, the difference pictures and the PNG plots")
      ("accept-threshold", po::value(&params.sequence.accept_threshold)
           ->default_value(params.sequence.accept_threshold),
       "answers are accepted at this confidence (distinctiveness, in spreads of the query's end costs)")
      ("out-of-map", po::bool_switch(&options.out_of_map), "no query frame is in the reference (new ground)")
      ("threads", po::value(&options.threads)->default_value(options.threads),
       "threads of both methods; 0 = OpenCV's default")
      ("alignment", po::value(&alignment)->default_value(alignment), "causal | centred: where the localised frame sits")
      ("velocity-min", doubleOption(&params.sequence.velocity_min),
       "slowest reference keyframes per test keyframe")
      ("velocity-max", doubleOption(&params.sequence.velocity_max),
       "fastest reference keyframes per test keyframe")
      ("velocity-step", doubleOption(&params.sequence.velocity_step),
       "step between the velocities tried (0.02 for sequences in the hundreds)")
      ("alignment-slack", po::value(&params.sequence.alignment_slack)->default_value(params.sequence.alignment_slack),
       "frames the path that places an answer may stray from the best straight trajectory; 0 = its end")
      ("levels", po::value(&params.mrs.levels)->default_value(params.mrs.levels),
       "mrs: l_max, coarsest stride 2^levels")
      ("tau", po::value(&params.mrs.tau)->default_value(params.mrs.tau), "mrs: particle overlap, P_init = M / N * tau");
  // clang-format on
  addDescriptorOptions(description, params.descriptor);
  po::variables_map variables;
  if (!parseCommandLine(argc, argv, kUsage, description, variables)) return std::nullopt;
  refuseOtherFrontEndsOptions(variables, params.descriptor);
  refuseEmptyPaths(variables, {"reference", "query", "ground-truth", "output", "plots"});
  options.descriptor_given = descriptorOptionsGiven(variables);
  options.min_appearance_change_given = givenOnCommandLine(variables, "min-appearance-change");

  if (options.method != "mrs" && options.method != "seqslam") {
    throw std::invalid_argument("unknown method '" + options.method + "' (expected mrs or seqslam)");
  }
  if (options.protocol != "per-frame" && options.protocol != "global") {
    throw std::invalid_argument("unknown protocol '" + options.protocol + "' (expected per-frame or global)");
  }
  if (options.tolerance < 0) throw std::invalid_argument("--tolerance must be >= 0");
  if (options.queries < 1 || options.queries > kMaxGlobalQueries) {
    throw std::invalid_argument("--queries must be in 1.." + std::to_string(kMaxGlobalQueries));
  }
  // OpenCV's thread pool fails at exit with tens of thousands of threads; no machine needs that many.
  if (options.threads < 0 || options.threads > 1024) throw std::invalid_argument("--threads must be in 0..1024");
  if (options.out_of_map && !options.ground_truth.empty()) {
    throw std::invalid_argument("--out-of-map and --ground-truth exclude each other");
  }
  if ((bag::isBagPath(options.reference) || bag::isBagPath(options.query)) &&
      options.topic.empty()) {
    throw std::invalid_argument("reading a bag needs --topic");
  }
  params.sequence.alignment = parseWindowAlignment(alignment);
  if (options.seed < 0) throw std::invalid_argument("--seed must be >= 0, got " + std::to_string(options.seed));
  params.mrs.seed = static_cast<std::uint64_t>(options.seed);
  params.validate();
  RecognizerParams keyframing;
  keyframing.min_appearance_change = options.min_appearance_change;
  keyframing.validate();
  // Written over neither input nor ground truth, nor into an image folder that a later run would read.
  const std::vector<NamedPath> inputs = {
      {"--reference", options.reference}, {"--query", options.query}, {"--ground-truth", options.ground_truth}};
  requireApartFromInputs({"--output", options.output}, inputs);
  requireApartFromInputs({"--plots", options.plots}, inputs);
  if (!options.plots.empty()) requireWritableFolder(options.plots, "--plots");
  if (!options.output.empty()) {
    if (std::filesystem::is_directory(options.output)) {
      throw std::invalid_argument("--output '" + options.output + "' is a folder; give the JSON file to write");
    }
    const std::filesystem::path folder = std::filesystem::path(options.output).parent_path();
    // The --plots folder may not exist yet: --plots creates it. Compared with links and dots resolved.
    const std::filesystem::path plots = options.plots.empty() ? "" : resolved(normalPath(options.plots).string());
    const bool in_plots = !plots.empty() && resolved(folder.empty() ? "." : folder.string()) == plots;
    // Named in the folder, or a link to the file there, which --plots would write over.
    const std::filesystem::path plots_json = plots.empty() ? "" : plots / "evaluation.json";
    if (!plots_json.empty() &&
        (writtenAt(options.output) == plots_json || resolved(options.output) == plots_json)) {
      throw std::invalid_argument("--output '" + options.output + "' is the JSON that --plots writes there; leave " +
                                  "--output out, or name another file");
    }
    if (!in_plots && !folder.empty() && !std::filesystem::is_directory(folder)) {
      throw std::invalid_argument("--output '" + options.output + "': there is no folder " + folder.string());
    }
    if (writtenInPlace(options.output)) {
      if (::access(options.output.c_str(), W_OK) != 0) {
        throw std::invalid_argument("--output '" + options.output + "': cannot write to it");
      }
    } else {
      requireWritableFolder(folder.empty() ? "." : folder.string(), "--output");
    }
  }
  return options;
}

}  // namespace tools
}  // namespace mrs_vpr

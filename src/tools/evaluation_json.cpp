#include "evaluation_json.hpp"

#include <filesystem>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <type_traits>
#include <variant>

#include "output_in_progress.hpp"

namespace mrs_vpr {
namespace tools {
namespace {

using json = OrderedJson;

/// Every descriptor parameter, named as in the parameter reference without "descriptor/" ("type",
/// "image_width", "hog/cell_size", ...).
json descriptorJson(const DescriptorParams& descriptor) {
  json fields = json::object();
  for (const auto& spec : descriptorParameters()) {
    const std::string name = spec.info.name.substr(spec.info.name.find('/') + 1);
    std::visit(
        [&](auto member) {
          using Value = std::decay_t<decltype(descriptor.*member)>;
          if constexpr (std::is_same_v<Value, WindowAlignment>) {
            fields[name] = toString(descriptor.*member);
          } else {
            fields[name] = descriptor.*member;
          }
        },
        spec.member);
  }
  return fields;
}

}  // namespace

json parametersToJson(const EvalOptions& options, const Parameters& p) {
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
        {"alignment", toString(p.sequence.alignment)},
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

json recordsToJson(const std::vector<QueryRecord>& records, int tolerance) {
  json list = json::array();
  for (const QueryRecord& record : records) {
    const int nearest = nearestTrueIndex(record);
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
                    {"correct", isCorrect(record, tolerance)}});
  }
  return list;
}

std::string jsonText(const json& document, int indent) {
  return document.dump(indent, ' ', false, json::error_handler_t::replace);
}

void writeJson(const json& document, const std::string& path) {
  const std::string text = jsonText(document, 2);
  const auto cannot = [&] { return std::runtime_error("cannot write '" + path + "'"); };
  if (writtenInPlace(path)) {
    std::ofstream file(path);
    if (!(file << text << "\n").flush()) throw cannot();
    file.close();
    if (file.fail()) throw cannot();
    std::cerr << "  wrote " << path << "\n";
    return;
  }
  OutputInProgress output(path);  // Removed unless renamed into place: an existing file is never emptied.
  {
    std::ofstream file(output.temporary());
    if (!(file << text << "\n").flush()) throw cannot();
  }
  try {
    output.commit();
  } catch (const std::filesystem::filesystem_error&) {
    throw cannot();
  }
  std::cerr << "  wrote " << path << "\n";
}

}  // namespace tools
}  // namespace mrs_vpr

#pragma once

// The evaluation JSON of mrs_vpr_eval (doc/evaluation.md): the parameters of a run and its records.

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "eval_options.hpp"
#include "mrs_vpr/evaluation/evaluation.hpp"
#include "mrs_vpr/parameters.hpp"

namespace mrs_vpr {
namespace tools {

using OrderedJson = nlohmann::ordered_json;  // Keeps fields in the documented order.

/// The parameters of the run: those of the command line, with `p` as the parameters in effect (the
/// front end of a map database given as the reference).
OrderedJson parametersToJson(const EvalOptions& options, const Parameters& p);

/// Each record as the evaluation JSON lists it, judged correct within `tolerance` frames.
OrderedJson recordsToJson(const std::vector<QueryRecord>& records, int tolerance);

/// Writes `document` to `path`, indented, and says so on stderr; throws std::runtime_error when it cannot.
void writeJson(const OrderedJson& document, const std::string& path);

}  // namespace tools
}  // namespace mrs_vpr

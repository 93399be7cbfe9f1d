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

/// `document` as text (indented when `indent` >= 0). A path or name that is not UTF-8 is written with
/// U+FFFD for its stray bytes rather than failing after all the work.
std::string jsonText(const OrderedJson& document, int indent = -1);

/// Writes `document` to `path`, indented, and says so on stderr: to `path`.part first, renamed when
/// complete, so that a failure never leaves an existing file emptied. Throws std::runtime_error when
/// it cannot.
void writeJson(const OrderedJson& document, const std::string& path);

}  // namespace tools
}  // namespace mrs_vpr

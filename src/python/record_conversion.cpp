// Evaluation records and summaries to and from Python dicts.

#include "record_conversion.hpp"

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <pybind11/stl.h>

namespace mrs_vpr {
namespace python {
namespace {

/// A record from a dict with recordDict's keys (as Python code may have built or filtered it).
QueryRecord recordFrom(const py::handle& row) {
  QueryRecord record;
  record.query_index = row["query_index"].cast<int>();
  record.true_indices = row["true_indices"].cast<std::vector<int>>();
  record.predicted_index = row["predicted_index"].cast<int>();
  if (py::isinstance<py::dict>(row) && row.cast<py::dict>().contains("predicted_last")) {
    record.predicted_last = row["predicted_last"].cast<int>();
  }
  record.score = row["score"].cast<float>();
  record.confidence = row["confidence"].cast<float>();
  record.accepted = row["accepted"].cast<bool>();
  // Optional: dicts built by hand before the field existed still read.
  if (py::isinstance<py::dict>(row) && row.cast<py::dict>().contains("rival_places")) {
    record.rival_places = row["rival_places"].cast<int>();
  }
  record.at_velocity_bound = row["at_velocity_bound"].cast<bool>();
  if (py::isinstance<py::dict>(row) && row.cast<py::dict>().contains("repeated_view")) {
    record.repeated_view = row["repeated_view"].cast<bool>();
  }
  record.time_ms = row["time_ms"].cast<double>();
  return record;
}

/// A figure, or None where it does not exist (NaN in the core), as mrs_vpr_eval writes null in its JSON.
py::object figure(double value) { return std::isnan(value) ? py::object(py::none()) : py::float_(value); }

}  // namespace

GroundTruth groundTruthFrom(const py::dict& truth) {
  GroundTruth ground_truth;
  for (const auto& [query, references] : truth) {
    try {
      ground_truth[query.cast<int>()] = references.cast<std::vector<int>>();
    } catch (const py::cast_error&) {
      throw std::invalid_argument("ground truth maps a query frame to a list of map frames, all integers; got " +
                                  py::repr(query).cast<std::string>() + ": " +
                                  py::repr(references).cast<std::string>());
    }
  }
  return ground_truth;
}

py::dict recordDict(const QueryRecord& record) {
  py::dict row;
  const int nearest = nearestTrueIndex(record);
  row["query_index"] = record.query_index;
  row["true_index"] = nearest >= 0 ? py::cast(nearest) : py::none();  // The nearest true frame, as mrs_vpr_eval's.
  row["true_indices"] = record.true_indices;
  row["predicted_index"] = record.predicted_index;
  row["predicted_last"] = record.predicted_last;
  row["score"] = record.score;
  row["confidence"] = record.confidence;
  row["accepted"] = record.accepted;
  row["rival_places"] = record.rival_places;
  row["at_velocity_bound"] = record.at_velocity_bound;
  row["repeated_view"] = record.repeated_view;
  row["time_ms"] = record.time_ms;
  return row;
}

QueryRecord recordOf(const py::handle& row) {
  try {
    return recordFrom(row);
  } catch (const py::cast_error&) {
    throw std::invalid_argument("a query record holds a value of the wrong type: " + py::repr(row).cast<std::string>());
  }
}

std::vector<QueryRecord> recordsFrom(const py::iterable& rows) {
  std::vector<QueryRecord> records;
  for (const py::handle row : rows) records.push_back(recordOf(row));
  return records;
}

py::dict summaryDict(const EvaluationSummary& summary) {
  py::dict row;
  row["tolerance"] = summary.tolerance;
  row["queries"] = summary.queries;
  row["queries_in_map"] = summary.queries_in_map;
  row["top1"] = figure(summary.top1);
  row["pr_auc"] = figure(summary.pr_auc);
  row["recall_at_100_precision"] = figure(summary.recall_at_100_precision);
  row["accepted"] = summary.accepted;
  row["accepted_rate"] = figure(summary.accepted_rate);
  row["accepted_precision"] = figure(summary.accepted_precision);
  row["accepted_recall"] = figure(summary.accepted_recall);
  row["largest_wrong_accepted_error"] = figure(summary.largest_wrong_accepted_error);
  row["median_abs_error"] = figure(summary.median_abs_error);
  row["median_time_ms"] = figure(summary.median_time_ms);
  row["total_time_s"] = figure(summary.total_time_s);
  return row;
}

}  // namespace python
}  // namespace mrs_vpr

#pragma once

#include <vector>

#include <pybind11/pybind11.h>

#include "mrs_vpr/evaluation/evaluation.hpp"

namespace mrs_vpr {
namespace python {

namespace py = pybind11;

/// GroundTruth from a dict {query frame: [reference frames]}.
GroundTruth groundTruthFrom(const py::dict& truth);

/// A query record as a dict whose keys are its field names.
py::dict recordDict(const QueryRecord& record);

/// A record from a dict with recordDict's keys (as Python code may have built or filtered it); a value
/// of the wrong type is an error that shows the dict.
QueryRecord recordOf(const py::handle& row);
/// recordOf() of each dict.
std::vector<QueryRecord> recordsFrom(const py::iterable& rows);

/// An evaluation summary as a dict whose keys are its field names.
py::dict summaryDict(const EvaluationSummary& summary);

}  // namespace python
}  // namespace mrs_vpr

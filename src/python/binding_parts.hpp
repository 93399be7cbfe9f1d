#pragma once

// The parts of the Python module mrs_vpr._bindings (bindings.cpp), each bound in a file of its own.

#include <pybind11/pybind11.h>

#include "mrs_vpr/stamp.hpp"

namespace mrs_vpr {
namespace python {

// --- Stamps ----------------------------------------------------------------------------------------
// Python hands stamps over as float seconds; the core holds whole nanoseconds. These two functions are
// the only place that converts: to the nearest nanosecond (as ros::Time::fromSec rounds), and back to
// the nearest float.

inline Stamp coreStamp(double seconds) { return Stamp::fromSeconds(seconds); }
inline double secondsOf(Stamp stamp) { return stamp.seconds(); }

/// Match and Answer (answer_bindings.cpp).
void bindAnswers(pybind11::module_& m);
/// PlaceRecognizer over a map store (recognizer_bindings.cpp).
void bindRecognizer(pybind11::module_& m);
/// The evaluation library: protocols, ground truth, records, summary (evaluation_bindings.cpp).
void bindEvaluation(pybind11::module_& m);

}  // namespace python
}  // namespace mrs_vpr

#pragma once

#include <string>

#include <pybind11/pybind11.h>

#include "mrs_vpr/parameters.hpp"
#include "mrs_vpr/place_recognizer.hpp"

namespace mrs_vpr {
namespace python {

namespace py = pybind11;

/// What a PlaceRecognizer is constructed from.
struct Settings {
  Parameters core;
  RecognizerParams recognizer;
};

/// The defaults with `parameters` (exact names) set over them. Their ranges and rules are checked by
/// the PlaceRecognizer constructed from them.
Settings settingsFrom(const py::dict& parameters);

/// Exact name -> value of every parameter of `settings`.
py::dict parameterValues(Settings settings, const std::string& prefix = "");

/// Every parameter: name, type, default, allowed values and meaning, as the node's --help gives them.
py::list parameterReference();

}  // namespace python
}  // namespace mrs_vpr

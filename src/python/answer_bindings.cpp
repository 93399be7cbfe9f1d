// Match and Answer for Python: the fields of a sequence search's answer, read-only, and their repr.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <sstream>
#include <string>

#include "binding_parts.hpp"
#include "mrs_vpr/match.hpp"
#include "mrs_vpr/place_recognizer.hpp"

namespace py = pybind11;

namespace mrs_vpr {
namespace python {
namespace {

/// A float as it prints with float's precision ("6.92", not 6.920000076293945).
std::string floatText(float value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

}  // namespace

void bindAnswers(py::module_& m) {
  py::class_<Match>(m, "Match", "The answer of a sequence search (mrs_vpr/match.hpp).")
      .def_readonly("reference_index", &Match::reference_index, "Matched map frame; -1 when none.")
      .def_readonly("score", &Match::score, "Best / runner-up sequence difference, in [0, 1]; lower is better.")
      .def_readonly("confidence", &Match::confidence,
                    "Distinctiveness in standard deviations of the query's own end costs; higher is surer.")
      .def_readonly("rivals", &Match::rivals, "Ends the confidence was judged against.")
      .def_readonly("rival_places", &Match::rival_places,
                    "Places among those ends; below 100 the confidence needed rises (doc/acceptance.md).")
      .def_readonly("accepted", &Match::accepted, "Whether the answer passes the acceptance rule (a loop closure).")
      .def_readonly("velocity", &Match::velocity, "Map frames per test frame along the answer's trajectory.")
      .def_readonly("at_velocity_bound", &Match::at_velocity_bound,
                    "The trajectory runs at the slowest or fastest velocity searched (never accepted).")
      .def_readonly("repeated_view", &Match::repeated_view,
                    "Most of the test sequence's keyframes show one view again, as a camera standing in the dark "
                    "makes them (never accepted).")
      .def_readonly("same_recording", &Match::same_recording,
                    "The test sequence's keyframes are in the map already, at the same times with the same views "
                    "(one recording added twice; match_recent only; never accepted).")
      .def_readonly("turned_back", &Match::turned_back,
                    "The test sequence returns to a place it passed, as a robot that turned back or backed up "
                    "(match_recent only; never accepted).")
      .def_readonly("across_drives", &Match::across_drives,
                    "The answer's trajectory runs across the junction of two drives, as a map loaded and the frames "
                    "offered after it (never accepted).")
      .def_readonly("sequence_difference", &Match::sequence_difference,
                    "Mean difference along the best trajectory; compare within one method and length only.")
      .def_readonly("comparisons", &Match::comparisons, "Image comparisons the search made.")
      .def("__repr__", [](const Match& match) {
        return "Match(reference_index=" + std::to_string(match.reference_index) +
               ", confidence=" + floatText(match.confidence) + ", accepted=" + (match.accepted ? "True" : "False") +
               ", score=" + floatText(match.score) + ")";
      });

  py::class_<PlaceAnswer>(m, "Answer", "The answer to a query: the match and the stamps of its frames.")
      .def_readonly("match", &PlaceAnswer::match)
      .def_property_readonly("reference_index", [](const PlaceAnswer& a) { return a.match.reference_index; },
                             "Matched map frame (the localised test frame's place); -1 when none.")
      .def_property_readonly("confidence", [](const PlaceAnswer& a) { return a.match.confidence; },
                             "Distinctiveness in standard deviations; higher is surer.")
      .def_property_readonly("accepted", [](const PlaceAnswer& a) { return a.match.accepted; },
                             "Whether the answer passes the acceptance rule (a loop closure).")
      .def_property_readonly("score", [](const PlaceAnswer& a) { return a.match.score; },
                             "Best / runner-up sequence difference, in [0, 1]; lower is better.")
      .def_property_readonly("reference_stamp", [](const PlaceAnswer& a) { return secondsOf(a.reference_stamp); },
                             "Stamp of the matched map frame [s]; 0 when none.")
      .def_property_readonly("newest_stamp", [](const PlaceAnswer& a) { return secondsOf(a.newest_stamp); },
                             "Stamp of the test sequence's newest frame [s] (match_recent; else 0).")
      .def_readonly("localised_frame", &PlaceAnswer::localised_frame,
                    "The localised frame's index in the map (match_recent; else -1): with reference_index, what "
                    "reject_closure() takes.")
      .def_readonly("localised_row", &PlaceAnswer::localised_row,
                    "The test-sequence frame the answer localises: the middle one (sequence/alignment centred, "
                    "the default) or the newest (causal).")
      .def_property_readonly("localised_stamp", [](const PlaceAnswer& a) { return secondsOf(a.localised_stamp); },
                             "Stamp of the localised frame [s] (match_recent; else 0).")
      .def_readonly("query_length", &PlaceAnswer::query_length, "Frames of the test sequence.")
      .def_readonly("method", &PlaceAnswer::method, "The method that answered.")
      .def_readonly("verdict", &PlaceAnswer::verdict,
                    "Why it was accepted or not, as the node's ~query message says ('accepted', 'not accepted: ...').")
      .def("__repr__", [](const PlaceAnswer& a) {
        return "Answer(reference_index=" + std::to_string(a.match.reference_index) +
               ", confidence=" + floatText(a.match.confidence) + ", accepted=" + (a.match.accepted ? "True" : "False") +
               ", score=" + floatText(a.match.score) +
               ", reference_stamp=" + py::repr(py::float_(secondsOf(a.reference_stamp))).cast<std::string>() +
               ", method='" + a.method + "')";
      });
}

}  // namespace python
}  // namespace mrs_vpr

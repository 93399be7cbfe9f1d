// The Python module mrs_vpr._bindings: PlaceRecognizer, its answers, the map database and the
// evaluation library, for NumPy images. The package python/mrs_vpr wraps it (keyword names of the
// parameters, offline evaluation); everything that validates input is the core's. Each part is bound
// in a file of its own (binding_parts.hpp); the module-level functions are here.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstdint>
#include <optional>
#include <string>

#include "binding_parts.hpp"
#include "image_conversion.hpp"
#include "mrs_vpr/store/map_database.hpp"
#include "mrs_vpr/synthetic_route.hpp"
#include "parameter_conversion.hpp"

namespace py = pybind11;

PYBIND11_MODULE(_bindings, m) {
  using namespace mrs_vpr;
  using namespace mrs_vpr::python;
  m.doc() = "mrs_vpr's core for Python; use the package mrs_vpr, which wraps it.";
  // A map database that cannot be used is bad input, like every other: a ValueError.
  py::register_exception<MapDatabaseError>(m, "MapDatabaseError", PyExc_ValueError);

  bindAnswers(m);
  bindRecognizer(m);
  bindEvaluation(m);

  m.def("check_save_target", &MapDatabase::checkSaveTarget, py::arg("path"),
        "Raises MapDatabaseError, naming the problem, when a map cannot be saved at `path`.");
  m.def("parameter_reference", &parameterReference,
        "Every parameter: name, type, default, allowed values and meaning (the core's tables).");
  m.def(
      "map_front_end",
      [](const std::string& path) {
        Settings settings;
        const MapDatabase map(path, MapAccess::kReadOnly);
        settings.core.descriptor = map.descriptorParams();
        py::dict own;  // The map's front end's parameters only: the others mean nothing for it.
        for (const auto& [name, value] : parameterValues(settings, "descriptor/")) {
          const std::string owner = frontEndOwning(name.cast<std::string>());
          if (owner.empty() || owner == settings.core.descriptor.type) own[name] = value;
        }
        // Frames asked about are keyframed as the map's were: on the map's scale.
        const std::optional<MapTraversal>& traversal = map.traversal();
        if (traversal && traversal->min_appearance_change) {
          own["min_appearance_change"] = *traversal->min_appearance_change;
        }
        return own;
      },
      py::arg("path"),
      "The descriptor parameters (exact names) of the front end a map database was written with, and the "
      "appearance change its keyframes were kept at (min_appearance_change) where it records one.");

  const SyntheticRouteParams defaults;
  m.def(
      "synthetic_route",
      [](int reference_frames, int query_frames, int image_width, int image_height, double speed_min,
         double speed_max, double start_place, double noise_std, std::uint64_t seed) {
        SyntheticRouteParams params;
        params.reference_frames = reference_frames;
        params.query_frames = query_frames;
        params.image_width = image_width;
        params.image_height = image_height;
        params.speed_min = speed_min;
        params.speed_max = speed_max;
        params.start_place = start_place;
        params.noise_std = noise_std;
        params.seed = seed;
        SyntheticRoute route;
        {
          py::gil_scoped_release released;
          route = generateSyntheticRoute(params);
        }
        py::dict result;
        result["reference"] = stackOf(route.reference, params);
        result["query"] = stackOf(route.query, params);
        result["query_to_reference"] = py::array_t<int>(static_cast<py::ssize_t>(route.query_to_reference.size()),
                                                        route.query_to_reference.data());
        return result;
      },
      py::arg("reference_frames") = defaults.reference_frames, py::arg("query_frames") = defaults.query_frames,
      py::arg("image_width") = defaults.image_width, py::arg("image_height") = defaults.image_height,
      py::arg("speed_min") = defaults.speed_min, py::arg("speed_max") = defaults.speed_max,
      py::arg("start_place") = defaults.start_place, py::arg("noise_std") = defaults.noise_std,
      py::arg("seed") = defaults.seed,
      "Two generated traversals of one route with known alignment (mrs_vpr/synthetic_route.hpp): "
      "reference and query as N x H x W x 3 BGR uint8 arrays, and query_to_reference.");
}

// The Python module mrs_vpr._bindings: PlaceRecognizer, its answers, the map database and the
// evaluation library, for NumPy images. The package python/mrs_vpr wraps it (keyword names of the
// parameters, offline evaluation); everything that validates input is the core's.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstdint>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <opencv2/core.hpp>

#include "mrs_vpr/evaluation/evaluation.hpp"
#include "mrs_vpr/parameters.hpp"
#include "mrs_vpr/place_recognizer.hpp"
#include "mrs_vpr/store/map_database.hpp"
#include "mrs_vpr/store/persistent_map.hpp"
#include "mrs_vpr/synthetic_route.hpp"

#include "image_conversion.hpp"
#include "parameter_conversion.hpp"
#include "record_conversion.hpp"

namespace py = pybind11;

namespace mrs_vpr {
namespace python {
namespace {

// --- Stamps ----------------------------------------------------------------------------------------
// Python hands stamps over as float seconds; the core holds whole nanoseconds. These two functions are
// the only place that converts: to the nearest nanosecond (as ros::Time::fromSec rounds), and back to
// the nearest float.

Stamp coreStamp(double seconds) { return Stamp::fromSeconds(seconds); }
double secondsOf(Stamp stamp) { return stamp.seconds(); }

// --- The recognizer ----------------------------------------------------------------------------------

/// A PlaceRecognizer and the map store through which its map is saved and loaded: frames are added
/// through the store, so that loading a map while frames arrive keeps both consistent.
class Recognizer {
 public:
  explicit Recognizer(const Settings& settings) : recognizer_(settings.core, settings.recognizer), map_(recognizer_) {}

  PlaceRecognizer& core() { return recognizer_; }
  PersistentMap& map() { return map_; }

  Settings settings() const { return {recognizer_.parameters(), recognizer_.recognizerParameters()}; }

 private:
  PlaceRecognizer recognizer_;
  PersistentMap map_;
};

/// A float as it prints with float's precision ("6.92", not 6.920000076293945).
std::string floatText(float value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

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
      .def_readonly("localised_row", &PlaceAnswer::localised_row,
                    "The test-sequence frame the answer localises: the middle one (sequence/alignment centred, "
                    "the default) or the newest (causal).")
      .def_property_readonly("localised_stamp", [](const PlaceAnswer& a) { return secondsOf(a.localised_stamp); },
                             "Stamp of the localised frame [s] (match_recent; else 0).")
      .def_readonly("query_length", &PlaceAnswer::query_length, "Frames of the test sequence.")
      .def_readonly("method", &PlaceAnswer::method, "The method that answered.")
      .def("__repr__", [](const PlaceAnswer& a) {
        return "Answer(reference_index=" + std::to_string(a.match.reference_index) +
               ", confidence=" + floatText(a.match.confidence) + ", accepted=" + (a.match.accepted ? "True" : "False") +
               ", score=" + floatText(a.match.score) +
               ", reference_stamp=" + py::repr(py::float_(secondsOf(a.reference_stamp))).cast<std::string>() +
               ", method='" + a.method + "')";
      });
}

void bindRecognizer(py::module_& m) {
  py::class_<Recognizer>(m, "PlaceRecognizer",
                         "Sequence-based place recognition over a map of frames (mrs_vpr/place_recognizer.hpp).")
      .def(py::init([](const py::dict& parameters) { return std::make_unique<Recognizer>(settingsFrom(parameters)); }),
           py::arg("parameters") = py::dict())
      .def(
          "add_frame",
          [](Recognizer& self, const py::handle& image, double stamp, const std::string& channel_order) {
            const ChannelOrder order = channelOrder(channel_order);
            const Image view = imageFrom(image);
            const Stamp exact = coreStamp(stamp);
            py::gil_scoped_release released;
            // The node's path: the map keeps the frame only if it is a keyframe.
            return self.map().offer(self.core().describe(view.mat, order), exact) == FrameAdmission::kAdmitted;
          },
          py::arg("image"), py::arg("stamp") = 0.0, py::arg("channel_order") = "bgr",
          "Offers a camera frame to the map; True when it became a keyframe. A frame too similar to the last "
          "keyframe (its view changed by less than min_appearance_change) is not kept, nor is one that finds "
          "the map full (max_frames).")
      .def(
          "add_frames",
          [](Recognizer& self, const py::handle& images, std::optional<std::vector<double>> stamps,
             const std::string& channel_order) {
            const ChannelOrder order = channelOrder(channel_order);
            const std::vector<Image> views = imagesFrom(images, "images");
            if (stamps && stamps->size() != views.size()) {
              throw std::invalid_argument("stamps has " + std::to_string(stamps->size()) + " entries for " +
                                          std::to_string(views.size()) + " images");
            }
            // Every stamp is converted and every image described before the first is offered: bad input
            // leaves the map as it was.
            std::vector<Stamp> exact(views.size());
            for (std::size_t i = 0; i < views.size() && stamps; ++i) {
              try {
                exact[i] = coreStamp((*stamps)[i]);
              } catch (const std::invalid_argument& error) {
                throw std::invalid_argument("stamp " + std::to_string(i) + " of stamps: " + error.what());
              }
            }
            py::gil_scoped_release released;
            const DescriptorSequence descriptors = describeAll(self.core(), views, order, "images");
            int admitted = 0;
            for (int i = 0; i < descriptors.size(); ++i) {
              admitted += self.map().offer(descriptors.descriptorRow(i).clone(), exact[static_cast<std::size_t>(i)]) ==
                                  FrameAdmission::kAdmitted
                              ? 1
                              : 0;
            }
            return admitted;
          },
          py::arg("images"), py::arg("stamps") = py::none(), py::arg("channel_order") = "bgr",
          "Offers frames (oldest first) to the map as add_frame does; returns how many became keyframes.")
      .def(
          "keyframes_of",
          [](Recognizer& self, const py::handle& images, const std::string& channel_order) {
            const ChannelOrder order = channelOrder(channel_order);
            const std::vector<Image> views = imagesFrom(images, "the test sequence");
            py::gil_scoped_release released;
            std::vector<int> chosen;
            self.core().keyframesOf(describeAll(self.core(), views, order, "the test sequence"), &chosen);
            return chosen;
          },
          py::arg("images"), py::arg("channel_order") = "bgr",
          "Which of the images (oldest first) match() keeps as the test sequence: their indices, chosen as the "
          "map's keyframes are (all of them when min_appearance_change is 0).")
      .def(
          "match",
          [](Recognizer& self, const py::handle& images, const std::string& method, const std::string& channel_order) {
            const ChannelOrder order = channelOrder(channel_order);
            const std::vector<Image> views = imagesFrom(images, "the test sequence");
            const std::vector<cv::Mat> mats = matsOf(views);
            py::gil_scoped_release released;
            // The core keyframes the images as the map's frames (keyframesOf) before it searches.
            return self.core().match(mats, method, order);
          },
          py::arg("images"), py::arg("method") = "", py::arg("channel_order") = "bgr",
          "Where the test sequence (images, oldest first) ends in the map. Its images are keyframed as the map's "
          "frames are (keyframes_of) and the answer localises the last keyframe; at least 2 are needed. method: "
          "'mrs', 'seqslam' or '' (default_method).")
      .def(
          "match_recent",
          [](Recognizer& self, long long frames, const std::string& method, int end) {
            py::gil_scoped_release released;
            return self.core().matchRecent(frames, method, nullptr, end);
          },
          py::arg("frames"), py::arg("method") = "", py::arg("end") = -1,
          "Where the map's newest `frames` frames (or those before map frame `end`) lie among its older "
          "ones, recent_exclusion frames back and more: a loop closure.")
      .def(
          "match_every_frame",
          [](Recognizer& self, const py::handle& images, const std::string& method, const std::string& channel_order) {
            const ChannelOrder order = channelOrder(channel_order);
            const std::vector<Image> views = imagesFrom(images, "the traversal");
            py::gil_scoped_release released;
            const DescriptorSequence traversal = describeAll(self.core(), views, order, "the traversal");
            return self.core().matchEveryFrame(traversal.view(), method);
          },
          py::arg("images"), py::arg("method") = "", py::arg("channel_order") = "bgr",
          "The per-frame protocol over a traversal: for every frame, the Match of the sequence of "
          "sequence_length frames that localises it (reference_index -1 where that sequence is incomplete).")
      .def(
          "describe",
          [](Recognizer& self, const py::handle& image, const std::string& channel_order) {
            const ChannelOrder order = channelOrder(channel_order);
            const Image view = imageFrom(image);
            cv::Mat descriptor;
            {
              py::gil_scoped_release released;
              descriptor = self.core().describe(view.mat, order);
            }
            return arrayOf(descriptor);
          },
          py::arg("image"), py::arg("channel_order") = "bgr",
          "The image's descriptor (uint8, descriptor_size bytes), without touching the map.")
      .def(
          "save",
          [](Recognizer& self, const std::string& path) {
            py::gil_scoped_release released;
            return self.map().save(path);
          },
          py::arg("path"),
          "Writes the map to the new SQLite map database `path` (never overwritten); returns the frames written.")
      .def(
          "load",
          [](Recognizer& self, const std::string& path) {
            py::gil_scoped_release released;
            return self.map().load(path);
          },
          py::arg("path"),
          "Replaces the map by the map database `path` (of this recognizer's front end); returns its frames.")
      .def(
          "reset",
          [](Recognizer& self) {
            py::gil_scoped_release released;
            return self.map().reset();
          },
          "Removes every frame; returns how many there were.")
      .def("__len__", [](Recognizer& self) { return self.core().size(); })
      .def_property_readonly(
          "pending_frames", [](Recognizer& self) { return self.core().pending(); },
          "Frames added while a query held the map, waiting to enter it.")
      .def_property_readonly(
          "descriptor_size", [](Recognizer& self) { return self.core().extractor().size(); }, "Bytes per descriptor.")
      .def_property_readonly(
          "front_end", [](Recognizer& self) { return self.core().parameters().descriptor.describe(); },
          "The descriptor's front end in words.")
      .def_property_readonly(
          "parameters", [](Recognizer& self) { return parameterValues(self.settings()); },
          "Every parameter in effect, by its exact name.");
}

void bindEvaluation(py::module_& m) {
  m.def(
      "per_frame_queries",
      [](int query_frames, int sequence_length, const std::string& alignment) {
        SequenceParams params;
        params.sequence_length = sequence_length;
        params.alignment = parseWindowAlignment(alignment);
        return perFrameQueries(query_frames, params);
      },
      py::arg("query_frames"), py::arg("sequence_length"), py::arg("alignment"),
      "Query frames with a full test sequence in the per-frame protocol.");
  m.def(
      "global_queries",
      [](int query_frames, int length, int count, std::uint64_t seed, const std::string& alignment) {
        py::list tests;
        for (const TestSequence& test :
             globalQueries(query_frames, length, count, seed, parseWindowAlignment(alignment))) {
          tests.append(py::make_tuple(test.start, test.length, test.query_index));
        }
        return tests;
      },
      py::arg("query_frames"), py::arg("length"), py::arg("count"), py::arg("seed"), py::arg("alignment"),
      "Test sequences (start, length, query_index) of the global localisation protocol.");
  m.def(
      "truths",
      [](const std::optional<py::dict>& truth, int query_frames, int reference_frames) {
        std::optional<GroundTruth> ground_truth;
        if (truth) {
          ground_truth = groundTruthFrom(*truth);
          checkGroundTruth(*ground_truth, query_frames, reference_frames);
        }
        py::list table;
        for (int query = 0; query < query_frames; ++query) {
          const auto true_indices = truthFor(query, ground_truth ? &*ground_truth : nullptr, reference_frames);
          table.append(true_indices ? py::cast(*true_indices) : py::none());
        }
        return table;
      },
      py::arg("ground_truth"), py::arg("query_frames"), py::arg("reference_frames"),
      "For every query frame its true map frames, or None where it is not evaluated; without ground truth, "
      "query frame i shows map frame i.");
  m.def(
      "query_record",
      [](int query_index, std::vector<int> truth, const Match& match, double time_ms) {
        return recordDict(queryRecordOf(query_index, std::move(truth), match, time_ms));
      },
      py::arg("query_index"), py::arg("true_indices"), py::arg("match"), py::arg("time_ms"));
  m.def(
      "summarise",
      [](const py::iterable& records, int tolerance) { return summaryDict(summarise(recordsFrom(records), tolerance)); },
      py::arg("records"), py::arg("tolerance"),
      "top1, pr_auc, recall_at_100_precision, accepted figures, median error and time of query records.");
  m.def(
      "precision_recall_curve",
      [](const py::iterable& records, int tolerance) {
        const std::vector<PrPoint> curve = precisionRecallCurve(recordsFrom(records), tolerance);
        py::array_t<double> threshold(static_cast<py::ssize_t>(curve.size()));
        py::array_t<double> precision(static_cast<py::ssize_t>(curve.size()));
        py::array_t<double> recall(static_cast<py::ssize_t>(curve.size()));
        for (std::size_t i = 0; i < curve.size(); ++i) {
          threshold.mutable_at(i) = curve[i].threshold;
          precision.mutable_at(i) = curve[i].precision;
          recall.mutable_at(i) = curve[i].recall;
        }
        py::dict result;
        result["threshold"] = threshold;
        result["precision"] = precision;
        result["recall"] = recall;
        return result;
      },
      py::arg("records"), py::arg("tolerance"),
      "The precision-recall curve over a threshold on confidence, from the highest threshold down.");
}

}  // namespace
}  // namespace python
}  // namespace mrs_vpr

PYBIND11_MODULE(_bindings, m) {
  using namespace mrs_vpr;
  using namespace mrs_vpr::python;
  m.doc() = "mrs_vpr's core for Python; use the package mrs_vpr, which wraps it.";
  // A map database that cannot be used is bad input, like every other: a ValueError.
  py::register_exception<MapDatabaseError>(m, "MapDatabaseError", PyExc_ValueError);

  bindAnswers(m);
  bindRecognizer(m);
  bindEvaluation(m);

  m.def("parameter_reference", &parameterReference,
        "Every parameter: name, type, default, allowed values and meaning (the core's tables).");
  m.def(
      "map_front_end",
      [](const std::string& path) {
        Settings settings;
        settings.core.descriptor = MapDatabase(path, MapAccess::kReadOnly).descriptorParams();
        return parameterValues(settings, "descriptor/");
      },
      py::arg("path"), "The descriptor parameters (exact names) a map database was written with.");

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

// The evaluation library for Python: the protocols' queries, ground truth, records, summary and
// precision-recall curve, as mrs_vpr_eval computes them.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "binding_parts.hpp"
#include "mrs_vpr/evaluation/evaluation.hpp"
#include "mrs_vpr/evaluation/image_folder.hpp"
#include "mrs_vpr/parameters.hpp"
#include "record_conversion.hpp"

namespace py = pybind11;

namespace mrs_vpr {
namespace python {

void bindEvaluation(py::module_& m) {
  // evaluate()'s defaults and limits, mrs_vpr_eval's.
  m.attr("DEFAULT_TOLERANCE") = kDefaultTolerance;
  m.attr("DEFAULT_GLOBAL_QUERIES") = kDefaultGlobalQueries;
  m.attr("MAX_GLOBAL_QUERIES") = kMaxGlobalQueries;
  m.attr("DEFAULT_SEED") = MrsParams{}.seed;
  m.def(
      "image_files",
      [](const std::string& folder) {
        std::vector<std::string> files;
        {
          py::gil_scoped_release released;
          files = listImageFiles(folder);
        }
        // As the tools print it: names such as cam1.9.png and cam1.10.png read otherwise as counters.
        const std::string note = fractionOrderNote(files);
        if (!note.empty()) {
          py::module_::import("warnings").attr("warn")(note, py::module_::import("builtins").attr("UserWarning"), 2);
        }
        return files;
      },
      py::arg("folder"),
      "The image files of `folder` as full paths, in the order mrs_vpr_eval and build_map read them (numbers in "
      "names as numbers, 2.png before 10.png; digits after a decimal point as a fraction, with a UserWarning "
      "where reading them as counters would order the folder otherwise); RuntimeError naming the problem when "
      "the folder is missing, holds no image or an entry named as an image is no file.");
  m.def(
      "too_few_rivals_note",
      [](const std::vector<Match>& matches, int map_keyframes) {
        const auto too_few = std::count_if(matches.begin(), matches.end(), hasTooFewRivals);
        return tooFewRivalsNote(static_cast<int>(too_few), static_cast<int>(matches.size()), map_keyframes);
      },
      py::arg("matches"), py::arg("map_keyframes"),
      "mrs_vpr_eval's note on the answers among `matches` that a map too small for the acceptance rule left "
      "at confidence 0; empty when there are none.");
  m.def(
      "per_frame_queries",
      [](int query_frames, int sequence_length, const std::string& alignment) {
        Parameters params;  // Checked by the core's rule: "sequence/sequence_length must be in 2..10000".
        params.sequence.sequence_length = sequence_length;
        params.sequence.alignment = parseWindowAlignment(alignment);
        params.validate();
        return perFrameQueries(query_frames, params.sequence);
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
  m.def("repeated_global_queries", &repeatedGlobalQueries, py::arg("query_frames"), py::arg("length"),
        py::arg("count"), "What to tell a user whose global test sequences repeat positions; '' when none does.");
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
      "is_correct", [](const py::handle& record, int tolerance) { return isCorrect(recordOf(record), tolerance); },
      py::arg("record"), py::arg("tolerance"),
      "Whether the record's answer lies within `tolerance` frames of a true one (mrs_vpr_eval's `correct`).");
  m.def(
      "summarise",
      [](const py::iterable& records, int tolerance) {
        return summaryDict(summarise(recordsFrom(records), tolerance));
      },
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

}  // namespace python
}  // namespace mrs_vpr

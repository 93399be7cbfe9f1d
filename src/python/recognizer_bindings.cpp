// PlaceRecognizer for Python: frames in (NumPy images or descriptors), queries out, and its map
// saved and loaded through the map store.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <opencv2/core.hpp>

#include "binding_parts.hpp"
#include "image_conversion.hpp"
#include "mrs_vpr/parameters.hpp"
#include "mrs_vpr/place_recognizer.hpp"
#include "mrs_vpr/store/persistent_map.hpp"
#include "parameter_conversion.hpp"

namespace py = pybind11;

namespace mrs_vpr {
namespace python {
namespace {

/// A PlaceRecognizer and the map store through which its map is saved and loaded: frames are added
/// through the store, so that loading a map while frames arrive keeps both consistent.
class Recognizer {
 public:
  explicit Recognizer(const Settings& settings) : recognizer_(settings.core, settings.recognizer), map_(recognizer_) {}

  PlaceRecognizer& core() { return recognizer_; }
  PersistentMap& map() { return map_; }

  Settings settings() const { return {recognizer_.parameters(), recognizer_.recognizerParameters()}; }

  /// Frames offered since the map was last emptied or loaded that it did not keep: while there are
  /// any, map frame i is not the i-th frame offered (which evaluate() without ground truth assumes).
  long long framesLeftOut() const { return frames_left_out_.load(); }
  void leftOut(long long frames) { frames_left_out_ += frames; }

  /// Numbers for the next `frames` frames offered: their places among the frames offered since the
  /// map was emptied, numbered on from a loaded map's last frame, as build_map numbers a traversal. A
  /// saved map's frames then keep the numbers that a ground truth gives them.
  std::int64_t numberFrames(std::int64_t frames) { return next_number_.fetch_add(frames); }

  /// After the map was emptied or replaced: numbering starts after its last frame.
  void startOver() {
    frames_left_out_ = 0;
    const int frames = recognizer_.size();
    next_number_ = frames == 0 ? 0 : std::max<std::int64_t>(map_.sequenceOf(frames - 1) + 1, frames);
  }

 private:
  PlaceRecognizer recognizer_;
  PersistentMap map_;
  std::atomic<long long> frames_left_out_{0};
  std::atomic<std::int64_t> next_number_{0};
};

}  // namespace

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
            const cv::Mat descriptor = self.core().describe(view.mat, order);
            const bool kept = self.map().offer(descriptor, exact, "", self.numberFrames(1)) == FrameAdmission::kAdmitted;
            self.leftOut(kept ? 0 : 1);
            return kept;
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
            const std::int64_t first_number = self.numberFrames(descriptors.size());
            int admitted = 0;
            for (int i = 0; i < descriptors.size(); ++i) {
              admitted += self.map().offer(descriptors.descriptorRow(i).clone(), exact[static_cast<std::size_t>(i)], "",
                                           first_number + i) == FrameAdmission::kAdmitted
                              ? 1
                              : 0;
            }
            self.leftOut(descriptors.size() - admitted);
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
          "frames are (keyframes_of) and the answer localises the middle keyframe (sequence alignment 'centred', the "
          "default) or the last ('causal'); at least 2 are needed. method: "
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
          "_check_images",
          [](Recognizer& self, const py::handle& images, const std::string& channel_order, const std::string& what) {
            const ChannelOrder order = channelOrder(channel_order);
            const std::vector<Image> views = imagesFrom(images, what);
            py::gil_scoped_release released;
            describeAll(self.core(), views, order, what);
          },
          py::arg("images"), py::arg("channel_order"), py::arg("what"),
          "Raises ValueError naming the first image (of `what`) that cannot be described; for evaluate().")
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
            const int frames = self.map().load(path);
            self.startOver();
            return frames;
          },
          py::arg("path"),
          "Replaces the map by the map database `path` (of this recognizer's front end); returns its frames.")
      .def(
          "reset",
          [](Recognizer& self) {
            py::gil_scoped_release released;
            const int frames = self.map().reset();
            self.startOver();
            return frames;
          },
          "Removes every frame; returns how many there were.")
      .def(
          "frame_number",
          [](Recognizer& self, int index) {
            if (index < 0 || index >= self.core().size()) {
              throw py::index_error("map frame " + std::to_string(index) + " of a map of " +
                                    std::to_string(self.core().size()) + " frames");
            }
            return self.map().sequenceOf(index);
          },
          py::arg("index"),
          "Map frame `index`'s number: its place among the frames offered since the map was emptied (counted "
          "on from a loaded map's last frame), or the number its map database records; saved with the map, as "
          "build_map saves a traversal's frame numbers, for ground truths that name the frames offered.")
      .def("__len__", [](Recognizer& self) { return self.core().size(); })
      .def_property_readonly(
          "frames_left_out", [](Recognizer& self) { return self.framesLeftOut(); },
          "Frames offered since the map was last emptied or loaded that it did not keep (too similar to the "
          "last keyframe, or the map full): while there are any, map frame i is not the i-th frame offered.")
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

}  // namespace python
}  // namespace mrs_vpr

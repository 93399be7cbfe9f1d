// PlaceRecognizer for Python: frames in (NumPy images or descriptors), queries out, and its map
// saved and loaded through the map store.

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <atomic>
#include <cstdint>
#include <mutex>
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
#include "mrs_vpr/store/map_traversal.hpp"
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

  /**
   * Offers camera frames (oldest first) to the map; returns how many became keyframes. Each is
   * numbered by its place among the frames offered since the map was emptied, on after a loaded map's
   * frames (FrameNumbering), as build_map numbers a traversal: a saved map's frames keep the numbers a ground truth
   * gives them. One lock orders numbering, offering, loading and emptying: a frame offered while
   * another thread loads a map waits for the load, and is numbered in the map it joins. A save keeps
   * loads and resets out (map_swap_mutex_), not frames.
   */
  int offer(const DescriptorSequence& descriptors, const std::vector<Stamp>& stamps) {
    const std::lock_guard<std::mutex> lock(numbering_mutex_);
    int admitted = 0;
    for (int i = 0; i < descriptors.size(); ++i) {
      const FrameAdmission admission =
          map_.offer(descriptors.descriptorRow(i).clone(), stamps[static_cast<std::size_t>(i)], "", next_number_);
      if (admission == FrameAdmission::kAdmitted) ++admitted;
      next_number_ = nextFrameNumber(next_number_);
    }
    frames_left_out_ += descriptors.size() - admitted;
    return admitted;
  }

  int load(const std::string& path) {
    const std::lock_guard<std::mutex> no_save(map_swap_mutex_);
    const std::lock_guard<std::mutex> lock(numbering_mutex_);
    const int frames = map_.load(path);
    startOver();
    return frames;
  }

  /// Saves the map with the count of frames offered and the appearance change they were kept at
  /// where it is known, so that mrs_vpr_eval judges it as it judges build_map's maps (on every frame
  /// offered, the query keyframed as the map). Frames go on arriving meanwhile: a count read before
  /// the snapshot may fall short of its last number, which the evaluator then takes instead; but no
  /// load or reset can put another map under the count.
  std::int64_t save(const std::string& path) {
    const std::lock_guard<std::mutex> no_swap(map_swap_mutex_);
    MapTraversal offered;
    {
      const std::lock_guard<std::mutex> lock(numbering_mutex_);
      offered.frames = next_number_;
      offered.min_appearance_change = keyframing_;
    }
    return map_.save(path, offered);
  }

  int reset() {
    const std::lock_guard<std::mutex> no_save(map_swap_mutex_);
    const std::lock_guard<std::mutex> lock(numbering_mutex_);
    const int frames = map_.reset();
    startOver();
    return frames;
  }

 private:
  /// After the map was emptied or replaced: numbering goes on after its frames' numbers and the
  /// traversal it records (the frames it was kept of, as build_map's and saved Python maps do), as
  /// build_map numbers a traversal appended to it.
  void startOver() {
    frames_left_out_ = 0;
    const int frames = recognizer_.size();
    map_.startDrive(frames);  // The frames offered next are another drive's.
    // The map's keyframes were kept at this recognizer's appearance change when it is empty or records
    // that one; else it is not known (another, or none recorded), and a saved map records none.
    const double own = recognizer_.recognizerParameters().min_appearance_change;
    const std::optional<MapTraversal>& loaded = map_.loadedTraversal();
    const bool as_own = loaded && loaded->min_appearance_change && *loaded->min_appearance_change == own;
    keyframing_ = frames == 0 || as_own ? std::optional<double>(own) : std::nullopt;
    FrameNumbering numbering;
    for (int i = 0; i < frames; ++i) numbering.see(map_.sequenceOf(i));
    next_number_ = numbering.next(loaded);
  }

  PlaceRecognizer recognizer_;
  PersistentMap map_;
  std::mutex map_swap_mutex_;  ///< Taken before numbering_mutex_ by load() and reset(), and by save().
  std::mutex numbering_mutex_;
  std::atomic<long long> frames_left_out_{0};
  std::int64_t next_number_ = 0;  ///< Guarded by numbering_mutex_.
  /// The appearance change the map's keyframes were kept at, when known; guarded by numbering_mutex_.
  std::optional<double> keyframing_ = recognizer_.recognizerParameters().min_appearance_change;
};

/// A camera frame offered from Python: its image, channel order and stamp converted (and checked) while
/// the GIL is held, its descriptor computed after it is released.
struct OfferedFrame {
  OfferedFrame(const py::handle& image, double stamp_s, const std::string& channel_order)
      : order(channelOrder(channel_order)), view(imageFrom(image)), stamp(coreStamp(stamp_s)) {}
  cv::Mat descriptor(const PlaceRecognizer& core) const { return core.describe(view.mat, order); }

  ChannelOrder order;
  Image view;
  Stamp stamp;
};

/// A query traversal's keyframes, described once and chosen as the map's frames are (keyframesOf), as
/// mrs_vpr_eval keyframes its query before either protocol; for evaluate().
struct KeyframedTraversal {
  DescriptorSequence keyframes;
  std::vector<int> chosen;  ///< Each keyframe's index among the traversal's images.
};

}  // namespace

void bindRecognizer(py::module_& m) {
  py::class_<KeyframedTraversal>(m, "_KeyframedTraversal", "A query traversal's keyframes, for evaluate().")
      .def_readonly("chosen", &KeyframedTraversal::chosen, "Each keyframe's index among the traversal's images.")
      .def("__len__", [](const KeyframedTraversal& self) { return self.keyframes.size(); });

  py::class_<Recognizer>(m, "PlaceRecognizer",
                         "Sequence-based place recognition over a map of frames (mrs_vpr/place_recognizer.hpp).")
      .def(py::init([](const py::dict& parameters) { return std::make_unique<Recognizer>(settingsFrom(parameters)); }),
           py::arg("parameters") = py::dict())
      .def(
          "add_frame",
          [](Recognizer& self, const py::handle& image, double stamp, const std::string& channel_order) {
            const OfferedFrame frame(image, stamp, channel_order);
            py::gil_scoped_release released;
            // The node's path: the map keeps the frame only if it is a keyframe.
            DescriptorSequence descriptor(self.core().extractor().size());
            descriptor.append(frame.descriptor(self.core()), frame.stamp);
            return self.offer(descriptor, {frame.stamp}) == 1;
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
            return self.offer(descriptors, exact);
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
          "ones, recent_exclusion frames back and more: a loop closure. A sequence that would join a loaded "
          "map's last frames to frames offered since (two drives) is refused.")
      .def(
          "add_to_trail",
          [](Recognizer& self, const py::handle& image, double stamp, const std::string& channel_order) {
            const OfferedFrame frame(image, stamp, channel_order);
            py::gil_scoped_release released;
            return self.core().offerToTrail(frame.descriptor(self.core()), frame.stamp) == FrameAdmission::kAdmitted;
          },
          py::arg("image"), py::arg("stamp") = 0.0, py::arg("channel_order") = "bgr",
          "For a map that stays as it is (the node's map_mode fixed): offers a camera frame as add_frame does, "
          "but a keyframe joins the trail of the camera's newest keyframes instead of the map; True when it "
          "became one.")
      .def(
          "match_trail",
          [](Recognizer& self, long long frames, const std::string& method, long long end) {
            py::gil_scoped_release released;
            return self.core().matchTrail(frames, method, nullptr, end);
          },
          py::arg("frames"), py::arg("method") = "", py::arg("end") = -1,
          "Where the trail's `frames` newest keyframes (or those before trail keyframe `end`) lie in the whole "
          "map, judged as match_recent's answers are; it links no place.")
      .def_property_readonly(
          "trail_size", [](Recognizer& self) { return self.core().trailSize(); },
          "Keyframes that joined the trail since the recognizer was made (add_to_trail).")
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
          "_keyframed_traversal",
          [](Recognizer& self, const py::handle& images, const std::string& channel_order) {
            const ChannelOrder order = channelOrder(channel_order);
            const std::vector<Image> views = imagesFrom(images, "the traversal");
            py::gil_scoped_release released;
            std::vector<int> chosen;
            DescriptorSequence keyframes =
                self.core().keyframesOf(describeAll(self.core(), views, order, "the traversal"), &chosen);
            return KeyframedTraversal{std::move(keyframes), std::move(chosen)};
          },
          py::arg("images"), py::arg("channel_order"),
          "The traversal's keyframes (keyframes_of), described once; for evaluate().")
      .def(
          "_match_every_keyframe",
          [](Recognizer& self, const KeyframedTraversal& traversal, const std::string& method) {
            py::gil_scoped_release released;
            return self.core().matchEveryFrame(traversal.keyframes.view(), method);
          },
          py::arg("traversal"), py::arg("method"),
          "match_every_frame over the traversal's keyframes; for evaluate().")
      .def(
          "_match_keyframes",
          [](Recognizer& self, const KeyframedTraversal& traversal, int first, int count, const std::string& method) {
            if (first < 0 || count < 0 || first > traversal.keyframes.size() - count) {
              throw py::index_error("keyframes " + std::to_string(first) + " + " + std::to_string(count) +
                                    " of a traversal of " + std::to_string(traversal.keyframes.size()));
            }
            py::gil_scoped_release released;
            return self.core().match(traversal.keyframes.view(first, first + count), method).match;
          },
          py::arg("traversal"), py::arg("first"), py::arg("count"), py::arg("method"),
          "The Match of keyframes [first, first + count) of the traversal, as they are; for evaluate().")
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
            return self.save(path);
          },
          py::arg("path"),
          "Writes the map to the new SQLite map database `path` (never overwritten); returns the frames written.")
      .def(
          "load",
          [](Recognizer& self, const std::string& path) {
            py::gil_scoped_release released;
            return self.load(path);
          },
          py::arg("path"),
          "Replaces the map by the map database `path` (of this recognizer's front end); returns its frames.")
      .def(
          "reject_closure",
          [](Recognizer& self, int localised_frame, int reference_index) {
            py::gil_scoped_release released;
            return self.map().forgetClosure(localised_frame, reference_index).size();
          },
          py::arg("localised_frame"), py::arg("reference_index"),
          "Forgets the place link by which an accepted match_recent answer put map frame `localised_frame` in "
          "the place of map frame `reference_index` (the answer's localised_frame and reference_index), for a "
          "closure found wrong afterwards; returns the links forgotten (1). Raises ValueError when there is none "
          "(the answer linked nothing, or was forgotten already) or a frame is not in the map.")
      .def(
          "reset",
          [](Recognizer& self) {
            py::gil_scoped_release released;
            return self.reset();
          },
          "Removes every frame; returns how many there were.")
      .def(
          "frame_number",
          [](Recognizer& self, long long index) {
            const int frames = self.core().size();
            if (index < 0 || index >= frames) {
              throw py::index_error("no map frame " + std::to_string(index) + ": the map holds " +
                                    std::to_string(frames) + " frames" +
                                    (frames > 0 ? " (0.." + std::to_string(frames - 1) + ")" : ""));
            }
            return self.map().sequenceOf(static_cast<int>(index));
          },
          py::arg("index"),
          "Map frame `index`'s number: its place among the frames offered since the map was emptied (counted "
          "on after a loaded map's frame numbers and recorded traversal), or the number its map database "
          "records (-1: none, as in maps saved from Python before frames were numbered); saved with the map, "
          "as build_map saves a "
          "traversal's frame numbers, for ground truths that name the frames offered.")
      .def("__len__", [](Recognizer& self) { return self.core().size(); })
      .def_property_readonly(
          "frames_left_out", [](Recognizer& self) { return self.framesLeftOut(); },
          "Frames offered since the map was last emptied or loaded that it did not keep (too similar to the "
          "last keyframe, or the map full): while there are any, map frame i is not the i-th frame offered.")
      .def_property_readonly(
          "linked_frames", [](Recognizer& self) { return self.core().state().linked_frames; },
          "Map frames that match_recent's accepted answers linked to a place an earlier visit shows, so that "
          "the place's visits are no rivals of each other; saved and loaded with the map.")
      .def_property_readonly(
          "drive_starts", [](Recognizer& self) { return self.core().driveStarts(); },
          "Map frames that begin a drive not continuing the frame before them (the first frame offered after "
          "a load, or a map's recorded ones): no answer runs across them; saved and loaded with the map.")
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

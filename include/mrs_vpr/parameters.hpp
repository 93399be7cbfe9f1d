#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

namespace mrs_vpr {

// Each parameter's allowed values are written once, as data, in the tables at the end of this file
// (defined in parameters.cpp): validate() checks them and the node prints them with --help, so the
// message and the reference cannot disagree. The field comments below give meanings only.

/// The largest descriptor allowed [bytes], a 1024 x 1024 thumbnail: a map holds one per frame.
constexpr int kMaxDescriptorBytes = 1 << 20;

/// The front ends an image can be described by (DescriptorParams::type).
inline constexpr const char* kThumbnailFrontEnd = "thumbnail";
inline constexpr const char* kHogFrontEnd = "hog";

/**
 * How an image becomes a descriptor: the front end, and the parameters of each. Only the fields of the
 * chosen type are used. The thumbnail's defaults are OpenSeqSLAM's; HOG's are those of the comparison
 * in doc/front_ends.md (128 x 64 window, cells of 16 px, 9 orientation bins, blocks of 2 x 2 cells).
 */
struct DescriptorParams {
  std::string type = kHogFrontEnd;  ///< kHogFrontEnd or kThumbnailFrontEnd.
  // The thumbnail: grey, resized, every patch normalised (OpenSeqSLAM).
  int image_width = 64;  ///< Width after resizing [px].
  int image_height = 32; ///< Height after resizing [px].
  int patch_size = 8;    ///< Side of the normalisation patches [px]; divides width and height.
  // HOG: OpenCV's histograms of oriented gradients of the grey image resized to the window.
  int hog_window_width = 128;  ///< Width of the window the image is resized to [px].
  int hog_window_height = 64;  ///< Height of that window [px].
  int hog_cell_size = 16;      ///< Side of a histogram cell [px]; divides the window, which holds 2 x 2 or more.
  int hog_bins = 9;            ///< Orientation bins over 0..180 degrees.
  /// Standard deviation of the Gaussian that smooths the window before its gradients are taken [px],
  /// 0 = none. For a camera whose noise shows at the window's scale: on real daytime frames it cost
  /// accepted answers of long global queries, so it is off by default (doc/front_ends.md).
  double hog_blur = 0.0;

  bool isHog() const { return type == kHogFrontEnd; }
  /// Bytes per descriptor of this front end (0 for HOG cells of no size, which validate() refuses).
  int descriptorSize() const;
  /// For messages: "hog (128 x 64 window, cells of 16 px, 9 bins)", "thumbnail (64 x 32, patches of 8 px)".
  std::string describe() const;
  /// Same type, and equal in the fields that type uses: descriptors of one can be compared with the other's.
  bool sameFrontEnd(const DescriptorParams& other) const;

  /// Throws std::invalid_argument naming the first parameter out of range.
  void validate() const;
};

/// Where the test sequence sits relative to the query frame it localises.
enum class WindowAlignment {
  kCausal,  ///< The sequence ends at the query frame (what a live robot has).
  kCentred, ///< The query frame is in the middle of the sequence (OpenSeqSLAM).
};

/// The fewest frames of a test sequence: one frame has no trajectory.
constexpr int kMinSequenceFrames = 2;

/// Velocities a search may try: each one costs a pass over the difference matrix, and a step so fine
/// that their count overflows would crash a search rather than just slow it.
constexpr int kMaxVelocities = 1000;

/// Sequence matching shared by brute-force SeqSLAM and MRS-VPR. Defaults are OpenSeqSLAM's but for the
/// sequence length, chosen on keyframed real frames (doc/keyframes.md).
struct SequenceParams {
  /// ds: keyframes per test sequence in the per-frame protocol and continuous mode. 20: on the tune half
  /// of Nordland (keyframed at the defaults) precision 0.998 and recall 0.905, where 10 recalls 0.750.
  int sequence_length = 20;
  double velocity_min = 0.8;   ///< Slowest reference frames per test frame.
  double velocity_max = 1.2;   ///< Fastest reference frames per test frame, >= velocity_min.
  double velocity_step = 0.1;  ///< Step between tried velocities; at most kMaxVelocities of them.
  int contrast_window = 10;    ///< R: reference frames in the local contrast window, 0 = off.
  int match_exclusion = 10;    ///< Rwindow: frames around the best match excluded from the runner-up.
  /// Centred: the answer localises the middle keyframe of the test sequence, where the sequence's
  /// evidence lies on both sides. At the causal end a trajectory a few keyframes too fast or slow (a
  /// stop's stray keyframes, a change of speed) lands off the place: on camera drives (tune half) 7 of
  /// 78 accepted closures were 3-24 route frames off, against 0 of 80 centred. A closure therefore
  /// names the keyframe at index sequence_length / 2 counted from the oldest: the 11th of 20, 9 before
  /// the newest (its stamp says which).
  WindowAlignment alignment = WindowAlignment::kCentred;
  /// Frames the path that places an answer may stray from the best straight trajectory, which found the
  /// place (flexible_alignment.hpp); 0 = the straight trajectory's end. Off by default: on camera
  /// drives 4 turned 2 of 7 near misses right, but in a stretch of identical frames (a camera blacked
  /// out) the path may wander and move a right answer off.
  int alignment_slack = 0;
  /// An answer is accepted as a loop closure when its confidence (distinctiveness, in standard
  /// deviations of the query's own end costs) reaches this and its trajectory does not run at the
  /// slowest or fastest velocity. 3 is a three-sigma rule, not a value fitted to a data set; see
  /// acceptance.hpp for its derivation and doc/acceptance.md and doc/results.md for checks.
  double accept_threshold = 3.0;

  /// How many velocities velocity_min, + velocity_step, ... up to velocity_max are (a double: an
  /// invalid step may make them more than an int holds). Counted in steps, not accumulated, and
  /// rounding-safe, so that 0.8 + 4 x 0.1 reaches 1.2.
  double velocityCount() const { return std::floor((velocity_max - velocity_min) / velocity_step + 1e-9) + 1.0; }
  void validate() const;
};

/// The coarse-to-fine particle search of MRS-VPR. Defaults follow the paper where it gives one.
struct MrsParams {
  int levels = 3;               ///< l_max: the coarsest stride is 2^levels, at most 2^kMaxLevels.
  /// A coarse cell averages up to 2^levels frames from 16-bit sums of their bytes (compact_cells.cpp),
  /// which hold 257 frames at most.
  static constexpr int kMaxLevels = 8;
  /// Fewer levels are used when N / 2^levels would drop below this. Below about 64 coarse
  /// rows the true place is too often not the coarse level's first minimum (doc/paper_gaps.md, Levels).
  int min_coarse_frames = 64;
  double tau = 2.0;             ///< Particle overlap factor, P_init = (M / N) * tau.
  int index_shift = 2;          ///< Id_shift: end-index search radius of a particle, in level frames.
  double coverage_threshold = 0.5;  ///< Go to the next level once coverage shrinks below this ratio.
  int max_iterations = 8;           ///< Cap on particle iterations per level (the paper has none).
  double resample_threshold = 0.5;  ///< Resample when N_eff < this fraction of the particle count.
  int min_particles = 4;            ///< Fewest particles spread over the coarsest level.
  /// Distinct minima of the coarsest level carried to the level below, which decides among them, at
  /// least 2. With one, nothing would check the coarse answer at a finer level, and a place that only
  /// looks right when pooled would be accepted (MrsMatcher tests).
  int hypotheses = 8;
  std::uint64_t seed = 42;          ///< Seed of the search's random generator: same seed, same answer.

  void validate() const;
};

/// How a PlaceRecognizer holds its map and answers, besides the search's own Parameters.
struct RecognizerParams {
  int max_frames = 2000000;            ///< Map capacity [frames], 0 = unbounded (about 1.9 GB with HOG).
  int max_pending_frames = 600;        ///< Frames held back while a query reads the map (20 s at 30 Hz).
  int recent_exclusion = 100;          ///< matchRecent does not search this many frames before the test sequence.
  std::string default_method = "mrs";  ///< Method of a query that names none: "mrs" or "seqslam".
  /// A camera frame becomes a keyframe once its view has changed by this fraction of the difference
  /// between unrelated views (appearance_keyframes.hpp); 0 = every frame.
  double min_appearance_change = 0.4;

  void validate() const;
};

/// Every tunable of the core in one place.
struct Parameters {
  DescriptorParams descriptor;
  SequenceParams sequence;
  MrsParams mrs;

  void validate() const;
};

/// Parses "causal" / "centred" (also "centered"); throws std::invalid_argument otherwise.
WindowAlignment parseWindowAlignment(const std::string& text);
/// "causal" or "centred"; the number, for a value that is no enumerator (which validate() refuses).
std::string toString(WindowAlignment alignment);

/// The numbers a parameter may take: an interval, and optionally 0 as well (a switch-off value).
struct Range {
  static constexpr double kNone = std::numeric_limits<double>::infinity();

  double low = -kNone;
  double high = kNone;
  bool low_open = false;
  bool high_open = false;
  bool zero_allowed = false;
  std::string zero_means;  ///< Shown as "0 (zero_means) or ..."; may be empty.

  static Range closed(double low, double high);      ///< [low, high]
  static Range open(double low, double high);        ///< (low, high)
  static Range openClosed(double low, double high);  ///< (low, high]
  static Range atLeast(double low);                  ///< [low, infinity)
  /// This range with 0 allowed as well.
  Range orZero(std::string meaning = "") const;

  bool contains(double value) const;
  /// "4..1024" (closed), "(0, 1]" (an open end), ">= 0" (no upper bound), "0 (off) or 2..1000".
  std::string text() const;
};

/// One parameter, described once: its name, allowed values and meaning.
struct ParameterInfo {
  std::string name;                  ///< As the node reads it, e.g. "sequence/velocity_step".
  Range range;                       ///< Numbers allowed (numeric parameters).
  std::vector<std::string> choices;  ///< Words allowed (text parameters); none for numbers.
  /// A condition on other parameters that validate() checks after the ranges, e.g. "dividing
  /// image_width and image_height"; empty when there is none.
  std::string rule;
  std::string meaning;               ///< One sentence for the parameter reference.

  /// The allowed values as the parameter reference prints them, e.g. "(0, 10), at most 1000 velocities".
  std::string allowed() const;
  /// The message for a rejected value: "<name> must be in <allowed()>, got <value>[ (<detail>)]".
  /// Every validation message starts with the parameter's name, so callers may qualify it.
  std::string rejection(const std::string& value, const std::string& detail = "") const;
  /// Throws std::invalid_argument with rejection() unless `value` is in range.
  void require(double value) const;
  /// Throws std::invalid_argument with rejection() unless `value` is one of the choices (any text
  /// for a free-text parameter).
  void require(const std::string& value) const;
  /// A text parameter of any value (a path): no range, no choices, and a rule that says what it is.
  bool isFreeText() const;
};

/// A parameter of the group `Group`: its description and the field it sets.
template <typename Group>
struct ParameterSpec {
  using Member = std::variant<int Group::*, double Group::*, std::uint64_t Group::*,
                              WindowAlignment Group::*, std::string Group::*>;
  ParameterInfo info;
  Member member;
};

/// The tables of the core's parameters, in the order of the parameter reference.
const std::vector<ParameterSpec<DescriptorParams>>& descriptorParameters();
const std::vector<ParameterSpec<SequenceParams>>& sequenceParameters();
const std::vector<ParameterSpec<MrsParams>>& mrsParameters();
const std::vector<ParameterSpec<RecognizerParams>>& recognizerParameters();

/// The front end a parameter belongs to ("descriptor/hog/bins": kHogFrontEnd, "descriptor/patch_size":
/// kThumbnailFrontEnd); empty for one of every front end. Setting another front end's parameter
/// changes nothing, and the tools and the Python API refuse it rather than ignore it.
std::string frontEndOwning(const std::string& name);

/// The entry of `specs` named `name`; throws std::logic_error when there is none.
template <typename Group>
const ParameterInfo& parameterInfo(const std::vector<ParameterSpec<Group>>& specs, const std::string& name) {
  for (const auto& spec : specs) {
    if (spec.info.name == name) return spec.info;
  }
  throw std::logic_error("no parameter " + name);
}

/// Checks every field of `group` against the range or choices of its entry in `specs`, in table
/// order; throws std::invalid_argument with the first rejection. Rules are left to the caller.
template <typename Group>
void requireInRange(const std::vector<ParameterSpec<Group>>& specs, const Group& group) {
  for (const auto& spec : specs) {
    std::visit(
        [&](auto member) {
          using Value = std::decay_t<decltype(group.*member)>;
          if constexpr (std::is_same_v<Value, std::string>) {
            spec.info.require(group.*member);
          } else if constexpr (std::is_same_v<Value, WindowAlignment>) {
            spec.info.require(toString(group.*member));  // A value cast from a number may be no enumerator.
          } else {
            spec.info.require(static_cast<double>(group.*member));
          }
        },
        spec.member);
  }
}

}  // namespace mrs_vpr

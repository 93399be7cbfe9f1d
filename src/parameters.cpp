#include "mrs_vpr/parameters.hpp"

#include <cmath>
#include <stdexcept>

#include "mrs_vpr/number_text.hpp"

namespace mrs_vpr {
namespace {

std::string join(const std::vector<std::string>& words) {
  std::string text;
  for (const auto& word : words) {
    text += (text.empty() ? "" : ", ") + word;
  }
  return text;
}

}  // namespace

// --- The tables: every range of the core, written once ---------------------------------------------

std::string frontEndOwning(const std::string& name) {
  if (name.rfind("descriptor/hog/", 0) == 0) return kHogFrontEnd;
  for (const char* thumbnail : {"descriptor/image_width", "descriptor/image_height", "descriptor/patch_size"}) {
    if (name == thumbnail) return kThumbnailFrontEnd;
  }
  return "";
}

const std::vector<ParameterSpec<DescriptorParams>>& descriptorParameters() {
  using P = DescriptorParams;
  static const std::vector<ParameterSpec<P>> table = {
      {{"descriptor/type", {}, {kHogFrontEnd, kThumbnailFrontEnd}, "",
        "Front end: hog (OpenCV's histograms of oriented gradients) or thumbnail (OpenSeqSLAM's "
        "patch-normalised image)."},
       &P::type},
      {{"descriptor/image_width", Range::closed(4, 1024), {}, "", "Thumbnail: width the image is resized to [px]."},
       &P::image_width},
      {{"descriptor/image_height", Range::closed(4, 1024), {}, "", "Thumbnail: height the image is resized to [px]."},
       &P::image_height},
      {{"descriptor/patch_size", Range::closed(2, 1024), {}, "dividing image_width and image_height",
        "Thumbnail: side of the patch-normalisation patches [px]."},
       &P::patch_size},
      {{"descriptor/hog/window_width", Range::closed(8, 1024), {}, "", "HOG: width the image is resized to [px]."},
       &P::hog_window_width},
      {{"descriptor/hog/window_height", Range::closed(8, 1024), {}, "", "HOG: height the image is resized to [px]."},
       &P::hog_window_height},
      {{"descriptor/hog/cell_size", Range::closed(2, 512), {}, "dividing both window sides into 2 cells or more",
        "HOG: side of a histogram cell [px]; blocks are 2 x 2 cells, one cell apart."},
       &P::hog_cell_size},
      {{"descriptor/hog/bins", Range::closed(2, 36), {}, "", "HOG: orientation bins over 0..180 degrees."},
       &P::hog_bins},
      {{"descriptor/hog/blur", Range::closed(0, 16), {}, "",
        "HOG: standard deviation of the Gaussian that smooths the window before its gradients [px]; 0 = none."},
       &P::hog_blur},
  };
  return table;
}

const std::vector<ParameterSpec<SequenceParams>>& sequenceParameters() {
  using P = SequenceParams;
  static const std::vector<ParameterSpec<P>> table = {
      {{"sequence/sequence_length", Range::closed(kMinSequenceFrames, 10000), {}, "",
        "Keyframes per test sequence in the per-frame protocol (continuous mode default)."},
       &P::sequence_length},
      {{"sequence/velocity_min", Range::open(0, 10), {}, "", "Slowest reference frames per test frame."},
       &P::velocity_min},
      {{"sequence/velocity_max", Range::openClosed(0, 10), {}, ">= velocity_min",
        "Fastest reference frames per test frame."},
       &P::velocity_max},
      // The bound on the count keeps it an int and each search's passes over the table finite.
      {{"sequence/velocity_step", Range::open(0, 10), {},
        "at most " + std::to_string(kMaxVelocities) + " velocities", "Step between the velocities tried."},
       &P::velocity_step},
      {{"sequence/contrast_window", Range::closed(2, 1000).orZero("off"), {}, "",
        "Reference frames in the local contrast-enhancement window."},
       &P::contrast_window},
      {{"sequence/match_exclusion", Range::closed(0, 10000), {}, "",
        "Frames around the best match excluded when looking for the runner-up."},
       &P::match_exclusion},
      {{"sequence/alignment", {}, {"causal", "centred"}, "",
        "centred: the frame localised is the middle of the test sequence (surest); causal: it is the newest "
        "(sooner, more often a few frames off)."},
       &P::alignment},
      {{"sequence/alignment_slack", Range::closed(0, 1000), {}, "",
        "Frames the path that places an answer may stray from the best straight trajectory; 0 = its end."},
       &P::alignment_slack},
      {{"sequence/accept_threshold", Range::closed(0, 1000), {}, "",
        "An answer is accepted when its confidence (distinctiveness, in standard deviations) reaches this "
        "(more on a map of fewer than 100 places) and its trajectory is not at the slowest or fastest velocity."},
       &P::accept_threshold},
  };
  return table;
}

const std::vector<ParameterSpec<MrsParams>>& mrsParameters() {
  using P = MrsParams;
  static const std::vector<ParameterSpec<P>> table = {
      {{"mrs/levels", Range::closed(0, MrsParams::kMaxLevels), {}, "", "Coarsest temporal stride is 2^levels."},
       &P::levels},
      {{"mrs/min_coarse_frames", Range::closed(2, 1000), {}, "",
        "Fewer levels are used when the coarsest level would keep fewer test frames."},
       &P::min_coarse_frames},
      {{"mrs/tau", Range::closed(1, 16), {}, "", "Particle overlap factor: initial particles = (M / N) * tau."},
       &P::tau},
      {{"mrs/index_shift", Range::closed(0, 1000), {}, "",
        "End-index search radius of a particle [frames of its level]."},
       &P::index_shift},
      {{"mrs/coverage_threshold", Range::open(0, 1), {}, "",
        "Go to the next level once particle coverage shrinks below this ratio."},
       &P::coverage_threshold},
      {{"mrs/max_iterations", Range::closed(1, 1000), {}, "", "Cap on particle iterations per level."},
       &P::max_iterations},
      {{"mrs/resample_threshold", Range::openClosed(0, 1), {}, "",
        "Resample when the effective particle count falls below this fraction."},
       &P::resample_threshold},
      {{"mrs/min_particles", Range::closed(1, 100000), {}, "",
        "Fewest particles spread over the coarsest level."},
       &P::min_particles},
      // Two at least: the second is the rival against which the finer level checks the coarse answer.
      {{"mrs/hypotheses", Range::closed(2, 1000), {}, "",
        "Distinct minima of the coarsest level carried to the level below, which decides among them."},
       &P::hypotheses},
      {{"mrs/seed", Range::atLeast(0), {}, "", "Seed of the particle search: same seed, same answer."}, &P::seed},
  };
  return table;
}

// --- Range and ParameterInfo --------------------------------------------------------------------------

Range Range::closed(double low, double high) {
  Range range;
  range.low = low;
  range.high = high;
  return range;
}

Range Range::open(double low, double high) {
  Range range = closed(low, high);
  range.low_open = range.high_open = true;
  return range;
}

Range Range::openClosed(double low, double high) {
  Range range = closed(low, high);
  range.low_open = true;
  return range;
}

Range Range::atLeast(double low) {
  Range range = closed(low, kNone);
  range.high_open = true;  // Infinity itself is not a value: a period or a distance must be finite.
  return range;
}

Range Range::orZero(std::string meaning) const {
  Range range = *this;
  range.zero_allowed = true;
  range.zero_means = std::move(meaning);
  return range;
}

bool Range::contains(double value) const {
  if (zero_allowed && value == 0.0) return true;
  // Written so that NaN is outside every range.
  const bool above_low = low_open ? value > low : value >= low;
  const bool below_high = high_open ? value < high : value <= high;
  return above_low && below_high;
}

std::string Range::text() const {
  std::string text;
  if (zero_allowed) {
    text = zero_means.empty() ? "0 or " : "0 (" + zero_means + ") or ";
  }
  if (high == kNone) {
    return text + (low_open ? "> " : ">= ") + numberText(low);
  }
  if (!low_open && !high_open) {
    return text + numberText(low) + ".." + numberText(high);
  }
  return text + (low_open ? "(" : "[") + numberText(low) + ", " + numberText(high) + (high_open ? ")" : "]");
}

std::string ParameterInfo::allowed() const {
  // Free text (a path): no range and no choices, only the rule says what it may be.
  if (isFreeText()) return rule;
  const std::string values = choices.empty() ? range.text() : join(choices);
  return rule.empty() ? values : values + ", " + rule;
}

std::string ParameterInfo::rejection(const std::string& value, const std::string& detail) const {
  // "must be in 1..10", "must be >= 0", "must be 0 (off) or 2..1000", "must be one of a, b".
  const bool interval = std::isfinite(range.low) && std::isfinite(range.high) && !range.zero_allowed;
  const std::string verb = !choices.empty() ? " must be one of " : interval ? " must be in " : " must be ";
  std::string message = name + verb + allowed() + ", got " + value;
  if (!detail.empty()) {
    message += " (" + detail + ")";
  }
  return message;
}

void ParameterInfo::require(double value) const {
  if (!range.contains(value)) {
    throw std::invalid_argument(rejection(numberText(value)));
  }
}

bool ParameterInfo::isFreeText() const {
  return choices.empty() && !std::isfinite(range.low) && !std::isfinite(range.high) && !rule.empty();
}

void ParameterInfo::require(const std::string& value) const {
  if (isFreeText()) return;
  for (const auto& choice : choices) {
    if (value == choice) return;
  }
  throw std::invalid_argument(rejection("'" + value + "'"));
}

// --- Validation: the ranges of the tables, then the rules that involve several parameters ------------

void DescriptorParams::validate() const {
  requireInRange(descriptorParameters(), *this);
  if (image_width % patch_size != 0 || image_height % patch_size != 0) {
    throw std::invalid_argument(parameterInfo(descriptorParameters(), "descriptor/patch_size")
                                    .rejection(std::to_string(patch_size),
                                               "image_width " + std::to_string(image_width) +
                                                   ", image_height " + std::to_string(image_height)));
  }
  // A block is 2 x 2 cells, so the window needs at least two cells each way.
  if (hog_window_width % hog_cell_size != 0 || hog_window_height % hog_cell_size != 0 ||
      hog_window_width < 2 * hog_cell_size || hog_window_height < 2 * hog_cell_size) {
    throw std::invalid_argument(parameterInfo(descriptorParameters(), "descriptor/hog/cell_size")
                                    .rejection(std::to_string(hog_cell_size),
                                               "window " + std::to_string(hog_window_width) + " x " +
                                                   std::to_string(hog_window_height)));
  }
  if (descriptorSize() > kMaxDescriptorBytes) {
    const std::string name = isHog() ? "descriptor/hog/cell_size" : "descriptor/patch_size";
    throw std::invalid_argument(name + ": " + describe() + " gives descriptors of " + std::to_string(descriptorSize()) +
                                " bytes, more than the " + std::to_string(kMaxDescriptorBytes) + " allowed");
  }
}

int DescriptorParams::descriptorSize() const {
  if (!isHog()) return image_width * image_height;
  if (hog_cell_size <= 0) return 0;  // No cells; validate() names the parameter.
  const int blocks_x = hog_window_width / hog_cell_size - 1;
  const int blocks_y = hog_window_height / hog_cell_size - 1;
  return blocks_x * blocks_y * 4 * hog_bins;
}

std::string DescriptorParams::describe() const {
  if (isHog()) {
    return std::string(kHogFrontEnd) + " (" + std::to_string(hog_window_width) + " x " +
           std::to_string(hog_window_height) + " window, cells of " + std::to_string(hog_cell_size) + " px, " +
           std::to_string(hog_bins) + " bins" + (hog_blur > 0.0 ? ", blur " + numberText(hog_blur) + " px" : "") + ")";
  }
  return std::string(kThumbnailFrontEnd) + " (" + std::to_string(image_width) + " x " + std::to_string(image_height) +
         ", patches of " + std::to_string(patch_size) + " px)";
}

bool DescriptorParams::sameFrontEnd(const DescriptorParams& other) const {
  if (type != other.type) return false;
  if (isHog()) {
    return hog_window_width == other.hog_window_width && hog_window_height == other.hog_window_height &&
           hog_cell_size == other.hog_cell_size && hog_bins == other.hog_bins && hog_blur == other.hog_blur;
  }
  return image_width == other.image_width && image_height == other.image_height && patch_size == other.patch_size;
}

void SequenceParams::validate() const {
  requireInRange(sequenceParameters(), *this);
  // Either bound may be the one the user set, so the message names both.
  if (velocity_max < velocity_min) {
    throw std::invalid_argument("sequence/velocity_min " + numberText(velocity_min) + " is above sequence/velocity_max " +
                                numberText(velocity_max) +
                                ": the slowest velocity tried must not exceed the fastest; lower the first or raise "
                                "the second");
  }
  const double velocity_count = velocityCount();
  if (velocity_count > kMaxVelocities) {
    throw std::invalid_argument(parameterInfo(sequenceParameters(), "sequence/velocity_step")
                                    .rejection(numberText(velocity_step),
                                               numberText(velocity_count) + " velocities from velocity_min " +
                                                   numberText(velocity_min) + " to velocity_max " +
                                                   numberText(velocity_max)));
  }
}

void MrsParams::validate() const { requireInRange(mrsParameters(), *this); }

void RecognizerParams::validate() const { requireInRange(recognizerParameters(), *this); }

const std::vector<ParameterSpec<RecognizerParams>>& recognizerParameters() {
  using P = RecognizerParams;
  static const std::vector<ParameterSpec<P>> table = {
      // One frame is not a sequence: a map of one could never answer a query.
      {{"max_frames", Range::atLeast(2).orZero("unbounded"), {}, "",
        "Reference map capacity [frames]; further keyframes are dropped and counted."},
       &P::max_frames},
      {{"max_pending_frames", Range::closed(1, 1000000), {}, "",
        "Keyframes buffered while a query holds the map; more are dropped and counted."},
       &P::max_pending_frames},
      {{"recent_exclusion", Range::closed(0, 1000000), {}, "",
        "Map frames just before a recent_frames test sequence that are not searched."},
       &P::recent_exclusion},
      {{"default_method", {}, {"mrs", "seqslam"}, "",
        "Method for requests with an empty method and for continuous mode."},
       &P::default_method},
      {{"min_appearance_change", Range::closed(0, 1), {}, "",
        "A frame becomes a keyframe once its view has changed by this fraction of the difference between "
        "unrelated views of the map; 0 = every frame (~min_travel, when set, decides instead)."},
       &P::min_appearance_change},
  };
  return table;
}

void Parameters::validate() const {
  descriptor.validate();
  sequence.validate();
  mrs.validate();
}

WindowAlignment parseWindowAlignment(const std::string& text) {
  if (text == "causal") return WindowAlignment::kCausal;
  if (text == "centred" || text == "centered") return WindowAlignment::kCentred;
  throw std::invalid_argument(parameterInfo(sequenceParameters(), "sequence/alignment").rejection("'" + text + "'"));
}

std::string toString(WindowAlignment alignment) {
  switch (alignment) {
    case WindowAlignment::kCausal:
      return "causal";
    case WindowAlignment::kCentred:
      return "centred";
  }
  return std::to_string(static_cast<int>(alignment));
}

}  // namespace mrs_vpr

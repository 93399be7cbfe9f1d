#include "mrs_vpr/parameters.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

namespace mrs_vpr {
namespace {

template <typename T>
void requireInRange(const char* name, T value, T low, T high, const char* range_text) {
  if (!(value >= low && value <= high)) {
    std::ostringstream message;
    message << "parameter '" << name << "' = " << value << " is out of range " << range_text;
    throw std::invalid_argument(message.str());
  }
}

void requireOpen(const char* name, double value, double low, double high, const char* range_text) {
  if (!(value > low && value < high)) {
    std::ostringstream message;
    message << "parameter '" << name << "' = " << value << " is out of range " << range_text;
    throw std::invalid_argument(message.str());
  }
}

}  // namespace

void DescriptorParams::validate() const {
  requireInRange("descriptor/image_width", image_width, 4, 1024, "[4, 1024]");
  requireInRange("descriptor/image_height", image_height, 4, 1024, "[4, 1024]");
  requireInRange("descriptor/patch_size", patch_size, 1, std::min(image_width, image_height),
                 "[1, min(image_width, image_height)]");
  if (image_width % patch_size != 0 || image_height % patch_size != 0) {
    std::ostringstream message;
    message << "parameter 'descriptor/patch_size' = " << patch_size
            << " must divide descriptor/image_width (" << image_width << ") and descriptor/image_height ("
            << image_height << ")";
    throw std::invalid_argument(message.str());
  }
}

void SequenceParams::validate() const {
  requireInRange("sequence/sequence_length", sequence_length, 2, 10000, "[2, 10000]");
  requireOpen("sequence/velocity_min", velocity_min, 0.0, 10.0, "(0, 10)");
  requireInRange("sequence/velocity_max", velocity_max, velocity_min, 10.0, "[velocity_min, 10]");
  requireOpen("sequence/velocity_step", velocity_step, 0.0, 10.0, "(0, 10)");
  const double velocity_count = std::floor((velocity_max - velocity_min) / velocity_step + 1e-9) + 1.0;
  if (velocity_count > kMaxVelocities) {
    std::ostringstream message;
    message << "parameter 'sequence/velocity_step' = " << velocity_step << " gives " << velocity_count
            << " velocities between velocity_min " << velocity_min << " and velocity_max " << velocity_max
            << "; at most " << kMaxVelocities << " are allowed";
    throw std::invalid_argument(message.str());
  }
  if (contrast_window != 0) {
    requireInRange("sequence/contrast_window", contrast_window, 2, 1000, "0 (off) or [2, 1000]");
  }
  requireInRange("sequence/match_exclusion", match_exclusion, 0, 10000, "[0, 10000]");
  requireInRange("sequence/accept_threshold", accept_threshold, 0.0, 1000.0, "[0, 1000]");
}

void MrsParams::validate() const {
  requireInRange("mrs/levels", levels, 0, 8, "[0, 8]");
  requireInRange("mrs/min_coarse_frames", min_coarse_frames, 2, 1000, "[2, 1000]");
  requireInRange("mrs/tau", tau, 1.0, 16.0, "[1, 16]");
  requireInRange("mrs/pixel_pooling", pixel_pooling, 1, 64, "[1, 64]");
  requireInRange("mrs/index_shift", index_shift, 0, 1000, "[0, 1000]");
  requireOpen("mrs/coverage_threshold", coverage_threshold, 0.0, 1.0, "(0, 1)");
  requireInRange("mrs/max_iterations", max_iterations, 1, 1000, "[1, 1000]");
  requireInRange("mrs/resample_threshold", resample_threshold, 1e-9, 1.0, "(0, 1]");
  requireInRange("mrs/min_particles", min_particles, 1, 100000, "[1, 100000]");
  // Two at least: the second is the rival against which the finer level checks the coarse answer.
  requireInRange("mrs/hypotheses", hypotheses, 2, 1000, "[2, 1000]");
}

void Parameters::validate() const {
  descriptor.validate();
  sequence.validate();
  mrs.validate();
  const int descriptor_size = descriptor.image_width * descriptor.image_height;
  if (descriptor_size % mrs.pixel_pooling != 0) {
    std::ostringstream message;
    message << "parameter 'mrs/pixel_pooling' = " << mrs.pixel_pooling
            << " must divide the descriptor size image_width * image_height = " << descriptor_size;
    throw std::invalid_argument(message.str());
  }
}

WindowAlignment parseWindowAlignment(const std::string& text) {
  if (text == "causal") return WindowAlignment::kCausal;
  if (text == "centred" || text == "centered") return WindowAlignment::kCentred;
  throw std::invalid_argument("alignment '" + text + "' is not one of: causal, centred");
}

std::string toString(WindowAlignment alignment) {
  return alignment == WindowAlignment::kCausal ? "causal" : "centred";
}

}  // namespace mrs_vpr

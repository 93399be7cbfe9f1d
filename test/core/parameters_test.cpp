#include <gtest/gtest.h>

#include <functional>
#include <limits>
#include <stdexcept>
#include <string>

#include "mrs_vpr/parameters.hpp"

namespace mrs_vpr {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// The message of validate()'s std::invalid_argument after `change` is applied to default parameters.
std::string rejection(const std::function<void(Parameters&)>& change) {
  Parameters params;
  change(params);
  try {
    params.validate();
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "(accepted)";
}

bool accepted(const std::function<void(Parameters&)>& change) { return rejection(change) == "(accepted)"; }

#define EXPECT_REJECTED(name, change)                                    \
  do {                                                                   \
    const std::string message = rejection(change);                       \
    EXPECT_NE(message.find(name), std::string::npos) << message;         \
  } while (false)

TEST(Parameters, DefaultsValidate) {
  EXPECT_NO_THROW(DescriptorParams{}.validate());
  EXPECT_NO_THROW(SequenceParams{}.validate());
  EXPECT_NO_THROW(MrsParams{}.validate());
  EXPECT_NO_THROW(Parameters{}.validate());
}

TEST(Parameters, DefaultsAreOpenSeqSlamsAndThePapers) {
  const Parameters params;
  EXPECT_EQ(params.descriptor.image_width, 64);
  EXPECT_EQ(params.descriptor.image_height, 32);
  EXPECT_EQ(params.descriptor.patch_size, 8);
  EXPECT_EQ(params.sequence.sequence_length, 10);
  EXPECT_EQ(params.sequence.contrast_window, 10);
  EXPECT_EQ(params.sequence.match_exclusion, 10);
  EXPECT_EQ(params.sequence.alignment, WindowAlignment::kCausal);
  EXPECT_EQ(params.mrs.levels, 3);
  EXPECT_DOUBLE_EQ(params.mrs.tau, 2.0);
  EXPECT_DOUBLE_EQ(params.mrs.coverage_threshold, 0.5);
}

TEST(DescriptorParams, OutOfRangeValuesNameTheParameter) {
  EXPECT_REJECTED("descriptor/image_width", [](Parameters& p) { p.descriptor.image_width = 3; });
  EXPECT_REJECTED("descriptor/image_width", [](Parameters& p) { p.descriptor.image_width = 1025; });
  EXPECT_REJECTED("descriptor/image_height", [](Parameters& p) { p.descriptor.image_height = 0; });
  EXPECT_REJECTED("descriptor/patch_size", [](Parameters& p) { p.descriptor.patch_size = 0; });
  EXPECT_REJECTED("descriptor/patch_size", [](Parameters& p) { p.descriptor.patch_size = 64; });
  // 6 divides neither 64 nor 32.
  const std::string message = rejection([](Parameters& p) { p.descriptor.patch_size = 6; });
  EXPECT_NE(message.find("descriptor/patch_size"), std::string::npos) << message;
  EXPECT_NE(message.find("divide"), std::string::npos) << message;
  EXPECT_TRUE(accepted([](Parameters& p) { p.descriptor.patch_size = 32; }));
}

TEST(DescriptorParams, MessageGivesTheValueAndTheRange) {
  const std::string message = rejection([](Parameters& p) { p.descriptor.image_width = 2000; });
  EXPECT_NE(message.find("2000"), std::string::npos) << message;
  EXPECT_NE(message.find("[4, 1024]"), std::string::npos) << message;
}

TEST(SequenceParams, OutOfRangeValuesNameTheParameter) {
  EXPECT_REJECTED("sequence/sequence_length", [](Parameters& p) { p.sequence.sequence_length = 1; });
  EXPECT_REJECTED("sequence/sequence_length", [](Parameters& p) { p.sequence.sequence_length = 10001; });
  EXPECT_REJECTED("sequence/velocity_min", [](Parameters& p) { p.sequence.velocity_min = 0.0; });
  EXPECT_REJECTED("sequence/velocity_min", [](Parameters& p) { p.sequence.velocity_min = kNaN; });
  EXPECT_REJECTED("sequence/velocity_max", [](Parameters& p) { p.sequence.velocity_max = 0.7; });
  EXPECT_REJECTED("sequence/velocity_max", [](Parameters& p) { p.sequence.velocity_max = 11.0; });
  EXPECT_REJECTED("sequence/velocity_step", [](Parameters& p) { p.sequence.velocity_step = 0.0; });
  // Steps so fine that the velocities would number billions (and their count overflow an int).
  EXPECT_REJECTED("sequence/velocity_step", [](Parameters& p) { p.sequence.velocity_step = 1e-10; });
  EXPECT_REJECTED("sequence/velocity_step", [](Parameters& p) {
    p.sequence.velocity_min = 0.0001;
    p.sequence.velocity_max = 10.0;
    p.sequence.velocity_step = 1e-9;
  });
  EXPECT_TRUE(accepted([](Parameters& p) {  // Exactly kMaxVelocities.
    p.sequence.velocity_min = 0.001;
    p.sequence.velocity_max = 1.0;
    p.sequence.velocity_step = 0.001;
  }));
  EXPECT_REJECTED("sequence/contrast_window", [](Parameters& p) { p.sequence.contrast_window = 1; });
  EXPECT_REJECTED("sequence/contrast_window", [](Parameters& p) { p.sequence.contrast_window = 1001; });
  EXPECT_REJECTED("sequence/match_exclusion", [](Parameters& p) { p.sequence.match_exclusion = -1; });
  EXPECT_TRUE(accepted([](Parameters& p) { p.sequence.contrast_window = 0; }));  // Off.
  EXPECT_TRUE(accepted([](Parameters& p) { p.sequence.velocity_max = p.sequence.velocity_min; }));
}

TEST(MrsParams, OutOfRangeValuesNameTheParameter) {
  EXPECT_REJECTED("mrs/levels", [](Parameters& p) { p.mrs.levels = -1; });
  EXPECT_REJECTED("mrs/levels", [](Parameters& p) { p.mrs.levels = 9; });
  EXPECT_REJECTED("mrs/min_coarse_frames", [](Parameters& p) { p.mrs.min_coarse_frames = 1; });
  EXPECT_REJECTED("mrs/tau", [](Parameters& p) { p.mrs.tau = 0.5; });
  EXPECT_REJECTED("mrs/tau", [](Parameters& p) { p.mrs.tau = 17.0; });
  EXPECT_REJECTED("mrs/tau", [](Parameters& p) { p.mrs.tau = kNaN; });
  EXPECT_REJECTED("mrs/pixel_pooling", [](Parameters& p) { p.mrs.pixel_pooling = 0; });
  EXPECT_REJECTED("mrs/pixel_pooling", [](Parameters& p) { p.mrs.pixel_pooling = 65; });
  EXPECT_REJECTED("mrs/index_shift", [](Parameters& p) { p.mrs.index_shift = -1; });
  EXPECT_REJECTED("mrs/coverage_threshold", [](Parameters& p) { p.mrs.coverage_threshold = 0.0; });
  EXPECT_REJECTED("mrs/coverage_threshold", [](Parameters& p) { p.mrs.coverage_threshold = 1.0; });
  EXPECT_REJECTED("mrs/max_iterations", [](Parameters& p) { p.mrs.max_iterations = 0; });
  EXPECT_REJECTED("mrs/resample_threshold", [](Parameters& p) { p.mrs.resample_threshold = 0.0; });
  EXPECT_REJECTED("mrs/resample_threshold", [](Parameters& p) { p.mrs.resample_threshold = 1.5; });
  EXPECT_REJECTED("mrs/min_particles", [](Parameters& p) { p.mrs.min_particles = 0; });
  EXPECT_REJECTED("mrs/hypotheses", [](Parameters& p) { p.mrs.hypotheses = 1; });
  EXPECT_REJECTED("mrs/hypotheses", [](Parameters& p) { p.mrs.hypotheses = 1001; });
  EXPECT_TRUE(accepted([](Parameters& p) { p.mrs.resample_threshold = 1.0; }));
  EXPECT_TRUE(accepted([](Parameters& p) { p.mrs.levels = 0; }));
}

TEST(Parameters, PixelPoolingMustDivideTheDescriptorSize) {
  // 64 x 32 = 2048 bytes: 3 is within [1, 64] but does not divide it.
  const std::string message = rejection([](Parameters& p) { p.mrs.pixel_pooling = 3; });
  EXPECT_NE(message.find("mrs/pixel_pooling"), std::string::npos) << message;
  EXPECT_NE(message.find("2048"), std::string::npos) << message;
  // On its own the MRS block has no descriptor size to check against.
  MrsParams mrs;
  mrs.pixel_pooling = 3;
  EXPECT_NO_THROW(mrs.validate());
  // 60 x 36 = 2160 is divisible by 3.
  EXPECT_TRUE(accepted([](Parameters& p) {
    p.descriptor.image_width = 60;
    p.descriptor.image_height = 36;
    p.descriptor.patch_size = 6;
    p.mrs.pixel_pooling = 3;
  }));
}

TEST(Parameters, ValidateChecksEveryBlock) {
  EXPECT_REJECTED("descriptor/", [](Parameters& p) { p.descriptor.image_height = 2; });
  EXPECT_REJECTED("sequence/", [](Parameters& p) { p.sequence.sequence_length = 0; });
  EXPECT_REJECTED("mrs/", [](Parameters& p) { p.mrs.levels = 100; });
}

TEST(WindowAlignment, ParsesBothSpellingsAndRoundTrips) {
  EXPECT_EQ(parseWindowAlignment("causal"), WindowAlignment::kCausal);
  EXPECT_EQ(parseWindowAlignment("centred"), WindowAlignment::kCentred);
  EXPECT_EQ(parseWindowAlignment("centered"), WindowAlignment::kCentred);
  EXPECT_EQ(toString(WindowAlignment::kCausal), "causal");
  EXPECT_EQ(toString(WindowAlignment::kCentred), "centred");
  for (WindowAlignment a : {WindowAlignment::kCausal, WindowAlignment::kCentred}) {
    EXPECT_EQ(parseWindowAlignment(toString(a)), a);
  }
}

TEST(WindowAlignment, UnknownTextThrowsNamingItAndTheChoices) {
  try {
    parseWindowAlignment("sideways");
    FAIL() << "no exception";
  } catch (const std::invalid_argument& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("'sideways'"), std::string::npos) << message;
    EXPECT_NE(message.find("causal"), std::string::npos) << message;
    EXPECT_NE(message.find("centred"), std::string::npos) << message;
  }
  EXPECT_THROW(parseWindowAlignment(""), std::invalid_argument);
  EXPECT_THROW(parseWindowAlignment("Causal"), std::invalid_argument);
}

}  // namespace
}  // namespace mrs_vpr

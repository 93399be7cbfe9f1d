#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <set>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <variant>
#include <vector>

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
  // 20 keyframes, not OpenSeqSLAM's 10 frames: chosen on keyframed real frames (doc/keyframes.md).
  EXPECT_EQ(params.sequence.sequence_length, 20);
  EXPECT_EQ(params.sequence.alignment_slack, 0);
  EXPECT_EQ(params.sequence.contrast_window, 10);
  EXPECT_EQ(params.sequence.match_exclusion, 10);
  // The middle keyframe: at the causal end stray keyframes put closures off the place (doc/keyframes.md).
  EXPECT_EQ(params.sequence.alignment, WindowAlignment::kCentred);
  EXPECT_EQ(params.mrs.levels, 3);
  EXPECT_DOUBLE_EQ(params.mrs.tau, 2.0);
  EXPECT_DOUBLE_EQ(params.mrs.coverage_threshold, 0.5);
}

TEST(DescriptorParams, OutOfRangeValuesNameTheParameter) {
  EXPECT_REJECTED("descriptor/image_width", [](Parameters& p) { p.descriptor.image_width = 3; });
  EXPECT_REJECTED("descriptor/image_width", [](Parameters& p) { p.descriptor.image_width = 1025; });
  EXPECT_REJECTED("descriptor/image_height", [](Parameters& p) { p.descriptor.image_height = 0; });
  EXPECT_REJECTED("descriptor/patch_size", [](Parameters& p) { p.descriptor.patch_size = 0; });
  // A patch of one pixel has no spread to normalise by: every descriptor would be the same.
  EXPECT_REJECTED("descriptor/patch_size", [](Parameters& p) { p.descriptor.patch_size = 1; });
  EXPECT_REJECTED("descriptor/patch_size", [](Parameters& p) { p.descriptor.patch_size = 64; });
  // 6 divides neither 64 nor 32.
  const std::string message = rejection([](Parameters& p) { p.descriptor.patch_size = 6; });
  EXPECT_NE(message.find("descriptor/patch_size"), std::string::npos) << message;
  EXPECT_NE(message.find("dividing"), std::string::npos) << message;
  EXPECT_TRUE(accepted([](Parameters& p) { p.descriptor.patch_size = 32; }));
}

TEST(DescriptorParams, MessageGivesTheValueAndTheRange) {
  const std::string message = rejection([](Parameters& p) { p.descriptor.image_width = 2000; });
  EXPECT_NE(message.find("2000"), std::string::npos) << message;
  EXPECT_NE(message.find("4..1024"), std::string::npos) << message;
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

TEST(SequenceParams, AMinimumVelocityAboveTheMaximumNamesBothBounds) {
  // A user who raised only velocity_min must find it in the message, not just velocity_max.
  const std::string message = rejection([](Parameters& p) { p.sequence.velocity_min = 1.5; });
  EXPECT_NE(message.find("sequence/velocity_min 1.5"), std::string::npos) << message;
  EXPECT_NE(message.find("sequence/velocity_max 1.2"), std::string::npos) << message;
}

TEST(MrsParams, OutOfRangeValuesNameTheParameter) {
  EXPECT_REJECTED("mrs/levels", [](Parameters& p) { p.mrs.levels = -1; });
  EXPECT_REJECTED("mrs/levels", [](Parameters& p) { p.mrs.levels = 9; });
  EXPECT_REJECTED("mrs/min_coarse_frames", [](Parameters& p) { p.mrs.min_coarse_frames = 1; });
  EXPECT_REJECTED("mrs/tau", [](Parameters& p) { p.mrs.tau = 0.5; });
  EXPECT_REJECTED("mrs/tau", [](Parameters& p) { p.mrs.tau = 17.0; });
  EXPECT_REJECTED("mrs/tau", [](Parameters& p) { p.mrs.tau = kNaN; });
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

TEST(Parameters, ValidateChecksEveryBlock) {
  EXPECT_REJECTED("descriptor/", [](Parameters& p) { p.descriptor.image_height = 2; });
  EXPECT_REJECTED("sequence/", [](Parameters& p) { p.sequence.sequence_length = 0; });
  EXPECT_REJECTED("mrs/", [](Parameters& p) { p.mrs.levels = 100; });
}

TEST(Range, TextSaysWhichEndsAreOpen) {
  EXPECT_EQ(Range::closed(4, 1024).text(), "4..1024");
  EXPECT_EQ(Range::closed(1, 1000000).text(), "1..1000000");  // not 1e+06
  EXPECT_EQ(Range::open(0, 1).text(), "(0, 1)");
  EXPECT_EQ(Range::openClosed(0, 0.5).text(), "(0, 0.5]");
  EXPECT_EQ(Range::atLeast(0).text(), ">= 0");
  EXPECT_EQ(Range::closed(2, 1000).orZero("off").text(), "0 (off) or 2..1000");
  EXPECT_EQ(Range::closed(2, 10).orZero().text(), "0 or 2..10");
}

TEST(Range, ContainsFollowsTheOpenAndClosedEnds) {
  EXPECT_TRUE(Range::closed(1, 2).contains(1.0));
  EXPECT_TRUE(Range::closed(1, 2).contains(2.0));
  EXPECT_FALSE(Range::open(1, 2).contains(1.0));
  EXPECT_FALSE(Range::open(1, 2).contains(2.0));
  EXPECT_TRUE(Range::openClosed(0, 1).contains(1.0));
  EXPECT_FALSE(Range::openClosed(0, 1).contains(0.0));
  EXPECT_TRUE(Range::atLeast(0).contains(1e300));
  EXPECT_TRUE(Range::closed(2, 10).orZero().contains(0.0));
  EXPECT_FALSE(Range::closed(2, 10).orZero().contains(1.0));
  EXPECT_FALSE(Range::closed(-1, 1).contains(kNaN));
  EXPECT_FALSE(Range::atLeast(0).contains(kNaN));
}

/// Values of a field of type `Value` just outside `range` at each bounded end.
template <typename Value>
std::vector<double> justOutside(const Range& range) {
  std::vector<double> values;
  const bool integer = std::is_integral_v<Value>;
  if (std::isfinite(range.low)) {
    values.push_back(range.low_open ? range.low : integer ? range.low - 1 : std::nextafter(range.low, -1e300));
  }
  if (std::isfinite(range.high)) {
    values.push_back(range.high_open ? range.high : integer ? range.high + 1 : std::nextafter(range.high, 1e300));
  }
  return values;
}

/// Sets each int or double field of one group just outside its table range and expects the message to
/// name the parameter and to give its allowed values exactly as the parameter reference prints them.
template <typename Group>
void expectEachRangeInItsMessage(const std::vector<ParameterSpec<Group>>& specs, Group Parameters::*group) {
  for (const auto& spec : specs) {
    std::visit(
        [&](auto member) {
          using Value = std::decay_t<decltype(Parameters{}.*group.*member)>;
          if constexpr (std::is_same_v<Value, int> || std::is_same_v<Value, double>) {
            for (double outside : justOutside<Value>(spec.info.range)) {
              const std::string message = rejection([&](Parameters& p) { (p.*group).*member = Value(outside); });
              EXPECT_EQ(message.rfind(spec.info.name + " must be", 0), 0U) << outside << ": " << message;
              EXPECT_NE(message.find(spec.info.allowed()), std::string::npos) << message;
            }
          }
        },
        spec.member);
  }
}

TEST(Parameters, EachMessageGivesTheRangeOfTheTable) {
  expectEachRangeInItsMessage(descriptorParameters(), &Parameters::descriptor);
  expectEachRangeInItsMessage(sequenceParameters(), &Parameters::sequence);
  expectEachRangeInItsMessage(mrsParameters(), &Parameters::mrs);
}

TEST(Parameters, RuleMessagesGiveTheWholeAllowedText) {
  const auto expectAllowed = [](const ParameterInfo& info, const std::function<void(Parameters&)>& change) {
    const std::string message = rejection(change);
    EXPECT_EQ(message.rfind(info.name + " must be in " + info.allowed() + ", got ", 0), 0U) << message;
  };
  expectAllowed(parameterInfo(descriptorParameters(), "descriptor/patch_size"),
                [](Parameters& p) { p.descriptor.patch_size = 6; });
  expectAllowed(parameterInfo(sequenceParameters(), "sequence/velocity_step"),
                [](Parameters& p) { p.sequence.velocity_step = 1e-10; });
}

TEST(Parameters, VelocityStepIsDocumentedAsChecked) {
  // It was documented as "> 0" but checked as (0, 10).
  const ParameterInfo& step = parameterInfo(sequenceParameters(), "sequence/velocity_step");
  EXPECT_EQ(step.allowed(), "(0, 10), at most " + std::to_string(kMaxVelocities) + " velocities");
  EXPECT_EQ(rejection([](Parameters& p) { p.sequence.velocity_step = 10.0; }),
            "sequence/velocity_step must be in " + step.allowed() + ", got 10");
}

TEST(Parameters, TablesNameEveryParameterOnceUnderItsGroup) {
  std::set<std::string> names;
  const auto add = [&](const auto& specs, const std::string& group) {
    for (const auto& spec : specs) {
      EXPECT_EQ(spec.info.name.rfind(group + "/", 0), 0U) << spec.info.name;
      EXPECT_TRUE(names.insert(spec.info.name).second) << spec.info.name;
      EXPECT_FALSE(spec.info.meaning.empty()) << spec.info.name;
    }
  };
  add(descriptorParameters(), "descriptor");
  add(sequenceParameters(), "sequence");
  add(mrsParameters(), "mrs");
  // Every field of DescriptorParams (the type, the thumbnail's 3, HOG's 5), SequenceParams and MrsParams.
  EXPECT_EQ(names.size(), 9U + 9U + 10U);
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
    // The same words as the parameter reference.
    EXPECT_NE(message.find(parameterInfo(sequenceParameters(), "sequence/alignment").allowed()), std::string::npos)
        << message;
  }
  EXPECT_THROW(parseWindowAlignment(""), std::invalid_argument);
  EXPECT_THROW(parseWindowAlignment("Causal"), std::invalid_argument);
}

TEST(WindowAlignment, AValueThatIsNoEnumeratorIsRefusedByValidate) {
  // Set from a number through the C++ API (a cast, a file read as an int): refused, not searched as centred.
  SequenceParams sequence;
  sequence.alignment = static_cast<WindowAlignment>(7);
  EXPECT_EQ(toString(sequence.alignment), "7");
  try {
    sequence.validate();
    FAIL() << "no exception";
  } catch (const std::invalid_argument& error) {
    const std::string message = error.what();
    EXPECT_NE(message.find("sequence/alignment"), std::string::npos) << message;
    EXPECT_NE(message.find("7"), std::string::npos) << message;
  }
  sequence.alignment = WindowAlignment::kCausal;
  EXPECT_NO_THROW(sequence.validate());
}

}  // namespace
}  // namespace mrs_vpr

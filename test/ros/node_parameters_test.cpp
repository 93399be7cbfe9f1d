#include <gtest/gtest.h>

#include <set>
#include <string>

#include "mrs_vpr/ros/node_parameters.hpp"

namespace mrs_vpr {
namespace node {
namespace {

std::string errorOf(const NodeParameters& params) {
  try {
    params.validate();
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "";
}

TEST(NodeParameters, DefaultsAreValid) { EXPECT_NO_THROW(NodeParameters{}.validate()); }

TEST(NodeParameters, ErrorsNameTheParameterAndRange) {
  NodeParameters params;
  params.frame_stride = 0;
  EXPECT_EQ(errorOf(params), "~frame_stride must be in 1..10000, got 0");

  params = NodeParameters{};
  params.core.sequence.accept_threshold = -1.0;
  EXPECT_EQ(errorOf(params), "parameter 'sequence/accept_threshold' = -1 is out of range [0, 1000]");

  params = NodeParameters{};
  params.default_method = "fast";
  EXPECT_EQ(errorOf(params), "~default_method must be mrs or seqslam, got 'fast'");

  params = NodeParameters{};
  params.core.descriptor.image_width = 2;
  const std::string core = errorOf(params);
  EXPECT_NE(core.find("descriptor/image_width"), std::string::npos) << core;
  EXPECT_NE(core.find("4"), std::string::npos) << core;  // the range
}

TEST(NodeParameters, AutoQueryFramesDefaultsToSequenceLength) {
  NodeParameters params;
  params.core.sequence.sequence_length = 17;
  EXPECT_EQ(params.autoQueryFrames(), 17);
  params.auto_query_frames = 40;
  EXPECT_EQ(params.autoQueryFrames(), 40);
}

TEST(NodeParameters, DescriptionsCoverEveryParameterOnce) {
  const auto descriptions = describeParameters();
  std::set<std::string> names;
  for (const auto& description : descriptions) {
    EXPECT_TRUE(names.insert(description.name).second) << description.name;
    EXPECT_FALSE(description.default_value.empty()) << description.name;
    EXPECT_FALSE(description.range.empty()) << description.name;
    EXPECT_FALSE(description.meaning.empty()) << description.name;
  }
  EXPECT_EQ(names.count("mrs/tau"), 1U);
  EXPECT_EQ(names.count("descriptor/image_width"), 1U);
  EXPECT_EQ(names.count("min_frame_interval"), 1U);
  EXPECT_EQ(descriptions.size(), 32U);
}

}  // namespace
}  // namespace node
}  // namespace mrs_vpr

// The launch files' arguments: a parameter file's values stay unless an argument is given
// (roslaunch --dump-params, no master needed).

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <string>

#include "support/temporary_folder.hpp"

namespace {

/// The node's parameters as `roslaunch --dump-params mrs_vpr LAUNCH ARGUMENTS` sets them, by name
/// (without the node's namespace); empty when roslaunch fails.
std::map<std::string, std::string> nodeParameters(const std::string& launch, const std::string& arguments) {
  const std::string command = "roslaunch --dump-params mrs_vpr " + launch + " " + arguments + " 2>/dev/null";
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
  std::map<std::string, std::string> parameters;
  if (!pipe) return parameters;
  const std::string prefix = "/mrs_vpr/";
  char line[4096];
  while (std::fgets(line, sizeof(line), pipe.get()) != nullptr) {
    std::string text(line);
    while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
    const std::size_t colon = text.find(": ");
    if (text.rfind(prefix, 0) != 0 || colon == std::string::npos) continue;
    parameters[text.substr(prefix.size(), colon - prefix.size())] = text.substr(colon + 2);
  }
  return parameters;
}

class LaunchFilesTest : public ::testing::TestWithParam<std::string> {
 protected:
  LaunchFilesTest() : folder_("mrs_vpr_launch_files_test") {
    std::ofstream(folder_.path("robot.yaml")) << "min_travel: 0.7\n"
                                                 "odom_frame: world\n"
                                                 "auto_query_period: 2.5\n"
                                                 "image_transport: compressed\n"
                                                 "database: /maps/robot.db\n";
  }
  /// The launch file under test with the arguments it always needs.
  std::string launch() const { return GetParam() == "replay.launch" ? "replay.launch bag:=/tmp/run.bag" : GetParam(); }
  std::string robotParams() const { return "params:=" + folder_.path("robot.yaml"); }

  mrs_vpr::testing_support::TemporaryFolder folder_;
};

TEST_P(LaunchFilesTest, WithoutArgumentsTheDefaultParameterFileDecides) {
  const auto parameters = nodeParameters(launch(), "");
  ASSERT_FALSE(parameters.empty()) << "roslaunch --dump-params failed for " << GetParam();
  EXPECT_EQ(parameters.at("min_travel"), "0.0");
  EXPECT_EQ(parameters.at("odom_frame"), "odom");
  EXPECT_EQ(parameters.at("base_frame"), "base_link");
  EXPECT_EQ(parameters.at("auto_query_period"), "0.0");
  EXPECT_EQ(parameters.at("database"), "''");
  EXPECT_EQ(parameters.count("image_transport"), 0U);  // The node's default, raw.
}

TEST_P(LaunchFilesTest, AParameterFilesValuesAreKept) {
  const auto parameters = nodeParameters(launch(), robotParams());
  ASSERT_FALSE(parameters.empty()) << "roslaunch --dump-params failed for " << GetParam();
  EXPECT_EQ(parameters.at("min_travel"), "0.7");
  EXPECT_EQ(parameters.at("odom_frame"), "world");
  EXPECT_EQ(parameters.count("base_frame"), 0U);  // Not in the file: the node's default.
  EXPECT_EQ(parameters.at("auto_query_period"), "2.5");
  EXPECT_EQ(parameters.at("image_transport"), "compressed");
  EXPECT_EQ(parameters.at("database"), "/maps/robot.db");
}

TEST_P(LaunchFilesTest, ArgumentsGivenOverrideTheParameterFile) {
  const auto parameters =
      nodeParameters(launch(), robotParams() + " min_travel:=1 base_frame:=base_footprint auto_query_period:=1.5" +
                                   " image_transport:=raw database:=/maps/other.db");
  ASSERT_FALSE(parameters.empty()) << "roslaunch --dump-params failed for " << GetParam();
  EXPECT_EQ(parameters.at("min_travel"), "1.0");
  EXPECT_EQ(parameters.at("odom_frame"), "world");
  EXPECT_EQ(parameters.at("base_frame"), "base_footprint");
  EXPECT_EQ(parameters.at("auto_query_period"), "1.5");
  EXPECT_EQ(parameters.at("image_transport"), "raw");
  EXPECT_EQ(parameters.at("database"), "/maps/other.db");
}

INSTANTIATE_TEST_SUITE_P(BothLaunchFiles, LaunchFilesTest, ::testing::Values("mrs_vpr.launch", "replay.launch"),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           return info.param == "replay.launch" ? std::string("Replay") : std::string("Node");
                         });

}  // namespace

// The launch files' arguments: a parameter file's values stay unless an argument is given
// (roslaunch --dump-params), topics are remapped only when asked (roslaunch --args), and an earlier
// launch's parameters are cleared first (roslaunch's loader); every argument is documented
// (roslaunch --ros-args); no master needed.

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "support/temporary_folder.hpp"

namespace {

/// The standard output of `command`, line by line; nothing when it cannot run.
std::vector<std::string> outputLines(const std::string& command) {
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen((command + " 2>/dev/null").c_str(), "r"), pclose);
  std::vector<std::string> lines;
  if (!pipe) return lines;
  char line[4096];
  while (std::fgets(line, sizeof(line), pipe.get()) != nullptr) {
    std::string text(line);
    while (!text.empty() && (text.back() == '\n' || text.back() == '\r')) text.pop_back();
    lines.push_back(text);
  }
  return lines;
}

/// The node's parameters as `roslaunch --dump-params mrs_vpr LAUNCH ARGUMENTS` sets them, by name
/// (without the node's namespace); empty when roslaunch fails.
std::map<std::string, std::string> nodeParameters(const std::string& launch, const std::string& arguments) {
  std::map<std::string, std::string> parameters;
  const std::string prefix = "/mrs_vpr/";
  for (const std::string& text : outputLines("roslaunch --dump-params mrs_vpr " + launch + " " + arguments)) {
    const std::size_t colon = text.find(": ");
    if (text.rfind(prefix, 0) != 0 || colon == std::string::npos) continue;
    parameters[text.substr(prefix.size(), colon - prefix.size())] = text.substr(colon + 2);
  }
  return parameters;
}

/// The node's remappings (FROM:=TO on its command line, as `roslaunch --args` prints it), by FROM;
/// the special arguments such as __name are left out. Empty when roslaunch fails.
std::map<std::string, std::string> nodeRemappings(const std::string& launch, const std::string& arguments) {
  std::map<std::string, std::string> remappings;
  for (const std::string& text : outputLines("roslaunch --args /mrs_vpr mrs_vpr " + launch + " " + arguments)) {
    std::istringstream words(text);
    std::string word;
    while (words >> word) {
      const std::size_t arrow = word.find(":=");
      if (arrow == std::string::npos || word.rfind("__", 0) == 0) continue;
      remappings[word.substr(0, arrow)] = word.substr(arrow + 2);
    }
  }
  return remappings;
}

/// The namespaces roslaunch empties before it sets the parameters of `roslaunch mrs_vpr LAUNCH`
/// (its nodes' clear_params), as its own loader reads the file; empty when it cannot.
std::vector<std::string> clearedNamespaces(const std::string& launch) {
  const std::string script = R"(
import sys, roslaunch.config, roslaunch.rlutil
files = roslaunch.rlutil.resolve_launch_arguments(["mrs_vpr", sys.argv[1]])
sys.argv = sys.argv[:1] + sys.argv[2:]  # The launch arguments (name:=value), where roslaunch reads them.
print("\n".join(roslaunch.config.load_config_default(files, None).clear_params))
)";
  return outputLines("/usr/bin/python3 -c '" + script + "' " + launch);
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

TEST_P(LaunchFilesTest, WithoutArgumentsTheDefaultParameterFileDecidesButContinuousModeIsOnEverySecond) {
  const auto parameters = nodeParameters(launch(), "");
  ASSERT_FALSE(parameters.empty()) << "roslaunch --dump-params failed for " << GetParam();
  EXPECT_EQ(parameters.at("min_travel"), "0.0");
  EXPECT_EQ(parameters.at("odom_frame"), "odom");
  EXPECT_EQ(parameters.at("base_frame"), "base_link");
  // image:= alone gives loop closures: continuous mode every second, not the node's 0 (off).
  EXPECT_EQ(parameters.at("auto_query_period"), "1.0");
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

TEST_P(LaunchFilesTest, AParameterFileWithoutContinuousModeLeavesItToTheNode) {
  std::ofstream(folder_.path("quiet.yaml")) << "min_travel: 0.7\n";
  const auto parameters = nodeParameters(launch(), "params:=" + folder_.path("quiet.yaml"));
  ASSERT_FALSE(parameters.empty()) << "roslaunch --dump-params failed for " << GetParam();
  EXPECT_EQ(parameters.at("min_travel"), "0.7");
  EXPECT_EQ(parameters.count("auto_query_period"), 0U);  // The node's default: off.
  // Continuous mode is still one argument away.
  EXPECT_EQ(nodeParameters(launch(), "params:=" + folder_.path("quiet.yaml") + " auto_query_period:=1").at(
                "auto_query_period"),
            "1.0");
}

TEST_P(LaunchFilesTest, ContinuousModeIsSwitchedOffByItsArgument) {
  EXPECT_EQ(nodeParameters(launch(), "auto_query_period:=0").at("auto_query_period"), "0.0");
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

TEST_P(LaunchFilesTest, WhatAnEarlierLaunchLeftOnTheMasterIsClearedFirst) {
  // Otherwise a parameter that neither the file nor an argument sets keeps an earlier launch's value:
  // its image transport (the node then waits for frames on another topic), its map database.
  const std::vector<std::string> cleared = clearedNamespaces(launch());
  EXPECT_EQ(cleared, std::vector<std::string>{"/mrs_vpr/"});
}

TEST_P(LaunchFilesTest, LoopClosureStampsStayOnTheNodesOwnTopicUnlessATopicIsGiven) {
  const auto remappings = nodeRemappings(launch(), "");
  ASSERT_EQ(remappings.count("image"), 1U) << "roslaunch --args failed for " << GetParam();
  EXPECT_EQ(remappings.count("~loop_closure_stamps"), 0U);
}

TEST_P(LaunchFilesTest, LoopClosureStampsGoWhereTheArgumentSays) {
  const auto remappings = nodeRemappings(launch(), "loop_closure_stamps_topic:=/lio_loop/loop_closure_detection");
  ASSERT_EQ(remappings.count("image"), 1U) << "roslaunch --args failed for " << GetParam();
  ASSERT_EQ(remappings.count("~loop_closure_stamps"), 1U);
  EXPECT_EQ(remappings.at("~loop_closure_stamps"), "/lio_loop/loop_closure_detection");
}

TEST_P(LaunchFilesTest, EveryArgumentIsDocumentedAndOnlyTheBagIsRequired) {
  // roslaunch's ros-args option lists an argument whose default is empty as required: each such
  // argument's doc must then say that it is optional.
  const std::vector<std::string> lines = outputLines("roslaunch --ros-args mrs_vpr " + launch());
  ASSERT_FALSE(lines.empty()) << "roslaunch --ros-args failed for " << GetParam();
  bool required = false;
  int arguments = 0;
  for (const std::string& line : lines) {
    if (line == "Required Arguments:" || line == "Optional Arguments:") {
      required = line == "Required Arguments:";
      continue;
    }
    ++arguments;
    EXPECT_EQ(line.find("undocumented"), std::string::npos) << line;
    const std::string name = line.substr(2, line.find_first_of(" :", 2) - 2);
    if (required && name != "bag") EXPECT_NE(line.find(": Optional"), std::string::npos) << line;
  }
  EXPECT_GE(arguments, 10);
}

TEST(ReplayLaunch, TheBagsClockIsTheMastersEvenInANamespace) {
  // Included in a robot's namespace, the replay still sets /use_sim_time, which roscpp reads, and
  // publishes the bag's clock on /clock, which it follows; not /robot/use_sim_time and /robot/clock.
  const std::string replay = "replay.launch bag:=/tmp/run.bag clock:=true";
  bool global_sim_time = false;
  for (const std::string& text : outputLines("ROS_NAMESPACE=robot roslaunch --dump-params mrs_vpr " + replay)) {
    EXPECT_EQ(text.find("/robot/use_sim_time"), std::string::npos) << text;
    global_sim_time = global_sim_time || text == "/use_sim_time: true";
  }
  EXPECT_TRUE(global_sim_time);
  const std::vector<std::string> player =
      outputLines("ROS_NAMESPACE=robot roslaunch --args /robot/player mrs_vpr " + replay);
  ASSERT_FALSE(player.empty());
  EXPECT_NE(player.front().find(" clock:=/clock"), std::string::npos) << player.front();
}

INSTANTIATE_TEST_SUITE_P(BothLaunchFiles, LaunchFilesTest, ::testing::Values("mrs_vpr.launch", "replay.launch"),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           return info.param == "replay.launch" ? std::string("Replay") : std::string("Node");
                         });

}  // namespace

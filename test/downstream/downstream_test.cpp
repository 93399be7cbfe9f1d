// A package that depends on mrs_vpr, built against this package's devel space as a user builds it
// (test/downstream/mrs_vpr_downstream): it compiles with the exported include folders, runs, and links
// the core without ROS.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

#include <opencv2/imgcodecs.hpp>

#include "mrs_vpr/synthetic_route.hpp"

namespace {

namespace fs = std::filesystem;

struct Outcome {
  int status = -1;
  std::string output;  // stdout and stderr
};

// A path as one word of the command that run() hands to bash in single quotes.
std::string quoted(const std::string& path) { return "\"" + path + "\""; }

// Runs a bash command in the devel space's environment.
Outcome run(const std::string& command) {
  const std::string line = "bash -c 'source " + quoted(MRS_VPR_DEVEL_SETUP) + " && " + command + "' 2>&1";
  Outcome result;
  FILE* pipe = popen(line.c_str(), "r");
  if (pipe == nullptr) return result;
  char buffer[4096];
  std::size_t read = 0;
  while ((read = std::fread(buffer, 1, sizeof(buffer), pipe)) > 0) result.output.append(buffer, read);
  const int status = pclose(pipe);
  result.status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return result;
}

class DownstreamPackage : public ::testing::Test {
 protected:
  // One build for every test of the suite.
  static void SetUpTestSuite() {
    std::string pattern = (fs::temp_directory_path() / "mrs_vpr_downstream.XXXXXX").string();
    if (mkdtemp(pattern.data()) == nullptr) return;
    workspace_ = pattern;
    const std::string script = quoted(MRS_VPR_DOWNSTREAM_DIR "/build_downstream.sh");
    const std::string package = quoted(MRS_VPR_DOWNSTREAM_DIR "/mrs_vpr_downstream");
    const std::string setup = quoted(MRS_VPR_DEVEL_SETUP);
    build_ = run(script + " " + setup + " " + package + " " + quoted(workspace_.string()));
    executable_ = workspace_ / "devel" / "lib" / "mrs_vpr_downstream" / "mrs_vpr_downstream";
  }

  static void TearDownTestSuite() {
    std::error_code ignored;
    if (!workspace_.empty()) fs::remove_all(workspace_, ignored);
  }

  void SetUp() override {
    ASSERT_FALSE(workspace_.empty()) << "could not create a temporary folder";
    ASSERT_EQ(build_.status, 0) << build_.output;
    ASSERT_TRUE(fs::is_regular_file(executable_)) << executable_ << " was not built\n" << build_.output;
  }

  static fs::path workspace_;
  static fs::path executable_;
  static Outcome build_;
};

fs::path DownstreamPackage::workspace_;
fs::path DownstreamPackage::executable_;
Outcome DownstreamPackage::build_;

TEST_F(DownstreamPackage, BuildsAgainstTheDevelSpace) {}

TEST_F(DownstreamPackage, FindsTheRightPlaceInFoldersOfImages) {
  // The README's example on two traversals of a generated route written as image folders.
  mrs_vpr::SyntheticRouteParams params;
  // The revisit starts past the map's first 60 or so keyframes, which are chosen before the map has
  // learnt its own scale of appearance change (appearance_keyframes.hpp).
  params.reference_frames = 600;
  params.query_frames = 200;
  params.start_place = 300.0;
  // Frames the size of a small camera's, so that shrinking them to the descriptor averages their noise.
  params.image_width = 320;
  params.image_height = 160;
  const mrs_vpr::SyntheticRoute route = mrs_vpr::generateSyntheticRoute(params);
  for (const auto& [folder, images] : {std::pair{"reference", &route.reference}, std::pair{"query", &route.query}}) {
    fs::create_directories(workspace_ / folder);
    for (std::size_t i = 0; i < images->size(); ++i) {
      char name[32];
      std::snprintf(name, sizeof(name), "%05zu.png", i);
      ASSERT_TRUE(cv::imwrite((workspace_ / folder / name).string(), (*images)[i]));
    }
  }
  const Outcome program = run(quoted(executable_.string()) + " " + quoted((workspace_ / "reference").string()) + " " +
                              quoted((workspace_ / "query").string()) + " 40");
  ASSERT_EQ(program.status, 0) << program.output;
  int localised = -1;
  int answer = -1;
  ASSERT_EQ(std::sscanf(program.output.c_str(), "query frame %d is reference frame %d", &localised, &answer), 2)
      << program.output;
  // The middle keyframe of the last 40 frames (every frame of this route is a keyframe but the first few).
  EXPECT_GE(localised, 160);
  EXPECT_LE(localised, 199);
  const int truth = route.query_to_reference.at(static_cast<std::size_t>(localised));
  EXPECT_LE(std::abs(answer - truth), 3) << program.output << "truth " << truth;
}

TEST_F(DownstreamPackage, ExplainsItsUsage) {
  const Outcome program = run(quoted(executable_.string()));
  EXPECT_EQ(program.status, 2) << program.output;
  EXPECT_NE(program.output.find("usage: mrs_vpr_downstream REFERENCE_DIR QUERY_DIR"), std::string::npos);
}

TEST_F(DownstreamPackage, LinksTheCoreAndNoRos) {
  const Outcome ldd = run("ldd " + quoted(executable_.string()));
  ASSERT_EQ(ldd.status, 0) << ldd.output;
  EXPECT_NE(ldd.output.find("libmrs_vpr_core.so"), std::string::npos) << ldd.output;
  EXPECT_NE(ldd.output.find("libopencv_core.so"), std::string::npos) << ldd.output;
  EXPECT_EQ(ldd.output.find("not found"), std::string::npos) << ldd.output;
  for (const char* library : {"libroscpp.so", "librosbag", "libnodeletlib", "libclass_loader", "libcv_bridge",
                              "libimage_transport", "libmrs_vpr_ros", "libmrs_vpr_nodelet", "libmrs_vpr_bag",
                              "libmrs_vpr_evaluation"}) {
    EXPECT_EQ(ldd.output.find(library), std::string::npos) << library << " is linked:\n" << ldd.output;
  }
}

}  // namespace

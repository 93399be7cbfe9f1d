#pragma once

// The command-line tools run as a user runs them, on a generated route written as image folders
// (route_folders.hpp) once for each suite, in a temporary folder.

#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "route_folders.hpp"
#include "support/command_run.hpp"
#include "support/temporary_folder.hpp"

namespace mrs_vpr {
namespace testing_support {

class RouteToolsTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    folder_ = std::make_unique<TemporaryFolder>("mrs_vpr_tools_test");
    writeRouteFolders(folder_->root());
  }
  static void TearDownTestSuite() { folder_.reset(); }

  /// Runs `command` (arguments already quoted) and captures its exit status, stdout and stderr.
  static CommandResult run(const std::string& command) { return runCommand(command, *folder_); }

  /// mrs_vpr_eval and build_map as these tests use them on the generated route: every frame a keyframe,
  /// as they count its frames, and the thumbnail front end its textures were made for
  /// (support/route_fixture.hpp). Both defaults have tests of their own.
  static std::string eval(const std::string& arguments) {
    return std::string(MRS_VPR_EVAL_PATH) + " --min-appearance-change 0 --descriptor thumbnail " + arguments;
  }
  static std::string buildMap() {
    return std::string(BUILD_MAP_PATH) + " --min-appearance-change 0 --descriptor thumbnail";
  }
  static std::string path(const std::string& child) { return folder_->path(child); }
  static const std::filesystem::path& root() { return folder_->root(); }

  /// A folder of 20000 frames, one image under many names: a tool reading it is still at work a
  /// moment after it began its output.
  static std::string manyFrames() {
    const std::string folder = path("many");
    if (!std::filesystem::exists(folder)) {
      std::filesystem::create_directory(folder);
      for (int i = 0; i < 20000; ++i) {
        const std::string name = folder + "/" + std::to_string(100000 + i) + ".png";
        std::filesystem::create_symlink(path("reference/00000.png"), name);
      }
    }
    return folder;
  }

  /// Expects exit code 1 and one error line on stderr, the last, that contains `text`. An error found
  /// only once the traversals are read (a sequence longer than the map) follows the tool's progress
  /// lines: its header and its indented lines about what it read.
  static void expectError(const std::string& arguments, const std::string& text) {
    const CommandResult result = run(eval(arguments));
    EXPECT_EQ(result.status, 1) << arguments << "\n" << result.err;
    std::istringstream lines(result.err);
    std::vector<std::string> errors;
    std::string line;
    std::string last_line;
    while (std::getline(lines, line)) {
      last_line = line;
      if (line.rfind("mrs_vpr_eval: error: ", 0) == 0) {
        errors.push_back(line);
      } else {
        const bool progress = line.rfind("  ", 0) == 0 || line.rfind("mrs_vpr_eval: ", 0) == 0;
        EXPECT_TRUE(progress) << "neither progress nor the error: '" << line << "'\n" << result.err;
      }
    }
    ASSERT_EQ(errors.size(), 1U) << result.err;
    EXPECT_EQ(errors.front(), last_line) << result.err;
    EXPECT_NE(last_line.find(text), std::string::npos) << result.err;
  }

 private:
  inline static std::unique_ptr<TemporaryFolder> folder_;
};

}  // namespace testing_support
}  // namespace mrs_vpr

#pragma once

// The command-line tools run as a user runs them, on a generated route written as image folders
// (route_folders.hpp) once for each suite, in a temporary folder.

#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <string>

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

  /// Expects exit code 1 and exactly one line on stderr that contains `text`.
  static void expectError(const std::string& arguments, const std::string& text) {
    const CommandResult result = run(eval(arguments));
    EXPECT_EQ(result.status, 1) << arguments << "\n" << result.err;
    EXPECT_NE(result.err.find(text), std::string::npos) << result.err;
    const std::string last_line = result.err.substr(result.err.rfind('\n', result.err.size() - 2) + 1);
    EXPECT_EQ(last_line.rfind("mrs_vpr_eval: error: ", 0), 0U) << result.err;
    EXPECT_NE(last_line.find(text), std::string::npos) << result.err;
  }

 private:
  inline static std::unique_ptr<TemporaryFolder> folder_;
};

}  // namespace testing_support
}  // namespace mrs_vpr

#pragma once

// A map whose writer died after a commit, as a node killed with kill -9 leaves it.

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "mrs_vpr/parameters.hpp"
#include "mrs_vpr/store/map_database.hpp"

namespace mrs_vpr {
namespace testing_support {

/// Writes `committed` to the map at `file` in a child process that exits without closing it: no
/// checkpoint, so the frames are committed in the log left beside the file. Use with ASSERT_NO_FATAL_FAILURE.
inline void crashAfterCommitting(const std::string& file, const std::vector<StoredFrame>& committed,
                                 const DescriptorParams& params) {
  const pid_t child = fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    MapDatabase database(file, params);
    database.append(committed);
    _exit(0);
  }
  int status = 0;
  waitpid(child, &status, 0);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  ASSERT_TRUE(std::filesystem::exists(file + "-wal"));
}

}  // namespace testing_support
}  // namespace mrs_vpr

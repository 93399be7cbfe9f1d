#pragma once

#include <sys/wait.h>

#include <cstdlib>
#include <string>

#include "support/temporary_folder.hpp"

namespace mrs_vpr {
namespace testing_support {

/// What a command-line tool did: its exit status (-1 when it did not exit normally), stdout and stderr.
struct CommandResult {
  int status = -1;
  std::string out;
  std::string err;
};

/// Runs `command` (arguments already quoted) through the shell, as a user would, with its output in
/// `scratch` (stdout.txt and stderr.txt, overwritten by the next command).
inline CommandResult runCommand(const std::string& command, const TemporaryFolder& scratch) {
  const std::string out = scratch.path("stdout.txt");
  const std::string err = scratch.path("stderr.txt");
  const int raw = std::system((command + " >'" + out + "' 2>'" + err + "'").c_str());
  return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, fileContents(out), fileContents(err)};
}

/**
 * A shell command that starts `command` in the background and sends it SIGTERM, as a supervisor
 * stopping it (or a user's Ctrl-C) would, once `started` exists (after 10 s at most); its status is
 * the command's. SIGTERM, since a shell that is not interactive starts a background command with
 * SIGINT ignored.
 */
inline std::string stoppedOnceExists(const std::string& command, const std::string& started) {
  return "{ " + command + " & pid=$!; for i in $(seq 1000); do [ -e '" + started +
         "' ] && break; sleep 0.01; done; kill -TERM $pid; wait $pid; }";
}

}  // namespace testing_support
}  // namespace mrs_vpr

#pragma once

// The file a path names through symbolic links, as the kernel follows them: what a map, a saved map or
// a tool's output named through a link is written to, the link staying in place.

#include <filesystem>
#include <string>
#include <system_error>

namespace mrs_vpr {

/// Why linkedFile() found no file, in a user's words after "'PATH' is ".
inline constexpr const char* kNoLinkedFile =
    "a link that leads to no file (a loop of links, or a chain of more than 40)";

/// The file that `path` names through a chain of symbolic links (at most 40, as the kernel follows),
/// also one not written yet; `path` itself when it is no link; empty for a loop of links, a longer
/// chain or a link that cannot be read.
inline std::string linkedFile(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code error;
  fs::path target = path;
  constexpr int kMostLinks = 40;  // As the kernel follows (ELOOP).
  for (int hops = 0; fs::is_symlink(target, error); ++hops) {
    if (hops == kMostLinks) return "";
    const fs::path next = fs::read_symlink(target, error);
    if (error) return "";
    target = next.is_absolute() ? next : target.parent_path() / next;
  }
  return target.string();
}

}  // namespace mrs_vpr

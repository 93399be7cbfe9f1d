#pragma once

// A tool's outputs kept apart from what it reads, so that no run writes over its own input: a bag,
// a map, an image of a folder, or new files in an image folder that the next run would read as frames;
// and written only into folders that exist.

#include <algorithm>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

namespace mrs_vpr {
namespace tools {

/// A path a tool reads or writes, with the option that named it (for messages).
struct NamedPath {
  std::string option;  ///< e.g. "--images"
  std::string path;    ///< empty: not given
};

/// `path` with every symbolic link and dot resolved, as far as it exists; empty when it cannot be.
inline std::filesystem::path resolved(const std::string& path) {
  std::error_code error;
  std::filesystem::path absolute = std::filesystem::weakly_canonical(path, error);
  return error ? std::filesystem::path() : absolute;
}

/// `path` without dots and without a trailing '/', so that its parent is the folder it lies in.
inline std::filesystem::path normalPath(const std::string& path) {
  std::filesystem::path normal = std::filesystem::path(path).lexically_normal();
  if (normal.filename().empty()) normal = normal.parent_path();
  return normal;
}

/// Throws std::invalid_argument, naming `option`, when the folder that is to hold `path` does not
/// exist: a tool creates only its own output, not a mistyped tree of folders.
inline void requireParentFolder(const std::string& option, const std::string& path) {
  const std::filesystem::path parent = normalPath(path).parent_path();
  if (!parent.empty() && !std::filesystem::exists(parent)) {
    throw std::invalid_argument(option + " '" + path + "': there is no folder " + parent.string());
  }
}

/// Where a file written at `path` lands: its folder resolved, its own name kept, since writing replaces
/// a symbolic link there rather than its target.
inline std::filesystem::path writtenAt(const std::string& path) {
  const std::filesystem::path name = normalPath(path);
  const std::filesystem::path folder = resolved(name.parent_path().empty() ? "." : name.parent_path().string());
  return folder.empty() ? folder : folder / name.filename();
}

/// Whether `inner` lies inside the folder `outer` (both resolved).
inline bool liesInside(const std::filesystem::path& inner, const std::filesystem::path& outer) {
  const auto outer_parts = std::distance(outer.begin(), outer.end());
  const auto inner_parts = std::distance(inner.begin(), inner.end());
  return inner_parts > outer_parts && std::equal(outer.begin(), outer.end(), inner.begin());
}

/**
 * Throws std::invalid_argument, naming both options, when `output` is one of `inputs` or lies inside
 * an input folder. Called before any work, so that the inputs stay as they were. An output that is a
 * symbolic link is checked both as the link (which a tool may replace) and as what it points to
 * (which a tool that writes through it, or into a linked folder, changes).
 */
inline void requireApartFromInputs(const NamedPath& output, const std::vector<NamedPath>& inputs) {
  if (output.path.empty()) return;
  std::vector<std::filesystem::path> written_places{writtenAt(output.path)};
  std::error_code no_link;
  if (std::filesystem::is_symlink(std::filesystem::symlink_status(normalPath(output.path), no_link))) {
    written_places.push_back(resolved(output.path));
  }
  for (const std::filesystem::path& written : written_places) {
    if (written.empty()) continue;  // The output's own checks name what is wrong with it.
    for (const NamedPath& input : inputs) {
      if (input.path.empty()) continue;
      const std::filesystem::path read = resolved(input.path);
      if (read.empty()) continue;
      if (written == read || written == writtenAt(input.path)) {
        throw std::invalid_argument(output.option + " '" + output.path + "' is what " + input.option +
                                    " reads: write it elsewhere");
      }
      std::error_code ignored;
      if (std::filesystem::is_directory(read, ignored) && liesInside(written, read)) {
        throw std::invalid_argument(output.option + " '" + output.path + "' lies inside the folder '" + input.path +
                                    "' that " + input.option + " reads: write it elsewhere");
      }
    }
  }
}

/// Throws std::invalid_argument when an input lies inside the folder `output`, which the tool replaces
/// as a whole (make_drive --force).
inline void requireNoInputInside(const NamedPath& output, const std::vector<NamedPath>& inputs) {
  const std::filesystem::path replaced = resolved(output.path);
  if (output.path.empty() || replaced.empty()) return;
  for (const NamedPath& input : inputs) {
    const std::filesystem::path read = resolved(input.path);
    if (!input.path.empty() && !read.empty() && liesInside(read, replaced)) {
      throw std::invalid_argument(input.option + " '" + input.path + "' lies inside the folder '" + output.path +
                                  "' that " + output.option + " replaces: write it elsewhere");
    }
  }
}

}  // namespace tools
}  // namespace mrs_vpr

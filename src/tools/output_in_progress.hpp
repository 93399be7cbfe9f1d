#pragma once

// An output written under a temporary name and renamed to its own when complete, so that a failed or
// interrupted run never leaves a file or folder that looks complete.

#include <filesystem>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>

#include "../store/linked_file.hpp"

namespace mrs_vpr {
namespace tools {

/// Whether `path` is a pipe, a device or a link (/dev/stdout), which an output is written into rather
/// than renamed onto: renaming would replace it, and whoever reads it would get nothing.
inline bool writtenInPlace(const std::string& path) {
  std::error_code ignored;
  const std::filesystem::file_status status = std::filesystem::symlink_status(path, ignored);
  return std::filesystem::exists(status) && !std::filesystem::is_regular_file(status);
}

/// The file the link `link` (named by `option`, for messages) points to, through links to links, also
/// one not written yet: an output named through a link replaces that file, not the link, as writing to
/// the link would. Throws std::invalid_argument for a loop.
inline std::string linkTarget(const std::string& option, const std::string& link) {
  const std::string file = linkedFile(link);
  if (file.empty()) throw std::invalid_argument(option + " '" + link + "' is " + kNoLinkedFile);
  return std::filesystem::weakly_canonical(file).string();
}

/// Throws std::invalid_argument when `path` (named by `option`) exists and is neither a regular file
/// nor a folder (a device, a pipe, a socket): an output renamed onto it when complete would replace it.
inline void requireNoSpecialFile(const std::string& option, const std::string& path) {
  std::error_code ignored;
  const std::filesystem::file_status status = std::filesystem::status(path, ignored);
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status) &&
      !std::filesystem::is_directory(status)) {
    throw std::invalid_argument(option + " '" + path + "' is no regular file (a device, a pipe or a socket), which " +
                                "the finished output would replace: name a file");
  }
}

/// `path`.part while it is written; removed (file or folder) unless commit() renamed it to `path`.
class OutputInProgress {
 public:
  explicit OutputInProgress(std::string path) : path_(std::move(path)), temporary_(path_ + ".part") {}
  OutputInProgress(const OutputInProgress&) = delete;
  OutputInProgress& operator=(const OutputInProgress&) = delete;
  ~OutputInProgress() {
    std::error_code ignored;
    if (!committed_) std::filesystem::remove_all(temporary_, ignored);
  }

  const std::string& temporary() const { return temporary_; }
  /// temporary() as a new, empty folder: what an interrupted earlier run left there is removed.
  const std::string& emptyFolder() const {
    std::filesystem::remove_all(temporary_);
    std::filesystem::create_directories(temporary_);
    return temporary_;
  }
  void commit() {
    std::filesystem::rename(temporary_, path_);
    committed_ = true;
  }

 private:
  std::string path_;
  std::string temporary_;
  bool committed_ = false;
};

}  // namespace tools
}  // namespace mrs_vpr

#include "map_path.hpp"

#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cstring>
#include <filesystem>
#include <string>

namespace mrs_vpr {

std::string nulByteProblem(const std::string& path) {
  const std::size_t nul = path.find('\0');
  if (nul == std::string::npos) return "";
  return "map path '" + path.substr(0, nul) + "' is followed by a NUL byte (at byte " + std::to_string(nul) +
         "), which would end it there: no file name holds one";
}

bool folderIsWritable(const std::string& path) {
  std::error_code ignored;
  const std::filesystem::path folder = std::filesystem::absolute(path, ignored).parent_path();
  return ::access(folder.c_str(), W_OK | X_OK) == 0;
}

std::string mapPathProblem(const std::string& path, std::size_t suffix) {
  namespace fs = std::filesystem;
  std::error_code error;
  if (path.empty()) return "no path given";
  const fs::file_status status = fs::status(path, error);
  if (fs::is_directory(status)) return "it is a folder, not a map file (give the path of a file)";
  if (fs::exists(status)) return fs::is_regular_file(status) ? "" : "it is not a regular file";
  // The file a link names is created, not the link: that file's folder is the one that counts.
  const std::string file = linkedFile(path);
  if (file.empty()) return std::string("it is ") + kNoLinkedFile;
  if (file.size() + suffix >= PATH_MAX) {
    return "the path is " + std::to_string(file.size()) + " bytes long, too long for this system (at most " +
           std::to_string(PATH_MAX - 1 - suffix) + ")";
  }
  const fs::path absolute = fs::absolute(file, error);
  const fs::path folder = absolute.parent_path();
  if (!fs::is_directory(folder, error)) {
    return "there is no folder " + folder.string() +
           (beginsWithHome(path) ? " (~ is not expanded to a home folder here: give the path in full)" : "");
  }
  // SQLite's only word for this would be "unable to open database file (No such file or directory)".
  if (!folderIsWritable(absolute.string())) {
    return "the folder " + folder.string() + " cannot be written to (" + std::strerror(errno) + ")";
  }
  const long name_max = ::pathconf(folder.c_str(), _PC_NAME_MAX);
  const std::size_t longest = name_max > 0 ? static_cast<std::size_t>(name_max) : NAME_MAX;
  const std::size_t name = absolute.filename().string().size();
  if (name + suffix > longest) {
    return "its file name is " + std::to_string(name) + " bytes long, too long for this file system: at most " +
           std::to_string(longest - suffix) + " (" + std::to_string(longest) + " less the " + std::to_string(suffix) +
           " of the files written beside it)";
  }
  return "";
}

}  // namespace mrs_vpr

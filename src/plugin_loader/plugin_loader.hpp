#pragma once

#include <string>

namespace mrs_vpr {
namespace plugins {

/**
 * Opens the plugin library `file` and returns what its unmangled, argument-less function `entry`
 * returns: the plugin's table of functions. The plugin is looked for beside this library (where it is
 * built and installed), then where the dynamic loader looks (LD_LIBRARY_PATH, a devel or install space).
 * Throws std::runtime_error("cannot load the <what>: <the loader's reasons>") when it cannot be opened
 * or has no `entry`.
 *
 * A plugin keeps heavy libraries (OpenCV's image codecs, rosbag) out of a program's start-up until the
 * first call that needs them. Callers keep the table in a function-local static (see load), so that a
 * plugin is opened once, also when several threads ask for it at once.
 */
const void* loadTable(const char* file, const char* entry, const std::string& what);

/// loadTable typed as the plugin's table.
template <typename Table>
const Table& load(const char* file, const char* entry, const std::string& what) {
  return *static_cast<const Table*>(loadTable(file, entry, what));
}

}  // namespace plugins
}  // namespace mrs_vpr

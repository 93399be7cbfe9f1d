#pragma once

// Whether a path can name a map file, said in a user's words before SQLite tries it (SQLite itself
// would say only "unable to open database file").

#include <cstddef>
#include <string>

#include "linked_file.hpp"

namespace mrs_vpr {

/// The longest suffix SQLite and MapDatabase add to a map's name for the files beside it.
constexpr std::size_t kDatabaseSuffix = sizeof("-journal") - 1;
/// ... and to a saved map's: PersistentMap writes `path`.build, whose journal is `path`.build-journal.
constexpr std::size_t kSaveSuffix = sizeof(".build-journal") - 1;

/// What SQLite keeps beside a database, and reads into whatever file next bears its name.
inline constexpr const char* kCompanionSuffixes[] = {"-wal", "-shm", "-journal"};

/// Whether `path` begins with ~, which a shell expands to a home folder; a path sent in a service
/// request, or read from a parameter, reaches this process as it was typed.
inline bool beginsWithHome(const std::string& path) { return path == "~" || path.rfind("~/", 0) == 0; }

/// Whether this process may create files in the folder of `path`; when not, errno says why (access()).
bool folderIsWritable(const std::string& path);

/**
 * Why `path` cannot name a map file (one that SQLite then names `path` + up to `suffix` bytes beside
 * it); empty when it can. A file that exists must be a regular file; otherwise its folder (for a link,
 * that of linkedFile(): SQLite opens that file, and a save writes it) must exist and be writable by
 * this process, and the file system must allow its name.
 */
std::string mapPathProblem(const std::string& path, std::size_t suffix);

/**
 * Empty, or a whole message when `path` holds a NUL byte: every system call would read the path only
 * up to it, and so open another file. The message quotes the path up to that byte only, since a
 * message is itself cut there on its way to the user.
 */
std::string nulByteProblem(const std::string& path);

/// `path` as SQLite opens the file of that name: ":memory:" and "file:..." would otherwise be a
/// database in memory and a URI, which a user who names a map file never means.
inline std::string sqliteFileName(const std::string& path) {
  const bool special = path == ":memory:" || path.rfind("file:", 0) == 0;
  return special ? "./" + path : path;
}

}  // namespace mrs_vpr

// Writing a map database to a new file: the checks on the target, the unfinished copy beside it,
// and the snapshot of every page at one moment (MapDatabase::backupTo).

#include <sqlite3.h>
#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

#include "mrs_vpr/store/map_database.hpp"
#include "mrs_vpr/store/map_hold.hpp"
#include "map_path.hpp"
#include "sqlite_problem.hpp"

namespace mrs_vpr {

namespace {

[[noreturn]] void refuseSave(const std::string& path, const std::string& problem) {
  throw MapDatabaseError("cannot save the map to '" + path + "': " + problem);
}

}  // namespace

void MapDatabase::removeCompanions(const std::string& path) {
  std::error_code ignored;
  for (const char* suffix : kCompanionSuffixes) std::filesystem::remove(path + suffix, ignored);
}

void MapDatabase::checkNotHeld(const std::string& path) { const MapHold hold(path); }

bool MapDatabase::isSqliteFile(const std::string& path) {
  static constexpr char kSqliteHeader[] = "SQLite format 3";  // With its NUL: the first 16 bytes.
  std::error_code error;
  if (!std::filesystem::is_regular_file(path, error)) return false;
  std::string head(sizeof(kSqliteHeader), '\0');
  std::ifstream file(path, std::ios::binary);
  return file.read(head.data(), static_cast<std::streamsize>(head.size())) &&
         head == std::string(kSqliteHeader, sizeof(kSqliteHeader));
}

void MapDatabase::removeUnfinished(const std::string& part, const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code error;
  const fs::file_status status = fs::symlink_status(part, error);
  if (fs::exists(status)) {
    // An empty file, or an SQLite database that is no link to one.
    const bool unfinished =
        fs::is_regular_file(status) && (fs::file_size(part, error) == 0 || isSqliteFile(part));
    if (!unfinished) {
      refuseSave(path, "'" + part + "', which the map is written to on its way there, is a folder or a file " +
                           "other than an unfinished map (remove it or choose another name)");
    }
    fs::remove(part, error);
  }
  removeCompanions(part);
}

void MapDatabase::makeSelfContained() {
  std::string mode;
  char* error = nullptr;
  const auto keepMode = [](void* result, int, char** values, char**) {
    *static_cast<std::string*>(result) = values[0] != nullptr ? values[0] : "";
    return 0;
  };
  if (sqlite3_exec(db_, "PRAGMA journal_mode = DELETE", keepMode, &mode, &error) != SQLITE_OK) {
    sqlite3_free(error);
    fail("its log cannot be copied into it (" + lastProblem(db_) + ")");
  }
  // SQLite keeps WAL mode, without an error, when the log cannot be copied in.
  if (mode != "delete") fail("its log cannot be copied into it (the journal stays '" + mode + "')");
}

void MapDatabase::checkSaveTarget(const std::string& path) {
  std::error_code error;
  const std::string nul = nulByteProblem(path);
  if (!nul.empty()) throw MapDatabaseError("cannot save the map: " + nul);
  if (path.empty()) refuseSave(path, "no path given");
  if (std::filesystem::is_directory(path, error)) {
    refuseSave(path, "it is a folder (give the path of a new file in it, such as " +
                         (std::filesystem::path(path) / "map.db").string() + ")");
  }
  if (std::filesystem::exists(path, error)) {
    refuseSave(path, "the file exists (a map is never overwritten: remove it or choose another name)");
  }
  // Beside the file written, which through a link is the file it names.
  const std::string file = linkedFile(path);
  if (file.empty()) refuseSave(path, std::string("it is ") + kNoLinkedFile);
  for (const char* suffix : kCompanionSuffixes) {
    if (std::filesystem::exists(file + suffix, error)) {
      refuseSave(path, "'" + file + suffix + "' is left beside it by an earlier map of that name, and SQLite would "
                 "read it into the new one (remove it or choose another name)");
    }
  }
  const std::string problem = mapPathProblem(path, kSaveSuffix);
  if (!problem.empty()) refuseSave(path, problem);
}

void MapDatabase::backupTo(const std::string& path) const {
  namespace fs = std::filesystem;
  const auto refuse = [&](const std::string& problem) { refuseSave(path, problem); };
  checkSaveTarget(path);
  // Through a link, the file it names is written, and the link stays (as build_map writes a map).
  const std::string file = linkedFile(path);
  const std::string part = file + ".part";
  const auto removePart = [&] {
    std::error_code ignored;
    fs::remove(part, ignored);
    removeCompanions(part);
  };
  removeUnfinished(part, path);
  // Created here, not by SQLite, whose only word for every reason is "unable to open database file".
  const int created = ::open(part.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (created < 0) {
    const int reason = errno;
    refuse("cannot create '" + part + "', where the map is written before it is renamed: " + std::strerror(reason));
  }
  ::close(created);
  sqlite3* copy = nullptr;
  std::string problem;
  const int opened = sqlite3_open_v2(sqliteFileName(part).c_str(), &copy, SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE,
                                     nullptr);
  if (opened != SQLITE_OK) {
    problem = copy != nullptr ? sqlite3_errmsg(copy) : "out of memory";
  } else {
    // One step copies every page under one read transaction: the copy is the map at one moment.
    sqlite3_backup* backup = sqlite3_backup_init(copy, "main", db_, "main");
    if (backup == nullptr) {
      problem = sqlite3_errmsg(copy);
    } else {
      const int step = sqlite3_backup_step(backup, -1);
      sqlite3_backup_finish(backup);
      if (step != SQLITE_DONE) problem = lastProblem(copy);
    }
    // The source's WAL mode is copied with its pages; a snapshot is better one file than three.
    if (problem.empty() && sqlite3_exec(copy, "PRAGMA journal_mode = DELETE", nullptr, nullptr, nullptr) != SQLITE_OK) {
      problem = lastProblem(copy);
    }
  }
  sqlite3_close(copy);
  if (problem.empty()) {
    std::error_code error;
    fs::rename(part, file, error);
    if (error) problem = error.message();
  }
  if (!problem.empty()) {
    removePart();
    refuse(problem);
  }
}

}  // namespace mrs_vpr

#include "mrs_vpr/store/map_hold.hpp"

#include <sqlite3.h>
#include <sys/stat.h>

#include <filesystem>
#include <iterator>

#include "mrs_vpr/store/map_database.hpp"
#include "map_path.hpp"

namespace mrs_vpr {

// A WAL map opened without a log gets an empty log and index beside it: the hold notes which it made.
static_assert(std::size(kCompanionSuffixes) == MapHold::kCompanionCount);

MapHold::MapHold(const std::string& path) : path_(path) {
  struct stat file {};
  if (::stat(path.c_str(), &file) != 0) return;  // Nothing there: nothing to hold.
  device_ = file.st_dev;
  inode_ = file.st_ino;
  for (std::size_t i = 0; i < kCompanionCount; ++i) {
    std::error_code ignored;
    existed_[i] = std::filesystem::exists(path + kCompanionSuffixes[i], ignored);
  }
  if (sqlite3_open_v2(sqliteFileName(path).c_str(), &db_, SQLITE_OPEN_READWRITE, nullptr) != SQLITE_OK) {
    sqlite3_close(db_);
    db_ = nullptr;
    return;  // Nothing SQLite can open is held by an owner of a map.
  }
  // Closing checkpoints a log into the file otherwise: the file stays as it was.
  sqlite3_db_config(db_, SQLITE_DBCONFIG_NO_CKPT_ON_CLOSE, 1, nullptr);
  sqlite3_busy_timeout(db_, 0);
  // A write transaction needs the lock an owner keeps (exclusive locking mode) for as long as it runs,
  // and keeps any other writer out while it is open.
  if (sqlite3_exec(db_, "BEGIN IMMEDIATE", nullptr, nullptr, nullptr) == SQLITE_OK) return;
  const int code = sqlite3_errcode(db_);
  release();
  if (code == SQLITE_BUSY || code == SQLITE_LOCKED) {
    throw MapDatabaseError("map database '" + path + "': it is held by another process (a node or tool writing it)");
  }
}

MapHold::~MapHold() { release(); }

void MapHold::release() {
  if (db_ == nullptr) return;
  sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
  sqlite3_close(db_);
  db_ = nullptr;
  // Opening a map in WAL mode that has no log creates an empty log and its index beside it: those the
  // hold made go with it, unless another file has taken the map's name meanwhile (the new map of a
  // tool that replaced it), whose companions are not the hold's.
  struct stat file {};
  if (::stat(path_.c_str(), &file) != 0 || file.st_dev != device_ || file.st_ino != inode_) return;
  for (std::size_t i = 0; i < kCompanionCount; ++i) {
    std::error_code ignored;
    if (!existed_[i]) std::filesystem::remove(path_ + kCompanionSuffixes[i], ignored);
  }
}

}  // namespace mrs_vpr

#include "mrs_vpr/store/map_hold.hpp"

#include <sqlite3.h>

#include "mrs_vpr/store/map_database.hpp"

namespace mrs_vpr {

MapHold::MapHold(const std::string& path) {
  if (sqlite3_open_v2(path.c_str(), &db_, SQLITE_OPEN_READWRITE, nullptr) != SQLITE_OK) {
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
  sqlite3_close(db_);
  db_ = nullptr;
  if (code == SQLITE_BUSY || code == SQLITE_LOCKED) {
    throw MapDatabaseError("map database '" + path + "': it is held by another process (a node or tool writing it)");
  }
}

MapHold::~MapHold() {
  if (db_ == nullptr) return;
  sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
  sqlite3_close(db_);
}

}  // namespace mrs_vpr

#pragma once

#include <sqlite3.h>

#include <string>

namespace mrs_vpr {

/// SQLite's last error on `db`, in the words a user of a map needs.
inline std::string lastProblem(sqlite3* db) {
  const int code = sqlite3_errcode(db);
  const std::string message = sqlite3_errmsg(db);
  if (code == SQLITE_BUSY || code == SQLITE_LOCKED) return "it is locked by another process (" + message + ")";
  return message;
}

}  // namespace mrs_vpr

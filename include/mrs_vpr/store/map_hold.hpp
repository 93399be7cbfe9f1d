#pragma once

#include <string>

struct sqlite3;

namespace mrs_vpr {

/**
 * Holds the map file at a path against writers while a tool replaces or extends it, so that no node
 * starts writing to a file that is about to be replaced: a write transaction is kept open, without
 * writing, until the hold is dropped. Readers go on. The file is never changed: no checkpoint on
 * close, so a log a killed writer left stays as it was.
 *
 * A missing file, or one that is no SQLite database, is held by nobody and needs no hold.
 */
class MapHold {
 public:
  /// Throws MapDatabaseError naming `path` when another process holds it (a node writing it).
  explicit MapHold(const std::string& path);
  ~MapHold();

  MapHold(const MapHold&) = delete;
  MapHold& operator=(const MapHold&) = delete;

 private:
  sqlite3* db_ = nullptr;
};

}  // namespace mrs_vpr

#pragma once

#include <sys/types.h>

#include <array>
#include <cstddef>
#include <string>

struct sqlite3;

namespace mrs_vpr {

/**
 * Holds the map file at a path against writers while a tool replaces or extends it, so that no node
 * starts writing to a file that is about to be replaced: a write transaction is kept open, without
 * writing, until the hold is dropped. Readers go on. The file is never changed: no checkpoint on
 * close, so a log a killed writer left stays as it was, and the empty log and index SQLite creates
 * beside a map in WAL mode that had none are removed again.
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

  /// The files SQLite keeps beside a map (-wal, -shm, -journal).
  static constexpr std::size_t kCompanionCount = 3;

 private:
  void release();

  std::string path_;
  dev_t device_ = 0;
  ino_t inode_ = 0;
  std::array<bool, kCompanionCount> existed_{};
  sqlite3* db_ = nullptr;
};

}  // namespace mrs_vpr

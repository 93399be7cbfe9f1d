#pragma once

// Maps of format 1, as releases before exact stamps wrote them (stamps as REAL seconds), written with
// raw SQL for the tests that check they are still read.

#include <cstdint>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <sqlite3.h>

namespace mrs_vpr {
namespace testing_support {

/// Bytes of a descriptor of the default parameters (64 x 32), which these maps are written for.
constexpr int kFormatOneDescriptorBytes = 64 * 32;

/// Runs `sql` on the SQLite file `file` (created when missing); fails the test on an error.
inline void runSql(const std::string& file, const std::string& sql) {
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(file.c_str(), &db), SQLITE_OK) << file;
  char* error = nullptr;
  const int result = sqlite3_exec(db, sql.c_str(), nullptr, nullptr, &error);
  EXPECT_EQ(result, SQLITE_OK) << (error != nullptr ? error : "") << "\n" << sql;
  sqlite3_free(error);
  sqlite3_close(db);
}

/// A map as earlier releases wrote it, with raw SQL: format 1, frame i stamped `seconds[i]` as REAL
/// and its descriptor filled with byte i.
inline void writeFormatOneMap(const std::string& file, const std::vector<double>& seconds) {
  runSql(file,
         "PRAGMA page_size = 65536;"
         "CREATE TABLE metadata (key TEXT PRIMARY KEY, value TEXT NOT NULL);"
         "CREATE TABLE frames (id INTEGER PRIMARY KEY, stamp REAL NOT NULL, frame_id TEXT NOT NULL,"
         " sequence INTEGER NOT NULL, descriptor BLOB NOT NULL);"
         "INSERT INTO metadata VALUES ('format_version', '1'), ('image_width', '64'), ('image_height', '32'),"
         " ('patch_size', '8'), ('descriptor_bytes', '2048'), ('created', '2024-05-01T12:00:00Z'),"
         " ('package_version', '0.9.0');");
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(file.c_str(), &db), SQLITE_OK) << file;
  sqlite3_stmt* insert = nullptr;
  const char* const sql = "INSERT INTO frames (stamp, frame_id, sequence, descriptor) VALUES (?, 'camera', ?, ?)";
  ASSERT_EQ(sqlite3_prepare_v2(db, sql, -1, &insert, nullptr), SQLITE_OK);
  for (std::size_t i = 0; i < seconds.size(); ++i) {
    const std::vector<std::uint8_t> descriptor(kFormatOneDescriptorBytes, static_cast<std::uint8_t>(i));
    sqlite3_bind_double(insert, 1, seconds[i]);
    sqlite3_bind_int64(insert, 2, static_cast<sqlite3_int64>(i));
    sqlite3_bind_blob(insert, 3, descriptor.data(), kFormatOneDescriptorBytes, SQLITE_TRANSIENT);
    EXPECT_EQ(sqlite3_step(insert), SQLITE_DONE);
    sqlite3_reset(insert);
  }
  sqlite3_finalize(insert);
  sqlite3_close(db);
}

}  // namespace testing_support
}  // namespace mrs_vpr

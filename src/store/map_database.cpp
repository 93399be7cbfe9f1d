#include "mrs_vpr/store/map_database.hpp"

#include <sqlite3.h>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "mrs_vpr/descriptor_sequence.hpp"
#include "mrs_vpr/drive_starts.hpp"
#include "front_end_metadata.hpp"
#include "map_path.hpp"
#include "sqlite_problem.hpp"

namespace mrs_vpr {
namespace {

/// A prepared statement that finalises itself.
using Statement = std::unique_ptr<sqlite3_stmt, decltype(&sqlite3_finalize)>;

/// Rows of the metadata table as SQL values, each followed by a comma.
std::string metadataRows(const std::vector<std::pair<std::string, std::string>>& rows) {
  std::string sql;
  for (const auto& [key, value] : rows) sql += " ('" + key + "', '" + value + "'),";
  return sql;
}

std::string utcNow() {
  const std::time_t now = std::time(nullptr);
  char text[32];
  std::strftime(text, sizeof(text), "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  return text;
}

/// The shortest text that reads back as exactly `value` (0.1, not 0.10000000000000001).
std::string shortestNumber(double value) {
  char text[32];
  const std::to_chars_result written = std::to_chars(text, text + sizeof(text), value);
  return std::string(text, written.ptr);
}

/// Every digit of `value` that tells it from its neighbours.
std::string preciseNumber(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.17g", value);
  return text;
}

/// An SQLite URI that opens `path` as a file that cannot change: no lock, no index beside it.
std::string immutableUri(const std::string& path) {
  std::string uri = "file:";
  for (const char c : path) {
    if (c == '%' || c == '?' || c == '#') {
      static const char kHex[] = "0123456789ABCDEF";
      uri += '%';
      uri += kHex[(static_cast<unsigned char>(c) >> 4) & 0xF];
      uri += kHex[static_cast<unsigned char>(c) & 0xF];
    } else {
      uri += c;
    }
  }
  return uri + "?immutable=1";
}

constexpr const char* kCreatePlaceLinks =
    "CREATE TABLE place_links (id INTEGER PRIMARY KEY, frame INTEGER NOT NULL, reference INTEGER NOT NULL);";

}  // namespace

MapDatabase::MapDatabase(const std::string& path, const DescriptorParams& params, MapAccess access)
    : path_(path), params_(params) {
  params.validate();  // Before any size is computed of them.
  descriptor_bytes_ = params.descriptorSize();
  open(access, true);
}

MapDatabase::MapDatabase(const std::string& path, MapAccess access) : path_(path) { open(access, false); }

void MapDatabase::open(MapAccess access, bool params_given) {
  const std::string& path = path_;
  const bool read_only = access == MapAccess::kReadOnly;
  std::error_code ignored;
  const std::string nul = nulByteProblem(path);
  if (!nul.empty()) throw MapDatabaseError(nul);
  if (read_only && !std::filesystem::exists(path, ignored)) fail("there is no such file");
  const std::string path_problem = mapPathProblem(path, kDatabaseSuffix);
  if (!path_problem.empty()) fail(path_problem);
  int flags = read_only ? SQLITE_OPEN_READONLY : SQLITE_OPEN_READWRITE | SQLITE_OPEN_CREATE;
  std::string name = sqliteFileName(path);
  // A map in WAL mode is read with an index (-shm) that SQLite creates beside it: in a folder nobody
  // may write to (a package's share/, a read-only mount) it must be read as the unchanging file it
  // is there, unless it holds a log, which only that index can read.
  // SQLite writes beside the file a link names: the folder that counts is that file's.
  std::error_code no_file;
  const std::string file = std::filesystem::weakly_canonical(path, no_file).string();
  if (read_only && !no_file && !folderIsWritable(file)) {
    std::error_code no_log;
    if (std::filesystem::file_size(file + "-wal", no_log) > 0 && !no_log) {
      fail("its write-ahead log '" + file + "-wal' can be read only where SQLite may write its index beside it, " +
           "and its folder is read-only: copy the map and its log to a folder you may write to");
    }
    name = immutableUri(file);  // Absolute, with one leading slash: no URI authority.
    flags |= SQLITE_OPEN_URI;
  }
  if (sqlite3_open_v2(name.c_str(), &db_, flags, nullptr) != SQLITE_OK) {
    std::string problem = db_ != nullptr ? sqlite3_errmsg(db_) : "out of memory";
    // SQLite's "unable to open database file" says nothing of why; the system's error does.
    const int reason = db_ != nullptr ? sqlite3_system_errno(db_) : 0;
    if (reason != 0) problem += " (" + std::string(std::strerror(reason)) + ")";
    sqlite3_close(db_);
    db_ = nullptr;
    throw MapDatabaseError("cannot open map database '" + path + "': " + problem);
  }
  try {
    if (!read_only && sqlite3_db_readonly(db_, "main") == 1) fail("it is read-only");
    // Not waiting for another writer: a map held by another node is an error to report, not to queue.
    sqlite3_busy_timeout(db_, 0);
    execute("PRAGMA cache_size = -" + std::to_string(kCacheKiB));
    // Reading the schema is the first access to the file: this is where "not a database" shows.
    Statement tables(nullptr, sqlite3_finalize);
    sqlite3_stmt* raw = nullptr;
    if (sqlite3_prepare_v2(db_, "SELECT name FROM sqlite_master WHERE type = 'table'", -1, &raw, nullptr) !=
        SQLITE_OK) {
      fail(lastProblem(db_));
    }
    tables.reset(raw);
    std::map<std::string, bool> names;
    int step = SQLITE_ROW;
    while ((step = sqlite3_step(tables.get())) == SQLITE_ROW) {
      names[reinterpret_cast<const char*>(sqlite3_column_text(tables.get(), 0))] = true;
    }
    if (step != SQLITE_DONE) fail(lastProblem(db_));
    tables.reset();
    // Nothing is written to a file that is not an empty new one or a map of these descriptors.
    const bool create = names.empty();
    if (create && read_only) fail("it holds no map (an empty file or database)");
    if (create && !params_given) fail("it holds no map yet, and no front end was given for a new one");
    if (!create && (names.count("metadata") == 0 || names.count("frames") == 0)) {
      fail("it is an SQLite database of another kind (no mrs_vpr metadata and frames tables)");
    }
    if (!create) checkMetadata(params_given);
    if (read_only) return;  // Nothing to lock or convert: the file is only read.
    // A map is written only when it is sound: SQLite reads a damaged b-tree without a word (wrong
    // frames in place of others) and fails every later commit. About 0.3 s for 100k frames.
    if (!create) checkIntegrity();
    // A 2 KiB thumbnail descriptor fills a default 4 KiB page alone; 64 KiB pages hold 31 of them (about 80
    // of HOG's), so a new map takes half the disk and loads in about half the reads. (Fixed when the
    // file is first written.)
    if (create) execute("PRAGMA page_size = " + std::to_string(kPageSize));
    // Exclusive: the lock taken by the first write is kept until the database is closed.
    execute("PRAGMA locking_mode = EXCLUSIVE");
    // Before the switch to WAL, which rewrites the header: a conversion that fails leaves every byte.
    if (!create && format_version_ < kFormatVersion) convertToCurrentFormat();
    execute("PRAGMA journal_mode = WAL");
    // A small log, checkpointed often and cut back after each checkpoint: at 64 KiB pages SQLite's
    // default (1000 pages, never cut back) keeps a 64 MiB log beside the smallest map.
    execute("PRAGMA wal_autocheckpoint = " + std::to_string(kWalCheckpointPages));
    execute("PRAGMA journal_size_limit = " + std::to_string(kWalSizeLimit));
    if (create) {
      createSchema(params_);
    } else {
      // Take the lock now, so that a second node fails at start-up rather than at its first frame.
      execute("BEGIN IMMEDIATE; COMMIT");
    }
  } catch (...) {
    sqlite3_close(db_);
    db_ = nullptr;
    throw;
  }
}

MapDatabase::~MapDatabase() { sqlite3_close(db_); }

void MapDatabase::fail(const std::string& problem) const {
  throw MapDatabaseError("map database '" + path_ + "': " + problem);
}

void MapDatabase::execute(const std::string& sql) const {
  char* error = nullptr;
  if (sqlite3_exec(db_, sql.c_str(), nullptr, nullptr, &error) != SQLITE_OK) {
    sqlite3_free(error);
    fail(lastProblem(db_));
  }
}

void MapDatabase::createSchema(const DescriptorParams& params) {
  execute(
      "BEGIN IMMEDIATE;"
      "CREATE TABLE metadata (key TEXT PRIMARY KEY, value TEXT NOT NULL);"
      "CREATE TABLE frames (id INTEGER PRIMARY KEY, stamp_ns INTEGER NOT NULL, frame_id TEXT NOT NULL,"
      " sequence INTEGER NOT NULL, descriptor BLOB NOT NULL);" +
      std::string(kCreatePlaceLinks) +
      "INSERT INTO metadata VALUES ('format_version', '" + std::to_string(kFormatVersion) + "')," +
      metadataRows(frontEndMetadata(params)) +
      " ('descriptor_bytes', '" + std::to_string(descriptor_bytes_) + "'),"
      " ('created', '" + utcNow() + "'),"
      " ('package_version', '" MRS_VPR_PACKAGE_VERSION "');"
      "COMMIT");
}

std::map<std::string, std::string> MapDatabase::readMetadata() const {
  std::map<std::string, std::string> stored;
  sqlite3_stmt* raw = nullptr;
  if (sqlite3_prepare_v2(db_, "SELECT key, value FROM metadata", -1, &raw, nullptr) != SQLITE_OK) {
    fail(lastProblem(db_));
  }
  const Statement rows(raw, sqlite3_finalize);
  int step = SQLITE_ROW;
  while ((step = sqlite3_step(rows.get())) == SQLITE_ROW) {
    const auto* key = reinterpret_cast<const char*>(sqlite3_column_text(rows.get(), 0));
    const auto* value = reinterpret_cast<const char*>(sqlite3_column_text(rows.get(), 1));
    if (key != nullptr && value != nullptr) stored[key] = value;
  }
  if (step != SQLITE_DONE) fail(lastProblem(db_));
  return stored;
}

std::optional<MapTraversal> MapDatabase::readTraversal() const { return traversalOfMetadata(readMetadata()); }

void MapDatabase::checkMetadata(bool params_given) {
  std::map<std::string, std::string> stored = readMetadata();
  format_version_ = 0;
  for (int version = kOldestFormatVersion; version <= kFormatVersion; ++version) {
    if (stored["format_version"] == std::to_string(version)) format_version_ = version;
  }
  if (format_version_ == 0) {
    fail("its format version is '" + stored["format_version"] + "', this package reads " +
         std::to_string(kOldestFormatVersion) + " to " + std::to_string(kFormatVersion));
  }
  const std::optional<DescriptorParams> written = frontEndOfMetadata(stored);
  if (!written) fail("its descriptor type or the parameters of its front end are missing or not numbers");
  try {
    written->validate();
  } catch (const std::invalid_argument& error) {
    fail(std::string("its front end is not valid: ") + error.what());
  }
  // Written with every map; a size that is not the front end's is a map edited or damaged by hand.
  const std::string size = std::to_string(written->descriptorSize());
  if (stored.count("descriptor_bytes") != 0 && stored["descriptor_bytes"] != size) {
    fail("its descriptor_bytes is '" + stored["descriptor_bytes"] + "', but its front end's descriptors are " + size +
         " bytes");
  }
  traversal_ = traversalOfMetadata(stored);
  if (!params_given) {
    params_ = *written;
    descriptor_bytes_ = params_.descriptorSize();
    return;
  }
  if (!written->sameFrontEnd(params_)) {
    // Two blurs that differ beyond the digits a description shows would otherwise read as one.
    const std::string beyond = written->describe() != params_.describe()
                                   ? ""
                                   : " (hog_blur " + preciseNumber(written->hog_blur) + " against " +
                                         preciseNumber(params_.hog_blur) + ")";
    fail("it holds descriptors of the " + written->describe() + " front end, not of the " + params_.describe() +
         " front end asked for" + beyond);
  }
}

namespace {

/// The message of a stamp that cannot be read, naming the frame.
std::string badStamp(sqlite3_int64 id, const std::string& why) {
  return "frame " + std::to_string(id) + " has an unusable stamp: " + why;
}

/// SQL function mrs_vpr_stamp_ns_of(id, seconds): a format-1 stamp in nanoseconds, or an error naming
/// the frame, so that the conversion rounds exactly as reading a format-1 map does.
void stampNanosecondsOf(sqlite3_context* context, int, sqlite3_value** arguments) {
  const sqlite3_int64 id = sqlite3_value_int64(arguments[0]);
  const int type = sqlite3_value_numeric_type(arguments[1]);
  try {
    if (type != SQLITE_FLOAT && type != SQLITE_INTEGER) throw std::invalid_argument("it is not a number");
    sqlite3_result_int64(context, Stamp::fromSeconds(sqlite3_value_double(arguments[1])).nanoseconds());
  } catch (const std::invalid_argument& error) {
    sqlite3_result_error(context, badStamp(id, error.what()).c_str(), -1);
  }
}

}  // namespace

void MapDatabase::convertToCurrentFormat() {
  if (sqlite3_create_function(db_, "mrs_vpr_stamp_ns_of", 2, SQLITE_UTF8 | SQLITE_DETERMINISTIC, nullptr,
                              &stampNanosecondsOf, nullptr, nullptr) != SQLITE_OK) {
    fail(lastProblem(db_));
  }
  // Format 1's stamps: a new table rather than a new column, as the stamp column of format 1 is
  // REAL, which would turn every integer written into it back into a double.
  const std::string exact_stamps =
      format_version_ > 1
          ? ""
          : "CREATE TABLE frames_v2 (id INTEGER PRIMARY KEY, stamp_ns INTEGER NOT NULL, frame_id TEXT NOT NULL,"
            " sequence INTEGER NOT NULL, descriptor BLOB NOT NULL);"
            "INSERT INTO frames_v2 SELECT id, mrs_vpr_stamp_ns_of(id, stamp), frame_id, sequence, descriptor FROM "
            "frames;"
            "DROP TABLE frames;"
            "ALTER TABLE frames_v2 RENAME TO frames;";
  const std::string convert =
      "PRAGMA cache_size = -" + std::to_string(kConversionCacheKiB) + ";"
      "BEGIN IMMEDIATE;" + exact_stamps + kCreatePlaceLinks +
      "UPDATE metadata SET value = '" + std::to_string(kFormatVersion) + "' WHERE key = 'format_version';"
      "COMMIT";
  const int converted = sqlite3_exec(db_, convert.c_str(), nullptr, nullptr, nullptr);
  const std::string problem = converted == SQLITE_OK ? "" : lastProblem(db_);
  if (converted != SQLITE_OK) sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
  // The usual cache again (its size changes only memory: a failure here would hide the one above).
  sqlite3_exec(db_, ("PRAGMA cache_size = -" + std::to_string(kCacheKiB)).c_str(), nullptr, nullptr, nullptr);
  if (converted != SQLITE_OK) {
    fail("cannot convert it from format " + std::to_string(format_version_) + " to " + std::to_string(kFormatVersion) +
         " (it is left as it was): " + problem);
  }
  converted_from_ = format_version_;
  format_version_ = kFormatVersion;
}

void MapDatabase::insertFrames(const FrameSource& source) {
  sqlite3_stmt* raw = nullptr;
  if (sqlite3_prepare_v2(db_, "INSERT INTO frames (stamp_ns, frame_id, sequence, descriptor) VALUES (?, ?, ?, ?)", -1,
                         &raw, nullptr) != SQLITE_OK) {
    fail(lastProblem(db_));
  }
  const Statement insert(raw, sqlite3_finalize);
  source([&](const StoredFrame& frame) {
    requireDescriptorBytes(frame.descriptor, descriptor_bytes_, "a stored descriptor");
    sqlite3_bind_int64(insert.get(), 1, frame.stamp.nanoseconds());
    sqlite3_bind_text(insert.get(), 2, frame.frame_id.c_str(), static_cast<int>(frame.frame_id.size()),
                      SQLITE_TRANSIENT);
    sqlite3_bind_int64(insert.get(), 3, frame.sequence);
    sqlite3_bind_blob(insert.get(), 4, frame.descriptor.data, descriptor_bytes_, SQLITE_STATIC);
    if (sqlite3_step(insert.get()) != SQLITE_DONE) fail(lastProblem(db_));
    sqlite3_reset(insert.get());
  });
}

void MapDatabase::insertLinks(const std::vector<PlaceLink>& links) {
  bindEachLink("INSERT INTO place_links (frame, reference) VALUES (?, ?)", links);
}

void MapDatabase::bindEachLink(const char* sql, const std::vector<PlaceLink>& links) {
  if (links.empty()) return;
  sqlite3_stmt* raw = nullptr;
  if (sqlite3_prepare_v2(db_, sql, -1, &raw, nullptr) != SQLITE_OK) fail(lastProblem(db_));
  const Statement statement(raw, sqlite3_finalize);
  for (const PlaceLink& link : links) {
    sqlite3_bind_int(statement.get(), 1, link.frame);
    sqlite3_bind_int(statement.get(), 2, link.reference);
    if (sqlite3_step(statement.get()) != SQLITE_DONE) fail(lastProblem(db_));
    sqlite3_reset(statement.get());
  }
}

void MapDatabase::append(const std::vector<StoredFrame>& frames, const std::vector<PlaceLink>& links) {
  // insertFrames checks each descriptor: a bad one rolls the batch back.
  inWriteTransaction([&] {
    insertFrames([&](const auto& insert) {
      for (const StoredFrame& frame : frames) insert(frame);
    });
    insertLinks(links);
    if (!frames.empty()) forgetTraversal();  // Links change no frame.
  });
}

void MapDatabase::forgetLinks(const std::vector<PlaceLink>& links) {
  if (links.empty()) return;
  inWriteTransaction([&] { bindEachLink("DELETE FROM place_links WHERE frame = ? AND reference = ?", links); });
}

std::vector<PlaceLink> MapDatabase::placeLinks(std::int64_t frames) const {
  if (format_version_ < 3) return {};  // Read as it is: no table of links yet.
  sqlite3_stmt* raw = nullptr;
  if (sqlite3_prepare_v2(db_, "SELECT id, frame, reference FROM place_links ORDER BY id", -1, &raw, nullptr) !=
      SQLITE_OK) {
    fail(lastProblem(db_));
  }
  const Statement rows(raw, sqlite3_finalize);
  std::vector<PlaceLink> links;
  int step = SQLITE_ROW;
  while ((step = sqlite3_step(rows.get())) == SQLITE_ROW) {
    const auto frameAt = [&](int column) {
      const sqlite3_int64 frame = sqlite3_column_int64(rows.get(), column);
      if (sqlite3_column_type(rows.get(), column) != SQLITE_INTEGER || frame < 0 || frame >= frames) {
        const auto* text = reinterpret_cast<const char*>(sqlite3_column_text(rows.get(), column));
        const std::string id = std::to_string(sqlite3_column_int64(rows.get(), 0));
        fail("place link " + id + ": its " + sqlite3_column_name(rows.get(), column) + " '" +
             (text != nullptr ? text : "NULL") + "' is not one of its " + std::to_string(frames) +
             " frames (counted from 0); with no node holding the map, sqlite3 '" + path_ +
             "' \"DELETE FROM place_links WHERE id = " + id + "\" removes the link (the frames stay)");
      }
      return static_cast<int>(frame);
    };
    const int frame = frameAt(1);
    links.push_back({frame, frameAt(2)});
  }
  if (step != SQLITE_DONE) fail(lastProblem(db_));
  return links;
}

void MapDatabase::replace(const FrameSource& source, const std::optional<MapTraversal>& traversal,
                          const std::vector<PlaceLink>& links, const std::vector<int>& drive_starts) {
  inWriteTransaction([&] {
    execute("DELETE FROM frames; DELETE FROM place_links");
    insertFrames(source);
    insertLinks(links);
    recordDriveStarts(drive_starts);
    forgetTraversal();
    if (traversal) recordTraversal(*traversal);
  });
  traversal_ = traversal;
}

std::vector<int> MapDatabase::driveStarts() const {
  const std::map<std::string, std::string> stored = readMetadata();
  const auto record = stored.find("drive_starts");
  if (record == stored.end()) return {};
  const auto damaged = [&] {
    fail("its drive_starts '" + record->second + "' is not a list of ascending frame numbers; with no node "
         "holding the map, sqlite3 '" + path_ + "' \"DELETE FROM metadata WHERE key = 'drive_starts'\" removes it "
         "(a drive's junction is then judged as a place)");
  };
  // Numbers separated by single spaces, as recordDriveStarts() writes them.
  std::vector<int> starts;
  const char* next = record->second.c_str();
  const char* const end = next + record->second.size();
  while (true) {
    int frame = 0;
    const auto [after, error] = std::from_chars(next, end, frame);
    if (error != std::errc() || frame <= 0 || (!starts.empty() && frame <= starts.back())) damaged();
    starts.push_back(frame);
    if (after == end) return starts;
    if (*after != ' ' || after + 1 == end) damaged();
    next = after + 1;
  }
}

void MapDatabase::addDriveStart(int frame) {
  if (frame < 0) fail("a drive cannot start at frame " + std::to_string(frame));
  if (frame == 0) return;
  inWriteTransaction([&] {
    std::vector<int> starts = driveStarts();
    if (insertDriveStart(starts, frame)) recordDriveStarts(starts);
  });
}

void MapDatabase::recordDriveStarts(const std::vector<int>& starts) {
  execute("DELETE FROM metadata WHERE key = 'drive_starts'");
  if (starts.empty()) return;
  std::string list;
  for (const int frame : starts) list += (list.empty() ? "" : " ") + std::to_string(frame);
  execute("INSERT INTO metadata VALUES ('drive_starts', '" + list + "')");
}

void MapDatabase::inWriteTransaction(const std::function<void()>& work) {
  execute("BEGIN IMMEDIATE");
  try {
    work();
    execute("COMMIT");
  } catch (...) {
    sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
    throw;
  }
}

void MapDatabase::forgetTraversal() {
  // Also a record read as none (stale, damaged): left, it could match the frames again after a refill.
  execute("DELETE FROM metadata WHERE key LIKE 'traversal\\_%' ESCAPE '\\'");
  traversal_.reset();  // Restored by nothing should the transaction roll back: a hint lost, never a false one.
}

void MapDatabase::setTraversal(const MapTraversal& traversal) {
  inWriteTransaction([&] {
    forgetTraversal();
    recordTraversal(traversal);
  });
  traversal_ = traversal;
}

void MapDatabase::recordTraversal(const MapTraversal& traversal) {
  execute("INSERT INTO metadata VALUES ('traversal_frames', '" + std::to_string(traversal.frames) + "'), " +
          "('traversal_last_frame', '" + lastFrame() + "')");
  if (traversal.min_appearance_change) {
    execute("INSERT INTO metadata VALUES ('traversal_min_appearance_change', '" +
            shortestNumber(*traversal.min_appearance_change) + "')");
  }
}

std::optional<MapTraversal> MapDatabase::traversalOfMetadata(const std::map<std::string, std::string>& stored) const {
  // A hint for evaluating the map, never a reason to refuse it: a record that is damaged, or that
  // another program's change of the frames left behind (its last frame is not the map's), is none.
  const auto number = [&](const char* key) -> std::optional<double> {
    const auto entry = stored.find(key);
    if (entry == stored.end() || entry->second.empty()) return std::nullopt;
    char* end = nullptr;
    errno = 0;
    const double value = std::strtod(entry->second.c_str(), &end);
    if (*end != '\0' || errno != 0 || !std::isfinite(value) || value < 0.0) return std::nullopt;
    return value;
  };
  const std::optional<double> frames = number("traversal_frames");
  const auto last_frame = stored.find("traversal_last_frame");
  constexpr double kLargestCount = 9e15;  // Exact in a double, and far beyond any map.
  if (!frames || *frames > kLargestCount || *frames != std::floor(*frames) || last_frame == stored.end() ||
      last_frame->second != lastFrame()) {
    return std::nullopt;
  }
  MapTraversal traversal;
  traversal.frames = static_cast<std::int64_t>(*frames);
  traversal.min_appearance_change = number("traversal_min_appearance_change");
  return traversal;
}

std::string MapDatabase::lastFrame() const {
  // Format 1 (read-only: a map opened for writing is converted) has seconds in `stamp`.
  const std::string select = std::string("SELECT id, ") + (format_version_ == 1 ? "stamp" : "stamp_ns") +
                             " FROM frames ORDER BY id DESC LIMIT 1";
  sqlite3_stmt* raw = nullptr;
  if (sqlite3_prepare_v2(db_, select.c_str(), -1, &raw, nullptr) != SQLITE_OK) fail(lastProblem(db_));
  const Statement last(raw, sqlite3_finalize);
  const int step = sqlite3_step(last.get());
  if (step == SQLITE_DONE) return "none";
  if (step != SQLITE_ROW) fail(lastProblem(db_));
  const auto* stamp = reinterpret_cast<const char*>(sqlite3_column_text(last.get(), 1));
  return std::to_string(sqlite3_column_int64(last.get(), 0)) + " at " + (stamp != nullptr ? stamp : "");
}

std::int64_t MapDatabase::size() const {
  sqlite3_stmt* raw = nullptr;
  if (sqlite3_prepare_v2(db_, "SELECT COUNT(*) FROM frames", -1, &raw, nullptr) != SQLITE_OK) fail(lastProblem(db_));
  const Statement count(raw, sqlite3_finalize);
  if (sqlite3_step(count.get()) != SQLITE_ROW) fail(lastProblem(db_));
  return sqlite3_column_int64(count.get(), 0);
}

void MapDatabase::forEachFrame(const std::function<void(const StoredFrame& frame)>& visit) const {
  sqlite3_stmt* raw = nullptr;
  // Format 1 (read-only: a map opened for writing is converted) has seconds in `stamp`.
  const bool in_seconds = format_version_ == 1;
  const std::string select = std::string("SELECT id, ") + (in_seconds ? "stamp" : "stamp_ns") +
                             ", frame_id, sequence, descriptor FROM frames ORDER BY id";
  if (sqlite3_prepare_v2(db_, select.c_str(), -1, &raw, nullptr) != SQLITE_OK) fail(lastProblem(db_));
  const Statement rows(raw, sqlite3_finalize);
  StoredFrame frame;
  int step = SQLITE_ROW;
  while ((step = sqlite3_step(rows.get())) == SQLITE_ROW) {
    // Types first: SQLite would read text as a descriptor and 'x' as the sequence number 0.
    if (sqlite3_column_type(rows.get(), 4) != SQLITE_BLOB) {
      fail("frame " + std::to_string(sqlite3_column_int64(rows.get(), 0)) + " holds a descriptor that is not a blob");
    }
    if (sqlite3_column_type(rows.get(), 3) != SQLITE_INTEGER) {
      fail("frame " + std::to_string(sqlite3_column_int64(rows.get(), 0)) + " has a sequence number that is not an "
           "integer");
    }
    if (sqlite3_column_bytes(rows.get(), 4) != descriptor_bytes_) {
      fail("frame " + std::to_string(sqlite3_column_int64(rows.get(), 0)) + " holds a descriptor of " +
           std::to_string(sqlite3_column_bytes(rows.get(), 4)) + " bytes, not " + std::to_string(descriptor_bytes_));
    }
    const sqlite3_int64 id = sqlite3_column_int64(rows.get(), 0);
    const int stamp_type = sqlite3_column_type(rows.get(), 1);
    try {
      if (in_seconds && stamp_type != SQLITE_FLOAT && stamp_type != SQLITE_INTEGER) {
        throw std::invalid_argument("it is not a number");
      }
      if (!in_seconds && stamp_type != SQLITE_INTEGER) throw std::invalid_argument("it is not an integer");
      frame.stamp = in_seconds ? Stamp::fromSeconds(sqlite3_column_double(rows.get(), 1))
                               : Stamp::fromNanoseconds(sqlite3_column_int64(rows.get(), 1));
    } catch (const std::invalid_argument& error) {
      fail(badStamp(id, error.what()));
    }
    const auto* frame_id = reinterpret_cast<const char*>(sqlite3_column_text(rows.get(), 2));
    frame.frame_id = frame_id != nullptr ? frame_id : "";
    frame.sequence = sqlite3_column_int64(rows.get(), 3);
    // A view of SQLite's buffer, valid until the next step: the visitor copies what it keeps.
    frame.descriptor = cv::Mat(1, descriptor_bytes_, CV_8UC1, const_cast<void*>(sqlite3_column_blob(rows.get(), 4)));
    visit(frame);
  }
  if (step != SQLITE_DONE) fail(lastProblem(db_));
}

void MapDatabase::clear() {
  inWriteTransaction([&] {
    execute("DELETE FROM frames; DELETE FROM place_links");
    recordDriveStarts({});
    forgetTraversal();
  });
}

void MapDatabase::readAtOneMoment(const std::function<void()>& read) const {
  execute("BEGIN");  // Deferred: the first read takes the snapshot that the others see.
  try {
    read();
  } catch (...) {
    sqlite3_exec(db_, "ROLLBACK", nullptr, nullptr, nullptr);
    throw;
  }
  execute("COMMIT");
}

void MapDatabase::checkIntegrity() const {
  sqlite3_stmt* raw = nullptr;
  // A truncated map can have thousands of problems; the first few are enough to tell.
  constexpr std::size_t kProblems = 10;
  const std::string check = "PRAGMA quick_check(" + std::to_string(kProblems) + ")";
  if (sqlite3_prepare_v2(db_, check.c_str(), -1, &raw, nullptr) != SQLITE_OK) fail(lastProblem(db_));
  const Statement rows(raw, sqlite3_finalize);
  std::vector<std::string> problems;
  int step = SQLITE_ROW;
  while ((step = sqlite3_step(rows.get())) == SQLITE_ROW) {
    const auto* text = reinterpret_cast<const char*>(sqlite3_column_text(rows.get(), 0));
    std::istringstream lines(text != nullptr ? text : "");
    for (std::string line; std::getline(lines, line);) {
      if (line != "ok" && line.rfind("***", 0) != 0) problems.push_back(line);  // "*** in database main ***"
    }
  }
  if (step != SQLITE_DONE) fail(lastProblem(db_));
  if (problems.empty()) return;
  const std::string count = problems.size() >= kProblems ? "at least " + std::to_string(kProblems) + " problems"
                                                         : std::to_string(problems.size()) + " problem" +
                                                               (problems.size() > 1 ? "s" : "");
  fail("it is corrupt or truncated (SQLite's quick_check finds " + count + "; the first: " + problems.front() + ")");
}

}  // namespace mrs_vpr

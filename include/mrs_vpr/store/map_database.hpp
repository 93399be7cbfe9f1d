#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "mrs_vpr/parameters.hpp"
#include "mrs_vpr/place_links.hpp"
#include "mrs_vpr/stamp.hpp"
#include "mrs_vpr/store/map_traversal.hpp"

struct sqlite3;

namespace mrs_vpr {

/// A map database that cannot be used: not SQLite, another schema, other descriptor parameters,
/// corrupt, read-only or locked. The message names the file and the problem.
class MapDatabaseError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// How a map database is opened.
enum class MapAccess {
  kReadWrite,  ///< Created when missing; held with an exclusive lock (the owner of a map).
  kReadOnly,   ///< Must exist; never written (a saved map to load); fails while another owner holds it.
};

/// One frame as stored: its descriptor and what is known of the image it came from.
struct StoredFrame {
  cv::Mat descriptor;        ///< 1 x descriptorSize() CV_8UC1, as DescriptorExtractor gives it.
  Stamp stamp;               ///< Exact, as the camera gave it.
  std::string frame_id;      ///< Camera frame, empty when unknown.
  /// The image's number: the camera's header.seq for the node, the frame's index in its folder or on
  /// its bag topic for build_map; -1 when unknown.
  std::int64_t sequence = -1;
};

/**
 * The reference map on disk: an SQLite database (WAL journal) that survives crashes and sessions and
 * that users can inspect with `sqlite3` or Python. Schema (format 3):
 *
 *   metadata(key TEXT PRIMARY KEY, value TEXT)   format_version, descriptor_type (hog, thumbnail),
 *                                                that front end's parameters (hog_window_width,
 *                                                hog_window_height, hog_cell_size, hog_bins, hog_blur;
 *                                                image_width, image_height, patch_size),
 *                                                descriptor_bytes, created, package_version;
 *                                                traversal_frames, traversal_last_frame and, for keyframes
 *                                                by appearance change, traversal_min_appearance_change
 *                                                (MapTraversal); drive_starts, the frames that begin
 *                                                a drive not continuing the frame before them
 *                                                (drive_starts.hpp), as numbers in ascending order
 *   frames(id INTEGER PRIMARY KEY, stamp_ns INTEGER, frame_id TEXT, sequence INTEGER, descriptor BLOB)
 *   place_links(id INTEGER PRIMARY KEY, frame INTEGER, reference INTEGER)
 *
 * stamp_ns is the exact stamp in nanoseconds since the Unix epoch. A place link is an accepted loop
 * closure of the map's own frames (place_links.hpp): `frame` and `reference` count frames in map
 * order from 0, and the links are kept in the order they were made. Format 2 had no place_links (a
 * map of no links); format 1 (earlier releases) also kept `stamp REAL` seconds instead of stamp_ns:
 * such maps are read as they are (stamps converted to the nearest nanosecond), and converted to
 * format 3 in place, in one transaction, when opened for writing. A stamp outside
 * Stamp's range (no ROS time) is an error naming the frame, never a stamp that a node cannot publish.
 * The write-ahead log is checkpointed every kWalCheckpointPages pages and cut back to
 * kWalSizeLimit bytes, so that it stays a few MiB whatever the map's size.
 *
 * A map that records no descriptor_type was written before the front end could be chosen: it holds
 * thumbnails. Frames are kept in id order, which is the map's order. Derived data (MRS's pooled levels) is not
 * stored: it is rebuilt when the frames are loaded. The database is held with an exclusive lock while
 * open, so that two nodes never write one map. Not thread-safe: one owner at a time.
 */
class MapDatabase {
 public:
  static constexpr int kFormatVersion = 3;
  /// The oldest format still read (and converted when written).
  static constexpr int kOldestFormatVersion = 1;
  /// Page size of the maps this class creates [bytes]: SQLite's largest, as frames are rows of 0.75
  /// (HOG) to 2 KiB (thumbnail).
  static constexpr int kPageSize = 65536;
  /// The log is copied into the map once it holds this many pages (SQLite's default of 1000 pages
  /// would let it reach 64 MiB at this page size)...
  static constexpr int kWalCheckpointPages = 64;
  /// ...and cut back to this size after each copy [bytes]; a larger transaction may grow it meanwhile.
  static constexpr std::int64_t kWalSizeLimit = std::int64_t{kWalCheckpointPages} * kPageSize;
  /// SQLite's page cache [KiB]: four 64 KiB pages. A map is read whole, once (its checks, a load),
  /// and appended to, so hardly a page is read twice; SQLite's default of 2 MiB, freed at the close,
  /// stayed with the process after a load (memory_reuse.hpp): 19 bytes a frame of a 100k-frame map.
  static constexpr int kCacheKiB = 256;
  /// ...but a conversion to the current format rewrites the whole map in one transaction, whose
  /// journal is synced each time the cache overflows: SQLite's default for it (13 times fewer syncs).
  static constexpr int kConversionCacheKiB = 2000;

  /**
   * Opens `path`, creating an empty map there when no file exists. Throws MapDatabaseError naming the
   * file when it is not an SQLite database, holds another schema, was written for other descriptor
   * parameters, cannot be written, or is locked by another process, and, before SQLite is asked, when
   * it is a folder, its folder does not exist or its name is too long for the file system (SQLite
   * would say "unable to open database file" for each). Never replaces a user's file.
   */
  MapDatabase(const std::string& path, const DescriptorParams& params, MapAccess access = MapAccess::kReadWrite);
  /// Opens the existing map `path` with whatever front end it holds (descriptorParams() tells which);
  /// throws MapDatabaseError as above, and when there is no map there yet.
  explicit MapDatabase(const std::string& path, MapAccess access = MapAccess::kReadOnly);
  ~MapDatabase();

  MapDatabase(const MapDatabase&) = delete;
  MapDatabase& operator=(const MapDatabase&) = delete;

  /// Appends frames, then place links (whose frames must be in the map by then), in one transaction:
  /// all of them are on disk when it returns, or none.
  void append(const std::vector<StoredFrame>& frames, const std::vector<PlaceLink>& links = {});
  /// The place links, in the order they were made. Throws MapDatabaseError for a link that is not two
  /// of the map's frames.
  std::vector<PlaceLink> placeLinks() const { return placeLinks(size()); }
  /// placeLinks() of the map's `frames`, which the caller has counted already (size() reads the whole
  /// table: half a second on a million frames).
  std::vector<PlaceLink> placeLinks(std::int64_t frames) const;
  /// Removes every stored place link equal to one of `links` (a refused closure's), in one transaction.
  void forgetLinks(const std::vector<PlaceLink>& links);
  /// Frames stored.
  std::int64_t size() const;
  /// Calls `visit` for every frame in map order. Throws MapDatabaseError on a corrupt or foreign row.
  void forEachFrame(const std::function<void(const StoredFrame& frame)>& visit) const;
  /// Calls `read` inside one read transaction: all it reads of this database (its size, its frames) is
  /// the file at one moment, whatever another program writes meanwhile.
  void readAtOneMoment(const std::function<void()>& read) const;
  /// Removes every frame, place link and drive start (the rest of the metadata stays).
  void clear();
  /// Where replace() takes its frames from: it calls `insert` once for each frame, in map order.
  using FrameSource = std::function<void(const std::function<void(const StoredFrame& frame)>& insert)>;
  /// Replaces every frame by those `source` gives, in one transaction: on any failure (a throw from
  /// `source` too) the old frames stay. The new frames need not all be in memory at once. The old
  /// frames' traversal, place links and drive starts are forgotten; `traversal`, the one the new
  /// frames were kept of, `links`, their place links, and `drive_starts`, theirs, are recorded.
  void replace(const FrameSource& source, const std::optional<MapTraversal>& traversal = std::nullopt,
               const std::vector<PlaceLink>& links = {}, const std::vector<int>& drive_starts = {});
  /// The drive starts the map records (drive_starts.hpp), in ascending order; none for a map that
  /// records none (one drive, or written by an earlier release). Throws MapDatabaseError, naming the
  /// sqlite3 command that removes it, for a record that is not such a list of frames.
  std::vector<int> driveStarts() const;
  /// Records that a drive begins at map frame `frame`: the map's size when the frames about to be
  /// appended come from another drive than its last frame. Frame 0 begins the map and records nothing.
  void addDriveStart(int frame);
  /// Throws MapDatabaseError naming the problem unless SQLite's quick_check finds the file sound; the
  /// message counts the problems and quotes the first, however damaged the file.
  void checkIntegrity() const;

  /**
   * Writes a consistent copy of the map to the new file `path` with SQLite's online backup, in
   * rollback-journal mode so that the copy is one self-contained file. Refuses an existing `path`
   * (a map is never overwritten); writes `path`.part and renames it when complete, so that a failed
   * copy never leaves a partial map. Throws MapDatabaseError naming `path` and the problem.
   */
  void backupTo(const std::string& path) const;
  /// Throws the MapDatabaseError backupTo() would when `path` is empty, exists, is a folder, has no
  /// folder, names a file too long for the file system with the suffixes written beside it, or has
  /// an earlier map's log or journal left beside it (path-wal, -shm, -journal), which SQLite would
  /// read into the new file.
  static void checkSaveTarget(const std::string& path);
  /// Throws MapDatabaseError when another process holds the map at `path` (a node writing it), which
  /// must then not be replaced. A missing file, or one that is no SQLite database, is held by nobody.
  static void checkNotHeld(const std::string& path);
  /// Removes what an earlier database at `path` left beside it (path-wal, -shm, -journal), which
  /// SQLite would otherwise read into a new file renamed to `path`. Only for a path no other process
  /// holds (the caller's own MapHold keeps any writer out).
  static void removeCompanions(const std::string& path);
  /// Whether `path` is a regular file that begins with SQLite's header (a map database, whatever its name).
  static bool isSqliteFile(const std::string& path);
  /// Removes `part`, the unfinished copy of the map `path` that an earlier run left (an empty file or
  /// an SQLite database), with its companions. Throws MapDatabaseError naming `path` when anything
  /// else is there (a folder, a file of the user's), which is left alone.
  static void removeUnfinished(const std::string& part, const std::string& path);

  /**
   * Copies the write-ahead log into the map and leaves it in rollback-journal mode: one
   * self-contained file, which can be renamed (a log beside a renamed file would be lost, or read
   * into another map). Throws MapDatabaseError when the log cannot be copied, as on a full disk.
   */
  void makeSelfContained();

  /// Records the traversal the map's frames were kept of (build_map, a map saved from Python). Any
  /// later change of the frames (append, clear) forgets it: they are no longer its alone; replace()
  /// records the one it is given, if any.
  void setTraversal(const MapTraversal& traversal);
  /// What setTraversal() or replace() recorded, as read when the map was opened; nullopt for a map
  /// that records none (a camera's frames).
  const std::optional<MapTraversal>& traversal() const { return traversal_; }
  /// The record as the file holds it now, read again: inside readAtOneMoment(), that of the frames read
  /// there, whatever another program wrote since this map was opened.
  std::optional<MapTraversal> readTraversal() const;

  const std::string& path() const { return path_; }
  /// The format of an older map converted to the current one when it was opened; 0 when none was.
  int convertedFromFormat() const { return converted_from_; }
  /// The front end of the map's descriptors (DescriptorParams::type and that type's fields).
  const DescriptorParams& descriptorParams() const { return params_; }

 private:
  [[noreturn]] void fail(const std::string& problem) const;
  void execute(const std::string& sql) const;
  /// Opens path_; with `params_given`, for params_ (refusing another front end), else adopting the map's.
  void open(MapAccess access, bool params_given);
  void createSchema(const DescriptorParams& params);
  /// Reads the format version and the front end: with `params_given` checks params_ against it, else
  /// adopts it.
  void checkMetadata(bool params_given);
  /// The metadata table's keys and values.
  std::map<std::string, std::string> readMetadata() const;
  /// The traversal the metadata records; nullopt when it records none, a damaged one, or one whose
  /// frames have changed since (traversal_last_frame is not the map's lastFrame()).
  std::optional<MapTraversal> traversalOfMetadata(const std::map<std::string, std::string>& stored) const;
  /// Removes the recorded traversal inside the caller's transaction: the frames are no longer its alone.
  void forgetTraversal();
  /// Records `traversal` of the frames as they are, inside the caller's transaction, after forgetTraversal().
  void recordTraversal(const MapTraversal& traversal);
  /// Runs `work` in one write transaction, rolled back when it throws.
  void inWriteTransaction(const std::function<void()>& work);
  /// The last frame's id and stamp as text ("none" for no frame): what a record of the traversal
  /// compares to tell whether the frames changed since, also by another program or a refill after a
  /// reset (whose ids start again at 1, but not its camera's stamps).
  std::string lastFrame() const;
  /// Converts an older map in one transaction: a format-1 map's frames are rewritten with exact
  /// stamps, and the place_links table is added.
  void convertToCurrentFormat();
  /// Records `starts` (ascending) as the drive starts, replacing any, inside the caller's transaction.
  void recordDriveStarts(const std::vector<int>& starts);
  /// Inserts `links` inside a transaction the caller has begun.
  void insertLinks(const std::vector<PlaceLink>& links);
  /// Runs `sql`, whose two parameters are a link's frame and reference, once for each of `links`.
  void bindEachLink(const char* sql, const std::vector<PlaceLink>& links);
  /// Inserts the frames of `source` inside a transaction the caller has begun; throws
  /// std::invalid_argument for a descriptor that is not of this map's size.
  void insertFrames(const FrameSource& source);

  std::string path_;
  DescriptorParams params_;
  int descriptor_bytes_ = 0;
  int format_version_ = kFormatVersion;
  int converted_from_ = 0;
  std::optional<MapTraversal> traversal_;
  sqlite3* db_ = nullptr;
};

}  // namespace mrs_vpr

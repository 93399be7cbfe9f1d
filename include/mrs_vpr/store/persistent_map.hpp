#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "mrs_vpr/place_recognizer.hpp"
#include "mrs_vpr/store/frame_labels.hpp"
#include "mrs_vpr/store/map_database.hpp"
#include "mrs_vpr/store/map_writer.hpp"

namespace mrs_vpr {

/**
 * A PlaceRecognizer's map mirrored in a map database, so that it survives crashes and restarts: the
 * database's frames, in the same order, are the map's (up to the frames still waiting for a commit,
 * see MapWriter), and its place links the map's (place_links.hpp): a place that accepted closures
 * linked across visits stays one after a restart or a load. Without a database the map lives in
 * memory only, and save() still writes one.
 *
 * reset(), load() and save() replace or copy the whole map consistently while add() goes on from
 * another thread, so that no frame reaches one of map and database without the other: add() waits
 * only while reset() empties the database and while load() swaps the maps. While load() rewrites the
 * database (after it has read and checked the new map), added frames join the old map and are held
 * back from the database, as many as the new map has room for (kMapFull after that); they follow the
 * new map's frames in both once it is in place, which add() waits for. Errors throw
 * MapDatabaseError naming the file and the problem; the map and the database are then as they were.
 * Every member is thread-safe.
 *
 * Once a recognizer belongs to a PersistentMap, every change of its map goes through the
 * PersistentMap (add, offer, reset, load): a frame added to the recognizer itself would be in the map
 * but not in the database, and would shift the frame ids and numbers of every later frame. Queries
 * go to the recognizer as before. Both constructors throw std::logic_error for a recognizer that
 * already holds frames: they would have no labels.
 */
class PersistentMap {
 public:
  /// Memory only.
  explicit PersistentMap(PlaceRecognizer& recognizer);
  /**
   * Opens `path` (creating an empty map when no file exists) and loads its frames into `recognizer`,
   * which must be empty. Throws MapDatabaseError naming the file when it is not a map of the
   * recognizer's descriptors, is corrupt, truncated, read-only or locked, or holds more frames than
   * RecognizerParams::max_frames: a user's map is never replaced by an empty one.
   */
  PersistentMap(PlaceRecognizer& recognizer, const std::string& path, const CommitPolicy& policy);
  /// Commits the frames still queued.
  ~PersistentMap();

  PersistentMap(const PersistentMap&) = delete;
  PersistentMap& operator=(const PersistentMap&) = delete;

  /// Adds a keyframe (one chosen by travel, say) to the map and, when admitted, queues it for the
  /// database. Cheap: never waits for the disk or a query (only for reset() and a map swap, see above).
  FrameAdmission add(const cv::Mat& descriptor, Stamp stamp, const std::string& frame_id = "",
                     std::int64_t sequence = -1);
  /// The same for a camera frame that joins the map only if its view has changed enough
  /// (PlaceRecognizer::offerDescriptor): kTooSimilar otherwise.
  FrameAdmission offer(const cv::Mat& descriptor, Stamp stamp, const std::string& frame_id = "",
                       std::int64_t sequence = -1);

  /// Empties the map and the database; returns the frames the map held.
  int reset();
  /**
   * Replaces the map (and the database) by the map saved at `path`, which is opened read-only and
   * checked first (integrity, descriptors, size); returns its frames. `path` may not be this map's
   * own database.
   */
  int load(const std::string& path);
  /**
   * Writes a consistent snapshot of the map, as it is when called, to the new file `path` (never
   * overwritten; written aside and renamed when complete). With a database it is SQLite's online
   * backup of it; in memory only, the map's frames as the database would hold them (descriptor,
   * stamp, frame id and number) and its place links. Returns the frames written.
   *
   * `traversal`, for a map in memory whose frames were numbered among the frames offered (Python's),
   * is recorded as MapDatabase::setTraversal() records it; without it, a map saved before any frame
   * joined the map last loaded keeps that map's record (loadedTraversal()). A map with a database
   * saves what its database records (the same, and nothing once frames were added to it), and
   * ignores `traversal`.
   */
  std::int64_t save(const std::string& path, const std::optional<MapTraversal>& traversal = std::nullopt);
  /// Commits the queued frames now.
  void commit();
  /**
   * Marks map frame `frame` as the first of a drive that does not continue the frame before it
   * (PlaceRecognizer::markDriveStart): the map's size when the camera's frames after a loaded map
   * are about to follow. The database records it too, so that the junction stays one after a restart
   * or a save and load. Throws MapDatabaseError when the record cannot be written (the recognizer
   * keeps the mark).
   */
  void startDrive(int frame);

  /**
   * Forgets the place link by which an accepted loop closure put map frame `frame` in the place of map
   * frame `reference` (PlaceRecognizer::linksOfClosure), for a closure that the robot's back end
   * refused afterwards: later answers no longer take those frames for one place. The database loses
   * the link too. Returns the links forgotten. Throws std::invalid_argument for a frame the map does
   * not hold, or when no such link is kept (the closure linked nothing, or was forgotten already), and
   * MapDatabaseError when the database cannot be written (the link is then kept in both).
   */
  std::vector<PlaceLink> forgetClosure(int frame, int reference);

  /// Map frame `index`'s frame id and number (StoredFrame), as added or loaded; "" and -1 for an
  /// index the map does not hold.
  std::string frameIdOf(int index) const;
  std::int64_t sequenceOf(int index) const;
  /// The traversal the map last loaded (or the database opened) records (MapDatabase::traversal);
  /// nullopt when it records none or no map was loaded since the last reset.
  const std::optional<MapTraversal>& loadedTraversal() const { return loaded_traversal_; }
  /// Bytes that the frames' ids and numbers hold (about 12 a frame), besides the recognizer's map.
  std::size_t labelBytes() const;

  bool persistent() const { return database_ != nullptr; }
  /// The format the database was converted from when it was opened (MapDatabase::convertedFromFormat).
  int convertedFromFormat() const { return database_ ? database_->convertedFromFormat() : 0; }
  /// The database's path; empty in memory only.
  std::string databasePath() const { return database_ ? database_->path() : ""; }
  /// Frames committed to the database, which survive a crash; 0 in memory only.
  std::uint64_t persisted() const { return writer_ ? writer_->persisted() : 0; }
  /// Why the last commit failed; empty when it succeeded.
  std::string writeError() const { return writer_ ? writer_->lastError() : ""; }
  /// Frames of the map waiting for a commit (kept through failed commits); 0 in memory only.
  std::size_t queued() const { return writer_ ? writer_->queued() : 0; }
  /// For a map that gets no frame any more (a node shutting down): commits what is queued, one last
  /// try, and stops committing. Returns the frames that try could not commit, which are lost with the
  /// process (writeError() says why); 0 in memory only.
  std::size_t close() { return writer_ ? writer_->stop() : 0; }

 private:
  FrameAdmission store(const cv::Mat& descriptor, Stamp stamp, const std::string& frame_id, std::int64_t sequence,
                       bool offered);
  std::int64_t saveFromMemory(const std::string& path, const std::optional<MapTraversal>& traversal);
  /// load()'s rewrite of the database by the frames of the map saved at `path`, which must be those of
  /// `prepared`; added frames are held back meanwhile.
  /// `traversal`, the new frames' record, and `links`, their place links, are written with them.
  void replaceDatabase(const std::string& path, const PlaceRecognizer::PreparedMap& prepared,
                       const FrameLabels& labels, const std::optional<MapTraversal>& traversal,
                       const std::vector<PlaceLink>& links, const std::vector<int>& drive_starts);

  PlaceRecognizer& recognizer_;
  std::unique_ptr<MapDatabase> database_;
  std::unique_ptr<MapWriter> writer_;
  // Held by add() while the frame goes to the map, its labels and the queue, so that all see frames
  // in one order; by reset() and load() while they swap the maps; by frameIdOf(), sequenceOf() and
  // saveFromMemory() while they read the labels.
  mutable std::mutex add_mutex_;
  // The frame ids and numbers of the recognizer's frames, in its order. Guarded by add_mutex_.
  FrameLabels labels_;
  /// Set at construction, by load() and by reset() (under whole_map_mutex_); read unlocked by
  /// loadedTraversal(), whose callers order their calls with load() and reset() themselves.
  std::optional<MapTraversal> loaded_traversal_;
  // The frames of the map that loaded_traversal_ is the record of: while the map holds no more, it is
  // still that map (frames are only ever appended). Written and read under whole_map_mutex_.
  int loaded_frames_ = 0;
  // labels_.memoryBytes(), for ~map_info, which must not wait for a reset's or a load's disk work.
  std::atomic<std::size_t> label_bytes_{0};
  // One whole-map operation (reset, load, save) at a time.
  std::mutex whole_map_mutex_;
  // While load() rewrites the database, add() holds the admitted frames back here instead of queuing
  // them for it. Both guarded by add_mutex_.
  bool rewriting_ = false;
  std::vector<StoredFrame> held_back_;
  std::size_t rewrite_room_ = 0;  // Frames the new map has room for after its own.
  // Set by reset() and load() while they replace the map: the writer then takes none of the place
  // links that queries make meanwhile, which name the old map's frames (install drops them), so that
  // none reaches the new map's database.
  std::atomic<bool> links_held_back_{false};
};

}  // namespace mrs_vpr

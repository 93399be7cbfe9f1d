#include "mrs_vpr/store/persistent_map.hpp"

#include <algorithm>
#include <exception>
#include <filesystem>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "linked_file.hpp"

namespace mrs_vpr {
namespace {

namespace fs = std::filesystem;

constexpr int kChunk = 4096;  // frames read or written at a time by a whole-map operation

/// Throws MapDatabaseError when `frames` do not fit in the recognizer's map.
void requireCapacity(const PlaceRecognizer& recognizer, const std::string& path, std::int64_t frames) {
  if (frames > std::numeric_limits<int>::max()) {
    throw MapDatabaseError("map database '" + path + "': it holds " + std::to_string(frames) +
                           " frames, more than a map can hold (" + std::to_string(std::numeric_limits<int>::max()) +
                           ")");
  }
  const int capacity = recognizer.recognizerParameters().max_frames;
  if (capacity > 0 && frames > capacity) {
    throw MapDatabaseError("map database '" + path + "': it holds " + std::to_string(frames) +
                           " frames, more than max_frames (" + std::to_string(capacity) +
                           "): raise max_frames to at least that, or to 0 (unbounded)");
  }
}

/// `recognizer`, which must hold no frame: frames join the map through a PersistentMap only, or they
/// would be missing from its database and have no labels.
PlaceRecognizer& requireEmpty(PlaceRecognizer& recognizer) {
  if (recognizer.size() + recognizer.pending() > 0) {
    throw std::logic_error("PersistentMap needs an empty PlaceRecognizer");
  }
  return recognizer;
}

/// Labels to reserve for a map of `frames`: with room for the camera's next frames, so that the first
/// of them does not copy a large map's labels on the camera's thread.
std::size_t withRoomToGrow(std::int64_t frames) { return static_cast<std::size_t>(frames + frames / 8 + 64); }

MapDatabaseError changedWhileLoaded(const std::string& path) {
  return MapDatabaseError("map database '" + path + "': it changed while it was loaded; load it again");
}

/// Gives `map`, whose frames were read from `database`, the place links the database keeps; returns them.
std::vector<PlaceLink> linkPlaces(PlaceRecognizer::PreparedMap& map, const MapDatabase& database) {
  // Checked there: every link is two of the frames read.
  std::vector<PlaceLink> links = database.placeLinks(map.size());
  map.linkPlaces(links);
  return links;
}

/// Holds a map's new place links back from its database while the map is replaced (see links_held_back_).
class LinksHeldBack {
 public:
  explicit LinksHeldBack(std::atomic<bool>& held) : held_(held) { held_ = true; }
  ~LinksHeldBack() { held_ = false; }
  LinksHeldBack(const LinksHeldBack&) = delete;
  LinksHeldBack& operator=(const LinksHeldBack&) = delete;

 private:
  std::atomic<bool>& held_;
};

}  // namespace

PersistentMap::PersistentMap(PlaceRecognizer& recognizer) : recognizer_(requireEmpty(recognizer)) {}

PersistentMap::PersistentMap(PlaceRecognizer& recognizer, const std::string& path, const CommitPolicy& policy)
    : recognizer_(requireEmpty(recognizer)),
      database_(std::make_unique<MapDatabase>(path, recognizer.parameters().descriptor)) {
  const std::int64_t frames = database_->size();
  requireCapacity(recognizer_, path, frames);
  // Streamed into a map built aside, as load() builds one: a million-frame map is not held twice, and
  // its size is known, so it is allocated once (with room for the camera's next frames).
  PlaceRecognizer::PreparedMap map = recognizer_.prepareMap(static_cast<int>(frames));
  labels_.reserve(withRoomToGrow(frames));
  database_->forEachFrame([&](const StoredFrame& frame) {
    map.append(frame.descriptor, frame.stamp);
    labels_.append(frame.frame_id, frame.sequence);
  });
  linkPlaces(map, *database_);
  map.markDriveStarts(database_->driveStarts());
  recognizer_.install(std::move(map));
  label_bytes_ = labels_.memoryBytes();
  loaded_traversal_ = database_->traversal();  // Before the camera's first frame makes it forgotten.
  loaded_frames_ = static_cast<int>(frames);
  // The links of accepted answers go to the database with the frames, but none of a map on its way
  // out: while reset() or load() replaces the map, they wait, and its install drops them.
  recognizer_.keepUnsavedLinks();
  writer_ = std::make_unique<MapWriter>(*database_, policy, [this] {
    return links_held_back_ ? std::vector<PlaceLink>() : recognizer_.takeUnsavedLinks();
  });
}

PersistentMap::~PersistentMap() {
  writer_.reset();  // Its last commit, before the database closes.
}

FrameAdmission PersistentMap::add(const cv::Mat& descriptor, Stamp stamp, const std::string& frame_id,
                                  std::int64_t sequence) {
  return store(descriptor, stamp, frame_id, sequence, false);
}

FrameAdmission PersistentMap::offer(const cv::Mat& descriptor, Stamp stamp, const std::string& frame_id,
                                    std::int64_t sequence) {
  return store(descriptor, stamp, frame_id, sequence, true);
}

FrameAdmission PersistentMap::store(const cv::Mat& descriptor, Stamp stamp, const std::string& frame_id,
                                    std::int64_t sequence, bool offered) {
  std::lock_guard<std::mutex> lock(add_mutex_);
  // Frames held back during a load's rewrite are for the new map: no more than it has room for.
  if (rewriting_ && held_back_.size() >= rewrite_room_) return FrameAdmission::kMapFull;
  FrameAdmission admission = FrameAdmission::kMapFull;
  const auto admit = [&] {
    admission =
        offered ? recognizer_.offerDescriptor(descriptor, stamp) : recognizer_.addDescriptor(descriptor, stamp);
    return admission == FrameAdmission::kAdmitted;
  };
  // The frame's labels, its record and its room in the queue are made before the map admits it: a
  // frame admitted has its labels and reaches the database, and a failed allocation (std::bad_alloc)
  // leaves it out of all of them.
  labels_.prepareFor(frame_id);
  bool labelled = false;
  const auto admitLabelled = [&] {
    if (!admit()) return false;
    labels_.append(frame_id, sequence);  // Cannot fail: prepared for.
    labelled = true;
    return true;
  };
  try {
    if (!writer_) {
      admitLabelled();
    } else if (!rewriting_) {
      writer_->addIf(StoredFrame{descriptor, stamp, frame_id, sequence}, admitLabelled);  // Shares the bytes.
    } else {
      if (held_back_.size() == held_back_.capacity()) {
        held_back_.reserve(std::max<std::size_t>(16, 2 * held_back_.capacity()));
      }
      StoredFrame frame{descriptor, stamp, frame_id, sequence};
      if (admitLabelled()) held_back_.push_back(std::move(frame));
    }
  } catch (...) {
    if (!labelled) labels_.cancelPrepared();
    throw;
  }
  if (!labelled) labels_.cancelPrepared();
  label_bytes_ = labels_.memoryBytes();
  return admission;
}

std::string PersistentMap::frameIdOf(int index) const {
  std::lock_guard<std::mutex> lock(add_mutex_);
  return index >= 0 && index < labels_.size() ? labels_.frameId(index) : "";
}

std::int64_t PersistentMap::sequenceOf(int index) const {
  std::lock_guard<std::mutex> lock(add_mutex_);
  return index >= 0 && index < labels_.size() ? labels_.sequence(index) : -1;
}

std::size_t PersistentMap::labelBytes() const { return label_bytes_; }

void PersistentMap::commit() {
  if (writer_) writer_->commit();
}

void PersistentMap::startDrive(int frame) {
  std::lock_guard<std::mutex> whole(whole_map_mutex_);
  recognizer_.markDriveStart(frame);
  if (writer_) writer_->withDatabase([&](MapDatabase& database) { database.addDriveStart(frame); });
}

std::vector<PlaceLink> PersistentMap::forgetClosure(int frame, int reference) {
  std::lock_guard<std::mutex> whole(whole_map_mutex_);
  const int frames = recognizer_.size();
  using Role = std::pair<const char*, int>;
  for (const auto& [role, index] : {Role{"localised frame", frame}, Role{"reference frame", reference}}) {
    if (index < 0 || index >= frames) {
      throw std::invalid_argument(std::string("the ") + role + " " + std::to_string(index) +
                                  " is not a frame of the map, " +
                                  (frames > 0 ? "which holds frames 0 to " + std::to_string(frames - 1)
                                              : std::string("which is empty")));
    }
  }
  std::vector<PlaceLink> links;
  const auto findLinks = [&] {
    links = recognizer_.linksOfClosure(frame, reference);
    if (links.empty()) {
      throw std::invalid_argument("map frame " + std::to_string(frame) + " is not linked to the place of map frame " +
                                  std::to_string(reference) +
                                  ": no accepted closure linked them (it was not accepted, or the two frames were "
                                  "one place already), or their link was forgotten already");
    }
  };
  if (writer_) {
    // After the commit of the links made so far, the database holds every link the recognizer keeps:
    // it loses them first, so that a failure leaves both as they were.
    writer_->withDatabase([&](MapDatabase& database) {
      findLinks();
      database.forgetLinks(links);
      recognizer_.forgetPlaceLinks(links);
    });
  } else {
    findLinks();
    recognizer_.forgetPlaceLinks(links);
  }
  return links;
}

int PersistentMap::reset() {
  std::lock_guard<std::mutex> whole(whole_map_mutex_);
  // The empty map is made first, then the database emptied: if either fails, the map stays as it is
  // and still matches its database. Putting the empty map in place cannot fail.
  PlaceRecognizer::PreparedMap empty = recognizer_.prepareMap({}, {});
  const LinksHeldBack held(links_held_back_);
  std::lock_guard<std::mutex> lock(add_mutex_);
  if (writer_) writer_->withDatabase([](MapDatabase& database) { database.clear(); });
  labels_.clear();
  label_bytes_ = labels_.memoryBytes();
  loaded_traversal_.reset();
  loaded_frames_ = 0;
  return recognizer_.install(std::move(empty));
}

int PersistentMap::load(const std::string& path) {
  std::lock_guard<std::mutex> whole(whole_map_mutex_);
  std::error_code ignored;
  if (database_ && fs::equivalent(path, database_->path(), ignored)) {
    throw MapDatabaseError("map database '" + path + "': it is this map's own database, already loaded");
  }
  // Everything is read and checked before anything changes: the recognizer's new map is built aside,
  // frame by frame as the file is read (a million-frame map is not held twice, as rows and as a map) ...
  FrameLabels labels;
  std::optional<MapTraversal> traversal;
  std::vector<PlaceLink> links;
  std::vector<int> drive_starts;
  PlaceRecognizer::PreparedMap prepared = [&] {
    const MapDatabase saved(path, recognizer_.parameters().descriptor, MapAccess::kReadOnly);
    std::optional<PlaceRecognizer::PreparedMap> map;
    saved.readAtOneMoment([&] {
      saved.checkIntegrity();
      traversal = saved.readTraversal();  // Of the frames read here, not of those when the file was opened.
      const std::int64_t frames = saved.size();
      requireCapacity(recognizer_, path, frames);
      map = recognizer_.prepareMap(static_cast<int>(frames));
      labels.reserve(withRoomToGrow(frames));
      saved.forEachFrame([&](const StoredFrame& frame) {
        map->append(frame.descriptor, frame.stamp);
        labels.append(frame.frame_id, frame.sequence);
      });
      links = linkPlaces(*map, saved);
      drive_starts = saved.driveStarts();
      map->markDriveStarts(drive_starts);
    });
    return std::move(*map);
  }();
  // ... the database rewritten from the file ...
  const LinksHeldBack held(links_held_back_);
  if (writer_) replaceDatabase(path, prepared, labels, traversal, links, drive_starts);
  // ... then the recognizer, by a move that cannot fail: a query meanwhile answers from the old map or
  // the new one. The frames that came while the database was rewritten follow the new map's.
  const int loaded = prepared.size();
  std::lock_guard<std::mutex> lock(add_mutex_);
  std::vector<StoredFrame> arrived;
  arrived.swap(held_back_);
  rewriting_ = false;
  recognizer_.install(std::move(prepared));
  labels_ = std::move(labels);
  loaded_traversal_ = traversal;
  loaded_frames_ = loaded;
  // The new map is in place in both: nothing may throw from here on. The frames fit (store() held back
  // no more than the new map has room for); only a failure to get memory would leave some out, of both.
  try {
    if (!arrived.empty()) recognizer_.reserve(static_cast<int>(loaded + arrived.size()));
    for (StoredFrame& frame : arrived) {
      labels_.prepareFor(frame.frame_id);
      FrameAdmission admission = recognizer_.addDescriptor(frame.descriptor, frame.stamp);
      if (admission == FrameAdmission::kPendingFull) {
        recognizer_.flush();  // A query holds the map: wait for it rather than drop a frame the camera gave.
        admission = recognizer_.addDescriptor(frame.descriptor, frame.stamp);
      }
      if (admission != FrameAdmission::kAdmitted) {
        labels_.cancelPrepared();
        break;
      }
      labels_.append(frame.frame_id, frame.sequence);
      writer_->add(std::move(frame));
    }
  } catch (const std::exception&) {
    // Out of memory: the frames not yet added are in neither, and the map still matches its database.
  }
  label_bytes_ = labels_.memoryBytes();
  return loaded;
}

void PersistentMap::replaceDatabase(const std::string& path, const PlaceRecognizer::PreparedMap& prepared,
                                    const FrameLabels& labels, const std::optional<MapTraversal>& traversal,
                                    const std::vector<PlaceLink>& links, const std::vector<int>& drive_starts) {
  // The database is rewritten in one transaction, which takes seconds for a large map. The camera's
  // frames go on joining the old map meanwhile, held back from the database so that it holds the old
  // map or the new one; load() puts them after the new map's frames ...
  {
    std::lock_guard<std::mutex> lock(add_mutex_);
    rewriting_ = true;
    const int capacity = recognizer_.recognizerParameters().max_frames;
    rewrite_room_ = capacity > 0 ? static_cast<std::size_t>(capacity - prepared.size())
                                 : std::numeric_limits<std::size_t>::max();
  }
  try {
    // The file is read a second time, rather than held in memory since the first, and must hold the
    // frames the new map was built from: else the database is left as it was.
    const MapDatabase saved(path, recognizer_.parameters().descriptor, MapAccess::kReadOnly);
    writer_->withDatabase([&](MapDatabase& database) {
      const auto frames = [&](const auto& insert) {
        int index = 0;
        saved.forEachFrame([&](const StoredFrame& frame) {
          if (!prepared.holds(index, frame.descriptor, frame.stamp) ||
              !labels.holds(index, frame.frame_id, frame.sequence)) {
            throw changedWhileLoaded(path);
          }
          insert(frame);
          ++index;
        });
        if (index != prepared.size()) throw changedWhileLoaded(path);
      };
      database.replace(frames, traversal, links, drive_starts);
    });
  } catch (...) {
    // ... or, when the rewrite fails, the old map stays in both, and its new frames go to its database.
    std::lock_guard<std::mutex> lock(add_mutex_);
    rewriting_ = false;
    for (StoredFrame& frame : held_back_) writer_->add(std::move(frame));
    held_back_.clear();
    throw;
  }
}

std::int64_t PersistentMap::save(const std::string& path, const std::optional<MapTraversal>& traversal) {
  std::lock_guard<std::mutex> whole(whole_map_mutex_);
  if (!writer_) return saveFromMemory(path, traversal);
  std::int64_t frames = 0;
  // Queued frames are committed first, so the snapshot holds every frame added before the call.
  writer_->withDatabase([&](MapDatabase& database) {
    database.backupTo(path);
    frames = database.size();
  });
  return frames;
}

std::int64_t PersistentMap::saveFromMemory(const std::string& path, const std::optional<MapTraversal>& traversal) {
  MapDatabase::checkSaveTarget(path);  // Before any work, in the words a backup would use.
  std::error_code ignored;
  // The frames go to a scratch database beside the target, which the online backup then turns into
  // the one-file snapshot, written aside and renamed like every saved map.
  const std::string scratch = linkedFile(path) + ".build";  // Beside the file written, through a link too.
  const auto removeScratch = [&] {
    fs::remove(scratch, ignored);
    MapDatabase::removeCompanions(scratch);
  };
  MapDatabase::removeUnfinished(scratch, path);  // What a save that stopped left; nothing of the user's.
  recognizer_.flush();
  const int frames = recognizer_.size();  // Frames added later are after the snapshot's moment.
  try {
    MapDatabase copy(scratch, recognizer_.parameters().descriptor);
    std::vector<StoredFrame> chunk;
    for (int begin = 0; begin < frames; begin += kChunk) {
      chunk.clear();
      recognizer_.visitFrames(begin, std::min(frames, begin + kChunk), [&](const cv::Mat& descriptor, Stamp stamp) {
        chunk.push_back({descriptor.clone(), stamp, "", -1});
      });
      {
        // The labels of frames the snapshot holds: those added since follow them, and none goes
        // while whole_map_mutex_ keeps reset() and load() out.
        std::lock_guard<std::mutex> lock(add_mutex_);
        for (std::size_t i = 0; i < chunk.size(); ++i) {
          const int index = begin + static_cast<int>(i);
          chunk[i].frame_id = labels_.frameId(index);
          chunk[i].sequence = labels_.sequence(index);
        }
      }
      copy.append(chunk);
    }
    // The loaded map's record holds while the snapshot is that map.
    const std::optional<MapTraversal>& record = (traversal || frames != loaded_frames_) ? traversal : loaded_traversal_;
    if (record) copy.setTraversal(*record);
    copy.append({}, recognizer_.placeLinks(frames));
    for (const int start : recognizer_.driveStarts()) {
      if (start <= frames) copy.addDriveStart(start);  // A start at `frames`: the next frame's drive.
    }
    copy.backupTo(path);
  } catch (const MapDatabaseError& error) {
    removeScratch();
    // The scratch file's name would only confuse: the user asked for `path`.
    const std::string message = error.what();
    if (message.find(scratch) == std::string::npos) throw;
    throw MapDatabaseError("cannot save the map to '" + path + "': " + message.substr(message.find(scratch) +
                                                                                        scratch.size() + 3));
  }
  removeScratch();
  return frames;
}

}  // namespace mrs_vpr

#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "mrs_vpr/store/map_database.hpp"

namespace mrs_vpr {

/// When queued frames are committed: whichever limit is reached first.
struct CommitPolicy {
  double period = 1.0;  ///< Longest wait of a frame for its commit [s].
  int frames = 100;     ///< Most frames in one commit's wait.
};

/**
 * Appends frames to a map database on a thread of its own, in batches: add() only queues (it never
 * waits for the disk), and a commit follows at most CommitPolicy::period seconds after the oldest
 * queued frame arrived, or as soon as CommitPolicy::frames are queued. persisted() counts the frames
 * committed, which survive a crash (even SIGKILL) of the process.
 *
 * Each commit also stores the place links that the map's accepted answers made since the last one,
 * taken from a LinkSource before the frames (a link names frames the map held when it was made, which
 * were queued by then); with no frame queued, the LinkSource is asked every CommitPolicy::period, so
 * that a link waits for its commit no longer than a frame does.
 *
 * A commit that fails (disk full, say) keeps its frames queued, in order, and its links, and is tried
 * again one period later; lastError() tells why meanwhile. Every member is thread-safe.
 */
class MapWriter {
 public:
  /// The place links made since it was last called (PlaceRecognizer::takeUnsavedLinks), on the
  /// writer's thread.
  using LinkSource = std::function<std::vector<PlaceLink>()>;

  /// `database` must outlive the writer, and is used only through it from now on; `links`, when
  /// given, must outlive it too.
  MapWriter(MapDatabase& database, const CommitPolicy& policy, LinkSource links = {});
  /// stop().
  ~MapWriter();

  MapWriter(const MapWriter&) = delete;
  MapWriter& operator=(const MapWriter&) = delete;

  /// Queues a frame for the next commit; cheap (the frame's descriptor is shared, not copied).
  void add(StoredFrame frame);
  /**
   * Makes room for one more frame in the queue, then calls `accept` (under the queue's lock, so that
   * nothing is committed in between) and queues `frame` when it returns true, with nothing left that
   * could fail. Throws std::bad_alloc, before `accept` is called, when the room cannot be had.
   * Returns what `accept` returned.
   */
  bool addIf(StoredFrame frame, const std::function<bool()>& accept);
  /// Commits every queued frame now; throws MapDatabaseError when that fails (the frames stay queued).
  void commit();
  /// Commits what is queued (one last try) and stops the thread; returns the frames that try could not
  /// commit (lastError() says why). Frames added later are never committed. Calling it again only
  /// returns the count.
  std::size_t stop();
  /**
   * Commits what is queued, then runs `task` on the database with no commit in between, so that it
   * sees every frame queued before the call; frames added meanwhile wait in the queue. persisted()
   * is then the database's frame count. Exceptions of `task` reach the caller.
   */
  void withDatabase(const std::function<void(MapDatabase& database)>& task);

  /// Frames committed: in the database, safe from a crash.
  std::uint64_t persisted() const { return persisted_.load(); }
  /// Frames waiting for a commit.
  std::size_t queued() const;
  /// Why the last commit failed; empty once one succeeds again.
  std::string lastError() const;

 private:
  void run();
  /// Commits the queue, holding database_mutex_; false when that failed.
  bool tryCommit();
  /// Commits the queue; the caller holds database_mutex_. Throws MapDatabaseError.
  void commitQueuedLocked();

  MapDatabase& database_;
  const CommitPolicy policy_;
  const LinkSource link_source_;
  std::vector<PlaceLink> links_;  // taken from link_source_, not yet committed; guarded by database_mutex_
  std::atomic<std::uint64_t> persisted_{0};

  // Lock order: database_mutex_, then queue_mutex_. The queue is taken while the database is held, so
  // that batches reach the database in the order their frames were added.
  std::mutex database_mutex_;
  mutable std::mutex queue_mutex_;
  std::condition_variable wake_;
  std::vector<StoredFrame> queue_;
  std::chrono::steady_clock::time_point oldest_;  // arrival of queue_.front()
  bool stopping_ = false;
  std::string last_error_;
  std::thread thread_;
};

}  // namespace mrs_vpr

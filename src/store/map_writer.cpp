#include "mrs_vpr/store/map_writer.hpp"

#include <algorithm>
#include <exception>
#include <iterator>
#include <utility>

namespace mrs_vpr {
namespace {

using Clock = std::chrono::steady_clock;

Clock::duration toDuration(double seconds) {
  return std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(seconds));
}

}  // namespace

MapWriter::MapWriter(MapDatabase& database, const CommitPolicy& policy, LinkSource links)
    : database_(database),
      policy_(policy),
      link_source_(std::move(links)),
      persisted_(static_cast<std::uint64_t>(database.size())) {
  thread_ = std::thread(&MapWriter::run, this);
}

MapWriter::~MapWriter() { stop(); }

std::size_t MapWriter::stop() {
  {
    std::lock_guard<std::mutex> lock(queue_mutex_);
    stopping_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
  // The thread may have ended on a commit that began before the stop and failed, with frames queued
  // meanwhile never tried: one last try of everything, now that nothing else commits.
  try {
    commit();
  } catch (const std::exception&) {
    // lastError() says why; the caller is told how many frames are left.
  }
  return queued();
}

void MapWriter::add(StoredFrame frame) {
  addIf(std::move(frame), [] { return true; });
}

bool MapWriter::addIf(StoredFrame frame, const std::function<bool()>& accept) {
  std::lock_guard<std::mutex> lock(queue_mutex_);
  if (queue_.size() == queue_.capacity()) queue_.reserve(std::max<std::size_t>(16, 2 * queue_.capacity()));
  if (!accept()) return false;
  const bool was_empty = queue_.empty();
  if (was_empty) oldest_ = Clock::now();
  queue_.push_back(std::move(frame));
  // The thread sleeps until a frame arrives (then until its deadline) or a batch is full.
  if (was_empty || static_cast<int>(queue_.size()) >= policy_.frames) wake_.notify_one();
  return true;
}

void MapWriter::commit() {
  std::lock_guard<std::mutex> lock(database_mutex_);
  commitQueuedLocked();
}

void MapWriter::withDatabase(const std::function<void(MapDatabase& database)>& task) {
  std::lock_guard<std::mutex> lock(database_mutex_);
  commitQueuedLocked();
  try {
    task(database_);
  } catch (...) {
    try {
      persisted_ = static_cast<std::uint64_t>(database_.size());
    } catch (const std::exception&) {  // The task's failure is the one to report.
    }
    throw;
  }
  persisted_ = static_cast<std::uint64_t>(database_.size());
}

std::size_t MapWriter::queued() const {
  std::lock_guard<std::mutex> lock(queue_mutex_);
  return queue_.size();
}

std::string MapWriter::lastError() const {
  std::lock_guard<std::mutex> lock(queue_mutex_);
  return last_error_;
}

void MapWriter::commitQueuedLocked() {
  // The links before the frames: the frames each names were queued before it was made.
  if (link_source_) {
    std::vector<PlaceLink> made = link_source_();
    links_.insert(links_.end(), made.begin(), made.end());
  }
  std::vector<StoredFrame> batch;
  Clock::time_point batch_oldest;
  {
    std::lock_guard<std::mutex> lock(queue_mutex_);
    batch.swap(queue_);
    batch_oldest = oldest_;
  }
  if (batch.empty() && links_.empty()) return;
  try {
    database_.append(batch, links_);  // One transaction: all of the batch is on disk, or none of it.
    links_.clear();
  } catch (const std::exception& error) {
    // Back to the front of the queue, before anything added meanwhile, for the next try.
    std::lock_guard<std::mutex> lock(queue_mutex_);
    batch.insert(batch.end(), std::make_move_iterator(queue_.begin()), std::make_move_iterator(queue_.end()));
    queue_.swap(batch);
    oldest_ = batch_oldest;
    last_error_ = error.what();
    throw MapDatabaseError(last_error_);
  }
  persisted_ += batch.size();
  std::lock_guard<std::mutex> lock(queue_mutex_);
  last_error_.clear();
}

bool MapWriter::tryCommit() {
  std::lock_guard<std::mutex> database_lock(database_mutex_);
  try {
    commitQueuedLocked();
  } catch (const std::exception&) {
    return false;  // lastError() has it; the frames and links wait for the next try.
  }
  return true;
}

void MapWriter::run() {
  std::unique_lock<std::mutex> lock(queue_mutex_);
  const auto frames_or_stop = [&] { return stopping_ || !queue_.empty(); };
  for (;;) {
    // Links also come with no frame after them (a robot standing, a full map, a service's question):
    // asked for every period, so that none waits longer than a frame would.
    if (link_source_) {
      wake_.wait_for(lock, toDuration(policy_.period), frames_or_stop);
    } else {
      wake_.wait(lock, frames_or_stop);
    }
    if (queue_.empty()) {
      if (stopping_) return;  // Everything is committed (stop() commits the links left).
      lock.unlock();
      tryCommit();  // The links alone, if any: nothing is written otherwise.
      lock.lock();
      continue;
    }
    wake_.wait_until(lock, oldest_ + toDuration(policy_.period),
                     [&] { return stopping_ || static_cast<int>(queue_.size()) >= policy_.frames; });
    lock.unlock();
    const bool failed = !tryCommit();
    lock.lock();
    if (failed) {
      if (stopping_) return;  // The last try failed too: the map keeps these frames, the file does not.
      wake_.wait_for(lock, toDuration(policy_.period), [&] { return stopping_; });
    }
  }
}

}  // namespace mrs_vpr

#pragma once

#include <atomic>
#include <stdexcept>

namespace mrs_vpr {

/// Thrown by a query that was stopped (PlaceRecognizer::stopQueries).
class QueryStopped : public std::runtime_error {
 public:
  QueryStopped() : std::runtime_error("the query was stopped: its recognizer is shutting down") {}
};

/**
 * A request, from any thread or from a signal handler, that running queries stop within a block of
 * their work and that later ones refuse: a node shutting down need not wait for a long brute-force
 * question. Only ever set, never cleared.
 */
class QueryStop {
 public:
  void request() noexcept { requested_.store(true, std::memory_order_relaxed); }
  bool requested() const noexcept { return requested_.load(std::memory_order_relaxed); }
  /// Throws QueryStopped once requested.
  void throwIfRequested() const {
    if (requested()) throw QueryStopped();
  }

 private:
  static_assert(std::atomic<bool>::is_always_lock_free, "request() must be safe in a signal handler");
  std::atomic<bool> requested_{false};
};

/// `stop` (may be null) asks to stop: for the blocks of a parallel loop, which cannot throw.
inline bool stopRequested(const QueryStop* stop) { return stop != nullptr && stop->requested(); }

/// Throws QueryStopped when `stop` (may be null) asks to: after a parallel loop that skipped blocks.
inline void throwIfStopped(const QueryStop* stop) {
  if (stop != nullptr) stop->throwIfRequested();
}

}  // namespace mrs_vpr

#pragma once

#include <cstddef>
#include <memory>

#include <opencv2/core.hpp>

namespace mrs_vpr {

/**
 * Storage for a query's N x M float matrix that a querying thread keeps for its next query. The map
 * grows by a frame at a time, so a cv::Mat of the new size would be allocated afresh (and its pages
 * faulted in) for every query; this storage only grows, geometrically. Storage above
 * kKeptQueryBufferBytes is handed back after the query (release()), so that one long query on a
 * huge map does not stay resident.
 */
class QueryBuffer {
 public:
  /// A CV_32FC1 matrix of rows x cols over the kept storage (its contents are not initialised).
  /// Valid until the next call.
  cv::Mat matrix(int rows, int cols);
  /// Frees the storage when it is larger than kKeptQueryBufferBytes.
  void release();
  /// Bytes held.
  std::size_t capacityBytes() const { return capacity_ * sizeof(float); }

  /// Calls release() as it goes out of scope, also when the query throws.
  class ReleaseAtExit {
   public:
    explicit ReleaseAtExit(QueryBuffer& buffer) : buffer_(buffer) {}
    ~ReleaseAtExit() { buffer_.release(); }
    ReleaseAtExit(const ReleaseAtExit&) = delete;
    ReleaseAtExit& operator=(const ReleaseAtExit&) = delete;

   private:
    QueryBuffer& buffer_;
  };

 private:
  // Not zeroed: every query writes its matrix whole before reading it, and zeroing a fresh buffer
  // was a third of a 1000 x 200k brute-force question's time.
  std::unique_ptr<float[]> storage_;
  std::size_t capacity_ = 0;  // floats
};

/// Largest buffer a thread keeps between queries: N = 100 on a 100k-frame map (40 MB).
constexpr std::size_t kKeptQueryBufferBytes = 64UL * 1024 * 1024;

}  // namespace mrs_vpr

#pragma once

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "mrs_vpr/descriptor_sequence.hpp"

namespace mrs_vpr {

/**
 * Contrast-enhanced differences between a test sequence and a reference, computed only where a
 * search looks and remembered for the rest of the search. A sampling level of stride s sees the test
 * frames `anchor + k * s` and the reference grid `J * s`; the raw differences are shared by all levels
 * (a coarse grid point is also a fine one), the enhanced values belong to a level.
 */
class LazyDifferenceMatrix {
 public:
  LazyDifferenceMatrix(SequenceView query, SequenceView reference, int contrast_window);

  /// Switches to a level: test frame `anchor + k * stride`, reference grid J * stride.
  void setLevel(int stride, int anchor);

  /// Enhanced difference between test frame anchor + k * stride and reference frame J * stride.
  float enhanced(int k, int grid_index);

  /// Reference frames on the current level's grid.
  int gridSize() const { return grid_size_; }
  /// Raw descriptor comparisons made so far.
  long long comparisons() const { return comparisons_; }

 private:
  float raw(int test_frame, int reference_frame);

  SequenceView query_;
  SequenceView reference_;
  int contrast_window_;
  int stride_ = 1;
  int anchor_ = 0;
  int grid_size_ = 0;
  long long comparisons_ = 0;
  std::unordered_map<std::uint64_t, float> raw_;
  std::unordered_map<std::uint64_t, float> enhanced_;
  std::vector<float> window_;
};

}  // namespace mrs_vpr

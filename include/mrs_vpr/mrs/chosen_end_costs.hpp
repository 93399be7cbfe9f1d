#pragma once

#include <vector>

#include "mrs_vpr/descriptor_sequence.hpp"
#include "mrs_vpr/trajectory_search.hpp"

namespace mrs_vpr {

/**
 * The brute force's costs (costsByAnchor on the contrast-enhanced full difference matrix) of chosen
 * ends only, from the cells their trajectories visit and the raw differences their contrast windows
 * see: a few hundred ends of a large map cost a few hundred thin diagonal bands of the matrix, not
 * the matrix. The cells are enhanced row by row as enhanceContrast does (enhanceRowSpan, with each
 * row's difference at column 0) and summed in the order costsByAnchor sums them, so a cost equals the
 * brute force's to the bit.
 */
class ChosenEndCosts {
 public:
  /// `reference` and `query` must outlive this object; `rows` as for costsByAnchor.
  ChosenEndCosts(SequenceView reference, SequenceView query, const SequenceRows& rows, std::vector<double> velocities,
                 int contrast_window);

  /// Costs and velocities of ends [begin, end) into cost[0 .. end - begin) and velocity[...]
  /// (infinity where no trajectory fits). Returns the raw descriptor comparisons made. Thread-safe.
  long long compute(int begin, int end, float* cost, float* velocity) const;

  /// Raw comparisons compute(end, end + 1) makes for one end far from the map's edges.
  long long comparisonsPerEnd() const;

 private:
  SequenceView reference_;
  SequenceView query_;
  SequenceRows rows_;
  std::vector<double> velocities_;
  int contrast_window_;
  std::vector<std::vector<int>> offsets_;  ///< offsets_[v][t - first]: row t's column, relative to the end's.
  std::vector<int> lowest_;                ///< Per row: the lowest offset of any velocity.
  std::vector<int> highest_;               ///< Per row: the highest.
  std::vector<float> first_differences_;   ///< Per row: at column 0, for enhanceRowSpan.
};

}  // namespace mrs_vpr

#pragma once

namespace mrs_vpr {

/// The answer of a sequence search.
struct Match {
  /// Reference frame (index into the searched reference view) matched to the query frame; -1 when none.
  int reference_index = -1;
  /// OpenSeqSLAM's match score: best / runner-up sequence difference, in [0, 1]; lower is better.
  float score = 1.0F;
  /// 1 - score: how much better the best sequence is than the runner-up; higher is surer.
  float confidence = 0.0F;
  /// Mean (shifted, contrast-enhanced) difference along the best trajectory; lower is more similar.
  float sequence_difference = 0.0F;
  /// Difference cells evaluated (image comparisons); a machine-independent measure of cost.
  long long comparisons = 0;
};

}  // namespace mrs_vpr

#pragma once

namespace mrs_vpr {

/// The answer of a sequence search.
struct Match {
  /// Reference frame (index into the searched reference view) matched to the query frame; -1 when none.
  int reference_index = -1;
  /// OpenSeqSLAM's match score: best / runner-up sequence difference, in [0, 1]; lower is better.
  float score = 1.0F;
  /**
   * Distinctiveness: by how many standard deviations of the costs of all ends the best sequence
   * beats its best rival (the lowest cost farther than match_exclusion / 2 from it), >= 0; higher is
   * surer; 0 when the answer's trajectory runs at a velocity bound. Unlike the ratio of `score`, it is measured in the
   * noise of this very query, so a threshold means the same for every method, sequence length and map size (see
   * acceptance.hpp).
   */
  float confidence = 0.0F;
  /// Ends with a trajectory outside the answer's window: the wrong places the confidence was judged
  /// against. Below kMinRivalEnds (acceptance.hpp) the confidence is 0: the map is too small to tell.
  int rivals = 0;
  /// The distinct places among the rivals (placesAmong, acceptance.hpp): on maps of fewer than
  /// kPlacesForPlainThreshold the confidence needed rises (requiredConfidence).
  int rival_places = 0;
  /// Whether the answer passes the acceptance rule (applyAcceptance): a match was found, confidence
  /// >= SequenceParams::accept_threshold and its velocity is not a bound of the searched ones. Only
  /// accepted answers should be used as loop closures.
  bool accepted = false;
  /// Reference frames per test frame along the answer's trajectory (0 when no match was found).
  float velocity = 0.0F;
  /// The trajectory runs at the slowest or fastest velocity searched (atVelocityBound): such an
  /// answer has confidence 0 and is never accepted.
  bool at_velocity_bound = false;
  /// Most of the test sequence's keyframes show one view again (repeated_views.hpp): a camera standing
  /// where its noise made keyframes. Set on an answer that passed the rest of the acceptance rule, which
  /// is then not accepted.
  bool repeated_view = false;
  /// The test sequence's keyframes are in the map already near the answer, at the same times with the
  /// same views (one recording added to the map twice, as a bag played again): a frame that finds
  /// itself, no loop closure (PlaceRecognizer::matchRecent). Set, as repeated_view, on an answer that is
  /// then not accepted.
  bool same_recording = false;
  /// The test sequence returns to a place it passed (turn_back.hpp): a robot that turned back or backed
  /// up, which trajectories running forwards place where the way out leads. Set, as repeated_view, on an
  /// answer that is then not accepted.
  bool turned_back = false;
  /// The answer's trajectory runs across the junction of two drives (drive_starts.hpp): a map loaded
  /// and the camera's frames after it, or two visits appended one after the other. Set, as
  /// repeated_view, on an answer that is then not accepted.
  bool across_drives = false;
  /// Mean difference along the best trajectory at the level that chose the answer (contrast-enhanced
  /// and shifted for seqslam and MRS's comparing level, raw at MRS's deeper levels); lower is more
  /// similar. Compare it between answers of one method and sequence length only.
  float sequence_difference = 0.0F;
  /// Difference cells evaluated (image comparisons); a machine-independent measure of cost.
  long long comparisons = 0;
};

}  // namespace mrs_vpr

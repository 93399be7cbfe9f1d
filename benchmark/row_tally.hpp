#pragma once

// A row of the map-scale benchmark: mrs's answers and times, and the brute force's on the first of
// the same questions, side by side.

#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "mrs_vpr/place_recognizer.hpp"

namespace mrs_vpr {
namespace benchmark {

/// The upper median (median.hpp), as the figures in the documentation were taken; 0 for no values.
double upperMedianOf(std::vector<double> values);

/// One row's figures: mrs's answers and times, and the brute force's on the first of the same questions.
struct RowTally {
  std::vector<double> mrs_ms;
  /// mrs's times on the questions the brute force was asked too: the speed-up compares like with like.
  std::vector<double> paired_mrs_ms;
  std::vector<double> brute_ms;
  int mrs_right = 0;
  int mrs_accepted = 0;
  int mrs_accepted_wrong = 0;
  int brute_right = 0;
  int same_frame = 0;
  int same_accepted = 0;
  double confidence_gap = 0.0;

  /// Asks `ask` once with each method, untimed, so that no timed question pays for the buffers that
  /// the searches keep between questions (a row's first question would, and only the brute force's
  /// few timed questions would show it).
  static void warmUp(const std::function<PlaceAnswer(const char* method)>& ask);
  /// Times `ask` (a question to the method named) with mrs, and with the brute force too when
  /// `with_brute`; `right` judges an answer. Returns the answers (the brute force's when asked).
  std::pair<PlaceAnswer, std::optional<PlaceAnswer>> time(const std::function<PlaceAnswer(const char* method)>& ask,
                                                          bool with_brute,
                                                          const std::function<bool(const PlaceAnswer&)>& right);
  void addMrs(const PlaceAnswer& mrs, double ms, bool right);
  void addBrute(const PlaceAnswer& mrs, const PlaceAnswer& brute, double ms, bool right);
  /// Prints the row of map `map`, test sequences of `length` frames, queries of `kind`.
  void print(const std::string& map, int length, const char* kind, double load_s, double rss_per_frame,
             double peak_per_frame) const;
};

}  // namespace benchmark
}  // namespace mrs_vpr

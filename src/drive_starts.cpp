#include "mrs_vpr/drive_starts.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "mrs_vpr/parameters.hpp"

namespace mrs_vpr {
namespace {

/// The first of `starts` within (begin, end), or -1: a junction with frames of [begin, end) on both sides.
int junctionWithin(FrameRange frames, const std::vector<int>& starts) {
  const auto after_begin = std::upper_bound(starts.begin(), starts.end(), frames.begin);
  return after_begin != starts.end() && *after_begin < frames.end ? *after_begin : -1;
}

}  // namespace

void refuseTestSequenceAcrossDrives(FrameRange test, const std::vector<int>& starts) {
  const int start = junctionWithin(test, starts);
  if (start < 0) return;
  const int next = test.end - start;
  const std::string fewer = next >= kMinSequenceFrames ? "ask about at most " + std::to_string(next) + ", or " : "ask ";
  throw std::invalid_argument("a test sequence of " + std::to_string(test.size()) + " frames would join the last " +
                              std::to_string(start - test.begin) + " frames of one drive to the first " +
                              std::to_string(next) + " of the next (a map was loaded, or a visit appended, " +
                              "between them): their junction is no place; " + fewer + "about " +
                              std::to_string(test.size()) + " once the next drive holds that many");
}

FrameRange trajectoryFrames(const Match& match, const SequenceRows& rows) {
  const auto at = [&](int row) {
    return match.reference_index + static_cast<int>(std::lround(match.velocity * (row - rows.anchor)));
  };
  return {at(rows.first), at(rows.last) + 1};
}

void refuseAcrossDrives(Match& match, const SequenceRows& rows, const std::vector<int>& starts) {
  if (!match.accepted || junctionWithin(trajectoryFrames(match, rows), starts) < 0) return;
  match.across_drives = true;
  match.accepted = false;
}

}  // namespace mrs_vpr

#include "mrs_vpr/drive_starts.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <stdexcept>
#include <string>

#include "mrs_vpr/parameters.hpp"

namespace mrs_vpr {
namespace {

/// The last of `starts` within (begin, end), or -1: a junction with frames of [begin, end) on both sides.
int lastJunctionWithin(FrameRange frames, const std::vector<int>& starts) {
  const auto before_end = std::lower_bound(starts.begin(), starts.end(), frames.end);
  if (before_end == starts.begin()) return -1;
  const int start = *std::prev(before_end);
  return start > frames.begin ? start : -1;
}

/// The searched velocity nearest `velocity`: the float a Match holds may round otherwise than the
/// double the search placed its trajectory with.
double searchedVelocity(float velocity, const std::vector<double>& velocities) {
  if (velocities.empty()) return velocity;
  const auto nearer = [velocity](double a, double b) { return std::abs(a - velocity) < std::abs(b - velocity); };
  return *std::min_element(velocities.begin(), velocities.end(), nearer);
}

}  // namespace

bool insertDriveStart(std::vector<int>& starts, int frame) {
  if (frame < 0) throw std::invalid_argument("a drive cannot start at map frame " + std::to_string(frame));
  const auto at = std::lower_bound(starts.begin(), starts.end(), frame);
  if (frame == 0 || (at != starts.end() && *at == frame)) return false;
  starts.insert(at, frame);
  return true;
}

void refuseTestSequenceAcrossDrives(FrameRange test, const std::vector<int>& starts) {
  const int start = lastJunctionWithin(test, starts);
  if (start < 0) return;
  const int own = test.end - start;
  const std::string fewer =
      own >= kMinSequenceFrames ? "at most " + std::to_string(own) + " frames, or about " : std::string();
  throw std::invalid_argument(
      "a test sequence of map frames [" + std::to_string(test.begin) + ", " + std::to_string(test.end) +
      ") runs across the start of a drive at frame " + std::to_string(start) +
      " (a map was loaded, as by a node started on its database or ~load_map, or a visit appended, before it): "
      "the junction of two drives is no place; ask about " + fewer + std::to_string(test.size()) +
      " once the drive holds that many");
}

FrameRange trajectoryFrames(const Match& match, const SequenceRows& rows, const std::vector<double>& velocities) {
  const double velocity = searchedVelocity(match.velocity, velocities);
  const auto at = [&](int row) {
    return match.reference_index + static_cast<int>(std::lround(velocity * (row - rows.anchor)));
  };
  return {at(rows.first), at(rows.last) + 1};
}

void refuseAcrossDrives(Match& match, const SequenceRows& rows, const std::vector<int>& starts,
                        const std::vector<double>& velocities) {
  if (!match.accepted || lastJunctionWithin(trajectoryFrames(match, rows, velocities), starts) < 0) return;
  match.across_drives = true;
  match.accepted = false;
}

}  // namespace mrs_vpr

#include "mrs_vpr/evaluation/camera_drive.hpp"

#include <algorithm>
#include <iterator>
#include <limits>
#include <map>
#include <stdexcept>
#include <string>

#include <opencv2/imgproc.hpp>

#include "mrs_vpr/number_text.hpp"

namespace mrs_vpr {
namespace {

/// The width the settings' noise, vibration and figure are given at.
constexpr double kReferenceWidth = 64.0;

/// SplitMix64's finaliser: each drive frame gets a generator of its own, so that a frame is the same
/// image however many frames were drawn before it.
std::uint64_t mixed(std::uint64_t value) {
  value += 0x9E3779B97F4A7C15ULL;
  value = (value ^ (value >> 30U)) * 0xBF58476D1CE4E5B9ULL;
  value = (value ^ (value >> 27U)) * 0x94D049BB133111EBULL;
  return value ^ (value >> 31U);
}

std::string settingError(const std::string& name, const std::string& allowed, double value) {
  return "camera drive: " + name + " must be " + allowed + ", got " + numberText(value);
}

/// Draws a dark upright figure (a body and a head) whose feet are at (x, foot) into `mask` as
/// anti-aliased coverage 0..255, at sub-pixel positions, so that it moves smoothly between frames.
void drawFigure(cv::Mat& mask, double x, double foot, double width, double height) {
  constexpr int kShift = 8;  // Fixed-point bits of OpenCV's drawing functions.
  constexpr double kScale = 1 << kShift;
  const double head_radius = std::min(0.35 * width, 0.125 * height);
  const double body_height = height - 2.0 * head_radius;
  const auto point = [&](double px, double py) {
    return cv::Point(cv::saturate_cast<int>(px * kScale), cv::saturate_cast<int>(py * kScale));
  };
  cv::ellipse(
      mask, point(x, foot - body_height / 2.0),
      cv::Size(cv::saturate_cast<int>(width / 2.0 * kScale), cv::saturate_cast<int>(body_height / 2.0 * kScale)), 0.0,
      0.0, 360.0, cv::Scalar(255), cv::FILLED, cv::LINE_AA, kShift);
  cv::circle(mask, point(x, foot - body_height - head_radius), cv::saturate_cast<int>(head_radius * kScale),
             cv::Scalar(255), cv::FILLED, cv::LINE_AA, kShift);
}

}  // namespace

void CameraDriveSettings::validate() const {
  // A drive is held in memory and written as images: an hour's stop at 30 Hz is plenty.
  constexpr int kMostStops = 1000;
  constexpr int kMostStopFrames = 100000;
  if (stops < 0 || stops > kMostStops) {
    throw std::invalid_argument(settingError("stops", "in 0.." + std::to_string(kMostStops), stops));
  }
  if (stops > 0 && stop_frames_min < 1)
    throw std::invalid_argument(settingError("stop_frames_min", ">= 1", stop_frames_min));
  if (stop_frames_max < stop_frames_min) {
    throw std::invalid_argument(settingError(
        "stop_frames_max", ">= stop_frames_min (" + std::to_string(stop_frames_min) + ")", stop_frames_max));
  }
  if (stop_frames_max > kMostStopFrames) {
    throw std::invalid_argument(
        settingError("stop_frames_max", "<= " + std::to_string(kMostStopFrames), stop_frames_max));
  }
  if (slow_frames < 0) throw std::invalid_argument(settingError("slow_frames", ">= 0", slow_frames));
  if (fast_frames < 0) throw std::invalid_argument(settingError("fast_frames", ">= 0", fast_frames));
  // Without noise a copy could come out exact; at 100 grey levels it is no longer a view of the place.
  if (!(noise_std > 0.0 && noise_std <= 100.0))
    throw std::invalid_argument(settingError("noise_std", "in (0, 100]", noise_std));
  if (!(vibration >= 0.0 && vibration <= 1.0))
    throw std::invalid_argument(settingError("vibration", "in 0..1 px", vibration));
  if (!(gain >= 0.0 && gain < 0.5)) throw std::invalid_argument(settingError("gain", "in [0, 0.5)", gain));
}

std::string toString(DriveFrameKind kind) {
  switch (kind) {
    case DriveFrameKind::kMoving:
      return "moving";
    case DriveFrameKind::kStopped:
      return "stopped";
    case DriveFrameKind::kSlowCopy:
      return "slow";
  }
  return "moving";
}

DriveFrameKind parseDriveFrameKind(const std::string& text) {
  for (const DriveFrameKind kind : {DriveFrameKind::kMoving, DriveFrameKind::kStopped, DriveFrameKind::kSlowCopy}) {
    if (toString(kind) == text) return kind;
  }
  throw std::invalid_argument("unknown drive frame kind '" + text + "' (expected moving, stopped or slow)");
}

CameraDrive::CameraDrive(int route_frames, const CameraDriveSettings& settings) : settings_(settings) {
  settings_.validate();
  const int slow = settings_.slow_frames;
  const int fast = settings_.fast_frames;
  if (route_frames < 1 || route_frames < slow + fast + settings_.stops) {
    throw std::invalid_argument("camera drive: a route of " + std::to_string(route_frames) +
                                " frames cannot hold a half-speed stretch of " + std::to_string(slow) +
                                ", a double-speed stretch of " + std::to_string(fast) + " and " +
                                std::to_string(settings_.stops) + " stops (one route frame each)");
  }
  cv::RNG rng(mixed(settings_.seed));

  // The stretches: two seeded gaps in the frames that neither takes, either stretch first.
  const int spare = route_frames - slow - fast;
  const int a = rng.uniform(0, spare + 1);
  const int b = rng.uniform(0, spare + 1);
  const bool slow_first = rng.uniform(0, 2) == 0;
  const int first_begin = std::min(a, b);
  const int second_begin = std::max(a, b) + (slow_first ? slow : fast);
  slow_begin_ = slow == 0 ? -1 : (slow_first ? first_begin : second_begin);
  fast_begin_ = fast == 0 ? -1 : (slow_first ? second_begin : first_begin);
  const auto in_slow = [&](int r) { return slow_begin_ >= 0 && r >= slow_begin_ && r < slow_begin_ + slow; };
  const auto in_fast = [&](int r) { return fast_begin_ >= 0 && r >= fast_begin_ && r < fast_begin_ + fast; };

  // The stops: one in each equal share of the frames at normal speed, so that they spread over the route.
  std::vector<int> normal;
  for (int r = 0; r < route_frames; ++r) {
    if (!in_slow(r) && !in_fast(r)) normal.push_back(r);
  }
  std::map<int, int> stop_length_at;  // route frame -> frames of its stop
  const auto count = static_cast<long long>(normal.size());
  for (int k = 0; k < settings_.stops; ++k) {
    const auto low = static_cast<int>(k * count / settings_.stops);
    const auto high = static_cast<int>((k + 1) * count / settings_.stops);
    const int at = normal[static_cast<std::size_t>(rng.uniform(low, high))];
    stop_length_at[at] = rng.uniform(settings_.stop_frames_min, settings_.stop_frames_max + 1);
    PasserBy passer_by;
    passer_by.left_to_right = rng.uniform(0, 2) == 0;
    passer_by.darkness = rng.uniform(0.05, 0.25);
    passer_by.foot = rng.uniform(0.85, 1.0);
    passers_by_.push_back(passer_by);
  }

  for (int r = 0; r < route_frames; ++r) {
    if (in_fast(r) && (r - fast_begin_) % 2 == 1) continue;
    frames_.push_back({r, DriveFrameKind::kMoving, -1, 0, 0});
    if (in_slow(r)) frames_.push_back({r, DriveFrameKind::kSlowCopy, -1, 0, 0});
    const auto stop = stop_length_at.find(r);
    if (stop == stop_length_at.end()) continue;
    const int index = static_cast<int>(std::distance(stop_length_at.begin(), stop));
    for (int i = 0; i < stop->second; ++i) frames_.push_back({r, DriveFrameKind::kStopped, index, i, stop->second});
  }
  route_frames_ = route_frames;
}

std::vector<int> routeFramesOf(const std::vector<DriveFrame>& frames) {
  std::vector<int> route;
  route.reserve(frames.size());
  for (const DriveFrame& frame : frames) route.push_back(frame.route_frame);
  return route;
}

cv::Mat CameraDrive::render(int index, const cv::Mat& route_image) const {
  if (index < 0 || index >= size()) {
    throw std::out_of_range("drive frame " + std::to_string(index) + " of " + std::to_string(size()));
  }
  if (route_image.empty() || route_image.depth() != CV_8U ||
      (route_image.channels() != 1 && route_image.channels() != 3 && route_image.channels() != 4)) {
    throw std::invalid_argument("camera drive: route images must be 8-bit with 1, 3 or 4 channels");
  }
  const DriveFrame& frame = frames_[static_cast<std::size_t>(index)];
  if (frame.kind == DriveFrameKind::kMoving) return route_image.clone();

  cv::RNG rng(mixed(settings_.seed ^ mixed(static_cast<std::uint64_t>(index) + 1)));
  const double scale = route_image.cols / kReferenceWidth;
  cv::Mat view;
  route_image.convertTo(view, CV_32FC(route_image.channels()));

  // Vibration: a sub-pixel shift of the whole view.
  const double reach = settings_.vibration * scale;
  const cv::Mat shift = (cv::Mat_<double>(2, 3) << 1, 0, rng.uniform(-reach, reach), 0, 1, rng.uniform(-reach, reach));
  cv::warpAffine(view, view, shift, view.size(), cv::INTER_LINEAR, cv::BORDER_REFLECT_101);

  if (frame.kind == DriveFrameKind::kStopped) {
    // The passer-by enters at the stop's first frame and has left after its last.
    const PasserBy& passer_by = passers_by_[static_cast<std::size_t>(frame.stop)];
    const double width = route_image.cols / 10.0;
    const double height = route_image.rows / 2.0;
    const double progress = (frame.stop_frame + 0.5) / frame.stop_length;
    const double travelled = -width / 2.0 + progress * (route_image.cols + width);
    const double x = passer_by.left_to_right ? travelled : route_image.cols - travelled;
    cv::Mat coverage = cv::Mat::zeros(route_image.size(), CV_8UC1);
    drawFigure(coverage, x, passer_by.foot * route_image.rows, width, height);
    cv::Mat weight;
    coverage.convertTo(weight, CV_32F, 1.0 / 255.0);
    std::vector<cv::Mat> channels;
    cv::split(view, channels);
    for (cv::Mat& channel : channels) {
      channel = channel.mul(1.0 - weight) + weight * (passer_by.darkness * 255.0);
    }
    cv::merge(channels, view);
  }

  // Gain, then sensor noise on the brightness (the same on every channel: grey levels).
  view *= rng.uniform(1.0 - settings_.gain, 1.0 + settings_.gain);
  cv::Mat noise(route_image.size(), CV_32FC1);
  rng.fill(noise, cv::RNG::NORMAL, 0.0, settings_.noise_std * scale);
  std::vector<cv::Mat> channels;
  cv::split(view, channels);
  for (cv::Mat& channel : channels) channel += noise;
  cv::merge(channels, view);
  cv::Mat image;
  view.convertTo(image, route_image.type());

  // Never an exact copy: should rounding undo every change, one seeded pixel moves by a grey level.
  if (cv::norm(image, route_image, cv::NORM_INF) == 0.0) {
    const int row = rng.uniform(0, image.rows);
    const int column = rng.uniform(0, image.cols * image.channels());
    std::uint8_t& value = image.ptr<std::uint8_t>(row)[column];
    value = value < 255 ? value + 1 : value - 1;
  }
  return image;
}

std::vector<cv::Mat> renderDrive(const CameraDrive& drive, const std::vector<cv::Mat>& route) {
  std::vector<cv::Mat> images;
  images.reserve(static_cast<std::size_t>(drive.size()));
  if (static_cast<int>(route.size()) != drive.routeLength()) {
    throw std::invalid_argument("camera drive: the drive is planned for " + std::to_string(drive.routeLength()) +
                                " route frames, but the route has " + std::to_string(route.size()) + " images");
  }
  for (int i = 0; i < drive.size(); ++i) {
    images.push_back(
        drive.render(i, route[static_cast<std::size_t>(drive.frames()[static_cast<std::size_t>(i)].route_frame)]));
  }
  return images;
}

GroundTruth driveGroundTruth(const std::vector<int>& reference_route_frames, const std::vector<int>& query_route_frames,
                             int route_tolerance) {
  if (route_tolerance < 0) {
    throw std::invalid_argument("route tolerance must be >= 0, got " + std::to_string(route_tolerance));
  }
  std::map<int, std::vector<int>> frames_of_route_frame;
  for (std::size_t j = 0; j < reference_route_frames.size(); ++j) {
    frames_of_route_frame[reference_route_frames[j]].push_back(static_cast<int>(j));
  }
  GroundTruth truth;
  for (std::size_t i = 0; i < query_route_frames.size(); ++i) {
    std::vector<int>& frames = truth[static_cast<int>(i)];
    // In 64 bits: a tolerance near INT_MAX must not wrap round.
    const long long route_frame = query_route_frames[i];
    const auto lowest =
        static_cast<int>(std::max<long long>(std::numeric_limits<int>::min(), route_frame - route_tolerance));
    for (auto it = frames_of_route_frame.lower_bound(lowest);
         it != frames_of_route_frame.end() && it->first <= route_frame + route_tolerance; ++it) {
      frames.insert(frames.end(), it->second.begin(), it->second.end());
    }
    std::sort(frames.begin(), frames.end());
  }
  return truth;
}

}  // namespace mrs_vpr

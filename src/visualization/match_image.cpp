#include "mrs_vpr/visualization/match_image.hpp"

#include <algorithm>
#include <cstdio>
#include <string>

#include <opencv2/imgproc.hpp>

namespace mrs_vpr {
namespace visualization {
namespace {

constexpr int kThumbnailHeight = 128;
constexpr int kBandHeight = 256;
constexpr int kCaptionHeight = 16;
constexpr int kLevelHeight = 16;
constexpr int kLevelLabelWidth = 96;
constexpr int kVerdictHeight = 40;
constexpr int kMapStatusHeight = 18;
constexpr int kFont = cv::FONT_HERSHEY_PLAIN;
constexpr int kTrajectoryDashes = 8;
const cv::Scalar kText(230, 230, 230);
const cv::Scalar kDimText(170, 170, 170);
const cv::Scalar kBackground(40, 40, 40);
const cv::Scalar kAcceptedColour(80, 220, 80);
const cv::Scalar kRejectedColour(60, 60, 255);

/// `value` with two decimals, as the captions show confidences and velocities.
std::string twoDecimals(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f", value);
  return text;
}

void label(cv::Mat& image, const std::string& text, cv::Point origin, const cv::Scalar& colour, double scale = 1.0) {
  cv::putText(image, text, origin, kFont, scale, colour, 1, cv::LINE_AA);
}

/// A descriptor (128 + 32 z per pixel) is already a viewable grey image; cells are scaled up as blocks.
void drawThumbnail(cv::Mat& image, const cv::Rect& area, const cv::Mat& thumbnail, const std::string& caption) {
  cv::Mat target = image(area);
  if (thumbnail.empty()) {
    target.setTo(kBackground);
  } else {
    cv::Mat colour;
    cv::cvtColor(thumbnail, colour, cv::COLOR_GRAY2BGR);
    cv::resize(colour, target, area.size(), 0, 0, cv::INTER_NEAREST);  // Into the image itself.
  }
  cv::rectangle(image, cv::Rect(area.x, area.y, area.width, 16), kBackground, cv::FILLED);
  label(image, caption, {area.x + 4, area.y + 12}, kText);
}

/**
 * Each reference frame's differences as z-scores over the band's test frames, from -3 (black) to +3
 * (white): some reference frames differ from every test frame (a dark tunnel, a bright sky), and
 * their columns would otherwise hide the few cells where a test frame matches.
 */
cv::Mat standardisedColumns(const cv::Mat& band) {
  cv::Mat mean;
  cv::Mat mean_of_squares;
  cv::reduce(band, mean, 0, cv::REDUCE_AVG);
  cv::reduce(band.mul(band), mean_of_squares, 0, cv::REDUCE_AVG);
  cv::Mat spread;
  cv::sqrt(cv::max(mean_of_squares - mean.mul(mean), 1e-12), spread);
  cv::Mat z = (band - cv::repeat(mean, band.rows, 1)) / cv::repeat(spread, band.rows, 1);
  cv::Mat grey;
  z.convertTo(grey, CV_8U, 255.0 / 6.0, 127.5);  // saturates beyond +-3
  return grey;
}

void drawBand(cv::Mat& image, const cv::Rect& area, const MatchExplanation& explanation) {
  cv::Mat target = image(area);
  if (explanation.band.empty()) {
    target.setTo(kBackground);
    label(image, "no match", {area.x + 8, area.y + area.height / 2}, kText);
    return;
  }
  const cv::Mat grey = standardisedColumns(explanation.band);
  cv::Mat colour;
  cv::cvtColor(grey, colour, cv::COLOR_GRAY2BGR);
  cv::resize(colour, target, area.size(), 0, 0, cv::INTER_NEAREST);  // Into the image itself.
  // Dashed, so that the dark cells it follows stay visible between the dashes.
  std::vector<cv::Point> dash;
  for (int t = 0; t < static_cast<int>(explanation.trajectory.size()); ++t) {
    if (trajectoryDrawnAt(explanation, t)) {
      dash.push_back(trajectoryPixel(explanation, t));
    } else if (!dash.empty()) {
      cv::polylines(image, dash, false, kTrajectoryColour, 1, cv::LINE_8);
      dash.clear();
    }
  }
  if (!dash.empty()) cv::polylines(image, dash, false, kTrajectoryColour, 1, cv::LINE_8);
}

/// The whole map across: where the level's particles ended, the band's stretch and the answer.
void drawLevel(cv::Mat& image, const cv::Rect& area, const MrsLevelTrace& level, const MatchExplanation& explanation,
               int answer) {
  label(image, "x" + std::to_string(level.stride) + ": " + std::to_string(level.candidates.size()) + " p.",
        {area.x + 4, area.y + 12}, kText);
  const cv::Rect bar(area.x + kLevelLabelWidth, area.y + 2, area.width - kLevelLabelWidth, area.height - 4);
  cv::rectangle(image, bar, cv::Scalar(70, 70, 70), cv::FILLED);
  const int frames = std::max(1, explanation.reference_frames);
  const auto x = [&](double frame) {
    return bar.x + std::clamp(static_cast<int>(frame * bar.width / frames), 0, bar.width - 1);
  };
  if (!explanation.band.empty()) {
    const int band_end = explanation.band_first + explanation.band.cols * explanation.band_step;
    cv::rectangle(image, cv::Point(x(explanation.band_first), bar.y), cv::Point(x(band_end), bar.y + bar.height - 1),
                  cv::Scalar(110, 110, 110), cv::FILLED);
  }
  // Lowest cost first: draw backwards so that the best particle stays on top.
  for (auto it = level.candidates.rbegin(); it != level.candidates.rend(); ++it) {
    const cv::Scalar& colour = it + 1 == level.candidates.rend() ? kBestParticleColour : kParticleColour;
    cv::line(image, cv::Point(x(*it), bar.y + 2), cv::Point(x(*it), bar.y + bar.height - 3), colour);
  }
  if (answer >= 0) {
    cv::line(image, cv::Point(x(answer), bar.y), cv::Point(x(answer), bar.y + bar.height - 1), kTrajectoryColour);
  }
}

void drawVerdict(cv::Mat& image, const cv::Rect& area, const MatchExplanation& explanation, const PlaceAnswer& answer) {
  const Match& match = answer.match;
  const std::string verdict = match.reference_index < 0 ? "no match" : match.accepted ? "ACCEPTED" : "not accepted";
  const std::string head = answer.method + "  reference " + std::to_string(match.reference_index) +
                           "  confidence " + twoDecimals(match.confidence) + "  " + verdict;
  label(image, head, {area.x + 4, area.y + 15}, match.accepted ? kAcceptedColour : kRejectedColour, 1.1);
  label(image,
        // The frames searched, which a question about the map's own newest frames ends well before its size.
        std::to_string(explanation.query_frames) + " test frames vs map frames 0.." +
            std::to_string(explanation.reference_frames - 1) + ", velocity " + twoDecimals(explanation.velocity),
        {area.x + 4, area.y + 33}, kDimText);
}

}  // namespace

MatchImageLayout matchImageLayout(int levels) {
  MatchImageLayout layout;
  const int width = MatchImageLayout::kWidth;
  layout.query_thumbnail = cv::Rect(0, 0, width / 2, kThumbnailHeight);
  layout.reference_thumbnail = cv::Rect(width / 2, 0, width - width / 2, kThumbnailHeight);
  layout.band = cv::Rect(0, kThumbnailHeight, width, kBandHeight);
  layout.band_caption = cv::Rect(0, layout.band.br().y, width, kCaptionHeight);
  int y = layout.band_caption.br().y;
  for (int level = 0; level < levels; ++level, y += kLevelHeight) {
    layout.levels.emplace_back(0, y, width, kLevelHeight);
  }
  layout.verdict = cv::Rect(0, y, width, kVerdictHeight);
  layout.map_status = cv::Rect(0, layout.verdict.br().y, width, kMapStatusHeight);
  layout.size = cv::Size(width, layout.map_status.br().y);
  return layout;
}

bool trajectoryDrawnAt(const MatchExplanation& explanation, int test_frame) {
  const int frames = std::max(1, static_cast<int>(explanation.trajectory.size()));
  return (test_frame * 2 * kTrajectoryDashes / frames) % 2 == 0;
}

cv::Point trajectoryPixel(const MatchExplanation& explanation, int test_frame) {
  const cv::Rect band = matchImageLayout(0).band;
  const double frames_across = static_cast<double>(explanation.band.cols) * explanation.band_step;
  const double frames_down = static_cast<double>(explanation.band.rows) * explanation.band_step;
  const double reference = explanation.trajectory.at(static_cast<std::size_t>(test_frame)) - explanation.band_first;
  const double row = test_frame - explanation.band_first_row;
  const int x = static_cast<int>((reference + 0.5) / frames_across * band.width);
  const int y = static_cast<int>((row + 0.5) / frames_down * band.height);
  return {band.x + std::clamp(x, 0, band.width - 1), band.y + std::clamp(y, 0, band.height - 1)};
}

cv::Mat renderMatchImage(const MatchExplanation& explanation, const PlaceAnswer& answer,
                         const std::string& map_status) {
  cv::Mat image;
  renderMatchImage(explanation, answer, image, map_status);
  return image;
}

void renderMatchImage(const MatchExplanation& explanation, const PlaceAnswer& answer, cv::Mat& image,
                      const std::string& map_status) {
  const MatchImageLayout layout = matchImageLayout(static_cast<int>(explanation.levels.size()));
  image.create(layout.size, CV_8UC3);  // Keeps the buffer when the size is the same.
  image.setTo(kBackground);
  const int reference = answer.match.reference_index;
  const bool newest = explanation.anchor == explanation.query_frames - 1;
  drawThumbnail(image, layout.query_thumbnail, explanation.query_thumbnail,
                "test frame " + std::to_string(explanation.anchor) + (newest ? " (newest)" : " (centre)"));
  drawThumbnail(image, layout.reference_thumbnail, explanation.reference_thumbnail,
                reference >= 0 ? "reference frame " + std::to_string(reference) : "no match");
  drawBand(image, layout.band, explanation);
  if (!explanation.band.empty()) {
    const int band_last = explanation.band_first + (explanation.band.cols - 1) * explanation.band_step;
    label(image,
          "across: reference " + std::to_string(explanation.band_first) + ".." + std::to_string(band_last) +
              (explanation.band_step > 1 ? " (every " + std::to_string(explanation.band_step) + ")" : "") +
              "; down: test frames",
          {layout.band_caption.x + 4, layout.band_caption.y + 12}, kDimText);
  }
  for (std::size_t level = 0; level < layout.levels.size(); ++level) {
    drawLevel(image, layout.levels[level], explanation.levels[level], explanation, reference);
  }
  drawVerdict(image, layout.verdict, explanation, answer);
  if (!map_status.empty()) label(image, map_status, {layout.map_status.x + 4, layout.map_status.y + 12}, kDimText);
}

}  // namespace visualization
}  // namespace mrs_vpr

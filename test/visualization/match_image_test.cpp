#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "mrs_vpr/visualization/match_image.hpp"

namespace mrs_vpr {
namespace visualization {
namespace {

/// 40 test frames against reference frames 100..179, a uniform band except a dark diagonal, the
/// trajectory along it ending at frame 159, and two MRS levels.
MatchExplanation handMadeExplanation() {
  MatchExplanation explanation;
  explanation.query_thumbnail = cv::Mat(32, 64, CV_8UC1, cv::Scalar(200));
  explanation.reference_thumbnail = cv::Mat(32, 64, CV_8UC1, cv::Scalar(60));
  explanation.band = cv::Mat(40, 80, CV_32FC1, cv::Scalar(1.0));
  explanation.band_first = 100;
  explanation.band_step = 1;
  for (int t = 0; t < 40; ++t) {
    explanation.trajectory.push_back(120 + t);
    explanation.band.at<float>(t, 20 + t) = 0.2F;
  }
  explanation.velocity = 1.0;
  explanation.reference_frames = 600;
  explanation.query_frames = 40;
  explanation.anchor = 39;
  MrsLevelTrace coarse;
  coarse.stride = 2;
  coarse.candidates = {158, 300, 520};
  MrsLevelTrace fine;
  fine.stride = 1;
  fine.candidates = {159};
  explanation.levels = {coarse, fine};
  return explanation;
}

PlaceAnswer answerAt(int reference_index, bool accepted) {
  PlaceAnswer answer;
  answer.method = "mrs";
  answer.query_length = 40;
  answer.match.reference_index = reference_index;
  answer.match.confidence = accepted ? 7.5F : 1.2F;
  answer.match.accepted = accepted;
  return answer;
}

cv::Scalar pixel(const cv::Mat& image, cv::Point point) {
  const cv::Vec3b bgr = image.at<cv::Vec3b>(point);
  return {static_cast<double>(bgr[0]), static_cast<double>(bgr[1]), static_cast<double>(bgr[2])};
}

TEST(MatchImage, HasTheLayoutsSizeAndShowsEveryPart) {
  const MatchExplanation explanation = handMadeExplanation();
  const cv::Mat image = renderMatchImage(explanation, answerAt(159, true));
  const MatchImageLayout layout = matchImageLayout(2);
  ASSERT_EQ(image.type(), CV_8UC3);
  ASSERT_EQ(image.size(), layout.size);
  EXPECT_EQ(layout.size.width, MatchImageLayout::kWidth);
  EXPECT_EQ(layout.size.height, matchImageLayout(0).size.height + 2 * layout.levels[0].height);

  // The thumbnails are the descriptors scaled up (below their captions).
  EXPECT_EQ(pixel(image, layout.query_thumbnail.br() - cv::Point(5, 5)), cv::Scalar(200, 200, 200));
  EXPECT_EQ(pixel(image, layout.reference_thumbnail.br() - cv::Point(5, 5)), cv::Scalar(60, 60, 60));
  // The band is grey, each column standardised: the diagonal's cells (beside the trajectory drawn
  // over them) are black, the uniform cells mid-grey.
  const cv::Scalar far_corner = pixel(image, {layout.band.x + 5, layout.band.br().y - 5});
  EXPECT_EQ(far_corner[0], far_corner[2]);
  EXPECT_GT(far_corner[0], 127.0);
  const cv::Point beside_trajectory = trajectoryPixel(explanation, 0) + cv::Point(2, 0);
  EXPECT_EQ(pixel(image, beside_trajectory), cv::Scalar(0, 0, 0));
}

TEST(MatchImage, DrawsTheTrajectoryWhereItsFramesAre) {
  const MatchExplanation explanation = handMadeExplanation();
  const cv::Mat image = renderMatchImage(explanation, answerAt(159, true));
  const cv::Rect band = matchImageLayout(2).band;
  int drawn = 0;
  for (int t = 0; t < 40; ++t) {
    const cv::Point point = trajectoryPixel(explanation, t);
    ASSERT_TRUE(band.contains(point));
    if (trajectoryDrawnAt(explanation, t)) {
      EXPECT_EQ(pixel(image, point), kTrajectoryColour) << "test frame " << t;
      ++drawn;
    } else {
      // Between the dashes the matching cells show: dark.
      EXPECT_EQ(pixel(image, point), cv::Scalar(0, 0, 0)) << "test frame " << t;
    }
  }
  EXPECT_GT(drawn, 10);  // 8 dashes: about half of the frames
  EXPECT_LT(drawn, 30);
  EXPECT_TRUE(trajectoryDrawnAt(explanation, 0));
  // Test frame t sits in row t of 40, reference frame 120 + t in column 20 + t of 80.
  EXPECT_EQ(trajectoryPixel(explanation, 0), cv::Point(band.x + static_cast<int>(20.5 / 80 * band.width),
                                                       band.y + static_cast<int>(0.5 / 40 * band.height)));
  EXPECT_EQ(trajectoryPixel(explanation, 39), cv::Point(band.x + static_cast<int>(59.5 / 80 * band.width),
                                                        band.y + static_cast<int>(39.5 / 40 * band.height)));
  // Nothing red off the trajectory: the band's far corner is still grey.
  const cv::Scalar corner = pixel(image, {band.br().x - 3, band.y + 3});
  EXPECT_EQ(corner[0], corner[2]);
}

TEST(MatchImage, MarksEachLevelsParticlesOverTheWholeMap) {
  const MatchExplanation explanation = handMadeExplanation();
  const cv::Mat image = renderMatchImage(explanation, answerAt(159, true));
  const MatchImageLayout layout = matchImageLayout(2);
  // Count particle-coloured columns along the middle row of each strip.
  const auto columns_of = [&](const cv::Rect& strip, const cv::Scalar& colour) {
    int count = 0;
    for (int x = strip.x; x < strip.br().x; ++x) {
      if (pixel(image, {x, strip.y + strip.height / 2}) == colour) ++count;
    }
    return count;
  };
  EXPECT_EQ(columns_of(layout.levels[0], kParticleColour), 2);      // 300 and 520
  EXPECT_EQ(columns_of(layout.levels[0], kBestParticleColour), 1);  // 158, the lowest cost
  EXPECT_EQ(columns_of(layout.levels[1], kParticleColour), 0);
}

TEST(MatchImage, WritesTheMapStatusOnTheLastLineOnlyWhenGiven) {
  const MatchExplanation explanation = handMadeExplanation();
  const cv::Rect line = matchImageLayout(2).map_status;
  const auto written = [&](const cv::Mat& image) {
    return cv::countNonZero(image(line).reshape(1) != image.at<cv::Vec3b>(line.y, line.x)[0]);
  };
  EXPECT_EQ(written(renderMatchImage(explanation, answerAt(159, true))), 0);
  EXPECT_GT(written(renderMatchImage(explanation, answerAt(159, true), "map 460 keyframes; 377 frames too similar")),
            0);
}

TEST(MatchImage, SeqslamAndNoMatchStillGiveAnImage) {
  MatchExplanation explanation = handMadeExplanation();
  explanation.levels.clear();
  EXPECT_EQ(renderMatchImage(explanation, answerAt(159, false)).size(), matchImageLayout(0).size);

  MatchExplanation none;
  none.query_thumbnail = cv::Mat(32, 64, CV_8UC1, cv::Scalar(128));
  none.query_frames = 10;
  const cv::Mat image = renderMatchImage(none, answerAt(-1, false));
  EXPECT_EQ(image.size(), matchImageLayout(0).size);
  EXPECT_GT(cv::countNonZero(image.reshape(1)), 0);
}

}  // namespace
}  // namespace visualization
}  // namespace mrs_vpr

#include <gtest/gtest.h>

#include <sensor_msgs/image_encodings.h>
#include <opencv2/imgproc.hpp>

#include "mrs_vpr/node/image_conversion.hpp"

namespace mrs_vpr {
namespace node {
namespace {

sensor_msgs::Image makeImage(const cv::Mat& image, const std::string& encoding) {
  return *cv_bridge::CvImage(std_msgs::Header(), encoding, image).toImageMsg();
}

/// A deterministic textured BGR image.
cv::Mat texturedBgr(int width = 160, int height = 120) {
  cv::Mat image(height, width, CV_8UC3);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      image.at<cv::Vec3b>(y, x) = cv::Vec3b(static_cast<uchar>((x * 7 + y * 3) % 256),
                                            static_cast<uchar>((x * x + y) % 256),
                                            static_cast<uchar>((y * 11) % 256));
    }
  }
  return image;
}

std::string errorOf(const sensor_msgs::Image& message) {
  try {
    fromImageMessage(message);
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "";
}

TEST(ImageConversion, SharesPixelsAndKeepsEncoding) {
  const cv::Mat bgr = texturedBgr();
  const sensor_msgs::Image message = makeImage(bgr, "bgr8");
  const ImageFrame frame = fromImageMessage(message);
  EXPECT_EQ(frame.image().type(), CV_8UC3);
  EXPECT_EQ(frame.image().data, message.data.data());  // no copy
  EXPECT_EQ(frame.order, ChannelOrder::kBgr);
}

TEST(ImageConversion, RgbOrderGivesTheSameDescriptorAsBgr) {
  const DescriptorExtractor extractor{DescriptorParams{}};
  const cv::Mat bgr = texturedBgr();
  cv::Mat rgb;
  cv::Mat bgra;
  cv::Mat rgba;
  cv::Mat mono;
  cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
  cv::cvtColor(bgr, bgra, cv::COLOR_BGR2BGRA);
  cv::cvtColor(bgr, rgba, cv::COLOR_BGR2RGBA);
  const cv::Mat reference = describeImage(extractor, makeImage(bgr, "bgr8"));
  ASSERT_EQ(reference.cols, extractor.size());
  EXPECT_EQ(cv::norm(reference, describeImage(extractor, makeImage(rgb, "rgb8")), cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(reference, describeImage(extractor, makeImage(bgra, "bgra8")), cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(reference, describeImage(extractor, makeImage(rgba, "rgba8")), cv::NORM_INF), 0.0);
  cv::cvtColor(bgr, mono, cv::COLOR_BGR2GRAY);
  EXPECT_EQ(describeImage(extractor, makeImage(mono, "mono8")).cols, extractor.size());
  cv::Mat mono16;
  mono.convertTo(mono16, CV_16UC1, 256.0);
  EXPECT_EQ(describeImage(extractor, makeImage(mono16, "mono16")).cols, extractor.size());
}

TEST(ImageConversion, RejectsUnsupportedEncodingsByName) {
  EXPECT_TRUE(isSupportedEncoding("rgba8"));
  EXPECT_FALSE(isSupportedEncoding("bayer_rggb8"));
  const std::string bayer = errorOf(makeImage(cv::Mat(8, 8, CV_8UC1, cv::Scalar(1)), "bayer_rggb8"));
  EXPECT_NE(bayer.find("unsupported encoding 'bayer_rggb8'"), std::string::npos) << bayer;
  EXPECT_NE(bayer.find("mono8"), std::string::npos) << bayer;
  const std::string float3 = errorOf(makeImage(cv::Mat(8, 8, CV_32FC3, cv::Scalar(1, 1, 1)), "32FC3"));
  EXPECT_NE(float3.find("'32FC3'"), std::string::npos) << float3;
}

TEST(ImageConversion, RejectsEmptyAndTruncatedImages) {
  sensor_msgs::Image empty;
  empty.encoding = "bgr8";
  EXPECT_NE(errorOf(empty).find("empty image (0 x 0"), std::string::npos) << errorOf(empty);

  sensor_msgs::Image truncated = makeImage(texturedBgr(), "bgr8");
  truncated.data.resize(truncated.data.size() / 2);
  EXPECT_NE(errorOf(truncated).find("bytes"), std::string::npos) << errorOf(truncated);

  sensor_msgs::Image bad_step = makeImage(texturedBgr(), "bgr8");
  bad_step.step = 10;
  EXPECT_NE(errorOf(bad_step).find("step 10"), std::string::npos) << errorOf(bad_step);
}

}  // namespace
}  // namespace node
}  // namespace mrs_vpr

#include <gtest/gtest.h>

#include <string>

#include <opencv2/imgproc.hpp>

#include "mrs_vpr/node/frame_describer.hpp"

namespace mrs_vpr {
namespace node {
namespace {

cv::Mat noise(int width, int height, int type, unsigned seed) {
  cv::Mat image(height, width, type);
  cv::RNG rng(seed);
  rng.fill(image, cv::RNG::UNIFORM, 0, CV_MAT_DEPTH(type) == CV_16U ? 65536 : 256);
  cv::GaussianBlur(image, image, cv::Size(5, 5), 2.0);  // some structure, as a camera's frames have
  return image;
}

std::string errorOf(FrameDescriber& describer, const cv::Mat& image) {
  try {
    describer.describe(image, ChannelOrder::kBgr);
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "";
}

TEST(FrameDescriber, GivesTheCoresDescriptorBitForBit) {
  const DescriptorExtractor extractor{DescriptorParams{}};
  FrameDescriber describer(extractor);
  // Integer and fractional scale factors, every type, and sizes changing between frames (the buffers
  // are reallocated) and repeating (they are reused).
  const cv::Size sizes[] = {{640, 480}, {640, 480}, {1280, 720}, {333, 97}, {64, 32}, {640, 480}};
  const int types[] = {CV_8UC3, CV_8UC4, CV_8UC1, CV_16UC1};
  unsigned seed = 1;
  for (const cv::Size& size : sizes) {
    for (const int type : types) {
      for (const ChannelOrder order : {ChannelOrder::kBgr, ChannelOrder::kRgb}) {
        SCOPED_TRACE(std::to_string(size.width) + " x " + std::to_string(size.height) + " " + cv::typeToString(type));
        const cv::Mat image = noise(size.width, size.height, type, seed++);
        const cv::Mat expected = extractor.compute(image, order);
        const cv::Mat described = describer.describe(image, order);
        ASSERT_EQ(described.size(), expected.size());
        ASSERT_EQ(described.type(), CV_8UC1);
        EXPECT_EQ(cv::norm(described, expected, cv::NORM_INF), 0.0);
      }
    }
  }
}

TEST(FrameDescriber, EachDescriptorIsItsOwn) {
  const DescriptorExtractor extractor{DescriptorParams{}};
  FrameDescriber describer(extractor);
  const cv::Mat first = describer.describe(noise(640, 480, CV_8UC3, 1), ChannelOrder::kBgr);
  const cv::Mat kept = first.clone();
  describer.describe(noise(640, 480, CV_8UC3, 2), ChannelOrder::kBgr);
  EXPECT_EQ(cv::norm(first, kept, cv::NORM_INF), 0.0);  // not overwritten by the next frame
}

TEST(FrameDescriber, RefusesWhatTheCoreRefusesWithItsMessages) {
  const DescriptorExtractor extractor{DescriptorParams{}};
  FrameDescriber describer(extractor);
  EXPECT_NE(errorOf(describer, cv::Mat()).find("empty"), std::string::npos);
  EXPECT_NE(errorOf(describer, cv::Mat(8, 8, CV_32FC3)).find("unsupported image type"), std::string::npos);
  const cv::Mat too_large(6000, 4200, CV_8UC1, cv::Scalar(0));
  EXPECT_NE(errorOf(describer, too_large).find("larger than the 25000000 pixels allowed"), std::string::npos);
}

}  // namespace
}  // namespace node
}  // namespace mrs_vpr

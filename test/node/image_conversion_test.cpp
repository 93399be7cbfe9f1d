#include <gtest/gtest.h>

#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <boost/make_shared.hpp>
#include <boost/weak_ptr.hpp>
#include <cv_bridge/cv_bridge.h>
#include <sensor_msgs/image_encodings.h>
#include <opencv2/imgproc.hpp>

#include "mrs_vpr/node/image_conversion.hpp"
#include "node/camera_mosaics.hpp"

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

TEST(ImageConversion, PaddedRowsAreSharedWithTheirStep) {
  sensor_msgs::Image message = makeImage(texturedBgr(5, 3), "bgr8");
  // Rows of 15 bytes padded to 16, as some drivers send them.
  std::vector<std::uint8_t> padded;
  for (int row = 0; row < 3; ++row) {
    padded.insert(padded.end(), message.data.begin() + row * 15, message.data.begin() + (row + 1) * 15);
    padded.push_back(0xEE);
  }
  message.data = padded;
  message.step = 16;
  const ImageFrame frame = fromImageMessage(message);
  EXPECT_EQ(frame.image().step[0], 16u);
  EXPECT_EQ(cv::norm(frame.image(), texturedBgr(5, 3), cv::NORM_INF), 0.0);
}

TEST(ImageConversion, Mono16OfTheOtherByteOrderIsSwapped) {
  sensor_msgs::Image message;
  message.encoding = "mono16";
  message.width = 2;
  message.height = 1;
  message.step = 4;
  message.data = {0x01, 0x02, 0xAB, 0xCD};
  message.is_bigendian = 1;
  const ImageFrame big = fromImageMessage(message);
  EXPECT_EQ(big.image().at<std::uint16_t>(0, 0), 0x0102);
  EXPECT_EQ(big.image().at<std::uint16_t>(0, 1), 0xABCD);
  EXPECT_NE(big.image().data, message.data.data());  // a swapped copy, the message stays as sent

  message.is_bigendian = 0;  // this machine's order (x86, ARM): shared as it is
  const ImageFrame little = fromImageMessage(message);
  EXPECT_EQ(little.image().at<std::uint16_t>(0, 0), 0x0201);
  EXPECT_EQ(little.image().data, message.data.data());
}

TEST(ImageConversion, TheFrameKeepsTheTrackedMessageAlive) {
  auto message = boost::make_shared<sensor_msgs::Image>(makeImage(texturedBgr(), "bgr8"));
  const boost::weak_ptr<sensor_msgs::Image> watch = message;
  ImageFrame frame = fromImageMessage(*message, message);
  message.reset();
  EXPECT_FALSE(watch.expired());
  EXPECT_EQ(cv::norm(frame.image(), texturedBgr(), cv::NORM_INF), 0.0);
  frame = ImageFrame();
  EXPECT_TRUE(watch.expired());
}

/// `bgr` in the four channel orders a camera sends, with their encodings ("bgr" + `depth`: bgr8, ...).
std::vector<std::pair<cv::Mat, std::string>> channelOrders(const cv::Mat& bgr, const std::string& depth) {
  std::vector<std::pair<cv::Mat, std::string>> orders{{bgr, "bgr" + depth}};
  for (const auto& [code, name] : std::vector<std::pair<int, std::string>>{
           {cv::COLOR_BGR2RGB, "rgb"}, {cv::COLOR_BGR2BGRA, "bgra"}, {cv::COLOR_BGR2RGBA, "rgba"}}) {
    cv::Mat converted;
    cv::cvtColor(bgr, converted, code);
    orders.emplace_back(converted, name + depth);
  }
  return orders;
}

TEST(ImageConversion, RgbOrderGivesTheSameDescriptorAsBgr) {
  const DescriptorExtractor extractor{DescriptorParams{}};
  const cv::Mat bgr = texturedBgr();
  const cv::Mat reference = describeImage(extractor, makeImage(bgr, "bgr8"));
  ASSERT_EQ(reference.cols, extractor.size());
  for (const auto& [image, encoding] : channelOrders(bgr, "8")) {
    EXPECT_EQ(cv::norm(reference, describeImage(extractor, makeImage(image, encoding)), cv::NORM_INF), 0.0) << encoding;
  }
  cv::Mat mono;
  // Grey images are described as the extractor describes them itself: read with the right type and step.
  cv::cvtColor(bgr, mono, cv::COLOR_BGR2GRAY);
  EXPECT_EQ(cv::norm(describeImage(extractor, makeImage(mono, "mono8")), extractor.compute(mono), cv::NORM_INF), 0.0);
  cv::Mat mono16;
  mono.convertTo(mono16, CV_16UC1, 256.0);
  EXPECT_EQ(cv::norm(describeImage(extractor, makeImage(mono16, "mono16")), extractor.compute(mono16), cv::NORM_INF),
            0.0);
}

TEST(ImageConversion, SixteenBitColourOfEitherOrderAndByteOrderIsDescribedAsItsDeepGrey) {
  // A machine-vision camera's 16-bit colour: described from its own 16-bit grey, as the core does.
  const DescriptorExtractor extractor{DescriptorParams{}};
  cv::Mat bgr16;
  testing::redAcrossBlueDown().convertTo(bgr16, CV_16UC3, 257.0);
  cv::Mat grey16;
  cv::cvtColor(bgr16, grey16, cv::COLOR_BGR2GRAY);
  const cv::Mat expected = extractor.compute(grey16);
  for (const auto& [image, encoding] : channelOrders(bgr16, "16")) {
    sensor_msgs::Image message = makeImage(image, encoding);
    EXPECT_EQ(cv::norm(describeImage(extractor, message), expected, cv::NORM_INF), 0.0) << encoding;
    // The same values sent big-endian.
    for (std::size_t i = 0; i + 1 < message.data.size(); i += 2) std::swap(message.data[i], message.data[i + 1]);
    message.is_bigendian = 1;
    EXPECT_EQ(cv::norm(describeImage(extractor, message), expected, cv::NORM_INF), 0.0) << encoding << ", big-endian";
  }
}

TEST(ImageConversion, BayerMosaicsBecomeTheGreyOfTheirColours) {
  const cv::Mat bgr = testing::redAcrossBlueDown();
  const cv::Mat grey = testing::greyOf(bgr);
  for (const std::string pattern : {"rggb", "bggr", "gbrg", "grbg"}) {
    const std::string encoding = "bayer_" + pattern + "8";
    const cv::Mat mosaic = testing::mosaicOf(bgr, pattern);
    const ImageFrame frame = fromImageMessage(makeImage(mosaic, encoding));
    ASSERT_EQ(frame.image().type(), CV_8UC1) << encoding;
    EXPECT_LT(testing::interiorDifference(frame.image(), grey), 1.5) << encoding;
    // Read as the pattern with red and blue swapped, the grey is far off: the pattern named is the one
    // demosaiced.
    std::string swapped = pattern;
    std::swap(swapped[swapped.find('r')], swapped[swapped.find('b')]);
    const ImageFrame wrong = fromImageMessage(makeImage(mosaic, "bayer_" + swapped + "8"));
    EXPECT_GT(testing::interiorDifference(wrong.image(), grey), 8.0) << encoding << " read as " << swapped;
  }
}

TEST(ImageConversion, A16BitBayerMosaicOfEitherByteOrderBecomesDeepGrey) {
  const cv::Mat bgr = testing::redAcrossBlueDown();
  cv::Mat grey16;
  testing::greyOf(bgr).convertTo(grey16, CV_16UC1, 256.0);
  for (const std::string pattern : {"rggb", "bggr", "gbrg", "grbg"}) {
    const std::string encoding = "bayer_" + pattern + "16";
    cv::Mat mosaic16;
    testing::mosaicOf(bgr, pattern).convertTo(mosaic16, CV_16UC1, 256.0);
    sensor_msgs::Image message = makeImage(mosaic16, encoding);
    const ImageFrame little = fromImageMessage(message);
    ASSERT_EQ(little.image().type(), CV_16UC1) << encoding;
    EXPECT_LT(testing::interiorDifference(little.image(), grey16), 1.5 * 256) << encoding;
    // The same values sent big-endian.
    for (std::size_t i = 0; i + 1 < message.data.size(); i += 2) std::swap(message.data[i], message.data[i + 1]);
    message.is_bigendian = 1;
    EXPECT_EQ(cv::norm(fromImageMessage(message).image(), little.image(), cv::NORM_INF), 0.0) << encoding;
  }
}

TEST(ImageConversion, Yuv422BecomesItsLuma) {
  // Two pixels a group of four bytes: U Y0 V Y1 (yuv422, UYVY) or Y0 U Y1 V (yuv422_yuy2, YUYV).
  sensor_msgs::Image message;
  message.width = 4;
  message.height = 1;
  message.step = 8;
  message.encoding = "yuv422";
  message.data = {100, 10, 200, 20, 100, 30, 200, 40};
  const cv::Mat uyvy = fromImageMessage(message).image();
  ASSERT_EQ(uyvy.type(), CV_8UC1);
  EXPECT_EQ(cv::norm(uyvy, cv::Mat_<uchar>({1, 4}, {10, 20, 30, 40}), cv::NORM_INF), 0.0) << uyvy;
  message.encoding = "yuv422_yuy2";
  message.data = {10, 100, 20, 200, 30, 100, 40, 200};
  const cv::Mat yuyv = fromImageMessage(message).image();
  EXPECT_EQ(cv::norm(yuyv, uyvy, cv::NORM_INF), 0.0) << yuyv;
  message.step = 7;  // fewer bytes than two a pixel
  EXPECT_NE(errorOf(message).find("step 7 is less than width 4 x 2 bytes of yuv422_yuy2"), std::string::npos)
      << errorOf(message);
}

TEST(ImageConversion, Yuv422OfAnOddWidthIsRefused) {
  // Its last pixel would have half a chroma pair: the camera or the bag is broken, so say so.
  sensor_msgs::Image message;
  message.width = 3;
  message.height = 1;
  message.step = 6;
  message.data = {100, 10, 200, 20, 100, 30};
  for (const char* encoding : {"yuv422", "yuv422_yuy2"}) {
    message.encoding = encoding;
    EXPECT_NE(errorOf(message).find(std::string(encoding) + " sends pixels in groups of 2, so its width must be a "
                                                            "multiple of 2, got 3"),
              std::string::npos)
        << errorOf(message);
  }
}

TEST(ImageConversion, OpenCvTypesAreReadAsOpenCvsImages) {
  // What cv_bridge's cv2_to_imgmsg publishes for an image given no encoding: OpenCV's type.
  const DescriptorExtractor extractor{DescriptorParams{}};
  const cv::Mat bgr = texturedBgr();
  cv::Mat grey;
  cv::Mat bgra;
  cv::cvtColor(bgr, grey, cv::COLOR_BGR2GRAY);
  cv::cvtColor(bgr, bgra, cv::COLOR_BGR2BGRA);
  for (const auto& [image, named, generic] :
       std::vector<std::tuple<cv::Mat, std::string, std::string>>{
           {grey, "mono8", "8UC1"}, {bgr, "bgr8", "8UC3"}, {bgra, "bgra8", "8UC4"}}) {
    const ImageFrame frame = fromImageMessage(makeImage(image, generic));
    EXPECT_EQ(frame.image().type(), image.type()) << generic;
    EXPECT_EQ(frame.order, ChannelOrder::kBgr) << generic;
    EXPECT_EQ(cv::norm(describeImage(extractor, makeImage(image, generic)),
                       describeImage(extractor, makeImage(image, named)), cv::NORM_INF),
              0.0)
        << generic;
  }
  // A depth camera's 16UC1 is not a view of a place: refused, with what a grey camera would send instead.
  const std::string depth = errorOf(makeImage(cv::Mat(8, 8, CV_16UC1, cv::Scalar(1000)), "16UC1"));
  EXPECT_NE(depth.find("unsupported encoding '16UC1'"), std::string::npos) << depth;
  EXPECT_NE(depth.find("a grey camera is published as mono8 or mono16"), std::string::npos) << depth;
}

TEST(ImageConversion, RejectsUnsupportedEncodingsByName) {
  EXPECT_TRUE(isSupportedEncoding("rgba8"));
  EXPECT_TRUE(isSupportedEncoding("bayer_rggb8"));
  EXPECT_FALSE(isSupportedEncoding("nv21"));
  const std::string nv21 = errorOf(makeImage(cv::Mat(8, 8, CV_8UC1, cv::Scalar(1)), "nv21"));
  EXPECT_NE(nv21.find("unsupported encoding 'nv21'"), std::string::npos) << nv21;
  EXPECT_NE(nv21.find("mono8"), std::string::npos) << nv21;
  EXPECT_NE(nv21.find("bayer_grbg16"), std::string::npos) << nv21;
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

TEST(ImageConversion, AStepShorterThanARowOfItsEncodingIsRefused) {
  // More bytes than pixels, but fewer than the encoding's bytes per pixel need: rows would overlap.
  sensor_msgs::Image bgr = makeImage(texturedBgr(), "bgr8");  // 160 px, 480 bytes a row
  bgr.step = 320;
  EXPECT_NE(errorOf(bgr).find("step 320 is less than width 160 x 3 bytes of bgr8"), std::string::npos)
      << errorOf(bgr);
  sensor_msgs::Image deep = makeImage(cv::Mat(8, 8, CV_16UC1, cv::Scalar(1)), "mono16");
  deep.step = 8;  // one byte a pixel
  EXPECT_NE(errorOf(deep).find("step 8 is less than width 8 x 2 bytes of mono16"), std::string::npos)
      << errorOf(deep);
  // Rows of 16-bit values must start at a value: OpenCV cannot read them otherwise.
  for (const std::string encoding : {"mono16", "bayer_rggb16"}) {
    sensor_msgs::Image odd = makeImage(cv::Mat(4, 4, CV_16UC1, cv::Scalar(1)), encoding);
    odd.step = 9;
    odd.data.resize(odd.step * odd.height);
    EXPECT_NE(errorOf(odd).find("step 9 is not a whole number of the 2-byte values of " + encoding), std::string::npos)
        << errorOf(odd);
  }
}

}  // namespace
}  // namespace node
}  // namespace mrs_vpr

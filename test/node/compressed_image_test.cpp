#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "mrs_vpr/node/compressed_format.hpp"
#include "mrs_vpr/node/compressed_image.hpp"
#include "node/camera_mosaics.hpp"

namespace mrs_vpr {
namespace node {
namespace {

/// A deterministic textured BGR image.
cv::Mat texturedBgr(int width = 160, int height = 120) {
  cv::Mat image(height, width, CV_8UC3);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      image.at<cv::Vec3b>(y, x) =
          cv::Vec3b(static_cast<uchar>((x * 7 + y * 3) % 256), static_cast<uchar>((x * x / 16 + y) % 256),
                    static_cast<uchar>((y * 11) % 256));
    }
  }
  return image;
}

/// What image_transport's compressed publisher sends: "<encoding>; <codec> compressed <encoding>".
sensor_msgs::CompressedImage compress(const cv::Mat& image, const std::string& codec,
                                      const std::string& encoding = "bgr8") {
  sensor_msgs::CompressedImage message;
  message.header.frame_id = "camera";
  message.format = encoding + "; " + codec + " compressed " + encoding;
  cv::imencode(codec == "jpeg" ? ".jpg" : ".png", image, message.data);
  return message;
}

std::string errorOf(const sensor_msgs::CompressedImage& message) {
  try {
    decodeCompressedImage(message);
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "";
}

TEST(CompressedImage, ParsesTheFormatsOfImageTransportAndCvBridge) {
  EXPECT_EQ(parseCompressedFormat("bgr8; jpeg compressed bgr8"), CompressedCodec::kJpeg);
  EXPECT_EQ(parseCompressedFormat("mono8; png compressed mono8"), CompressedCodec::kPng);
  EXPECT_EQ(parseCompressedFormat("rgb8; png compressed bgr8"), CompressedCodec::kPng);
  EXPECT_EQ(parseCompressedFormat("jpeg"), CompressedCodec::kJpeg);
  EXPECT_EQ(parseCompressedFormat("jpg"), CompressedCodec::kJpeg);
  EXPECT_EQ(parseCompressedFormat("PNG"), CompressedCodec::kPng);
  for (const std::string bad : {"", "tiff", "bgr8; bmp compressed bgr8", "jpeg or png"}) {
    try {
      parseCompressedFormat(bad);
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const std::invalid_argument& error) {
      EXPECT_NE(std::string(error.what()).find("unsupported compressed format '" + bad + "' (supported: jpeg, png)"),
                std::string::npos)
          << error.what();
    }
  }
  EXPECT_THROW(parseCompressedFormat("16UC1; compressedDepth png"), std::invalid_argument);
}

TEST(CompressedImage, PngDecodesToTheRawPixelsAndTheSameDescriptor) {
  const DescriptorExtractor extractor{DescriptorParams{}};
  const cv::Mat bgr = texturedBgr();
  const ImageFrame frame = decodeCompressedImage(compress(bgr, "png"));
  ASSERT_EQ(frame.image().type(), CV_8UC3);
  EXPECT_EQ(frame.order, ChannelOrder::kBgr);
  EXPECT_EQ(cv::norm(frame.image(), bgr, cv::NORM_INF), 0.0);
  EXPECT_EQ(cv::norm(extractor.compute(frame.image(), frame.order), extractor.compute(bgr), cv::NORM_INF), 0.0);
}

TEST(CompressedImage, JpegDecodesWithinTheCodecsError) {
  const DescriptorExtractor extractor{DescriptorParams{}};
  const cv::Mat bgr = texturedBgr(320, 240);
  const ImageFrame frame = decodeCompressedImage(compress(bgr, "jpeg"));
  ASSERT_EQ(frame.image().size(), bgr.size());
  cv::Mat gray;
  cv::Mat decoded_gray;
  cv::cvtColor(bgr, gray, cv::COLOR_BGR2GRAY);
  cv::cvtColor(frame.image(), decoded_gray, cv::COLOR_BGR2GRAY);
  // Grey levels after JPEG at OpenCV's default quality 95: a few levels off on average.
  EXPECT_LT(cv::norm(gray, decoded_gray, cv::NORM_L1) / static_cast<double>(gray.total()), 4.0);
  const cv::Mat raw = extractor.compute(bgr);
  const cv::Mat decoded = extractor.compute(frame.image(), frame.order);
  EXPECT_LT(cv::norm(raw, decoded, cv::NORM_L1) / raw.cols, 8.0);  // 32 levels per standard deviation
}

TEST(CompressedImage, KeepsGreyDepthAndAlpha) {
  cv::Mat mono;
  cv::cvtColor(texturedBgr(), mono, cv::COLOR_BGR2GRAY);
  EXPECT_EQ(decodeCompressedImage(compress(mono, "jpeg", "mono8")).image().type(), CV_8UC1);
  cv::Mat mono16;
  mono.convertTo(mono16, CV_16UC1, 257.0);
  const ImageFrame deep = decodeCompressedImage(compress(mono16, "png", "mono16"));
  EXPECT_EQ(deep.image().type(), CV_16UC1);
  EXPECT_EQ(cv::norm(deep.image(), mono16, cv::NORM_INF), 0.0);
  cv::Mat bgra;
  cv::cvtColor(texturedBgr(), bgra, cv::COLOR_BGR2BGRA);
  EXPECT_EQ(decodeCompressedImage(compress(bgra, "png", "bgra8")).image().type(), CV_8UC4);
}

TEST(CompressedImage, ACompressedBayerMosaicBecomesTheGreyOfItsColours) {
  const cv::Mat bgr = testing::redAcrossBlueDown();
  const cv::Mat mosaic = testing::mosaicOf(bgr, "gbrg");
  // image_transport's publisher compresses a mosaic as it is: "bayer_gbrg8; png compressed ".
  sensor_msgs::CompressedImage message = compress(mosaic, "png", "bayer_gbrg8");
  message.format = "bayer_gbrg8; png compressed ";
  const ImageFrame frame = decodeCompressedImage(message);
  ASSERT_EQ(frame.image().type(), CV_8UC1);
  EXPECT_LT(testing::interiorDifference(frame.image(), testing::greyOf(bgr)), 1.5);
  // A format that names no encoding gives the stored pixels, and so does a Bayer image that its
  // publisher made grey before compressing it: it must not be demosaiced again.
  for (const std::string format : {"png", "bayer_gbrg8; png compressed mono8"}) {
    message.format = format;
    EXPECT_EQ(cv::norm(decodeCompressedImage(message).image(), mosaic, cv::NORM_INF), 0.0) << format;
  }
}

TEST(CompressedImage, TheFormatTellsWhetherTheImageIsABayerMosaic) {
  EXPECT_EQ(compressedMosaicEncoding("bayer_rggb8; jpeg compressed "), "bayer_rggb8");
  EXPECT_EQ(compressedMosaicEncoding(" BAYER_GRBG16 ; png compressed"), "bayer_grbg16");
  EXPECT_EQ(compressedMosaicEncoding("bayer_bggr8; png compressed bayer_bggr8"), "bayer_bggr8");
  EXPECT_EQ(compressedMosaicEncoding("bayer_bggr8; jpeg compressed bgr8"), "");
  EXPECT_EQ(compressedMosaicEncoding("bgr8; jpeg compressed bgr8"), "");
  EXPECT_EQ(compressedMosaicEncoding("mono8; png compressed "), "");
  EXPECT_EQ(compressedMosaicEncoding("jpeg"), "");
  EXPECT_EQ(compressedMosaicEncoding(""), "");
}

TEST(CompressedImage, ReadsTheSizeFromTheHeader) {
  const cv::Mat bgr = texturedBgr(200, 80);
  EXPECT_EQ(compressedImageSize(compress(bgr, "jpeg").data, CompressedCodec::kJpeg), cv::Size(200, 80));
  EXPECT_EQ(compressedImageSize(compress(bgr, "png").data, CompressedCodec::kPng), cv::Size(200, 80));
}

TEST(CompressedImage, RefusesFormatsAndDataThatDoNotMatch) {
  const cv::Mat bgr = texturedBgr();
  sensor_msgs::CompressedImage tiff = compress(bgr, "png");
  tiff.format = "tiff";
  EXPECT_NE(errorOf(tiff).find("unsupported compressed format 'tiff'"), std::string::npos) << errorOf(tiff);

  sensor_msgs::CompressedImage mislabelled = compress(bgr, "jpeg");
  mislabelled.format = "png";
  EXPECT_NE(errorOf(mislabelled).find("not a PNG stream"), std::string::npos) << errorOf(mislabelled);

  sensor_msgs::CompressedImage empty;
  empty.format = "jpeg";
  EXPECT_NE(errorOf(empty).find("0 bytes that are not a JPEG stream"), std::string::npos) << errorOf(empty);
}

TEST(CompressedImage, WithoutAFormatTheBytesNameTheCodec) {
  // A publisher of its own that leaves `format` empty: read as cv_bridge and the bag tools read it.
  const cv::Mat bgr = texturedBgr();
  for (const std::string codec : {"jpeg", "png"}) {
    sensor_msgs::CompressedImage unnamed = compress(bgr, codec);
    const cv::Mat labelled = decodeCompressedImage(unnamed).image();
    unnamed.format = "";
    EXPECT_EQ(cv::norm(decodeCompressedImage(unnamed).image(), labelled, cv::NORM_INF), 0.0) << codec;
  }
  sensor_msgs::CompressedImage neither;
  neither.data = {'B', 'M', 0, 0, 0, 0};
  EXPECT_EQ(errorOf(neither), "the format is empty, and the 6 bytes begin as neither a jpeg nor a png stream");
}

TEST(CompressedImage, RefusesCorruptData) {
  const cv::Mat bgr = texturedBgr();
  sensor_msgs::CompressedImage short_png = compress(bgr, "png");
  short_png.data.resize(20);
  EXPECT_NE(errorOf(short_png).find("PNG header is truncated"), std::string::npos) << errorOf(short_png);

  sensor_msgs::CompressedImage cut_png = compress(bgr, "png");
  cut_png.data.resize(cut_png.data.size() / 3);  // a valid header, then too little image data
  EXPECT_NE(errorOf(cut_png).find("corrupt data: OpenCV cannot decode the PNG image"), std::string::npos)
      << errorOf(cut_png);

  sensor_msgs::CompressedImage garbage_jpeg = compress(bgr, "jpeg");
  garbage_jpeg.data.resize(3);
  garbage_jpeg.data.insert(garbage_jpeg.data.end(), 1000, 0x5A);  // no marker after the signature
  EXPECT_NE(errorOf(garbage_jpeg).find("corrupt data"), std::string::npos) << errorOf(garbage_jpeg);

  sensor_msgs::CompressedImage headless_jpeg = compress(bgr, "jpeg");
  headless_jpeg.data.resize(40);  // cut inside the headers, before the frame header
  EXPECT_NE(errorOf(headless_jpeg).find("corrupt data"), std::string::npos) << errorOf(headless_jpeg);
}

TEST(CompressedImage, RefusesATruncatedJpegThatLibjpegWouldFillWithGrey) {
  // libjpeg decodes a JPEG cut short with a warning only, grey where the data is missing.
  const sensor_msgs::CompressedImage whole = compress(texturedBgr(320, 240), "jpeg");
  for (const double kept : {0.95, 0.5, 0.3, 0.15}) {
    SCOPED_TRACE(kept);
    sensor_msgs::CompressedImage cut = whole;
    cut.data.resize(static_cast<std::size_t>(static_cast<double>(whole.data.size()) * kept));
    EXPECT_NE(errorOf(cut).find("corrupt data"), std::string::npos) << errorOf(cut);
  }
  sensor_msgs::CompressedImage cut = whole;
  cut.data.resize(whole.data.size() / 2);
  EXPECT_NE(errorOf(cut).find("the JPEG stream is truncated: it ends after " + std::to_string(cut.data.size()) +
                              " bytes, before its end-of-image marker"),
            std::string::npos)
      << errorOf(cut);
  // Complete streams still decode: with trailing bytes after the marker, with restart markers, and
  // progressive (several scans).
  sensor_msgs::CompressedImage padded = whole;
  padded.data.insert(padded.data.end(), 16, 0x00);
  EXPECT_EQ(errorOf(padded), "");
  for (const std::vector<int>& options : {std::vector<int>{cv::IMWRITE_JPEG_RST_INTERVAL, 4},
                                          std::vector<int>{cv::IMWRITE_JPEG_PROGRESSIVE, 1}}) {
    sensor_msgs::CompressedImage other = whole;
    cv::imencode(".jpg", texturedBgr(320, 240), other.data, options);
    EXPECT_EQ(errorOf(other), "") << options[0];
    other.data.resize(other.data.size() * 2 / 3);
    EXPECT_NE(errorOf(other).find("truncated"), std::string::npos) << options[0] << ": " << errorOf(other);
  }
}

TEST(CompressedImage, RefusesACorruptJpegThatStillEndsWithItsMarker) {
  // Bytes lost in transit from the middle of the scan: libjpeg would make up the rest of the image.
  const sensor_msgs::CompressedImage whole = compress(texturedBgr(320, 240), "jpeg");
  sensor_msgs::CompressedImage holed = whole;
  holed.data.resize(whole.data.size() / 2);
  holed.data.insert(holed.data.end(), {0xFF, 0xD9});
  EXPECT_NE(errorOf(holed).find("corrupt data: libjpeg cannot decode the JPEG stream without making up pixels: "
                                "Corrupt JPEG data"),
            std::string::npos)
      << errorOf(holed);
  EXPECT_EQ(errorOf(whole), "");
}

/// Writes `width` x `height` into the header of an encoded image, as a malicious or broken camera could.
void forgeSize(sensor_msgs::CompressedImage& message, CompressedCodec codec, std::uint32_t width,
               std::uint32_t height) {
  std::vector<std::uint8_t>& data = message.data;
  if (codec == CompressedCodec::kPng) {
    for (int i = 0; i < 4; ++i) {
      data[16 + i] = static_cast<std::uint8_t>(width >> (24 - 8 * i));
      data[20 + i] = static_cast<std::uint8_t>(height >> (24 - 8 * i));
    }
    return;
  }
  for (std::size_t at = 2; at + 9 < data.size(); ++at) {  // the baseline frame header SOF0 of imencode
    if (data[at] == 0xFF && data[at + 1] == 0xC0) {
      data[at + 5] = static_cast<std::uint8_t>(height >> 8);
      data[at + 6] = static_cast<std::uint8_t>(height);
      data[at + 7] = static_cast<std::uint8_t>(width >> 8);
      data[at + 8] = static_cast<std::uint8_t>(width);
      return;
    }
  }
  FAIL() << "no SOF0 marker";
}

TEST(CompressedImage, RefusesImagesLargerThanThePixelLimitBeforeDecoding) {
  const cv::Mat bgr = texturedBgr();
  sensor_msgs::CompressedImage huge_png = compress(bgr, "png");
  forgeSize(huge_png, CompressedCodec::kPng, 100000, 100000);
  EXPECT_NE(errorOf(huge_png).find("image of 100000 x 100000 pixels is larger than the 25000000 pixels allowed"),
            std::string::npos)
      << errorOf(huge_png);

  sensor_msgs::CompressedImage huge_jpeg = compress(bgr, "jpeg");
  forgeSize(huge_jpeg, CompressedCodec::kJpeg, 65535, 65535);
  EXPECT_NE(errorOf(huge_jpeg).find("image of 65535 x 65535 pixels is larger than"), std::string::npos)
      << errorOf(huge_jpeg);

  sensor_msgs::CompressedImage zero_png = compress(bgr, "png");
  forgeSize(zero_png, CompressedCodec::kPng, 0, 120);
  EXPECT_NE(errorOf(zero_png).find("empty PNG image (0 x 120 px)"), std::string::npos) << errorOf(zero_png);
}

/// The same JPEG with its Huffman tables (DHT, 0xC4) moved before its frame header, as some camera encoders write them.
std::vector<std::uint8_t> huffmanTablesFirst(const std::vector<std::uint8_t>& jpeg) {
  std::vector<std::vector<std::uint8_t>> segments;  // from SOI to the start of scan
  std::size_t at = 2;
  while (at + 4 <= jpeg.size() && jpeg[at] == 0xFF && jpeg[at + 1] != 0xDA) {
    const std::size_t length = (static_cast<std::size_t>(jpeg[at + 2]) << 8) | jpeg[at + 3];
    segments.emplace_back(jpeg.begin() + static_cast<std::ptrdiff_t>(at),
                          jpeg.begin() + static_cast<std::ptrdiff_t>(at + 2 + length));
    at += 2 + length;
  }
  std::stable_partition(segments.begin(), segments.end(),
                        [](const std::vector<std::uint8_t>& segment) { return segment[1] == 0xC4; });
  std::vector<std::uint8_t> moved(jpeg.begin(), jpeg.begin() + 2);
  for (const auto& segment : segments) moved.insert(moved.end(), segment.begin(), segment.end());
  moved.insert(moved.end(), jpeg.begin() + static_cast<std::ptrdiff_t>(at), jpeg.end());
  return moved;
}

TEST(CompressedImage, ReadsTheSizeFromTheFrameHeaderWhenHuffmanTablesComeFirst) {
  sensor_msgs::CompressedImage message = compress(texturedBgr(200, 80), "jpeg");
  const std::vector<std::uint8_t> moved = huffmanTablesFirst(message.data);
  ASSERT_EQ(moved.size(), message.data.size());
  ASSERT_NE(moved, message.data) << "imencode already wrote its tables first: nothing is tested";
  message.data = moved;
  EXPECT_EQ(compressedImageSize(message.data, CompressedCodec::kJpeg), cv::Size(200, 80));
  EXPECT_EQ(errorOf(message), "");
  EXPECT_EQ(decodeCompressedImage(message).image().size(), cv::Size(200, 80));
}


TEST(CompressedImage, APngHeightBeyondTheRangeOfAnIntIsCorruptData) {
  sensor_msgs::CompressedImage tall = compress(texturedBgr(), "png");
  forgeSize(tall, CompressedCodec::kPng, 160, 0x80000000U);
  try {
    const cv::Size size = compressedImageSize(tall.data, CompressedCodec::kPng);
    ADD_FAILURE() << "read as " << size.width << " x " << size.height;
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("corrupt data: PNG size 160 x 2147483648"), std::string::npos)
        << error.what();
  }
  EXPECT_NE(errorOf(tall).find("corrupt data: PNG size 160 x 2147483648"), std::string::npos) << errorOf(tall);
}

}  // namespace
}  // namespace node
}  // namespace mrs_vpr

// decodeStrictly: the pixels OpenCV decodes from a whole JPEG stream, and an error, naming libjpeg's
// warning, for a stream whose data is corrupt though it ends with its end-of-image marker.

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>  // jpeglib.h needs FILE
#include <cstdlib>
#include <string>
#include <vector>

#include <jpeglib.h>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "mrs_vpr/image_codecs.hpp"

namespace mrs_vpr {
namespace {

cv::Mat texture(int type) {
  cv::Mat image(96, 128, type);
  cv::RNG random(5);
  random.fill(image, cv::RNG::UNIFORM, 0, 256);
  return image;
}

std::vector<std::uint8_t> encoded(const cv::Mat& image, const std::vector<int>& options = {}) {
  std::vector<std::uint8_t> bytes;
  cv::imencode(".jpg", image, bytes, options);
  return bytes;
}

/// `image` (4 channels) as the JPEG stream of a print workflow's CMYK, or YCCK: OpenCV writes neither,
/// so libjpeg's own encoder makes them.
std::vector<std::uint8_t> encodedCmyk(const cv::Mat& image, J_COLOR_SPACE stored) {
  jpeg_compress_struct info{};
  jpeg_error_mgr errors{};
  info.err = jpeg_std_error(&errors);  // exit() on an error: none is expected here
  jpeg_create_compress(&info);
  unsigned char* buffer = nullptr;
  unsigned long size = 0;
  jpeg_mem_dest(&info, &buffer, &size);
  info.image_width = static_cast<JDIMENSION>(image.cols);
  info.image_height = static_cast<JDIMENSION>(image.rows);
  info.input_components = 4;
  info.in_color_space = JCS_CMYK;
  jpeg_set_defaults(&info);
  jpeg_set_colorspace(&info, stored);  // with the Adobe marker that tells CMYK from YCCK
  jpeg_start_compress(&info, TRUE);
  while (info.next_scanline < info.image_height) {
    JSAMPROW row = const_cast<JSAMPROW>(image.ptr<JSAMPLE>(static_cast<int>(info.next_scanline)));
    jpeg_write_scanlines(&info, &row, 1);
  }
  jpeg_finish_compress(&info);
  jpeg_destroy_compress(&info);
  std::vector<std::uint8_t> bytes(buffer, buffer + size);
  std::free(buffer);
  return bytes;
}

cv::Mat decodedStrictly(const std::vector<std::uint8_t>& bytes) {
  return image_codecs::decodeStrictly(bytes.data(), bytes.size());
}

std::string problemOf(const std::vector<std::uint8_t>& bytes) {
  try {
    decodedStrictly(bytes);
  } catch (const image_codecs::CorruptJpeg& error) {
    return error.what();
  }
  return "";
}

/// Where the entropy-coded data of the stream's first scan begins.
std::size_t scanData(const std::vector<std::uint8_t>& bytes) {
  for (std::size_t at = 2; at + 3 < bytes.size(); ++at) {
    if (bytes[at] == 0xFF && bytes[at + 1] == 0xDA) return at + 2 + (bytes[at + 2] << 8 | bytes[at + 3]);
  }
  ADD_FAILURE() << "no start of scan";
  return bytes.size();
}

/// The pixels decodeStrictly gives `bytes` are those OpenCV gives.
void expectOpenCvPixels(const std::vector<std::uint8_t>& bytes) {
  const cv::Mat opencv = cv::imdecode(bytes, cv::IMREAD_UNCHANGED);
  const cv::Mat strict = decodedStrictly(bytes);
  ASSERT_EQ(strict.type(), opencv.type());
  ASSERT_EQ(strict.size(), opencv.size());
  EXPECT_EQ(cv::norm(strict, opencv, cv::NORM_INF), 0.0);
}

/// `whole` with bytes lost in transit from the middle of its scan, the end-of-image marker still there.
std::vector<std::uint8_t> holed(const std::vector<std::uint8_t>& whole) {
  std::vector<std::uint8_t> bytes(whole.begin(), whole.begin() + static_cast<long>(scanData(whole) + 200));
  bytes.insert(bytes.end(), {0xFF, 0xD9});
  return bytes;
}

TEST(StrictJpegDecoding, AWholeStreamGivesThePixelsOpenCvGives) {
  const std::vector<std::vector<int>> options = {{},
                                                 {cv::IMWRITE_JPEG_QUALITY, 60},
                                                 {cv::IMWRITE_JPEG_PROGRESSIVE, 1},
                                                 {cv::IMWRITE_JPEG_RST_INTERVAL, 3},
                                                 {cv::IMWRITE_JPEG_OPTIMIZE, 1}};
  for (const int type : {CV_8UC1, CV_8UC3}) {
    for (const std::vector<int>& option : options) {
      SCOPED_TRACE(std::to_string(type) + (option.empty() ? "" : ", option " + std::to_string(option[0])));
      expectOpenCvPixels(encoded(texture(type), option));
    }
  }
  // Not JPEG: decoded by OpenCV as it is.
  std::vector<std::uint8_t> png;
  cv::imencode(".png", texture(CV_8UC3), png);
  EXPECT_EQ(cv::norm(decodedStrictly(png), texture(CV_8UC3), cv::NORM_INF), 0.0);
}

TEST(StrictJpegDecoding, CmykAndYcckStreamsGiveThePixelsOpenCvGivesOrTheirCorruption) {
  for (const J_COLOR_SPACE stored : {JCS_CMYK, JCS_YCCK}) {
    SCOPED_TRACE(stored == JCS_CMYK ? "CMYK" : "YCCK");
    const std::vector<std::uint8_t> whole = encodedCmyk(texture(CV_8UC4), stored);
    expectOpenCvPixels(whole);
    // OpenCV would give an image with made-up pixels.
    const std::vector<std::uint8_t> corrupt = holed(whole);
    EXPECT_FALSE(cv::imdecode(corrupt, cv::IMREAD_UNCHANGED).empty());
    EXPECT_NE(problemOf(corrupt).find("Corrupt JPEG data: premature end of data segment"), std::string::npos)
        << problemOf(corrupt);
  }
}

TEST(StrictJpegDecoding, CorruptDataThatEndsWithItsMarkerIsRefusedNamingLibjpegsWarning) {
  const std::vector<std::uint8_t> whole = encoded(texture(CV_8UC3));
  const std::vector<std::uint8_t> corrupt = holed(whole);
  EXPECT_NE(problemOf(corrupt).find("Corrupt JPEG data: premature end of data segment"), std::string::npos)
      << problemOf(corrupt);
  EXPECT_FALSE(cv::imdecode(corrupt, cv::IMREAD_UNCHANGED).empty()) << "what OpenCV would have given";
  // Nothing after the signature: the data ends before the image begins.
  EXPECT_EQ(problemOf({0xFF, 0xD8, 0x00, 0x00}), "Premature end of JPEG file");
  // A stream libjpeg cannot decode at all (no frame header before the scan): left to OpenCV, which
  // gives no image, as it always did.
  std::vector<std::uint8_t> frameless = whole;
  for (std::size_t at = 2; at + 1 < frameless.size(); ++at) {
    if (frameless[at] == 0xFF && frameless[at + 1] == 0xC0) frameless[at + 1] = 0xC3;  // lossless: unsupported
  }
  EXPECT_EQ(problemOf(frameless), "");
  EXPECT_TRUE(decodedStrictly(frameless).empty());
}

// Many cameras' streams carry warnings that leave every pixel whole: they are decoded as OpenCV does.
TEST(StrictJpegDecoding, WarningsThatLeaveThePixelsWholeAreNoCorruption) {
  const std::vector<std::uint8_t> whole = encoded(texture(CV_8UC3));
  const cv::Mat pixels = cv::imdecode(whole, cv::IMREAD_UNCHANGED);
  // Stray bytes before the end-of-image marker (libjpeg: "3 extraneous bytes before marker 0xd9").
  std::vector<std::uint8_t> padded = whole;
  padded.insert(padded.end() - 2, {0x12, 0x34, 0x56});
  // A JFIF revision libjpeg does not know ("unknown JFIF revision number 2.01").
  std::vector<std::uint8_t> revised = whole;
  ASSERT_EQ(std::string(revised.begin() + 6, revised.begin() + 10), "JFIF");
  revised[11] = 2;
  for (const std::vector<std::uint8_t>* stream : {&padded, &revised}) {
    EXPECT_EQ(problemOf(*stream), "");
    EXPECT_EQ(cv::norm(decodedStrictly(*stream), pixels, cv::NORM_INF), 0.0);
  }
}

}  // namespace
}  // namespace mrs_vpr

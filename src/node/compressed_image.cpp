#include "mrs_vpr/node/compressed_image.hpp"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <stdexcept>

#include <opencv2/imgproc.hpp>

#include "mrs_vpr/image_codecs.hpp"
#include "mrs_vpr/node/compressed_format.hpp"

namespace mrs_vpr {
namespace node {
namespace {

const std::array<std::uint8_t, 3> kJpegSignature{0xFF, 0xD8, 0xFF};
const std::array<std::uint8_t, 8> kPngSignature{0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};

bool contains(const std::string& text, const char* word) { return text.find(word) != std::string::npos; }

const char* codecName(CompressedCodec codec) { return codec == CompressedCodec::kJpeg ? "JPEG" : "PNG"; }

template <std::size_t N>
bool startsWith(const std::vector<std::uint8_t>& data, const std::array<std::uint8_t, N>& signature) {
  return data.size() >= N && std::equal(signature.begin(), signature.end(), data.begin());
}

std::uint32_t bigEndian16(const std::vector<std::uint8_t>& data, std::size_t at) {
  return (static_cast<std::uint32_t>(data[at]) << 8) | data[at + 1];
}

std::uint32_t bigEndian32(const std::vector<std::uint8_t>& data, std::size_t at) {
  return (bigEndian16(data, at) << 16) | bigEndian16(data, at + 2);
}

std::invalid_argument truncated(CompressedCodec codec) {
  return std::invalid_argument(std::string("corrupt data: the ") + codecName(codec) + " header is truncated");
}

/// The frame header (SOFn) holds the size; the segments before it are skipped by their lengths.
cv::Size jpegSize(const std::vector<std::uint8_t>& data) {
  std::size_t at = 2;  // after SOI
  while (at < data.size()) {
    if (data[at] != 0xFF) {
      throw std::invalid_argument("corrupt data: no JPEG marker at byte " + std::to_string(at));
    }
    while (at < data.size() && data[at] == 0xFF) ++at;  // fill bytes
    if (at >= data.size()) break;
    const std::uint8_t marker = data[at++];
    if (marker == 0x01 || (marker >= 0xD0 && marker <= 0xD7)) continue;  // markers without a segment
    if (marker == 0xD9 || marker == 0xDA) {
      throw std::invalid_argument("corrupt data: the JPEG stream has no frame header before its image data");
    }
    if (at + 2 > data.size()) break;
    const std::uint32_t length = bigEndian16(data, at);
    if (length < 2) {
      throw std::invalid_argument("corrupt data: a JPEG segment of length " + std::to_string(length));
    }
    const bool frame_header = marker >= 0xC0 && marker <= 0xCF && marker != 0xC4 && marker != 0xC8 && marker != 0xCC;
    if (frame_header) {
      if (at + 7 > data.size()) break;
      return cv::Size(static_cast<int>(bigEndian16(data, at + 5)), static_cast<int>(bigEndian16(data, at + 3)));
    }
    at += length;
  }
  throw truncated(CompressedCodec::kJpeg);
}

/// The first chunk of a PNG is IHDR, whose first fields are the width and height.
cv::Size pngSize(const std::vector<std::uint8_t>& data) {
  if (data.size() < 24) throw truncated(CompressedCodec::kPng);
  if (!std::equal(data.begin() + 12, data.begin() + 16, "IHDR")) {
    throw std::invalid_argument("corrupt data: the PNG stream does not start with an IHDR chunk");
  }
  const std::uint32_t width = bigEndian32(data, 16);
  const std::uint32_t height = bigEndian32(data, 20);
  if (width > 0x7FFFFFFFU || height > 0x7FFFFFFFU) {
    throw std::invalid_argument("corrupt data: PNG size " + std::to_string(width) + " x " + std::to_string(height));
  }
  return cv::Size(static_cast<int>(width), static_cast<int>(height));
}

/// The message's codec: the one its format names, or where it names none (a publisher of its own that
/// left `format` empty) the one its bytes begin with, as cv_bridge and the bag tools read it.
CompressedCodec codecOf(const sensor_msgs::CompressedImage& message) {
  if (message.format.find_first_not_of(" \t") != std::string::npos) return parseCompressedFormat(message.format);
  if (startsWith(message.data, kJpegSignature)) return CompressedCodec::kJpeg;
  if (startsWith(message.data, kPngSignature)) return CompressedCodec::kPng;
  throw std::invalid_argument("the format is empty, and the " + std::to_string(message.data.size()) +
                              " bytes begin as neither a jpeg nor a png stream");
}

bool isDescribable(int type) { return type == CV_8UC1 || type == CV_16UC1 || type == CV_8UC3 || type == CV_8UC4; }

}  // namespace

CompressedCodec parseCompressedFormat(const std::string& format) {
  const CompressedFormat parts(format);
  if (contains(parts.text, "compresseddepth")) {
    throw std::invalid_argument("format '" + format + "' is of the compressedDepth transport, which is not supported");
  }
  // "bgr8; jpeg compressed bgr8": the codec follows the original encoding.
  const bool jpeg = contains(parts.codec, "jpeg") || contains(parts.codec, "jpg");
  const bool png = contains(parts.codec, "png");
  if (jpeg == png) {
    throw std::invalid_argument("unsupported compressed format '" + format + "' (supported: jpeg, png)");
  }
  return jpeg ? CompressedCodec::kJpeg : CompressedCodec::kPng;
}

cv::Size compressedImageSize(const std::vector<std::uint8_t>& data, CompressedCodec codec) {
  const bool signed_right =
      codec == CompressedCodec::kJpeg ? startsWith(data, kJpegSignature) : startsWith(data, kPngSignature);
  if (!signed_right) {
    throw std::invalid_argument(std::string("corrupt data: ") + std::to_string(data.size()) + " bytes that are not a " +
                                codecName(codec) + " stream");
  }
  return codec == CompressedCodec::kJpeg ? jpegSize(data) : pngSize(data);
}

ImageFrame decodeCompressedImage(const sensor_msgs::CompressedImage& message) {
  const CompressedCodec codec = codecOf(message);
  const cv::Size size = compressedImageSize(message.data, codec);
  if (size.width <= 0 || size.height <= 0) {
    throw std::invalid_argument(std::string("empty ") + codecName(codec) + " image (" + std::to_string(size.width) +
                                " x " + std::to_string(size.height) + " px)");
  }
  if (static_cast<long long>(size.width) * size.height > DescriptorExtractor::kMaxImagePixels) {
    throw std::invalid_argument("image of " + std::to_string(size.width) + " x " + std::to_string(size.height) +
                                " pixels is larger than the " + std::to_string(DescriptorExtractor::kMaxImagePixels) +
                                " pixels allowed");
  }
  // libjpeg decodes a stream cut short with a warning only, grey where it is cut: refused instead.
  const bool truncated = codec == CompressedCodec::kJpeg &&
                         !image_codecs::jpegReachesEndOfImage(message.data.data(), message.data.size());
  if (truncated) {
    throw std::invalid_argument("corrupt data: the JPEG stream is truncated: it ends after " +
                                std::to_string(message.data.size()) + " bytes, before its end-of-image marker");
  }
  cv::Mat image;
  try {
    // IMREAD_UNCHANGED keeps grey, depth and alpha.
    image = image_codecs::decodeStrictly(message.data.data(), message.data.size());
  } catch (const image_codecs::CorruptJpeg& error) {
    throw std::invalid_argument(std::string("corrupt data: libjpeg cannot decode the JPEG stream without making up "
                                            "pixels: ") +
                                error.what());
  } catch (const cv::Exception& error) {
    throw std::invalid_argument(std::string("corrupt data: OpenCV cannot decode the ") + codecName(codec) +
                                " image: " + error.what());
  }  // std::runtime_error of a codec plugin that cannot be loaded passes as it is
  if (image.empty()) {
    throw std::invalid_argument(std::string("corrupt data: OpenCV cannot decode the ") + codecName(codec) + " image");
  }
  if (!isDescribable(image.type())) {
    throw std::invalid_argument(
        std::string("the ") + codecName(codec) + " image decodes to " + cv::typeToString(image.type()) +
        ", which is not described (supported: " + "8-bit grey, colour or colour with alpha, 16-bit grey)");
  }
  ImageFrame frame;
  // A Bayer camera's image is compressed as its mosaic (image_transport's publisher keeps it so).
  const int demosaic = bayerToGreyCode(compressedMosaicEncoding(message.format));
  if (demosaic >= 0 && image.channels() == 1) {
    cv::cvtColor(image, frame.pixels, demosaic);
  } else {
    frame.pixels = image;
  }
  frame.order = ChannelOrder::kBgr;  // imdecode returns blue first, whatever the publisher's encoding was
  return frame;
}

}  // namespace node
}  // namespace mrs_vpr

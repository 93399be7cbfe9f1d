#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include <opencv2/core.hpp>

namespace mrs_vpr {
namespace image_codecs {

/// What decodeJpegStrictly() made of a stream.
enum class JpegDecoding {
  kDecoded,     ///< The image, as OpenCV decodes it.
  kCorrupt,     ///< libjpeg found an error or warned (its message is the problem).
  kNotHandled,  ///< Not one or three components (CMYK, say), or too large: for OpenCV to decode or refuse.
};

/**
 * libjpeg's decoding of a JPEG stream into the image cv::imdecode(IMREAD_UNCHANGED) gives (grey stays
 * grey, colour becomes BGR), stopped at the first warning. libjpeg decodes a stream whose
 * entropy-coded data is corrupt with a warning only (on stderr), making up what it cannot read;
 * OpenCV gives that image as if nothing were wrong. Part of the codec plugin, which links libjpeg.
 */
JpegDecoding decodeJpegStrictly(const std::uint8_t* data, std::size_t size, cv::Mat* image, std::string* problem);

}  // namespace image_codecs
}  // namespace mrs_vpr

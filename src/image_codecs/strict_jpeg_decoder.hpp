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
  kCorrupt,     ///< libjpeg warned that it made up pixels it could not read (its message is the problem).
  /// Not one, three or four components (grey, colour, CMYK or YCCK), too large, or not decodable by
  /// libjpeg at all: for OpenCV to decode or refuse, as it did before.
  kNotHandled,
};

/**
 * libjpeg's decoding of a JPEG stream into the image cv::imdecode(IMREAD_UNCHANGED) gives (grey stays
 * grey, colour and CMYK become BGR), stopped at the first warning that it made up pixels. libjpeg decodes a
 * stream whose entropy-coded data is missing or undecodable with a warning only (on stderr), making
 * up what it cannot read; OpenCV gives that image as if nothing were wrong. Warnings that leave the
 * pixels whole (stray bytes between segments, an unknown JFIF revision) are ignored, as many cameras'
 * streams carry them. Part of the codec plugin, which links libjpeg.
 */
JpegDecoding decodeJpegStrictly(const std::uint8_t* data, std::size_t size, cv::Mat* image, std::string* problem);

}  // namespace image_codecs
}  // namespace mrs_vpr

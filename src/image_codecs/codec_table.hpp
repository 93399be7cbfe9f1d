#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "strict_jpeg_decoder.hpp"

namespace mrs_vpr {
namespace image_codecs {

/// What the codec plugin hands to the loader: OpenCV's own functions, so that their behaviour
/// (formats, flags, exceptions) is exactly OpenCV's, and libjpeg's strict decoding of JPEG.
struct CodecTable {
  cv::Mat (*read)(const cv::String& path, int flags);
  cv::Mat (*decode)(cv::InputArray buffer, int flags);
  bool (*write)(const cv::String& path, cv::InputArray image, const std::vector<int>& params);
  bool (*encode)(const cv::String& extension, cv::InputArray image, std::vector<std::uint8_t>& buffer,
                 const std::vector<int>& params);
  JpegDecoding (*decode_jpeg)(const std::uint8_t* data, std::size_t size, cv::Mat* image, std::string* problem);
};

/// The plugin's one exported symbol (unmangled, for dlsym).
/// It names the table's layout: a plugin of another release, with another table, is not found (an
/// error naming the plugin) rather than read past its end.
constexpr const char* kCodecTableSymbol = "mrs_vpr_opencv_codec_table_v2";
/// The plugin's file name; it is installed beside the library that loads it.
constexpr const char* kCodecPluginFile = "libmrs_vpr_opencv_codecs.so";

}  // namespace image_codecs
}  // namespace mrs_vpr

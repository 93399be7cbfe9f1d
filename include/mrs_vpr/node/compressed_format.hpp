#pragma once

#include <algorithm>
#include <cctype>
#include <string>

namespace mrs_vpr {
namespace node {

/**
 * The Bayer encoding whose mosaic a sensor_msgs/CompressedImage of `format` holds: "bayer_rggb8" of
 * "bayer_rggb8; png compressed ", as image_transport's compressed publisher writes a Bayer camera's
 * frames. Empty when it holds another image: a format that names no encoding ("jpeg"), a colour or
 * grey one, or a Bayer one compressed as another ("bayer_rggb8; jpeg compressed mono8", a publisher
 * that made grey first, which must not be demosaiced again). Header-only: the bag reader plugin reads
 * compressed frames too, without the node's libraries.
 */
inline std::string compressedMosaicEncoding(std::string format) {
  std::transform(format.begin(), format.end(), format.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  const auto trimmed = [](const std::string& text) {
    const std::size_t begin = text.find_first_not_of(" \t");
    return begin == std::string::npos ? std::string() : text.substr(begin, text.find_last_not_of(" \t") - begin + 1);
  };
  const std::size_t separator = format.find(';');
  if (separator == std::string::npos) return "";
  const std::string original = trimmed(format.substr(0, separator));
  const std::string codec = format.substr(separator + 1);
  const std::size_t compressed = codec.find("compressed");
  const std::string target =
      compressed == std::string::npos ? std::string() : trimmed(codec.substr(compressed + sizeof("compressed") - 1));
  const auto isBayer = [](const std::string& encoding) { return encoding.rfind("bayer_", 0) == 0; };
  return isBayer(original) && (target.empty() || target == original) ? original : "";
}

}  // namespace node
}  // namespace mrs_vpr

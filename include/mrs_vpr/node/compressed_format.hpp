#pragma once

#include <algorithm>
#include <cctype>
#include <string>
#include <utility>

namespace mrs_vpr {
namespace node {

/**
 * A sensor_msgs/CompressedImage format, lower-cased and split into its parts. image_transport's
 * compressed publisher writes "<encoding>; <codec> compressed <target>": "bgr8; jpeg compressed bgr8"
 * (a colour image made bgr8 first), "bayer_rggb8; png compressed " (a Bayer mosaic as it was); cv_bridge
 * and older publishers write the codec alone ("jpeg"). Header-only: the bag reader plugin reads
 * compressed frames too, without the node's libraries.
 */
struct CompressedFormat {
  explicit CompressedFormat(std::string format) : text(std::move(format)) {
    std::transform(text.begin(), text.end(), text.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    const std::size_t separator = text.find(';');
    if (separator != std::string::npos) encoding = trimmed(text.substr(0, separator));
    codec = separator == std::string::npos ? text : text.substr(separator + 1);
    const std::size_t compressed = codec.find("compressed");
    if (compressed != std::string::npos) target = trimmed(codec.substr(compressed + sizeof("compressed") - 1));
  }

  std::string text;      ///< The whole format, lower-cased.
  std::string encoding;  ///< Before ';': the image's encoding before it was compressed; "" when none is named.
  std::string codec;     ///< After ';', or the whole format without one: the codec and what follows it.
  std::string target;    ///< After "compressed": what the image was made before it was compressed; "" when as it was.

 private:
  static std::string trimmed(const std::string& part) {
    const std::size_t begin = part.find_first_not_of(" \t");
    return begin == std::string::npos ? std::string() : part.substr(begin, part.find_last_not_of(" \t") - begin + 1);
  }
};

/**
 * The Bayer encoding whose mosaic a CompressedImage of `format` holds: "bayer_rggb8" of
 * "bayer_rggb8; png compressed ", as image_transport's publisher writes a Bayer camera's frames. Empty
 * when it holds another image: a format that names no encoding ("jpeg"), a colour or grey one, or a
 * Bayer one compressed as another ("bayer_rggb8; jpeg compressed mono8", a publisher that made grey
 * first, which must not be demosaiced again).
 */
inline std::string compressedMosaicEncoding(const std::string& format) {
  const CompressedFormat parts(format);
  const bool bayer = parts.encoding.rfind("bayer_", 0) == 0;
  return bayer && (parts.target.empty() || parts.target == parts.encoding) ? parts.encoding : "";
}

}  // namespace node
}  // namespace mrs_vpr

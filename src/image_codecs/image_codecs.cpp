#include "mrs_vpr/image_codecs.hpp"

#include <string>

#include "../plugin_loader/plugin_loader.hpp"
#include "codec_table.hpp"

namespace mrs_vpr {
namespace image_codecs {
namespace {

const CodecTable& loadTable() {
  // A function-local static is initialised once, also when several threads read images at once.
  static const CodecTable& table = plugins::load<CodecTable>(kCodecPluginFile, kCodecTableSymbol, "image codecs");
  return table;
}

}  // namespace

cv::Mat read(const std::string& path, int flags) { return loadTable().read(path, flags); }

cv::Mat decode(const cv::Mat& buffer, int flags) { return loadTable().decode(buffer, flags); }

cv::Mat decodeStrictly(const std::uint8_t* data, std::size_t size) {
  const bool jpeg = size >= 2 && data[0] == 0xFF && data[1] == 0xD8;
  if (jpeg) {
    cv::Mat image;
    std::string problem;
    switch (loadTable().decode_jpeg(data, size, &image, &problem)) {
      case JpegDecoding::kDecoded:
        return image;
      case JpegDecoding::kCorrupt:
        throw CorruptJpeg(problem);
      case JpegDecoding::kNotHandled:
        break;
    }
  }
  // imdecode only reads the bytes it wraps.
  const cv::Mat buffer(1, static_cast<int>(size), CV_8UC1, const_cast<std::uint8_t*>(data));
  return decode(buffer, cv::IMREAD_UNCHANGED);
}

bool write(const std::string& path, const cv::Mat& image, const std::vector<int>& params) {
  return loadTable().write(path, image, params);
}

bool encode(const std::string& extension, const cv::Mat& image, std::vector<std::uint8_t>& buffer,
            const std::vector<int>& params) {
  return loadTable().encode(extension, image, buffer, params);
}

}  // namespace image_codecs
}  // namespace mrs_vpr

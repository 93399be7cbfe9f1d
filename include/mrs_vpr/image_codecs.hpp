#pragma once

#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>  // The cv::IMREAD_* and cv::IMWRITE_* flags only.

namespace mrs_vpr {
namespace image_codecs {

/**
 * OpenCV's image file and stream codecs (cv::imread, cv::imdecode, cv::imwrite, cv::imencode), loaded
 * the first time one is called instead of when the program starts.
 *
 * Debian's libopencv_imgcodecs brings GDAL and about 120 further libraries; loading them took most of
 * a tool's start-up (0.1 s), also for runs that never touch an image file (`--help`, a map database).
 * The codecs live in a plugin library (libmrs_vpr_opencv_codecs.so, beside this library) that is
 * opened once, thread-safely, on the first call. Each function behaves exactly as its OpenCV namesake
 * and throws std::runtime_error, naming the plugin and the loader's reason, when it cannot be loaded.
 */
cv::Mat read(const std::string& path, int flags);

/// cv::imdecode of an encoded stream (a 1 x n CV_8UC1 matrix or a vector of bytes).
cv::Mat decode(const cv::Mat& buffer, int flags);

/// A JPEG stream whose data libjpeg finds missing or undecodable; what() is libjpeg's warning.
class CorruptJpeg : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/**
 * decode(buffer, cv::IMREAD_UNCHANGED) of a camera frame or image file, except that a JPEG stream
 * whose data libjpeg finds missing or undecodable (bytes lost in transit, a bad Huffman code) throws
 * CorruptJpeg: libjpeg decodes such a stream with a warning on stderr only, making up what it cannot
 * read, and OpenCV gives that image as if it were whole. Only what libjpeg notices is caught (few
 * flipped bits are), and warnings that leave the pixels whole are ignored (strict_jpeg_decoder.hpp).
 * JPEG of one, three or four components (grey, colour, CMYK or YCCK) is decoded by libjpeg directly,
 * into the pixels OpenCV gives; other streams, and those libjpeg cannot decode at all, by OpenCV.
 */
cv::Mat decodeStrictly(const std::uint8_t* data, std::size_t size);

/// cv::imwrite: false when OpenCV cannot write the file; cv::Exception as OpenCV throws it.
bool write(const std::string& path, const cv::Mat& image, const std::vector<int>& params = {});

/**
 * True when a JPEG stream of `size` bytes reaches its end-of-image marker, false when it is cut short
 * (or not JPEG at all). libjpeg, and so cv::imdecode and cv::imread, decode a truncated stream with a
 * warning only, filling what is missing with grey; a camera frame or file cut short must be refused
 * instead. Reads the segments and skips the entropy-coded data of each scan; decodes nothing.
 */
bool jpegReachesEndOfImage(const std::uint8_t* data, std::size_t size);

/// cv::imencode into `buffer` in the format of `extension` (".png", ".jpg").
bool encode(const std::string& extension, const cv::Mat& image, std::vector<std::uint8_t>& buffer,
            const std::vector<int>& params = {});

}  // namespace image_codecs
}  // namespace mrs_vpr

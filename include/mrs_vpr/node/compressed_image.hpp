#pragma once

#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <sensor_msgs/CompressedImage.h>

#include "mrs_vpr/node/image_conversion.hpp"

namespace mrs_vpr {
namespace node {

/// The codecs of the `compressed` image transport that the node decodes.
enum class CompressedCodec { kJpeg, kPng };

/**
 * The codec a CompressedImage's `format` names. Accepts the strings of image_transport's
 * compressed publisher ("bgr8; jpeg compressed bgr8", "mono8; png compressed mono8") and of cv_bridge
 * and older publishers ("jpeg", "jpg", "png"), in any case. Throws std::invalid_argument for any other
 * format, compressedDepth included.
 */
CompressedCodec parseCompressedFormat(const std::string& format);

/**
 * Width and height stored in the header of a JPEG or PNG stream, read without decoding it, so that
 * an image too large to describe is refused before it costs any memory. Throws std::invalid_argument
 * when the data is not a stream of `codec` or its header is truncated or malformed.
 */
cv::Size compressedImageSize(const std::vector<std::uint8_t>& data, CompressedCodec codec);

/**
 * Decodes a sensor_msgs/CompressedImage (jpeg or png) into a frame for DescriptorExtractor::compute:
 * CV_8UC1, CV_16UC1, CV_8UC3 (BGR) or CV_8UC4 (BGRA) as stored; a Bayer mosaic (compressed_format.hpp)
 * demosaiced to grey. Checks the format string, the stream's signature and its size against
 * DescriptorExtractor::kMaxImagePixels before decoding. Throws std::invalid_argument, with a message
 * naming the problem, for a bad format, corrupt data or an image too large.
 */
ImageFrame decodeCompressedImage(const sensor_msgs::CompressedImage& message);

}  // namespace node
}  // namespace mrs_vpr

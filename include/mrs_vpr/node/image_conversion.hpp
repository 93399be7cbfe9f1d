#pragma once

#include <string>

#include <boost/shared_ptr.hpp>
#include <opencv2/core.hpp>
#include <sensor_msgs/Image.h>

#include "mrs_vpr/descriptor.hpp"

namespace mrs_vpr {
namespace node {

/// An image message as OpenCV sees it, ready for DescriptorExtractor::compute.
struct ImageFrame {
  /// Shares the message's pixels when possible, so a frame costs no copy.
  cv::Mat pixels;
  /// Keeps the message alive while `pixels` shares its memory (null when nothing needs keeping).
  boost::shared_ptr<void const> owner;
  ChannelOrder order = ChannelOrder::kBgr;

  const cv::Mat& image() const { return pixels; }
};

/// True for the encodings the descriptor accepts: mono8, mono16, bgr8, rgb8, bgra8, rgba8, bgr16,
/// rgb16, bgra16, rgba16, the Bayer mosaics bayer_{rggb,bggr,gbrg,grbg}{8,16}, yuv422 (UYVY) and
/// yuv422_yuy2 (YUYV), and OpenCV's 8UC1, 8UC3 and 8UC4 (read as OpenCV's images: mono8, bgr8, bgra8).
bool isSupportedEncoding(const std::string& encoding);

/// The encodings accepted, for messages: "mono8, mono16, bgr8, ...".
std::string supportedEncodings();

/// For a Bayer encoding ("bayer_rggb8", ...), the cv::cvtColor code that demosaics it to grey; -1 for
/// any other encoding. A compressed Bayer image decodes to its mosaic, which needs it as well.
int bayerToGreyCode(const std::string& encoding);

/**
 * Converts an image message. Grey and colour images keep their encoding, and `tracked_object` keeps
 * the message's memory alive while the returned frame shares it (pass the message's shared pointer,
 * or nullptr when the caller outlives the frame). A Bayer mosaic or YUV image becomes a grey copy (of
 * the mosaic's depth), the only image the front ends read. Throws std::invalid_argument, with a
 * message naming the problem, for an empty image, an unsupported encoding or a data array too short
 * for its size and step.
 */
ImageFrame fromImageMessage(const sensor_msgs::Image& message,
                            const boost::shared_ptr<void const>& tracked_object = nullptr);

/// Converts and describes one image. Throws std::invalid_argument as fromImageMessage and compute do.
cv::Mat describeImage(const DescriptorExtractor& extractor, const sensor_msgs::Image& message,
                      const boost::shared_ptr<void const>& tracked_object = nullptr);

}  // namespace node
}  // namespace mrs_vpr

#include "traversal_reader.hpp"

#include <chrono>
#include <iomanip>
#include <iostream>
#include <stdexcept>

#include "mrs_vpr/evaluation/image_folder.hpp"
#include "mrs_vpr/node/bag_images.hpp"
#include "mrs_vpr/node/image_conversion.hpp"

namespace mrs_vpr {
namespace tools {
namespace {

double secondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

Traversal readTraversal(const std::string& source, const std::string& topic, const std::string& what,
                        const DescriptorExtractor& extractor,
                        const std::function<void(const cv::Mat& descriptor, double stamp)>& append) {
  const auto start = std::chrono::steady_clock::now();
  Traversal traversal;
  const auto add = [&](const cv::Mat& descriptor, double stamp) {
    append(descriptor, stamp);
    if (++traversal.frames % 500 == 0) std::cerr << "  " << what << ": " << traversal.frames << " frames\n";
  };
  const auto checkSize = [&](const cv::Size& size, const std::string& image_name) {
    if (traversal.frames == 0) {
      traversal.image_size = size;
    } else if (size != traversal.image_size) {
      throw std::runtime_error(image_name + " is " + std::to_string(size.width) + "x" + std::to_string(size.height) +
                               " but the first " + what + " image is " + std::to_string(traversal.image_size.width) +
                               "x" + std::to_string(traversal.image_size.height));
    }
  };

  if (mrs_vpr::bag::isBagPath(source)) {
    mrs_vpr::bag::forEachImage(source, topic, [&](int index, const sensor_msgs::ImageConstPtr& image) {
      const std::string name = what + " message " + std::to_string(index) + " of '" + source + "'";
      checkSize(cv::Size(static_cast<int>(image->width), static_cast<int>(image->height)), name);
      try {
        add(mrs_vpr::node::describeImage(extractor, *image, image), image->header.stamp.toSec());
      } catch (const std::invalid_argument& error) {
        throw std::runtime_error(name + ": " + error.what());
      }
    });
  } else {
    mrs_vpr::forEachImage(source, [&](int index, const std::string& path, const cv::Mat& image) {
      checkSize(image.size(), "image '" + path + "'");
      try {
        // cv::imread gives BGR; the frame index is the stamp, as a folder has no times.
        add(extractor.compute(image, mrs_vpr::ChannelOrder::kBgr), index);
      } catch (const std::invalid_argument& error) {
        throw std::runtime_error("image '" + path + "': " + error.what());
      }
    });
  }
  std::cerr << "  " << what << ": " << traversal.frames << " frames of " << traversal.image_size.width
            << "x" << traversal.image_size.height << " px described in " << std::fixed << std::setprecision(2)
            << secondsSince(start) << " s\n";
  return traversal;
}

}  // namespace tools
}  // namespace mrs_vpr

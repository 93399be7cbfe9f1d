#include "traversal_reader.hpp"

#include <iostream>
#include <stdexcept>
#include <vector>

#include "mrs_vpr/evaluation/image_folder.hpp"
#include "mrs_vpr/evaluation/progress_line.hpp"
#include "mrs_vpr/node/bag_images.hpp"
#include "mrs_vpr/node/image_conversion.hpp"
#include "mrs_vpr/node/ros_stamp.hpp"
#include "interruption.hpp"

namespace mrs_vpr {
namespace tools {

namespace {

bool isBag(const std::string& source, SourceKind kind) {
  return kind == SourceKind::kByName ? mrs_vpr::bag::isBagPath(source) : kind == SourceKind::kBag;
}

}  // namespace

int countFrames(const std::string& source, const std::string& topic, SourceKind kind) {
  return isBag(source, kind) ? mrs_vpr::bag::countImages(source, topic)
                             : static_cast<int>(mrs_vpr::listImageFiles(source).size());
}

Traversal readTraversal(const std::string& source, const std::string& topic, const std::string& what,
                        const DescriptorExtractor& extractor,
                        const std::function<void(const cv::Mat& descriptor, Stamp stamp)>& append,
                        SourceKind kind) {
  const bool bag = isBag(source, kind);
  int total = 0;
  if (bag) {
    total = countFrames(source, topic, kind);
  } else {
    std::vector<std::string> left_out;
    const std::vector<std::string> files = mrs_vpr::listImageFiles(source, &left_out);
    total = static_cast<int>(files.size());
    for (const std::string& note : {mrs_vpr::leftOutNote(source, left_out), mrs_vpr::fractionOrderNote(files)}) {
      if (!note.empty()) std::cerr << "  " << what << ": " << note << "\n";
    }
  }
  ProgressLine progress = ProgressLine::onStderr("  " + what, "frames", total);
  Traversal traversal;
  const auto add = [&](const cv::Mat& descriptor, Stamp stamp) {
    stopIfInterrupted();
    append(descriptor, stamp);
    progress.update(++traversal.frames);
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

  if (bag) {
    mrs_vpr::bag::forEachImage(source, topic, [&](int index, const sensor_msgs::ImageConstPtr& image) {
      const std::string name = what + " message " + std::to_string(index) + " of '" + source + "'";
      checkSize(cv::Size(static_cast<int>(image->width), static_cast<int>(image->height)), name);
      try {
        add(mrs_vpr::node::describeImage(extractor, *image, image), mrs_vpr::node::stampOf(image->header.stamp));
      } catch (const std::invalid_argument& error) {
        throw std::runtime_error(name + ": " + error.what());
      }
    });
  } else {
    mrs_vpr::forEachImage(source, [&](int index, const std::string& path, const cv::Mat& image) {
      checkSize(image.size(), "image '" + path + "'");
      try {
        // cv::imread gives BGR; the frame index is the stamp, as a folder has no times.
        add(extractor.compute(image, mrs_vpr::ChannelOrder::kBgr), Stamp::fromSecondsAndNanoseconds(index, 0));
      } catch (const std::invalid_argument& error) {
        throw std::runtime_error("image '" + path + "': " + error.what());
      }
    });
  }
  progress.finish("of " + std::to_string(traversal.image_size.width) + "x" +
                  std::to_string(traversal.image_size.height) + " px described");
  return traversal;
}

}  // namespace tools
}  // namespace mrs_vpr

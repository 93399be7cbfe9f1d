#pragma once

// Reading a traversal for the command-line tools: every image of a folder (file-name order) or of a
// bag's topic, described, with its stamp.

#include <functional>
#include <string>

#include <opencv2/core.hpp>

#include "mrs_vpr/descriptor.hpp"
#include "mrs_vpr/stamp.hpp"

namespace mrs_vpr {
namespace tools {

/// How a traversal's source is read.
enum class SourceKind {
  kByName,  ///< A bag when its name ends in .bag, else an image folder (the evaluator's DIR|BAG).
  kBag,     ///< A bag, whatever its name (build_map --bag).
  kFolder,  ///< An image folder, whatever its name (build_map --images).
};

/// What was read of a traversal: how many frames, and the size of its images.
struct Traversal {
  int frames = 0;
  cv::Size image_size;
};

/// The frames of a folder or of a bag's `topic`, counted without reading an image: a check of what
/// depends on the count comes before minutes of describing.
int countFrames(const std::string& source, const std::string& topic, SourceKind kind = SourceKind::kByName);

/**
 * Reads and describes every image of a folder or bag (`topic`), handing each descriptor with its
 * exact stamp to `append` (a folder's frames are stamped with their index, in seconds), and reports
 * progress on stderr as `what`. `kind` says whether `source` is a bag or a folder. Throws
 * std::runtime_error naming the image when one cannot be read or described, or differs in size from
 * the first, and naming the bag when it cannot be opened.
 */
Traversal readTraversal(const std::string& source, const std::string& topic, const std::string& what,
                        const DescriptorExtractor& extractor,
                        const std::function<void(const cv::Mat& descriptor, Stamp stamp)>& append,
                        SourceKind kind = SourceKind::kByName);

}  // namespace tools
}  // namespace mrs_vpr

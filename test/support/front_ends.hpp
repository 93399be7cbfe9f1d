#pragma once

// Descriptor parameters of each front end, for tests of one front end's own behaviour.

#include "mrs_vpr/parameters.hpp"

namespace mrs_vpr {
namespace testing_support {

/// OpenSeqSLAM's thumbnail, by default its 64 x 32 image with patches of 8.
inline DescriptorParams thumbnailParams(int width = 64, int height = 32, int patch = 8) {
  DescriptorParams params;
  params.type = kThumbnailFrontEnd;
  params.image_width = width;
  params.image_height = height;
  params.patch_size = patch;
  return params;
}

}  // namespace testing_support
}  // namespace mrs_vpr

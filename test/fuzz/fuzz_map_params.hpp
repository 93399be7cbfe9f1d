#pragma once

#include "mrs_vpr/parameters.hpp"

namespace mrs_vpr {

/// The descriptors of the fuzzed maps: 8 x 4 pixels (32-byte descriptors) keep a valid map a few
/// pages long, so that the fuzzer's mutations reach the frames' rows instead of blank pages.
inline DescriptorParams fuzzMapParams() {
  DescriptorParams params;
  params.type = kThumbnailFrontEnd;
  params.image_width = 8;
  params.image_height = 4;
  params.patch_size = 4;
  return params;
}

}  // namespace mrs_vpr

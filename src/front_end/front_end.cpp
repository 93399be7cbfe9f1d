#include "mrs_vpr/front_end/front_end.hpp"

#include "mrs_vpr/front_end/hog_front_end.hpp"
#include "mrs_vpr/front_end/thumbnail_front_end.hpp"

namespace mrs_vpr {

std::unique_ptr<const FrontEnd> makeFrontEnd(const DescriptorParams& params) {
  params.validate();
  if (params.isHog()) return std::make_unique<HogFrontEnd>(params);
  return std::make_unique<ThumbnailFrontEnd>(params);
}

}  // namespace mrs_vpr

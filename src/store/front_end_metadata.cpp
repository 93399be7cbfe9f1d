#include "front_end_metadata.hpp"

#include <cmath>
#include <cstddef>
#include <exception>
#include <iomanip>
#include <limits>
#include <sstream>
#include <type_traits>

namespace mrs_vpr {
namespace {

/// A front-end parameter as the metadata table keeps it: integers as integers, fractions in full.
std::string metadataValue(double value) {
  std::ostringstream text;
  text << std::setprecision(17) << value;
  return text.str();
}

/// `text` as a number of type T, when the whole of it is one (for an integral T, a whole number that T
/// holds: a corrupt map's "1e20" must not overflow the conversion).
template <typename T>
std::optional<T> numberIn(const std::string& text) {
  try {
    std::size_t used = 0;
    const double value = std::stod(text, &used);
    if (used != text.size()) return std::nullopt;
    if constexpr (std::is_integral_v<T>) {
      const bool whole = value == std::floor(value);
      if (!whole || value < std::numeric_limits<T>::min() || value > std::numeric_limits<T>::max()) {
        return std::nullopt;
      }
    }
    return static_cast<T>(value);
  } catch (const std::exception&) {  // empty, or not a number
    return std::nullopt;
  }
}

}  // namespace

std::vector<std::pair<std::string, std::string>> frontEndMetadata(const DescriptorParams& params) {
  std::vector<std::pair<std::string, std::string>> rows = {{"descriptor_type", params.type}};
  if (params.isHog()) {
    rows.insert(rows.end(), {{"hog_window_width", metadataValue(params.hog_window_width)},
                             {"hog_window_height", metadataValue(params.hog_window_height)},
                             {"hog_cell_size", metadataValue(params.hog_cell_size)},
                             {"hog_bins", metadataValue(params.hog_bins)},
                             {"hog_blur", metadataValue(params.hog_blur)}});
  } else {
    rows.insert(rows.end(), {{"image_width", metadataValue(params.image_width)},
                             {"image_height", metadataValue(params.image_height)},
                             {"patch_size", metadataValue(params.patch_size)}});
  }
  return rows;
}


std::optional<DescriptorParams> frontEndOfMetadata(const std::map<std::string, std::string>& stored) {
  const auto value = [&](const std::string& key) {
    const auto found = stored.find(key);
    return found == stored.end() ? std::string() : found->second;
  };
  DescriptorParams params;
  params.type = stored.count("descriptor_type") != 0 ? value("descriptor_type") : kThumbnailFrontEnd;
  bool complete = true;
  const auto read = [&](const std::string& key, auto& field) {
    const auto number = numberIn<std::decay_t<decltype(field)>>(value(key));
    complete = complete && number.has_value();
    if (number) field = *number;
  };
  if (params.type == kHogFrontEnd) {
    read("hog_window_width", params.hog_window_width);
    read("hog_window_height", params.hog_window_height);
    read("hog_cell_size", params.hog_cell_size);
    read("hog_bins", params.hog_bins);
    read("hog_blur", params.hog_blur);
  } else if (params.type == kThumbnailFrontEnd) {
    read("image_width", params.image_width);
    read("image_height", params.image_height);
    read("patch_size", params.patch_size);
  } else {
    complete = false;
  }
  if (!complete) return std::nullopt;
  return params;
}

}  // namespace mrs_vpr

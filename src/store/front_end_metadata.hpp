#pragma once

// How a map database records its front end in its metadata table (key, value), and reads it back.

#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "mrs_vpr/parameters.hpp"

namespace mrs_vpr {

/// The metadata rows that record the front end of `params`: its type and its parameters, integers as
/// integers and fractions in full.
std::vector<std::pair<std::string, std::string>> frontEndMetadata(const DescriptorParams& params);

/// The front end that metadata rows record; none when a value is missing or not a number. Maps
/// written before there was a choice of front end record no type: they hold thumbnails.
std::optional<DescriptorParams> frontEndOfMetadata(const std::map<std::string, std::string>& stored);

}  // namespace mrs_vpr

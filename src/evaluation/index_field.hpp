#pragma once

#include <string>

namespace mrs_vpr {
namespace evaluation_detail {

/// A frame index written in a CSV field: a non-negative decimal integer of at most 9 digits, or -1
/// when `text` is anything else (so that a stray sign, space or exponent is refused, not read).
inline long long parseIndex(const std::string& text) {
  if (text.empty() || text.size() > 9) return -1;
  for (char c : text) {
    if (c < '0' || c > '9') return -1;
  }
  return std::stoll(text);
}

}  // namespace evaluation_detail
}  // namespace mrs_vpr

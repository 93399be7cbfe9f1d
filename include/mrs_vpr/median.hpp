#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace mrs_vpr {

/// The value at position size / 2 in sorted order (the upper median of an even count); reorders
/// `values`, which must not be empty. One pass of nth_element, no sort.
template <typename Value>
Value upperMedian(std::vector<Value>& values) {
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  return *middle;
}

}  // namespace mrs_vpr

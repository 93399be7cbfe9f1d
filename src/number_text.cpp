#include "mrs_vpr/number_text.hpp"

#include <cmath>
#include <sstream>

namespace mrs_vpr {

std::string numberText(double value) {
  if (std::isfinite(value) && value == std::floor(value) && std::fabs(value) < 1e15) {
    return std::to_string(static_cast<long long>(value));
  }
  std::ostringstream out;
  out << value;
  return out.str();
}

}  // namespace mrs_vpr

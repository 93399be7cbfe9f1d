#pragma once

// What the node's warnings about frames and queries share.

#include <string>

namespace mrs_vpr {
namespace node {

constexpr double kWarningPeriod = 5.0;  // [s] between repeated warnings of one kind

inline std::string inQuotes(const std::string& text) { return "'" + text + "'"; }

}  // namespace node
}  // namespace mrs_vpr

#pragma once

// Numbers in messages to users: as a person writes them, not as std::to_string does (0.400000).

#include <string>

namespace mrs_vpr {

/// Whole numbers as integers (1000000, not 1e+06), others as a stream writes them (0.4, 1e-10).
std::string numberText(double value);

}  // namespace mrs_vpr

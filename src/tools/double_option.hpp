#pragma once

// A floating-point command-line option whose default --help prints as a person writes it.

#include <boost/program_options.hpp>

#include "mrs_vpr/number_text.hpp"

namespace mrs_vpr {
namespace tools {

/// An option of `target`, its current value the default, shown as "0.4" rather than boost's
/// "0.40000000000000002".
inline boost::program_options::typed_value<double>* doubleOption(double* target) {
  return boost::program_options::value(target)->default_value(*target, numberText(*target));
}

}  // namespace tools
}  // namespace mrs_vpr

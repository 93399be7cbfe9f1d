#pragma once

#include <stdexcept>
#include <string>

namespace mrs_vpr {
namespace testing_support {

/// The message of the std::invalid_argument that `action` throws ("" when it throws none).
template <typename Action>
std::string invalidArgumentMessage(Action action) {
  try {
    action();
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "";
}

/// The message of the std::runtime_error that `action` throws ("" when it throws none).
template <typename Action>
std::string runtimeErrorMessage(Action action) {
  try {
    action();
  } catch (const std::runtime_error& error) {
    return error.what();
  }
  return "";
}

}  // namespace testing_support
}  // namespace mrs_vpr

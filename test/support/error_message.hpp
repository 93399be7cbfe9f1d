#pragma once

#include <stdexcept>
#include <string>

namespace mrs_vpr {
namespace testing_support {

/// The message of the `Error` that `action` throws ("" when it throws none).
template <typename Error, typename Action>
std::string messageOf(Action action) {
  try {
    action();
  } catch (const Error& error) {
    return error.what();
  }
  return "";
}

/// The message of the std::invalid_argument that `action` throws ("" when it throws none).
template <typename Action>
std::string invalidArgumentMessage(Action action) {
  return messageOf<std::invalid_argument>(action);
}

/// The message of the std::runtime_error that `action` throws ("" when it throws none).
template <typename Action>
std::string runtimeErrorMessage(Action action) {
  return messageOf<std::runtime_error>(action);
}

}  // namespace testing_support
}  // namespace mrs_vpr

#include "plugin_loader.hpp"

#include <dlfcn.h>

#include <stdexcept>

namespace mrs_vpr {
namespace plugins {
namespace {

/// The folder of the library holding this code, where the plugins are built and installed beside it.
std::string ownFolder() {
  static const char anchor = 0;  // Any object of this library: dladdr names the file it was loaded from.
  Dl_info info{};
  if (dladdr(&anchor, &info) == 0 || info.dli_fname == nullptr) return {};
  const std::string path = info.dli_fname;
  const std::size_t slash = path.rfind('/');
  return slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
}

}  // namespace

const void* loadTable(const char* file, const char* entry, const std::string& what) {
  const std::string beside = ownFolder() + file;
  void* handle = dlopen(beside.c_str(), RTLD_NOW | RTLD_LOCAL);
  std::string reason;
  if (handle == nullptr) {
    reason = dlerror();
    handle = dlopen(file, RTLD_NOW | RTLD_LOCAL);
  }
  if (handle == nullptr) throw std::runtime_error("cannot load the " + what + ": " + reason + "; " + dlerror());
  using Entry = const void* (*)();
  const auto function = reinterpret_cast<Entry>(dlsym(handle, entry));
  if (function == nullptr) {
    throw std::runtime_error("cannot load the " + what + ": " + file + " has no " + entry);
  }
  return function();
}

}  // namespace plugins
}  // namespace mrs_vpr

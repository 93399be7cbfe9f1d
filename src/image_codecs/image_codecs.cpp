#include "mrs_vpr/image_codecs.hpp"

#include <dlfcn.h>

#include <stdexcept>

#include "codec_table.hpp"

namespace mrs_vpr {
namespace image_codecs {
namespace {

/// The folder of the library holding this code, where the plugin is built and installed beside it.
std::string ownFolder() {
  static const char anchor = 0;  // Any object of this library: dladdr names the file it was loaded from.
  Dl_info info{};
  if (dladdr(&anchor, &info) == 0 || info.dli_fname == nullptr) return {};
  const std::string path = info.dli_fname;
  const std::size_t slash = path.rfind('/');
  return slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
}

const CodecTable& loadTable() {
  // A function-local static is initialised once, also when several threads read images at once.
  static const CodecTable* const table = [] {
    const std::string beside = ownFolder() + kCodecPluginFile;
    void* handle = dlopen(beside.c_str(), RTLD_NOW | RTLD_LOCAL);
    std::string reason;
    if (handle == nullptr) {
      reason = dlerror();
      // Also where the dynamic loader looks (LD_LIBRARY_PATH, a devel or install space).
      handle = dlopen(kCodecPluginFile, RTLD_NOW | RTLD_LOCAL);
    }
    if (handle == nullptr) {
      throw std::runtime_error(std::string("cannot load the image codecs: ") + reason + "; " + dlerror());
    }
    using Entry = const CodecTable* (*)();
    const auto entry = reinterpret_cast<Entry>(dlsym(handle, kCodecTableSymbol));
    if (entry == nullptr) {
      throw std::runtime_error(std::string("cannot load the image codecs: ") + kCodecPluginFile + " has no " +
                               kCodecTableSymbol);
    }
    return entry();
  }();
  return *table;
}

}  // namespace

cv::Mat read(const std::string& path, int flags) { return loadTable().read(path, flags); }

cv::Mat decode(const cv::Mat& buffer, int flags) { return loadTable().decode(buffer, flags); }

bool write(const std::string& path, const cv::Mat& image, const std::vector<int>& params) {
  return loadTable().write(path, image, params);
}

bool encode(const std::string& extension, const cv::Mat& image, std::vector<std::uint8_t>& buffer,
            const std::vector<int>& params) {
  return loadTable().encode(extension, image, buffer, params);
}

}  // namespace image_codecs
}  // namespace mrs_vpr

#include "mrs_vpr/image_codecs.hpp"

#include <algorithm>

namespace mrs_vpr {
namespace image_codecs {
namespace {

bool isRestart(std::uint8_t marker) { return marker >= 0xD0 && marker <= 0xD7; }

}  // namespace

bool jpegReachesEndOfImage(const std::uint8_t* data, std::size_t size) {
  const std::uint8_t* const end = data + size;
  if (size < 2 || data[0] != 0xFF || data[1] != 0xD8) return false;  // no start of image
  const std::uint8_t* at = data + 2;
  while (at < end) {
    if (*at != 0xFF) return false;  // a segment must follow a segment
    while (at < end && *at == 0xFF) ++at;  // fill bytes
    if (at == end) return false;
    const std::uint8_t marker = *at++;
    if (marker == 0xD9) return true;  // end of image
    if (marker == 0x01 || isRestart(marker)) continue;  // markers without a segment
    if (end - at < 2) return false;
    const int length = (at[0] << 8) | at[1];
    if (length < 2 || end - at < length) return false;
    at += length;  // Segments (an EXIF thumbnail with its own markers among them) are skipped whole.
    if (marker != 0xDA) continue;
    // After a start of scan, entropy-coded data up to the next marker: there 0xFF is followed only by
    // a stuffed 0x00 or a restart marker.
    for (;;) {
      at = std::find(at, end, std::uint8_t{0xFF});
      if (end - at < 2) return false;
      if (at[1] != 0x00 && !isRestart(at[1]) && at[1] != 0xFF) break;
      ++at;
    }
  }
  return false;
}

}  // namespace image_codecs
}  // namespace mrs_vpr

// libjpeg's decoding of a JPEG stream, stopped where it would make up pixels: part of the codec plugin.

#include <csetjmp>
#include <cstdint>
#include <cstdio>  // jpeglib.h needs FILE

#include <jpeglib.h>
#include <jerror.h>  // the message codes of its warnings (after jpeglib.h, which it needs)

#include "strict_jpeg_decoder.hpp"

namespace mrs_vpr {
namespace image_codecs {
namespace {

/// libjpeg's error manager, which reports by a jump back to the decoder instead of exit() (errors) or a
/// line on stderr (warnings).
struct JumpingErrors {
  jpeg_error_mgr manager;  // first: libjpeg sees a pointer to it
  std::jmp_buf back;
  char message[JMSG_LENGTH_MAX];
};

/// What a jump back says.
enum Jump : int { kUndecodable = 1, kMadeUp = 2 };

[[noreturn]] void jumpBack(j_common_ptr info, Jump why) {
  auto* errors = reinterpret_cast<JumpingErrors*>(info->err);
  (*info->err->format_message)(info, errors->message);
  std::longjmp(errors->back, why);
}

[[noreturn]] void jumpBackOnError(j_common_ptr info) { jumpBack(info, kUndecodable); }

/// The warnings after which libjpeg fills what it could not read with made-up coefficients: data
/// missing (a segment or the file ending early, a restart marker lost) or undecodable (a Huffman code;
/// arithmetic coding, which cameras do not use, is left to its own warnings).
bool pixelsMadeUp(int message_code) {
  switch (message_code) {
    case JWRN_HIT_MARKER:
    case JWRN_JPEG_EOF:
    case JWRN_MUST_RESYNC:
    case JWRN_HUFF_BAD_CODE:
      return true;
    default:  // An unknown JFIF revision, stray bytes between segments, unusual scan parameters: whole pixels.
      return false;
  }
}

void jumpBackOnMadeUpPixels(j_common_ptr info, int level) {
  if (level < 0 && pixelsMadeUp(info->err->msg_code)) jumpBack(info, kMadeUp);  // traces (level >= 0) ignored
}

/// One row of libjpeg's CMYK (as Adobe writes it, inverted) to BGR, with OpenCV's arithmetic
/// (icvCvt_CMYK2BGR_8u_C4C3R), so that the pixels are those cv::imdecode gives.
void cmykToBgr(const JSAMPLE* cmyk, JDIMENSION width, JSAMPLE* bgr) {
  for (JDIMENSION x = 0; x < width; ++x, cmyk += 4, bgr += 3) {
    const int k = cmyk[3];
    const auto ink = [k](int value) { return static_cast<JSAMPLE>(k - ((255 - value) * k >> 8)); };
    bgr[0] = ink(cmyk[2]);
    bgr[1] = ink(cmyk[1]);
    bgr[2] = ink(cmyk[0]);
  }
}

}  // namespace

// No object with a destructor lives in this function's frame across setjmp(): longjmp() skips none.
JpegDecoding decodeJpegStrictly(const std::uint8_t* data, std::size_t size, cv::Mat* image, std::string* problem) {
  jpeg_decompress_struct info{};
  JumpingErrors errors{};
  info.err = jpeg_std_error(&errors.manager);
  errors.manager.error_exit = jumpBackOnError;
  errors.manager.emit_message = jumpBackOnMadeUpPixels;
  const int jumped = setjmp(errors.back);
  if (jumped != 0) {
    jpeg_destroy_decompress(&info);
    if (jumped == kUndecodable) return JpegDecoding::kNotHandled;  // OpenCV says why, as it always did
    *problem = errors.message;
    return JpegDecoding::kCorrupt;
  }
  jpeg_create_decompress(&info);
  jpeg_mem_src(&info, data, static_cast<unsigned long>(size));
  jpeg_read_header(&info, TRUE);
  // OpenCV refuses an image of more than 2^30 pixels (CV_IO_MAX_IMAGE_PIXELS) before it allocates it.
  const bool huge = static_cast<std::uint64_t>(info.image_width) * info.image_height > (std::uint64_t{1} << 30);
  if ((info.num_components != 1 && info.num_components != 3 && info.num_components != 4) || huge) {
    jpeg_destroy_decompress(&info);
    return JpegDecoding::kNotHandled;
  }
  // As OpenCV's JPEG decoder gives IMREAD_UNCHANGED: grey stays grey, colour and CMYK become BGR.
  const bool colour = info.num_components != 1;
  const bool cmyk = info.num_components == 4;  // CMYK or YCCK, which libjpeg gives as CMYK
  info.out_color_space = cmyk ? JCS_CMYK : colour ? JCS_EXT_BGR : JCS_GRAYSCALE;
  jpeg_start_decompress(&info);
  // A CMYK row is read here first (from libjpeg's pools, which a jump frees too).
  JSAMPARRAY cmyk_row = cmyk ? (*info.mem->alloc_sarray)(reinterpret_cast<j_common_ptr>(&info), JPOOL_IMAGE,
                                                         info.output_width * 4, 1)
                             : nullptr;
  try {
    image->create(static_cast<int>(info.output_height), static_cast<int>(info.output_width),
                  colour ? CV_8UC3 : CV_8UC1);
  } catch (...) {
    jpeg_destroy_decompress(&info);  // libjpeg's pools, which no jump frees now
    throw;
  }
  while (info.output_scanline < info.output_height) {
    JSAMPROW row = image->ptr<JSAMPLE>(static_cast<int>(info.output_scanline));
    if (cmyk) {
      jpeg_read_scanlines(&info, cmyk_row, 1);
      cmykToBgr(cmyk_row[0], info.output_width, row);
    } else {
      jpeg_read_scanlines(&info, &row, 1);
    }
  }
  jpeg_finish_decompress(&info);
  jpeg_destroy_decompress(&info);
  return JpegDecoding::kDecoded;
}

}  // namespace image_codecs
}  // namespace mrs_vpr

// libjpeg's decoding of a JPEG stream, stopped at its first warning: part of the codec plugin.

#include <csetjmp>
#include <cstdint>
#include <cstdio>  // jpeglib.h needs FILE

#include <jpeglib.h>

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

[[noreturn]] void jumpBack(j_common_ptr info) {
  auto* errors = reinterpret_cast<JumpingErrors*>(info->err);
  (*info->err->format_message)(info, errors->message);
  std::longjmp(errors->back, 1);
}

void jumpBackOnWarning(j_common_ptr info, int level) {
  if (level < 0) jumpBack(info);  // a warning: the data is corrupt; traces (level >= 0) are ignored
}

}  // namespace

// No object with a destructor lives in this function's frame across setjmp(): longjmp() skips none.
JpegDecoding decodeJpegStrictly(const std::uint8_t* data, std::size_t size, cv::Mat* image, std::string* problem) {
  jpeg_decompress_struct info{};
  JumpingErrors errors{};
  info.err = jpeg_std_error(&errors.manager);
  errors.manager.error_exit = jumpBack;
  errors.manager.emit_message = jumpBackOnWarning;
  if (setjmp(errors.back) != 0) {
    jpeg_destroy_decompress(&info);
    *problem = errors.message;
    return JpegDecoding::kCorrupt;
  }
  jpeg_create_decompress(&info);
  jpeg_mem_src(&info, data, static_cast<unsigned long>(size));
  jpeg_read_header(&info, TRUE);
  // OpenCV refuses an image of more than 2^30 pixels (CV_IO_MAX_IMAGE_PIXELS) before it allocates it.
  const bool huge = static_cast<std::uint64_t>(info.image_width) * info.image_height > (std::uint64_t{1} << 30);
  if ((info.num_components != 1 && info.num_components != 3) || huge) {
    jpeg_destroy_decompress(&info);
    return JpegDecoding::kNotHandled;
  }
  // As OpenCV's JPEG decoder gives IMREAD_UNCHANGED: grey stays grey, colour becomes BGR.
  const bool colour = info.num_components == 3;
  info.out_color_space = colour ? JCS_EXT_BGR : JCS_GRAYSCALE;
  jpeg_start_decompress(&info);
  image->create(static_cast<int>(info.output_height), static_cast<int>(info.output_width), colour ? CV_8UC3 : CV_8UC1);
  while (info.output_scanline < info.output_height) {
    JSAMPROW row = image->ptr<JSAMPLE>(static_cast<int>(info.output_scanline));
    jpeg_read_scanlines(&info, &row, 1);
  }
  jpeg_finish_decompress(&info);
  jpeg_destroy_decompress(&info);
  return JpegDecoding::kDecoded;
}

}  // namespace image_codecs
}  // namespace mrs_vpr

// The only code linked with libopencv_imgcodecs (and libjpeg): loaded at run time by image_codecs.cpp.
#include <opencv2/imgcodecs.hpp>

#include "codec_table.hpp"

extern "C" const mrs_vpr::image_codecs::CodecTable* mrs_vpr_opencv_codec_table_v2() {
  // imdecode is overloaded (with and without an output matrix): the cast picks the one in the table.
  static const mrs_vpr::image_codecs::CodecTable table{
      &cv::imread, static_cast<cv::Mat (*)(cv::InputArray, int)>(&cv::imdecode), &cv::imwrite, &cv::imencode,
      &mrs_vpr::image_codecs::decodeJpegStrictly};
  return &table;
}

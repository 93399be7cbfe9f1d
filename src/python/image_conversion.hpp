#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "mrs_vpr/descriptor.hpp"
#include "mrs_vpr/descriptor_sequence.hpp"
#include "mrs_vpr/place_recognizer.hpp"
#include "mrs_vpr/synthetic_route.hpp"

namespace mrs_vpr {
namespace python {

namespace py = pybind11;

/// A NumPy image and the cv::Mat over its memory; `array` keeps that memory alive.
struct Image {
  py::array array;
  cv::Mat mat;
};

/// An H x W or H x W x C NumPy array as a cv::Mat, without a copy unless OpenCV cannot address it as
/// it lies (negative or odd strides). Which types and channel counts are supported is the core's to
/// say: only what OpenCV cannot represent at all is refused here.
Image imageFrom(const py::handle& object);

/// The images of a sequence (a list, or an array stacked along its first axis), oldest first.
std::vector<Image> imagesFrom(const py::handle& images, const std::string& what);

/// The cv::Mat headers of `images` (no copies).
std::vector<cv::Mat> matsOf(const std::vector<Image>& images);

/// "bgr" or "rgb"; anything else is an error that names both.
ChannelOrder channelOrder(const std::string& name);

/// A descriptor row as a one-dimensional uint8 array (a copy).
py::array_t<std::uint8_t> arrayOf(const cv::Mat& descriptor);

/// The generated route's frames as one N x H x W x 3 uint8 array (a copy).
py::array_t<std::uint8_t> stackOf(const std::vector<cv::Mat>& frames, const SyntheticRouteParams& params);

/// Every image's descriptor, in order; a bad image is named by its position in `what`.
DescriptorSequence describeAll(const PlaceRecognizer& recognizer, const std::vector<Image>& images, ChannelOrder order,
                               const std::string& what);

}  // namespace python
}  // namespace mrs_vpr

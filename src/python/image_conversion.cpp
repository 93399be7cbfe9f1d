// Images from Python: NumPy arrays as cv::Mat headers over their memory.

#include "image_conversion.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

namespace mrs_vpr {
namespace python {
namespace {

/// The OpenCV depth of a NumPy dtype, or -1 when OpenCV has none (int64, bool, complex, object...).
int depthOf(const py::dtype& dtype) {
  const char kind = dtype.kind();
  const auto size = dtype.itemsize();
  // The depths the front ends take; any other is refused here in NumPy's words, not OpenCV's.
  if (kind == 'u') return size == 1 ? CV_8U : size == 2 ? CV_16U : -1;
  return -1;
}

std::string shapeText(const py::array& array) { return py::repr(py::tuple(array.attr("shape"))).cast<std::string>(); }

/// Whether OpenCV can address the array's pixels as they lie: pixels and channels packed, rows any
/// whole number of elements apart, elements aligned.
bool opencvLayout(const py::array& array) {
  const auto item = array.itemsize();
  const auto channels = array.ndim() == 3 ? array.shape(2) : 1;
  if (array.strides(1) != channels * item || (array.ndim() == 3 && array.strides(2) != item)) return false;
  if (array.strides(0) < array.shape(1) * channels * item || array.strides(0) % item != 0) return false;
  return reinterpret_cast<std::uintptr_t>(array.data()) % static_cast<std::uintptr_t>(item) == 0;
}

}  // namespace

Image imageFrom(const py::handle& object) {
  if (!py::isinstance<py::array>(object)) {
    throw std::invalid_argument("an image must be a NumPy array, got " +
                                py::str(py::type::handle_of(object).attr("__name__")).cast<std::string>());
  }
  py::array array = py::reinterpret_borrow<py::array>(object);
  if (array.ndim() != 2 && array.ndim() != 3) {
    throw std::invalid_argument("an image must be H x W (grey) or H x W x C (BGR, BGRA), got an array of " +
                                std::to_string(array.ndim()) + " dimensions, shape " + shapeText(array));
  }
  const int depth = depthOf(array.dtype());
  if (depth < 0) {
    // Such as matplotlib's imread gives for a PNG.
    const std::string floats = array.dtype().kind() == 'f'
                                   ? "; scale an image of floats in 0..1 first: (image * 255).round().astype(np.uint8)"
                                   : "";
    throw std::invalid_argument("unsupported image dtype " + py::str(array.dtype()).cast<std::string>() +
                                " (supported: uint8 or uint16 grey, BGR or BGRA)" + floats);
  }
  if (array.size() == 0) throw std::invalid_argument("image is empty: an array of shape " + shapeText(array));
  const auto channels = array.ndim() == 3 ? array.shape(2) : 1;
  if (channels < 1 || channels > CV_CN_MAX || array.shape(0) > INT_MAX || array.shape(1) > INT_MAX) {
    throw std::invalid_argument("unsupported image shape " + shapeText(array));
  }
  if (!array.dtype().attr("isnative").cast<bool>()) {
    array = array.attr("astype")(array.dtype().attr("newbyteorder")("="));
  }
  if (array.size() > 0 && !opencvLayout(array)) array = array.attr("copy")();
  Image image{array, {}};
  if (array.size() == 0) return image;  // The core says what is wrong with an empty image.
  image.mat = cv::Mat(static_cast<int>(array.shape(0)), static_cast<int>(array.shape(1)),
                      CV_MAKETYPE(depth, static_cast<int>(channels)), const_cast<void*>(array.data()),
                      static_cast<std::size_t>(array.strides(0)));
  return image;
}

std::vector<Image> imagesFrom(const py::handle& images, const std::string& what) {
  if (py::isinstance<py::array>(images)) {
    // One image is not a sequence of them. An H x W x 3 array would otherwise pass as H grey images
    // of W x 3 pixels: a stack of such narrow grey images is a list's job.
    const auto array = py::reinterpret_borrow<py::array>(images);
    const bool colour_image = array.ndim() == 3 && (array.shape(2) == 3 || array.shape(2) == 4);
    if (array.ndim() < 3 || colour_image) {
      throw std::invalid_argument(what + " must be a sequence of images (a list, or an N x H x W or N x H x W x C "
                                  "array), got one array of shape " + shapeText(array));
    }
  }
  if (PyUnicode_Check(images.ptr()) || !PySequence_Check(images.ptr())) {
    throw std::invalid_argument(what + " must be a sequence of images, got " +
                                py::str(py::type::handle_of(images).attr("__name__")).cast<std::string>());
  }
  std::vector<Image> result;
  const py::sequence sequence = py::reinterpret_borrow<py::sequence>(images);
  result.reserve(sequence.size());
  for (std::size_t i = 0; i < sequence.size(); ++i) {
    try {
      result.push_back(imageFrom(sequence[i]));
    } catch (const std::invalid_argument& error) {
      throw std::invalid_argument("image " + std::to_string(i) + " of " + what + ": " + error.what());
    }
  }
  return result;
}

std::vector<cv::Mat> matsOf(const std::vector<Image>& images) {
  std::vector<cv::Mat> mats;
  mats.reserve(images.size());
  for (const Image& image : images) mats.push_back(image.mat);
  return mats;
}

ChannelOrder channelOrder(const std::string& name) {
  if (name == "bgr") return ChannelOrder::kBgr;
  if (name == "rgb") return ChannelOrder::kRgb;
  throw std::invalid_argument("channel_order must be 'bgr' or 'rgb', got '" + name + "'");
}

py::array_t<std::uint8_t> arrayOf(const cv::Mat& descriptor) {
  const cv::Mat row = descriptor.isContinuous() ? descriptor : descriptor.clone();
  py::array_t<std::uint8_t> array(static_cast<py::ssize_t>(row.total()));
  std::copy(row.data, row.data + row.total(), array.mutable_data());
  return array;
}

py::array_t<std::uint8_t> stackOf(const std::vector<cv::Mat>& frames, const SyntheticRouteParams& params) {
  py::array_t<std::uint8_t> stack({static_cast<int>(frames.size()), params.image_height, params.image_width, 3});
  const std::size_t frame_bytes = static_cast<std::size_t>(params.image_height) * params.image_width * 3;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    cv::Mat view(frames[i].rows, frames[i].cols, frames[i].type(), stack.mutable_data() + i * frame_bytes);
    frames[i].copyTo(view);
  }
  return stack;
}

DescriptorSequence describeAll(const PlaceRecognizer& recognizer, const std::vector<Image>& images, ChannelOrder order,
                               const std::string& what) {
  DescriptorSequence descriptors(recognizer.extractor().size());
  descriptors.reserve(static_cast<int>(images.size()));
  for (std::size_t i = 0; i < images.size(); ++i) {
    try {
      descriptors.append(recognizer.describe(images[i].mat, order));
    } catch (const std::invalid_argument& error) {
      throw std::invalid_argument("image " + std::to_string(i) + " of " + what + ": " + error.what());
    }
  }
  return descriptors;
}

}  // namespace python
}  // namespace mrs_vpr

#include "mrs_vpr/evaluation/image_folder.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <utility>
#include <vector>

#include "index_field.hpp"
#include "mrs_vpr/image_codecs.hpp"

namespace mrs_vpr {

namespace fs = std::filesystem;

namespace {

/// The extension of `path` in lower case, with its dot.
std::string extensionOf(const fs::path& path) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return extension;
}

/// Named as an image. GIF is among them although OpenCV 4.6 reads none: such a file is refused by name
/// rather than left out, which would shift the frames after it.
const char* const kImageExtensions[] = {".png", ".jpg", ".jpeg", ".bmp", ".tif", ".tiff", ".pgm",
                                        ".ppm", ".pnm", ".pbm", ".webp", ".jp2", ".gif"};

/// "png, jpg, ...", for a message.
std::string imageExtensionsText() {
  std::string text;
  for (const char* extension : kImageExtensions) text += (text.empty() ? "" : ", ") + std::string(extension + 1);
  return text;
}

bool isImageFile(const fs::path& path) {
  const std::string extension = extensionOf(path);
  return std::any_of(std::begin(kImageExtensions), std::end(kImageExtensions),
                     [&extension](const char* known) { return extension == known; });
}

/// The digits of `text` from `at` on, without leading zeros, and where they end.
std::pair<std::string_view, std::size_t> numberAt(std::string_view text, std::size_t at) {
  std::size_t end = at;
  while (end < text.size() && std::isdigit(static_cast<unsigned char>(text[end]))) ++end;
  std::size_t first = at;
  while (first + 1 < end && text[first] == '0') ++first;
  return {text.substr(first, end - first), end};
}

/// Whether the digits at `at` are a decimal fraction: they follow a point that follows a digit.
bool isFraction(std::string_view text, std::size_t at) {
  return at >= 2 && text[at - 1] == '.' && std::isdigit(static_cast<unsigned char>(text[at - 2])) != 0;
}

/// File-name order in which a run of digits counts as its number, so that frame2.png comes before
/// frame10.png as a camera wrote them (zero-padded names sort as they do byte by byte), and, with
/// `fractions`, the digits after a decimal point as a fraction, so that 1614000000.05.png comes before
/// 1614000000.1.png (stamps written as seconds); names that differ only by leading zeros fall back to
/// byte order.
bool namedBefore(std::string_view a, std::string_view b, bool fractions = true) {
  std::size_t i = 0;
  std::size_t j = 0;
  while (i < a.size() && j < b.size()) {
    const bool digit_a = std::isdigit(static_cast<unsigned char>(a[i])) != 0;
    const bool digit_b = std::isdigit(static_cast<unsigned char>(b[j])) != 0;
    if (digit_a && digit_b) {
      const auto [number_a, end_a] = numberAt(a, i);
      const auto [number_b, end_b] = numberAt(b, j);
      if (fractions && isFraction(a, i) && isFraction(b, j)) {
        // Digit by digit, leading zeros included: the order of the fractions' values.
        const std::string_view digits_a = a.substr(i, end_a - i);
        const std::string_view digits_b = b.substr(j, end_b - j);
        if (digits_a != digits_b) return digits_a < digits_b;
      } else {
        if (number_a.size() != number_b.size()) return number_a.size() < number_b.size();
        if (number_a != number_b) return number_a < number_b;
      }
      i = end_a;
      j = end_b;
    } else {
      if (a[i] != b[j]) return static_cast<unsigned char>(a[i]) < static_cast<unsigned char>(b[j]);
      ++i;
      ++j;
    }
  }
  if (a.size() - i != b.size() - j) return a.size() - i < b.size() - j;
  return a < b;
}

/// The first few of `names`, for a message.
std::string namesOf(const std::vector<std::string>& names) {
  constexpr std::size_t kNamed = 5;
  std::string text;
  for (std::size_t i = 0; i < std::min(kNamed, names.size()); ++i) text += (i == 0 ? "" : ", ") + names[i];
  return names.size() > kNamed ? text + " and " + std::to_string(names.size() - kNamed) + " more" : text;
}

std::string sizeText(const cv::Mat& image) {
  return std::to_string(image.cols) + "x" + std::to_string(image.rows);
}

std::string trim(const std::string& text) {
  const auto first = text.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) return {};
  const auto last = text.find_last_not_of(" \t\r\n");
  return text.substr(first, last - first + 1);
}

/// Why OpenCV read no image from `path`, for the error message.
std::string whyUnreadable(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  if (!file) return std::strerror(errno);
  std::error_code error;
  if (fs::file_size(path, error) == 0 && !error) return "the file is empty";
  return "no image decoder of OpenCV reads it (a corrupt file, or a format this build of OpenCV lacks)";
}

using evaluation_detail::parseIndex;

}  // namespace

std::vector<std::string> listImageFiles(const std::string& folder, std::vector<std::string>* left_out) {
  std::error_code error;
  if (!fs::exists(folder, error)) throw std::runtime_error("image folder '" + folder + "' does not exist");
  if (!fs::is_directory(folder, error)) throw std::runtime_error("'" + folder + "' is not a folder");
  std::vector<std::string> files;
  std::vector<std::string> others;
  std::vector<std::string> folders;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder)) {
    const bool named_as_image = isImageFile(entry.path());
    if (!named_as_image && entry.is_directory(error)) {
      folders.push_back(entry.path().filename().string());
      continue;
    }
    if (!named_as_image) {
      others.push_back(entry.path().filename().string());
      continue;
    }
    if (entry.is_directory(error)) {
      throw std::runtime_error("image '" + entry.path().string() + "' is a folder");
    }
    // An image that cannot be read is an error, not left out: every later frame would be numbered one
    // too low, and the evaluation's ground truth would be wrong without a word.
    if (entry.is_symlink(error) && !entry.exists(error)) {
      throw std::runtime_error("image '" + entry.path().string() + "' is a broken symbolic link (to '" +
                               fs::read_symlink(entry.path(), error).string() + "')");
    }
    if (!entry.is_regular_file(error)) {
      throw std::runtime_error("image '" + entry.path().string() + "' is not a regular file");
    }
    files.push_back(entry.path().string());
  }
  std::sort(others.begin(), others.end());
  if (files.empty()) {
    // Named, so that a folder of images of another extension, or of folders of images, is told apart.
    std::string message = "image folder '" + folder + "' holds no image files";
    if (!others.empty()) {
      message += " (" + namesOf(others) +
                 (others.size() == 1 ? " is not named as an image: " : " are not named as images: ") +
                 imageExtensionsText() + ")";
    }
    if (!folders.empty()) {
      std::sort(folders.begin(), folders.end());
      const std::string which = folders.size() == 1 ? "the folder " : "the folders ";
      message += (others.empty() ? ", only " : ", and ") + which + namesOf(folders);
    }
    throw std::runtime_error(message);
  }
  // Full paths in one folder: their names decide.
  std::sort(files.begin(), files.end(), [](const std::string& a, const std::string& b) { return namedBefore(a, b); });
  if (left_out) *left_out = std::move(others);
  return files;
}

std::string fractionOrderNote(const std::vector<std::string>& files) {
  // Two orders that differ invert a pair of neighbours in one of them.
  for (std::size_t i = 0; i + 1 < files.size(); ++i) {
    if (namedBefore(files[i + 1], files[i], false)) {
      const std::string first = fs::path(files[i]).filename().string();
      const std::string second = fs::path(files[i + 1]).filename().string();
      return "read '" + first + "' before '" + second + "', the digits after a point as a decimal fraction (stamps " +
             "in seconds); if they count frames, write them with as many digits each (zeros in front)";
    }
  }
  return "";
}

std::string leftOutNote(const std::string& folder, const std::vector<std::string>& left_out) {
  if (left_out.empty()) return "";
  return "left out " + std::to_string(left_out.size()) + (left_out.size() == 1 ? " file" : " files") + " of '" +
         folder + "' not named as an image (" + namesOf(left_out) + ")";
}

cv::Mat loadImage(const std::string& path) {
  if (extensionOf(path) != ".jpg" && extensionOf(path) != ".jpeg") {
    cv::Mat image = image_codecs::read(path, cv::IMREAD_UNCHANGED);
    if (image.empty()) throw std::runtime_error("cannot read image '" + path + "': " + whyUnreadable(path));
    return image;
  }
  // libjpeg reads a JPEG file cut short or corrupt with a warning only, making up the pixels it cannot read.
  std::ifstream file(path, std::ios::binary);
  if (!file) throw std::runtime_error("cannot read image '" + path + "': " + whyUnreadable(path));
  const std::vector<std::uint8_t> bytes{std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
  if (bytes.empty()) throw std::runtime_error("cannot read image '" + path + "': " + whyUnreadable(path));
  if (!image_codecs::jpegReachesEndOfImage(bytes.data(), bytes.size())) {
    throw std::runtime_error("image '" + path + "' is a truncated JPEG file (" + std::to_string(bytes.size()) +
                             " bytes, no end-of-image marker)");
  }
  cv::Mat image;
  try {
    image = image_codecs::decodeStrictly(bytes.data(), bytes.size());
  } catch (const image_codecs::CorruptJpeg& error) {
    throw std::runtime_error("image '" + path + "' is a corrupt JPEG file, which libjpeg cannot decode without " +
                             "making up pixels: " + error.what());
  }
  if (image.empty()) throw std::runtime_error("cannot read image '" + path + "': " + whyUnreadable(path));
  return image;
}

void forEachImage(const std::string& folder,
                  const std::function<void(int index, const std::string& path, const cv::Mat& image)>& visit) {
  const std::vector<std::string> files = listImageFiles(folder);
  cv::Size first_size;
  for (std::size_t i = 0; i < files.size(); ++i) {
    const cv::Mat image = loadImage(files[i]);
    if (i == 0) {
      first_size = image.size();
    } else if (image.size() != first_size) {
      throw std::runtime_error("image '" + files[i] + "' is " + sizeText(image) + " but '" + files[0] + "' is " +
                               std::to_string(first_size.width) + "x" + std::to_string(first_size.height) +
                               ": all images of a folder must have one size");
    }
    visit(static_cast<int>(i), files[i], image);
  }
}

std::vector<cv::Mat> loadImageFolder(const std::string& folder) {
  std::vector<cv::Mat> images;
  forEachImage(folder, [&images](int, const std::string&, const cv::Mat& image) { images.push_back(image); });
  return images;
}

GroundTruth readGroundTruthCsv(const std::string& path) {
  // An ifstream opens a folder and reads nothing from it: it would be "empty".
  if (std::filesystem::is_directory(path)) {
    throw std::invalid_argument("ground-truth file '" + path + "' is a folder (give the CSV file)");
  }
  std::ifstream file(path);
  if (!file) throw std::runtime_error("cannot open ground-truth file '" + path + "'");
  const auto fail = [&path](int line, const std::string& what) {
    throw std::invalid_argument(path + ":" + std::to_string(line) + ": " + what);
  };

  GroundTruth truth;
  std::string text;
  int line = 0;
  bool header_seen = false;
  while (std::getline(file, text)) {
    ++line;
    text = trim(text);
    if (text.empty()) continue;
    if (!header_seen) {
      // A UTF-8 byte-order mark, as spreadsheet programs write, is not part of the header.
      if (text.rfind("\xEF\xBB\xBF", 0) == 0) text = text.substr(3);
      if (text != "query_index,matching_ref_indices") {
        fail(line, "expected the header 'query_index,matching_ref_indices', got '" + text + "'");
      }
      header_seen = true;
      continue;
    }
    const auto comma = text.find(',');
    if (comma == std::string::npos) fail(line, "expected 'query_index,ref ref ...', got '" + text + "'");
    const std::string query_text = trim(text.substr(0, comma));
    const long long query = parseIndex(query_text);
    if (query < 0) fail(line, "query index '" + query_text + "' is not a non-negative integer");
    if (truth.count(static_cast<int>(query)) > 0) {
      fail(line, "query index " + query_text + " is listed twice");
    }
    std::vector<int> matches;
    std::istringstream references(text.substr(comma + 1));
    std::string reference_text;
    while (references >> reference_text) {
      const long long reference = parseIndex(reference_text);
      if (reference < 0) fail(line, "reference index '" + reference_text + "' is not a non-negative integer");
      matches.push_back(static_cast<int>(reference));
    }
    truth.emplace(static_cast<int>(query), std::move(matches));
  }
  if (!header_seen) fail(line, "the file is empty (expected the header 'query_index,matching_ref_indices')");
  return truth;
}

}  // namespace mrs_vpr

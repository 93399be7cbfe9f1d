#include "mrs_vpr/evaluation/drive_file.hpp"

#include <fstream>
#include <stdexcept>
#include <string>

#include "index_field.hpp"

namespace mrs_vpr {
namespace {

constexpr const char* kHeader = "drive_frame,route_frame,kind";

using evaluation_detail::parseIndex;

}  // namespace

void writeDriveFile(const std::string& path, const std::vector<DriveFrame>& frames, int first_route_frame) {
  std::ofstream file(path);
  file << kHeader << "\n";
  for (std::size_t i = 0; i < frames.size(); ++i) {
    file << i << "," << frames[i].route_frame + first_route_frame << "," << toString(frames[i].kind) << "\n";
  }
  if (!file) throw std::runtime_error("cannot write '" + path + "'");
}

std::vector<DriveFrame> readDriveFile(const std::string& path) {
  std::ifstream file(path);
  if (!file) throw std::runtime_error("cannot open drive file '" + path + "'");
  const auto fail = [&path](int line, const std::string& what) {
    throw std::invalid_argument(path + ":" + std::to_string(line) + ": " + what);
  };
  std::vector<DriveFrame> frames;
  std::string text;
  int line = 0;
  bool header_seen = false;
  while (std::getline(file, text)) {
    ++line;
    if (!text.empty() && text.back() == '\r') text.pop_back();
    if (text.empty()) continue;
    if (!header_seen) {
      if (text != kHeader) fail(line, "expected the header '" + std::string(kHeader) + "', got '" + text + "'");
      header_seen = true;
      continue;
    }
    const auto first = text.find(',');
    const auto second = first == std::string::npos ? first : text.find(',', first + 1);
    if (second == std::string::npos) fail(line, "expected 'drive_frame,route_frame,kind', got '" + text + "'");
    const long long index = parseIndex(text.substr(0, first));
    if (index != static_cast<long long>(frames.size())) {
      fail(line, "expected drive frame " + std::to_string(frames.size()) + ", got '" + text.substr(0, first) + "'");
    }
    const std::string route_text = text.substr(first + 1, second - first - 1);
    const long long route_frame = parseIndex(route_text);
    if (route_frame < 0) fail(line, "route frame '" + route_text + "' is not a non-negative integer");
    DriveFrame frame;
    frame.route_frame = static_cast<int>(route_frame);
    try {
      frame.kind = parseDriveFrameKind(text.substr(second + 1));
    } catch (const std::invalid_argument& error) {
      fail(line, error.what());
    }
    frames.push_back(frame);
  }
  if (!header_seen) fail(line, "the file is empty (expected the header '" + std::string(kHeader) + "')");
  return frames;
}

}  // namespace mrs_vpr

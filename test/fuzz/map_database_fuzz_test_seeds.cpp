// Writes the seed corpus of the map loader's fuzzer into a folder: a valid map written by the store,
// a truncated copy, an empty file and a map of other descriptors.
// Generated at run time so that the seeds always follow the store's current format.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "fuzz_map_params.hpp"
#include "mrs_vpr/store/map_database.hpp"

namespace fs = std::filesystem;

namespace {

void writeMap(const fs::path& file, const mrs_vpr::DescriptorParams& params, int frames) {
  fs::remove(file);
  mrs_vpr::MapDatabase database(file.string(), params);
  std::vector<mrs_vpr::StoredFrame> batch(static_cast<std::size_t>(frames));
  cv::RNG rng(7);
  for (int i = 0; i < frames; ++i) {
    batch[i].descriptor = cv::Mat(1, params.image_width * params.image_height, CV_8UC1);
    rng.fill(batch[i].descriptor, cv::RNG::UNIFORM, 0, 256);
    batch[i].stamp = mrs_vpr::Stamp::fromSecondsAndNanoseconds(10 + i, 0);
    batch[i].frame_id = i % 2 == 0 ? "camera" : "";
    batch[i].sequence = i;
  }
  database.append(batch);
}  // Closing checkpoints the WAL: the map is one self-contained file.

std::string contents(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void writeFile(const fs::path& file, const std::string& bytes) {
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out << bytes;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: map_database_fuzz_test_seeds FOLDER\n";
    return 2;
  }
  try {
    const fs::path folder = argv[1];
    fs::create_directories(folder);
    const fs::path scratch = folder / "scratch.db";
    writeMap(scratch, mrs_vpr::fuzzMapParams(), 6);
    const std::string valid = contents(scratch);
    writeFile(folder / "valid_map.db", valid);
    writeFile(folder / "truncated_map.db", valid.substr(0, valid.size() / 2));
    writeFile(folder / "empty.db", "");
    mrs_vpr::DescriptorParams other = mrs_vpr::fuzzMapParams();
    other.image_width = 16;
    writeMap(scratch, other, 1);
    writeFile(folder / "other_descriptors.db", contents(scratch));
    fs::remove(scratch);
    std::cout << "Seeds in " << folder.string() << " (valid map of " << valid.size() << " bytes)\n";
  } catch (const std::exception& error) {
    std::cerr << "map_database_fuzz_test_seeds: " << error.what() << "\n";
    return 1;
  }
  return 0;
}

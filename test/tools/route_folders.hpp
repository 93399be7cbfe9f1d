#pragma once

// The tools tests' input: a generated route written as image folders, with its
// ground truth.

#include <filesystem>
#include <fstream>
#include <iomanip>
#include <opencv2/imgcodecs.hpp>
#include <sstream>
#include <vector>

#include "mrs_vpr/synthetic_route.hpp"

namespace mrs_vpr {
namespace testing_support {

/// Writes `frames` into `folder` as 00000.png, 00001.png, ...
inline void writeImageFolder(const std::filesystem::path& folder, const std::vector<cv::Mat>& frames) {
  std::filesystem::create_directories(folder);
  for (std::size_t i = 0; i < frames.size(); ++i) {
    std::ostringstream name;
    name << std::setw(5) << std::setfill('0') << i << ".png";
    cv::imwrite((folder / name.str()).string(), frames[i]);
  }
}

/// The route writeRouteFolders writes: 150 reference and 100 query frames.
inline const SyntheticRoute& routeOfFolders() {
  static const SyntheticRoute route = [] {
    SyntheticRouteParams params;
    params.reference_frames = 150;
    params.query_frames = 100;
    params.start_place = 20.0;
    return generateSyntheticRoute(params);
  }();
  return route;
}

/// The route in `root`/reference and `root`/query, and its ground truth in `root`/truth.csv
/// (mrs_vpr_eval's --ground-truth format).
inline void writeRouteFolders(const std::filesystem::path& root) {
  const SyntheticRoute& route = routeOfFolders();
  writeImageFolder(root / "reference", route.reference);
  writeImageFolder(root / "query", route.query);
  std::ofstream truth(root / "truth.csv");
  truth << "query_index,matching_ref_indices\n";
  for (std::size_t i = 0; i < route.query_to_reference.size(); ++i) {
    truth << i << "," << route.query_to_reference[i] << "\n";
  }
}

}  // namespace testing_support
}  // namespace mrs_vpr

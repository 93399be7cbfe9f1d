// The README's example: map one traversal (a folder of images), then find where the last frames of
// another traversal lie in it. Links mrs_vpr's core alone.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include <opencv2/core/utility.hpp>
#include <opencv2/imgcodecs.hpp>

#include "mrs_vpr/place_recognizer.hpp"

int main(int argc, char** argv) try {
  if (argc < 3) {
    std::cerr << "usage: mrs_vpr_downstream REFERENCE_DIR QUERY_DIR [FRAMES]\n";
    return 2;
  }
  mrs_vpr::PlaceRecognizer recognizer;  // The documented defaults.
  std::vector<cv::String> files;
  cv::glob(argv[1], files);  // File-name order.
  for (std::size_t i = 0; i < files.size(); ++i) {
    // Frame i at i s. A frame whose view has not changed since the last one kept is not kept.
    recognizer.addFrame(cv::imread(files[i]), mrs_vpr::Stamp::fromSeconds(static_cast<double>(i)));
  }
  cv::glob(argv[2], files);
  const std::size_t frames = argc > 3 ? std::stoul(argv[3]) : 50;
  std::vector<cv::Mat> test;
  for (std::size_t i = files.size() - std::min(frames, files.size()); i < files.size(); ++i) {
    test.push_back(cv::imread(files[i]));
  }
  const mrs_vpr::PlaceAnswer answer = recognizer.match(test);
  // The answer's stamp names the reference image (its map index counts only the frames kept).
  const long reference = answer.match.reference_index < 0 ? -1 : std::lround(answer.reference_stamp.seconds());
  // The answer localises one of the test images: the middle keyframe by default.
  const std::size_t localised = files.size() - test.size() + static_cast<std::size_t>(answer.localised_row);
  std::cout << "query frame " << localised << " is reference frame " << reference << ", confidence "
            << answer.match.confidence << (answer.match.accepted ? ", accepted\n" : ", not accepted\n");
  return 0;
} catch (const std::exception& error) {
  std::cerr << "mrs_vpr_downstream: " << error.what() << "\n";
  return 1;
}

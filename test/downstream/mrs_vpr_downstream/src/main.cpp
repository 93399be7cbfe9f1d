// Uses the core alone: describes a synthetic route, matches a stretch of it, prints the answer.
#include <iostream>

#include <opencv2/core.hpp>

#include "mrs_vpr/descriptor.hpp"
#include "mrs_vpr/sequence_matcher.hpp"

int main() {
  mrs_vpr::Parameters params;
  const mrs_vpr::DescriptorExtractor extractor(params.descriptor);
  mrs_vpr::DescriptorSequence reference(extractor.size());
  mrs_vpr::DescriptorSequence query(extractor.size());
  cv::RNG rng(7);
  for (int frame = 0; frame < 60; ++frame) {
    cv::Mat image(96, 128, CV_8UC3);
    rng.fill(image, cv::RNG::UNIFORM, 0, 256);
    reference.append(extractor.compute(image));
    if (frame >= 20 && frame < 30) query.append(extractor.compute(image));
  }
  const auto matcher = mrs_vpr::makeMatcher("seqslam", params);
  const mrs_vpr::Match match = matcher->match(reference.view(), query.view());
  std::cout << "reference_index " << match.reference_index << " accepted " << match.accepted << "\n";
  return match.reference_index == 29 ? 0 : 1;
}

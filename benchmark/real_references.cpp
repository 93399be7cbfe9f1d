#include "real_references.hpp"

#include "mrs_vpr/evaluation/image_folder.hpp"
#include "mrs_vpr/evaluation/progress_line.hpp"

namespace mrs_vpr {
namespace benchmark {
namespace {

cv::Mat mirrored(const cv::Mat& image) {
  cv::Mat flipped;
  cv::flip(image, flipped, 1);
  return flipped;
}

/// Appends frames [begin, end) of `frames` (optionally mirrored, optionally backwards), as the true
/// places of their route frames or as distractors.
void appendFrames(Reference& reference, const DescriptorExtractor& extractor, const std::vector<cv::Mat>& frames,
                  int begin, int end, bool mirror, bool backwards, bool true_place, ProgressLine& progress) {
  for (int i = 0; i < end - begin; ++i) {
    const int frame = backwards ? end - 1 - i : begin + i;
    const cv::Mat& image = frames[static_cast<std::size_t>(frame)];
    reference.descriptors.append(extractor.compute(mirror ? mirrored(image) : image));
    reference.route_frame.push_back(true_place ? frame : -1);
    progress.update(static_cast<long long>(reference.route_frame.size()));
  }
}

}  // namespace

RealFrames loadRealFrames(const std::string& data) {
  RealFrames frames;
  frames.summer = loadImageFolder(data + "/nordland/summer");
  frames.winter = loadImageFolder(data + "/nordland/winter");
  frames.corridor = loadImageFolder(data + "/corridor/ref");
  for (const cv::Mat& image : loadImageFolder(data + "/corridor/query")) frames.corridor.push_back(image);
  return frames;
}

Reference buildReference(const RealFrames& frames, const DescriptorExtractor& extractor, int begin, int end,
                         bool distractors, const std::string& name) {
  Reference reference{name, DescriptorSequence(extractor.size()), {}};
  const int corridor = static_cast<int>(frames.corridor.size());
  ProgressLine progress =
      ProgressLine::onStderr("reference " + name, "frames", distractors ? 5LL * (end - begin) + corridor : end - begin);
  appendFrames(reference, extractor, frames.summer, begin, end, false, false, true, progress);
  if (distractors) {
    appendFrames(reference, extractor, frames.summer, begin, end, true, false, false, progress);
    appendFrames(reference, extractor, frames.winter, begin, end, true, false, false, progress);
    appendFrames(reference, extractor, frames.summer, begin, end, false, true, false, progress);
    appendFrames(reference, extractor, frames.winter, begin, end, true, true, false, progress);
    appendFrames(reference, extractor, frames.corridor, 0, corridor, false, false, false, progress);
  }
  progress.finish();
  return reference;
}

Reference stretchOf(const DescriptorSequence& summer, int begin, int end) {
  Reference stretch{"stretch", DescriptorSequence(summer.descriptorSize()), {}};
  for (int frame = begin; frame < end; ++frame) {
    stretch.descriptors.append(summer.descriptorRow(frame));
    stretch.route_frame.push_back(frame);
  }
  return stretch;
}

DescriptorSequence describe(const std::vector<cv::Mat>& frames, const DescriptorExtractor& extractor) {
  DescriptorSequence sequence(extractor.size());
  for (const cv::Mat& image : frames) sequence.append(extractor.compute(image));
  return sequence;
}

std::vector<int> truthOf(const Reference& reference, int frame) {
  std::vector<int> truth;
  for (std::size_t j = 0; j < reference.route_frame.size(); ++j) {
    if (reference.route_frame[j] == frame) truth.push_back(static_cast<int>(j));
  }
  return truth;
}

}  // namespace benchmark
}  // namespace mrs_vpr

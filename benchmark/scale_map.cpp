#include "scale_map.hpp"

#include <algorithm>
#include <cstdio>
#include <utility>
#include <vector>

#include <opencv2/imgproc.hpp>

#include "mrs_vpr/descriptor.hpp"
#include "mrs_vpr/evaluation/image_folder.hpp"
#include "mrs_vpr/store/map_database.hpp"
#include "tools/stopwatch.hpp"

namespace mrs_vpr {
namespace benchmark {

using tools::Clock;
using tools::secondsSince;

Augmenter::Look Augmenter::nextLook(int flip) {
  std::uniform_real_distribution<double> shift_x(-6.0, 6.0);
  std::uniform_real_distribution<double> shift_y(-3.0, 3.0);
  std::uniform_real_distribution<double> gain(0.7, 1.3);
  std::uniform_real_distribution<double> offset(-30.0, 30.0);
  return {flip, shift_x(rng_), shift_y(rng_), gain(rng_), offset(rng_)};
}

cv::Mat Augmenter::apply(const cv::Mat& image, const Look& look) {
  cv::Mat source = image;  // Shares the pixels: flipped into a new image, never in place.
  if (look.flip != 2) {
    source = cv::Mat();
    cv::flip(image, source, look.flip);
  }
  const cv::Mat shift = (cv::Mat_<double>(2, 3) << 1, 0, look.dx, 0, 1, look.dy);
  cv::Mat moved;
  cv::warpAffine(source, moved, shift, source.size(), cv::INTER_LINEAR, cv::BORDER_REPLICATE);
  cv::Mat noise(moved.size(), CV_MAKETYPE(CV_16S, moved.channels()));
  cv::theRNG().state = rng_();
  cv::randn(noise, 0, 3);
  cv::Mat changed;
  moved.convertTo(changed, CV_16S, look.gain, look.offset);
  changed += noise;
  changed.convertTo(moved, image.type());
  return moved;
}

long long writeScaleMap(const std::string& path, long long frames, const MapScaleOptions& options) {
  const DescriptorExtractor extractor(options.descriptor);
  const std::vector<cv::Mat> summer = loadImageFolder(options.data + "/nordland/summer");
  // Winter, the queries' season, is left out, and Nordland distractors are turned upside down (or by
  // 180 degrees), so that no distractor shows a query's place, not even mirrored: the truth is never
  // ambiguous, and a wrong answer is the search's fault.
  std::vector<std::vector<cv::Mat>> sources = {summer, loadImageFolder(options.data + "/corridor/ref")};
  for (const cv::Mat& image : loadImageFolder(options.data + "/corridor/query")) sources[1].push_back(image);
  const long long route = static_cast<long long>(summer.size());
  std::mt19937_64 rng(options.seed + static_cast<std::uint64_t>(frames));
  const long long truth_offset = std::uniform_int_distribution<long long>(0, frames - route)(rng);
  Augmenter augmenter(options.seed);

  const std::string aside = path + ".part";
  std::remove(aside.c_str());
  MapDatabase map(aside, options.descriptor);
  std::vector<StoredFrame> batch;
  const auto start = Clock::now();
  long long written = 0;
  auto add = [&](const cv::Mat& image) {
    StoredFrame frame;
    frame.descriptor = extractor.compute(image);
    frame.stamp = Stamp::fromNanoseconds(static_cast<std::int64_t>(written) * 100'000'000);
    frame.sequence = written++;
    batch.push_back(std::move(frame));
    if (batch.size() == 10000) {
      map.append(batch);
      batch.clear();
      std::fprintf(stderr, "\rwriting %s: %lld / %lld frames, %.0f frames/s ", path.c_str(), written, frames,
                   written / secondsSince(start));
    }
  };
  while (written < frames) {
    if (written == truth_offset) {
      for (const cv::Mat& image : summer) add(image);
      continue;
    }
    // A distractor segment that stops at the true places or the end of the map.
    const long long room = (written < truth_offset ? truth_offset : frames) - written;
    const int source_index = std::uniform_int_distribution<int>(0, 1)(rng);
    const auto& source = sources[static_cast<std::size_t>(source_index)];
    const long long length = std::min<long long>(room, std::uniform_int_distribution<long long>(200, 800)(rng));
    const long long begin = std::uniform_int_distribution<long long>(0, static_cast<long long>(source.size()) - 1)(rng);
    const bool backwards = std::uniform_int_distribution<int>(0, 1)(rng) == 1;
    const int flip = source_index == 0 ? (backwards ? -1 : 0) : 2;
    const Augmenter::Look look = augmenter.nextLook(flip);
    for (long long i = 0; i < length; ++i) {
      const long long step = backwards ? -i : i;
      const long long n = static_cast<long long>(source.size());
      add(augmenter.apply(source[static_cast<std::size_t>(((begin + step) % n + n) % n)], look));
    }
  }
  if (!batch.empty()) map.append(batch);
  std::fprintf(stderr, "\rwrote %s: %lld frames in %.1f s%20s\n", path.c_str(), written, secondsSince(start), "");
  return truth_offset;
}

}  // namespace benchmark
}  // namespace mrs_vpr

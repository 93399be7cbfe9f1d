#include "mrs_vpr/synthetic_route.hpp"

#include <cmath>
#include <random>
#include <stdexcept>
#include <string>

#include <opencv2/imgproc.hpp>

namespace mrs_vpr {
namespace {

constexpr double kPixelsPerPlace = 8.0;  // Consecutive frames overlap, as a moving camera's do.
constexpr int kMargin = 8;               // Room around the crops for shifts.

/// Smooth random texture: random values on coarse grids of several scales, upsampled and summed.
cv::Mat fractalNoise(cv::Size size, std::mt19937_64& rng) {
  cv::Mat sum = cv::Mat::zeros(size, CV_32FC3);
  std::normal_distribution<float> gaussian(0.0F, 1.0F);
  for (int cell : {48, 16, 6, 3}) {
    cv::Mat coarse(std::max(2, size.height / cell + 2), std::max(2, size.width / cell + 2), CV_32FC3);
    for (auto it = coarse.begin<cv::Vec3f>(); it != coarse.end<cv::Vec3f>(); ++it) {
      const float shared = gaussian(rng);  // Mostly grey structure with some colour.
      *it = cv::Vec3f(shared + 0.3F * gaussian(rng), shared + 0.3F * gaussian(rng), shared + 0.3F * gaussian(rng));
    }
    cv::Mat fine;
    cv::resize(coarse, fine, size, 0, 0, cv::INTER_CUBIC);
    sum += fine * (static_cast<float>(cell) / 48.0F + 0.25F);
  }
  return sum;
}

/// The route's appearance: texture plus solid blocks (the "buildings" that make places distinct).
cv::Mat makeWorld(cv::Size size, std::mt19937_64& rng) {
  cv::Mat world = fractalNoise(size, rng);
  std::uniform_int_distribution<int> x_at(0, size.width - 1);
  std::uniform_int_distribution<int> width_of(4, 40);
  std::uniform_int_distribution<int> height_of(size.height / 4, size.height);
  std::uniform_real_distribution<float> value(-2.0F, 2.0F);
  const int blocks = size.width / 12;
  for (int i = 0; i < blocks; ++i) {
    const int height = height_of(rng);
    const cv::Rect block(x_at(rng), size.height - height, width_of(rng), height);
    const float grey = value(rng);
    world(block & cv::Rect(cv::Point(), size)) = cv::Scalar(grey + 0.2F * value(rng), grey, grey + 0.2F * value(rng));
  }
  cv::Mat world8;
  world.convertTo(world8, CV_8UC3, 32.0, 128.0);
  return world8;
}

cv::Mat cropAt(const cv::Mat& world, double place, cv::Size size, cv::Point2d shift) {
  cv::Mat crop;
  const cv::Point2f centre(static_cast<float>(kMargin + place * kPixelsPerPlace + size.width / 2.0 + shift.x),
                           static_cast<float>(world.rows / 2.0 + shift.y));
  cv::getRectSubPix(world, size, centre, crop);
  return crop;
}

/// Smooth value in [0, 1] along the route: a few random sinusoids with periods in [min, max] frames.
class SmoothSignal {
 public:
  SmoothSignal(std::mt19937_64& rng, double min_period, double max_period) {
    std::uniform_real_distribution<double> period(min_period, max_period);
    std::uniform_real_distribution<double> phase(0.0, 2.0 * M_PI);
    for (int i = 0; i < 3; ++i) components_.push_back({2.0 * M_PI / period(rng), phase(rng)});
  }
  double at(double x) const {
    double sum = 0.0;
    for (const auto& [frequency, phase] : components_) sum += std::sin(frequency * x + phase);
    return 0.5 + sum / (2.0 * static_cast<double>(components_.size()));
  }

 private:
  std::vector<std::pair<double, double>> components_;
};

}  // namespace

void SyntheticRouteParams::validate() const {
  // Upper bounds too: the route's world is one image some 8 px a reference frame wide.
  constexpr int kMostFrames = 1000000;
  constexpr int kLargestSide = 4096;
  const auto inside = [](int value, int low, int high) { return value >= low && value <= high; };
  if (!inside(reference_frames, 2, kMostFrames) || !inside(query_frames, 1, kMostFrames) ||
      !inside(image_width, 8, kLargestSide) || !inside(image_height, 8, kLargestSide)) {
    throw std::invalid_argument("a synthetic route needs 2.." + std::to_string(kMostFrames) + " reference frames, 1.." +
                                std::to_string(kMostFrames) + " query frames and images of 8.." +
                                std::to_string(kLargestSide) + " px a side");
  }
  if (!(speed_min > 0.0 && speed_min <= speed_max)) {
    throw std::invalid_argument("synthetic route speeds must satisfy 0 < speed_min <= speed_max");
  }
}

SyntheticRoute generateSyntheticRoute(const SyntheticRouteParams& params) {
  params.validate();
  std::mt19937_64 rng(params.seed);
  const cv::Size frame_size(params.image_width, params.image_height);
  const cv::Size world_size(
      static_cast<int>(params.reference_frames * kPixelsPerPlace) + params.image_width + 2 * kMargin,
      params.image_height + 2 * kMargin);
  const cv::Mat world = makeWorld(world_size, rng);

  SyntheticRoute route;
  route.reference.reserve(static_cast<std::size_t>(params.reference_frames));
  for (int i = 0; i < params.reference_frames; ++i) {
    route.reference.push_back(cropAt(world, i, frame_size, {0.0, 0.0}));
  }

  // Second traversal: another season (a second texture blended in), other light, other camera.
  const cv::Mat season = makeWorld(world_size, rng);
  cv::Mat changed_world;
  cv::addWeighted(world, 0.75, season, 0.25, 0.0, changed_world);
  // Speed drifts slowly (a vehicle, not a jittering hand): over 300 frames it changes by less than
  // 0.1, so that a straight trajectory fits a long test sequence to within a frame or two, as SeqSLAM
  // and MRS-VPR assume. Light changes much faster.
  const SmoothSignal speed(rng, 5000.0, 15000.0);
  const SmoothSignal light(rng, 40.0, 400.0);
  cv::RNG pixel_noise(rng());
  std::uniform_real_distribution<double> jitter(-2.0, 2.0);
  double place = params.start_place;
  for (int i = 0; i < params.query_frames; ++i) {
    const long nearest = std::lround(place);
    if (place < 0.0 || nearest >= params.reference_frames) {
      throw std::invalid_argument("the second traversal leaves the route at query frame " + std::to_string(i) +
                                  "; use more reference frames or fewer query frames");
    }
    cv::Mat frame = cropAt(changed_world, place, frame_size, {jitter(rng), jitter(rng)});
    cv::GaussianBlur(frame, frame, cv::Size(3, 3), 0.8);
    const double gain = 0.55 + 0.6 * light.at(i);  // Illumination and contrast.
    const double bias = 40.0 * (light.at(i + 1000.0) - 0.5);
    cv::Mat noisy(frame.size(), CV_32FC3);
    frame.convertTo(noisy, CV_32FC3, gain, bias);
    cv::Mat grain(frame.size(), CV_32FC3);
    pixel_noise.fill(grain, cv::RNG::NORMAL, 0.0, params.noise_std);
    noisy += grain;
    noisy.convertTo(frame, CV_8UC3);
    route.query.push_back(frame);
    route.query_to_reference.push_back(static_cast<int>(nearest));
    place += params.speed_min + (params.speed_max - params.speed_min) * speed.at(i);
  }
  return route;
}

}  // namespace mrs_vpr

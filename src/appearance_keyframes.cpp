#include "mrs_vpr/appearance_keyframes.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <memory>
#include <stdexcept>
#include <string>

#include "mrs_vpr/front_end/front_end.hpp"
#include "mrs_vpr/median.hpp"

namespace mrs_vpr {
namespace {

std::vector<float> asFloats(const cv::Mat& descriptor) {
  return std::vector<float>(descriptor.ptr<std::uint8_t>(), descriptor.ptr<std::uint8_t>() + descriptor.total());
}

}  // namespace

AppearanceKeyframes::AppearanceKeyframes(const DescriptorParams& front_end, double min_change)
    : min_change_(min_change),
      size_(front_end.descriptorSize()),
      regions_(std::make_shared<const DescriptorRegions>(front_end)) {
  // A view unrelated to any place: seeded noise, so that every run has the same stand-in.
  cv::Mat noise(front_end.isHog() ? front_end.hog_window_height : front_end.image_height,
                front_end.isHog() ? front_end.hog_window_width : front_end.image_width, CV_8UC1);
  cv::RNG(kNoiseSeed).fill(noise, cv::RNG::UNIFORM, 0, 256);
  const cv::Mat unrelated = makeFrontEnd(front_end)->describeGrey(noise);
  unrelated_view_.assign(unrelated.ptr<std::uint8_t>(), unrelated.ptr<std::uint8_t>() + unrelated.total());
}

double AppearanceKeyframes::regionDifference(const std::uint8_t* a, const float* b) const {
  return regions_->difference(a, b);
}

double AppearanceKeyframes::standIn(const float* view) const { return regionDifference(unrelated_view_.data(), view); }

std::vector<float> AppearanceKeyframes::referenceMean() const {
  std::vector<float> mean(sum_.size());
  // In floats, as when the sums were floats: the same means while those were exact (below 2^24).
  const auto frames = static_cast<float>(frames_in_mean_);
  for (std::size_t i = 0; i < mean.size(); ++i) mean[i] = static_cast<float>(sum_[i]) / frames;
  return mean;
}

std::optional<double> AppearanceKeyframes::learntScale() const {
  if (static_cast<int>(samples_.size()) < kMinScaleSamples) return std::nullopt;
  std::vector<double> values(samples_.begin(), samples_.end());
  const double median = upperMedian(values);
  // Zero when most pairs are one view (keyframes taken by travel or loaded from a map while the
  // camera was covered): every change would then read as none, and no keyframe would ever come
  // to change it. The stand-in measures the change instead.
  return median > 0.0 ? std::optional<double>(median) : std::nullopt;
}

double AppearanceKeyframes::scale() const {
  if (const std::optional<double> learnt = learntScale()) return *learnt;
  return frames_in_mean_ == 0 ? 0.0 : standIn(referenceMean().data());
}

bool AppearanceKeyframes::wants(const cv::Mat& descriptor) {
  CV_Assert(descriptor.type() == CV_8UC1 && static_cast<int>(descriptor.total()) == size_ && descriptor.isContinuous());
  last_seen_before_ = false;
  if (!enabled() || frames_in_mean_ == 0) {
    last_change_ = 0.0;
    last_keyframe_change_ = 0.0;
    return true;
  }
  const std::vector<float> mean = referenceMean();
  // scale(), with the learnt scale and the mean at hand once.
  const std::optional<double> learnt = learntScale();
  const double unrelated = learnt ? *learnt : standIn(mean.data());
  last_change_ = unrelated > 0.0 ? regionDifference(descriptor.ptr<std::uint8_t>(), mean.data()) / unrelated : 0.0;
  // The mean is the keyframe until a frame joins it.
  last_keyframe_change_ =
      frames_in_mean_ == 1 || unrelated <= 0.0
          ? last_change_
          : regionDifference(descriptor.ptr<std::uint8_t>(), recent_keyframes_.back().data()) / unrelated;
  if (last_change_ < min_change_) return false;
  const auto unchanged_from = [&](const std::vector<float>& other) {
    return regionDifference(descriptor.ptr<std::uint8_t>(), other.data()) < min_change_ * unrelated;
  };
  // The newest keyframe is the mean's; the kRecentKeyframes - 1 before it are compared one by one,
  // on the stand-in of the two views that is nearer noise while no scale is learnt (see the class).
  const bool stand_in = !learnt;
  const std::size_t kept = recent_keyframes_.size();
  for (std::size_t k = kept - std::min<std::size_t>(kept, kRecentKeyframes); compare_recent_ && k + 1 < kept; ++k) {
    const double scale_k = stand_in ? std::min(keyframe_stand_ins_[k], unrelated) : unrelated;
    if (regionDifference(descriptor.ptr<std::uint8_t>(), recent_keyframes_[k].data()) < min_change_ * scale_k) {
      last_seen_before_ = true;
      return false;
    }
  }
  // A stray of a standing camera: the view of the newest keyframe, like one of its noisy copies.
  return last_keyframe_change_ >= kStrayShare * min_change_ ||
         std::none_of(joined_.begin(), joined_.end(), unchanged_from);
}

bool AppearanceKeyframes::offer(const cv::Mat& descriptor) {
  if (!wants(descriptor)) {
    skip(descriptor);
    return false;
  }
  keep(descriptor);
  return true;
}

void AppearanceKeyframes::keep(const cv::Mat& descriptor) {
  std::vector<float> values = asFloats(descriptor);
  if (static_cast<int>(recent_keyframes_.size()) == kUnrelatedGap) {
    samples_.push_back(regionDifference(descriptor.ptr<std::uint8_t>(), recent_keyframes_.front().data()));
    if (static_cast<int>(samples_.size()) > kScaleSamples) samples_.pop_front();
    recent_keyframes_.pop_front();
    keyframe_stand_ins_.pop_front();
  }
  keyframe_stand_ins_.push_back(standIn(values.data()));
  joined_.clear();
  sum_.assign(descriptor.ptr<std::uint8_t>(), descriptor.ptr<std::uint8_t>() + size_);
  recent_keyframes_.push_back(std::move(values));
  frames_in_mean_ = 1;
}

void AppearanceKeyframes::skip(const cv::Mat& descriptor) {
  if (frames_in_mean_ == 0) return;  // Nothing to compare with yet: the next frame is a keyframe anyway.
  // A frame well on its way from the keyframe is motion, not noise. Measured from the keyframe, not
  // from the mean, so that joined frames cannot drag the reference along with the camera (measured
  // from the mean at three quarters of min_change: gaps of 128 places on the generated route).
  if (last_keyframe_change_ >= min_change_ * kReferenceShare) return;
  const std::uint8_t* bytes = descriptor.ptr<std::uint8_t>();
  for (int i = 0; i < size_; ++i) sum_[static_cast<std::size_t>(i)] += bytes[i];
  ++frames_in_mean_;
  joined_.push_front(asFloats(descriptor));
  if (static_cast<int>(joined_.size()) > kJoinedFrames) joined_.pop_back();
}

AppearanceKeyframes AppearanceKeyframes::follower() const {
  AppearanceKeyframes next(*this);
  next.sum_.clear();
  next.joined_.clear();
  next.compare_recent_ = false;
  next.frames_in_mean_ = 0;
  next.last_change_ = 0.0;
  next.last_keyframe_change_ = 0.0;
  return next;
}

void AppearanceKeyframes::reset() {
  sum_.clear();
  joined_.clear();
  frames_in_mean_ = 0;
  recent_keyframes_.clear();
  keyframe_stand_ins_.clear();
  samples_.clear();
  last_change_ = 0.0;
  last_keyframe_change_ = 0.0;
  last_seen_before_ = false;
}

}  // namespace mrs_vpr

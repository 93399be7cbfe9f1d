#include "mrs_vpr/place_recognizer.hpp"

#include <algorithm>
#include <cstring>
#include <limits>
#include <new>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "mrs_vpr/acceptance.hpp"
#include "mrs_vpr/drive_starts.hpp"
#include "mrs_vpr/mrs_matcher.hpp"
#include "mrs_vpr/number_text.hpp"
#include "mrs_vpr/same_recording.hpp"
#include "mrs_vpr/turn_back.hpp"
#include "mrs_vpr/trajectory_search.hpp"

namespace mrs_vpr {
namespace {

// Frames of spare storage a map gets ahead of need: over two minutes of a 30 Hz camera, unless
// descriptors are so large that this would hold more than kMaxSpareBytes of them.
constexpr int kMinimumReserve = 4096;
constexpr std::size_t kMaxSpareBytes = 64UL * 1024 * 1024;

/// `text` with control characters written as \xNN, so that a message quoting user input is never
/// cut short by a NUL on its way to the user (ROS strings, C strings).
std::string printable(const std::string& text) {
  std::string result;
  for (const char c : text) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
      const char digits[] = "0123456789abcdef";
      result += "\\x";
      result += digits[(static_cast<unsigned char>(c) >> 4) & 0xf];
      result += digits[static_cast<unsigned char>(c) & 0xf];
    } else {
      result += c;
    }
  }
  return result;
}

/// Throws std::invalid_argument unless a question about the newest keyframes names enough of them.
void requireRecentFrames(long long frames) {
  if (frames < kMinSequenceFrames) {
    throw std::invalid_argument("recent_frames must be at least " + std::to_string(kMinSequenceFrames) + ", got " +
                                std::to_string(frames));
  }
}

}  // namespace

PlaceRecognizer::PlaceRecognizer(const Parameters& params, const RecognizerParams& recognizer)
    : params_(params),
      recognizer_(recognizer),
      extractor_(params.descriptor),
      trail_(extractor_.size()),
      keyframes_(params.descriptor, recognizer.min_appearance_change),
      map_(extractor_.size()) {
  params_.validate();
  recognizer_.validate();
  for (const char* method : {"mrs", "seqslam"}) {
    matchers_[method] = makeMatcher(method, params_);
    matchers_[method]->stopWith(&stop_);
    matchers_[method]->linkPlacesWith(&links_);
  }
  // The map keeps MRS's coarse cells up to date as frames arrive, so that a query does not
  // transform the whole map again.
  map_.keepCoarseCells(params_.mrs.levels, params_.descriptor);
  recent_rows_ = std::make_unique<RecentRows>(params_.sequence.contrast_window, kMaxRecentRows);
}

cv::Mat PlaceRecognizer::describe(const cv::Mat& image, ChannelOrder order) const {
  return extractor_.compute(image, order);
}

FrameAdmission PlaceRecognizer::addFrame(const cv::Mat& image, Stamp stamp, ChannelOrder order) {
  return offerDescriptor(describe(image, order), stamp);  // Described before any lock is taken.
}

FrameAdmission PlaceRecognizer::offerDescriptor(const cv::Mat& descriptor, Stamp stamp) {
  requireDescriptorBytes(descriptor, extractor_.size());
  std::lock_guard<std::mutex> lock(keyframes_mutex_);
  if (const auto refused = notAKeyframeLocked(descriptor)) return *refused;
  const FrameAdmission admission = append(descriptor, stamp);
  // A full map still follows the camera as if it had room, so that only the frames that would have
  // been keyframes are dropped (a robot standing at a new place drops one); a frame that only waited
  // for a query (kPendingFull) is not kept by the rule, so that the next one can take its place.
  if (admission == FrameAdmission::kAdmitted || admission == FrameAdmission::kMapFull) {
    keepKeyframeLocked(descriptor);
    newest_keyframe_in_map_ = admission == FrameAdmission::kAdmitted;
  } else {
    keyframes_.skip(descriptor);
  }
  return admission;
}

FrameAdmission PlaceRecognizer::offerToTrail(const cv::Mat& descriptor, Stamp stamp) {
  requireDescriptorBytes(descriptor, extractor_.size());
  std::lock_guard<std::mutex> lock(keyframes_mutex_);
  if (const auto refused = notAKeyframeLocked(descriptor)) return *refused;
  return appendToTrailLocked(descriptor, stamp);
}

FrameAdmission PlaceRecognizer::addToTrail(const cv::Mat& descriptor, Stamp stamp) {
  requireDescriptorBytes(descriptor, extractor_.size());
  std::lock_guard<std::mutex> lock(keyframes_mutex_);
  return appendToTrailLocked(descriptor, stamp);
}

FrameAdmission PlaceRecognizer::appendToTrailLocked(const cv::Mat& descriptor, Stamp stamp) {
  {
    std::lock_guard<std::mutex> trail_lock(trail_mutex_);
    trail_.append(descriptor, stamp);
  }
  keepKeyframeLocked(descriptor);
  newest_keyframe_in_map_ = true;  // a keyframe a question can localise, as a map keyframe
  return FrameAdmission::kAdmitted;
}

std::int64_t PlaceRecognizer::trailSize() const {
  std::lock_guard<std::mutex> lock(trail_mutex_);
  return trail_.size();
}

std::optional<FrameAdmission> PlaceRecognizer::notAKeyframeLocked(const cv::Mat& descriptor) {
  if (keyframes_.wants(descriptor)) return std::nullopt;
  keyframes_.skip(descriptor);
  return keyframes_.lastSeenBefore() ? FrameAdmission::kSeenRecently : FrameAdmission::kTooSimilar;
}

void PlaceRecognizer::keepKeyframeLocked(const cv::Mat& descriptor) {
  try {
    keyframes_.keep(descriptor);
  } catch (const std::bad_alloc&) {
    // The frame is in the map already: the rule starts over, as after a reset, rather than the caller
    // being told that an admitted frame failed.
    keyframes_.reset();
  }
}

FrameAdmission PlaceRecognizer::addDescriptor(const cv::Mat& descriptor, Stamp stamp) {
  requireDescriptorBytes(descriptor, extractor_.size());
  std::lock_guard<std::mutex> lock(keyframes_mutex_);
  const FrameAdmission admission = append(descriptor, stamp);
  if (admission == FrameAdmission::kAdmitted) {
    keepKeyframeLocked(descriptor);
    newest_keyframe_in_map_ = true;
  }
  return admission;
}

double PlaceRecognizer::lastAppearanceChange() const {
  std::lock_guard<std::mutex> lock(keyframes_mutex_);
  return keyframes_.lastChange();
}

bool PlaceRecognizer::lastFrameStood() const {
  std::lock_guard<std::mutex> lock(keyframes_mutex_);
  return newest_keyframe_in_map_ && keyframes_.lastStood();
}

FrameAdmission PlaceRecognizer::append(const cv::Mat& descriptor, Stamp stamp) {
  {
    std::lock_guard<std::mutex> lock(pending_mutex_);
    if (recognizer_.max_frames > 0 && frames_admitted_ >= recognizer_.max_frames) return FrameAdmission::kMapFull;
    if (static_cast<int>(pending_.size()) >= recognizer_.max_pending_frames) return FrameAdmission::kPendingFull;
    // A copy: the caller may reuse its buffer while the frame waits for a query to release the map.
    pending_.push_back({descriptor.clone(), stamp});
    ++frames_admitted_;
  }
  // Never wait for a query: if one holds the map, the frame stays pending until the map is free.
  // Nor for memory: when the map cannot grow now, the frame stays pending for the next flush, and
  // once the pending buffer is full, frames are refused as kPendingFull.
  std::unique_lock<std::shared_mutex> map_lock(map_mutex_, std::try_to_lock);
  if (map_lock.owns_lock()) {
    try {
      flushLocked();
    } catch (const std::bad_alloc&) {
    }
  }
  return FrameAdmission::kAdmitted;
}

void PlaceRecognizer::flushLocked() {
  // A frame leaves the pending buffer only once the map holds it, so that a failed allocation loses
  // none: the frames not yet stored wait for the next flush. New frames may arrive meanwhile, behind.
  std::size_t stored = 0;
  try {
    for (;; ++stored) {
      PendingFrame frame;
      {
        std::lock_guard<std::mutex> lock(pending_mutex_);
        if (stored == pending_.size()) break;
        frame = pending_[stored];
      }
      map_.append(frame.descriptor, frame.stamp);
    }
  } catch (...) {
    forgetStored(stored);
    throw;
  }
  forgetStored(stored);
}

void PlaceRecognizer::forgetStored(std::size_t stored) {
  {
    std::lock_guard<std::mutex> lock(pending_mutex_);
    pending_.erase(pending_.begin(), pending_.begin() + static_cast<std::ptrdiff_t>(stored));
  }
  map_frames_ = map_.size();
}

void PlaceRecognizer::flush() {
  std::unique_lock<std::shared_mutex> map_lock(map_mutex_);
  flushLocked();
}

bool PlaceRecognizer::tryFlush() {
  std::unique_lock<std::shared_mutex> map_lock(map_mutex_, std::try_to_lock);
  if (!map_lock.owns_lock()) return false;
  flushLocked();
  reserveAheadLocked();  // Under the same lock: a query starting now is not waited for either.
  return true;
}

void PlaceRecognizer::reserveAhead() {
  std::unique_lock<std::shared_mutex> map_lock(map_mutex_);
  reserveAheadLocked();
}

int PlaceRecognizer::spareFrames() const {
  const auto frame_bytes = static_cast<std::size_t>(std::max(1, extractor_.size()));
  const std::size_t fitting = std::max<std::size_t>(1, kMaxSpareBytes / frame_bytes);
  return static_cast<int>(std::min<std::size_t>(kMinimumReserve, fitting));
}

void PlaceRecognizer::reserveAheadLocked() {
  const int frames = map_.size();
  if (frames < reserved_frames_ - reserved_frames_ / 4) return;
  int target = std::max(spareFrames(), 2 * std::max(reserved_frames_, frames));
  if (recognizer_.max_frames > 0) target = std::min(target, recognizer_.max_frames);
  if (target <= reserved_frames_) return;
  // Copying a large map takes a while; meanwhile addFrame parks frames in the pending buffer.
  try {
    map_.reserve(target);
    reserved_frames_ = target;
  } catch (const std::bad_alloc&) {
    // Twice the map may not fit where the map still grows by a frame at a time.
  }
}

void PlaceRecognizer::reserve(int frames) {
  std::unique_lock<std::shared_mutex> map_lock(map_mutex_);
  if (recognizer_.max_frames > 0) frames = std::min(frames, recognizer_.max_frames);
  if (frames <= reserved_frames_) return;
  map_.reserve(frames);
  reserved_frames_ = frames;
}

void PlaceRecognizer::visitFrames(int begin, int end,
                                  const std::function<void(const cv::Mat& descriptor, Stamp stamp)>& visit) const {
  std::shared_lock<std::shared_mutex> map_lock(map_mutex_);
  if (begin < 0 || end > map_.size() || begin > end) {
    throw std::invalid_argument("frames [" + std::to_string(begin) + ", " + std::to_string(end) +
                                ") are not in a map of " + std::to_string(map_.size()));
  }
  for (int i = begin; i < end; ++i) visit(map_.descriptorRow(i), map_.stamp(i));
}

int PlaceRecognizer::pending() const {
  std::lock_guard<std::mutex> lock(pending_mutex_);
  return static_cast<int>(pending_.size());
}

int PlaceRecognizer::reset() { return install(prepareMap({}, {})); }

void PlaceRecognizer::replace(const std::vector<cv::Mat>& descriptors, const std::vector<Stamp>& stamps) {
  install(prepareMap(descriptors, stamps));
}

PlaceRecognizer::PreparedMap PlaceRecognizer::prepareMap(const std::vector<cv::Mat>& descriptors,
                                                         const std::vector<Stamp>& stamps) const {
  if (descriptors.size() != stamps.size()) {
    throw std::invalid_argument(std::to_string(stamps.size()) + " stamps for " + std::to_string(descriptors.size()) +
                                " descriptors");
  }
  if (descriptors.size() > static_cast<std::size_t>(std::numeric_limits<int>::max())) {
    throw std::invalid_argument(std::to_string(descriptors.size()) + " frames are more than a map can hold");
  }
  // Checked before the map's storage is allocated.
  for (const cv::Mat& descriptor : descriptors) requireDescriptorBytes(descriptor, extractor_.size());
  PreparedMap prepared = prepareMap(static_cast<int>(descriptors.size()));
  for (std::size_t i = 0; i < descriptors.size(); ++i) prepared.append(descriptors[i], stamps[i]);
  return prepared;
}

PlaceRecognizer::PreparedMap PlaceRecognizer::prepareMap(int frames) const {
  if (frames < 0) throw std::invalid_argument("a map cannot hold " + std::to_string(frames) + " frames");
  if (recognizer_.max_frames > 0 && frames > recognizer_.max_frames) {
    throw std::invalid_argument(std::to_string(frames) + " frames exceed max_frames (" +
                                std::to_string(recognizer_.max_frames) + ")");
  }
  // Built aside, without any lock: queries and new frames go on with the old map meanwhile.
  PreparedMap prepared(params_, recognizer_, extractor_.size());
  prepared.expected_frames_ = frames;
  // Room for the camera's next frames too, where memory allows: the first of them must not copy the
  // whole map on the camera's thread. Growing further is reserveAhead()'s, off the camera's path.
  const int room =
      recognizer_.max_frames > 0 ? std::min(spareFrames(), recognizer_.max_frames - frames) : spareFrames();
  try {
    prepared.map_.reserve(frames + room);
    prepared.reserved_frames_ = frames + room;
  } catch (const std::bad_alloc&) {
    prepared.map_.reserve(frames);
    prepared.reserved_frames_ = frames;
  }
  return prepared;
}

void PlaceRecognizer::PreparedMap::append(const cv::Mat& descriptor, Stamp stamp) {
  requireDescriptorBytes(descriptor, map_.descriptorSize());
  if (map_.size() >= expected_frames_) {
    throw std::invalid_argument("a map prepared for " + std::to_string(expected_frames_) +
                                " frames was given more");
  }
  map_.append(descriptor, stamp);
  keyframes_.keep(descriptor);
}

void PlaceRecognizer::PreparedMap::linkPlaces(const std::vector<PlaceLink>& links) {
  places_ = PlaceLinks::placesOf(links, map_.size());
  links_ = links;
}

void PlaceRecognizer::PreparedMap::markDriveStarts(const std::vector<int>& starts) {
  drive_starts_.clear();
  for (const int start : starts) {
    if (start > 0 && start <= map_.size()) insertDriveStart(drive_starts_, start);
  }
}

bool PlaceRecognizer::PreparedMap::holds(int index, const cv::Mat& descriptor, Stamp stamp) const {
  if (index < 0 || index >= map_.size() || !(map_.stamp(index) == stamp)) return false;
  const auto bytes = static_cast<std::size_t>(map_.descriptorSize());
  return descriptor.isContinuous() && descriptor.total() * descriptor.elemSize() == bytes &&
         std::memcmp(map_.descriptorRow(index).data, descriptor.data, bytes) == 0;
}

PlaceRecognizer::PreparedMap::PreparedMap(const Parameters& params, const RecognizerParams& recognizer,
                                          int descriptor_size)
    : descriptor_(params.descriptor),
      map_(descriptor_size),
      keyframes_(params.descriptor, recognizer.min_appearance_change) {
  map_.keepCoarseCells(params.mrs.levels, params.descriptor);
}

void PlaceRecognizer::linkPlaces(const std::vector<PlaceLink>& links) {
  flush();  // The links name frames that may still be pending.
  std::unique_lock<std::shared_mutex> map_lock(map_mutex_);
  std::vector<PlaceLink> kept = links;
  links_.adopt(PlaceLinks::placesOf(links, map_.size()), std::move(kept));
}

int PlaceRecognizer::newestFrameStamped(Stamp stamp) const {
  std::shared_lock<std::shared_mutex> map_lock(map_mutex_);
  for (int i = map_.size() - 1; i >= 0; --i) {
    if (map_.stamp(i) == stamp) return i;
  }
  return -1;
}

int PlaceRecognizer::install(PreparedMap&& prepared) {
  if (!prepared.descriptor_.sameFrontEnd(params_.descriptor)) {
    throw std::invalid_argument("a map prepared for the " + prepared.descriptor_.describe() +
                                " front end cannot replace one of the " + params_.descriptor.describe() + " front end");
  }
  // Every lock for the exchange, which only moves what was built, so that queries never see it half
  // done. The map's first: waiting for a running query must not hold the keyframe rule's lock, or a
  // camera frame would wait for the query too. offerDescriptor holds that lock only to try the map's.
  std::unique_lock<std::shared_mutex> map_lock(map_mutex_);
  std::lock_guard<std::mutex> keyframes_lock(keyframes_mutex_);
  std::lock_guard<std::mutex> lock(pending_mutex_);
  const int cleared = map_.size() + static_cast<int>(pending_.size());
  keyframes_ = std::move(prepared.keyframes_);
  newest_keyframe_in_map_ = true;
  map_ = std::move(prepared.map_);
  pending_.clear();
  recent_rows_->clear();
  // Those its database kept; none for a map of frames alone.
  links_.adopt(std::move(prepared.places_), std::move(prepared.links_));
  drive_starts_ = std::move(prepared.drive_starts_);  // Its database's; none for a map of frames alone.
  map_frames_ = map_.size();
  frames_admitted_ = map_.size();
  reserved_frames_ = prepared.reserved_frames_;
  return cleared;
}

void PlaceRecognizer::markDriveStart(int frame) {
  if (frame == 0) return;  // No junction: no need to wait for running queries.
  std::unique_lock<std::shared_mutex> map_lock(map_mutex_);
  insertDriveStart(drive_starts_, frame);
}

std::vector<int> PlaceRecognizer::driveStarts() const {
  std::shared_lock<std::shared_mutex> map_lock(map_mutex_);
  return drive_starts_;
}

PlaceRecognizer::MapState PlaceRecognizer::state() const {
  MapState state;
  {
    std::shared_lock<std::shared_mutex> map_lock(map_mutex_);
    state.frames = map_.size();
    state.memory_bytes = map_.memoryBytes() + recent_rows_->memoryBytes() + links_.memoryBytes();
    state.descriptor_size = map_.descriptorSize();
    state.linked_frames = links_.linkedFrames();
    std::lock_guard<std::mutex> trail_lock(trail_mutex_);
    state.memory_bytes += trail_.memoryBytes();
    if (!map_.empty()) {
      state.first_stamp = map_.stamp(0);
      state.last_stamp = map_.stamp(map_.size() - 1);
    }
    // Under the map's lock, which every flush holds: no frame is counted twice or missed in between.
    state.pending = pending();
  }
  return state;
}

int PlaceRecognizer::framesToSearchLocked() const {
  if (map_.empty()) throw std::invalid_argument("the reference map is empty: add frames first");
  return map_.size();
}

const SequenceMatcher& PlaceRecognizer::matcherFor(const std::string& method) const {
  const std::string& name = method.empty() ? recognizer_.default_method : method;
  const auto matcher = matchers_.find(name);
  if (matcher == matchers_.end()) {
    throw std::invalid_argument("unknown method '" + printable(name) + "': use 'mrs' or 'seqslam'");
  }
  return *matcher->second;
}

PlaceAnswer PlaceRecognizer::answer(SequenceView reference, SequenceView query, const std::string& method,
                                    MatchExplanation* explanation, const MapFrames* map_frames) const {
  stop_.throwIfRequested();
  const SequenceMatcher& matcher = matcherFor(method);
  PlaceAnswer answer;
  answer.method = matcher.name();
  answer.query_length = query.count;
  answer.localised_row = wholeSequenceRows(query.count, params_.sequence.alignment).anchor;
  std::vector<MrsLevelTrace> levels;
  const auto* mrs = dynamic_cast<const MrsMatcher*>(&matcher);
  // Only an explained MRS answer records its levels: the same search, plus a copy of the particles.
  std::vector<MrsLevelTrace>* trace = explanation != nullptr ? &levels : nullptr;
  if (mrs != nullptr && map_frames != nullptr) {
    answer.match = mrs->matchMapFrames(map_frames->map, reference.count, map_frames->first, query.count, *recent_rows_,
                                       trace);
  } else {
    answer.match = mrs != nullptr ? mrs->match(reference, query, trace) : matcher.match(reference, query);
  }
  if (answer.match.reference_index >= 0) answer.reference_stamp = map_.stamp(answer.match.reference_index);
  refuseAcrossDrives(answer.match, wholeSequenceRows(query.count, params_.sequence.alignment), drive_starts_,
                     velocities(params_.sequence));
  answer.verdict = acceptanceVerdict(answer.match, params_.sequence);
  if (explanation != nullptr) {
    *explanation = explainMatch(reference, query, answer.match, params_.sequence, params_.descriptor);
    explanation->levels = std::move(levels);
  }
  return answer;
}

PlaceAnswer PlaceRecognizer::match(const std::vector<cv::Mat>& test_sequence, const std::string& method,
                                   ChannelOrder order) {
  DescriptorSequence descriptors(extractor_.size());
  descriptors.reserve(static_cast<int>(test_sequence.size()));
  for (std::size_t i = 0; i < test_sequence.size(); ++i) {
    try {
      descriptors.append(describe(test_sequence[i], order));
    } catch (const std::exception& error) {
      throw std::invalid_argument("image " + std::to_string(i) + " of the test sequence: " + error.what());
    }
  }
  return matchKeyframesOf(descriptors, method);
}

PlaceAnswer PlaceRecognizer::matchKeyframesOf(const DescriptorSequence& frames, const std::string& method,
                                              MatchExplanation* explanation) {
  std::vector<int> kept;
  const DescriptorSequence keyframes = keyframesOf(frames, &kept);
  if (frames.size() >= kMinSequenceFrames && keyframes.size() < kMinSequenceFrames) {
    throw std::invalid_argument("the test sequence's " + std::to_string(frames.size()) + " images hold fewer than " +
                                std::to_string(kMinSequenceFrames) + " keyframes: the view hardly changes across them "
                                "(min_appearance_change " + numberText(recognizer_.min_appearance_change) + ")");
  }
  PlaceAnswer answer = matchSequence(keyframes.view(), method, explanation, frames.size());
  if (answer.localised_row >= 0) answer.localised_row = kept.at(static_cast<std::size_t>(answer.localised_row));
  return answer;
}

RepeatedViews PlaceRecognizer::repeatedViews() const {
  std::lock_guard<std::mutex> lock(keyframes_mutex_);
  return RepeatedViews(keyframes_);
}

DescriptorSequence PlaceRecognizer::keyframesOf(const DescriptorSequence& frames, std::vector<int>* chosen) const {
  AppearanceKeyframes keyframes = [&] {
    std::lock_guard<std::mutex> lock(keyframes_mutex_);
    return keyframes_.follower();
  }();
  DescriptorSequence kept(extractor_.size());
  if (chosen != nullptr) chosen->clear();
  for (int i = 0; i < frames.size(); ++i) {
    const cv::Mat descriptor = frames.descriptorRow(i);
    if (!keyframes.offer(descriptor)) continue;
    kept.append(descriptor, frames.stamp(i));
    if (chosen != nullptr) chosen->push_back(i);
  }
  return kept;
}

PlaceAnswer PlaceRecognizer::match(const DescriptorSequence& test_sequence, const std::string& method,
                                   MatchExplanation* explanation) {
  return match(test_sequence.view(), method, explanation);
}

PlaceAnswer PlaceRecognizer::match(SequenceView test_sequence, const std::string& method,
                                   MatchExplanation* explanation) {
  return matchSequence(test_sequence, method, explanation, -1);
}

PlaceAnswer PlaceRecognizer::matchSequence(SequenceView test_sequence, const std::string& method,
                                           MatchExplanation* explanation, int images) {
  matcherFor(method);  // An unknown method is reported before anything else.
  if (test_sequence.count < kMinSequenceFrames) {
    throw std::invalid_argument("a test sequence needs at least " + std::to_string(kMinSequenceFrames) +
                                " images, got " + std::to_string(test_sequence.count));
  }
  PlaceAnswer result;
  {
    std::shared_lock<std::shared_mutex> map_lock(map_mutex_);
    const int frames = framesToSearchLocked();
    if (test_sequence.count > frames) {
      // Counted as the user gave them: images kept as keyframes differ from the images passed.
      const std::string held = images < 0 || images == test_sequence.count
                                   ? " has " + std::to_string(test_sequence.count) + " frames"
                                   : "'s " + std::to_string(images) + " images hold " +
                                         std::to_string(test_sequence.count) + " keyframes";
      throw std::invalid_argument("the test sequence" + held + " but the reference map only " +
                                  std::to_string(frames) + " frames");
    }
    // The search may take a while; frames arriving meanwhile wait in the pending buffer.
    result = answer(map_.view(), test_sequence, method, explanation);
  }
  flush();
  return result;
}

std::vector<Match> PlaceRecognizer::matchEveryFrame(SequenceView traversal, const std::string& method) {
  const SequenceMatcher& matcher = matcherFor(method);
  std::vector<Match> matches;
  {
    std::shared_lock<std::shared_mutex> map_lock(map_mutex_);
    framesToSearchLocked();
    matches = matcher.matchEveryFrame(map_.view(), traversal);
    const std::vector<double> searched = velocities(params_.sequence);
    for (std::size_t frame = 0; frame < matches.size(); ++frame) {
      refuseAcrossDrives(matches[frame], sequenceRowsFor(static_cast<int>(frame), params_.sequence), drive_starts_,
                         searched);
    }
  }
  flush();
  return matches;
}

PlaceAnswer PlaceRecognizer::matchTrail(long long frames, const std::string& method, MatchExplanation* explanation,
                                        long long end) {
  matcherFor(method);
  requireRecentFrames(frames);
  if (end < -1) {
    throw std::invalid_argument("a test sequence cannot end at keyframe " + std::to_string(end) +
                                " (-1: after the newest keyframe)");
  }
  // A copy of the test keyframes and of those before them that the turn-back rule reads: the camera
  // goes on adding keyframes while the question runs.
  DescriptorSequence keyframes(extractor_.size());
  int before = 0;
  {
    std::lock_guard<std::mutex> lock(trail_mutex_);
    const std::int64_t stop = end < 0 ? trail_.size() : end;
    if (stop > trail_.size()) {
      throw std::invalid_argument("a test sequence cannot end at keyframe " + std::to_string(end) + ": the camera " +
                                  "has given " + std::to_string(trail_.size()) + " keyframes");
    }
    if (frames > stop - trail_.oldest()) {
      throw std::invalid_argument("recent_frames " + std::to_string(frames) + " is more than the " +
                                  std::to_string(stop - trail_.oldest()) + " keyframes the camera has given" +
                                  (trail_.oldest() > 0 ? " that are still held" : "") +
                                  (end >= 0 ? " before keyframe " + std::to_string(end) : ""));
    }
    const std::int64_t reach = kReachInSequenceLengths * (frames + AppearanceKeyframes::kRecentKeyframes);
    before = static_cast<int>(std::min<std::int64_t>(stop - frames - trail_.oldest(), reach));
    keyframes = trail_.copy(stop - frames - before, stop);
  }
  const int count = static_cast<int>(frames);
  const SequenceView test = keyframes.view(before, before + count);
  PlaceAnswer result;
  {
    std::shared_lock<std::shared_mutex> map_lock(map_mutex_);
    const RepeatedViews repeated_views = repeatedViews();
    if (map_.empty()) {
      throw std::invalid_argument("the reference map is empty: the camera's keyframes are localised in a map "
                                  "loaded first, and do not join it");
    }
    const int in_map = framesToSearchLocked();
    if (count > in_map) {
      throw std::invalid_argument("recent_frames " + std::to_string(count) + " is more than the " +
                                  std::to_string(in_map) + " frames in the reference map");
    }
    result = answer(map_.view(), test, method, explanation);
    refuseRepeatedViews(result.match, test, repeated_views);
    // None of the trail is in the map: every keyframe before the sequence is left out of the search.
    refuseTurnsBack(result.match, keyframes, {before, before + count}, result.localised_row, before, repeated_views);
    result.verdict = acceptanceVerdict(result.match, params_.sequence);
    result.newest_stamp = keyframes.stamp(before + count - 1);
    result.localised_stamp = keyframes.stamp(before + result.localised_row);
  }
  flush();
  return result;
}

PlaceAnswer PlaceRecognizer::matchRecent(long long frames, const std::string& method,
                                         MatchExplanation* explanation, int end) {
  matcherFor(method);
  requireRecentFrames(frames);
  flush();  // The newest frames must be in the map before they can be the test sequence.
  PlaceAnswer result;
  {
    std::shared_lock<std::shared_mutex> map_lock(map_mutex_);
    // Judged on the scale of the camera that made both the map and these keyframes (repeated_views.hpp),
    // taken under the map's lock: a map loaded or reset meanwhile brings its own.
    const RepeatedViews repeated_views = repeatedViews();
    const int frames_in_map = framesToSearchLocked();
    if (end < -1) {
      throw std::invalid_argument("a test sequence cannot end at frame " + std::to_string(end) +
                                  " (-1: after the newest frame)");
    }
    if (end > frames_in_map) {
      throw std::invalid_argument("a test sequence cannot end at frame " + std::to_string(end) + ": the map holds " +
                                  std::to_string(frames_in_map) + " frames");
    }
    const int size = end < 0 ? frames_in_map : end;
    if (frames > size) {
      throw std::invalid_argument("recent_frames " + std::to_string(frames) + " is more than the " +
                                  std::to_string(size) + " frames in the reference map" +
                                  (end >= 0 ? " before frame " + std::to_string(end) : ""));
    }
    const int recent = static_cast<int>(frames);
    const int searchable = size - recent - recognizer_.recent_exclusion;
    if (size < fewestFramesForRecent(recent)) {
      throw std::invalid_argument("recent_frames " + std::to_string(recent) + " leaves " +
                                  std::to_string(std::max(searchable, 0)) + " searchable frames (map " +
                                  std::to_string(size) + " - recent " + std::to_string(recent) +
                                  " - recent_exclusion " + std::to_string(recognizer_.recent_exclusion) +
                                  "); the search needs at least " + std::to_string(recent));
    }
    refuseTestSequenceAcrossDrives({size - recent, size}, drive_starts_);
    // The test frames are the map's own: MRS keeps their rows of the difference matrix between queries.
    const MapFrames map_frames{map_.view(0, frames_in_map), size - recent};
    result = answer(map_.view(0, searchable), map_.view(size - recent, size), method, explanation, &map_frames);
    refuseRepeatedViews(result.match, map_.view(size - recent, size), repeated_views);
    refuseTurnsBack(result.match, map_, {size - recent, size}, result.localised_row, recognizer_.recent_exclusion,
                    repeated_views);
    // A frame that finds itself is no loop closure; its first pass lies within the sequence's reach.
    refuseSameRecording(result.match, map_, {size - recent, size}, searchable,
                        recent + params_.sequence.match_exclusion, repeated_views);
    result.verdict = acceptanceVerdict(result.match, params_.sequence);  // A rule above may have refused it.
    result.localised_frame = size - recent + result.localised_row;
    // The map's own keyframe shows the answer's place: an accepted closure links the two visits, so
    // that the next visit's answers have neither as a rival (place_links.hpp).
    if (result.match.accepted) links_.link(result.localised_frame, result.match.reference_index);
    result.newest_stamp = map_.stamp(size - 1);
    result.localised_stamp = map_.stamp(result.localised_frame);
  }
  flush();
  return result;
}

}  // namespace mrs_vpr

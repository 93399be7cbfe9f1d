#pragma once

#include <atomic>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <shared_mutex>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "mrs_vpr/appearance_keyframes.hpp"
#include "mrs_vpr/descriptor.hpp"
#include "mrs_vpr/descriptor_sequence.hpp"
#include "mrs_vpr/match.hpp"
#include "mrs_vpr/match_explanation.hpp"
#include "mrs_vpr/mrs/recent_rows.hpp"
#include "mrs_vpr/parameters.hpp"
#include "mrs_vpr/place_links.hpp"
#include "mrs_vpr/query_stop.hpp"
#include "mrs_vpr/repeated_views.hpp"
#include "mrs_vpr/sequence_matcher.hpp"
#include "mrs_vpr/stamp.hpp"
#include "mrs_vpr/trail.hpp"

namespace mrs_vpr {

/// The answer to a query.
struct PlaceAnswer {
  Match match;                 ///< Reference frame, confidence, acceptance (see Match).
  Stamp reference_stamp;       ///< Stamp of the matched reference frame (0 when none).
  Stamp newest_stamp;          ///< Stamp of the test sequence's newest frame (matchRecent; else 0).
  /// The test-sequence frame the answer localises: the newest keyframe (sequence/alignment causal) or
  /// the middle one (centred), counted among the frames given (match of images: among the images).
  /// The reference frame is that frame's place.
  int localised_row = -1;
  Stamp localised_stamp;       ///< Stamp of the localised frame (matchRecent; else 0).
  int localised_frame = -1;    ///< The localised frame's index in the map (matchRecent; else -1).
  int query_length = 0;        ///< Frames of the test sequence.
  std::string method;          ///< The method that answered.
  /// Why the answer was accepted or not, in the words of the node's ~query message ("accepted", "not
  /// accepted: ..."; acceptanceVerdict).
  std::string verdict;
};

/// What became of a frame handed to addFrame.
enum class FrameAdmission {
  kAdmitted,     ///< In the map, or waiting for a query to release it (see addFrame).
  kMapFull,      ///< Dropped: the map holds RecognizerParams::max_frames.
  kPendingFull,  ///< Dropped: max_pending_frames are already waiting for a long query.
  kTooSimilar,   ///< Not a keyframe: too little has changed since the last one (offerDescriptor).
  /// Not a keyframe: it looks like one of the keyframes before the last (a view seen again; offerDescriptor).
  kSeenRecently,
};

/**
 * The one object a C++ user needs for sequence-based place recognition: the descriptor extractor,
 * the reference map (with the coarse cells MRS keeps for it) and both methods.
 *
 *   mrs_vpr::PlaceRecognizer recognizer;                 // the documented defaults
 *   for (...) recognizer.addFrame(image, stamp);         // build the map (an exact mrs_vpr::Stamp)
 *   const auto answer = recognizer.match(last_images);   // where do these frames lie?
 *   if (answer.match.accepted) use(answer.match.reference_index);
 *
 * Thread safety: every member may be called from any thread. Queries read the map under a shared
 * lock; addFrame never waits for one: when a query holds the map, the new frame waits in a small
 * pending buffer that the next writer moves into the map. Bad input throws std::invalid_argument
 * with a message for the user; the object stays usable.
 */
class PlaceRecognizer {
 public:
  /// Throws std::invalid_argument naming the first parameter out of range.
  explicit PlaceRecognizer(const Parameters& params = Parameters{}, const RecognizerParams& recognizer = {});

  PlaceRecognizer(const PlaceRecognizer&) = delete;
  PlaceRecognizer& operator=(const PlaceRecognizer&) = delete;

  /// The descriptor of an image (8UC1, 16UC1, 8UC3, 16UC3, 8UC4, 16UC4 in `order`), without touching the map.
  cv::Mat describe(const cv::Mat& image, ChannelOrder order = ChannelOrder::kBgr) const;

  /// Offers a camera frame (described here): it joins the map if it is a keyframe (offerDescriptor).
  /// Never waits for a running query.
  FrameAdmission addFrame(const cv::Mat& image, Stamp stamp = Stamp(), ChannelOrder order = ChannelOrder::kBgr);
  /// Offers a frame's descriptor (from describe(), for callers that describe outside their own locks):
  /// it joins the map when its view has changed enough since the last keyframe
  /// (RecognizerParams::min_appearance_change, appearance_keyframes.hpp), else kTooSimilar. Its bytes
  /// are copied: the caller may reuse the buffer at once.
  FrameAdmission offerDescriptor(const cv::Mat& descriptor, Stamp stamp = Stamp());
  /// Appends a descriptor that is a keyframe already (a saved map's, or one chosen by travel): no
  /// keyframe decision, but the next offers are compared with it. Its bytes are copied.
  FrameAdmission addDescriptor(const cv::Mat& descriptor, Stamp stamp = Stamp());
  /// The appearance change of the frame last offered, in units of the difference between unrelated
  /// views (0 when keyframes are not chosen by appearance).
  double lastAppearanceChange() const;
  /// Whether the last frame offerDescriptor() refused as kTooSimilar shows the newest keyframe's view
  /// itself (AppearanceKeyframes::lastStood): the node restates the keyframe's closures for such frames
  /// only, not for frames on their way to the next place. False when that keyframe is one a full map
  /// dropped (the rule follows the camera on), as the map holds no frame of its place.
  bool lastFrameStood() const;

  /// Where the test sequence (images, oldest first, at the camera's rate or spaced already) ends in the
  /// map. Its keyframes are matched, chosen as the map's (keyframesOf). `method` "" is the default one.
  /// Throws std::invalid_argument when fewer than 2 of them are keyframes.
  PlaceAnswer match(const std::vector<cv::Mat>& test_sequence, const std::string& method = "",
                    ChannelOrder order = ChannelOrder::kBgr);
  /**
   * The keyframes of a test sequence of descriptors, chosen as the map's frames are (appearance change,
   * RecognizerParams::min_appearance_change, measured on the map's scale), so that a sequence at the
   * camera's rate is spaced as the map is; every frame when that is 0. Stamps are kept; `chosen`
   * receives the index of each keyframe in `frames`.
   */
  DescriptorSequence keyframesOf(const DescriptorSequence& frames, std::vector<int>* chosen = nullptr) const;
  /// match() of a test sequence of descriptors at the camera's rate: its keyframes (keyframesOf) are
  /// matched, and the answer's localised_row counts among `frames`. Throws std::invalid_argument when
  /// fewer than 2 of them are keyframes.
  PlaceAnswer matchKeyframesOf(const DescriptorSequence& frames, const std::string& method = "",
                               MatchExplanation* explanation = nullptr);
  /**
   * The same with a test sequence of descriptors. When `explanation` is not null it receives what a
   * picture of the answer needs (see match_explanation.hpp), computed while the map is still held;
   * without it the query costs nothing more.
   */
  PlaceAnswer match(const DescriptorSequence& test_sequence, const std::string& method = "",
                    MatchExplanation* explanation = nullptr);
  PlaceAnswer match(SequenceView test_sequence, const std::string& method = "",
                    MatchExplanation* explanation = nullptr);
  /**
   * The per-frame protocol over a whole traversal of descriptors: for every frame, the sequence of
   * sequence_length frames that localises it (Match::reference_index -1 where it is incomplete).
   */
  std::vector<Match> matchEveryFrame(SequenceView traversal, const std::string& method = "");
  /**
   * Where the map's own `frames` newest frames lie among its older ones: only frames
   * [0, size - frames - recent_exclusion) are searched, so that the answer is a loop closure and not
   * the place just passed. `explanation` as for match(). With `end` >= 0 the test sequence is the
   * `frames` frames before map frame `end` instead of the newest ones (and the searched frames end as
   * much earlier): continuous mode localises each keyframe that came since its last question. `end`
   * below -1 throws std::invalid_argument. These keyframes are the map's camera's own, so three more
   * rules judge an accepted answer on its scale, and take it back: a sequence that mostly shows one
   * view again (Match::repeated_view, repeated_views.hpp), one whose localised keyframe lies where the
   * robot went back over its path (Match::turned_back, turn_back.hpp), and an answer near which the map
   * holds the test sequence's own keyframes (at the same times with the same views: one recording mapped
   * twice; Match::same_recording, same_recording.hpp).
   */
  PlaceAnswer matchRecent(long long frames, const std::string& method = "", MatchExplanation* explanation = nullptr,
                          int end = -1);
  /**
   * For a map that stays as it is (a map built earlier, localisation only): offers a camera frame's
   * descriptor as offerDescriptor() does, but a keyframe joins the trail of the camera's newest
   * keyframes (trail.hpp) instead of the map. kAdmitted, kTooSimilar or kSeenRecently.
   */
  FrameAdmission offerToTrail(const cv::Mat& descriptor, Stamp stamp = Stamp());
  /// The same for a descriptor that is a keyframe already (one chosen by travel): always kAdmitted.
  FrameAdmission addToTrail(const cv::Mat& descriptor, Stamp stamp = Stamp());
  /// Keyframes that joined the trail since the recognizer was made: where its newest ends.
  std::int64_t trailSize() const;
  /**
   * matchRecent() for the trail: where the trail's `frames` newest keyframes (those before trail
   * keyframe `end`, counted as trailSize() counts, when `end` >= 0) lie in the whole map. The rules of
   * the camera's own keyframes judge it as they judge matchRecent's answers, but for the recording's
   * (its keyframes are not in the map), and it links no place. Throws std::invalid_argument when the
   * trail does not hold those keyframes (it holds the newest kTrailKeyframes at least) or the map
   * holds fewer than `frames` frames. PlaceAnswer::localised_frame is -1.
   */
  PlaceAnswer matchTrail(long long frames, const std::string& method = "", MatchExplanation* explanation = nullptr,
                         long long end = -1);

  /// The fewest map frames with which matchRecent can ask about `frames` of them: the searched
  /// older frames (all but those and recent_exclusion) must be at least as many. Wide, so that no
  /// count of frames overflows it.
  long long fewestFramesForRecent(long long frames) const { return 2 * frames + recognizer_.recent_exclusion; }

  /// Makes a running query throw QueryStopped within a block of its work (the brute force's columns,
  /// rows or anchors), and every later one at once: for a shutdown that need not wait for a long
  /// question. Frames are still added. Safe to call from a signal handler; cannot be undone.
  void stopQueries() noexcept { stop_.request(); }

  /// Frames in the map (not counting pending ones).
  int size() const { return map_frames_.load(); }
  /// Frames waiting for the map.
  int pending() const;
  /// Removes every frame; returns how many there were (pending ones included).
  int reset();
  /**
   * Replaces the whole map with `descriptors` (keyframes already, as a map database holds them) and
   * their `stamps`, in one step: a query running meanwhile answers from the old map or the new one,
   * never from a part of it. Throws std::invalid_argument, leaving the map as it was, when a
   * descriptor is not of this front end, the counts differ, or the frames exceed max_frames.
   */
  void replace(const std::vector<cv::Mat>& descriptors, const std::vector<Stamp>& stamps);

  /// A whole map built by prepareMap(), for install() to put in place at once.
  class PreparedMap {
   public:
    int size() const { return map_.size(); }
    /// Appends a keyframe (its bytes are copied). Throws std::invalid_argument when the descriptor is
    /// not of the front end's size, or when the map already holds the frames it was prepared for.
    void append(const cv::Mat& descriptor, Stamp stamp);
    /// Whether frame `index` holds exactly these bytes and this stamp.
    bool holds(int index, const cv::Mat& descriptor, Stamp stamp) const;
    /// The place links the map keeps (a map database's), once its frames are appended. Throws
    /// std::invalid_argument for a link to a frame it does not hold.
    void linkPlaces(const std::vector<PlaceLink>& links);
    /// The drive starts the map keeps (a map database's, drive_starts.hpp), once its frames are
    /// appended, sorted; a start beyond its frames (a file edited by hand) is left out.
    void markDriveStarts(const std::vector<int>& starts);

   private:
    friend class PlaceRecognizer;
    PreparedMap(const Parameters& params, const RecognizerParams& recognizer, int descriptor_size);
    DescriptorParams descriptor_;
    DescriptorSequence map_;
    AppearanceKeyframes keyframes_;
    std::vector<int> places_;  // PlaceLinks::placesOf() its links
    std::vector<PlaceLink> links_;
    std::vector<int> drive_starts_;
    int expected_frames_ = 0;  // frames it was prepared for
    int reserved_frames_ = 0;  // frames map_ holds storage for
  };
  /// replace() in two steps, for a caller with its own step in between (a database to rewrite): builds
  /// the map aside, with no lock held and nothing changed, and throws as replace() does ...
  PreparedMap prepareMap(const std::vector<cv::Mat>& descriptors, const std::vector<Stamp>& stamps) const;
  /// ... or an empty map with storage for `frames` frames, to fill by PreparedMap::append (a map read
  /// from a file, frame by frame, is not held twice). Throws std::invalid_argument beyond max_frames.
  PreparedMap prepareMap(int frames) const;
  /// ... then puts it in place by moving it, which cannot fail for want of memory. Returns the frames
  /// it cleared (pending ones included). Throws std::invalid_argument for another front end's map.
  int install(PreparedMap&& prepared);

  /// Calls `visit` with the descriptor (a view, valid during the call) and stamp of map frames
  /// [begin, end), in order, under the map's shared lock: queries go on, new frames wait as pending.
  void visitFrames(int begin, int end, const std::function<void(const cv::Mat& descriptor, Stamp stamp)>& visit) const;

  /// Moves pending frames into the map, waiting for running queries.
  void flush();
  /// The same, and reserveAhead(), unless a query (or another writer) holds the map: then returns
  /// false at once, and the frames stay pending.
  bool tryFlush();
  /// Grows the map's storage ahead of need, so that no addFrame pays for a reallocation. Only an
  /// optimisation: when the memory cannot be had, the map stays as it was and frames are added as before.
  void reserveAhead();
  /// Grows the map's storage to hold `frames` frames (at most max_frames) at once, so that adding
  /// frames of known number copies the map at most once.
  void reserve(int frames);

  /**
   * Marks map frame `frame` as the first of a drive that does not continue the frame before it
   * (drive_starts.hpp): the camera's first keyframe after a map loaded, or the first frame of a visit
   * appended to one. Then no test sequence of matchRecent, and no accepted answer's trajectory, holds
   * frames on both sides. Frame 0 marks nothing. Marks last until the map is emptied or replaced (reset(),
   * replace(), install(), which puts a prepared map's own in place). Throws std::invalid_argument for a
   * negative frame.
   */
  void markDriveStart(int frame);
  /// The drive starts marked, sorted.
  std::vector<int> driveStarts() const;

  /// A consistent look at the map.
  struct MapState {
    int frames = 0;
    int pending = 0;
    std::size_t memory_bytes = 0;
    int descriptor_size = 0;
    int linked_frames = 0;  ///< PlaceLinks::linkedFrames()
    Stamp first_stamp;
    Stamp last_stamp;
  };
  MapState state() const;

  /// Replaces the map's place links by `links` (a map database's, read with its frames): for a map
  /// filled frame by frame. Throws std::invalid_argument, leaving the links as they were, for a link
  /// to a frame the map does not hold.
  void linkPlaces(const std::vector<PlaceLink>& links);
  /// The place links among map frames [0, frames), as PlaceLinks::asLinks() gives them: for a copy of the map.
  std::vector<PlaceLink> placeLinks(int frames) const { return links_.asLinks(frames); }
  /// The links by which an accepted answer put map frame `frame` in the place of map frame `reference`
  /// (PlaceLinks::linksOfClosure()), for forgetPlaceLinks() when the robot's back end refused it.
  std::vector<PlaceLink> linksOfClosure(int frame, int reference) const {
    return links_.linksOfClosure(frame, reference);
  }
  /// Forgets `links` (PlaceLinks::forget()): later answers no longer take their frames for one place.
  void forgetPlaceLinks(const std::vector<PlaceLink>& links) { links_.forget(links); }
  /// The newest map frame stamped `stamp` (a published closure's localised keyframe), or -1.
  int newestFrameStamped(Stamp stamp) const;
  /// From now on, logs the links accepted answers make until takeUnsavedLinks() (for a map database).
  void keepUnsavedLinks() { links_.keepUnsaved(); }
  /// The links accepted answers made since the last call (PlaceLinks::takeUnsaved()); a map put in
  /// place (install(), reset()) drops those of the map it replaced.
  std::vector<PlaceLink> takeUnsavedLinks() { return links_.takeUnsaved(); }

  /// Throws std::invalid_argument naming `method` unless it is one a query can use ("" is the default
  /// method): a request can be refused before its images are described.
  void requireMethod(const std::string& method) const { matcherFor(method); }

  const Parameters& parameters() const { return params_; }
  const DescriptorExtractor& extractor() const { return extractor_; }
  const RecognizerParams& recognizerParameters() const { return recognizer_; }

 private:
  struct PendingFrame {
    cv::Mat descriptor;
    Stamp stamp;
  };

  const SequenceMatcher& matcherFor(const std::string& method) const;
  /// match() of a test sequence that holds the keyframes of `images` images (-1: its frames were given
  /// as they are), which a sequence longer than the map is told in.
  PlaceAnswer matchSequence(SequenceView test_sequence, const std::string& method, MatchExplanation* explanation,
                            int images);
  /// The repeated-view rule on the keyframes' scale as it stands, taken under their lock; the caller
  /// holds the map's, so that the scale is that of the map it reads.
  RepeatedViews repeatedViews() const;
  /// The map's frames; throws std::invalid_argument when there are none. The caller holds map_mutex_.
  int framesToSearchLocked() const;
  /// Test frames that are the map's own: frames [first, first + count) of `map`, the whole map.
  struct MapFrames {
    SequenceView map;
    int first = 0;
  };
  PlaceAnswer answer(SequenceView reference, SequenceView query, const std::string& method,
                     MatchExplanation* explanation, const MapFrames* map_frames = nullptr) const;
  /// Moves pending frames into the map; the caller holds map_mutex_ exclusively. When an append
  /// throws, the frames not yet in the map stay pending.
  void flushLocked();
  /// kTooSimilar or kSeenRecently, the frame skipped by the keyframe rule, when `descriptor` is no
  /// keyframe; nullopt for a keyframe. The caller holds keyframes_mutex_.
  std::optional<FrameAdmission> notAKeyframeLocked(const cv::Mat& descriptor);
  /// A keyframe joins the trail and the keyframe rule; the caller holds keyframes_mutex_.
  FrameAdmission appendToTrailLocked(const cv::Mat& descriptor, Stamp stamp);
  /// keyframes_.keep() of an admitted frame, or of one a full map dropped; the caller holds
  /// keyframes_mutex_.
  void keepKeyframeLocked(const cv::Mat& descriptor);
  /// reserveAhead(); the caller holds map_mutex_ exclusively.
  void reserveAheadLocked();
  /// Frames of spare storage a map gets ahead of need.
  int spareFrames() const;
  /// Drops the first `stored` pending frames, which the map now holds.
  void forgetStored(std::size_t stored);
  /// addDescriptor without the keyframe bookkeeping.
  FrameAdmission append(const cv::Mat& descriptor, Stamp stamp);

  Parameters params_;
  RecognizerParams recognizer_;
  DescriptorExtractor extractor_;
  QueryStop stop_;  // before the matchers, which point to it
  PlaceLinks links_;  // the same; its own lock (continuous mode links while queries read)
  mutable std::mutex trail_mutex_;  // held only to append to the trail or copy from it
  Trail trail_;
  std::map<std::string, std::unique_ptr<SequenceMatcher>> matchers_;

  // Held while a frame is offered, so that frames are decided and added one at a time, in order.
  mutable std::mutex keyframes_mutex_;
  AppearanceKeyframes keyframes_;
  // False while the rule's newest keyframe is a frame a full map dropped: no answer is about its place.
  bool newest_keyframe_in_map_ = true;

  // Read by queries under a shared lock, written under an exclusive one.
  mutable std::shared_mutex map_mutex_;
  DescriptorSequence map_;
  std::atomic<int> map_frames_{0};  // map_.size(), readable without the map lock
  int reserved_frames_ = 0;         // under map_mutex_
  std::vector<int> drive_starts_;   // under map_mutex_; sorted (drive_starts.hpp)
  // MRS's rows of the difference matrix for the newest frames, for matchRecent; emptied with the map.
  // Made once the parameters are validated.
  std::unique_ptr<RecentRows> recent_rows_;

  // Under pending_mutex_, held for a few instructions only. frames_admitted_ counts the map and the
  // pending frames in one place, so that a frame arriving while a flush has emptied the buffer but not
  // yet grown the map cannot push the map past max_frames.
  mutable std::mutex pending_mutex_;
  std::vector<PendingFrame> pending_;
  int frames_admitted_ = 0;
};

}  // namespace mrs_vpr

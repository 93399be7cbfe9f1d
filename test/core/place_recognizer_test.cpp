#include <atomic>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "mrs_vpr/drive_starts.hpp"
#include "mrs_vpr/place_recognizer.hpp"
#include "mrs_vpr/synthetic_route.hpp"
#include "support/route_fixture.hpp"

namespace mrs_vpr {
namespace {

using testing_support::globalSearchParams;
using testing_support::routeParameters;
using testing_support::within;

/// The recognizer takes images, not descriptors.
const SyntheticRoute& route() { return testing_support::standardRouteImages(); }

std::vector<cv::Mat> queryImages(int first, int count) {
  return {route().query.begin() + first, route().query.begin() + first + count};
}

/// A recognizer whose map is the route's reference traversal, stamped 100 + frame / 10.
void mapReference(PlaceRecognizer& recognizer) {
  for (std::size_t i = 0; i < route().reference.size(); ++i) {
    ASSERT_EQ(recognizer.addFrame(route().reference[i], Stamp::fromNanoseconds(100'000'000'000 + 100'000'000 * i)),
              FrameAdmission::kAdmitted);
  }
}

std::string errorOf(const std::function<void()>& call) {
  try {
    call();
  } catch (const std::invalid_argument& error) {
    return error.what();
  }
  return "(no error)";
}

TEST(PlaceRecognizer, DefaultConstructedWithTheDocumentedDefaults) {
  const PlaceRecognizer recognizer;
  EXPECT_EQ(recognizer.size(), 0);
  EXPECT_EQ(recognizer.parameters().sequence.accept_threshold, SequenceParams{}.accept_threshold);
  EXPECT_EQ(recognizer.recognizerParameters().default_method, "mrs");
  EXPECT_EQ(recognizer.parameters().descriptor.type, "hog");
  EXPECT_EQ(recognizer.describe(route().reference[0]).total(), 756U);  // 7 x 3 blocks of 4 cells x 9 bins.
}

TEST(PlaceRecognizer, FindsAndAcceptsAStretchOfTheMappedRouteWithBothMethods) {
  PlaceRecognizer recognizer(globalSearchParams());
  mapReference(recognizer);
  EXPECT_EQ(recognizer.size(), 600);
  const int first = 100;
  const int count = 150;  // One coarser level for mrs.
  const int truth = route().query_to_reference[first + count - 1];
  for (const std::string method : {"", "mrs", "seqslam"}) {
    const PlaceAnswer answer = recognizer.match(queryImages(first, count), method);
    EXPECT_TRUE(within(answer.match.reference_index, truth, 3)) << method << ": " << answer.match.reference_index;
    EXPECT_TRUE(answer.match.accepted) << method << ": confidence " << answer.match.confidence;
    EXPECT_EQ(answer.reference_stamp.nanoseconds(), 100'000'000'000 + 100'000'000LL * answer.match.reference_index);
    EXPECT_EQ(answer.query_length, count);
    EXPECT_EQ(answer.method, method.empty() ? "mrs" : method);
  }
}

/// Then the second traversal's frames 100..249 (map frames 600..749), frame i stamped 1000 + i s.
void mapRevisit(PlaceRecognizer& recognizer) {
  for (int i = 100; i < 250; ++i) {
    recognizer.addFrame(route().query[static_cast<std::size_t>(i)], Stamp::fromSecondsAndNanoseconds(1000 + i, 0));
  }
}

TEST(PlaceRecognizer, MatchRecentSearchesOnlyOlderFramesBeyondTheExclusion) {
  RecognizerParams limits;
  limits.recent_exclusion = 50;
  PlaceRecognizer recognizer(globalSearchParams(), limits);
  mapReference(recognizer);
  mapRevisit(recognizer);
  const PlaceAnswer answer = recognizer.matchRecent(150, "seqslam");
  EXPECT_TRUE(within(answer.match.reference_index, route().query_to_reference[249], 3)) << answer.match.reference_index;
  EXPECT_LT(answer.match.reference_index, 750 - 150 - 50);  // Only [0, 550) is searched.
  EXPECT_EQ(answer.newest_stamp, Stamp::fromSecondsAndNanoseconds(1249, 0));
}

TEST(PlaceRecognizer, MatchRecentEndingAtAnOlderFrameSearchesOnlyFramesOlderStill) {
  RecognizerParams limits;
  limits.recent_exclusion = 50;
  PlaceRecognizer recognizer(globalSearchParams(), limits);
  mapReference(recognizer);
  mapRevisit(recognizer);
  // Map frames 600..699 are the second traversal's 100..199; the 50 frames after them are not used.
  const PlaceAnswer answer = recognizer.matchRecent(100, "seqslam", nullptr, 700);
  EXPECT_TRUE(within(answer.match.reference_index, route().query_to_reference[199], 3)) << answer.match.reference_index;
  EXPECT_LT(answer.match.reference_index, 700 - 100 - 50);
  EXPECT_EQ(answer.localised_stamp, Stamp::fromSecondsAndNanoseconds(1199, 0));
  EXPECT_EQ(answer.newest_stamp, Stamp::fromSecondsAndNanoseconds(1199, 0));
  EXPECT_NE(errorOf([&] { recognizer.matchRecent(100, "seqslam", nullptr, 751); }).find("the map holds 750 frames"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { recognizer.matchRecent(100, "seqslam", nullptr, 60); }).find("before frame 60"),
            std::string::npos);
  // -1 is the newest frame; any other negative end is a mistake, not the newest frame too.
  EXPECT_EQ(errorOf([&] { recognizer.matchRecent(100, "seqslam", nullptr, -5); }),
            "a test sequence cannot end at frame -5 (-1: after the newest frame)");
}

// The route's one traversal, declared two drives at map frame 300 (drive_starts.hpp): an answer whose
// trajectory runs across the junction is not accepted, whichever method, and a test sequence of the
// map's own frames across it is refused; answers on either side stand.
TEST(PlaceRecognizer, NoAnswerAndNoTestSequenceRunsAcrossTheJunctionOfTwoDrives) {
  RecognizerParams limits;
  limits.recent_exclusion = 50;
  PlaceRecognizer recognizer(globalSearchParams(), limits);
  mapReference(recognizer);
  recognizer.markDriveStart(300);
  const int count = 150;
  for (const std::string method : {"mrs", "seqslam"}) {
    int across = 0;
    int beside = 0;
    for (int first = 0; first + count <= 400; first += 50) {
      const PlaceAnswer answer = recognizer.match(queryImages(first, count), method);
      const int truth = route().query_to_reference[first + count - 1];
      const bool crosses = route().query_to_reference[first] < 300 && truth >= 300;
      ASSERT_TRUE(within(answer.match.reference_index, truth, 3)) << method << " " << first;
      EXPECT_EQ(answer.match.across_drives, crosses) << method << " " << first;
      EXPECT_EQ(answer.match.accepted, !crosses) << method << " " << first << ": " << answer.verdict;
      if (crosses) {
        EXPECT_EQ(answer.verdict.rfind("not accepted: the answer's trajectory runs across the junction of two", 0), 0U);
      }
      (crosses ? across : beside) += 1;
    }
    EXPECT_GE(across, 2) << method;
    EXPECT_GE(beside, 2) << method;
  }
  // The per-frame protocol judges each frame's answer so too (the map's own frames 250..349 as the
  // traversal, in sequences long enough to be accepted on the generated route).
  Parameters longer = globalSearchParams();
  longer.sequence.sequence_length = 30;
  PlaceRecognizer per_frame(longer);
  mapReference(per_frame);
  per_frame.markDriveStart(300);
  DescriptorSequence traversal(per_frame.extractor().size());
  for (int frame = 250; frame < 350; ++frame) traversal.append(per_frame.describe(route().reference[frame]));
  const std::vector<Match> every_frame = per_frame.matchEveryFrame(traversal.view(), "seqslam");
  int refused = 0;
  int accepted = 0;
  for (std::size_t frame = 0; frame < every_frame.size(); ++frame) {
    const Match& match = every_frame[frame];
    const FrameRange path =
        trajectoryFrames(match, sequenceRowsFor(static_cast<int>(frame), per_frame.parameters().sequence));
    if (match.accepted) EXPECT_TRUE(path.end <= 300 || path.begin >= 300) << frame;
    refused += match.across_drives ? 1 : 0;
    accepted += match.accepted ? 1 : 0;
  }
  EXPECT_GE(refused, 20);
  EXPECT_GE(accepted, 30);
  mapRevisit(recognizer);  // map frames 600..749: the second traversal's 100..249
  recognizer.markDriveStart(610);
  EXPECT_EQ(recognizer.driveStarts(), (std::vector<int>{300, 610}));
  EXPECT_EQ(errorOf([&] { recognizer.matchRecent(150); }),
            "a test sequence of map frames [600, 750) runs across the start of a drive at frame 610 (a map was "
            "loaded, as by a node started on its database or ~load_map, or a visit appended, before it): the "
            "junction of two drives is no place; ask about at most 140 frames, or about 150 once the drive holds "
            "that many");
  EXPECT_TRUE(within(recognizer.matchRecent(140).match.reference_index, route().query_to_reference[249], 3));
  recognizer.reset();
  EXPECT_TRUE(recognizer.driveStarts().empty());
}

// A bag played twice without a reset maps its route twice, at the same times with the same views: each frame of
// the second pass finds its own first pass, which is no loop closure. The same frames on a clock of
// their own (a clock reset), and another traversal on the same clock that is elsewhere at those times
// (simulated time starts at 0 every run), are loop closures.
TEST(PlaceRecognizer, AFrameThatFindsItselfIsNoLoopClosure) {
  RecognizerParams limits;
  limits.recent_exclusion = 50;
  struct Case {
    const char* name;
    const std::vector<cv::Mat>* frames;
    int first;
    std::int64_t start_ns;
    std::int64_t step_ns;
    bool accepted;
  };
  constexpr std::int64_t kMapStart = 100'000'000'000;  // mapReference: 100 + frame / 10 s
  constexpr std::int64_t kStep = 100'000'000;
  for (const Case& pass : {
           Case{"the same bag again", &route().reference, 0, kMapStart, kStep, false},
           // As a camera-rate replay whose second pass keeps other frames than the first: no keyframe of
           // it has a twin in the map, but each lies between two map keyframes in time and shows a view
           // that would not have become a keyframe by them; a little later or earlier.
           Case{"the same bag again, other frames kept", &route().reference, 0, kMapStart + kStep / 2, kStep, false},
           Case{"the same bag again, a little earlier", &route().reference, 0, kMapStart - kStep / 2, kStep, false},
           Case{"the same frames, unstamped", &route().reference, 0, 0, 0, false},
           Case{"the same frames, another clock", &route().reference, 0, 10'000'000'000, kStep, true},
           Case{"another traversal, the same clock, elsewhere", &route().query, 100, kMapStart, kStep, true}}) {
    PlaceRecognizer recognizer(globalSearchParams(), limits);
    mapReference(recognizer);
    for (int i = 0; i < 300; ++i) {
      recognizer.addFrame((*pass.frames)[static_cast<std::size_t>(pass.first + i)],
                          Stamp::fromNanoseconds(pass.start_ns + pass.step_ns * i));
    }
    const PlaceAnswer answer = recognizer.matchRecent(150, "seqslam");
    const int newest = pass.first + 299;
    const int truth = pass.frames == &route().reference ? newest : route().query_to_reference[newest];
    EXPECT_TRUE(within(answer.match.reference_index, truth, 3)) << pass.name << ": " << answer.match.reference_index;
    EXPECT_GT(answer.match.confidence, 3.0F) << pass.name;
    EXPECT_EQ(answer.match.accepted, pass.accepted) << pass.name << ": " << answer.verdict;
    EXPECT_EQ(answer.match.same_recording, !pass.accepted) << pass.name;
    const std::string verdict = pass.accepted ? "accepted"
                                              : "not accepted: the test sequence's keyframes are in the map already, "
                                                "at the same times with the same views";
    EXPECT_EQ(answer.verdict.rfind(verdict, 0), 0U) << pass.name << ": " << answer.verdict;
  }
}

// A map of two sessions, the second begun long after the first ended, and a revisit of the first's
// places stamped between them (bags played out of order): the two sessions' keyframes enclose its
// stamps, but no recording leaves such a gap between two keyframes, and the closures stand.
TEST(PlaceRecognizer, ARevisitStampedBetweenTwoSessionsOfTheMapIsALoopClosure) {
  RecognizerParams limits;
  limits.recent_exclusion = 50;
  PlaceRecognizer recognizer(globalSearchParams(), limits);
  for (int i = 0; i < 600; ++i) {
    const std::int64_t session_start = i < 300 ? 100'000'000'000 : 500'000'000'000;
    ASSERT_EQ(recognizer.addFrame(route().reference[static_cast<std::size_t>(i)],
                                  Stamp::fromNanoseconds(session_start + 100'000'000LL * (i % 300))),
              FrameAdmission::kAdmitted);
  }
  for (int i = 100; i < 300; ++i) {
    recognizer.addFrame(route().query[static_cast<std::size_t>(i)],
                        Stamp::fromNanoseconds(300'000'000'000 + 100'000'000LL * i));
  }
  const PlaceAnswer answer = recognizer.matchRecent(150, "seqslam");
  EXPECT_TRUE(within(answer.match.reference_index, route().query_to_reference[299], 3)) << answer.match.reference_index;
  EXPECT_TRUE(answer.match.accepted) << answer.verdict;
  EXPECT_FALSE(answer.match.same_recording);
}

/// A recognizer whose map is the route's reference traversal, keyframed at the defaults, that asks after
/// each new keyframe of a revisit as continuous mode does and counts its answers.
class ContinuousRevisit {
 public:
  struct Counts {
    int right = 0;
    int wrong = 0;
    int turned_back = 0;
    int turned_back_right = 0;  // of those, answers that named the right place
  };

  /// Asks about the newest `sequence_length` keyframes, localising the newest (routeParameters()).
  /// `per_frame_length`: the sequences of the per-frame protocol (everyFrame).
  explicit ContinuousRevisit(int sequence_length = 20, int per_frame_length = 10)
      : recognizer_(parameters(per_frame_length), limits()), sequence_length_(sequence_length) {
    for (int frame = 0; frame < 600; ++frame) offer(frame);
  }

  /// Drives over the reference frames `frames` (the same images again, on a later clock).
  Counts drive(const std::vector<int>& frames) {
    Counts counts;
    for (int frame : frames) {
      if (!offer(frame)) continue;
      const PlaceAnswer answer = recognizer_.matchRecent(sequence_length_);
      const int truth = place_of_keyframe_[static_cast<std::size_t>(answer.localised_frame)];
      const int found = place_of_keyframe_[static_cast<std::size_t>(answer.match.reference_index)];
      if (answer.match.turned_back) {
        ++counts.turned_back;
        counts.turned_back_right += within(found, truth, 5) ? 1 : 0;
        EXPECT_FALSE(answer.match.accepted);
        EXPECT_EQ(answer.verdict.rfind("not accepted: the test sequence returns to a place it passed", 0), 0U)
            << answer.verdict;
      }
      if (!answer.match.accepted) continue;
      ++(within(found, truth, 5) ? counts.right : counts.wrong);
    }
    return counts;
  }

  /// A question about the newest `frames` keyframes.
  PlaceAnswer ask(int frames, const std::string& method) { return recognizer_.matchRecent(frames, method); }
  /// The per-frame protocol over the reference frames `frames`, described as a traversal of their own.
  std::vector<Match> everyFrame(const std::vector<int>& frames, const std::string& method) {
    DescriptorSequence traversal(recognizer_.extractor().size());
    for (int frame : frames) traversal.append(recognizer_.describe(route().reference[static_cast<std::size_t>(frame)]));
    return recognizer_.matchEveryFrame(traversal.view(), method);
  }

  /// Drives `frames` frames over ground the route does not hold (views of noise), as a robot does
  /// between two visits of a stretch.
  void driveElsewhere(int frames) {
    cv::RNG rng(static_cast<std::uint64_t>(place_of_keyframe_.size()));
    for (int i = 0; i < frames; ++i) {
      stamp_ns_ += 100'000'000;
      cv::Mat view(route().reference[0].size(), route().reference[0].type());
      rng.fill(view, cv::RNG::UNIFORM, 0, 256);
      cv::GaussianBlur(view, view, cv::Size(0, 0), 2.0);
      if (recognizer_.addFrame(view, Stamp::fromNanoseconds(stamp_ns_)) == FrameAdmission::kAdmitted) {
        place_of_keyframe_.push_back(-1000);  // no place of the route
      }
    }
  }

 private:
  static Parameters parameters(int per_frame_length) {
    Parameters params = routeParameters();
    params.sequence.sequence_length = per_frame_length;
    return params;
  }

  static RecognizerParams limits() {
    RecognizerParams limits;
    limits.recent_exclusion = 50;
    return limits;
  }

  bool offer(int frame) {
    stamp_ns_ += 100'000'000;
    const cv::Mat& image = route().reference[static_cast<std::size_t>(frame)];
    if (recognizer_.addFrame(image, Stamp::fromNanoseconds(stamp_ns_)) != FrameAdmission::kAdmitted) return false;
    place_of_keyframe_.push_back(frame);
    return true;
  }

  PlaceRecognizer recognizer_;
  int sequence_length_;
  std::vector<int> place_of_keyframe_;  // the reference frame each map keyframe shows
  std::int64_t stamp_ns_ = 100'000'000'000;
};

std::vector<int> framesFromTo(int first, int last) {
  std::vector<int> frames;
  for (int frame = first; frame != last; frame += first < last ? 1 : -1) frames.push_back(frame);
  frames.push_back(last);
  return frames;
}

// A revisit that drives part of the route, backs up over part of it and drives on again: a sequence
// that holds both sides of the turn fits a forward trajectory by its way out only, which leads on past
// the turn (without the rule, 5 answers about the way back were accepted 17 to 25 frames ahead). None
// is accepted, and the verdict says why; the way out's answers stand, also those about its last
// keyframes asked after the turn, and so do those of the way forward again, which shows the way back's
// places again in reverse but the way out's in order.
TEST(PlaceRecognizer, ARevisitThatTurnsBackIsNotPlacedWhereItsWayOutLeads) {
  ContinuousRevisit revisit;
  const ContinuousRevisit::Counts out = revisit.drive(framesFromTo(100, 299));
  EXPECT_GT(out.right, 100);
  EXPECT_EQ(out.wrong, 0);
  EXPECT_EQ(out.turned_back, 0);
  const ContinuousRevisit::Counts back = revisit.drive(framesFromTo(298, 200));
  EXPECT_EQ(back.wrong, 0);
  EXPECT_GT(back.turned_back, 0);
  EXPECT_EQ(back.turned_back_right, 0);  // answers about the way out's last keyframes stand
  const ContinuousRevisit::Counts forward_again = revisit.drive(framesFromTo(201, 399));
  EXPECT_GT(forward_again.right, 50);
  EXPECT_EQ(forward_again.wrong, 0);
  EXPECT_LT(forward_again.turned_back, 10);
}

// The same with sequences longer than the keyframes the rule judges (RepeatedViews::kMaxJudged): the
// localised keyframe, the newest here, is judged whatever the sequence's length.
TEST(PlaceRecognizer, ALongSequenceThatTurnsBackIsNotPlacedWhereItsWayOutLeads) {
  for (const int length : {70, 100}) {
    ContinuousRevisit revisit(length);
    const ContinuousRevisit::Counts out = revisit.drive(framesFromTo(100, 299));
    EXPECT_GT(out.right, 50) << length;
    EXPECT_EQ(out.wrong, 0) << length;
    EXPECT_EQ(out.turned_back, 0) << length;
    const ContinuousRevisit::Counts back = revisit.drive(framesFromTo(298, 200));
    EXPECT_EQ(back.wrong, 0) << length;
    EXPECT_GT(back.turned_back, 0) << length;
  }
}

// A robot that drives the same stretch again and again, elsewhere in between, its map growing by each
// visit: from the third visit on the map holds each place twice, once per visit before, and the two
// cost the same. The closures of the second visit link them, so that neither is the other's rival,
// and the third and fourth visits close their loops as the second did (without the links: none).
TEST(PlaceRecognizer, AStretchDrivenAgainAndAgainKeepsClosingItsLoops) {
  ContinuousRevisit revisit;
  revisit.driveElsewhere(60);
  const ContinuousRevisit::Counts second = revisit.drive(framesFromTo(100, 299));
  EXPECT_GT(second.right, 100);
  EXPECT_EQ(second.wrong, 0);
  for (int visit = 3; visit <= 4; ++visit) {
    revisit.driveElsewhere(60);
    const ContinuousRevisit::Counts again = revisit.drive(framesFromTo(100, 299));
    EXPECT_GE(again.right, second.right - 5) << "visit " << visit;
    EXPECT_EQ(again.wrong, 0) << "visit " << visit;
  }
}

// A map that stays as it is (built on an earlier drive): the camera's keyframes join the trail, not the
// map, and questions about the newest of them find the places of a stretch the map holds, and none on
// ground it does not hold.
TEST(PlaceRecognizer, AFixedMapLocalisesTheCamerasKeyframesWithoutGrowing) {
  RecognizerParams limits;
  limits.recent_exclusion = 50;
  PlaceRecognizer recognizer(routeParameters(), limits);
  for (int frame = 0; frame < 600; ++frame) {
    recognizer.addFrame(route().reference[static_cast<std::size_t>(frame)], Stamp::fromNanoseconds(frame + 1));
  }
  const int mapped = recognizer.size();
  std::vector<int> frame_of_keyframe;  // the route frame each trail keyframe shows; -1 elsewhere
  std::int64_t stamp_ns = 1'000'000'000'000;
  const auto offer = [&](const cv::Mat& image, int frame) {
    stamp_ns += 100'000'000;
    if (recognizer.offerToTrail(recognizer.describe(image), Stamp::fromNanoseconds(stamp_ns)) !=
        FrameAdmission::kAdmitted) {
      return false;
    }
    frame_of_keyframe.push_back(frame);
    return true;
  };
  int right = 0;
  int wrong = 0;
  int elsewhere_accepted = 0;
  cv::RNG rng(3);
  for (int i = 0; i < 60; ++i) {  // ground the map does not hold
    cv::Mat view(route().reference[0].size(), route().reference[0].type());
    rng.fill(view, cv::RNG::UNIFORM, 0, 256);
    cv::GaussianBlur(view, view, cv::Size(0, 0), 2.0);
    if (offer(view, -1) && recognizer.trailSize() >= 20) elsewhere_accepted += recognizer.matchTrail(20).match.accepted;
  }
  for (int frame = 100; frame < 300; ++frame) {
    if (!offer(route().reference[static_cast<std::size_t>(frame)], frame)) continue;
    const PlaceAnswer answer = recognizer.matchTrail(20);
    EXPECT_EQ(answer.localised_frame, -1);
    if (!answer.match.accepted) continue;
    const int localised = static_cast<int>(recognizer.trailSize()) - 20 + answer.localised_row;
    const int truth = frame_of_keyframe[static_cast<std::size_t>(localised)];
    ++(truth >= 0 && within(answer.match.reference_index, truth, 5) ? right : wrong);
  }
  EXPECT_EQ(elsewhere_accepted, 0);
  EXPECT_GT(right, 100);
  EXPECT_EQ(wrong, 0);
  EXPECT_EQ(recognizer.size(), mapped);  // the map stayed as it was
  // A question names keyframes the trail holds, and a map large enough.
  EXPECT_NE(errorOf([&] { recognizer.matchTrail(20, "", nullptr, 10000); }).find("the camera has given"),
            std::string::npos);
  PlaceRecognizer empty(routeParameters());
  EXPECT_NE(errorOf([&] { empty.matchTrail(20); }).find("recent_frames 20 is more than the 0 keyframes"),
            std::string::npos);
  for (int frame = 0; frame < 30; ++frame) {
    empty.addToTrail(empty.describe(route().reference[static_cast<std::size_t>(frame)]), Stamp());
  }
  EXPECT_NE(errorOf([&] { empty.matchTrail(20); }).find("the reference map is empty: the camera's keyframes are "
                                                         "localised in a map loaded first"),
            std::string::npos);
}

// A map filled frame by frame (mrs_vpr_eval's, of a map database) takes the links its database kept,
// and refuses a link to a frame it does not hold, keeping those it has.
TEST(PlaceRecognizer, AMapFilledFrameByFrameTakesItsLinksAndRefusesOnesOutsideIt) {
  PlaceRecognizer recognizer(routeParameters());
  for (int frame = 0; frame < 10; ++frame) {
    recognizer.addFrame(route().reference[static_cast<std::size_t>(frame)], Stamp::fromNanoseconds(frame + 1));
  }
  recognizer.linkPlaces({{8, 2}, {9, 3}});  // pending frames among them
  EXPECT_EQ(recognizer.state().linked_frames, 2);
  EXPECT_THROW(recognizer.linkPlaces({{10, 2}}), std::invalid_argument);
  EXPECT_EQ(recognizer.placeLinks(10).size(), 2U);
  recognizer.reset();
  EXPECT_EQ(recognizer.state().linked_frames, 0);
}

// The same judged by both methods over a sequence long enough for MRS's coarser level, whose
// confidence is read on pooled ends: the place linked across visits is no rival of either.
TEST(PlaceRecognizer, BothMethodsTakeAPlaceLinkedAcrossVisitsForNoRival) {
  ContinuousRevisit revisit;
  for (int visit = 2; visit <= 3; ++visit) {
    revisit.driveElsewhere(60);
    revisit.drive(framesFromTo(100, 399));
  }
  const PlaceAnswer mrs = revisit.ask(150, "mrs");
  const PlaceAnswer seqslam = revisit.ask(150, "seqslam");
  EXPECT_TRUE(mrs.match.accepted) << mrs.verdict;
  EXPECT_TRUE(seqslam.match.accepted) << seqslam.verdict;
  EXPECT_EQ(mrs.match.reference_index, seqslam.match.reference_index);
  EXPECT_LT(mrs.match.comparisons, seqslam.match.comparisons / 2);  // MRS searched on a coarser level
}

// And the per-frame protocol, through every method's own path: a traversal of the stretch asked frame by
// frame (30-frame sequences) of a map that holds it three times, linked, has most of its 100 frames
// accepted, as of a map that holds it once (71); without the links, none.
TEST(PlaceRecognizer, ThePerFrameProtocolTakesAPlaceLinkedAcrossVisitsForNoRival) {
  ContinuousRevisit revisit(20, 30);
  for (int visit = 2; visit <= 3; ++visit) {
    revisit.driveElsewhere(60);
    revisit.drive(framesFromTo(100, 399));
  }
  for (const std::string method : {"mrs", "seqslam"}) {
    int accepted = 0;
    for (const Match& match : revisit.everyFrame(framesFromTo(150, 249), method)) accepted += match.accepted ? 1 : 0;
    EXPECT_GT(accepted, 50) << method;
  }
}

// A robot that goes round a small loop again and again shows its places again within a few dozen
// keyframes too, but forwards: its closures stand.
TEST(PlaceRecognizer, ARobotGoingRoundASmallLoopDoesNotTurnBack) {
  ContinuousRevisit revisit;
  std::vector<int> laps;
  for (int lap = 0; lap < 4; ++lap) {
    for (int frame : framesFromTo(100, 149)) laps.push_back(frame);
  }
  const ContinuousRevisit::Counts counts = revisit.drive(laps);
  EXPECT_GT(counts.right, 40);
  EXPECT_EQ(counts.turned_back, 0);
}

// Questions about the newest frames after each new one, as continuous mode asks: once MRS has kept
// their rows (mrs/recent_rows.hpp), its answers are the brute force's; the rows are counted in the
// map's memory and go with a reset.
TEST(PlaceRecognizer, QuestionsAboutTheNewestFramesReadKeptRowsWithTheBruteForcesAnswer) {
  RecognizerParams limits;
  limits.recent_exclusion = 50;
  PlaceRecognizer recognizer(globalSearchParams(), limits);
  mapReference(recognizer);
  const std::size_t map_bytes = recognizer.state().memory_bytes;
  for (int i = 100; i < 160; ++i) {
    recognizer.addFrame(route().query[static_cast<std::size_t>(i)], Stamp::fromSecondsAndNanoseconds(1000 + i, 0));
    if (i < 120) continue;
    const PlaceAnswer mrs = recognizer.matchRecent(20, "mrs");
    const PlaceAnswer brute = recognizer.matchRecent(20, "seqslam");
    EXPECT_EQ(mrs.match.reference_index, brute.match.reference_index) << "frame " << i;
    EXPECT_EQ(mrs.match.accepted, brute.match.accepted) << "frame " << i;
    EXPECT_EQ(mrs.match.confidence, brute.match.confidence) << "frame " << i;
    EXPECT_EQ(mrs.localised_stamp, brute.localised_stamp) << "frame " << i;
  }
  // 20 rows of 4 bytes for each of about 640 map frames, and the room each keeps to grow.
  const std::size_t with_rows = recognizer.state().memory_bytes;
  EXPECT_GE(with_rows, map_bytes + 20 * 4 * 600);
  recognizer.reset();  // The rows go; the empty map holds what any reset map does, room for new frames.
  PlaceRecognizer never_asked(globalSearchParams(), limits);
  never_asked.reset();
  EXPECT_EQ(recognizer.state().memory_bytes, never_asked.state().memory_bytes);
}

TEST(PlaceRecognizer, ACentredAnswerLocalisesTheMiddleFrameAndCarriesItsStamp) {
  Parameters centred = globalSearchParams();
  centred.sequence.alignment = WindowAlignment::kCentred;  // the default
  RecognizerParams limits;
  limits.recent_exclusion = 50;
  PlaceRecognizer recognizer(centred, limits);
  mapReference(recognizer);
  mapRevisit(recognizer);
  // The newest 150 frames are 100..249; the localised one is the middle, 100 + 75.
  const PlaceAnswer answer = recognizer.matchRecent(150, "seqslam");
  EXPECT_EQ(answer.localised_row, 75);
  EXPECT_EQ(answer.localised_stamp, Stamp::fromSecondsAndNanoseconds(1175, 0));
  EXPECT_EQ(answer.newest_stamp, Stamp::fromSecondsAndNanoseconds(1249, 0));
  EXPECT_TRUE(within(answer.match.reference_index, route().query_to_reference[175], 3)) << answer.match.reference_index;
  // A causal answer localises the newest frame.
  Parameters causal = centred;
  causal.sequence.alignment = WindowAlignment::kCausal;
  PlaceRecognizer newest(causal, limits);
  mapReference(newest);
  mapRevisit(newest);
  const PlaceAnswer causal_answer = newest.matchRecent(150, "seqslam");
  EXPECT_EQ(causal_answer.localised_row, 149);
  EXPECT_EQ(causal_answer.localised_stamp, Stamp::fromSecondsAndNanoseconds(1249, 0));
}

TEST(PlaceRecognizer, FramesAtTheCameraRateAreKeyframedAndTheAnswerNamesTheFrameGiven) {
  Parameters centred = globalSearchParams();
  centred.sequence.alignment = WindowAlignment::kCentred;
  PlaceRecognizer recognizer(centred);
  mapReference(recognizer);
  // A camera twice as fast as the map's: each view twice, the second copy never a keyframe.
  DescriptorSequence frames(recognizer.extractor().size());
  for (int i = 100; i < 200; ++i) {
    const cv::Mat descriptor = recognizer.describe(route().query[static_cast<std::size_t>(i)]);
    frames.append(descriptor);
    frames.append(descriptor);
  }
  const PlaceAnswer answer = recognizer.matchKeyframesOf(frames, "seqslam");
  ASSERT_GE(answer.localised_row, 0);
  EXPECT_EQ(answer.localised_row % 2, 0) << "a repeated frame cannot be the keyframe localised";
  EXPECT_LE(answer.query_length, 100);
  const int localised = 100 + answer.localised_row / 2;
  EXPECT_TRUE(within(answer.match.reference_index, route().query_to_reference[static_cast<std::size_t>(localised)], 3))
      << answer.match.reference_index << " for frame " << localised;
  // A view that never changes holds a single keyframe.
  DescriptorSequence standing(recognizer.extractor().size());
  for (int i = 0; i < 10; ++i) standing.append(frames.descriptorRow(0));
  EXPECT_NE(errorOf([&] { recognizer.matchKeyframesOf(standing); }).find("hold fewer than 2 keyframes"),
            std::string::npos);
  // Longer than the map: told in the images given and the keyframes they hold, not the one as the other.
  PlaceRecognizer small(centred);
  for (int i = 0; i < 30; ++i) small.addFrame(route().reference[static_cast<std::size_t>(i)]);
  const std::string map_size = " but the reference map only " + std::to_string(small.size()) + " frames";
  EXPECT_EQ(errorOf([&] { small.matchKeyframesOf(frames); }),
            "the test sequence's 200 images hold " + std::to_string(answer.query_length) + " keyframes" + map_size);
  EXPECT_EQ(errorOf([&] { small.match(frames); }), "the test sequence has 200 frames" + map_size);
}

TEST(PlaceRecognizer, BadRequestsAreRefusedWithAMessageAndTheRecognizerStaysUsable) {
  PlaceRecognizer recognizer(routeParameters());
  EXPECT_NE(errorOf([&] { recognizer.match(queryImages(0, 10)); }).find("reference map is empty"), std::string::npos);
  mapReference(recognizer);
  EXPECT_NE(errorOf([&] { recognizer.match(queryImages(0, 10), "fast"); }).find("unknown method 'fast'"),
            std::string::npos);
  EXPECT_EQ(errorOf([&] { recognizer.requireMethod("fast"); }), "unknown method 'fast': use 'mrs' or 'seqslam'");
  for (const std::string method : {"", "mrs", "seqslam"}) EXPECT_NO_THROW(recognizer.requireMethod(method));
  EXPECT_NE(errorOf([&] { recognizer.match(queryImages(0, 1)); }).find("at least 2 images"), std::string::npos);
  // A NUL in the method used to cut the message short on its way to the user.
  const std::string with_nul = errorOf([&] { recognizer.match(queryImages(0, 10), std::string("m\0rs", 4)); });
  EXPECT_EQ(with_nul.find('\0'), std::string::npos);
  EXPECT_NE(with_nul.find("unknown method 'm\\x00rs': use 'mrs' or 'seqslam'"), std::string::npos) << with_nul;
  EXPECT_NE(errorOf([&] { recognizer.match({route().query[0], cv::Mat()}); }).find("image 1 of the test sequence"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { recognizer.matchRecent(1); }).find("at least 2"), std::string::npos);
  // A request larger than any int is reported as it was made, not wrapped or clamped.
  EXPECT_NE(errorOf([&] { recognizer.matchRecent(2147483647LL); }).find("recent_frames 2147483647 is more than"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { recognizer.matchRecent(300); }).find("leaves 200 searchable frames"), std::string::npos);
  EXPECT_NE(errorOf([&] { recognizer.addDescriptor(cv::Mat(1, 10, CV_8U)); }).find("2048 continuous bytes"),
            std::string::npos);
  // Still answers.
  EXPECT_GE(recognizer.match(queryImages(0, 20)).match.reference_index, 0);
}

TEST(PlaceRecognizer, InvalidParametersAreRefusedAtConstruction) {
  RecognizerParams limits;
  limits.max_frames = 1;
  EXPECT_THROW(PlaceRecognizer(routeParameters(), limits), std::invalid_argument);
  limits = RecognizerParams{};
  limits.default_method = "fast";
  EXPECT_THROW(PlaceRecognizer(routeParameters(), limits), std::invalid_argument);
  Parameters params = routeParameters();
  params.mrs.hypotheses = 1;
  EXPECT_THROW(PlaceRecognizer{params}, std::invalid_argument);
}

TEST(PlaceRecognizer, CapacityDropsFramesBeyondMaxFramesAndResetEmpties) {
  RecognizerParams limits;
  limits.max_frames = 5;
  PlaceRecognizer recognizer(routeParameters(), limits);
  for (int i = 0; i < 5; ++i) EXPECT_EQ(recognizer.addFrame(route().reference[i]), FrameAdmission::kAdmitted);
  EXPECT_EQ(recognizer.addFrame(route().reference[5]), FrameAdmission::kMapFull);
  EXPECT_EQ(recognizer.size(), 5);
  EXPECT_EQ(recognizer.reset(), 5);
  EXPECT_EQ(recognizer.size(), 0);
  EXPECT_EQ(recognizer.addFrame(route().reference[0]), FrameAdmission::kAdmitted);
}

TEST(PlaceRecognizer, AFullMapDropsOnlyTheFramesThatWouldHaveBeenKeyframes) {
  // A full map went on comparing each camera frame with its last keyframe, so that a robot standing at
  // a new place had every frame counted as a keyframe dropped.
  RecognizerParams limits;
  limits.max_frames = 20;
  PlaceRecognizer recognizer(routeParameters(), limits);
  std::size_t next = 0;
  while (recognizer.size() < limits.max_frames) {
    recognizer.offerDescriptor(recognizer.describe(route().reference[next++]));
  }
  const cv::Mat standing = recognizer.describe(route().reference[next + 100]);
  EXPECT_EQ(recognizer.offerDescriptor(standing), FrameAdmission::kMapFull);
  for (int i = 0; i < 5; ++i) {
    EXPECT_EQ(recognizer.offerDescriptor(standing), FrameAdmission::kTooSimilar) << i;
    // Not standing at the map's newest keyframe, whose closures the node would restate: the map holds
    // no frame of this place.
    EXPECT_FALSE(recognizer.lastFrameStood()) << i;
  }
  EXPECT_EQ(recognizer.offerDescriptor(recognizer.describe(route().reference[next + 200])), FrameAdmission::kMapFull);
  // Emptied, the map takes the view at once: the rule starts over with it, and a camera standing there
  // stands at a keyframe of the map.
  recognizer.reset();
  EXPECT_EQ(recognizer.offerDescriptor(standing), FrameAdmission::kAdmitted);
  EXPECT_EQ(recognizer.offerDescriptor(standing), FrameAdmission::kTooSimilar);
  EXPECT_TRUE(recognizer.lastFrameStood());
}

// A map loaded while queries run: each query sees the old map or the new one, never a part of either.
TEST(PlaceRecognizer, ReplaceExchangesTheWholeMapInOneStep) {
  PlaceRecognizer recognizer(routeParameters());
  mapReference(recognizer);
  const int whole = recognizer.size();
  std::vector<cv::Mat> all;
  std::vector<Stamp> stamps;
  recognizer.visitFrames(0, whole, [&](const cv::Mat& descriptor, Stamp stamp) {
    all.push_back(descriptor.clone());
    stamps.push_back(stamp);
  });
  const std::vector<cv::Mat> part(all.begin(), all.begin() + 200);
  const std::vector<Stamp> part_stamps(stamps.begin(), stamps.begin() + 200);
  // A bad frame, or one stamp short: refused, and the map is as it was.
  std::vector<cv::Mat> bad = part;
  bad[100] = cv::Mat(1, 3, CV_8UC1);
  EXPECT_NE(errorOf([&] { recognizer.replace(bad, part_stamps); }).find("descriptor"), std::string::npos);
  EXPECT_NE(errorOf([&] { recognizer.replace(part, stamps); }).find(std::to_string(whole) + " stamps for 200"),
            std::string::npos);
  EXPECT_EQ(recognizer.size(), whole);

  std::atomic<bool> done{false};
  std::atomic<int> partial{0};
  std::atomic<int> samples{0};
  std::thread reader([&] {
    while (!done) {
      const int size = recognizer.state().frames;
      if (size != whole && size != 200) ++partial;
      ++samples;
    }
  });
  // At least 20 rounds, and on until the reader has looked often enough to have seen a partial map.
  for (int round = 0; round < 20 || (samples < 1000 && round < 100000); ++round) {
    recognizer.replace(part, part_stamps);
    recognizer.replace(all, stamps);
  }
  done = true;
  reader.join();
  EXPECT_GE(samples, 1000);
  EXPECT_EQ(partial, 0);
  // The map answers as the one built frame by frame.
  const PlaceAnswer answer = recognizer.match(queryImages(150, 30));
  EXPECT_TRUE(within(answer.match.reference_index, route().query_to_reference[150 + answer.localised_row], 3))
      << answer.match.reference_index;
}

TEST(PlaceRecognizer, ReserveHoldsAKnownNumberOfFramesWithoutSpareCapacity) {
  RecognizerParams limits;
  limits.max_frames = 300;
  PlaceRecognizer recognizer(routeParameters(), limits);
  const std::size_t empty = recognizer.state().memory_bytes;
  recognizer.reserve(200);
  const std::size_t reserved = recognizer.state().memory_bytes;
  const auto frame_bytes = static_cast<std::size_t>(recognizer.extractor().size()) + sizeof(double);
  const std::size_t coarse_bytes = 256;  // at most, a frame, of MRS's kept compact cells (strides 1 to 8)
  EXPECT_GE(reserved - empty, 200 * frame_bytes);
  EXPECT_LT(reserved - empty, 200 * (frame_bytes + coarse_bytes));
  // Filling what was reserved allocates nothing more.
  for (int i = 0; i < 200; ++i) ASSERT_EQ(recognizer.addFrame(route().reference[i]), FrameAdmission::kAdmitted);
  EXPECT_EQ(recognizer.state().memory_bytes, reserved);
  // Never beyond max_frames.
  recognizer.reserve(1000000);
  EXPECT_LT(recognizer.state().memory_bytes - empty, 300 * (frame_bytes + coarse_bytes));
}

/// The descriptors and stamps of the first `count` frames a recognizer maps of the route's reference.
std::pair<std::vector<cv::Mat>, std::vector<Stamp>> mappedFrames(int count) {
  PlaceRecognizer built(routeParameters());
  mapReference(built);
  std::pair<std::vector<cv::Mat>, std::vector<Stamp>> frames;
  built.visitFrames(0, count, [&](const cv::Mat& descriptor, Stamp stamp) {
    frames.first.push_back(descriptor.clone());
    frames.second.push_back(stamp);
  });
  return frames;
}

// A loaded map leaves room for the camera's next frames: the first of them copied the whole map on
// the camera's thread (0.2-0.8 s for 60k frames), the next growth being reserveAhead()'s.
TEST(PlaceRecognizer, AReplacedMapTakesTheCamerasNextFramesWithoutGrowing) {
  const auto [descriptors, stamps] = mappedFrames(300);
  PlaceRecognizer recognizer(routeParameters());
  recognizer.replace(descriptors, stamps);
  const std::size_t loaded = recognizer.state().memory_bytes;
  int added = 0;
  for (int i = 300; i < 600; ++i) {
    if (recognizer.addFrame(route().reference[static_cast<std::size_t>(i)]) == FrameAdmission::kAdmitted) ++added;
  }
  EXPECT_GT(added, 200);
  EXPECT_EQ(recognizer.size(), 300 + added);
  EXPECT_EQ(recognizer.state().memory_bytes, loaded);
  // The room stops at max_frames.
  RecognizerParams limits;
  limits.max_frames = 310;
  PlaceRecognizer limited(routeParameters(), limits);
  limited.replace(descriptors, stamps);
  const auto frame_bytes = static_cast<std::size_t>(limited.extractor().size()) + sizeof(double);
  EXPECT_LT(limited.state().memory_bytes, 310 * (frame_bytes + 256));
}

// A map read from a file is built frame by frame (PersistentMap::load), never given more frames than
// it was prepared for, and tells whether a second read of the file gave the same frames.
TEST(PlaceRecognizer, AMapPreparedFrameByFrameHoldsWhatItWasGivenAndNoMore) {
  const auto [descriptors, stamps] = mappedFrames(3);
  PlaceRecognizer recognizer(routeParameters());
  PlaceRecognizer::PreparedMap prepared = recognizer.prepareMap(2);
  prepared.append(descriptors[0], stamps[0]);
  prepared.append(descriptors[1], stamps[1]);
  EXPECT_THROW(prepared.append(descriptors[2], stamps[2]), std::invalid_argument);
  EXPECT_THROW(recognizer.prepareMap(1).append(cv::Mat(1, 3, CV_8UC1), stamps[0]), std::invalid_argument);
  EXPECT_TRUE(prepared.holds(1, descriptors[1], stamps[1]));
  EXPECT_FALSE(prepared.holds(1, descriptors[1], stamps[0]));  // another stamp
  EXPECT_FALSE(prepared.holds(1, descriptors[0], stamps[1]));  // other bytes
  EXPECT_FALSE(prepared.holds(2, descriptors[2], stamps[2]));  // beyond its frames
  EXPECT_EQ(recognizer.install(std::move(prepared)), 0);
  EXPECT_EQ(recognizer.size(), 2);
  RecognizerParams limits;
  limits.max_frames = 2;
  EXPECT_THROW(PlaceRecognizer(routeParameters(), limits).prepareMap(3), std::invalid_argument);
}

// A map built aside (replace(), a load) takes its frames as its keyframes: the camera's next frame is
// compared with the map's last one, so a view that has not changed is no new keyframe after a load.
TEST(PlaceRecognizer, AReplacedMapsFramesAreTheKeyframesTheNextFrameIsComparedWith) {
  const auto [descriptors, stamps] = mappedFrames(20);
  PlaceRecognizer recognizer(routeParameters());
  recognizer.replace(descriptors, stamps);
  const Stamp next = Stamp::fromNanoseconds(stamps.back().nanoseconds() + 100'000'000);
  EXPECT_EQ(recognizer.offerDescriptor(descriptors.back(), next), FrameAdmission::kTooSimilar);
  EXPECT_EQ(recognizer.size(), 20);
  PlaceRecognizer::PreparedMap prepared = recognizer.prepareMap(2);
  prepared.append(descriptors[0], stamps[0]);
  prepared.append(descriptors[1], stamps[1]);
  recognizer.install(std::move(prepared));
  EXPECT_EQ(recognizer.offerDescriptor(descriptors[1], next), FrameAdmission::kTooSimilar);
  EXPECT_EQ(recognizer.size(), 2);
}

// prepareMap(frames) takes a count read from a file: a negative one is refused, rather than a map
// prepared for no frame that refuses each one the file then gives.
TEST(PlaceRecognizer, AMapPreparedForANegativeNumberOfFramesIsRefused) {
  const PlaceRecognizer recognizer(routeParameters());
  const auto messageOf = [](const PlaceRecognizer& refusing, int frames) -> std::string {
    try {
      refusing.prepareMap(frames);
    } catch (const std::invalid_argument& error) {
      return error.what();
    }
    return "(no error)";
  };
  EXPECT_EQ(messageOf(recognizer, -1), "a map cannot hold -1 frames");  // Not "-1 frames exceed max_frames".
  RecognizerParams limits;
  limits.max_frames = 2;
  EXPECT_EQ(messageOf(PlaceRecognizer(routeParameters(), limits), -1), "a map cannot hold -1 frames");
  EXPECT_EQ(messageOf(PlaceRecognizer(routeParameters(), limits), 3), "3 frames exceed max_frames (2)");
  EXPECT_EQ(recognizer.prepareMap(0).size(), 0);
}

TEST(PlaceRecognizer, TheFewestFramesForARecentSequenceDoNotOverflowForAnyCount) {
  RecognizerParams limits;
  limits.recent_exclusion = 50;
  const PlaceRecognizer recognizer(routeParameters(), limits);
  EXPECT_EQ(recognizer.fewestFramesForRecent(10), 70);
  const long long most = std::numeric_limits<int>::max();
  EXPECT_EQ(recognizer.fewestFramesForRecent(most), 2 * most + 50);  // Negative would let any map pass.
}

// The room is frames of over two minutes of a camera, but never more than 64 MB of descriptors:
// large ones (a 512 x 512 thumbnail's 256 KB) made an emptied map hold a gigabyte.
TEST(PlaceRecognizer, TheRoomForNewFramesHoldsAt64MegabytesOfDescriptorsWhateverTheirSize) {
  Parameters large = routeParameters();
  large.descriptor.type = kThumbnailFrontEnd;
  large.descriptor.image_width = 512;
  large.descriptor.image_height = 512;
  PlaceRecognizer recognizer(large);
  recognizer.reset();
  const std::size_t descriptors = 64U * 1024 * 1024;
  EXPECT_GE(recognizer.state().memory_bytes, descriptors);
  EXPECT_LT(recognizer.state().memory_bytes, descriptors + descriptors / 4);  // with stamps and MRS's cells
}

TEST(PlaceRecognizer, FramesArrivingDuringQueriesAreKeptAndNeverExceedTheCapacity) {
  // One thread adds frames while another queries without pause: every frame is either in the map or
  // reported dropped, and the map never grows past max_frames, however the two interleave.
  RecognizerParams limits;
  limits.max_frames = 700;
  limits.max_pending_frames = 1000;
  limits.recent_exclusion = 0;
  PlaceRecognizer recognizer(routeParameters(), limits);
  for (int i = 0; i < 100; ++i) recognizer.addFrame(route().reference[static_cast<std::size_t>(i)]);

  std::atomic<bool> adding{true};
  std::atomic<int> queries{0};
  std::thread querying([&] {
    while (adding.load()) {
      recognizer.matchRecent(10, "seqslam");
      ++queries;
    }
  });
  int admitted = 100;
  int dropped = 0;
  for (int i = 100; i < 1000; ++i) {
    const cv::Mat& image = route().reference[static_cast<std::size_t>(i % 600)];
    if (recognizer.addFrame(image) == FrameAdmission::kAdmitted) {
      ++admitted;
    } else {
      ++dropped;
    }
    EXPECT_LE(recognizer.size() + recognizer.pending(), limits.max_frames);
  }
  adding = false;
  querying.join();
  recognizer.flush();
  EXPECT_GT(queries.load(), 0);
  EXPECT_EQ(admitted, 700);
  EXPECT_EQ(dropped, 300);
  EXPECT_EQ(recognizer.size(), 700);
  EXPECT_EQ(recognizer.pending(), 0);
}

TEST(PlaceRecognizer, TryFlushLeavesFramesPendingWhileTheMapIsHeldAndFlushesThemOnceFree) {
  RecognizerParams limits;
  limits.recent_exclusion = 0;
  PlaceRecognizer recognizer(routeParameters(), limits);
  for (int i = 0; i < 20; ++i) recognizer.addFrame(route().reference[static_cast<std::size_t>(i)]);
  // While the map is read (as a query reads it), a frame from another thread waits as pending, and a
  // flush that may not wait leaves it so.
  bool flushed_while_held = true;
  recognizer.visitFrames(0, 1, [&](const cv::Mat&, Stamp) {
    std::thread other([&] {
      recognizer.addFrame(route().reference[20]);
      flushed_while_held = recognizer.tryFlush();
    });
    other.join();
  });
  EXPECT_FALSE(flushed_while_held);
  EXPECT_EQ(recognizer.pending(), 1);
  EXPECT_EQ(recognizer.size(), 20);
  EXPECT_TRUE(recognizer.tryFlush());
  EXPECT_EQ(recognizer.pending(), 0);
  EXPECT_EQ(recognizer.size(), 21);
}

// A caller that describes frames into one buffer of its own and reuses it: a frame that waits as
// pending while a query reads the map keeps its own bytes, not what the buffer holds by the flush.
TEST(PlaceRecognizer, AFrameWaitingForAQueryKeepsItsOwnCopyOfTheDescriptor) {
  RecognizerParams limits;
  limits.recent_exclusion = 0;
  PlaceRecognizer recognizer(routeParameters(), limits);
  for (int i = 0; i < 20; ++i) recognizer.addFrame(route().reference[static_cast<std::size_t>(i)]);
  cv::Mat buffer = recognizer.describe(route().reference[20]);
  const cv::Mat expected = buffer.clone();
  recognizer.visitFrames(0, 1, [&](const cv::Mat&, Stamp) {
    std::thread other([&] {
      recognizer.addDescriptor(buffer);
      buffer.setTo(0);  // the caller's next frame
    });
    other.join();
  });
  ASSERT_EQ(recognizer.pending(), 1);
  ASSERT_TRUE(recognizer.tryFlush());
  recognizer.visitFrames(20, 21, [&](const cv::Mat& stored, Stamp) { EXPECT_EQ(cv::norm(stored, expected), 0.0); });
}

}  // namespace
}  // namespace mrs_vpr

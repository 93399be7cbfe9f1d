#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include <opencv2/core.hpp>

#include "mrs_vpr/contrast_enhancement.hpp"
#include "mrs_vpr/difference_matrix.hpp"
#include "mrs_vpr/mrs/recent_rows.hpp"
#include "mrs_vpr/mrs_matcher.hpp"
#include "mrs_vpr/seqslam_matcher.hpp"

namespace mrs_vpr {
namespace {

constexpr int kWindow = 10;
const std::vector<double> kVelocities{0.8, 0.9, 1.0, 1.1, 1.2};

/// `count` random descriptors of `size` bytes appended to `map`.
void appendRandomFrames(DescriptorSequence& map, int count, int size, cv::RNG& rng) {
  for (int i = 0; i < count; ++i) {
    cv::Mat frame(1, size, CV_8U);
    rng.fill(frame, cv::RNG::UNIFORM, 0, 256);
    map.append(frame);
  }
}

/// A map of `frames` random descriptors of 64 bytes.
DescriptorSequence randomMap(int frames, cv::RNG& rng) {
  DescriptorSequence map(64);
  appendRandomFrames(map, frames, 64, rng);
  return map;
}

/// The brute force's costs: the whole enhanced difference matrix of the test frames.
AnchorCosts bruteForceCosts(SequenceView map, int first, int count, int columns, const SequenceRows& rows) {
  const cv::Mat differences = computeDifferenceMatrix(map.slice(first, first + count), map.slice(0, columns));
  return costsByAnchor(enhanceContrast(differences, kWindow), rows, kVelocities);
}

void expectSameCosts(const AnchorCosts& kept, const AnchorCosts& brute, const std::string& where) {
  ASSERT_EQ(kept.cost.size(), brute.cost.size()) << where;
  for (std::size_t j = 0; j < brute.cost.size(); ++j) {
    if (std::isinf(brute.cost[j])) {
      EXPECT_TRUE(std::isinf(kept.cost[j])) << where << ", end " << j;
      continue;
    }
    // To the bit: every piece of a row is enhanced as the whole row, and summed in the same order.
    ASSERT_EQ(kept.cost[j], brute.cost[j]) << where << ", end " << j;
    ASSERT_EQ(kept.velocity[j], brute.velocity[j]) << where << ", end " << j;
  }
}

/// The kept rows' costs for map frames [first, first + count) against [0, columns) are the brute force's.
void expectBruteForceCosts(RecentRows& recent, SequenceView map, int first, int count, int columns,
                           const SequenceRows& rows, const std::string& where) {
  AnchorCosts kept;
  recent.costs(map, first, count, columns, rows, kVelocities, kept);
  expectSameCosts(kept, bruteForceCosts(map, first, count, columns, rows), where);
}

// A map growing by a few frames between questions about its newest 20, each question's reference
// ending at a different distance before them: the kept rows give the brute force's cost for every end.
TEST(RecentRows, KeptRowsGiveTheBruteForceCostsAsTheMapGrows) {
  cv::RNG rng(3);
  DescriptorSequence map = randomMap(300, rng);
  RecentRows recent(kWindow, kMaxRecentRows);
  const SequenceRows rows{0, 19, 10};
  for (int step = 0; step < 12; ++step) {
    appendRandomFrames(map, 1 + step % 4, 64, rng);
    const int first = map.size() - 20;
    for (const int gap : {30, 3, 100}) {  // A shorter reference after a longer one: tails put back.
      const int columns = first - gap;
      expectBruteForceCosts(recent, map.view(), first, 20, columns, rows,
                            "map " + std::to_string(map.size()) + ", reference " + std::to_string(columns));
    }
  }
  EXPECT_EQ(recent.rowCount(), 20);  // Rows of frames that left the test sequence were dropped.
  EXPECT_GE(recent.memoryBytes(), 20 * map.size() * sizeof(float));
}

// One long question among short ones (a ~query of 100 keyframes while continuous mode asks about 20)
// keeps its rows only until the map has grown by kMaxRecentRows frames since; long questions asked
// again and again keep theirs.
TEST(RecentRows, ALongQuestionsRowsGoOnceTheMapHasGrownPastIt) {
  cv::RNG rng(5);
  DescriptorSequence map = randomMap(300, rng);
  RecentRows recent(kWindow, kMaxRecentRows);
  const SequenceRows rows{0, 19, 10};
  const SequenceRows long_rows{0, 99, 50};
  AnchorCosts costs;
  recent.costs(map.view(), map.size() - 100, 100, map.size() - 150, long_rows, kVelocities, costs);
  EXPECT_EQ(recent.rowCount(), 100);
  for (int step = 1; step <= kMaxRecentRows + 10; ++step) {
    appendRandomFrames(map, 1, 64, rng);
    recent.costs(map.view(), map.size() - 20, 20, map.size() - 70, rows, kVelocities, costs);
    if (step == kMaxRecentRows) EXPECT_EQ(recent.rowCount(), 100) << "kept while the map grew by " << step;
  }
  EXPECT_EQ(recent.rowCount(), 20);
  EXPECT_LT(recent.memoryBytes(), 25 * map.size() * sizeof(float));
  // Asked again every few frames, the long question keeps its rows.
  for (int step = 0; step < 2 * kMaxRecentRows; ++step) {
    appendRandomFrames(map, 1, 64, rng);
    const bool long_question = step % 50 == 0;
    recent.costs(map.view(), map.size() - (long_question ? 100 : 20), long_question ? 100 : 20, map.size() - 150,
                 long_question ? long_rows : rows, kVelocities, costs);
  }
  EXPECT_EQ(recent.rowCount(), 100);
}

// A map of at most half a contrast window has no final cell: the rows still cover every frame and give
// the brute force's costs as the map grows past it (a null row was read there before).
TEST(RecentRows, AMapSmallerThanHalfAContrastWindowGivesTheBruteForceCosts) {
  cv::RNG rng(13);
  DescriptorSequence map = randomMap(2, rng);
  RecentRows recent(kWindow, kMaxRecentRows);
  for (int frames = 2; frames <= kWindow + 2; ++frames) {
    expectBruteForceCosts(recent, map.view(), map.size() - 2, 2, map.size(), SequenceRows{0, 1, 1},
                          "map " + std::to_string(frames));
    appendRandomFrames(map, 1, 64, rng);
  }
}

TEST(RecentRows, AMapEmptiedAndFilledAgainIsNotReadFromOldRows) {
  cv::RNG rng(5);
  DescriptorSequence map = randomMap(400, rng);
  RecentRows recent(kWindow, kMaxRecentRows);
  const SequenceRows rows{0, 9, 9};
  AnchorCosts kept;
  recent.costs(map.view(), 390, 10, 350, rows, kVelocities, kept);
  DescriptorSequence smaller = randomMap(200, rng);
  recent.costs(smaller.view(), 190, 10, 150, rows, kVelocities, kept);
  expectSameCosts(kept, bruteForceCosts(smaller.view(), 190, 10, 150, rows), "after the map shrank");
  recent.clear();
  EXPECT_EQ(recent.rowCount(), 0);
  EXPECT_EQ(recent.missingRows(smaller.view(), 190, 10), 10);
}

// A question answered without the rows keeps none, however often questions come: the next question
// computes them if it keeps pace. A map that shrank is another map, whose questions are not those noted.
TEST(RecentRows, AQuestionAnsweredWithoutTheRowsIsNotedNotKept) {
  cv::RNG rng(7);
  DescriptorSequence map = randomMap(300, rng);
  RecentRows recent(kWindow, kMaxRecentRows);
  recent.noteAsked(map.view(), 260, 20);
  EXPECT_EQ(recent.rowCount(), 0);
  EXPECT_EQ(recent.missingRows(map.view(), 265, 20), 20);
  EXPECT_TRUE(recent.keepsPace(map.view(), 265, 20));
  EXPECT_TRUE(recent.readsRows(map.view(), 265, 20));    // Every row missing, but the questions keep pace.
  EXPECT_FALSE(recent.readsRows(map.view(), 266, 20));   // 6 test frames after the noted one.
  const DescriptorSequence smaller = randomMap(285, rng);
  EXPECT_FALSE(recent.keepsPace(smaller.view(), 265, 20));
  EXPECT_FALSE(recent.keepsPace(map.view(), 265, 20));  // Forgotten with the smaller map.
}

// Continuous mode asks about each keyframe since its last question, oldest first: the first question
// computes the rows of the keyframes after its own in the same pass, so that the next ones find them,
// a quarter of its length at most however far back it asks.
TEST(RecentRows, AQuestionBeforeTheNewestKeyframesComputesTheirRowsInTheSamePass) {
  cv::RNG rng(13);
  DescriptorSequence map = randomMap(300, rng);
  RecentRows recent(kWindow, kMaxRecentRows);
  const SequenceRows rows{0, 19, 10};
  AnchorCosts kept;
  const long long comparisons = recent.costs(map.view(), 277, 20, 250, rows, kVelocities, kept);
  // Test frames 277..296 and the newer 297..299 against the whole map, and again, for each test frame,
  // the 10 raw cells of the 5 that the reference's end clips.
  EXPECT_EQ(comparisons, 23LL * 300 + 20 * 10);
  EXPECT_EQ(recent.rowCount(), 23);
  for (const int first : {278, 279, 280}) {
    EXPECT_EQ(recent.missingRows(map.view(), first, 20), 0) << first;
    EXPECT_TRUE(recent.readsRows(map.view(), first, 20)) << first;
    recent.costs(map.view(), first, 20, 250, rows, kVelocities, kept);
    expectSameCosts(kept, bruteForceCosts(map.view(), first, 20, 250, rows),
                    "test frames from " + std::to_string(first));
  }

  RecentRows far_back(kWindow, kMaxRecentRows);
  far_back.costs(map.view(), 200, 20, 150, rows, kVelocities, kept);
  EXPECT_EQ(far_back.rowCount(), 25);  // 5 newer rows: a quarter of the 20 test frames, not all 80.
  expectSameCosts(kept, bruteForceCosts(map.view(), 200, 20, 150, rows), "far back");
}

// Questions keep pace when the newest test frame that has a row, or that the last question asked
// about, is followed by at most a quarter of the test frames: the missing rows are then worth one pass.
TEST(RecentRows, KeepPaceWhileAtMostAQuarterOfTheTestFramesFollowTheNewestKnownOne) {
  cv::RNG rng(15);
  DescriptorSequence map = randomMap(300, rng);
  RecentRows recent(kWindow, kMaxRecentRows);
  EXPECT_FALSE(recent.keepsPace(map.view(), 280, 20));  // Nothing known.
  recent.noteAsked(map.view(), 270, 20);                // A question about frames up to 289.
  EXPECT_TRUE(recent.keepsPace(map.view(), 270, 20));
  EXPECT_TRUE(recent.keepsPace(map.view(), 275, 20));    // 5 test frames after frame 289.
  EXPECT_FALSE(recent.keepsPace(map.view(), 276, 20));   // 6.
  EXPECT_FALSE(recent.keepsPace(map.view(), 290, 10));   // Frame 289 is not a test frame.
  EXPECT_EQ(recent.rowCount(), 0);                       // Asking computes nothing.

  AnchorCosts kept;
  recent.costs(map.view(), 255, 20, 200, SequenceRows{0, 19, 10}, kVelocities, kept);  // Rows of 255..279.
  recent.noteAsked(map.view(), 200, 20);                 // An older question: frame 219.
  EXPECT_TRUE(recent.keepsPace(map.view(), 264, 20));    // 4 test frames after the row of frame 279.
}

TEST(RecentRows, RefusesFramesOutsideTheMapAndSequencesLongerThanItKeeps) {
  cv::RNG rng(9);
  DescriptorSequence map = randomMap(100, rng);
  RecentRows recent(kWindow, 16);
  AnchorCosts kept;
  EXPECT_FALSE(recent.covers(17));
  EXPECT_THROW(recent.costs(map.view(), 80, 17, 50, SequenceRows{0, 16, 16}, kVelocities, kept), std::invalid_argument);
  EXPECT_THROW(recent.costs(map.view(), 95, 10, 50, SequenceRows{0, 9, 9}, kVelocities, kept), std::invalid_argument);
  EXPECT_THROW(recent.costs(map.view(), 80, 10, 101, SequenceRows{0, 9, 9}, kVelocities, kept), std::invalid_argument);
}

// Questions about a revisit, asked after each new frame as continuous mode asks: the first searches;
// from the second on the questions keep pace, every row is computed in one pass, and MRS's answer is
// the brute force's.
TEST(RecentRows, MrsAnswersAsTheBruteForceFromKeptRows) {
  cv::RNG rng(11);
  const int size = DescriptorParams{}.descriptorSize();
  DescriptorSequence map(size);
  appendRandomFrames(map, 800, size, rng);
  SequenceParams sequence;
  sequence.contrast_window = kWindow;
  const MrsMatcher mrs(sequence, MrsParams{});
  const SeqSlamMatcher brute(sequence);
  RecentRows recent(kWindow, kMaxRecentRows);
  int answered_from_rows = 0;
  int searched = 0;
  for (int revisit = 0; revisit < 60; ++revisit) {
    const cv::Mat original(1, size, CV_8U, const_cast<std::uint8_t*>(map.view().frame(200 + revisit)));
    cv::Mat noise(1, size, CV_16S);
    rng.fill(noise, cv::RNG::NORMAL, 0, 12);
    cv::Mat frame;
    original.convertTo(frame, CV_16S);
    frame += noise;
    cv::Mat revisited;
    frame.convertTo(revisited, CV_8U);  // Saturating: a noisy view of frame 200 + revisit.
    map.append(revisited);
    if (revisit < 20) continue;
    const int first = map.size() - 20;
    const int columns = first - 10;
    const bool search = !recent.readsRows(map.view(), first, 20);
    const Match kept = mrs.matchMapFrames(map.view(), columns, first, 20, recent);
    const Match reference = brute.match(map.view(0, columns), map.view(first, map.size()));
    if (search) {
      ++searched;
      const Match own_search = mrs.match(map.view(0, columns), map.view(first, map.size()));
      EXPECT_EQ(kept.reference_index, own_search.reference_index) << "revisit " << revisit;
      EXPECT_FLOAT_EQ(kept.confidence, own_search.confidence) << "revisit " << revisit;
      continue;
    }
    ++answered_from_rows;
    EXPECT_EQ(kept.reference_index, reference.reference_index) << "revisit " << revisit;
    EXPECT_EQ(kept.velocity, reference.velocity) << "revisit " << revisit;
    EXPECT_EQ(kept.confidence, reference.confidence) << "revisit " << revisit;
    EXPECT_EQ(kept.accepted, reference.accepted) << "revisit " << revisit;
    // The centred anchor, 9 frames before the newest: a view of frame 200 + revisit - 9.
    EXPECT_NEAR(kept.reference_index, 200 + revisit - 9, 2) << "revisit " << revisit;
  }
  EXPECT_EQ(searched, 1);  // The first question: no row yet.
  EXPECT_EQ(answered_from_rows, 39);
}

}  // namespace
}  // namespace mrs_vpr

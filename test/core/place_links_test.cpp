#include "mrs_vpr/place_links.hpp"

#include <gtest/gtest.h>

#include <random>
#include <stdexcept>
#include <utility>
#include <vector>

namespace mrs_vpr {
namespace {

std::vector<std::pair<int, int>> pairsOf(const std::vector<FrameRange>& ranges) {
  std::vector<std::pair<int, int>> pairs;
  for (const FrameRange& range : ranges) pairs.emplace_back(range.begin, range.end);
  return pairs;
}

std::vector<std::pair<int, int>> pairsOf(const std::vector<PlaceLink>& links) {
  std::vector<std::pair<int, int>> pairs;
  for (const PlaceLink& link : links) pairs.emplace_back(link.frame, link.reference);
  return pairs;
}

using Pairs = std::vector<std::pair<int, int>>;

TEST(PlaceLinks, NothingLinkedShowsNoOtherVisit) {
  const PlaceLinks links;
  EXPECT_TRUE(links.samePlaceAs(50, 5).empty());
  EXPECT_EQ(links.linkedFrames(), 0);
}

TEST(PlaceLinks, ASecondVisitShowsTheFirstVisitsPlaceAndTheOtherWayRound) {
  PlaceLinks links;
  // Frames 200..203 of a second visit showed frames 50..53 of the first.
  for (int i = 0; i < 4; ++i) links.link(200 + i, 50 + i);
  EXPECT_EQ(links.linkedFrames(), 4);
  // From the second visit: the first visit's frames at the places its window shows, as wide as a window.
  EXPECT_EQ(pairsOf(links.samePlaceAs(201, 2)), (Pairs{{49, 54}}));
  // From the first: the second visit's frames linked to its window's places (its own window left out).
  EXPECT_EQ(pairsOf(links.samePlaceAs(51, 2)), (Pairs{{199, 204}}));
  // Far from the linked places: nothing.
  EXPECT_TRUE(links.samePlaceAs(120, 2).empty());
}

TEST(PlaceLinks, AThirdVisitLinkedToTheSecondShowsTheFirstToo) {
  PlaceLinks links;
  links.link(200, 50);  // second visit -> first
  links.link(400, 200);  // third -> second: the first visit's place
  EXPECT_EQ(pairsOf(links.samePlaceAs(400, 1)), (Pairs{{49, 52}, {199, 202}}));
  EXPECT_EQ(pairsOf(links.samePlaceAs(50, 1)), (Pairs{{199, 202}, {399, 402}}));
  // A link between two places already joined changes nothing.
  links.link(400, 50);
  EXPECT_EQ(links.linkedFrames(), 2);
}

// A second visit linked frame by frame: from its middle, the first visit's window at the place, no
// wider than the answer's own, and none of the second visit's own frames beyond its window.
TEST(PlaceLinks, AVisitLinkedFrameByFrameShowsTheOtherVisitsWindowOnly) {
  PlaceLinks links;
  for (int i = 0; i < 300; ++i) links.link(300 + i, i);
  EXPECT_EQ(pairsOf(links.samePlaceAs(450, 5)), (Pairs{{145, 156}}));
  EXPECT_EQ(pairsOf(links.samePlaceAs(150, 5)), (Pairs{{445, 456}}));
}

TEST(PlaceLinks, TwoPlacesJoinedLaterAreNamedByTheOlder) {
  PlaceLinks links;
  links.link(300, 100);  // frame 300 shows 100
  links.link(120, 10);   // frame 120 shows 10 ...
  links.link(100, 120);  // ... and 100 shows 120: 300, 100 and 120 show 10
  EXPECT_EQ(links.linkedFrames(), 3);
  EXPECT_EQ(pairsOf(links.samePlaceAs(300, 0)), (Pairs{{10, 11}, {100, 101}, {120, 121}}));
}

TEST(PlaceLinks, RangesNearTheMapsStartAreClippedAndClearForgetsEveryLink) {
  PlaceLinks links;
  links.link(500, 1);
  EXPECT_EQ(pairsOf(links.samePlaceAs(500, 3)), (Pairs{{0, 5}}));
  links.clear();
  EXPECT_TRUE(links.samePlaceAs(500, 3).empty());
  EXPECT_EQ(links.linkedFrames(), 0);
  EXPECT_THROW(links.link(-1, 3), std::invalid_argument);
}

// A map read back gets its places at once: the same as linking one by one, whatever the order.
TEST(PlaceLinks, PlacesOfALinkListAreThoseOfItsLinksMadeOneByOne) {
  const std::vector<PlaceLink> made = {{50, 10}, {80, 50}, {12, 3}, {90, 12}, {91, 80}, {91, 10}, {70, 71}};
  PlaceLinks one_by_one;
  int joined = 0;
  for (const PlaceLink& link : made) joined += one_by_one.link(link.frame, link.reference) ? 1 : 0;
  EXPECT_EQ(joined, 6);  // 91 and 10 were one place already
  PlaceLinks adopted;
  adopted.adopt(PlaceLinks::placesOf(made, 100), std::vector<PlaceLink>(made));
  EXPECT_EQ(adopted.linkedFrames(), one_by_one.linkedFrames());
  for (const int frame : {10, 50, 80, 3, 12, 90, 70, 40}) {
    EXPECT_EQ(pairsOf(adopted.samePlaceAs(frame, 2)), pairsOf(one_by_one.samePlaceAs(frame, 2))) << frame;
  }
  // The few links that make the same places again: each linked frame to its place's first frame.
  PlaceLinks again;
  again.adopt(PlaceLinks::placesOf(one_by_one.asLinks(100), 100), one_by_one.asLinks(100));
  EXPECT_EQ(again.asLinks(100).size(), static_cast<std::size_t>(one_by_one.linkedFrames()));
  for (const int frame : {10, 50, 80, 3, 12, 90, 70}) {
    EXPECT_EQ(pairsOf(again.samePlaceAs(frame, 2)), pairsOf(one_by_one.samePlaceAs(frame, 2))) << frame;
  }
  EXPECT_EQ(one_by_one.asLinks(13).size(), 1U);  // among frames [0, 13): 12 of 3
}

// Continuous mode links each new keyframe, for the first time, to an old place; merging two places
// that hold frames already relabels one of them. Both, mixed, make the places of the list.
TEST(PlaceLinks, ManyLinksMadeOneByOneMakeThePlacesOfTheirList) {
  std::mt19937 random(3);
  std::vector<PlaceLink> made;
  for (int frame = 200; frame < 1000; ++frame) {
    made.push_back({frame, static_cast<int>(random() % 200)});  // a newest keyframe closes a loop
    if (frame % 7 == 0) {  // two places, each holding frames, found to be one
      made.push_back({static_cast<int>(random() % frame), static_cast<int>(random() % frame)});
    }
  }
  PlaceLinks one_by_one;
  for (const PlaceLink& link : made) one_by_one.link(link.frame, link.reference);
  PlaceLinks adopted;
  adopted.adopt(PlaceLinks::placesOf(made, 1000), std::vector<PlaceLink>(made));
  EXPECT_EQ(pairsOf(one_by_one.asLinks(1000)), pairsOf(adopted.asLinks(1000)));
  EXPECT_EQ(one_by_one.linkedFrames(), adopted.linkedFrames());
}

TEST(PlaceLinks, ALinkListNamingAFrameOutsideTheMapIsRefused) {
  EXPECT_THROW(PlaceLinks::placesOf({{5, 1}, {20, 3}}, 20), std::invalid_argument);
  EXPECT_THROW(PlaceLinks::placesOf({{-1, 3}}, 20), std::invalid_argument);
  EXPECT_TRUE(PlaceLinks::placesOf({}, 0).empty());
}

// The links made since a database last took them, for its next commit: only those that joined two
// places, and only once asked for.
TEST(PlaceLinks, TheUnsavedLogHoldsTheLinksThatJoinedPlacesSinceItWasTaken) {
  PlaceLinks links;
  links.link(20, 5);
  EXPECT_TRUE(links.takeUnsaved().empty());  // not kept before keepUnsaved()
  links.keepUnsaved();
  links.link(40, 20);
  links.link(40, 5);  // one place already
  links.link(41, 6);
  const std::vector<PlaceLink> taken = links.takeUnsaved();
  ASSERT_EQ(taken.size(), 2U);
  EXPECT_EQ(taken[0].frame, 40);
  EXPECT_EQ(taken[1].reference, 6);
  EXPECT_TRUE(links.takeUnsaved().empty());
  links.link(60, 7);
  links.adopt({}, {});  // a map put in place: its links are not the old map's
  EXPECT_TRUE(links.takeUnsaved().empty());
  EXPECT_EQ(links.linkedFrames(), 0);
}

// A closure that the robot's back end refused: forgetting its link parts the places it joined, and
// only those; links made later through its frames stay, and so do those of other places.
TEST(PlaceLinks, AForgottenClosurePartsThePlacesItJoinedAndNoOther) {
  PlaceLinks links;
  links.keepUnsaved();
  links.link(200, 50);  // second visit -> first, right
  links.link(210, 90);  // a wrong closure: frame 210 put in frame 90's place
  links.link(400, 200);  // third visit -> second, right
  links.link(410, 210);  // third -> the frame of the wrong closure: frame 90's place too
  links.link(420, 60);   // another place
  EXPECT_EQ(links.linkedFrames(), 5);
  EXPECT_EQ(pairsOf(links.samePlaceAs(90, 0)), (Pairs{{210, 211}, {410, 411}}));
  const std::vector<PlaceLink> wrong = links.linksOfClosure(210, 90);
  EXPECT_EQ(pairsOf(wrong), (Pairs{{210, 90}}));
  EXPECT_TRUE(links.linksOfClosure(210, 50).empty());  // 210 shows 90's place, not 50's
  EXPECT_TRUE(links.linksOfClosure(211, 90).empty());   // 211 was never linked
  links.forget(wrong);
  EXPECT_EQ(links.linkedFrames(), 4);
  EXPECT_TRUE(links.samePlaceAs(90, 0).empty());  // no other visit shows frame 90's place
  EXPECT_EQ(pairsOf(links.samePlaceAs(410, 0)), (Pairs{{210, 211}}));  // the third visit still shows 210's
  EXPECT_EQ(pairsOf(links.samePlaceAs(400, 0)), (Pairs{{50, 51}, {200, 201}}));
  EXPECT_EQ(pairsOf(links.samePlaceAs(420, 0)), (Pairs{{60, 61}}));
  EXPECT_TRUE(links.linksOfClosure(210, 90).empty());  // forgotten already
  // The log of links a database has yet to store no longer holds it; a new closure links again.
  EXPECT_EQ(pairsOf(links.takeUnsaved()), (Pairs{{200, 50}, {400, 200}, {410, 210}, {420, 60}}));
  EXPECT_TRUE(links.link(210, 90));
}

// A map saved without its links as made keeps each linked frame's link to its place's first frame;
// the closure's link is found through it.
TEST(PlaceLinks, AClosureIsForgottenInAMapThatKeptItsPlacesOnly) {
  PlaceLinks made;
  made.link(200, 50);
  made.link(300, 200);  // kept as 300 -> 50
  PlaceLinks saved;
  saved.adopt(PlaceLinks::placesOf(made.asLinks(400), 400), made.asLinks(400));
  const std::vector<PlaceLink> closure = saved.linksOfClosure(300, 200);
  EXPECT_EQ(pairsOf(closure), (Pairs{{300, 50}}));
  saved.forget(closure);
  EXPECT_EQ(pairsOf(saved.samePlaceAs(50, 0)), (Pairs{{200, 201}}));
  EXPECT_EQ(saved.linkedFrames(), 1);
}

}  // namespace
}  // namespace mrs_vpr

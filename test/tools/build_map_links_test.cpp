// build_map closes loops over the frames it adds, as a node mapping them in continuous mode would,
// and keeps the place links: a stretch that a map built offline holds twice is no rival of itself,
// and a third visit appended to it closes its loops as the second did.

#include <gtest/gtest.h>

#include <cstdint>
#include <iostream>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>

#include "mrs_vpr/store/map_database.hpp"
#include "route_folders.hpp"
#include "route_tools_fixture.hpp"
#include "support/command_run.hpp"
#include "support/route_fixture.hpp"

namespace {

using mrs_vpr::MapAccess;
using mrs_vpr::MapDatabase;
using mrs_vpr::PlaceLink;
using mrs_vpr::testing_support::CommandResult;
using mrs_vpr::testing_support::standardRouteImages;

constexpr int kRouteFrames = 600;
constexpr int kElsewhereFrames = 60;
constexpr int kRevisitBegin = 100;
constexpr int kRevisitEnd = 300;
/// Places of the ground the route does not hold: the same views on every revisit, far from the route's.
constexpr int kElsewhere = 10000;

class BuildMapLinksTest : public mrs_vpr::testing_support::RouteToolsTest {
 protected:
  /// The route once ("route"), and a drive over ground the route does not hold followed by a stretch
  /// of the route again ("revisit"); every frame is a keyframe (buildMap()).
  static void SetUpTestSuite() {
    RouteToolsTest::SetUpTestSuite();
    const std::vector<cv::Mat>& route = standardRouteImages().reference;
    mrs_vpr::testing_support::writeImageFolder(path("route"), {route.begin(), route.begin() + kRouteFrames});
    std::vector<cv::Mat> revisit;
    cv::RNG rng(7);
    for (int i = 0; i < kElsewhereFrames; ++i) {
      cv::Mat view(route.front().size(), route.front().type());
      rng.fill(view, cv::RNG::UNIFORM, 0, 256);
      cv::GaussianBlur(view, view, cv::Size(0, 0), 2.0);
      revisit.push_back(view);
    }
    revisit.insert(revisit.end(), route.begin() + kRevisitBegin, route.begin() + kRevisitEnd);
    mrs_vpr::testing_support::writeImageFolder(path("revisit"), revisit);
  }

  /// The place at each frame of a map of the route and then `revisits` revisits.
  static std::vector<int> placesOfMapFrames(int revisits) {
    std::vector<int> places;
    for (int frame = 0; frame < kRouteFrames; ++frame) places.push_back(frame);
    for (int visit = 0; visit < revisits; ++visit) {
      for (int frame = 0; frame < kElsewhereFrames; ++frame) places.push_back(kElsewhere + frame);
      for (int frame = kRevisitBegin; frame < kRevisitEnd; ++frame) places.push_back(frame);
    }
    return places;
  }

  static CommandResult add(const std::string& folder, const std::string& map, const std::string& options) {
    return run(buildMap() + " --images " + path(folder) + " --output " + map + options);
  }

  static std::vector<PlaceLink> linksOf(const std::string& map) {
    return MapDatabase(map, MapAccess::kReadOnly).placeLinks();
  }

  /// Links among `links` whose two frames show one place (within 5 frames).
  static int rightLinks(const std::vector<PlaceLink>& links, const std::vector<int>& places) {
    int right = 0;
    for (const PlaceLink& link : links) {
      const int frame = places.at(static_cast<std::size_t>(link.frame));
      const int reference = places.at(static_cast<std::size_t>(link.reference));
      if (mrs_vpr::testing_support::within(frame, reference, 5)) ++right;
    }
    return right;
  }

  /// Links among `links` made for the route's stretch of the last visit of `places`.
  static int linksOfTheLastStretch(const std::vector<PlaceLink>& links, const std::vector<int>& places) {
    const int stretch_begin = static_cast<int>(places.size()) - (kRevisitEnd - kRevisitBegin);
    int count = 0;
    for (const PlaceLink& link : links) count += link.frame >= stretch_begin ? 1 : 0;
    return count;
  }
};

TEST_F(BuildMapLinksTest, AStretchAppendedTwiceIsLinkedAndAThirdVisitClosesItsLoops) {
  const std::string map = path("linked.db");
  const CommandResult first = add("route", map, "");
  ASSERT_EQ(first.status, 0) << first.err;
  EXPECT_TRUE(linksOf(map).empty()) << "the route passes no place twice";

  const CommandResult second = add("revisit", map, " --append");
  ASSERT_EQ(second.status, 0) << second.err;
  const std::vector<PlaceLink> second_links = linksOf(map);
  const int second_stretch = linksOfTheLastStretch(second_links, placesOfMapFrames(1));
  EXPECT_GT(second_stretch, 80) << second.err;
  EXPECT_EQ(second_stretch, static_cast<int>(second_links.size())) << "new ground links nothing";
  EXPECT_EQ(rightLinks(second_links, placesOfMapFrames(1)), static_cast<int>(second_links.size()));
  EXPECT_NE(second.err.find(std::to_string(second_links.size()) + " loop closures accepted of"), std::string::npos)
      << second.err;

  // The third visit's stretch is held twice; linked, neither visit is the other's rival. (Its ground
  // off the route was seen once, on the second visit, and links to it.)
  const CommandResult third = add("revisit", map, " --append");
  ASSERT_EQ(third.status, 0) << third.err;
  const std::vector<PlaceLink> third_links = linksOf(map);
  const int third_stretch = linksOfTheLastStretch(third_links, placesOfMapFrames(2));
  EXPECT_GE(third_stretch, second_stretch - 5);
  EXPECT_EQ(rightLinks(third_links, placesOfMapFrames(2)), static_cast<int>(third_links.size()));
  // Each appended visit begins a drive (drive_starts.hpp): the map records where, with or without links.
  const int route_frames = static_cast<int>(placesOfMapFrames(0).size());
  const int visit_frames = static_cast<int>(placesOfMapFrames(1).size()) - route_frames;
  EXPECT_EQ(MapDatabase(map, MapAccess::kReadOnly).driveStarts(),
            (std::vector<int>{route_frames, route_frames + visit_frames}));

  // The same visits appended without links, as before build_map closed loops: the third is refused.
  const std::string unlinked = path("unlinked.db");
  ASSERT_EQ(add("route", unlinked, "").status, 0);
  ASSERT_EQ(add("revisit", unlinked, " --append --no-place-links").status, 0);
  EXPECT_TRUE(linksOf(unlinked).empty());
  ASSERT_EQ(add("revisit", unlinked, " --append").status, 0);
  const int unlinked_stretch = linksOfTheLastStretch(linksOf(unlinked), placesOfMapFrames(2));
  EXPECT_LT(unlinked_stretch, third_stretch / 2);
  EXPECT_EQ(MapDatabase(unlinked, MapAccess::kReadOnly).driveStarts(),
            (std::vector<int>{route_frames, route_frames + visit_frames}));
  std::cout << "stretch links: second visit " << second_stretch << ", third " << third_stretch
            << ", third after an unlinked second " << unlinked_stretch << "\n";
}

// A map whose visits were appended without links gets, drive by drive, the links a build with them made.
TEST_F(BuildMapLinksTest, AMapBuiltWithoutLinksIsLinkedAfterwardsAsIfBuiltWithThem) {
  const std::string linked = path("linked-as-built.db");
  const std::string unlinked = path("linked-afterwards.db");
  for (const std::string& map : {linked, unlinked}) {
    const std::string links = map == linked ? "" : " --no-place-links";
    ASSERT_EQ(add("route", map, links).status, 0);
    ASSERT_EQ(add("revisit", map, " --append" + links).status, 0);
    ASSERT_EQ(add("revisit", map, " --append" + links).status, 0);
  }
  ASSERT_TRUE(linksOf(unlinked).empty());
  const std::vector<PlaceLink> as_built = linksOf(linked);
  ASSERT_GT(linksOfTheLastStretch(as_built, placesOfMapFrames(2)), 80);

  const CommandResult linking = run(buildMap() + " --link-places --output " + unlinked);
  ASSERT_EQ(linking.status, 0) << linking.err;
  const std::vector<PlaceLink> afterwards = linksOf(unlinked);
  ASSERT_EQ(afterwards.size(), as_built.size()) << linking.err;
  for (std::size_t i = 0; i < as_built.size(); ++i) {
    EXPECT_EQ(afterwards[i].frame, as_built[i].frame) << "link " << i;
    EXPECT_EQ(afterwards[i].reference, as_built[i].reference) << "link " << i;
  }
  EXPECT_NE(linking.err.find("over the map's 3 drives: " + std::to_string(as_built.size()) + " place links added"),
            std::string::npos)
      << linking.err;
  // Linked again, or a map built with its links: nothing new, and no link twice.
  for (const std::string& map : {unlinked, linked}) {
    const CommandResult again = run(buildMap() + " --link-places --output " + map);
    ASSERT_EQ(again.status, 0) << again.err;
    EXPECT_NE(again.err.find(": 0 place links added"), std::string::npos) << again.err;
    EXPECT_EQ(linksOf(map).size(), as_built.size());
  }
  // The frames are the map's own, and so is the front end (buildMap() names the route's).
  EXPECT_NE(run(buildMap() + " --link-places --images " + path("route") + " --output " + unlinked).err.find(
                "--link-places adds no frames"),
            std::string::npos);
  const CommandResult other_front_end = run(std::string(BUILD_MAP_PATH) + " --link-places --descriptor hog --output " +
                                            unlinked);
  EXPECT_NE(other_front_end.status, 0);
  EXPECT_NE(other_front_end.err.find("holds descriptors of the thumbnail"), std::string::npos) << other_front_end.err;
  EXPECT_NE(run(buildMap() + " --link-places --output " + path("no-such-map.db")).err.find("there is no map"),
            std::string::npos);
}

}  // namespace

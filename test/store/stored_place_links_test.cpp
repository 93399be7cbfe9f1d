// The place links of a map database: the loop closures that tell a map which of its frames show one
// place kept with the frames, so that a place the map holds more than once stays no rival of itself
// after a restart, a ~load_map or a ~save_map; and maps written before them read as maps of no links.

#include <atomic>
#include <chrono>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>
#include <sqlite3.h>

#include "mrs_vpr/store/map_database.hpp"
#include "mrs_vpr/store/persistent_map.hpp"
#include "support/format_one_map.hpp"
#include "support/front_ends.hpp"
#include "support/route_fixture.hpp"
#include "support/temporary_folder.hpp"

namespace mrs_vpr {
namespace {

namespace fs = std::filesystem;
using testing_support::runSql;
using testing_support::thumbnailParams;
using testing_support::within;

constexpr int kDescriptorBytes = testing_support::kFormatOneDescriptorBytes;

std::vector<StoredFrame> frames(int count) {
  std::vector<StoredFrame> stored;
  for (int i = 0; i < count; ++i) {
    stored.push_back({cv::Mat(1, kDescriptorBytes, CV_8UC1, cv::Scalar(i)), Stamp::fromNanoseconds(i), "", i});
  }
  return stored;
}

/// Links as (frame, reference) pairs, for comparison.
std::vector<std::pair<int, int>> pairsOf(const std::vector<PlaceLink>& links) {
  std::vector<std::pair<int, int>> pairs;
  for (const PlaceLink& link : links) pairs.emplace_back(link.frame, link.reference);
  return pairs;
}

std::string metadataValue(const std::string& file, const std::string& key) {
  sqlite3* db = nullptr;
  EXPECT_EQ(sqlite3_open_v2(file.c_str(), &db, SQLITE_OPEN_READONLY, nullptr), SQLITE_OK);
  sqlite3_stmt* statement = nullptr;
  const std::string sql = "SELECT value FROM metadata WHERE key = '" + key + "'";
  EXPECT_EQ(sqlite3_prepare_v2(db, sql.c_str(), -1, &statement, nullptr), SQLITE_OK);
  std::string value = "(none)";
  if (sqlite3_step(statement) == SQLITE_ROW) value = reinterpret_cast<const char*>(sqlite3_column_text(statement, 0));
  sqlite3_finalize(statement);
  sqlite3_close(db);
  return value;
}

class StoredPlaceLinksTest : public ::testing::Test {
 protected:
  std::string path(const std::string& name) const { return folder_.path(name); }

  testing_support::TemporaryFolder folder_{"mrs_vpr_stored_place_links_test"};
};

TEST_F(StoredPlaceLinksTest, AMapKeepsItsPlaceLinksInTheOrderTheyWereMade) {
  {
    MapDatabase database(path("map.db"), thumbnailParams());
    database.append(frames(6), {{3, 1}});
    database.append(frames(2), {{7, 2}, {6, 0}});
    database.append({}, {{5, 4}});  // Links alone, when no frame came since.
  }
  const MapDatabase database(path("map.db"), thumbnailParams(), MapAccess::kReadOnly);
  EXPECT_EQ(database.size(), 8);
  EXPECT_EQ(pairsOf(database.placeLinks()), (std::vector<std::pair<int, int>>{{3, 1}, {7, 2}, {6, 0}, {5, 4}}));
  EXPECT_EQ(metadataValue(path("map.db"), "format_version"), "3");
}

TEST_F(StoredPlaceLinksTest, LinksWithoutFramesKeepTheRecordOfTheTraversal) {
  MapDatabase database(path("map.db"), thumbnailParams());
  database.append(frames(4));
  database.setTraversal(MapTraversal{40, std::nullopt});
  database.append({}, {{3, 0}});
  EXPECT_TRUE(database.readTraversal().has_value());
  database.append(frames(1));
  EXPECT_FALSE(database.readTraversal().has_value());  // New frames are no longer the traversal's alone.
}

TEST_F(StoredPlaceLinksTest, ClearAndReplaceForgetTheOldFramesLinks) {
  MapDatabase database(path("map.db"), thumbnailParams());
  database.append(frames(5), {{4, 1}});
  database.clear();
  EXPECT_TRUE(database.placeLinks().empty());
  database.append(frames(5), {{4, 1}});
  const std::vector<StoredFrame> replacement = frames(3);
  database.replace([&](const auto& insert) {
    for (const StoredFrame& frame : replacement) insert(frame);
  });
  EXPECT_TRUE(database.placeLinks().empty());
  database.replace(
      [&](const auto& insert) {
        for (const StoredFrame& frame : replacement) insert(frame);
      },
      std::nullopt, {{2, 0}});
  EXPECT_EQ(pairsOf(database.placeLinks()), (std::vector<std::pair<int, int>>{{2, 0}}));
}

// Format 2 is format 3 without place_links: written by the releases before the links.
TEST_F(StoredPlaceLinksTest, AFormatTwoMapHasNoLinksAndGainsTheirTableWhenWritten) {
  { MapDatabase(path("old.db"), thumbnailParams()).append(frames(4)); }
  runSql(path("old.db"),
         "DROP TABLE place_links; UPDATE metadata SET value = '2' WHERE key = 'format_version'; PRAGMA "
         "journal_mode = DELETE");
  {
    const MapDatabase database(path("old.db"), thumbnailParams(), MapAccess::kReadOnly);
    EXPECT_EQ(database.size(), 4);
    EXPECT_TRUE(database.placeLinks().empty());
  }
  EXPECT_EQ(metadataValue(path("old.db"), "format_version"), "2");  // Only read: left as it was.
  {
    MapDatabase database(path("old.db"), thumbnailParams());
    EXPECT_EQ(database.convertedFromFormat(), 2);  // for the node to say so
    database.append({}, {{3, 0}});
  }
  EXPECT_EQ(MapDatabase(path("old.db"), thumbnailParams()).convertedFromFormat(), 0);
  EXPECT_EQ(metadataValue(path("old.db"), "format_version"), "3");
  EXPECT_EQ(pairsOf(MapDatabase(path("old.db"), thumbnailParams(), MapAccess::kReadOnly).placeLinks()),
            (std::vector<std::pair<int, int>>{{3, 0}}));
}

TEST_F(StoredPlaceLinksTest, ALinkThatIsNotTwoOfTheMapsFramesIsAnErrorNamingIt) {
  { MapDatabase(path("map.db"), thumbnailParams()).append(frames(4), {{3, 0}}); }
  runSql(path("map.db"), "INSERT INTO place_links (frame, reference) VALUES (9, 1)");
  try {
    MapDatabase(path("map.db"), thumbnailParams(), MapAccess::kReadOnly).placeLinks();
    FAIL() << "no error";
  } catch (const MapDatabaseError& error) {
    EXPECT_NE(std::string(error.what()).find("place link 2: its frame '9' is not one of its 4 frames (counted from 0); "
                                             "with no node holding the map, sqlite3 '" + path("map.db") +
                                             "' \"DELETE FROM place_links WHERE id = 2\" removes the link"),
              std::string::npos)
        << error.what();
  }
  runSql(path("map.db"), "UPDATE place_links SET frame = 1, reference = 'x' WHERE id = 2");
  try {
    MapDatabase(path("map.db"), thumbnailParams(), MapAccess::kReadOnly).placeLinks();
    FAIL() << "no error";
  } catch (const MapDatabaseError& error) {
    EXPECT_NE(std::string(error.what()).find("place link 2: its reference 'x' is not one of"), std::string::npos)
        << error.what();
  }
  // A node does not start on it (the map is never replaced by an empty one).
  PlaceRecognizer recognizer(testing_support::routeParameters());
  EXPECT_THROW(PersistentMap(recognizer, path("map.db"), CommitPolicy{}), MapDatabaseError);
}

/// A robot that maps as it drives, its map in a database, over the standard route: the route's first
/// `kRouteFrames` frames, then ground the route does not hold, then a stretch of the route again (the
/// same images, on a later clock), with a question about its newest keyframes after each keyframe.
/// Remembers which place of the route each keyframe shows, across restarts.
class MappingDrive {
 public:
  struct Counts {
    int right = 0;
    int wrong = 0;
  };

  static constexpr int kRouteFrames = 600;

  explicit MappingDrive(std::string database, CommitPolicy commits = {})
      : database_(std::move(database)), commits_(commits) {}
  /// The drive `history` made so far, on `database`, a copy of its map (stopped).
  MappingDrive(std::string database, const MappingDrive& history)
      : database_(std::move(database)), place_of_keyframe_(history.place_of_keyframe_), stamp_ns_(history.stamp_ns_) {}

  /// A node on the database, as after a restart: the map and its links as the database holds them.
  void start() {
    map_.reset();
    recognizer_ = std::make_unique<PlaceRecognizer>(testing_support::routeParameters(), limits());
    map_ = std::make_unique<PersistentMap>(*recognizer_, database_, commits_);
    ASSERT_EQ(recognizer_->size(), static_cast<int>(place_of_keyframe_.size()));
  }
  /// Stops the node (committing what is queued).
  void stop() {
    map_.reset();
    recognizer_.reset();
  }

  void mapRoute() {
    for (int frame = 0; frame < kRouteFrames; ++frame) offer(frame);
  }

  /// A node started on the database maps the route, drives elsewhere and revisits a stretch, which
  /// its closures link to the route's first visit.
  void mapAndRevisit() {
    start();
    mapRoute();
    driveElsewhere(60);
    revisit(100, 300);
  }

  /// Drives the route's frames [begin, end) again, asking after each keyframe.
  Counts revisit(int begin, int end) {
    Counts counts;
    for (int frame = begin; frame < end; ++frame) {
      if (!offer(frame)) continue;
      const PlaceAnswer answer = recognizer_->matchRecent(kSequenceLength);
      if (!answer.match.accepted) continue;
      const int truth = place_of_keyframe_[static_cast<std::size_t>(answer.localised_frame)];
      const int found = place_of_keyframe_[static_cast<std::size_t>(answer.match.reference_index)];
      ++(within(found, truth, 5) ? counts.right : counts.wrong);
    }
    return counts;
  }

  /// Drives `frames` frames over ground the route does not hold (views of noise).
  void driveElsewhere(int frames) {
    cv::RNG rng(static_cast<std::uint64_t>(place_of_keyframe_.size()));
    const cv::Mat& like = testing_support::standardRouteImages().reference[0];
    for (int i = 0; i < frames; ++i) {
      cv::Mat view(like.size(), like.type());
      rng.fill(view, cv::RNG::UNIFORM, 0, 256);
      cv::GaussianBlur(view, view, cv::Size(0, 0), 2.0);
      if (add(view)) place_of_keyframe_.push_back(-1000);  // no place of the route
    }
  }

  PlaceRecognizer& recognizer() { return *recognizer_; }
  PersistentMap& map() { return *map_; }

 private:
  static constexpr int kSequenceLength = 20;

  static RecognizerParams limits() {
    RecognizerParams limits;
    limits.recent_exclusion = 50;
    return limits;
  }

  bool add(const cv::Mat& image) {
    stamp_ns_ += 100'000'000;
    return map_->offer(recognizer_->describe(image), Stamp::fromNanoseconds(stamp_ns_)) == FrameAdmission::kAdmitted;
  }

  bool offer(int frame) {
    if (!add(testing_support::standardRouteImages().reference[static_cast<std::size_t>(frame)])) return false;
    place_of_keyframe_.push_back(frame);
    return true;
  }

  std::string database_;
  CommitPolicy commits_;
  std::unique_ptr<PlaceRecognizer> recognizer_;
  std::unique_ptr<PersistentMap> map_;
  std::vector<int> place_of_keyframe_;
  std::int64_t stamp_ns_ = 0;
};

// The user's case: a node on ~database, restarted between drives that pass the same stretch. Without
// its links a restarted map holds the stretch twice with nothing to tell that both are one place, and
// refuses the next visit's right answers; with them it closes that visit's loops as the second did.
TEST_F(StoredPlaceLinksTest, AMapRestartedBetweenVisitsKeepsClosingTheirLoops) {
  MappingDrive drive(path("map.db"));
  drive.start();
  drive.mapRoute();
  drive.driveElsewhere(60);
  const MappingDrive::Counts second = drive.revisit(100, 300);
  EXPECT_GT(second.right, 100);
  EXPECT_EQ(second.wrong, 0);
  const int linked = drive.recognizer().state().linked_frames;
  EXPECT_GT(linked, 100);
  drive.stop();

  // The same map without its links, as the releases before them kept it: the third visit is refused.
  fs::copy_file(path("map.db"), path("unlinked.db"));
  runSql(path("unlinked.db"), "DELETE FROM place_links");
  MappingDrive unlinked(path("unlinked.db"), drive);
  unlinked.start();
  EXPECT_EQ(unlinked.recognizer().state().linked_frames, 0);
  unlinked.driveElsewhere(60);
  const MappingDrive::Counts unlinked_third = unlinked.revisit(100, 300);
  EXPECT_LT(unlinked_third.right, second.right / 2);
  unlinked.stop();

  drive.start();
  EXPECT_EQ(drive.recognizer().state().linked_frames, linked);
  for (int visit = 3; visit <= 4; ++visit) {
    drive.driveElsewhere(60);
    const MappingDrive::Counts again = drive.revisit(100, 300);
    EXPECT_GE(again.right, second.right - 5) << "visit " << visit;
    EXPECT_EQ(again.wrong, 0) << "visit " << visit;
    drive.stop();
    drive.start();
  }

}

// A map saved (from its database, or from memory) and loaded again keeps its links, and a reset
// forgets them with the frames.
TEST_F(StoredPlaceLinksTest, SaveAndLoadCarryThePlaceLinksAndResetForgetsThem) {
  MappingDrive drive(path("map.db"));
  drive.mapAndRevisit();
  const int linked = drive.recognizer().state().linked_frames;
  ASSERT_GT(linked, 0);
  drive.map().save(path("saved.db"));
  // One row a link that joined two places.
  EXPECT_EQ(MapDatabase(path("saved.db"), MapAccess::kReadOnly).placeLinks().size(), static_cast<std::size_t>(linked));
  {
    PlaceRecognizer recognizer(testing_support::routeParameters());
    PersistentMap in_memory(recognizer);
    in_memory.load(path("saved.db"));
    EXPECT_EQ(recognizer.state().linked_frames, linked);
    in_memory.save(path("from_memory.db"));
  }
  {
    PlaceRecognizer recognizer(testing_support::routeParameters());
    PersistentMap map(recognizer, path("other.db"), CommitPolicy{});
    map.load(path("from_memory.db"));
    EXPECT_EQ(recognizer.state().linked_frames, linked);
  }
  EXPECT_EQ(MapDatabase(path("other.db"), MapAccess::kReadOnly).placeLinks().size(), static_cast<std::size_t>(linked));
  drive.map().reset();
  EXPECT_EQ(drive.recognizer().state().linked_frames, 0);
  drive.stop();
  EXPECT_TRUE(MapDatabase(path("map.db"), MapAccess::kReadOnly).placeLinks().empty());
}

// A closure that the robot's back end refused: its link goes from the map and from its database, so
// that it stays gone after a restart, and asking again, or about frames it does not hold, is refused.
TEST_F(StoredPlaceLinksTest, ARejectedClosuresLinkIsForgottenInTheMapAndItsDatabase) {
  MappingDrive drive(path("map.db"));
  drive.mapAndRevisit();
  drive.stop();  // The database is the node's alone while it runs.
  const std::vector<PlaceLink> stored = MapDatabase(path("map.db"), MapAccess::kReadOnly).placeLinks();
  drive.start();
  const int linked = drive.recognizer().state().linked_frames;
  ASSERT_GT(linked, 10);
  ASSERT_EQ(stored.size(), static_cast<std::size_t>(linked));
  const PlaceLink rejected = stored[stored.size() / 2];
  const std::vector<PlaceLink> forgotten = drive.map().forgetClosure(rejected.frame, rejected.reference);
  EXPECT_EQ(pairsOf(forgotten), pairsOf({rejected}));
  EXPECT_EQ(drive.recognizer().state().linked_frames, linked - 1);
  EXPECT_THROW(drive.map().forgetClosure(rejected.frame, rejected.reference), std::invalid_argument);
  EXPECT_THROW(drive.map().forgetClosure(rejected.frame, drive.recognizer().size()), std::invalid_argument);
  EXPECT_THROW(drive.map().forgetClosure(-1, rejected.reference), std::invalid_argument);
  drive.stop();
  std::vector<PlaceLink> kept = stored;
  kept.erase(kept.begin() + static_cast<std::ptrdiff_t>(stored.size() / 2));
  EXPECT_EQ(pairsOf(MapDatabase(path("map.db"), MapAccess::kReadOnly).placeLinks()), pairsOf(kept));
  drive.start();
  EXPECT_EQ(drive.recognizer().state().linked_frames, linked - 1);
  EXPECT_TRUE(drive.recognizer().linksOfClosure(rejected.frame, rejected.reference).empty());
  drive.stop();

  // In memory only (no ~database), from a map loaded with the links.
  PlaceRecognizer recognizer(testing_support::routeParameters());
  PersistentMap in_memory(recognizer);
  in_memory.load(path("map.db"));
  const PlaceLink other = kept.front();
  EXPECT_EQ(pairsOf(in_memory.forgetClosure(other.frame, other.reference)), pairsOf({other}));
  EXPECT_EQ(recognizer.state().linked_frames, linked - 2);
}

// Links made of the old map while load() replaces it name the old map's frames: none may reach the
// new map's database. Whatever the timing, the database holds the links the map holds, of its frames.
// (Without the hold-back, a commit between the rewrite and the swap wrote 5 to 14 of them there.)
TEST_F(StoredPlaceLinksTest, LinksMadeWhileAMapIsLoadedNeverReachTheLoadedMapsDatabase) {
  {
    MappingDrive route(path("route.db"));
    route.start();
    route.mapRoute();
    route.map().save(path("saved.db"));
  }
  MappingDrive drive(path("map.db"), CommitPolicy{0.001, 1});  // a commit after each keyframe
  drive.start();
  drive.mapRoute();
  drive.driveElsewhere(60);
  std::atomic<bool> loaded{false};
  std::thread camera([&] { drive.revisit(100, 500); });  // closing loops, linking, meanwhile
  std::thread committer([&] {  // a commit at any moment, the one between the rewrite and the swap too
    while (!loaded) drive.map().commit();
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(40));
  drive.map().load(path("saved.db"));
  loaded = true;
  committer.join();
  camera.join();
  const int linked = drive.recognizer().state().linked_frames;
  drive.stop();
  const MapDatabase database(path("map.db"), MapAccess::kReadOnly);
  const std::vector<PlaceLink> links = database.placeLinks();  // every one two of its frames (else it throws)
  PlaceLinks stored;
  stored.adopt(PlaceLinks::placesOf(links, static_cast<int>(database.size())), std::vector<PlaceLink>(links));
  EXPECT_EQ(stored.linkedFrames(), linked);
  EXPECT_EQ(links.size(), static_cast<std::size_t>(linked));
  EXPECT_GT(linked, 0);  // the new map's own loops, closed after the load
}

}  // namespace
}  // namespace mrs_vpr

#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <optional>
#include <random>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <sqlite3.h>

#include "mrs_vpr/store/persistent_map.hpp"
#include "mrs_vpr/synthetic_route.hpp"
#include "support/temporary_folder.hpp"

namespace mrs_vpr {
namespace {

namespace fs = std::filesystem;
using testing_support::fileContents;

/// A small generated route, described once for every test.
const SyntheticRoute& route() {
  static const SyntheticRoute generated = [] {
    SyntheticRouteParams params;
    params.reference_frames = 300;
    params.query_frames = 200;
    return generateSyntheticRoute(params);
  }();
  return generated;
}

const std::vector<cv::Mat>& referenceDescriptors() {
  static const std::vector<cv::Mat> described = [] {
    const DescriptorExtractor extractor{DescriptorParams{}};
    std::vector<cv::Mat> result;
    for (const cv::Mat& image : route().reference) result.push_back(extractor.compute(image));
    return result;
  }();
  return described;
}

/// Frame i's stamp: i seconds.
Stamp secondsStamp(int i) { return Stamp::fromSecondsAndNanoseconds(static_cast<std::uint32_t>(i), 0); }

/// The map's frames as (descriptor, stamp), copied.
std::vector<std::pair<cv::Mat, Stamp>> framesOf(const PlaceRecognizer& recognizer) {
  std::vector<std::pair<cv::Mat, Stamp>> frames;
  recognizer.visitFrames(0, recognizer.size(), [&](const cv::Mat& descriptor, Stamp stamp) {
    frames.emplace_back(descriptor.clone(), stamp);
  });
  return frames;
}

/// The database's frames as (descriptor, stamp), copied.
std::vector<std::pair<cv::Mat, Stamp>> framesOf(const std::string& path) {
  std::vector<std::pair<cv::Mat, Stamp>> frames;
  MapDatabase(path, DescriptorParams{}, MapAccess::kReadOnly).forEachFrame([&](const StoredFrame& frame) {
    frames.emplace_back(frame.descriptor.clone(), frame.stamp);
  });
  return frames;
}

/// The database's frames' ids and numbers.
std::vector<std::pair<std::string, std::int64_t>> labelsOf(const std::string& path) {
  std::vector<std::pair<std::string, std::int64_t>> labels;
  MapDatabase(path, DescriptorParams{}, MapAccess::kReadOnly).forEachFrame([&](const StoredFrame& frame) {
    labels.emplace_back(frame.frame_id, frame.sequence);
  });
  return labels;
}

/// The map's frames' ids and numbers, as PersistentMap tells them.
std::vector<std::pair<std::string, std::int64_t>> labelsOf(const PersistentMap& map, int frames) {
  std::vector<std::pair<std::string, std::int64_t>> labels;
  for (int i = 0; i < frames; ++i) labels.emplace_back(map.frameIdOf(i), map.sequenceOf(i));
  return labels;
}

/// The labels addReference gives frames [begin, end): frame id "camera", number i.
std::vector<std::pair<std::string, std::int64_t>> expectedLabels(int begin, int end) {
  std::vector<std::pair<std::string, std::int64_t>> labels;
  for (int i = begin; i < end; ++i) labels.emplace_back("camera", i);
  return labels;
}

/// Reference frames [begin, end) as the map should hold them: descriptor and stamp i.
std::vector<std::pair<cv::Mat, Stamp>> expectedFrames(int begin, int end) {
  std::vector<std::pair<cv::Mat, Stamp>> frames;
  for (int i = begin; i < end; ++i) {
    frames.emplace_back(referenceDescriptors()[static_cast<std::size_t>(i)], secondsStamp(i));
  }
  return frames;
}

void expectSameFrames(const std::vector<std::pair<cv::Mat, Stamp>>& actual,
                      const std::vector<std::pair<cv::Mat, Stamp>>& expected) {
  ASSERT_EQ(actual.size(), expected.size());
  for (std::size_t i = 0; i < actual.size(); ++i) {
    EXPECT_EQ(cv::norm(actual[i].first, expected[i].first, cv::NORM_L1), 0.0) << "frame " << i;
    EXPECT_EQ(actual[i].second, expected[i].second) << "frame " << i;
  }
}

class PersistentMapTest : public ::testing::Test {
 protected:
  std::string path(const std::string& name) const { return folder_.path(name); }

  static void addReference(PersistentMap& map, int begin, int end) {
    for (int i = begin; i < end; ++i) {
      ASSERT_EQ(map.add(referenceDescriptors()[static_cast<std::size_t>(i)], secondsStamp(i), "camera", i),
                FrameAdmission::kAdmitted);
    }
  }

  /// The message of the MapDatabaseError that `action` throws, or "(no error)".
  template <typename Action>
  static std::string errorOf(Action action) {
    try {
      action();
    } catch (const MapDatabaseError& error) {
      return error.what();
    }
    return "(no error)";
  }


  /// Loads `file` into `map`; true when the load was refused because the file changed meanwhile (any
  /// other refusal fails the test).
  static bool refusedAsChanged(PersistentMap& map, const std::string& file) {
    const std::string message = errorOf([&] { map.load(file); });
    if (message == "(no error)") return false;
    EXPECT_NE(message.find(file + "': it changed while it was loaded"), std::string::npos) << message;
    return true;
  }

  /// Expects `map`'s database to hold the frames of `recognizer`, read through a snapshot (the
  /// database itself is locked while the map is open).
  void expectDatabaseHoldsTheMap(PersistentMap& map, const PlaceRecognizer& recognizer) const {
    const std::string copy = path("copy.db");
    map.save(copy);
    expectSameFrames(framesOf(copy), framesOf(recognizer));
    EXPECT_EQ(labelsOf(copy), labelsOf(map, recognizer.size()));
    fs::remove(copy);
  }

  /// A map database of reference frames [begin, end) at `file`, written by a PersistentMap.
  static void writeMap(const std::string& file, int begin, int end) {
    PlaceRecognizer recognizer;
    PersistentMap map(recognizer, file, CommitPolicy{});
    addReference(map, begin, end);
  }

  testing_support::TemporaryFolder folder_{"mrs_vpr_persistent_map_test"};
};

TEST_F(PersistentMapTest, AMapOfExactlyMaxFramesStartsAndLoads) {
  writeMap(path("full.db"), 0, 40);
  RecognizerParams capacity;
  capacity.max_frames = 40;
  {
    PlaceRecognizer recognizer(Parameters{}, capacity);
    PersistentMap map(recognizer, path("full.db"), CommitPolicy{});
    expectSameFrames(framesOf(recognizer), expectedFrames(0, 40));
  }
  PlaceRecognizer recognizer(Parameters{}, capacity);
  PersistentMap map(recognizer, path("map.db"), CommitPolicy{});
  EXPECT_EQ(map.load(path("full.db")), 40);
  expectSameFrames(framesOf(recognizer), expectedFrames(0, 40));
}

// A frame the map refuses (it is full, or the frame is no keyframe) must not reach the database
// either: the next start would load other frames than the map held.
TEST_F(PersistentMapTest, FramesTheMapRefusesAreNotStored) {
  RecognizerParams capacity;
  capacity.max_frames = 10;
  {
    PlaceRecognizer recognizer(Parameters{}, capacity);
    PersistentMap map(recognizer, path("map.db"), CommitPolicy{});
    addReference(map, 0, 9);
    EXPECT_EQ(map.offer(referenceDescriptors()[8], secondsStamp(9), "camera", 9), FrameAdmission::kTooSimilar);
    addReference(map, 9, 10);
    EXPECT_EQ(map.add(referenceDescriptors()[10], secondsStamp(10), "camera", 10), FrameAdmission::kMapFull);
    map.commit();
    EXPECT_EQ(map.persisted(), 10U);
  }
  expectSameFrames(framesOf(path("map.db")), expectedFrames(0, 10));
}

TEST_F(PersistentMapTest, ARestartedMapHoldsEveryFrameInOrderAndAnswersAboutThem) {
  {
    PlaceRecognizer recognizer;
    PersistentMap map(recognizer, path("map.db"), CommitPolicy{});
    addReference(map, 0, 300);
  }  // A clean stop commits what is queued.
  // Every stored frame is a keyframe already; the test frames are matched as they are, like them.
  RecognizerParams every_frame;
  every_frame.min_appearance_change = 0.0;
  PlaceRecognizer recognizer(Parameters(), every_frame);
  PersistentMap map(recognizer, path("map.db"), CommitPolicy{});
  EXPECT_EQ(map.persisted(), 300U);
  expectSameFrames(framesOf(recognizer), expectedFrames(0, 300));
  // The query traversal's frames 60..139 lie in the restored map.
  const std::vector<cv::Mat> test(route().query.begin() + 60, route().query.begin() + 140);
  const PlaceAnswer answer = recognizer.match(test, "seqslam");
  // The answer localises the test sequence's middle frame (sequence/alignment centred, the default).
  EXPECT_NEAR(answer.match.reference_index, route().query_to_reference[60 + answer.localised_row], 3);
  EXPECT_EQ(answer.localised_row, 40);
  EXPECT_TRUE(answer.match.accepted);
}

TEST_F(PersistentMapTest, FramesAddedAfterARestartFollowTheLoadedOnes) {
  writeMap(path("map.db"), 0, 100);
  {
    PlaceRecognizer recognizer;
    PersistentMap map(recognizer, path("map.db"), CommitPolicy{});
    addReference(map, 100, 150);
  }
  expectSameFrames(framesOf(path("map.db")), expectedFrames(0, 150));
}

// The junction of two drives (drive_starts.hpp) is one after a restart, a save and a load, in the
// recognizer and in the database: the next day's run must not take yesterday's junction for a place.
TEST_F(PersistentMapTest, DriveStartsLastThroughARestartASaveAndALoadAndGoWithAReset) {
  writeMap(path("map.db"), 0, 100);
  {
    PlaceRecognizer recognizer;
    PersistentMap map(recognizer, path("map.db"), CommitPolicy{});
    map.startDrive(100);  // a camera's run after the loaded map
    addReference(map, 100, 150);
  }
  {
    PlaceRecognizer recognizer;
    PersistentMap map(recognizer, path("map.db"), CommitPolicy{});
    EXPECT_EQ(recognizer.driveStarts(), (std::vector<int>{100}));
    map.startDrive(150);  // the next run, with no frame yet
    EXPECT_EQ(recognizer.driveStarts(), (std::vector<int>{100, 150}));
    map.save(path("snapshot.db"));
  }
  EXPECT_EQ(MapDatabase(path("map.db"), MapAccess::kReadOnly).driveStarts(), (std::vector<int>{100, 150}));
  EXPECT_EQ(MapDatabase(path("snapshot.db"), MapAccess::kReadOnly).driveStarts(), (std::vector<int>{100, 150}));

  PlaceRecognizer memory_only;
  PersistentMap in_memory(memory_only);
  EXPECT_EQ(in_memory.load(path("snapshot.db")), 150);
  EXPECT_EQ(memory_only.driveStarts(), (std::vector<int>{100, 150}));
  in_memory.startDrive(150);  // marked once
  addReference(in_memory, 150, 160);
  in_memory.save(path("from_memory.db"));
  EXPECT_EQ(MapDatabase(path("from_memory.db"), MapAccess::kReadOnly).driveStarts(), (std::vector<int>{100, 150}));

  PlaceRecognizer recognizer;
  PersistentMap other(recognizer, path("other.db"), CommitPolicy{});
  EXPECT_EQ(other.load(path("from_memory.db")), 160);
  EXPECT_EQ(recognizer.driveStarts(), (std::vector<int>{100, 150}));
  other.reset();
  EXPECT_TRUE(recognizer.driveStarts().empty());
  other.commit();
  other.save(path("after_reset.db"));
  EXPECT_TRUE(MapDatabase(path("after_reset.db"), MapAccess::kReadOnly).driveStarts().empty());
}

TEST_F(PersistentMapTest, QueuedCountsTheFramesNotYetCommitted) {
  PlaceRecognizer recognizer;
  PersistentMap map(recognizer, path("map.db"), CommitPolicy{60.0, 1000});
  addReference(map, 0, 5);
  EXPECT_EQ(map.queued(), 5U);
  map.commit();
  EXPECT_EQ(map.queued(), 0U);
  EXPECT_EQ(map.persisted(), 5U);
  // Closing commits what is queued and says what it could not commit: here nothing.
  addReference(map, 5, 8);
  EXPECT_EQ(map.queued(), 3U);
  EXPECT_EQ(map.close(), 0U);
  EXPECT_EQ(map.persisted(), 8U);
  EXPECT_EQ(map.close(), 0U);
  PlaceRecognizer in_memory_recognizer;
  PersistentMap in_memory(in_memory_recognizer);
  EXPECT_EQ(in_memory.queued(), 0U);
  EXPECT_EQ(in_memory.close(), 0U);
}

TEST_F(PersistentMapTest, ResetEmptiesTheMapAndTheDatabase) {
  PlaceRecognizer recognizer;
  {
    PersistentMap map(recognizer, path("map.db"), CommitPolicy{3600.0, 1000});
    addReference(map, 0, 50);
    EXPECT_EQ(map.reset(), 50);
    EXPECT_EQ(recognizer.size(), 0);
    EXPECT_EQ(map.persisted(), 0U);
    EXPECT_EQ(map.frameIdOf(0), "");
    EXPECT_EQ(map.sequenceOf(0), -1);
    addReference(map, 50, 60);
    EXPECT_EQ(labelsOf(map, 10), expectedLabels(50, 60));
  }
  expectSameFrames(framesOf(path("map.db")), expectedFrames(50, 60));
}

TEST_F(PersistentMapTest, SaveWritesASnapshotWhileFramesKeepArriving) {
  PlaceRecognizer recognizer;
  PersistentMap map(recognizer, path("map.db"), CommitPolicy{0.05, 20});
  addReference(map, 0, 100);
  std::atomic<bool> saved{false};
  std::thread camera([&] {
    for (int i = 100; i < 300 && !saved; ++i) {
      map.add(referenceDescriptors()[static_cast<std::size_t>(i)], secondsStamp(i));
    }
  });
  const std::int64_t frames = map.save(path("snapshot.db"));
  saved = true;
  camera.join();
  // A consistent moment of the map: every frame added before the call, then a prefix of the rest.
  EXPECT_GE(frames, 100);
  expectSameFrames(framesOf(path("snapshot.db")), expectedFrames(0, static_cast<int>(frames)));
  // One self-contained file, nothing left aside.
  EXPECT_FALSE(fs::exists(path("snapshot.db-wal")));
  EXPECT_FALSE(fs::exists(path("snapshot.db.part")));
}

TEST_F(PersistentMapTest, SaveNeverOverwritesAFile) {
  PlaceRecognizer recognizer;
  PersistentMap map(recognizer, path("map.db"), CommitPolicy{});
  addReference(map, 0, 10);
  {
    std::ofstream notes(path("notes.db"));
    notes << "my notes\n";
  }
  const std::string message = errorOf([&] { map.save(path("notes.db")); });
  EXPECT_NE(message.find(path("notes.db")), std::string::npos) << message;
  EXPECT_NE(message.find("exists"), std::string::npos) << message;
  EXPECT_EQ(fileContents(path("notes.db")), "my notes\n");
  const std::string no_folder = errorOf([&] { map.save(path("missing/map.db")); });
  EXPECT_NE(no_folder.find("no folder"), std::string::npos) << no_folder;
  // Through a link, to a file or to none yet: the file it names, never overwritten; the link stays
  // (a save replaced it by the map), with a database and in memory alike.
  fs::create_symlink(path("notes.db"), path("to_notes.db"));
  EXPECT_NE(errorOf([&] { map.save(path("to_notes.db")); }).find("exists"), std::string::npos);
  EXPECT_EQ(fileContents(path("notes.db")), "my notes\n");
  fs::create_directory(path("maps"));
  PlaceRecognizer in_memory_recognizer;
  PersistentMap in_memory(in_memory_recognizer);
  addReference(in_memory, 0, 4);
  for (PersistentMap* saved : {&map, &in_memory}) {
    const std::string name = saved == &map ? "with_database" : "in_memory";
    fs::create_symlink("maps/" + name + ".db", path(name + "_link.db"));
    ASSERT_EQ(saved->save(path(name + "_link.db")), saved == &map ? 10 : 4) << name;
    EXPECT_TRUE(fs::is_symlink(path(name + "_link.db"))) << name;
    EXPECT_EQ(framesOf(path("maps/" + name + ".db")).size(), saved == &map ? 10U : 4U) << name;
  }
  // A loop of links leads to no file: refused, and the links stay.
  fs::create_symlink(path("loop_b.db"), path("loop_a.db"));
  fs::create_symlink(path("loop_a.db"), path("loop_b.db"));
  for (PersistentMap* saved : {&map, &in_memory}) {
    const std::string loop = errorOf([&] { saved->save(path("loop_a.db")); });
    EXPECT_NE(loop.find("it is a link that leads to no file (a loop of links"), std::string::npos) << loop;
    EXPECT_TRUE(fs::is_symlink(path("loop_a.db")));
  }
}

TEST_F(PersistentMapTest, AMapInMemoryIsSavedAsADatabase) {
  PlaceRecognizer recognizer;
  PersistentMap map(recognizer);
  addReference(map, 0, 120);
  EXPECT_FALSE(map.persistent());
  EXPECT_EQ(map.persisted(), 0U);
  EXPECT_EQ(map.save(path("memory.db")), 120);
  expectSameFrames(framesOf(path("memory.db")), expectedFrames(0, 120));
  EXPECT_EQ(labelsOf(path("memory.db")), expectedLabels(0, 120));  // Not "" and -1, which lost them.
  EXPECT_FALSE(fs::exists(path("memory.db.build")));
  // The scratch file's name holding a file of the user's: refused, and the file left alone.
  std::ofstream(path("notes.db.build")) << "mine\n";
  const std::string refused = errorOf([&] { map.save(path("notes.db")); });
  EXPECT_NE(refused.find("'" + path("notes.db.build") + "'"), std::string::npos) << refused;
  EXPECT_EQ(fileContents(path("notes.db.build")), "mine\n");
  EXPECT_FALSE(fs::exists(path("notes.db")));
}

TEST_F(PersistentMapTest, ARecognizerThatHoldsFramesAlreadyIsRefused) {
  // Frames that did not come through the PersistentMap have no frame ids or numbers to save.
  PlaceRecognizer recognizer;
  recognizer.addDescriptor(referenceDescriptors()[0], secondsStamp(0));
  EXPECT_THROW(PersistentMap{recognizer}, std::logic_error);
  EXPECT_THROW((PersistentMap{recognizer, path("map.db"), CommitPolicy{}}), std::logic_error);
}

TEST_F(PersistentMapTest, AMapInMemoryKeepsTheFrameIdsAndNumbersOfTheMapItLoaded) {
  writeMap(path("saved.db"), 200, 260);
  PlaceRecognizer recognizer;
  PersistentMap map(recognizer);
  addReference(map, 0, 10);
  ASSERT_EQ(map.load(path("saved.db")), 60);
  EXPECT_EQ(labelsOf(map, 60), expectedLabels(200, 260));
  map.add(referenceDescriptors()[0], secondsStamp(1000), "other_camera", 7);
  EXPECT_EQ(map.frameIdOf(60), "other_camera");
  EXPECT_EQ(map.sequenceOf(60), 7);
  EXPECT_EQ(map.frameIdOf(61), "");  // No such frame.
  ASSERT_EQ(map.save(path("again.db")), 61);
  auto expected = expectedLabels(200, 260);
  expected.emplace_back("other_camera", 7);
  EXPECT_EQ(labelsOf(path("again.db")), expected);
}

TEST_F(PersistentMapTest, AMapSavedAsItWasLoadedKeepsItsRecordedTraversalAndOneWithNewFramesDoesNot) {
  // A node's ~load_map then ~save_map: the copy is the loaded map, kept of the same traversal.
  writeMap(path("saved.db"), 200, 260);
  MapTraversal recorded;
  recorded.frames = 75;
  recorded.min_appearance_change = 0.4;
  MapDatabase(path("saved.db"), DescriptorParams{}).setTraversal(recorded);
  const auto traversalOf = [](const std::string& file) {
    return MapDatabase(file, DescriptorParams{}, MapAccess::kReadOnly).traversal();
  };
  for (const bool with_database : {true, false}) {
    SCOPED_TRACE(with_database ? "with a database" : "in memory");
    const std::string prefix = with_database ? "database_" : "memory_";
    PlaceRecognizer recognizer;
    std::unique_ptr<PersistentMap> map = with_database
                                             ? std::make_unique<PersistentMap>(recognizer, path(prefix + "map.db"),
                                                                               CommitPolicy{})
                                             : std::make_unique<PersistentMap>(recognizer);
    addReference(*map, 0, 10);
    ASSERT_EQ(map->load(path("saved.db")), 60);
    ASSERT_EQ(map->save(path(prefix + "as_loaded.db")), 60);
    const std::optional<MapTraversal> kept = traversalOf(path(prefix + "as_loaded.db"));
    ASSERT_TRUE(kept.has_value());
    EXPECT_EQ(kept->frames, 75);
    EXPECT_EQ(kept->min_appearance_change, 0.4);
    // A frame more, and the map is no longer that traversal's alone.
    addReference(*map, 260, 261);
    map->commit();
    ASSERT_EQ(map->save(path(prefix + "grown.db")), 61);
    EXPECT_FALSE(traversalOf(path(prefix + "grown.db")).has_value());
    // Emptied, nothing of it is left either.
    map->reset();
    ASSERT_EQ(map->save(path(prefix + "emptied.db")), 0);
    EXPECT_FALSE(traversalOf(path(prefix + "emptied.db")).has_value());
  }
}

TEST_F(PersistentMapTest, LoadReplacesTheMapAndTheDatabase) {
  writeMap(path("saved.db"), 200, 260);
  {
    PlaceRecognizer recognizer;
    PersistentMap map(recognizer, path("map.db"), CommitPolicy{});
    addReference(map, 0, 100);
    EXPECT_EQ(map.load(path("saved.db")), 60);
    EXPECT_EQ(map.persisted(), 60U);
    expectSameFrames(framesOf(recognizer), expectedFrames(200, 260));
    addReference(map, 260, 270);  // Frames after a load follow the loaded ones.
  }
  expectSameFrames(framesOf(path("map.db")), expectedFrames(200, 270));
  expectSameFrames(framesOf(path("saved.db")), expectedFrames(200, 260));  // Only read.
}

/// What a camera thread saw while a PersistentMap loaded a large map: the map's and the database's
/// frames after the load, and each added frame's admission.
struct LoadWhileFramesArrive {
  static constexpr int kSaved = 20000;          // Large enough that rewriting the database takes a while.
  static constexpr int kCameraStart = 1000000;  // The camera's frame i has stamp kCameraStart + i.
  std::vector<std::pair<cv::Mat, Stamp>> in_map;
  std::vector<std::pair<cv::Mat, Stamp>> in_database;
  std::vector<FrameAdmission> admissions;  // Of the camera's frames, in order.
  int last_before_load_returned = -1;      // The camera's last frame whose add() returned before load() did.

  /// The camera's frame that `frame` is, or -1 for a frame of the saved map.
  static int cameraFrame(const std::pair<cv::Mat, Stamp>& frame) {
    const std::int64_t seconds = frame.second.nanoseconds() / 1000000000;
    return seconds >= kCameraStart ? static_cast<int>(seconds - kCameraStart) : -1;
  }
};

LoadWhileFramesArrive loadWhileFramesArrive(const std::string& folder, int max_frames) {
  const std::string saved_path = folder + "/saved.db";
  if (!fs::exists(saved_path)) {
    PlaceRecognizer recognizer;
    PersistentMap saved(recognizer, saved_path, CommitPolicy{});
    for (int i = 0; i < LoadWhileFramesArrive::kSaved; ++i) {
      saved.add(referenceDescriptors()[static_cast<std::size_t>(i % 300)], secondsStamp(i));
    }
  }
  LoadWhileFramesArrive seen;
  const std::string map_path = folder + "/map" + std::to_string(max_frames) + ".db";
  RecognizerParams capacity;
  capacity.max_frames = max_frames;
  PlaceRecognizer recognizer(Parameters{}, capacity);
  {
    PersistentMap map(recognizer, map_path, CommitPolicy{0.05, 20});
    std::atomic<bool> loaded{false};
    std::thread camera([&] {
      for (int i = 0; !loaded; ++i) {
        seen.admissions.push_back(map.add(referenceDescriptors()[static_cast<std::size_t>(i % 300)],
                                          secondsStamp(LoadWhileFramesArrive::kCameraStart + i)));
        if (!loaded) seen.last_before_load_returned = i;
        std::this_thread::sleep_for(std::chrono::microseconds(100));  // A fast camera, not a flood.
      }
    });
    EXPECT_EQ(map.load(saved_path), LoadWhileFramesArrive::kSaved);
    loaded = true;
    camera.join();
    seen.in_map = framesOf(recognizer);
  }
  seen.in_database = framesOf(map_path);
  return seen;
}

/// The saved map's frames, then each of the camera's frames admitted from the first one kept on, in
/// both the map and the database.
void expectLoadedThenAdmitted(const LoadWhileFramesArrive& seen) {
  ASSERT_EQ(seen.in_database.size(), seen.in_map.size());
  for (std::size_t i = 0; i < seen.in_map.size(); ++i) ASSERT_EQ(seen.in_database[i].second, seen.in_map[i].second);
  ASSERT_GT(seen.in_map.size(), static_cast<std::size_t>(LoadWhileFramesArrive::kSaved));
  for (int i = 0; i < LoadWhileFramesArrive::kSaved; ++i) {
    ASSERT_EQ(seen.in_map[static_cast<std::size_t>(i)].second, secondsStamp(i)) << i;
  }
  std::vector<int> kept;
  for (std::size_t i = LoadWhileFramesArrive::kSaved; i < seen.in_map.size(); ++i) {
    kept.push_back(LoadWhileFramesArrive::cameraFrame(seen.in_map[i]));
  }
  std::vector<int> admitted;
  for (int i = kept.front(); i < static_cast<int>(seen.admissions.size()); ++i) {
    if (seen.admissions[static_cast<std::size_t>(i)] == FrameAdmission::kAdmitted) admitted.push_back(i);
  }
  EXPECT_EQ(kept, admitted);
}

TEST_F(PersistentMapTest, FramesArrivingWhileLoadRewritesTheDatabaseJoinTheLoadedMapWithoutWaiting) {
  const LoadWhileFramesArrive seen = loadWhileFramesArrive(folder_.path(""), 0);
  ASSERT_NO_FATAL_FAILURE(expectLoadedThenAdmitted(seen));
  // Frames kept that were added while the database was being rewritten: the camera did not wait for
  // the rewrite (when it did, only frames added after the swap were kept).
  const int first = LoadWhileFramesArrive::cameraFrame(seen.in_map[LoadWhileFramesArrive::kSaved]);
  EXPECT_GE(seen.last_before_load_returned - first, 10) << "first camera frame kept " << first;
}

TEST_F(PersistentMapTest, FramesArrivingWhileLoadRewritesTheDatabaseAreAdmittedOnlyAsTheNewMapHasRoom) {
  constexpr int kRoom = 5;
  const LoadWhileFramesArrive seen = loadWhileFramesArrive(folder_.path(""), LoadWhileFramesArrive::kSaved + kRoom);
  ASSERT_NO_FATAL_FAILURE(expectLoadedThenAdmitted(seen));  // Every frame said admitted is in both.
  EXPECT_LE(seen.in_map.size(), static_cast<std::size_t>(LoadWhileFramesArrive::kSaved + kRoom));
  EXPECT_NE(std::count(seen.admissions.begin(), seen.admissions.end(), FrameAdmission::kMapFull), 0);
}

// load() reads the file twice (once for the map, once for the database) rather than holding it in
// memory: while another program appends to the file, each load either gives the map and the database
// the same frames or is refused, naming the file, and leaves both as they were.
TEST_F(PersistentMapTest, AFileThatChangesWhileItIsLoadedLeavesTheMapEqualToItsDatabase) {
  writeMap(path("growing.db"), 0, 200);
  constexpr int kAppended = 20000;  // rows the other program appends at most
  std::atomic<bool> done{false};
  std::atomic<int> appended{0};
  std::thread writer([&] {  // Another program, say sqlite3: a node's own database is locked for others.
    sqlite3* db = nullptr;
    ASSERT_EQ(sqlite3_open(path("growing.db").c_str(), &db), SQLITE_OK);
    sqlite3_busy_timeout(db, 1000);
    while (!done && appended < kAppended) {
      const int inserted = sqlite3_exec(db,
                                        "INSERT INTO frames (stamp_ns, frame_id, sequence, descriptor) "
                                        "SELECT stamp_ns + 1000000000000, frame_id, sequence, descriptor "
                                        "FROM frames WHERE id = 1",
                                        nullptr, nullptr, nullptr);
      EXPECT_EQ(inserted, SQLITE_OK) << sqlite3_errmsg(db);
      if (inserted != SQLITE_OK) break;
      ++appended;
    }
    sqlite3_close(db);
  });
  PlaceRecognizer recognizer;
  int refused = 0;
  {
    PersistentMap map(recognizer, path("map.db"), CommitPolicy{});
    addReference(map, 0, 30);
    for (int attempt = 0; attempt < 20; ++attempt) {
      SCOPED_TRACE(attempt);
      if (refusedAsChanged(map, path("growing.db"))) ++refused;
      expectDatabaseHoldsTheMap(map, recognizer);
      EXPECT_TRUE(recognizer.size() == 30 || recognizer.size() >= 200) << recognizer.size();  // its own, or a load's
    }
  }
  done = true;
  writer.join();
  std::cout << refused << " of 20 loads refused while " << appended << " rows were appended" << std::endl;
}

// The second read must give the very frames of the first, not only as many: a row changed in place (another
// stamp, the same count) or removed between the reads is refused like a row appended, else the map holds
// one frame and the database another, or the map a frame that the database lacks. One kind of change at a
// time: a stamp changed as well would be refused for the stamp whatever became of a removed row.
TEST_F(PersistentMapTest, AFileWhoseRowsChangeOrGoWhileItIsLoadedLeavesTheMapEqualToItsDatabase) {
  writeMap(path("changing.db"), 0, 300);
  const std::vector<std::vector<const char*>> kinds = {
      {"UPDATE frames SET stamp_ns = stamp_ns + 1 WHERE id = 150"},  // a row changed in place
      {"UPDATE frames SET frame_id = frame_id || 'x' WHERE id = 150"},  // only its frame id
      {"UPDATE frames SET sequence = sequence + 1 WHERE id = 150"},     // only its number
      {"INSERT INTO frames (stamp_ns, frame_id, sequence, descriptor) "  // a row appended, then removed
       "SELECT stamp_ns + 1000000000000, frame_id, sequence, descriptor FROM frames WHERE id = 1",
       "DELETE FROM frames WHERE id = (SELECT MAX(id) FROM frames)"},
  };
  // Another program, say sqlite3: open, and its first read done, before any load, as a load meeting the
  // first connection's setup of the file's log would be refused for a lock.
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path("changing.db").c_str(), &db), SQLITE_OK);
  sqlite3_busy_timeout(db, 1000);
  ASSERT_EQ(sqlite3_exec(db, "SELECT COUNT(*) FROM frames", nullptr, nullptr, nullptr), SQLITE_OK);
  PlaceRecognizer recognizer;
  PersistentMap map(recognizer, path("map.db"), CommitPolicy{});
  addReference(map, 0, 30);
  for (const std::vector<const char*>& changes : kinds) {
    SCOPED_TRACE(changes.front());
    std::atomic<bool> done{false};
    std::thread writer([&] {  // Not paced: most loads meet a change between their reads.
      for (std::size_t i = 0; !done; ++i) {
        const int changed = sqlite3_exec(db, changes[i % changes.size()], nullptr, nullptr, nullptr);
        EXPECT_EQ(changed, SQLITE_OK) << sqlite3_errmsg(db);
        if (changed != SQLITE_OK) break;
      }
    });
    int refused = 0;
    int attempts = 0;
    for (; attempts < 200 && refused < 10 && !HasFatalFailure(); ++attempts) {
      SCOPED_TRACE(attempts);
      if (refusedAsChanged(map, path("changing.db"))) ++refused;
      expectDatabaseHoldsTheMap(map, recognizer);
    }
    done = true;
    writer.join();
    std::cout << refused << " of " << attempts << " loads refused" << std::endl;
  }
  sqlite3_close(db);
}

TEST_F(PersistentMapTest, LoadRefusesBadFilesNamingThemAndKeepsTheMap) {
  writeMap(path("big.db"), 0, 50);
  {
    std::ofstream text(path("notes.db"));
    text << "my notes, not a map\n";
  }
  sqlite3* db = nullptr;
  ASSERT_EQ(sqlite3_open(path("other.db").c_str(), &db), SQLITE_OK);
  sqlite3_exec(db, "CREATE TABLE recipes (name TEXT)", nullptr, nullptr, nullptr);
  sqlite3_close(db);
  writeMap(path("truncated.db"), 0, 300);
  fs::resize_file(path("truncated.db"), fs::file_size(path("truncated.db")) / 2);
  // Every frame of it reads, but its free list points past the file (the header's first free-list trunk
  // page and count of free pages): only SQLite's check tells, and a map written over it would fail.
  writeMap(path("free_list.db"), 0, 20);
  {
    std::fstream file(path("free_list.db"), std::ios::in | std::ios::out | std::ios::binary);
    file.seekp(32);
    file.write("\0\0\x27\x0f\0\0\0\x01", 8);
  }
  {
    DescriptorParams params;  // Another front end.
    params.type = kThumbnailFrontEnd;
    params.image_width = 32;
    MapDatabase other(path("small.db"), params);
  }

  RecognizerParams capacity;
  capacity.max_frames = 40;
  PlaceRecognizer recognizer(Parameters{}, capacity);
  PersistentMap map(recognizer, path("map.db"), CommitPolicy{});
  addReference(map, 0, 30);
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"notes.db", "not a database"},
      {"other.db", "another kind"},
      {"truncated.db", "malformed"},
      {"free_list.db", "it is corrupt or truncated (SQLite's quick_check finds"},
      {"small.db",
       "descriptors of the thumbnail (32 x 32, patches of 8 px) front end, not of the hog (128 x 64 window"},
      {"big.db", "50 frames, more than max_frames (40): raise max_frames to at least that, or to 0 (unbounded)"},
      {"missing.db", "no such file"},
      {"map.db", "own database"},
  };
  for (const auto& [file, problem] : cases) {
    SCOPED_TRACE(file);
    const std::string before = fileContents(path(file));
    const std::string message = errorOf([&] { map.load(path(file)); });
    EXPECT_NE(message.find(path(file)), std::string::npos) << message;
    EXPECT_NE(message.find(problem), std::string::npos) << message;
    if (file != "map.db") EXPECT_EQ(fileContents(path(file)), before) << "the file was changed";
    expectSameFrames(framesOf(recognizer), expectedFrames(0, 30));
  }
  map.commit();
  EXPECT_EQ(map.persisted(), 30U);
}

TEST_F(PersistentMapTest, StartingOnABadDatabaseFailsNamingItAndLeavesItUntouched) {
  {
    std::ofstream text(path("notes.db"));
    text << "my notes, not a map\n";
  }
  writeMap(path("truncated.db"), 0, 300);
  fs::resize_file(path("truncated.db"), fs::file_size(path("truncated.db")) / 2);
  writeMap(path("big.db"), 0, 50);
  for (const auto& [file, problem] : std::vector<std::pair<std::string, std::string>>{
           {"notes.db", "not a database"}, {"truncated.db", "malformed"}, {"big.db", "more than max_frames"}}) {
    SCOPED_TRACE(file);
    const std::string before = fileContents(path(file));
    RecognizerParams capacity;
    capacity.max_frames = 40;
    PlaceRecognizer recognizer(Parameters{}, capacity);
    const std::string message = errorOf([&] { PersistentMap map(recognizer, path(file), CommitPolicy{}); });
    EXPECT_NE(message.find(path(file)), std::string::npos) << message;
    EXPECT_NE(message.find(problem), std::string::npos) << message;
    EXPECT_EQ(fileContents(path(file)), before);
  }
  // A map held by a running owner.
  PlaceRecognizer first_recognizer;
  PersistentMap first(first_recognizer, path("map.db"), CommitPolicy{});
  PlaceRecognizer second_recognizer;
  const std::string message = errorOf([&] { PersistentMap second(second_recognizer, path("map.db"), CommitPolicy{}); });
  EXPECT_NE(message.find("locked by another process"), std::string::npos) << message;
}

TEST_F(PersistentMapTest, AKillAtAnyMomentLosesNoFrameReportedPersisted) {
  // A child adds frames at about 30 Hz with the default commit policy scaled down (0.1 s or 10
  // frames) and reports persisted() through a pipe whenever it grows; the parent kills it with
  // SIGKILL at seeded moments after its first commit (on a loaded machine, opening the database can
  // take longer than a fixed delay). Reopened, the map holds at least every frame reported, bit for bit.
  std::mt19937 rng(5);
  referenceDescriptors();  // Described before the fork, so that the child starts adding at once.
  for (int round = 0; round < 4; ++round) {
    const std::string file = path("crash" + std::to_string(round) + ".db");
    int report[2];
    ASSERT_EQ(pipe(report), 0);
    const pid_t child = fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      close(report[0]);
      PlaceRecognizer recognizer;
      PersistentMap map(recognizer, file, CommitPolicy{0.1, 10});
      std::uint64_t reported = 0;
      for (int i = 0;; i = (i + 1) % 300) {
        map.add(referenceDescriptors()[static_cast<std::size_t>(i)], secondsStamp(i));
        const std::uint64_t persisted = map.persisted();
        if (persisted != reported) {
          reported = persisted;
          if (write(report[1], &persisted, sizeof(persisted)) != sizeof(persisted)) _exit(1);
        }
        usleep(33000);
      }
    }
    close(report[1]);
    pollfd first_report{report[0], POLLIN, 0};
    const bool committed = poll(&first_report, 1, 60000) == 1;
    usleep(std::uniform_int_distribution<int>(0, 1500000)(rng));
    kill(child, SIGKILL);
    waitpid(child, nullptr, 0);
    ASSERT_TRUE(committed) << "nothing was committed within 60 s";
    std::uint64_t persisted = 0;
    std::uint64_t value = 0;
    while (read(report[0], &value, sizeof(value)) == sizeof(value)) persisted = value;
    close(report[0]);
    ASSERT_GT(persisted, 0U) << "nothing was committed in time";
    const auto frames = framesOf(file);
    EXPECT_GE(frames.size(), persisted);
    for (std::size_t i = 0; i < frames.size(); ++i) {
      EXPECT_EQ(cv::norm(frames[i].first, referenceDescriptors()[i % 300], cv::NORM_L1), 0.0) << "frame " << i;
    }
  }
}

}  // namespace
}  // namespace mrs_vpr

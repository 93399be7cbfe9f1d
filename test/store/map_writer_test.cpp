#include <atomic>
#include <chrono>
#include <cstdlib>
#include <string>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "mrs_vpr/store/map_writer.hpp"
#include "support/temporary_folder.hpp"
#include "support/front_ends.hpp"

namespace mrs_vpr {
namespace {

using testing_support::thumbnailParams;

class MapWriterTest : public ::testing::Test {
 protected:
  std::string path() const { return folder_.path("map.db"); }

  static StoredFrame frame(int i) {
    StoredFrame stored;
    stored.descriptor = cv::Mat(1, 64 * 32, CV_8UC1, cv::Scalar(i % 256));
    stored.descriptor.at<std::uint8_t>(0, 0) = static_cast<std::uint8_t>(i / 256);
    stored.stamp = Stamp::fromSecondsAndNanoseconds(i, 0);
    return stored;
  }

  /// Waits up to `seconds` for the writer to report `frames` persisted.
  static bool waitPersisted(const MapWriter& writer, std::uint64_t frames, double seconds) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
    while (writer.persisted() < frames && std::chrono::steady_clock::now() < deadline) {
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    }
    return writer.persisted() >= frames;
  }

  testing_support::TemporaryFolder folder_{"mrs_vpr_writer_test"};
};

TEST_F(MapWriterTest, AddOnlyQueuesAndTheCommitFollowsWithinThePeriod) {
  MapDatabase database(path(), thumbnailParams());
  MapWriter writer(database, CommitPolicy{2.0, 1000});
  const auto added = std::chrono::steady_clock::now();
  for (int i = 0; i < 5; ++i) writer.add(frame(i));
  // Far below the batch size: nothing is written before the period has passed, a quarter of it later
  // either (a writer that ignored the period would have committed by then).
  EXPECT_EQ(writer.persisted(), 0U);
  EXPECT_EQ(writer.queued(), 5U);
  std::this_thread::sleep_for(std::chrono::milliseconds(500));
  if (std::chrono::steady_clock::now() - added < std::chrono::milliseconds(1900)) {
    EXPECT_EQ(writer.persisted(), 0U) << "committed before the period";
  }
  EXPECT_TRUE(waitPersisted(writer, 5, 10.0));
  EXPECT_EQ(writer.queued(), 0U);
  std::int64_t stored = 0;
  writer.withDatabase([&](MapDatabase& db) { stored = db.size(); });
  EXPECT_EQ(stored, 5);
}

// A place link made with no frame after it (a robot standing, a full map) is committed within a
// period too, not with the next frame or at the stop: a kill -9 would lose it.
TEST_F(MapWriterTest, LinksWithNoFrameAfterThemAreCommittedWithinThePeriod) {
  MapDatabase database(path(), thumbnailParams());
  database.append({frame(0), frame(1), frame(2)});
  std::atomic<bool> made{false};
  std::atomic<bool> taken{false};
  MapWriter writer(database, CommitPolicy{0.05, 1000}, [&] {
    if (!made || taken.exchange(true)) return std::vector<PlaceLink>();
    return std::vector<PlaceLink>{{2, 0}};
  });
  std::this_thread::sleep_for(std::chrono::milliseconds(100));
  made = true;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (!taken && std::chrono::steady_clock::now() < deadline) {
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_TRUE(taken) << "the writer did not ask for the link";
  std::vector<PlaceLink> stored;
  writer.withDatabase([&](MapDatabase& db) { stored = db.placeLinks(); });
  ASSERT_EQ(stored.size(), 1U);
  EXPECT_EQ(stored[0].frame, 2);
  EXPECT_EQ(writer.persisted(), 3U);
}

TEST_F(MapWriterTest, AFullBatchIsCommittedWithoutWaitingForThePeriod) {
  MapDatabase database(path(), thumbnailParams());
  MapWriter writer(database, CommitPolicy{3600.0, 10});
  for (int i = 0; i < 10; ++i) writer.add(frame(i));
  EXPECT_TRUE(waitPersisted(writer, 10, 10.0)) << "the batch waited for the hour-long period";
}

TEST_F(MapWriterTest, StoppingCommitsWhatIsQueued) {
  {
    MapDatabase database(path(), thumbnailParams());
    MapWriter writer(database, CommitPolicy{3600.0, 1000});
    for (int i = 0; i < 7; ++i) writer.add(frame(i));
  }
  EXPECT_EQ(MapDatabase(path(), thumbnailParams()).size(), 7);
}

TEST_F(MapWriterTest, FramesReachTheDatabaseInTheOrderAddedWhateverCommitsThem) {
  constexpr int kFrames = 3000;
  {
    MapDatabase database(path(), thumbnailParams());
    MapWriter writer(database, CommitPolicy{0.001, 7});
    // The writer's thread, explicit commits and whole-database tasks all take batches meanwhile.
    std::thread committer([&] {
      for (int i = 0; i < 50; ++i) {
        writer.commit();
        writer.withDatabase([](MapDatabase&) {});
      }
    });
    for (int i = 0; i < kFrames; ++i) writer.add(frame(i));
    committer.join();
    writer.commit();
    EXPECT_EQ(writer.persisted(), static_cast<std::uint64_t>(kFrames));
  }
  int i = 0;
  MapDatabase(path(), thumbnailParams()).forEachFrame([&](const StoredFrame& stored) {
    EXPECT_EQ(stored.stamp, Stamp::fromSecondsAndNanoseconds(i, 0)) << "frame " << i;
    EXPECT_EQ(cv::norm(stored.descriptor, frame(i).descriptor, cv::NORM_L1), 0.0) << "frame " << i;
    ++i;
  });
  EXPECT_EQ(i, kFrames);
}

TEST_F(MapWriterTest, PersistedStartsAtTheFramesAlreadyStored) {
  {
    MapDatabase database(path(), thumbnailParams());
    database.append({frame(0), frame(1), frame(2)});
  }
  MapDatabase database(path(), thumbnailParams());
  MapWriter writer(database, CommitPolicy{});
  EXPECT_EQ(writer.persisted(), 3U);
  writer.add(frame(3));
  writer.commit();
  EXPECT_EQ(writer.persisted(), 4U);
  writer.withDatabase([](MapDatabase& db) { db.clear(); });
  EXPECT_EQ(writer.persisted(), 0U);
}

TEST_F(MapWriterTest, ABatchFilledWhileTheWriterWaitsIsCommittedAsSoonAsItIsFull) {
  // Keyframes come one by one, so the writer is already waiting for the period when the batch fills.
  MapDatabase database(path(), thumbnailParams());
  MapWriter writer(database, CommitPolicy{3600.0, 10});
  for (int batch = 1; batch <= 2; ++batch) {
    for (int i = 0; i < 10; ++i) {
      writer.add(frame(10 * (batch - 1) + i));
      std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    EXPECT_TRUE(waitPersisted(writer, 10U * batch, 10.0)) << "batch " << batch << " waited for the hour-long period";
  }
  EXPECT_EQ(writer.queued(), 0U);
}

}  // namespace
}  // namespace mrs_vpr

// Failed allocations while the map grows or is loaded: every allocation through operator new is made to fail in
// turn, and the map must be left whole each time. This binary replaces the global allocation
// functions, so it holds these tests alone.
#include <gtest/gtest.h>

#include <atomic>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <new>
#include <string>
#include <vector>

#include <opencv2/core.hpp>
#include <opencv2/core/utility.hpp>

#include "mrs_vpr/contrast_enhancement.hpp"
#include "mrs_vpr/descriptor_sequence.hpp"
#include "mrs_vpr/difference_matrix.hpp"
#include "mrs_vpr/mrs/recent_rows.hpp"
#include "mrs_vpr/parameters.hpp"
#include "mrs_vpr/place_recognizer.hpp"
#include "mrs_vpr/store/persistent_map.hpp"
#include "mrs_vpr/trajectory_search.hpp"
#include "support/temporary_folder.hpp"

namespace {

/// Allocations left before one fails; negative: none fails.
std::atomic<long> allocations_before_failure{-1};

void* allocate(std::size_t size) {
  if (allocations_before_failure.load() >= 0 && allocations_before_failure.fetch_sub(1) == 0) throw std::bad_alloc();
  if (void* memory = std::malloc(size == 0 ? 1 : size)) return memory;
  throw std::bad_alloc();
}

}  // namespace

// Under LeakSanitizer (make test-sanitize): OpenCV's cv::Mat::create allocates its buffer with
// cv::fastMalloc and then its header with operator new, and loses the buffer when that fails, as it
// does here on purpose. Those buffers are OpenCV's; every other leak is still reported.
extern "C" const char* __lsan_default_suppressions() { return "leak:cv::fastMalloc\n"; }

void* operator new(std::size_t size) { return allocate(size); }
void* operator new[](std::size_t size) { return allocate(size); }
void operator delete(void* memory) noexcept { std::free(memory); }
void operator delete[](void* memory) noexcept { std::free(memory); }
void operator delete(void* memory, std::size_t) noexcept { std::free(memory); }
void operator delete[](void* memory, std::size_t) noexcept { std::free(memory); }

namespace mrs_vpr {
namespace {

/// Fails the `allocation`-th allocation from now (0: the next one) until disarmed.
class FailingAllocation {
 public:
  explicit FailingAllocation(long allocation) { allocations_before_failure = allocation; }
  ~FailingAllocation() { allocations_before_failure = -1; }
  FailingAllocation(const FailingAllocation&) = delete;
  FailingAllocation& operator=(const FailingAllocation&) = delete;
};

/// More attempts than any one call makes allocations: a call that still fails after it is a defect.
constexpr long kMaxAllocations = 64;

/// A recognizer's parameters under which every frame offered is a keyframe.
RecognizerParams everyFrameAKeyframe() {
  RecognizerParams params;
  params.min_appearance_change = 0.0;
  return params;
}

cv::Mat randomDescriptor(int size, cv::RNG& random) {
  cv::Mat descriptor(1, size, CV_8UC1);
  random.fill(descriptor, cv::RNG::UNIFORM, 0, 256);
  return descriptor;
}

/// Every byte a sequence holds: descriptors, stamps and the coarse cells of each stride kept.
std::vector<std::int64_t> contentsOf(const DescriptorSequence& sequence, const DescriptorParams& geometry) {
  std::vector<std::int64_t> contents{sequence.size()};
  for (int frame = 0; frame < sequence.size(); ++frame) {
    const std::uint8_t* bytes = sequence.descriptor(frame);
    contents.insert(contents.end(), bytes, bytes + sequence.descriptorSize());
    contents.push_back(sequence.stamp(frame).nanoseconds());
  }
  for (int stride = 1; stride <= 16; stride *= 2) {
    const SequenceView cells = sequence.view().coarseCells(stride, geometry);
    contents.push_back(cells.count);
    contents.insert(contents.end(), cells.data,
                    cells.data + static_cast<std::ptrdiff_t>(cells.count) * cells.descriptor_size);
  }
  return contents;
}

TEST(AllocationFailure, AFailedAppendLeavesTheSequenceAsItWas) {
  const DescriptorParams geometry = Parameters{}.descriptor;
  const int size = geometry.descriptorSize();
  DescriptorSequence sequence(size);
  sequence.keepCoarseCells(3, geometry);
  DescriptorSequence undisturbed(size);
  undisturbed.keepCoarseCells(3, geometry);
  cv::RNG random(7);
  int failures = 0;
  for (int frame = 0; frame < 40; ++frame) {
    const cv::Mat descriptor = randomDescriptor(size, random);
    const Stamp stamp = Stamp::fromNanoseconds(1000LL * frame);
    undisturbed.append(descriptor, stamp);
    const std::vector<std::int64_t> before = contentsOf(sequence, geometry);
    bool appended = false;
    for (long allocation = 0; allocation < kMaxAllocations && !appended; ++allocation) {
      try {
        FailingAllocation failing(allocation);
        sequence.append(descriptor, stamp);
        appended = true;
      } catch (const std::bad_alloc&) {
        ++failures;
        ASSERT_EQ(contentsOf(sequence, geometry), before) << "frame " << frame << ", allocation " << allocation;
      }
    }
    ASSERT_TRUE(appended) << "frame " << frame;
  }
  EXPECT_EQ(contentsOf(sequence, geometry), contentsOf(undisturbed, geometry));
  // The first append alone allocates each of the six arrays (descriptors, stamps, cells of strides 1 to 8).
  EXPECT_GE(failures, 6);
}

TEST(AllocationFailure, EveryFrameThePlaceRecognizerAdmittedReachesTheMapInOrder) {
  // Keyframes by appearance, so that the keyframe rule's own allocations fail too.
  PlaceRecognizer recognizer;
  const int size = recognizer.extractor().size();
  cv::RNG random(11);
  std::vector<cv::Mat> admitted;
  int failures = 0;
  for (int frame = 0; frame < 60; ++frame) {
    const cv::Mat descriptor = randomDescriptor(size, random);
    const Stamp stamp = Stamp::fromNanoseconds(1000LL * frame);
    bool answered = false;
    for (long allocation = 0; allocation < kMaxAllocations && !answered; ++allocation) {
      FrameAdmission admission = FrameAdmission::kMapFull;
      try {
        FailingAllocation failing(allocation);
        admission = frame % 2 == 0 ? recognizer.offerDescriptor(descriptor, stamp)
                                   : recognizer.addDescriptor(descriptor, stamp);
        answered = true;
      } catch (const std::bad_alloc&) {
        ++failures;  // nothing admitted: the next attempt offers the same frame again
      }
      if (answered && admission == FrameAdmission::kAdmitted) admitted.push_back(descriptor);
      ASSERT_EQ(recognizer.size() + recognizer.pending(), static_cast<int>(admitted.size()))
          << "frame " << frame << ", allocation " << allocation;
    }
    ASSERT_TRUE(answered) << "frame " << frame;
    // A flush that fails keeps the frames waiting.
    for (long allocation = 0; allocation < kMaxAllocations; ++allocation) {
      try {
        FailingAllocation failing(allocation);
        recognizer.flush();
        break;
      } catch (const std::bad_alloc&) {
        ++failures;
        ASSERT_EQ(recognizer.size() + recognizer.pending(), static_cast<int>(admitted.size()));
      }
    }
  }
  recognizer.flush();
  EXPECT_GE(failures, 10);          // each time the map's or the keyframe rule's arrays grow
  EXPECT_GT(admitted.size(), 30U);  // random views are unrelated: most are keyframes
  ASSERT_EQ(recognizer.size(), static_cast<int>(admitted.size()));
  int frame = 0;
  recognizer.visitFrames(0, recognizer.size(), [&](const cv::Mat& descriptor, Stamp) {
    EXPECT_EQ(cv::norm(descriptor, admitted[static_cast<std::size_t>(frame)], cv::NORM_INF), 0.0) << "frame " << frame;
    ++frame;
  });
}

TEST(AllocationFailure, AFailedReplaceKeepsTheOldMap) {
  const RecognizerParams every_frame = everyFrameAKeyframe();
  PlaceRecognizer recognizer(Parameters{}, every_frame);
  const int size = recognizer.extractor().size();
  cv::RNG random(13);
  std::vector<cv::Mat> old_map;
  std::vector<cv::Mat> new_map;
  for (int frame = 0; frame < 30; ++frame) old_map.push_back(randomDescriptor(size, random));
  for (int frame = 0; frame < 45; ++frame) new_map.push_back(randomDescriptor(size, random));
  recognizer.replace(old_map, std::vector<Stamp>(old_map.size()));
  const auto frames = [&] {
    std::vector<cv::Mat> held;
    recognizer.visitFrames(0, recognizer.size(),
                           [&](const cv::Mat& descriptor, Stamp) { held.push_back(descriptor.clone()); });
    return held;
  };
  const auto same = [](const std::vector<cv::Mat>& a, const std::vector<cv::Mat>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i) {
      if (cv::norm(a[i], b[i], cv::NORM_INF) != 0.0) return false;
    }
    return true;
  };
  const std::vector<Stamp> new_stamps(new_map.size());
  int failures = 0;
  bool replaced = false;
  for (long allocation = 0; allocation < 4 * kMaxAllocations && !replaced; ++allocation) {
    try {
      FailingAllocation failing(allocation);
      recognizer.replace(new_map, new_stamps);
      replaced = true;
    } catch (const std::bad_alloc&) {
      ++failures;
      ASSERT_TRUE(same(frames(), old_map)) << "allocation " << allocation;
    }
  }
  ASSERT_TRUE(replaced);
  EXPECT_GT(failures, 5);
  EXPECT_TRUE(same(frames(), new_map));
}

TEST(AllocationFailure, AQuestionThatFailedLeavesNoKeptRowWrong) {
  // One thread: the allocations counted are this thread's, in the same order at every run.
  const int threads = cv::getNumThreads();
  cv::setNumThreads(1);
  constexpr int kWindow = 10;
  const std::vector<double> velocities{0.8, 0.9, 1.0, 1.1, 1.2};
  const SequenceRows rows{0, 19, 10};
  DescriptorSequence map(64);
  cv::RNG random(19);
  for (int frame = 0; frame < 300; ++frame) map.append(randomDescriptor(64, random));
  RecentRows recent(kWindow, kMaxRecentRows);
  int failures = 0;
  for (int question = 0; question < 8; ++question) {
    for (int frame = 0; frame < 1 + question % 3; ++frame) map.append(randomDescriptor(64, random));
    const int first = map.size() - 20;
    const int columns = first - 30;
    const AnchorCosts brute = costsByAnchor(
        enhanceContrast(computeDifferenceMatrix(map.view(first, first + 20), map.view(0, columns)), kWindow), rows,
        velocities);
    AnchorCosts kept;
    bool answered = false;
    for (long allocation = 0; allocation < 1000 && !answered; ++allocation) {  // a question makes about 100
      try {
        FailingAllocation failing(allocation);
        recent.costs(map.view(), first, 20, columns, rows, velocities, kept);
        answered = true;
      } catch (const std::bad_alloc&) {
        ++failures;
      }
    }
    ASSERT_TRUE(answered) << "question " << question;
    // To the bit, as the kept rows promise: none was left part-extended by a failed attempt.
    ASSERT_EQ(kept.cost, brute.cost) << "question " << question;
    ASSERT_EQ(kept.velocity, brute.velocity) << "question " << question;
  }
  cv::setNumThreads(threads);
  EXPECT_GT(failures, 8);
}

/// Frames in `map`'s database, counted through a copy in `folder` (the database is open for writing).
int databaseFrames(PersistentMap& map, const testing_support::TemporaryFolder& folder) {
  static int copies = 0;
  return map.save(folder.path("copy" + std::to_string(++copies) + ".db"));
}

/// Makes `change` fail at each allocation in turn until it succeeds; after each failure the map and
/// its database must still hold `frames` frames. Returns the failures, -1 when the map changed.
int failEachAllocationOf(const std::function<void()>& change, const PlaceRecognizer& recognizer, PersistentMap& map,
                         const testing_support::TemporaryFolder& folder, int frames) {
  int failures = 0;
  for (long allocation = 0; allocation < 2000; ++allocation) {
    try {
      FailingAllocation failing(allocation);
      change();
      return failures;
    } catch (const std::bad_alloc&) {
      ++failures;
      if (recognizer.size() != frames || databaseFrames(map, folder) != frames) {
        ADD_FAILURE() << "allocation " << allocation << " changed the map: " << recognizer.size() << " frames, "
                      << databaseFrames(map, folder) << " in its database, " << frames << " before";
        return -1;
      }
    }
  }
  ADD_FAILURE() << "still failing after 2000 allocations";
  return -1;
}

TEST(AllocationFailure, AFailedLoadLeavesTheDatabaseAndTheMapAsTheyWere) {
  const testing_support::TemporaryFolder folder("mrs_vpr_allocation_failure_test");
  const RecognizerParams every_frame = everyFrameAKeyframe();
  cv::RNG random(17);
  const auto mapOf = [&](PlaceRecognizer& recognizer, PersistentMap& map, int frames) {
    for (int frame = 0; frame < frames; ++frame) {
      map.add(randomDescriptor(recognizer.extractor().size(), random), Stamp::fromNanoseconds(frame));
    }
    map.commit();
  };
  {
    PlaceRecognizer recognizer(Parameters{}, every_frame);
    PersistentMap saved(recognizer, folder.path("saved.db"), CommitPolicy{});
    mapOf(recognizer, saved, 45);
  }
  PlaceRecognizer recognizer(Parameters{}, every_frame);
  PersistentMap map(recognizer, folder.path("map.db"), CommitPolicy{});
  mapOf(recognizer, map, 30);
  // A load makes about 300 allocations.
  EXPECT_GT(failEachAllocationOf([&] { map.load(folder.path("saved.db")); }, recognizer, map, folder, 30), 5);
  EXPECT_EQ(recognizer.size(), 45);
  EXPECT_EQ(databaseFrames(map, folder), 45);
}

// A keyframe's place in the database's queue is made before the map admits it: a failed allocation
// leaves the frame out of both, never in the map alone (lost at the next start).
TEST(AllocationFailure, AFrameThatCouldNotBeQueuedForTheDatabaseIsNotInTheMapEither) {
  const testing_support::TemporaryFolder folder("mrs_vpr_allocation_failure_test");
  const RecognizerParams every_frame = everyFrameAKeyframe();
  cv::RNG random(23);
  PlaceRecognizer recognizer(Parameters{}, every_frame);
  PersistentMap map(recognizer, folder.path("map.db"), CommitPolicy{60.0, 1000});  // nothing commits by itself
  int frames = 0;
  for (; frames < 16; ++frames) {
    ASSERT_EQ(map.add(randomDescriptor(recognizer.extractor().size(), random), Stamp::fromNanoseconds(frames)),
              FrameAdmission::kAdmitted);
  }
  map.commit();
  // Frames added with their first allocation failing, their second, and so on (an add makes a few;
  // how many depends on whether the map grows); after each the map and its database hold the same
  // frames. The commits between them empty the queue, so that each add grows it.
  int failures = 0;
  for (long allocation = 0; allocation < kMaxAllocations; ++allocation) {
    for (int repeat = 0; repeat < 4; ++repeat) {
      const cv::Mat descriptor = randomDescriptor(recognizer.extractor().size(), random);
      const std::string frame_id(40, 'c');  // longer than a short string's own storage
      try {
        FailingAllocation failing(allocation);
        if (map.add(descriptor, Stamp::fromNanoseconds(frames), frame_id) == FrameAdmission::kAdmitted) ++frames;
      } catch (const std::bad_alloc&) {
        ++failures;
      }
      ASSERT_EQ(databaseFrames(map, folder), recognizer.size() + recognizer.pending()) << "allocation " << allocation;
      ASSERT_EQ(recognizer.size() + recognizer.pending(), frames) << "allocation " << allocation;
    }
  }
  EXPECT_GT(failures, 0);
}

// ~reset empties the database only once the empty map is made: a failure keeps both whole.
TEST(AllocationFailure, AFailedResetLeavesTheDatabaseAndTheMapAsTheyWere) {
  const testing_support::TemporaryFolder folder("mrs_vpr_allocation_failure_test");
  const RecognizerParams every_frame = everyFrameAKeyframe();
  cv::RNG random(19);
  PlaceRecognizer recognizer(Parameters{}, every_frame);
  PersistentMap map(recognizer, folder.path("map.db"), CommitPolicy{});
  for (int frame = 0; frame < 30; ++frame) {
    map.add(randomDescriptor(recognizer.extractor().size(), random), Stamp::fromNanoseconds(frame));
  }
  map.commit();
  EXPECT_GT(failEachAllocationOf([&] { map.reset(); }, recognizer, map, folder, 30), 0);
  EXPECT_EQ(recognizer.size(), 0);
  EXPECT_EQ(databaseFrames(map, folder), 0);
}

}  // namespace
}  // namespace mrs_vpr

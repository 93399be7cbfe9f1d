#include <gtest/gtest.h>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "mrs_vpr/memory_budget.hpp"
#include "mrs_vpr/sequence_matcher.hpp"
#include "support/error_message.hpp"
#include "support/route_fixture.hpp"

namespace mrs_vpr {
namespace {

using testing_support::invalidArgumentMessage;

TEST(MemoryBudget, RefusesOnlyWhatExceedsTheMemoryAvailableNamingBothSizes) {
  EXPECT_NO_THROW(requireAvailableMemory(2'000'000'000, "a matrix", "ask less", 2'000'000'000));
  EXPECT_NO_THROW(requireAvailableMemory(5'000'000'000, "a matrix", "ask less", std::nullopt));  // unknown
  const std::string message =
      invalidArgumentMessage([] { requireAvailableMemory(2'500'000'000, "a matrix", "ask less", 1'200'000'000); });
  EXPECT_EQ(message, "a matrix needs 2.5 GB, more than the 1.2 GB of memory available: ask less");
}

TEST(MemoryBudget, ThisMachineSaysWhatIsAvailable) {
  const auto available = availableMemoryBytes();
  ASSERT_TRUE(available.has_value());
  EXPECT_GT(*available, 0U);
}

// A brute-force question whose matrix this machine cannot hold is refused before anything is
// allocated, not granted by the kernel and then filled until the process is killed.
TEST(MemoryBudget, ABruteForceQuestionBeyondTheMemoryIsRefusedNamingTheRemedy) {
  const std::vector<std::uint8_t> frame(64, 7);
  // Every frame of these views is the same bytes (step 0): 100k x 2G cells, 800 TB of differences.
  const SequenceView map{frame.data(), 2'000'000'000, 64, 0};
  const SequenceView query{frame.data(), 100'000, 64, 0};
  const auto matcher = makeMatcher("seqslam", testing_support::routeParameters());
  const std::string message = invalidArgumentMessage([&] { matcher->match(map, query); });
  EXPECT_NE(message.find("the difference matrix of a seqslam question about 100000 frames of a map of 2000000000 "
                         "needs 800000.0 GB"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("ask about fewer frames, or use mrs"), std::string::npos) << message;
}

// The per-frame protocol (mrs_vpr_eval, query_bag) holds one matrix of every query frame against the
// map: one it cannot hold is refused with the remedy, by either method (MRS is the brute force at this length).
TEST(MemoryBudget, APerFrameRunBeyondTheMemoryIsRefusedNamingTheRemedy) {
  const std::vector<std::uint8_t> frame(64, 7);
  const SequenceView map{frame.data(), 2'000'000'000, 64, 0};
  const SequenceView query{frame.data(), 100'000, 64, 0};
  for (const std::string method : {"seqslam", "mrs"}) {
    const auto matcher = makeMatcher(method, testing_support::routeParameters());
    const std::string message = invalidArgumentMessage([&] { matcher->matchEveryFrame(map, query); });
    EXPECT_NE(message.find("the difference matrix of every frame of 100000 query frames against a map of "
                           "2000000000 needs 800000.0 GB"),
              std::string::npos)
        << method << ": " << message;
    EXPECT_NE(message.find("split the query frames into parts"), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace mrs_vpr

#include <cstdlib>
#include <vector>

#include <gtest/gtest.h>

#include "mrs_vpr/memory_reuse.hpp"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace mrs_vpr {
namespace {

TEST(RetainFreedMemory, AFreedQueryBufferStaysWithTheProcessForTheNextQuery) {
#if !defined(__GLIBC__) || defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "glibc's own allocator only";
#else
  retainFreedMemory();
  constexpr std::size_t kBuffer = 20 * 1024 * 1024;  // a query's difference matrix, say
  {
    std::vector<float> matrix(kBuffer / sizeof(float), 1.0F);
    ASSERT_EQ(matrix[kBuffer / sizeof(float) - 1], 1.0F);
  }
  // Without the policy glibc maps a block this large on its own and unmaps it when freed; with it the
  // block comes from the heap and stays there, free for the next query.
  EXPECT_GE(mallinfo2().fordblks, kBuffer);
#endif
}

}  // namespace
}  // namespace mrs_vpr

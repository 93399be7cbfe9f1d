#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "mrs_vpr/memory_reuse.hpp"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace mrs_vpr {
namespace {

constexpr std::size_t kBuffer = 20 * 1024 * 1024;  // a query's difference matrix, say
/// Set in the process this test starts of itself: "retain" or "default", the allocator's policy there.
constexpr const char* kPolicyVariable = "MRS_VPR_MEMORY_POLICY";
constexpr const char* kFreeHeapLine = "free heap bytes after the buffer: ";

/// The heap's free bytes after a buffer of kBuffer was used and freed, in a fresh process of this test
/// with `policy`: in this one, the bytes earlier tests freed (and glibc's threshold, which adapts to
/// them) would decide the figure whatever the policy.
long long freeHeapAfterABuffer(const std::string& policy) {
  const std::string self = std::filesystem::read_symlink("/proc/self/exe").string();
  const std::string command = std::string(kPolicyVariable) + "=" + policy + " '" + self +
                              "' --gtest_filter=RetainFreedMemory.* 2>&1";
  FILE* child = popen(command.c_str(), "r");
  if (child == nullptr) return -1;
  long long free_bytes = -1;
  char line[512];
  while (std::fgets(line, sizeof(line), child) != nullptr) {
    const std::string text(line);
    if (text.rfind(kFreeHeapLine, 0) == 0) free_bytes = std::stoll(text.substr(std::string(kFreeHeapLine).size()));
  }
  return pclose(child) == 0 ? free_bytes : -1;
}

TEST(RetainFreedMemory, AFreedQueryBufferStaysWithTheProcessForTheNextQuery) {
#if !defined(__GLIBC__) || defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "glibc's own allocator only";
#else
  if (const char* policy = std::getenv(kPolicyVariable)) {
    // The fresh process: use and free the buffer, and report what the heap keeps.
    if (std::string(policy) == "retain") retainFreedMemory();
    {
      std::vector<float> matrix(kBuffer / sizeof(float), 1.0F);
      ASSERT_EQ(matrix[kBuffer / sizeof(float) - 1], 1.0F);
    }
    std::printf("%s%zu\n", kFreeHeapLine, mallinfo2().fordblks);
    return;
  }
  // Without the policy glibc maps a block this large on its own and unmaps it when freed; with it the
  // block comes from the heap and stays there, free for the next query.
  const long long retained = freeHeapAfterABuffer("retain");
  const long long by_default = freeHeapAfterABuffer("default");
  EXPECT_GE(retained, static_cast<long long>(kBuffer));
  EXPECT_GE(by_default, 0);
  EXPECT_LT(by_default, static_cast<long long>(kBuffer));
#endif
}

}  // namespace
}  // namespace mrs_vpr

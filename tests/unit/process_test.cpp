// scansurf/process.h: after keepFreedMemoryForReuse, a large block freed stays with the
// allocator for the next allocation instead of going back to the kernel.
#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>

#include "scansurf/process.h"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

// AddressSanitizer replaces the allocator (its mallopt does nothing): gcc and clang say so
// differently.
#if defined(__SANITIZE_ADDRESS__)
#define SCANSURF_TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SCANSURF_TEST_ASAN 1
#endif
#endif

namespace scansurf {
namespace {

TEST(Process, FreedLargeBlocksStayForReuse) {
#if !defined(__GLIBC__) || defined(SCANSURF_TEST_ASAN)
  GTEST_SKIP() << "not glibc's allocator";
#else
  constexpr std::size_t kBytes = std::size_t{64} << 20;  // far above glibc's mmap threshold
  ASSERT_TRUE(keepFreedMemoryForReuse());
  void* block = std::malloc(kBytes);
  ASSERT_NE(block, nullptr);
  std::memset(block, 1, kBytes);
  const struct mallinfo2 held = mallinfo2();
  EXPECT_EQ(held.hblkhd, 0u) << "the block was mapped on its own";
  std::free(block);
  const struct mallinfo2 freed = mallinfo2();
  EXPECT_GE(freed.fordblks, kBytes) << "the freed block went back to the kernel";
  EXPECT_GE(freed.arena, kBytes);
#endif
}

}  // namespace
}  // namespace scansurf

#include "mm/sim/memory.hpp"

#include <gtest/gtest.h>

#include <cstddef>
#include <cstdlib>
#include <cstring>

#if defined(__GLIBC__) && !defined(__SANITIZE_ADDRESS__)
#include <malloc.h>
#define MM_TEST_GLIBC_MALLOC 1
#endif

namespace {

TEST(sim_memory, a_freed_large_block_stays_in_the_heap_for_the_next_run) {
#if defined(MM_TEST_GLIBC_MALLOC)
  mm::sim::retain_freed_memory();
  constexpr std::size_t size = std::size_t{8} << 20;  // above glibc's default mmap threshold
  const struct mallinfo2 before = mallinfo2();
  void* block = std::malloc(size);
  ASSERT_NE(block, nullptr);
  std::memset(block, 1, size);
  const struct mallinfo2 during = mallinfo2();
  EXPECT_EQ(during.hblks, before.hblks) << "the block was mapped on its own, not taken from the heap";
  std::free(block);
  const struct mallinfo2 after = mallinfo2();
  EXPECT_GE(after.fordblks, size) << "the freed block was returned to the system";
#else
  GTEST_SKIP() << "glibc's allocator only (not under AddressSanitizer)";
#endif
}

}  // namespace

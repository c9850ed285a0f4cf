#include "mm/sample_mask.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

#include "property.hpp"

namespace mm {
namespace {

TEST(sample_mask, all_in_agrees_with_testing_every_index_of_the_range) {
  std::mt19937_64 rng(testing::property_seed() + 21);
  const std::size_t count = testing::property_count(400);
  for (std::size_t trial = 0; trial < count; ++trial) {
    const std::size_t size = 1 + rng() % 300;
    sample_mask mask(size);
    // Long runs of members, so that ranges over whole words are all set now and then.
    const double density = trial % 3 == 0 ? 0.5 : 0.97;
    std::bernoulli_distribution member(density);
    for (std::size_t i = 0; i < size; ++i) {
      if (member(rng)) mask.set(i);
    }
    for (int range = 0; range < 20; ++range) {
      const std::size_t begin = rng() % (size + 1);
      const std::size_t end = begin + rng() % (size - begin + 1);
      bool every = true;
      for (std::size_t i = begin; i < end; ++i) every = every && mask.test(i);
      ASSERT_EQ(mask.all_in(begin, end), every) << "size " << size << ", [" << begin << ", " << end << ")";
    }
  }
}

TEST(sample_mask, an_empty_range_is_all_in_and_a_full_mask_holds_every_range) {
  sample_mask mask(130);
  EXPECT_TRUE(mask.all_in(5, 5));
  EXPECT_FALSE(mask.all_in(0, 1));
  for (std::size_t i = 0; i < 130; ++i) mask.set(i);
  EXPECT_TRUE(mask.all_in(0, 130));
  EXPECT_TRUE(mask.all_in(64, 128));
  mask.reset(127);
  EXPECT_FALSE(mask.all_in(64, 128));
  EXPECT_TRUE(mask.all_in(64, 127));
  EXPECT_TRUE(mask.all_in(128, 130));
}

TEST(sample_mask, bits_and_add_bits_read_and_write_the_indices_of_a_range_one_by_one) {
  std::mt19937_64 rng(testing::property_seed() + 22);
  const std::size_t count = testing::property_count(400);
  for (std::size_t trial = 0; trial < count; ++trial) {
    const std::size_t size = 1 + rng() % 300;
    sample_mask mask(size);
    for (std::size_t i = 0; i < size; ++i) {
      if (rng() % 2 == 0) mask.set(i);
    }
    const std::size_t begin = rng() % size;
    const std::size_t width = std::min<std::size_t>(64, rng() % (size - begin + 1));
    std::uint64_t expected = 0;
    for (std::size_t j = 0; j < width; ++j) expected |= std::uint64_t{mask.test(begin + j)} << j;
    ASSERT_EQ(mask.bits(begin, width), expected) << "size " << size << ", begin " << begin << ", width " << width;

    // Bits at and above `width` are ignored.
    const std::uint64_t added = rng();
    sample_mask written = mask;
    written.add_bits(begin, width, added);
    for (std::size_t i = 0; i < size; ++i) {
      const bool inside = i >= begin && i < begin + width && ((added >> (i - begin)) & 1U) != 0;
      ASSERT_EQ(written.test(i), mask.test(i) || inside)
          << "size " << size << ", begin " << begin << ", width " << width << ", index " << i;
    }
  }
}

TEST(sample_mask, the_complement_and_the_difference_hold_what_they_say_and_nothing_past_the_size) {
  std::mt19937_64 rng(testing::property_seed() + 23);
  for (std::size_t trial = 0; trial < testing::property_count(200); ++trial) {
    const std::size_t size = 1 + rng() % 300;
    sample_mask a(size);
    sample_mask b(size);
    for (std::size_t i = 0; i < size; ++i) {
      if (rng() % 2 == 0) a.set(i);
      if (rng() % 3 == 0) b.set(i);
    }
    sample_mask complement(7);
    complement.assign_complement(a);
    sample_mask difference = a;
    difference.subtract(b);
    ASSERT_EQ(complement.size(), size);
    std::size_t outside = 0;
    for (std::size_t i = 0; i < size; ++i) {
      ASSERT_EQ(complement.test(i), !a.test(i)) << "size " << size << ", index " << i;
      ASSERT_EQ(difference.test(i), a.test(i) && !b.test(i)) << "size " << size << ", index " << i;
      outside += a.test(i) ? 0 : 1;
    }
    EXPECT_EQ(complement.count(), outside) << "size " << size;
  }
}

}  // namespace
}  // namespace mm

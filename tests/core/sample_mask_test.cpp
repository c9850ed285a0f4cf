#include "mm/sample_mask.hpp"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace mm

#pragma once

#include <cstddef>
#include <cstdint>

namespace mm::testing {

/// Seed of the randomized property tests: `--seed=N` on the command line, else the environment
/// variable MM_SEED, else a fixed default (so CTest runs are reproducible).
std::uint64_t property_seed();

/// Number of random cases: `--count=N`, else MM_COUNT, else `fallback` (divided by 4 when
/// MM_TEST_SCALE=sanitize, for the slower sanitizer build).
std::size_t property_count(std::size_t fallback);

/// True in the sanitizer build (MM_TEST_SCALE=sanitize).
bool sanitizer_scale();

}  // namespace mm::testing

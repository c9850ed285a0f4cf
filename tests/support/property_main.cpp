// main() of the property-test executables: GoogleTest plus --seed=N and --count=N.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <algorithm>
#include <optional>
#include <string>

#include "property.hpp"

namespace mm::testing {
std::optional<std::uint64_t> seed_argument;
std::optional<std::size_t> count_argument;

namespace {

std::optional<std::uint64_t> environment(const char* name) {
  const char* value = std::getenv(name);
  if (value == nullptr || *value == '\0') return std::nullopt;
  return std::strtoull(value, nullptr, 10);
}

}  // namespace

std::uint64_t property_seed() {
  if (seed_argument) return *seed_argument;
  return environment("MM_SEED").value_or(20261122);
}

std::size_t property_count(std::size_t fallback) {
  if (count_argument) return *count_argument;
  if (const auto count = environment("MM_COUNT")) return static_cast<std::size_t>(*count);
  return sanitizer_scale() ? std::max<std::size_t>(1, fallback / 4) : fallback;
}

bool sanitizer_scale() {
  const char* scale = std::getenv("MM_TEST_SCALE");
  return scale != nullptr && std::strcmp(scale, "sanitize") == 0;
}

}  // namespace mm::testing

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg.rfind("--seed=", 0) == 0) {
      mm::testing::seed_argument = std::strtoull(arg.c_str() + 7, nullptr, 10);
    } else if (arg.rfind("--count=", 0) == 0) {
      mm::testing::count_argument = static_cast<std::size_t>(std::strtoull(arg.c_str() + 8, nullptr, 10));
    } else {
      std::fprintf(stderr, "unknown argument %s (expected --seed=N, --count=N or GoogleTest flags)\n", argv[i]);
      return 2;
    }
  }
  std::printf("property tests: seed %llu (rerun with --seed=N --count=N)\n",
              static_cast<unsigned long long>(mm::testing::property_seed()));
  return RUN_ALL_TESTS();
}

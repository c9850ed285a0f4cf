#!/usr/bin/env bash
# Builds the scenario-parser fuzzer with clang (libFuzzer, AddressSanitizer, UndefinedBehavior-
# Sanitizer) and runs it for a bounded time from a seed corpus of the built-in scenarios.
#   bash scripts/fuzz.sh [SECONDS]   (default 60)
# Exits non-zero if the fuzzer finds a crash, a leak, a timeout or an uncaught exception; the
# offending input is left in build/fuzz/artifacts/.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
build=build/fuzz
CC=clang CXX=clang++ cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DMM_BUILD_FUZZERS=ON -DMM_BUILD_TESTS=OFF -DMM_BUILD_EXAMPLES=OFF -DMM_BUILD_BENCHMARKS=OFF \
  -DMM_SANITIZE=address,undefined -DCMAKE_CXX_FLAGS="-fsanitize=fuzzer-no-link" >/dev/null
cmake --build "$build" --target scenario_parser_fuzzer
corpus="$build/corpus"
mkdir -p "$corpus" "$build/artifacts"
cp scenarios/*.yaml "$corpus/"
ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  "$build/fuzz/scenario_parser_fuzzer" "$corpus" -dict=fuzz/scenario.dict -max_total_time="$seconds" \
  -timeout=10 -rss_limit_mb=2048 -max_len=16384 -print_final_stats=1 -artifact_prefix="$build/artifacts/"
echo "fuzzing the scenario parser for ${seconds} s found nothing"

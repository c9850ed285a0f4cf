#!/usr/bin/env bash
# Builds the fuzzers of the scenario parser, of the CommonRoad reader and of the planner with clang
# (libFuzzer, AddressSanitizer, UndefinedBehaviorSanitizer) and runs each for a bounded time from a
# seed corpus (the built-in scenarios; small CommonRoad files in fuzz/commonroad_seeds/; none for the
# planner, whose every byte string decodes to a planning input).
#   bash scripts/fuzz.sh [SECONDS]   (default 60, for each of the three)
# Exits non-zero if a fuzzer finds a crash, a leak, a timeout or an uncaught exception; the
# offending input is left in build/fuzz/artifacts/.
set -euo pipefail
cd "$(dirname "$0")/.."
seconds="${1:-60}"
build=build/fuzz
CC=clang CXX=clang++ cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DMM_BUILD_FUZZERS=ON -DMM_BUILD_TESTS=OFF -DMM_BUILD_EXAMPLES=OFF -DMM_BUILD_BENCHMARKS=OFF -DMM_BUILD_PYTHON=OFF \
  -DMM_SANITIZE=address,undefined -DCMAKE_CXX_FLAGS="-fsanitize=fuzzer-no-link" >/dev/null
cmake --build "$build" --target scenario_parser_fuzzer commonroad_reader_fuzzer planner_fuzzer
mkdir -p "$build/artifacts"

# fuzz TARGET DICT SEEDS...: runs TARGET for $seconds from its own corpus, seeded with SEEDS (none
# or an empty DICT: without).
fuzz() {
  local target="$1" dict="$2"
  shift 2
  local corpus="$build/corpus-$target"
  mkdir -p "$corpus"
  if (($# > 0)); then cp "$@" "$corpus/"; fi
  ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
    "$build/fuzz/$target" "$corpus" ${dict:+-dict="$dict"} -max_total_time="$seconds" \
    -timeout=10 -rss_limit_mb=2048 -max_len=16384 -print_final_stats=1 -artifact_prefix="$build/artifacts/"
}
fuzz scenario_parser_fuzzer fuzz/scenario.dict scenarios/*.yaml
fuzz commonroad_reader_fuzzer fuzz/commonroad.dict fuzz/commonroad_seeds/*.xml
fuzz planner_fuzzer ""
echo "fuzzing the scenario parser, the CommonRoad reader and the planner for ${seconds} s each found nothing"

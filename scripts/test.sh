#!/usr/bin/env bash
# Installs the dependencies, builds, and runs the whole test suite twice: an optimised build with
# warnings as errors, then a build under AddressSanitizer and UndefinedBehaviorSanitizer; then
# fuzzes the scenario parser, the CommonRoad reader and the planner for 30 s each (scripts/fuzz.sh).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh
jobs=$(nproc)

cmake -S . -B build/release -G Ninja -DCMAKE_BUILD_TYPE=Release -DMM_WARNINGS_AS_ERRORS=ON
cmake --build build/release -j "$jobs"
ctest --test-dir build/release --output-on-failure -j "$jobs"

cmake -S . -B build/sanitize -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DMM_WARNINGS_AS_ERRORS=ON \
  -DMM_SANITIZE=address,undefined -DMM_BUILD_BENCHMARKS=OFF
cmake --build build/sanitize -j "$jobs"
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1 \
  MM_TEST_SCALE=sanitize ctest --test-dir build/sanitize --output-on-failure -j "$jobs"
bash scripts/fuzz.sh 30
echo "all tests passed (release and address+undefined sanitizers), and 30 s of fuzzing of each parser and of the planner found nothing"

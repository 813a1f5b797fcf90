#!/usr/bin/env bash
# The unit tests (no Vulkan) under AddressSanitizer + UndefinedBehaviorSanitizer, in build-asan
# (scripts/setup.sh --sanitize: clang at -O1 with line tables, only the unit tests and what they
# use). Extra arguments go to ctest.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh --sanitize build-asan
cd build-asan
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
ctest --output-on-failure -j"$(nproc)" -L unit "$@"

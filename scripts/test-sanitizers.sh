#!/usr/bin/env bash
# The unit tests (no Vulkan) under AddressSanitizer + UndefinedBehaviorSanitizer, in build-asan
# (which builds only them and what they use).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh --tests build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DGBL_SANITIZE=ON -DGBL_BUILD_BENCH=OFF -DGBL_TEST_LABELS=unit
cd build-asan
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
ctest --output-on-failure -j"$(nproc)" -L unit "$@"

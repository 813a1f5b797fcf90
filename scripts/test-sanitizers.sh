#!/usr/bin/env bash
# The unit tests (no Vulkan) under AddressSanitizer + UndefinedBehaviorSanitizer, in build-asan
# (which builds only them and what they use). Built by clang at -O1 with line tables only (the
# Sanitize build type, CMakeLists.txt): ASan's and UBSan's reports still name file:line, and the
# build takes well under half of GCC's -O2 -g (docs/testing.md, "CI's budget").
set -euo pipefail
cd "$(dirname "$0")/.."
. scripts/packages.sh
install_missing clang libclang-rt-14-dev
scripts/setup.sh --tests build-asan -DCMAKE_BUILD_TYPE=Sanitize -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ \
  -DGBL_SANITIZE=ON -DGBL_BUILD_BENCH=OFF -DGBL_TEST_LABELS=unit
cd build-asan
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
ctest --output-on-failure -j"$(nproc)" -L unit "$@"

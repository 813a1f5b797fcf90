#!/usr/bin/env bash
# Set-up (packages + Release build), then the whole test suite through CTest, with Vulkan
# validation layers on (any validation error fails the test that caused it).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh --tests build
cd build
ctest --output-on-failure -j"$(nproc)" "$@"

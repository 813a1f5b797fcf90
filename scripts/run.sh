#!/usr/bin/env bash
# Set-up (packages + Release build), then gbufferlab's main job: compare on the bundled scenes
# (scenes/default-suite.toml).
# Extra arguments go to gbufferlab, e.g. scripts/run.sh render --size 640x360.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh build
if [ $# -eq 0 ]; then set -- compare; fi
exec build/gbufferlab "$@"

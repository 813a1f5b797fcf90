#!/usr/bin/env bash
# Runs render.mjs on a job and reports its wall time and the peak memory of the whole process tree
# (Node, Chromium and Chromium's GPU and renderer processes): the sum of their proportional set
# sizes (PSS, /proc/PID/smaps_rollup, so pages the processes share count once), sampled every
# 50 ms. /usr/bin/time's maximum resident size would see Node alone, or one process at a time.
# Usage: tools/gltf-viewer/measure.sh JOB.json
set -euo pipefail
[ $# -eq 1 ] || { echo "usage: $0 JOB.json" >&2; exit 2; }
here=$(cd "$(dirname "$0")" && pwd)

tree() {  # the pid and all its descendants
  local p=$1 c
  echo "$p"
  for c in $(cat /proc/"$p"/task/*/children 2>/dev/null); do tree "$c"; done
}

start=$(date +%s.%N)
node "$here/render.mjs" "$1" &
pid=$!
peak=0
while kill -0 "$pid" 2>/dev/null; do
  kb=0
  for p in $(tree "$pid"); do
    v=$(awk '/^Pss:/ {print $2}' /proc/"$p"/smaps_rollup 2>/dev/null || true)
    kb=$((kb + ${v:-0}))
  done
  ((kb > peak)) && peak=$kb
  sleep 0.05
done
rc=0
wait "$pid" || rc=$?
end=$(date +%s.%N)
printf 'measure.sh: %s: exit %d, wall %.2f s, peak PSS of the process tree %d MiB\n' "$1" "$rc" \
  "$(awk -v a="$start" -v b="$end" 'BEGIN {print b - a}')" $((peak / 1024))
exit "$rc"

#!/usr/bin/env bash
# The search's per-candidate cost before and after a change (issue 33: every metric per candidate
# must cost at most 1.5x the FLIP + PSNR evaluation), side by side in one run: the two binaries
# alternate, so both see the same load on a shared machine.
#
# usage: bench/search_metrics_cost.sh BEFORE_BINARY AFTER_BINARY [candidates] [rounds]
#   e.g. a build of the commit before (git archive <commit> | tar -x -C DIR; scripts/setup.sh)
#   and build/gbufferlab. Each round runs
#     gbufferlab search --budget 12 --size 320x180 --views 3 --candidates N --seed 1 --threads 2 --no-confirm
#   with each binary (default 600 candidates, 2 rounds) and reads its search.json:
#   candidates per minute (wall) and CPU seconds per candidate (process CPU over the evaluations:
#   what a candidate costs whatever else runs). Prints each run, the load average before and after,
#   and the ratio after / before of the mean CPU seconds per candidate, and the rate 2 threads
#   would reach with their cores to themselves (60 x 2 / CPU s per candidate).
# Caveat: the two searches do not evaluate the same candidates (the constraints change what is
# proposed), so the ratio is of the mean over each search's own 600.
set -euo pipefail
before=${1:?usage: bench/search_metrics_cost.sh BEFORE_BINARY AFTER_BINARY [candidates] [rounds]}
after=${2:?usage: bench/search_metrics_cost.sh BEFORE_BINARY AFTER_BINARY [candidates] [rounds]}
candidates=${3:-600}
rounds=${4:-2}
out=$(mktemp -d "${TMPDIR:-/tmp}/gbl-search-cost.XXXXXX")
trap 'rm -rf "$out"' EXIT

echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg)"
for r in $(seq 1 "$rounds"); do
  for which in before after; do
    bin=${!which}
    "$bin" search --budget 12 --size 320x180 --views 3 --candidates "$candidates" --seed 1 --threads 2 \
      --no-confirm --out "$out/$which-$r" >"$out/$which-$r.log" 2>&1 || { cat "$out/$which-$r.log"; exit 1; }
    python3 - "$out/$which-$r/search.json" "$which" "$r" <<'EOF'
import json, sys
j = json.load(open(sys.argv[1]))
print(f"{sys.argv[2]:6} round {sys.argv[3]}: {j['candidates']} candidates, {j['candidates_per_minute']:.0f}/min wall, "
      f"{j['cpu_seconds_per_candidate']:.4f} CPU s per candidate")
EOF
  done
done
echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)"
python3 - "$out" "$rounds" <<'EOF'
import json, sys
out, rounds = sys.argv[1], int(sys.argv[2])
def mean(which):
    return sum(json.load(open(f"{out}/{which}-{r}/search.json"))["cpu_seconds_per_candidate"]
               for r in range(1, rounds + 1)) / rounds
b, a = mean("before"), mean("after")
print(f"CPU s per candidate: before {b:.4f}, after {a:.4f}, ratio after/before {a / b:.2f} (goal <= 1.5)")
print(f"per minute on 2 threads with their cores to themselves: before {120 / b:.0f}, after {120 / a:.0f} (goal > 600)")
EOF

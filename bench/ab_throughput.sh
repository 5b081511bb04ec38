#!/bin/bash
# Planner throughput of two builds compared on a noisy machine: one run of
# each in turn, PAIRS times, and the medians and the median ratio B/A
# (BENCHMARKS.md quotes these).
#
#   bench/ab_throughput.sh OLD/planner_bench NEW/planner_bench PROGRAM.ngc [PAIRS]
#   FIELD=2 bench/ab_throughput.sh ...   # with step quantization (default 1: through
#                                        # coarse interpolation, the goal's stages)
set -euo pipefail
if [[ $# -lt 3 ]]; then
  echo "usage: $0 A/planner_bench B/planner_bench PROGRAM.ngc [PAIRS]" >&2
  exit 2
fi
a=$1 b=$2 program=$3 pairs=${4:-9}
# field 1: through coarse interpolation (the goal's stages); 2: with step quantization
field=${FIELD:-1}
rate() {
  "$1" --throughput-only "$program" 1 |
    sed -n 's/.*median: \([0-9]*\) segments.*quantization \([0-9]*\) segments.*/\1 \2/p' |
    cut -d' ' -f"$field"
}
for ((i = 1; i <= pairs; ++i)); do
  ra=$(rate "$a")
  rb=$(rate "$b")
  echo "$ra $rb"
  echo "pair $i/$pairs: A $ra  B $rb segments/s" >&2
done | python3 -c '
import statistics, sys
pairs = [tuple(map(float, line.split())) for line in sys.stdin if line.strip()]
a = [p[0] for p in pairs]; b = [p[1] for p in pairs]; r = [p[1] / p[0] for p in pairs]
print("A median %.0f segments/s, B median %.0f segments/s, B/A median %.3f (%.3f to %.3f)"
      % (statistics.median(a), statistics.median(b), statistics.median(r), min(r), max(r)))'

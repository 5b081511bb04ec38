#!/usr/bin/env bash
# RT wake-up latency of the project's RT loop against cyclictest, back to
# back on the same machine: at each period, REPEATS pairs of
#   build/bench/rt_latency_bench --period-us P --seconds RUN_S --hist …
#   cyclictest -m -p 80 -i P -l RUN_S/P -h 2000 -q
# (the pair's order alternates, so a drift in the machine's load does not
# always favour the same tool). Both write a 1 µs histogram (cyclictest's -h
# format; ours mimics it) and one parser computes p50/p99/p99.9/max of each
# the way LatencyHistogram::quantile_us does: the upper edge of the bucket
# holding sample ⌊q·(n−1)⌋+1, the max when that sample overflowed. Prints
# every run, then a markdown table of the medians with the p99.9 ratio
# ours / cyclictest (goal ≤ 1.2). Both run SCHED_FIFO 80 with mlockall and
# /dev/cpu_dma_latency held at 0, unpinned. Needs root.
#
#   bench/rt_latency_vs_cyclictest.sh [BUILD_DIR]      (default build/)
#   env: RUN_S=10 REPEATS=3 PERIODS_US="75 25" PRIORITY=80
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
RUN_S=${RUN_S:-10}
REPEATS=${REPEATS:-3}
PERIODS_US=${PERIODS_US:-75 25}
PRIORITY=${PRIORITY:-80}
bench="$build/bench/rt_latency_bench"
[ -x "$bench" ] || { echo "no $bench: cmake --build $build --target rt_latency_bench" >&2; exit 2; }
command -v cyclictest >/dev/null || { echo "no cyclictest: scripts/deps.sh installs rt-tests" >&2; exit 2; }
command -v python3 >/dev/null || { echo "needs python3" >&2; exit 2; }
[ "$(id -u)" -eq 0 ] || echo "warning: not root: SCHED_FIFO and mlockall will be refused" >&2

tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
echo "# $(date -u +%F) $(uname -r), $(nproc) CPUs, load $(cut -d' ' -f1-3 /proc/loadavg)," \
     "${RUN_S} s per run, ${REPEATS} pairs per period"
for p in $PERIODS_US; do
  loops=$(( RUN_S * 1000000 / p ))
  for r in $(seq 1 "$REPEATS"); do
    ours() {
      "$bench" --period-us "$p" --seconds "$RUN_S" --priority "$PRIORITY" \
               --hist "$tmp/ours_${p}_$r.hist" > "$tmp/ours_${p}_$r.log"
    }
    theirs() {
      cyclictest -m -p "$PRIORITY" -i "$p" -l "$loops" -h 2000 -q > "$tmp/cyclictest_${p}_$r.hist"
    }
    if (( r % 2 )); then ours; theirs; else theirs; ours; fi
    grep -h "^warning" "$tmp/ours_${p}_$r.log" >&2 || true
  done
done

python3 - "$tmp" "$PERIODS_US" "$REPEATS" "$RUN_S" <<'PY'
import re, statistics, sys
tmp, periods, repeats, run_s = sys.argv[1], sys.argv[2].split(), int(sys.argv[3]), sys.argv[4]
QS = (0.5, 0.99, 0.999)

def figures(path):
    counts, overflows, max_us = [], 0, 0
    for line in open(path):
        m = re.match(r"^(\d{6}) (\d+)\s*$", line)
        if m:
            counts.append(int(m.group(2)))
        elif line.startswith("# Histogram Overflows:"):
            overflows = int(line.split(":")[1].split()[0])
        elif line.startswith("# Max Latencies:"):
            max_us = int(line.split(":")[1].split()[0])
    n = sum(counts) + overflows
    out = []
    for q in QS:
        rank, seen, value = int(q * (n - 1)) + 1, 0, float(max_us)
        for b, c in enumerate(counts):
            seen += c
            if seen >= rank:
                value = b + 1.0
                break
        out.append(value)
    return out + [float(max_us)], n

def fmt(v):
    return " / ".join(f"{x:g}" for x in v)

rows = []
for p in periods:
    ours, theirs, ratios = [], [], []
    for r in range(1, repeats + 1):
        o, no = figures(f"{tmp}/ours_{p}_{r}.hist")
        c, nc = figures(f"{tmp}/cyclictest_{p}_{r}.hist")
        ours.append(o); theirs.append(c); ratios.append(o[2] / c[2])
        print(f"{p} us run {r}: ours {fmt(o)} us ({no} samples) | cyclictest {fmt(c)} us "
              f"({nc} samples) | p99.9 ratio {o[2] / c[2]:.2f}")
    med_o = [statistics.median(x[i] for x in ours) for i in range(4)]
    med_c = [statistics.median(x[i] for x in theirs) for i in range(4)]
    rows.append((p, med_o, med_c, med_o[2] / med_c[2], ratios))
print()
print(f"| period | RtKernel p50 / p99 / p99.9 / max (µs) | cyclictest p50 / p99 / p99.9 / max (µs) "
      f"| p99.9 ratio (runs) |")
print("|---|---|---|---|")
for p, o, c, ratio, ratios in rows:
    runs = ", ".join(f"{x:.2f}" for x in ratios)
    print(f"| {p} µs | {fmt(o)} | {fmt(c)} | **{ratio:.2f}** ({runs}) |")
print(f"\nMedians of {repeats} runs of {run_s} s each; goal: p99.9 ratio ≤ 1.2.")
PY

#!/usr/bin/env bash
# How much faster than real time the simulated clock (`lasercnc run --fast`)
# runs a job: machine time over the wall time of the whole command (reading
# the program, the check, planning, the RT periods, the report), the median
# of N runs each, on the sample job, the 5-axis example under tool-centre-
# point control and a program of 100,000 chords (tests/e2e's wave).
#   bench/simulated_clock.sh [BUILD_DIR] [N]
set -euo pipefail
build=${1:-build}
n=${2:-5}
src=$(cd "$(dirname "$0")/.." && pwd)
exe="$build/app/lasercnc"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
sed 's/tcp = false/tcp = true/' "$src/share/machines/default.toml" > "$work/tcp.toml"
python3 - "$work/wave_100k.ngc" <<'PY'
import math, sys
with open(sys.argv[1], "w") as f:
    f.write("G21 G90 G64 P0.01\nG0 X10 Y200 Z5\nM3 S60\nF30000\n")
    n = 100000
    for i in range(1, n + 1):
        x = 10.0 + 980.0 * i / n
        y = 200.0 + 20.0 * math.sin(2.0 * math.pi * (x - 10.0) / 100.0)
        f.write("G1 X%.4f Y%.4f\n" % (x, y))
    f.write("M5\nM2\n")
PY
echo "| job | segments | machine time s | wall time s (median of $n) | faster than real time |"
echo "|---|---|---|---|---|"
run() {  # name, args
  local name=$1; shift
  local walls=() cycle="" segs=""
  for _ in $(seq "$n"); do
    local t0 t1 out
    t0=$(date +%s.%N)
    out=$("$exe" run "$@" --fast --json --no-progress)
    t1=$(date +%s.%N)
    walls+=("$(python3 -c "print($t1 - $t0)")")
    cycle=$(echo "$out" | python3 -c 'import json,sys; print(json.load(sys.stdin)["cycle_time_s"])')
    segs=$(echo "$out" | python3 -c 'import json,sys; print(json.load(sys.stdin)["segments"])')
  done
  local med
  med=$(printf '%s\n' "${walls[@]}" | sort -g | awk '{a[NR]=$1} END {print (NR%2 ? a[(NR+1)/2] : (a[NR/2]+a[NR/2+1])/2)}')
  printf '| %s | %s | %.3f | %.3f | x%.0f |\n' "$name" "$segs" "$cycle" "$med" "$(python3 -c "print($cycle / $med)")"
}
run "share/examples/bracket.ngc" "$src/share/examples/bracket.ngc"
run "share/examples/tcp_bevel.ngc (tcp = true)" "$src/share/examples/tcp_bevel.ngc" --machine "$work/tcp.toml"
run "wave of 100,000 chords, G64 P0.01" "$work/wave_100k.ngc"

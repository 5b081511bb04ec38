#!/usr/bin/env bash
# Zero underruns while the daemon runs a 1,000,000-segment program (issue
# "RT kernel"): lasercncd streams a dense CAM program (chords of 0.01–0.02 mm)
# through the position buffer while the RT thread runs it; prints the job's
# result and the kernel's underrun / low-buffer counts.
#
#   bench/daemon_stream.sh [BUILD_DIR] [LINES]
set -euo pipefail
build=${1:-build}
lines=${2:-1011500}  # lines; ~1,000,000 segments (the rest are S words and comments)
here=$(cd "$(dirname "$0")" && pwd)
prog=/tmp/lcnc_daemon_stream_${lines}.ngc
shm=/lcnc_bench_$$
[ -f "$prog" ] || python3 "$here/gen_program.py" "$prog" --lines "$lines" --chord 0.01 0.02
"$build/app/lasercnc" check "$prog"
"$build/app/lasercncd" --shm "$shm" 2>/tmp/lcnc_daemon_stream.log &
pid=$!
trap 'kill $pid 2>/dev/null || true' EXIT
for _ in $(seq 100); do "$build/app/lasercnc" status --shm "$shm" >/dev/null 2>&1 && break; sleep 0.05; done
"$build/app/lasercnc" send load "$prog" --shm "$shm"
/usr/bin/time -f "daemon wall time %e s" "$build/app/lasercnc" send start --wait --timeout 30 --shm "$shm"
"$build/app/lasercnc" status --shm "$shm"
"$build/app/lasercnc" status --json --shm "$shm" | python3 -c '
import json, sys
s = json.load(sys.stdin)
print("underruns %d  low-buffer decelerations %d  cycle %.3f s  RT latency p99 %s us"
      % (s["underruns"], s["starvations"], s["last_cycle_time_s"], s["latency_us"]["p99"]))'
kill -TERM $pid
wait $pid

#!/usr/bin/env bash
# `lasercnc cut` of drawings with one polyline of up to a million vertices:
# wall time and peak memory (maximum resident set size) of the whole command
# — reading the DXF, the crossing check, nesting, the kerf offset, lead-ins
# and writing the G-code — the median of N runs each.
#   bench/cut_large.sh [BUILD_DIR] [N]
set -euo pipefail
build=${1:-build}
n=${2:-3}
exe="$build/app/lasercnc"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
python3 - "$work" <<'PY'
import math, sys
d = sys.argv[1]
def write(name, pts):
    with open(f"{d}/{name}", "w") as f:
        f.write("0\nSECTION\n2\nHEADER\n9\n$INSUNITS\n70\n4\n0\nENDSEC\n0\nSECTION\n2\nENTITIES\n")
        f.write("0\nLWPOLYLINE\n8\nCUT\n90\n%d\n70\n1\n" % len(pts))
        f.write("".join("10\n%.6f\n20\n%.6f\n" % p for p in pts))
        f.write("0\nENDSEC\n0\nEOF\n")
def ring(n, wave):
    out = []
    for i in range(n):
        t = 2 * math.pi * i / n
        r = 200.0 + wave(t)
        out.append((250 + r * math.cos(t), 250 + r * math.sin(t)))
    return out
write("circle_900k.dxf", ring(900_000, lambda t: 0.0))
write("gear_1M.dxf", ring(1_000_000, lambda t: 10.0 * math.sin(200 * t)))
PY
echo "| drawing | vertices | wall time s (median of $n) | peak memory MB (median) | G-code lines |"
echo "|---|---|---|---|---|"
run() {  # file, label, vertices
  python3 - "$exe" "$work/$1" "$work/out.ngc" "$2" "$3" "$n" <<'PY'
import os, statistics, subprocess, sys, time
exe, dxf, out, label, verts, n = sys.argv[1], sys.argv[2], sys.argv[3], sys.argv[4], sys.argv[5], int(sys.argv[6])
walls, rss = [], []
for _ in range(n):
    t0 = time.monotonic()
    p = subprocess.Popen([exe, "cut", dxf, "-o", out], stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    _, status, usage = os.wait4(p.pid, 0)
    walls.append(time.monotonic() - t0)
    rss.append(usage.ru_maxrss / 1024.0)
    if status != 0:
        sys.exit(f"{label}: lasercnc cut failed: {p.stderr.read().decode()}")
lines = sum(1 for _ in open(out))
print(f"| {label} | {verts} | {statistics.median(walls):.2f} | {statistics.median(rss):.0f} | {lines} |")
PY
}
run circle_900k.dxf "circle, r 200 mm" 900000
run gear_1M.dxf "wavy ring, r 200 ± 10 mm, 200 waves" 1000000

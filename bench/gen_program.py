#!/usr/bin/env python3
"""Writes a dense CAM-style G-code program for benchmarks.

  bench/gen_program.py OUT.ngc [--lines N] [--seed S] [--chord MIN MAX]

A spiral of short G1 chords (default 0.01–1 mm) in the XY plane with a slow Z drift,
interleaved, as CAM output is, with S words, comments and arcs. Deterministic
for a given seed.
"""
import argparse
import math
import random


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("out")
    ap.add_argument("--lines", type=int, default=1_000_000)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--chord", type=float, nargs=2, default=(0.01, 1.0), metavar=("MIN", "MAX"),
                    help="chord length range, mm")
    args = ap.parse_args()
    rng = random.Random(args.seed)
    cx, cy = 500.0, 225.0
    with open(args.out, "w") as f:
        f.write("%\n(benchmark program: dense chords)\nG21 G90 G17 G94 G54 G64 P0.01\n")
        f.write(f"G0 X{cx + 1:.4f} Y{cy:.4f} Z10\nS80 M3\nG1 F6000\n")
        written = 6
        ang, rad, z = 0.0, 1.0, 10.0
        n = 0
        while written < args.lines - 2:
            n += 1
            step = rng.uniform(*args.chord)
            ang += step / rad
            rad = min(200.0, rad + 0.0002)
            z = 10.0 + 0.5 * math.sin(ang / 50.0)
            x, y = cx + rad * math.cos(ang), cy + rad * math.sin(ang)
            if n % 1000 == 0:
                f.write(f"(layer {n // 1000})\n")
            elif n % 97 == 0:
                f.write(f"S{70 + n % 30}\n")
            elif n % 251 == 0:
                # a small arc back to the spiral's tangent direction
                f.write(f"G2 X{x:.4f} Y{y:.4f} R{rad:.4f}\n")
            else:
                f.write(f"G1 X{x:.4f} Y{y:.4f} Z{z:.4f}\n")
            written += 1
        f.write("M5\nM2\n")


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""Plots the planner benchmark's speed profiles: ours against the time-optimal
traversal of the same blended path, and the velocity limit curve.

  build/bench/planner_bench --csv /tmp/planner_csv
  python3 bench/plot_planner.py /tmp/planner_csv docs/bench/planner_speed.png

Needs matplotlib (pip install matplotlib).
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

CASES = [
    ("square", "50 mm square, 3 laps, F6000 (first lap)", 200.0),
    ("circle", "R40 circle of 2000 chords, F6000", None),
    ("zigzag", "60° zig-zag, 10 mm strokes, F3000 (first 60 mm)", 60.0),
    ("gear", "gear outline, 0.05 mm chords, F6000 (first 3 teeth)", 32.0),
]


def load(path, s_max):
    s, opt, ours, lim = [], [], [], []
    with open(path) as f:
        for row in csv.DictReader(f):
            x = float(row["s_mm"])
            if s_max is not None and x > s_max:
                break
            s.append(x)
            opt.append(float(row["v_optimal"]))
            ours.append(float(row["v_ours"]))
            lim.append(min(float(row["v_limit"]), 120.0))
    return s, opt, ours, lim


def main() -> None:
    src, out = sys.argv[1], sys.argv[2]
    fig, axes = plt.subplots(len(CASES), 1, figsize=(11, 12))
    for ax, (key, title, s_max) in zip(axes, CASES):
        s, opt, ours, lim = load(f"{src}/{key}.csv", s_max)
        ax.plot(s, lim, color="0.75", lw=1, label="velocity limit curve")
        ax.plot(s, opt, color="tab:green", lw=1.6, label="time-optimal")
        ax.plot(s, ours, color="tab:blue", lw=1, ls="--", label="LaserCNC planner")
        ax.set_title(title, fontsize=10)
        ax.set_ylabel("path speed [mm/s]")
        ax.set_ylim(0, 115)
        ax.grid(alpha=0.3)
    axes[-1].set_xlabel("path length s [mm]")
    axes[0].legend(loc="lower right", fontsize=8)
    fig.suptitle("Planned path speed against the time-optimal traversal "
                 "(vmax 100 mm/s, amax 2000 mm/s² per axis, P 0.01 mm)")
    fig.tight_layout()
    fig.savefig(out, dpi=90)


if __name__ == "__main__":
    main()

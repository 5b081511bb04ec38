#!/usr/bin/env python3
"""Plots a main + auxiliary axes decomposition from its kinematics table
(the CSV of `lasercnc decompose --csv` or `decompose_bench --csv`):

  left:   the contour S green and the main-axis path S1 blue (Kondratenko et al. 2015 Fig. 6)
  middle: the auxiliary path S2 = S - S1 red, in its field
  right:  effective (beam) and main-axis acceleration over time (Fig. 8)

  python3 bench/plot_decompose.py TABLE.csv OUT.png [--title T]
                                  [--limit A_mm_s2] [--field HALF_mm]

Needs matplotlib (Debian: apt-get install python3-matplotlib). Without it
the script says so and exits 3; the CSV (and the SVGs the C++ writes) stand.
"""
import argparse
import csv
import sys

try:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
except ImportError:
    print("plot_decompose.py: matplotlib is missing (apt-get install python3-matplotlib); "
          "no PNG made, the CSV is unchanged", file=sys.stderr)
    sys.exit(3)


def load(path):
    """Per contour: lists of x, y, p, q, sx, sy, t, a_main, a_eff."""
    contours = {}
    with open(path) as f:
        for row in csv.DictReader(f):
            c = contours.setdefault(row["contour"], {k: [] for k in
                                                     ("x", "y", "p", "q", "sx", "sy", "t", "a_main", "a_eff")})
            c["x"].append(float(row["x_mm"]))
            c["y"].append(float(row["y_mm"]))
            c["p"].append(float(row["p_mm"]))
            c["q"].append(float(row["q_mm"]))
            c["sx"].append(float(row["sx_mm"]))
            c["sy"].append(float(row["sy_mm"]))
            c["t"].append(float(row["t_s"]))
            c["a_main"].append(float(row["a_main_mm_s2"]) / 1000.0)
            c["a_eff"].append(float(row["a_eff_mm_s2"]) / 1000.0)
    return contours


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("csv")
    ap.add_argument("png")
    ap.add_argument("--title", default="")
    ap.add_argument("--limit", type=float, default=0.5 * 9806.65, help="main-axis limit, mm/s^2")
    ap.add_argument("--field", type=float, default=5.0, help="auxiliary half field, mm")
    a = ap.parse_args()
    contours = load(a.csv)

    fig, (ax1, ax2, ax3) = plt.subplots(1, 3, figsize=(18, 6), gridspec_kw={"width_ratios": [1.3, 1, 1.6]})
    t0 = 0.0
    for i, c in enumerate(contours.values()):
        ax1.plot(c["sx"], c["sy"], color="green", lw=2.0, label="S contour" if i == 0 else None)
        ax1.plot(c["x"], c["y"], color="blue", lw=0.8, label="S1 main axes (X, Y)" if i == 0 else None)
        ax2.plot(c["p"], c["q"], color="red", lw=0.8, label="S2 auxiliary axes (P, Q)" if i == 0 else None)
        t = [t0 + v for v in c["t"]]
        ax3.plot(t, c["a_eff"], color="green", lw=0.8, label="effective (beam)" if i == 0 else None)
        ax3.plot(t, c["a_main"], color="blue", lw=0.8, label="main axes" if i == 0 else None)
        t0 = t[-1]
    f = a.field
    ax2.plot([-f, f, f, -f, -f], [-f, -f, f, f, -f], color="grey", ls="--", lw=0.8, label="field")
    ax3.axhline(a.limit / 1000.0, color="blue", ls="--", lw=0.8, label="main-axis limit")
    peak = max(max(c["a_eff"] + c["a_main"]) for c in contours.values())
    if peak > 20 * a.limit / 1000.0:  # sharp corners: a log scale keeps the main axes visible
        ax3.set_yscale("log")
        ax3.set_ylim(bottom=1e-3)
    for ax in (ax1, ax2):
        ax.set_aspect("equal")
        ax.set_xlabel("mm")
        ax.legend(loc="upper right", fontsize=8)
    ax1.set_title("contour and main-axis path")
    ax2.set_title("auxiliary path in its field")
    ax3.set_title("acceleration")
    ax3.set_xlabel("time, s")
    ax3.set_ylabel("m/s²")
    ax3.legend(loc="upper right", fontsize=8)
    if a.title:
        fig.suptitle(a.title)
    fig.tight_layout()
    fig.savefig(a.png, dpi=90)
    print(f"wrote {a.png}")


if __name__ == "__main__":
    main()

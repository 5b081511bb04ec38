#!/usr/bin/env python3
"""Plots the orientation benchmark (the A/C axis curves of Shao (2022) Fig. 16):
A and C position, C speed and orientation error along a move that passes
0.005° from the A = 0 singularity, for the three interpolators.

  build/bench/orientation_bench --csv /tmp/orientation_csv
  python3 bench/plot_orientation.py /tmp/orientation_csv docs/bench/orientation_ac.png

Needs matplotlib only for the picture (Debian: apt-get install
python3-matplotlib); the bench writes its table and CSV without it.
"""
import csv
import sys

METHODS = [
    ("joint_linear", "joint-linear (A, C linear)", "tab:orange", "-"),
    ("vector", "vector (great circle)", "tab:red", "-"),
    ("pole_smoothed", "pole-smoothed (improved vector)", "tab:blue", "--"),
]


def load(path):
    cols = {}
    with open(path) as f:
        for row in csv.DictReader(f):
            for k, v in row.items():
                cols.setdefault(k, []).append(float(v))
    return cols


def main() -> None:
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    src, out = sys.argv[1], sys.argv[2]
    try:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        sys.exit("plot_orientation.py: matplotlib is missing, so no picture "
                 "(apt-get install python3-matplotlib, or pip install matplotlib); "
                 f"the CSV in {src}/ is complete without it.")

    data = {key: load(f"{src}/{key}.csv") for key, *_ in METHODS}
    fig, axes = plt.subplots(4, 1, figsize=(10, 12), sharex=True)
    for key, label, color, ls in METHODS:
        d = data[key]
        t = d["t_s"]
        axes[0].plot(t, d["a_deg"], color=color, ls=ls, lw=1.4, label=label)
        axes[1].plot(t, d["c_deg"], color=color, ls=ls, lw=1.4, label=label)
        axes[2].plot(t, [abs(v) for v in d["c_vel_deg_s"]], color=color, ls=ls, lw=1.4,
                     label=label)
        axes[3].plot(t, [max(e, 1e-12) for e in d["error_deg"]], color=color, ls=ls, lw=1.4,
                     label=label)
    axes[0].set_ylabel("A [deg]")
    axes[1].set_ylabel("C [deg]")
    axes[2].set_ylabel("|C speed| [deg/s]")
    axes[2].set_yscale("log")
    axes[2].axhline(360.0, color="0.4", lw=0.8, ls=":")
    axes[2].text(0.01, 420.0, "C max velocity 360 °/s", fontsize=8, color="0.3")
    axes[3].set_ylabel("orientation error [deg]")
    axes[3].set_yscale("log")
    axes[3].set_ylim(1e-6, 100.0)
    axes[3].axhline(0.01, color="0.4", lw=0.8, ls=":")
    axes[3].text(0.01, 0.013, "tolerance 0.01°", fontsize=8, color="0.3")
    axes[3].text(0.01, 2e-6, "vector: 0 (exact, shown at the floor)", fontsize=8, color="tab:red")
    axes[3].set_xlabel("time [s]")
    for ax in axes:
        ax.grid(alpha=0.3)
    axes[0].legend(loc="lower left", fontsize=8)
    fig.suptitle("Tool orientation through the A = 0 singularity: (30°, 0°) → (30°, 179.98°), "
                 "great circle 0.005° from the pole,\n1 s rest to rest; A/C limits of the default "
                 "machine (C 360 °/s, 3600 °/s²)")
    fig.tight_layout()
    fig.savefig(out, dpi=90)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()

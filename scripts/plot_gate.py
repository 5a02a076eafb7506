#!/usr/bin/python3
"""Elastic gate runs against the published results (paper Figs. 11, 12, 14).

usage: plot_gate.py RUN_DIR [RUN_DIR ...] [--labels A B ...] [--output FILE.png] [--window S]

Top: x-displacement of the gate's top-left corner (probe `tip`) of each run against the
published curves in tests/data/walhorn_elastic_gate/. Bottom: P* on the gate's left face
(probes P_h20, P_h40, P_h60) of the first run, as a centred moving average over --window
seconds (0: every step). Prints each run's peak and its time.
"""
import argparse
import csv
import glob
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

from plot_probes import moving_average

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = os.path.join(ROOT, "tests/data/walhorn_elastic_gate")
PUBLISHED = {
    "mps_jl_walhorn.csv": "Walhorn et al. 2005",
    "mps_jl_idelsohn.csv": "Idelsohn et al. 2008 (PFEM)",
    "mps_jl_ryzhakov.csv": "Ryzhakov et al. 2010",
    "mps_jl_rafiee.csv": "Rafiee & Thiagarajan 2009 (SPH)",
    "mps_jl_li.csv": "Li et al.",
}


def read_csv(path):
    with open(path) as f:
        rows = [l for l in f if not l.startswith("#")]
    r = csv.reader(rows)
    header = next(r)
    return header, np.array([[float(v) for v in row] for row in r])


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("runs", nargs="+")
    ap.add_argument("--labels", nargs="*")
    ap.add_argument("--output", default="gate.png")
    ap.add_argument("--window", type=float, default=0.0)
    args = ap.parse_args()
    labels = args.labels or [os.path.basename(os.path.normpath(r)) for r in args.runs]

    fig, (ax, bx) = plt.subplots(2, 1, figsize=(8, 8))
    for name, label in PUBLISHED.items():
        d = np.loadtxt(os.path.join(DATA, name), delimiter=",")
        ax.plot(d[:, 0], d[:, 1] * 1e3, lw=0.8, color="0.55", ls="--" if "li" in name else "-")
        i = np.argmax(d[:, 1])
        print(f"{label:34s} peak {d[i, 1] * 1e3:5.1f} mm at {d[i, 0]:.3f} s")
    ax.plot([], [], color="0.55", lw=0.8, label="published (5 methods)")
    for run, label in zip(args.runs, labels):
        header, d = read_csv(os.path.join(run, "tip.csv"))
        t, dx = d[:, header.index("t")], d[:, header.index("dx")]
        i = np.argmax(dx)
        print(f"{label:34s} peak {dx[i] * 1e3:5.1f} mm at {t[i]:.3f} s")
        ax.plot(t, dx * 1e3, lw=1.2, label=f"bsmpm {label}")
    ax.set_xlabel("t [s]")
    ax.set_ylabel("x-displacement of the top-left corner [mm]")
    ax.set_xlim(0, 0.5)
    ax.set_ylim(bottom=-5)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)

    for path in sorted(glob.glob(os.path.join(args.runs[0], "P_h*.csv"))):
        header, d = read_csv(path)
        t = d[:, header.index("t")]
        bx.plot(t, moving_average(t, d[:, header.index("P*")], args.window), lw=0.8, label=os.path.basename(path)[:-4])
    bx.set_xlabel("t [s]")
    bx.set_ylabel("P* = P / (rho g H)" + (f", moving average {args.window * 1e3:g} ms" if args.window > 0 else ""))
    bx.set_xlim(0, 0.5)
    bx.grid(alpha=0.3)
    bx.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(args.output, dpi=110)
    print(f"plot_gate: wrote {args.output}")


if __name__ == "__main__":
    main()

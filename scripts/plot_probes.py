#!/usr/bin/python3
"""Plots the pressure probes of a run (P* against T*), optionally against experiment.

usage: plot_probes.py RUN_DIR [RUN_DIR ...] [--labels LABEL ...] [--experiment lobovsky_h300]
                      [--output FILE.png] [--probes NAME ...] [--window DT* | --sensor]
                      [--title TEXT]

The experimental curves come from tests/data/ (Lobovsky et al. 2014, one run at 20 kHz),
with the 2.5-97.5 % band of the peak over 100 repeats (their Table 2) drawn as a bar.
--window draws a centred moving average of that width in T* of the simulation over its
raw samples (drawn faint); 0, the default, draws the raw samples only.
--sensor draws every series, simulated and measured, through the documented sensor model
(docs/studies.md: resampled to 20 kHz, 1 ms centred moving average) by `bsmpm metrics`.
Several runs are drawn over each other (the first one's directory gets the figure).
"""
import subprocess
import argparse
import csv
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXPERIMENTS = {
    "lobovsky_h300": {
        "P_z30": ("tests/data/lobovsky2014_h300/sensor3_z30mm_run.dat", 30.0),
        "P_z80": ("tests/data/lobovsky2014_h300/sensor4_z80mm_run.dat", 80.0),
    }
}


def read_probe(path):
    with open(path) as f:
        lines = [l for l in f if not l.startswith("#")]
    reader = csv.reader(lines)
    header = next(reader)
    data = np.array([[float(v) for v in row] for row in reader])
    return header, data


def peak_band(z_mm):
    path = os.path.join(ROOT, "tests/data/lobovsky2014_h300/peak_statistics.txt")
    for row in np.loadtxt(path, comments="#"):
        if abs(row[0] - z_mm) < 1e-6:
            return row[4], row[5], row[6]  # median, 2.5 %, 97.5 % of P*
    return None


def moving_average(t, y, width):
    if width <= 0:
        return y
    c = np.concatenate([[0.0], np.cumsum(y)])
    lo = np.searchsorted(t, t - width / 2)
    hi = np.searchsorted(t, t + width / 2, side="right")
    return (c[hi] - c[lo]) / np.maximum(hi - lo, 1)


def sensor_series(args_list):
    """Runs `bsmpm metrics ARGS` and returns (T*, value) of its CSV output."""
    out = subprocess.run([os.path.join(ROOT, "build/render/bsmpm"), "metrics"] + args_list,
                         check=True, capture_output=True, text=True).stdout
    rows = [l.split(",") for l in out.splitlines()[1:] if l and not l.startswith("#")]
    d = np.array([[float(v) for v in r] for r in rows])
    return d[:, 1], d[:, 2]


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("run_dirs", nargs="+")
    ap.add_argument("--labels", nargs="*")
    ap.add_argument("--experiment", choices=sorted(EXPERIMENTS))
    ap.add_argument("--output", default=None)
    ap.add_argument("--probes", nargs="*")
    ap.add_argument("--window", type=float, default=0.0)
    ap.add_argument("--sensor", action="store_true")
    ap.add_argument("--title", default=None)
    args = ap.parse_args()
    labels = args.labels or [os.path.basename(r.rstrip("/")) if len(args.run_dirs) > 1 else "bsmpm" for r in args.run_dirs]
    if len(labels) != len(args.run_dirs):
        sys.exit("plot_probes: give one --labels entry per run directory")

    first = args.run_dirs[0]
    names = args.probes or sorted(f[:-4] for f in os.listdir(first) if f.endswith(".csv") and f.startswith("P"))
    if not names:
        sys.exit(f"plot_probes: no pressure probe CSVs in {first}")
    fig, axes = plt.subplots(len(names), 1, figsize=(8, 2.8 * len(names)), squeeze=False)
    colours = ["tab:blue", "tab:red", "tab:green", "tab:orange", "tab:purple"]
    for ax, name in zip(axes[:, 0], names):
        exp = EXPERIMENTS.get(args.experiment, {}).get(name)
        if exp:
            e = np.loadtxt(os.path.join(ROOT, exp[0]))
            eT, eP = sensor_series(["--series-file", os.path.join(ROOT, exp[0]), "--length", "0.3"]) if args.sensor \
                else (e[:, 0], e[:, 1])
            ax.plot(eT, eP, color="0.5", lw=0.7, label="experiment (Lobovsky et al. 2014)")
            band = peak_band(exp[1])
            if band:
                ax.errorbar([e[np.argmax(e[:, 1]), 0]], [band[0]], yerr=[[band[0] - band[1]], [band[2] - band[0]]],
                            fmt="s", color="k", ms=4, capsize=3, label="peak median, 2.5-97.5 %")
        T_end = 6.0
        for k, (run, label) in enumerate(zip(args.run_dirs, labels)):
            colour = colours[k % len(colours)]
            header, d = read_probe(os.path.join(run, name + ".csv"))
            if "P*" not in header:
                continue
            T, P = d[:, header.index("T*")], d[:, header.index("P*")]
            T_end = max(T_end, T.max())
            if args.sensor:
                sT, sP = sensor_series([run, "--series", name])
                ax.plot(sT, sP, color=colour, lw=0.9, label=f"{label}")
            elif args.window > 0:  # raw samples underneath, faint
                ax.plot(T, P, color=colour, lw=0.4, alpha=0.3, label=f"{label}, every step")
                ax.plot(T, moving_average(T, P, args.window), color=colour, lw=1.0,
                        label=f"{label}, moving average {args.window:g} T*")
            else:
                ax.plot(T, P, color=colour, lw=0.9, label=label)
        ax.set_ylabel("P*" + (" (sensor model)" if args.sensor else ""))
        ax.set_title(name, fontsize=10)
        ax.set_xlim(0, T_end)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8, loc="upper left")
    if args.title:
        fig.suptitle(args.title, fontsize=10)
    axes[-1, 0].set_xlabel("T* = t sqrt(g/H)")
    fig.tight_layout()
    out = args.output or os.path.join(first, "pressure_probes.png")
    fig.savefig(out, dpi=110)
    print(f"plot_probes: wrote {out}")


if __name__ == "__main__":
    main()

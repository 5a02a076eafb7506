#!/usr/bin/python3
"""Elastic gate runs against the published results (paper Figs. 11, 12, 14).

usage: plot_gate.py RUN_DIR [RUN_DIR ...] [--labels A B ...] [--output FILE.png] [--window S]

Top: x-displacement of the gate's top-left corner (probe `tip`) of each run against the
published curves in tests/data/walhorn_elastic_gate/. Bottom: P* on the gate's left face
(probes P_h20, P_h40, P_h60) of the first run, as a centred moving average over --window
seconds (0: every step). Prints each run's peak and its time.
"""
import glob
import json
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from plot_probes import finish_figure, moving_average, run_labels, run_name, runs_argument_parser  # noqa: E402
from run_csv import read_run_csv  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = os.path.join(ROOT, "tests/data/walhorn_elastic_gate")
# The five published curves, each with its own grey line style so that the legend names each.
PUBLISHED = {
    "mps_jl_walhorn.csv": ("Walhorn et al. 2005", "-"),
    "mps_jl_idelsohn.csv": ("Idelsohn et al. 2008 (PFEM)", "--"),
    "mps_jl_ryzhakov.csv": ("Ryzhakov et al. 2010", "-."),
    "mps_jl_rafiee.csv": ("Rafiee & Thiagarajan 2009 (SPH)", ":"),
    "mps_jl_li.csv": ("Li et al.", (0, (5, 1, 1, 1, 1, 1))),
}


def read_csv(path):
    """(column names, rows) of a probe CSV, with units in its header or not (run_csv.py)."""
    names, _, rows = read_run_csv(path)
    return names, rows


def provenance(runs):
    """'bsmpm 0.1.0 (abc123)' of the runs (their summary.json), each revision once."""
    seen = []
    for run in runs:
        try:
            with open(os.path.join(run, "summary.json")) as f:
                s = json.load(f)
            text = f"bsmpm {s['program_version']} ({s['git_revision']})"
        except (OSError, KeyError, ValueError):
            text = "bsmpm (revision unknown)"
        if text not in seen:
            seen.append(text)
    return ", ".join(seen)


def reference_length(run):
    """H of the run's P* (run.h5 /reference), or None when it cannot be read."""
    try:
        import h5py
        with h5py.File(os.path.join(run, "run.h5"), "r") as f:
            return float(f["reference"].attrs["length"])
    except Exception:  # noqa: BLE001 -- a label without H is still right
        return None


def draw(runs, labels, window):
    """The figure: the tip's deflection of every run against the published curves (top), the
    face pressures of the first run (bottom). Prints each curve's peak."""
    fig, (ax, bx) = plt.subplots(2, 1, figsize=(8, 8.6))
    for name, (label, style) in PUBLISHED.items():
        d = np.loadtxt(os.path.join(DATA, name), delimiter=",")
        ax.plot(d[:, 0], d[:, 1] * 1e3, lw=0.9, color="0.5", ls=style, label=label)
        i = np.argmax(d[:, 1])
        print(f"{label:34s} peak {d[i, 1] * 1e3:5.1f} mm at {d[i, 0]:.3f} s")
    for run, label in zip(runs, labels):
        header, d = read_csv(os.path.join(run, "tip.csv"))
        t, dx = d[:, header.index("t")], d[:, header.index("dx")]
        i = np.argmax(dx)
        print(f"{label:34s} peak {dx[i] * 1e3:5.1f} mm at {t[i]:.3f} s")
        ax.plot(t, dx * 1e3, lw=1.6, label=f"bsmpm, {label}")
    ax.set_title("x-displacement of the gate's top-left corner, against five published methods", fontsize=10)
    ax.set_xlabel("t [s]")
    ax.set_ylabel("x-displacement [mm]")
    ax.set_xlim(0, 0.5)
    ax.set_ylim(bottom=-5)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7, ncol=2)

    for path in sorted(glob.glob(os.path.join(runs[0], "P_h*.csv"))):
        header, d = read_csv(path)
        t = d[:, header.index("t")]
        name = os.path.basename(path)[:-4]
        bx.plot(t, moving_average(t, d[:, header.index("P*")], window), lw=0.8,
                label=f"{name}: {name[3:]} mm above the floor")
    smoothing = f", moving average {window * 1e3:g} ms" if window > 0 else ", every step"
    bx.set_title(f"Pressure on the gate's face, bsmpm {labels[0]}{smoothing}", fontsize=10)
    bx.set_xlabel("t [s]")
    H = reference_length(runs[0])
    bx.set_ylabel("P* = P / (rho g H)" + (f", H = {H * 1e3:g} mm" if H else ""))
    bx.set_xlim(0, 0.5)
    bx.grid(alpha=0.3)
    bx.legend(fontsize=8)
    fig.suptitle("Elastic gate (Walhorn et al. 2005 benchmark): paper Figs. 11, 12 and 14", fontsize=11)
    return finish_figure(fig, provenance(runs))


def main():
    args = runs_argument_parser(__doc__, "runs", "gate.png").parse_args()
    labels = run_labels("plot_gate", args.runs, args.labels, run_name)
    draw(args.runs, labels, args.window).savefig(args.output, dpi=110)
    print(f"plot_gate: wrote {args.output}")


if __name__ == "__main__":
    main()

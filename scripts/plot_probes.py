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
import argparse
import os
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from run_csv import read_run_csv  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
EXPERIMENTS = {
    "lobovsky_h300": {
        "P_z30": ("tests/data/lobovsky2014_h300/sensor3_z30mm_run.dat", 30.0),
        "P_z80": ("tests/data/lobovsky2014_h300/sensor4_z80mm_run.dat", 80.0),
    }
}


def read_probe(path):
    """(column names, rows) of a probe CSV, with units in its header or not (run_csv.py)."""
    names, _, rows = read_run_csv(path)
    return names, rows


def peak_band(z_mm):
    path = os.path.join(ROOT, "tests/data/lobovsky2014_h300/peak_statistics.txt")
    for row in np.loadtxt(path, comments="#"):
        if abs(row[0] - z_mm) < 1e-6:
            return row[4], row[5], row[6]  # median, 2.5 %, 97.5 % of P*
    return None


def finish_figure(fig, footer):
    """The data's provenance in small grey type at the bottom left, and a layout that leaves it room."""
    fig.text(0.01, 0.005, footer, fontsize=6, color="0.4", va="bottom")
    fig.tight_layout(rect=(0, 0.02, 1, 1))
    return fig


def runs_argument_parser(doc, runs, output_default):
    """The options every plot of runs takes: the run directories (`runs`), --labels, --output, --window."""
    ap = argparse.ArgumentParser(description=doc, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument(runs, nargs="+")
    ap.add_argument("--labels", nargs="*")
    ap.add_argument("--output", default=output_default)
    ap.add_argument("--window", type=float, default=0.0)
    return ap


def run_name(run):
    """A run's directory name, the default label of a run."""
    return os.path.basename(os.path.normpath(run))


def run_labels(program, runs, labels, default):
    """The given --labels, one per run, or default(run) for each run."""
    labels = labels or [default(r) for r in runs]
    if len(labels) != len(runs):
        sys.exit(f"{program}: give one --labels entry per run directory")
    return labels


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


def run_facts(run):
    """(title, grid cell size [m], 'bsmpm VERSION (REVISION)') of a run, from its run.h5."""
    try:
        import h5py
        with h5py.File(os.path.join(run, "run.h5"), "r") as f:
            title = f.attrs.get("title", b"")
            title = title.decode() if isinstance(title, bytes) else str(title)
            version = f.attrs.get("program_version", b"?")
            revision = f.attrs.get("git_revision", b"?")
            decode = (lambda v: v.decode() if isinstance(v, bytes) else str(v))
            return title, float(f["grid"].attrs["cell_size"][0]), f"bsmpm {decode(version)} ({decode(revision)})"
    except Exception:  # noqa: BLE001 -- a run without run.h5 is drawn all the same
        return "", None, "bsmpm (revision unknown)"


def draw(run_dirs, labels, experiment=None, probes=None, window=0.0, sensor=False, title=None):
    """The figure: one panel per pressure probe, P* against T* of every run, the experiment's
    series and peak band when given."""
    first = run_dirs[0]
    names = probes or sorted(f[:-4] for f in os.listdir(first) if f.endswith(".csv") and f.startswith("P"))
    if not names:
        sys.exit(f"plot_probes: no pressure probe CSVs in {first}")
    facts = [run_facts(r) for r in run_dirs]
    fig, axes = plt.subplots(len(names), 1, figsize=(8, 2.8 * len(names) + 0.6), squeeze=False)
    colours = ["tab:blue", "tab:red", "tab:green", "tab:orange", "tab:purple"]
    for ax, name in zip(axes[:, 0], names):
        exp = EXPERIMENTS.get(experiment, {}).get(name)
        if exp:
            e = np.loadtxt(os.path.join(ROOT, exp[0]))
            eT, eP = sensor_series(["--series-file", os.path.join(ROOT, exp[0]), "--length", "0.3"]) if sensor \
                else (e[:, 0], e[:, 1])
            ax.plot(eT, eP, color="0.5", lw=0.7, label="experiment (Lobovsky et al. 2014)")
            band = peak_band(exp[1])
            if band:
                ax.errorbar([e[np.argmax(e[:, 1]), 0]], [band[0]], yerr=[[band[0] - band[1]], [band[2] - band[0]]],
                            fmt="s", color="k", ms=4, capsize=3, label="peak median, 2.5-97.5 %")
        T_end = 6.0
        for k, (run, label) in enumerate(zip(run_dirs, labels)):
            colour = colours[k % len(colours)]
            header, d = read_probe(os.path.join(run, name + ".csv"))
            if "P*" not in header:
                continue
            T, P = d[:, header.index("T*")], d[:, header.index("P*")]
            T_end = max(T_end, T.max())
            if sensor:
                sT, sP = sensor_series([run, "--series", name])
                ax.plot(sT, sP, color=colour, lw=0.9, label=f"{label}")
            elif window > 0:  # raw samples underneath, faint
                ax.plot(T, P, color=colour, lw=0.4, alpha=0.3, label=f"{label}, every step")
                ax.plot(T, moving_average(T, P, window), color=colour, lw=1.0,
                        label=f"{label}, moving average {window:g} T*")
            else:
                ax.plot(T, P, color=colour, lw=0.9, label=label)
        ax.set_ylabel("P* = P / (rho g H)" + (" (sensor model)" if sensor else ""))
        height = name[3:] if name.startswith("P_z") else ""
        ax.set_title(f"{name}: {height} mm above the floor" if height.isdigit() else name, fontsize=10)
        ax.set_xlim(0, T_end)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8, loc="upper left")
    if title is None:  # the run and its grid: a reader must tell a 5 mm run from a 2 mm one
        run_title, cell, _ = facts[0]
        grids = sorted({f[1] for f in facts if f[1]})
        title = (run_title or os.path.basename(os.path.normpath(first))) + \
            (", h = " + " and ".join(f"{h * 1e3:g} mm" for h in grids) if grids else "")
    fig.suptitle(title, fontsize=10)
    axes[-1, 0].set_xlabel("T* = t sqrt(g/H)")
    return finish_figure(fig, ", ".join(dict.fromkeys(f[2] for f in facts)))


def main():
    ap = runs_argument_parser(__doc__, "run_dirs", None)
    ap.add_argument("--experiment", choices=sorted(EXPERIMENTS))
    ap.add_argument("--probes", nargs="*")
    ap.add_argument("--sensor", action="store_true")
    ap.add_argument("--title", default=None)
    args = ap.parse_args()
    labels = run_labels("plot_probes", args.run_dirs, args.labels,
                        lambda r: run_name(r) if len(args.run_dirs) > 1 else "bsmpm")
    fig = draw(args.run_dirs, labels, args.experiment, args.probes, args.window, args.sensor, args.title)
    out = args.output or os.path.join(args.run_dirs[0], "pressure_probes.png")
    fig.savefig(out, dpi=110)
    print(f"plot_probes: wrote {out}")


if __name__ == "__main__":
    main()

#!/usr/bin/python3
"""Draws a study's [[plots]] from its CSV (docs/studies.md, "Plots"); run by the Snakefile's
plots rule in OUT. Writes OUT/<plot>.png for each plot and OUT/<study>_fits.csv with the
coefficients and R^2 of every fitted curve.

usage: plot_study.py PLAN.json STUDY.csv

  metric   a metric against an axis, one curve per combination of the other axes
  profile  several metrics at positions (e.g. probe heights), one curve per case
  series   probe signals through the sensor model (bsmpm metrics --series), one panel per
           probe, one curve per case, with reference series filtered the same way
"""
import csv
import io
import itertools
import math
import os
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import fits  # noqa: E402


def number(v):
    try:
        return float(v)
    except (TypeError, ValueError):
        return math.nan


def run_csv(command):
    out = subprocess.run(command, check=True, capture_output=True, text=True).stdout
    rows = list(csv.reader(io.StringIO(out)))
    return rows[0], np.array([[float(v) for v in r] for r in rows[1:]]).reshape(-1, len(rows[0]))


def value_label(axis, label):
    """An axis value as a legend shows it: its label, with the axis's unit when the label is
    the bare number (grid = 0.01 m; a label such as "300 mm" says its own)."""
    try:
        float(label)
    except (TypeError, ValueError):
        return label
    return f"{label} {axis['unit']}" if axis.get("unit") else label


def case_label(plan, row, skip=()):
    return ", ".join(f"{a['name']} = {value_label(a, row[a['name'] + '_label'])}" for a in plan["axes"]
                     if a["name"] not in skip)


def plot_title(plan, plot):
    """The plot's own title; without one, the study's title for its first plot (the figure the
    study is for) and what the others show for the others (a cost plot must not carry the
    figure's title)."""
    if plot["title"]:
        return plot["title"]
    if plot is plan["plots"][0]:
        return plan["title"]
    what = plot["ylabel"] or ", ".join(plot["y"]) if plot["type"] != "series" else plot["column"]
    return f"{plan['title']}: {what} against {plot['xlabel'] or plot['x']}" if plot["type"] == "metric" \
        else f"{plan['title']}: {what}"


def footnote(plan, fig):
    fig.text(0.01, 0.005, f"study {plan['name']} ({plan['version']})", fontsize=6, color="0.4", va="bottom")


def draw_fit(ax, kind, x, y, offset, color, fit_rows, plot, group):
    f = fits.fit(kind, x, y, offset)
    if f is None:
        return
    xs = np.linspace(min(x), max(x), 200)
    ax.plot(xs, f.predict(xs), "--", color=color, lw=1.0,
            label=f"fit {f.formula()}, R² = {f.r2:.3f}" + (f" ({f.note})" if f.note else ""))
    c = (f.coefficients + [math.nan] * 3)[:3]
    fit_rows.append([plot["name"], group, kind, *c, f.r2, f.points, f.note])


def metric_plot(plan, plot, rows, ax, fit_rows):
    others = [a for a in plan["axes"] if a["name"] != plot["x"]]
    groups = {}
    for r in rows:
        groups.setdefault(tuple(r[o["name"] + "_label"] for o in others), []).append(r)
    colors = itertools.cycle(plt.rcParams["axes.prop_cycle"].by_key()["color"])
    for group, members in groups.items():
        for y_name in plot["y"]:
            pts = sorted((number(r[plot["x"]]), number(r[y_name])) for r in members)
            x, y = np.array([p[0] for p in pts]), np.array([p[1] for p in pts])
            color = next(colors)
            name = ", ".join(f"{o['name']} = {value_label(o, g)}" for o, g in zip(others, group))
            label = (y_name if len(plot["y"]) > 1 else "") + (" " if len(plot["y"]) > 1 and name else "") + name
            ax.plot(x, y, "o-", color=color, label=label or y_name)
            if plot["fit"]:
                draw_fit(ax, plot["fit"], x, y, plot["fit_offset"], color, fit_rows, plot, label or y_name)
    axis = next(a for a in plan["axes"] if a["name"] == plot["x"])
    ax.set_xlabel(plot["xlabel"] or (plot["x"] + (f" [{axis['unit']}]" if axis["unit"] else "")))
    ax.set_ylabel(plot["ylabel"] or ", ".join(plot["y"]))


def profile_plot(plan, plot, rows, ax, fit_rows):
    colors = itertools.cycle(plt.rcParams["axes.prop_cycle"].by_key()["color"])
    x = np.array(plot["positions"], float)
    for r in rows:
        y = np.array([number(r[m]) for m in plot["y"]])
        color = next(colors)
        label = case_label(plan, r)
        ax.plot(x, y, "o-", color=color, label=label)
        if plot["fit"]:
            draw_fit(ax, plot["fit"], x, y, plot["fit_offset"], color, fit_rows, plot, label)
    ax.set_xlabel(plot["xlabel"] or "position")
    ax.set_ylabel(plot["ylabel"] or "metric")


def series_plot(plan, plot, rows, fig):
    axes = fig.subplots(len(plot["probes"]), 1, squeeze=False)[:, 0]
    column = 1 if plot["x"] == "T*" else 0
    for ax, probe in zip(axes, plot["probes"]):
        for ref in plot["references"]:
            if ref["probe"] != probe:
                continue
            _, d = run_csv([plan["program"], "metrics", "--series-file", ref["path"], "--length", str(ref["length"]),
                            "--rate", str(plan["sensor"]["rate"]), "--window", str(plan["sensor"]["window"])])
            ax.plot(d[:, column], d[:, 2], color="0.55", lw=0.9, label=ref["label"])
        for r in rows:
            _, d = run_csv([plan["program"], "metrics", r["run_dir"], "--series", probe, "--column", plot["column"],
                            "--study", plan["study_file"]])
            ax.plot(d[:, column], d[:, 2], lw=1.0, label=case_label(plan, r))
        ax.set_title(probe, fontsize=10)
        ax.set_ylabel(plot["ylabel"] or plot["column"])
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    axes[-1].set_xlabel(plot["xlabel"] or ("T* = t sqrt(g/H)" if plot["x"] == "T*" else "t [s]"))


def draw_plot(plan, plot, rows, fit_rows):
    """One of the study's [[plots]] as a matplotlib figure (its fits appended to fit_rows)."""
    fig = plt.figure(figsize=(7.5, 3.2 * max(1, len(plot["probes"]))) if plot["type"] == "series" else (7.5, 5))
    if plot["type"] == "series":
        series_plot(plan, plot, rows, fig)
    else:
        ax = fig.subplots()
        (metric_plot if plot["type"] == "metric" else profile_plot)(plan, plot, rows, ax, fit_rows)
        ax.grid(alpha=0.3)
        ax.legend(fontsize=7)
    fig.suptitle(plot_title(plan, plot), fontsize=11)
    footnote(plan, fig)
    fig.tight_layout(rect=(0, 0.02, 1, 1))
    return fig


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    plan_path, csv_path = (os.path.abspath(p) for p in sys.argv[1:])
    os.chdir(os.path.dirname(plan_path))
    import json

    with open(plan_path) as f:
        plan = json.load(f)
    with open(csv_path) as f:
        rows = [r for r in csv.DictReader(f) if r["status"] == "completed"]
    fit_rows = []
    for plot in plan["plots"]:
        fig = draw_plot(plan, plot, rows, fit_rows)
        fig.savefig(plot["name"] + ".png", dpi=110)
        plt.close(fig)
        print(f"plot_study: wrote {plot['name']}.png")
    with open(plan["name"] + "_fits.csv", "w", newline="") as f:
        w = csv.writer(f, lineterminator="\n")
        w.writerow(["plot", "curve", "fit", "a", "b", "c", "r2", "points", "note"])
        w.writerows(fit_rows)


if __name__ == "__main__":
    main()

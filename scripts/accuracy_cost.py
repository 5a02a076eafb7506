#!/usr/bin/python3
"""The accuracy-cost map (docs/accuracy-cost.md): the error of every case of the
accuracy-cost studies against its reference, and its cost.

    scripts/accuracy_cost.py [--column DIR] [--hydrostatic DIR] [--martin-moyce DIR]
                             [--gate DIR] [--lobovsky DIR] [--extra PROBLEM RUN_DIR LABEL ...]
                             (each problem's option repeatable: several studies of one problem)
                             [--png media/accuracy_cost.png] [--csv OUT.csv] [--markdown OUT.md]

Each DIR is the output directory of `bsmpm study scenes/studies/accuracy_cost_PROBLEM.toml --dir DIR`
(its CSV names every case's run directory); --extra adds single runs (e.g. the Lobovsky tank
at 4 mm as shipped, run with `bsmpm run`). The errors, each relative, as
docs/accuracy-cost.md defines them:
  column        RMS over the run of the top point's displacement error, over g H^2 / c^2
                (the closed form of docs/method.md §11)
  hydrostatic   the largest error of the three probes' mean pressure over the last 0.1 s,
                against the weight of the column above each: rho g d (1 + rho g d / 2K), the
                weakly compressible column compressed, and rho g d for an incompressible run
  martin_moyce  RMS of (Z - Z_table) / Z_table over Table 2, T = 0.41 ... 2.32
  gate          RMS of the tip's dx against the mean of the five published curves over
                0-0.5 s, over the mean published peak (the peak's own error is listed too)
  lobovsky      mean of the relative errors of the impact time at 30 mm, the first-impact
                peaks at 30 and 80 mm and the means over T* = 3.5-5.5 at 30 and 80 mm,
                against the measured run through the same sensor model
Reference data: tests/data/ (provenance in tests/data/README.md).
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from run_csv import read_columns  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
DATA = os.path.join(ROOT, "tests", "data")
BSMPM = os.environ.get("BSMPM", os.path.join(ROOT, "build", "render", "bsmpm"))


def read_probe(path):
    """{column name: values} of a probe CSV (DIR/<probe>.csv), with units in its header or not."""
    return read_columns(path)


# -- 1. The elastic column: the closed form of docs/method.md §11 (d'Alembert) ------------
COLUMN_H, COLUMN_C, COLUMN_G = 1.0, math.sqrt(1.0e8 / 1000.0), 9.81


def column_static(Y):
    return -(COLUMN_G / COLUMN_C**2) * (COLUMN_H * Y - 0.5 * Y * Y)


def column_extended(Y):
    H = COLUMN_H
    Y = np.fmod(Y, 4 * H)
    Y = np.where(Y < -2 * H, Y + 4 * H, Y)
    Y = np.where(Y > 2 * H, Y - 4 * H, Y)
    sign = np.where(Y < 0, -1.0, 1.0)
    Y = np.abs(Y)
    return sign * column_static(np.where(Y > H, 2 * H - Y, Y))


def column_exact(Y, t):
    ct = COLUMN_C * t
    return column_static(Y) - 0.5 * (column_extended(Y - ct) + column_extended(Y + ct))


def column_error(run):
    p = read_probe(os.path.join(run, "top.csv"))
    Y = p["y"] - p["dy"]
    e = p["dy"] - column_exact(Y, p["t"])
    return {"error": float(np.sqrt(np.mean(e[1:] ** 2)) / (COLUMN_G * COLUMN_H**2 / COLUMN_C**2))}


# -- 2. The hydrostatic tank --------------------------------------------------------------
def hydrostatic_error(run):
    rho, g, K = 1000.0, 9.81, 1.0e6  # scenes/hydrostatic_tank.toml
    # The incompressible model (method.md §12) does not compress the column: its run made
    # pressure solves (docs/output-format.md: 0 without one), and the weight above a probe is rho g d.
    incompressible = summary_of(run).get("pressure_solves", 0) > 0
    worst = 0.0
    for depth_mm in (50, 100, 150):
        p = read_probe(os.path.join(run, "P_depth%d.csv" % depth_mm))
        t_end = p["t"][-1]
        mean = float(np.mean(p["P"][p["t"] >= t_end - 0.1]))
        d = depth_mm * 1e-3
        # rho g d, and for the weakly compressible column its compression to first order in p/K
        exact = rho * g * d * (1.0 if incompressible else 1.0 + rho * g * d / (2.0 * K))
        worst = max(worst, abs(mean - exact) / exact)
    return {"error": worst}


# -- 3. Martin & Moyce --------------------------------------------------------------------
def martin_moyce_table():
    rows = np.loadtxt(os.path.join(DATA, "martin_moyce_1952", "front_n2_2.txt"))
    return rows[rows[:, 0] <= 2.5]


def martin_moyce_error(run):
    a, g = 0.05715, 9.81
    p = read_probe(os.path.join(run, "front.csv"))
    T = p["t"] * math.sqrt(2 * g / a)
    Z = p["front"] / a
    table = martin_moyce_table()
    rel = (np.interp(table[:, 0], T, Z) - table[:, 1]) / table[:, 1]
    return {"error": float(np.sqrt(np.mean(rel**2))), "largest": float(np.max(np.abs(rel)))}


# -- 4. The elastic gate ------------------------------------------------------------------
def gate_reference():
    curves = []
    for name in ("walhorn", "idelsohn", "ryzhakov", "rafiee", "li"):
        c = np.loadtxt(os.path.join(DATA, "walhorn_elastic_gate", "mps_jl_%s.csv" % name), delimiter=",")
        curves.append(c)
    t = np.linspace(0.0, min(c[-1, 0] for c in curves), 1001)
    mean = np.mean([np.interp(t, c[:, 0], c[:, 1]) for c in curves], axis=0)
    peaks = [float(np.max(c[:, 1])) for c in curves]
    return t, mean, float(np.mean(peaks))


def gate_error(run):
    t_ref, mean, mean_peak = gate_reference()
    p = read_probe(os.path.join(run, "tip.csv"))
    t = t_ref[t_ref <= p["t"][-1]]
    dx = np.interp(t, p["t"], p["dx"])
    rms = float(np.sqrt(np.mean((dx - mean[: len(t)]) ** 2))) / mean_peak
    return {"error": rms, "peak_error": (float(np.max(p["dx"])) - mean_peak) / mean_peak}


# -- 5. The Lobovsky tank -----------------------------------------------------------------
LOBOVSKY_METRICS = ("impact_z30_star", "peak_z30", "mean_z30", "peak_z80", "mean_z80")


def sensor_series(args):
    out = subprocess.run([BSMPM, "metrics"] + args, check=True, capture_output=True, text=True).stdout
    rows = [l.split(",") for l in out.splitlines() if l and not l[0].isalpha() and not l.startswith("#")]
    a = np.array([[float(x) for x in r] for r in rows])
    return a[:, 1], a[:, 2]  # T*, value


def lobovsky_values(Ts, P30, Ts80, P80):
    def window(T, P, lo, hi):
        return P[(T >= lo) & (T <= hi)]
    impact = float(Ts[np.argmax(P30 > 0.05)])
    return {
        "impact_z30_star": impact,
        "peak_z30": float(np.max(window(Ts, P30, 0.0, 3.5))),
        "mean_z30": float(np.mean(window(Ts, P30, 3.5, 5.5))),
        "peak_z80": float(np.max(window(Ts80, P80, 2.3, 3.3))),
        "mean_z80": float(np.mean(window(Ts80, P80, 3.5, 5.5))),
    }


_LOBOVSKY_MEASURED = None


def lobovsky_measured():
    global _LOBOVSKY_MEASURED
    if _LOBOVSKY_MEASURED is None:
        d = os.path.join(DATA, "lobovsky2014_h300")
        T30, P30 = sensor_series(["--series-file", os.path.join(d, "sensor3_z30mm_run.dat"), "--length", "0.3"])
        T80, P80 = sensor_series(["--series-file", os.path.join(d, "sensor4_z80mm_run.dat"), "--length", "0.3"])
        _LOBOVSKY_MEASURED = lobovsky_values(T30, P30, T80, P80)
    return _LOBOVSKY_MEASURED


def lobovsky_error(run):
    T30, P30 = sensor_series([run, "--series", "P_z30"])
    T80, P80 = sensor_series([run, "--series", "P_z80"])
    sim, exp = lobovsky_values(T30, P30, T80, P80), lobovsky_measured()
    rel = {k: (sim[k] - exp[k]) / exp[k] for k in LOBOVSKY_METRICS}
    out = {"error": float(np.mean([abs(v) for v in rel.values()]))}
    out.update({k + "_error": v for k, v in rel.items()})
    return out


PROBLEMS = {
    "column": ("Elastic column (closed form)", column_error, "top displacement, RMS"),
    "hydrostatic": ("Hydrostatic tank", hydrostatic_error, "probe pressure, largest"),
    "martin_moyce": ("Martin & Moyce", martin_moyce_error, "surge front, RMS"),
    "gate": ("Elastic gate", gate_error, "tip dx, RMS vs published mean"),
    "lobovsky": ("Lobovsky tank, H = 300 mm", lobovsky_error, "mean of 5 relative errors"),
}


def grid_label(problem, h):
    """The grid as the problem's own scale reads it: H/N for the column, a/N for Martin &
    Moyce (a = 57.15 mm), millimetres for the rest."""
    if problem == "column":
        return "h = H/%d" % round(COLUMN_H / h)
    if problem == "martin_moyce":
        return "h = a/%d" % round(0.05715 / h)
    return "h = %g mm" % (h * 1e3)


def study_cases(problem, directory):
    csvs = [f for f in os.listdir(directory) if f.endswith(".csv") and f.startswith("accuracy_cost_")]
    if not csvs:
        sys.exit("accuracy_cost.py: no accuracy_cost_*.csv in %s" % directory)
    with open(os.path.join(directory, csvs[0])) as f:
        rows = list(csv.DictReader(f))
    cases, failed = [], []
    for r in rows:
        parts = []
        for axis in ("grid", "order", "ppc", "update", "setting"):
            if axis + "_label" not in r:
                continue
            value = r[axis + "_label"]
            if axis == "grid":
                parts.append(grid_label(problem, float(r["grid"])))
            elif axis == "order":
                parts.append("order " + value)
            elif axis == "ppc":
                parts.append("%sx%s" % (value, value))
            else:
                parts.append(value)
        case = {"label": ", ".join(parts), "run": os.path.join(directory, r["run_dir"]), "row": r}
        if r["status"] == "completed":
            cases.append(case)
        elif r["status"] == "failed":
            case["reason"] = failure_reason(case["run"])
            failed.append(case)
    return cases, failed


def failure_reason(run):
    """The program's error line from a failed case's log, shortened to its cause."""
    try:
        with open(os.path.join(run, "run.log")) as f:
            for line in f:
                if "error:" in line:
                    text = line.split("error:", 1)[1].strip()
                    return text.split(":")[0] if "numerical instability" in text else text[:80]
    except OSError:
        pass
    return "failed"


def summary_of(run):
    with open(os.path.join(run, "summary.json")) as f:
        return json.load(f)


def column_convergence(cases):
    """The column's error against h for each spline order (2x2 per cell, pure FLIP), and the
    order of convergence between successive grids, log2(e(2h) / e(h))."""
    md = ["### Elastic column: convergence by spline order (2x2 per cell, pure FLIP)\n",
          "| order | " + " | ".join("H/%d" % n for n in (8, 16, 32, 64)) + " | orders |", "|---|---|---|---|---|---|"]
    for order in ("1", "2", "3"):
        errors = {}
        for c in cases:
            r = c["row"]
            if r.get("order_label") == order and r.get("ppc_label") == "2" and r.get("update_label") == "FLIP":
                errors[round(1 / float(r["grid"]))] = c["error"]
        cells = [errors.get(n) for n in (8, 16, 32, 64)]
        rates = ["%.2f" % math.log2(a / b) for a, b in zip(cells, cells[1:]) if a and b]
        md.append("| %s | %s | %s |" % (order, " | ".join("%.3g %%" % (100 * e) if e else "-" for e in cells),
                                        ", ".join(rates)))
    return md + [""]


def pareto(points):
    """Indices of the points no other point beats in both cost and error."""
    order = sorted(range(len(points)), key=lambda i: (points[i][0], points[i][1]))
    front, best = [], float("inf")
    for i in order:
        if points[i][1] < best:
            front.append(i)
            best = points[i][1]
    return front


def cases_from_csv(path):
    """{problem: cases} from a CSV written with --csv: setting, error and wall time per case."""
    results = {}
    with open(path) as f:
        for row in csv.DictReader(f):
            results.setdefault(row["problem"], []).append(
                {"label": row["setting"], "error": float(row["error"]), "wall": float(row["wall_seconds"])})
    return results


def label_box(annotation, renderer):
    """The window extent of an annotation's text alone (its leader line left out)."""
    import matplotlib.text
    annotation.update_positions(renderer)
    return matplotlib.text.Text.get_window_extent(annotation, renderer)


def place_labels(fig, ax, points, labels):
    """Labels beside their points, each moved up or down in steps of its own height (with a
    leader line) until it overlaps no label placed before it."""
    renderer = fig.canvas.get_renderer()
    placed, annotations = [], []
    for (x, y), text in sorted(zip(points, labels)):
        a = ax.annotate(text, (x, y), fontsize=6, xytext=(3, 2), textcoords="offset points",
                        arrowprops=dict(arrowstyle="-", lw=0.3, color="0.6", shrinkA=0, shrinkB=2))
        for step in range(1, 200):
            box = label_box(a, renderer)
            if not any(box.overlaps(b) for b in placed):
                break
            shift = 7 * ((step + 1) // 2) * (1 if step % 2 else -1)  # 7, -7, 14, -14, ... points
            a.xyann = (3, 2 + shift)
        placed.append(label_box(a, renderer))
        annotations.append(a)
    return annotations


def draw_map(results, footer=""):
    """The accuracy-cost map: a panel per problem (error against wall time, the Pareto front
    labelled), and a last panel that says how to read them and the cheapest settings."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    n = len(results)
    cols = min(n + 1, 3)
    rows = (n + 1 + cols - 1) // cols
    fig, axes = plt.subplots(rows, cols, figsize=(6.2 * cols, 5.0 * rows), squeeze=False)
    panels = []
    for ax, (problem, cases) in zip(axes.flat, results.items()):
        title, _, what = PROBLEMS[problem]
        x = [c["wall"] for c in cases]
        y = [max(c["error"], 1e-9) for c in cases]  # log axis: an exact case drawn at 1e-9
        # The incompressible model's cases (method.md §12) apart, so the two water models read side by side.
        ic = [i for i, c in enumerate(cases) if "incompressible" in c["label"]]
        wc = [i for i in range(len(cases)) if i not in ic]
        ax.scatter([x[i] for i in wc], [y[i] for i in wc], s=14, color="tab:blue", zorder=3, label="a setting")
        if ic:
            ax.scatter([x[i] for i in ic], [y[i] for i in ic], s=30, marker="^", color="tab:green", zorder=3,
                       label="incompressible water")
        # A Pareto front per water model, each labelled: one front over both would hide the
        # weakly compressible settings behind the incompressible ones.
        front = []
        for group, style, name in ((wc, "-", "Pareto front (labelled)"),
                                   (ic, "--", "incompressible water's front")):
            if not group:
                continue
            g_front = [group[k] for k in pareto([(x[i], y[i]) for i in group])]
            ax.plot([x[i] for i in g_front], [y[i] for i in g_front], style, color="tab:red", lw=1.2, zorder=2,
                    label=name)
            front += g_front
        for target in (0.10, 0.05, 0.02):
            ax.axhline(target, color="0.8", lw=0.6, zorder=1)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("wall time per run [s], 1 thread, 2-core machine")
        ax.set_ylabel("relative error (%s)" % what)
        ax.set_title(title, fontsize=10)
        ax.legend(fontsize=7, loc="lower left")
        ax.grid(True, which="both", alpha=0.25)
        panels.append((ax, [(x[i], y[i]) for i in front], [cases[i]["label"] for i in front]))
    key = list(axes.flat)[n]
    key.axis("off")
    lines = ["How to read the panels",
             "Each point is one setting (grid, spline order, particles per cell,",
             "velocity update, time step) against that problem's reference.",
             "Red: the Pareto front, no setting both cheaper and more accurate;",
             "its settings are labelled. Grey lines: 10, 5 and 2 % error.",
             "Green triangles: the incompressible water model (its scenes",
             "as shipped, method.md §12), its own front dashed; blue: weakly",
             "compressible.",
             "", "The cheapest setting within 5 %:"]
    for problem, cases in results.items():
        ok = [c for c in cases if c["error"] <= 0.05]
        best = min(ok, key=lambda c: c["wall"]) if ok else None
        lines.append("  %s: %s" % (PROBLEMS[problem][0],
                                   "%s, %.3g s" % (best["label"], best["wall"]) if best else "none"))
    key.text(0.0, 1.0, "\n".join(lines), va="top", ha="left", fontsize=9, family="DejaVu Sans",
             transform=key.transAxes)
    for ax in list(axes.flat)[n + 1:]:
        ax.axis("off")
    fig.suptitle("What accuracy costs in time (docs/accuracy-cost.md)")
    if footer:
        fig.text(0.01, 0.005, footer, fontsize=7, color="0.4", va="bottom")
    fig.tight_layout(rect=(0, 0.02, 1, 1))
    fig.canvas.draw()  # the final layout: labels are placed in its coordinates
    for ax, points, labels in panels:
        place_labels(fig, ax, points, labels)
    return fig


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    for name in PROBLEMS:
        ap.add_argument("--" + name.replace("_", "-"), dest=name, action="append", default=[],
                        help="study output directory (repeatable: e.g. the incompressible model's study too)")
    ap.add_argument("--extra", action="append", nargs=3, default=[], metavar=("PROBLEM", "RUN_DIR", "LABEL"),
                    help="a single run of PROBLEM (e.g. made with bsmpm run) as one more case")
    ap.add_argument("--from-csv", metavar="CSV",
                    help="draw --png from a CSV this script wrote (media/accuracy_cost.csv), without the runs")
    ap.add_argument("--png")
    ap.add_argument("--csv")
    ap.add_argument("--markdown")
    args = ap.parse_args()

    if args.from_csv:
        results = cases_from_csv(args.from_csv)
        if args.png:
            draw_map(results, footer="data: " + os.path.relpath(args.from_csv, ROOT)).savefig(args.png, dpi=110)
        return
    results, failures = {}, {}
    for problem, (title, error_of, _) in PROBLEMS.items():
        cases, failures[problem] = [], []
        for directory in getattr(args, problem):
            done, failed = study_cases(problem, directory)
            cases += done
            failures[problem] += failed
        for p, run, label in args.extra:
            if p == problem:
                cases.append({"label": label, "run": run, "row": {}})
        for c in cases:
            s = summary_of(c["run"])
            c.update(error_of(c["run"]))
            c["wall"] = float(s["wall_seconds"])
            c["steps"] = int(s["steps"])
            c["particles"] = int(s["particles"])
            c["threads"] = int(s.get("threads", 1))
            c["memory_mb"] = float(s.get("peak_memory_mb", float("nan")))
            c["particle_steps"] = c["steps"] * c["particles"]
        if cases:
            results[problem] = cases

    if args.csv:
        with open(args.csv, "w", newline="") as f:
            w = csv.writer(f)
            w.writerow(["problem", "setting", "error", "wall_seconds", "threads", "steps", "particles",
                        "particle_steps", "peak_memory_mb"])
            for problem, cases in results.items():
                for c in cases:
                    w.writerow([problem, c["label"], "%.4g" % c["error"], "%.3f" % c["wall"], c["threads"],
                                c["steps"], c["particles"], c["particle_steps"], "%.1f" % c["memory_mb"]])

    md = []
    for problem, cases in results.items():
        title, _, what = PROBLEMS[problem]
        md.append("### %s (error: %s)\n" % (title, what))
        md.append("| setting | error | wall time [s] | particle-steps | peak memory [MB] |")
        md.append("|---|---|---|---|---|")
        front = set(pareto([(c["wall"], c["error"]) for c in cases]))
        # A long table (the column's 108 cases) lists its Pareto front and the scene as shipped
        # (order 2, 2x2, pure FLIP); every case is in the CSV.
        long_table = len(cases) > 40
        if long_table:
            md.insert(-2, "The Pareto front and the scene as shipped (order 2, 2x2, FLIP); all %d cases: "
                          "`media/accuracy_cost.csv`.\n" % len(cases))
        for i, c in sorted(enumerate(cases), key=lambda ic: ic[1]["wall"]):
            if long_table and i not in front and not (c["label"] + ",").endswith("order 2, 2x2, FLIP,"):
                continue
            md.append("| %s%s | %.3g %% | %.2f | %.3g | %.0f |" % (c["label"], " (Pareto)" if i in front else "",
                                                                   100 * c["error"], c["wall"], c["particle_steps"],
                                                                   c["memory_mb"]))
        for c in failures.get(problem, []):
            md.append("| %s | failed: %s | | | |" % (c["label"], c["reason"]))
        md.append("")
        parts = [k for k in cases[0] if k.endswith("_error")]
        if parts:  # the signed errors the headline error is made of
            md.append("| setting | " + " | ".join(k[:-len("_error")] for k in parts) + " |")
            md.append("|---" * (len(parts) + 1) + "|")
            for c in sorted(cases, key=lambda c: c["wall"]):
                md.append("| %s | " % c["label"] + " | ".join("%+.1f %%" % (100 * c[k]) for k in parts) + " |")
            md.append("")
        for target in (0.10, 0.05, 0.02, 0.01, 0.005):
            ok = [c for c in cases if c["error"] <= target]
            if ok:
                best = min(ok, key=lambda c: c["wall"])
                md.append("- %g %%: %s, %.3g %% in %.2f s" % (100 * target, best["label"], 100 * best["error"],
                                                             best["wall"]))
            else:
                md.append("- %g %%: none of these settings (the best: %.3g %%)" %
                          (100 * target, 100 * min(c["error"] for c in cases)))
        md.append("")
    if "column" in results:
        md += column_convergence(results["column"])
    text = "\n".join(md)
    if args.markdown:
        with open(args.markdown, "w") as f:
            f.write(text + "\n")
    else:
        print(text)

    if args.png:
        draw_map(results, footer="data: the accuracy-cost studies' runs").savefig(args.png, dpi=110)


if __name__ == "__main__":
    main()

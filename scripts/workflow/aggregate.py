#!/usr/bin/python3
"""Writes a study's CSV: a row per case, from OUT/plan.json and each case's metrics.json
and summary.json (docs/studies.md). Run by the Snakefile's aggregate rule in OUT.

usage: aggregate.py PLAN.json OUT.csv [--partial]

A case whose metrics.json was made under other metric definitions (the study's
[[metrics]] changed) is extracted again from its run with `bsmpm metrics`. --partial
writes a row for every case even when some did not finish: their status is "failed"
(a `failed` marker) or "missing", their metrics empty.
"""
import argparse
import csv
import json
import os
import subprocess
import sys

COSTS = ["wall_seconds", "predicted_wall_seconds", "steps", "particles", "peak_memory_mb", "particle_steps_per_second", "threads"]


def read_json(path):
    with open(path) as f:
        return json.load(f)


def case_metrics(plan, key):
    """The case's metrics, extracted again when its definitions are out of date."""
    path = os.path.join("cases", key, "metrics.json")
    metrics = read_json(path)
    if metrics.get("metrics_hash") != plan["metrics_hash"]:
        out = subprocess.run([plan["program"], "metrics", os.path.join("cases", key), "--study", plan["study_file"],
                              "--json"], check=True, capture_output=True, text=True).stdout
        with open(path + ".tmp", "w") as f:
            f.write(out)
        os.replace(path + ".tmp", path)
        metrics = json.loads(out)
    return metrics


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("plan")
    ap.add_argument("output")
    ap.add_argument("--partial", action="store_true")
    args = ap.parse_args()
    os.chdir(os.path.dirname(os.path.abspath(args.plan)))
    plan = read_json(os.path.basename(args.plan))
    axes = plan["axes"]
    metric_columns = [c for m in plan["metrics"] for c in m["columns"]]
    costs = [c for c in COSTS if c not in metric_columns]
    header = ["case"] + [h for a in axes for h in (a["name"], a["name"] + "_label")] + metric_columns + costs
    header += ["status", "run_dir"]
    rows = []
    for case in plan["cases"]:
        key = case["key"]
        row = {"case": key, "run_dir": os.path.join("cases", key)}
        for a, i in zip(axes, case["axes"]):
            v = a["values"][i]
            row[a["name"]] = "" if v["value"] is None else v["value"]
            row[a["name"] + "_label"] = v["label"]
        if os.path.exists(os.path.join("cases", key, "metrics.json")):
            summary = read_json(os.path.join("cases", key, "summary.json"))
            # predicted_wall_seconds: null without a calibration, absent before it existed
            row.update({c: ("" if summary.get(c) is None else summary[c]) for c in costs})
            metrics = case_metrics(plan, key)
            row.update({c: ("" if metrics.get(c) is None else metrics[c]) for c in metric_columns})
            row["status"] = summary["status"]
        elif args.partial:
            row["status"] = "failed" if os.path.exists(os.path.join("cases", key, "failed")) else "missing"
        else:
            sys.exit(f"aggregate: case {key} has no metrics.json")
        rows.append(row)
    tmp = args.output + ".tmp"
    with open(tmp, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=header, restval="", lineterminator="\n")
        w.writeheader()
        w.writerows(rows)
    os.replace(tmp, args.output)
    print(f"aggregate: wrote {args.output} ({len(rows)} cases)")


if __name__ == "__main__":
    main()

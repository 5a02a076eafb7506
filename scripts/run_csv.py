"""Reading a run's CSV files (DIR/<probe>.csv, DIR/conservation.csv; docs/output-format.md):
'#' comment lines (the first describes the probe; a last one says where a run that did not
complete stopped), a header row, then one row of numbers per sample. Each header cell is a
column's name and its unit in brackets, "t [s]", "P [Pa]", a number without unit bare ("T*");
files written before the units had the names alone ("t,T*,P,P*") and read the same.
"""
import csv

import numpy as np


def column_name(cell):
    """'P [Pa]' -> 'P'; 'P*' -> 'P*'."""
    return cell.split(" [", 1)[0].strip()


def column_unit(cell):
    """'P [Pa]' -> 'Pa'; 'P*' -> '1' (a number without unit); None for a file before units
    (a name alone is then ambiguous: read_run_csv tells the two apart)."""
    if " [" in cell and cell.rstrip().endswith("]"):
        return cell.rstrip()[cell.index(" [") + 2:-1]
    return "1"


def read_run_csv(path):
    """(names, units, rows): the column names, their units (None for every column of a file
    written before units) and the rows as a 2-D float array."""
    with open(path) as f:
        lines = [line for line in f if line.strip() and not line.startswith("#")]
    reader = csv.reader(lines)
    header = next(reader)
    names = [column_name(c) for c in header]
    has_units = any(" [" in c for c in header)
    units = [column_unit(c) for c in header] if has_units else [None] * len(header)
    rows = np.array([[float(v) for v in row] for row in reader], dtype=float).reshape(-1, len(header))
    return names, units, rows


def read_columns(path):
    """{name: column} of a run's CSV file."""
    names, _, rows = read_run_csv(path)
    return {name: rows[:, k] for k, name in enumerate(names)}

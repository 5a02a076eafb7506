"""The plotting scripts (scripts/plot_probes.py, plot_gate.py, accuracy_cost.py,
workflow/plot_study.py) on small runs made here: every figure has its title, every curve its
legend entry, every axis its quantity and unit, on run files with units in their CSV headers
and on files written before them. Run by ctest (tests/CMakeLists.txt) with Debian's python3."""
import csv
import os
import sys
import tempfile
import unittest

import matplotlib

matplotlib.use("Agg")
import h5py  # noqa: E402
import numpy as np  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "scripts"))
sys.path.insert(0, os.path.join(ROOT, "scripts", "workflow"))
import accuracy_cost  # noqa: E402
import plot_gate  # noqa: E402
import plot_probes  # noqa: E402
import plot_study  # noqa: E402
from run_csv import read_run_csv  # noqa: E402


def write_probe_csv(path, header, rows, stopped=False):
    with open(path, "w") as f:
        f.write("# a probe\n" + ",".join(header) + "\n")
        for r in rows:
            f.write(",".join("%.9g" % v for v in r) + "\n")
        if stopped:
            f.write("# the run stopped here, at t = 0.5 s (step 5): interrupted\n")


def write_run_h5(run, title, cell, revision="abc123def456"):
    with h5py.File(os.path.join(run, "run.h5"), "w") as f:
        f.attrs["title"] = title
        f.attrs["program_version"] = "0.1.0"
        f.attrs["git_revision"] = revision
        f.create_group("grid").attrs["cell_size"] = [cell, cell]
        f.create_group("reference").attrs["length"] = 0.292


def make_lobovsky_run(run, units):
    os.makedirs(run)
    t = np.linspace(0.0, 1.0, 200)
    for name in ("P_z30", "P_z80"):
        header = ["t [s]", "T*", "P [Pa]", "P*"] if units else ["t", "T*", "P", "P*"]
        write_probe_csv(os.path.join(run, name + ".csv"), header,
                        np.column_stack([t, t * 5.7, 3000 * np.sin(t) ** 2, np.sin(t) ** 2]), stopped=units)


def legend_texts(ax):
    legend = ax.get_legend()
    return [t.get_text() for t in legend.get_texts()] if legend else []


class RunCsvTest(unittest.TestCase):
    def test_old_and_new_headers_read_the_same(self):
        with tempfile.TemporaryDirectory() as d:
            rows = [[0.0, 0.0, 1.5, 0.1], [0.1, 0.57, 2.5, 0.2]]
            write_probe_csv(os.path.join(d, "new.csv"), ["t [s]", "T*", "P [Pa]", "P*"], rows, stopped=True)
            write_probe_csv(os.path.join(d, "old.csv"), ["t", "T*", "P", "P*"], rows)
            new, old = read_run_csv(os.path.join(d, "new.csv")), read_run_csv(os.path.join(d, "old.csv"))
            self.assertEqual(new[0], ["t", "T*", "P", "P*"])
            self.assertEqual(new[0], old[0])
            self.assertEqual(new[1], ["s", "1", "Pa", "1"])
            self.assertEqual(old[1], [None] * 4)
            np.testing.assert_array_equal(new[2], old[2])


class PlotProbesTest(unittest.TestCase):
    def test_title_names_the_run_and_its_grid_panels_their_probe(self):
        for units in (True, False):
            with tempfile.TemporaryDirectory() as d:
                run = os.path.join(d, "demo")
                make_lobovsky_run(run, units)
                write_run_h5(run, "Lobovsky dam break, H = 300 mm", 0.005)
                fig = plot_probes.draw([run], ["bsmpm"])
                self.assertEqual(fig._suptitle.get_text(), "Lobovsky dam break, H = 300 mm, h = 5 mm")
                axes = fig.get_axes()
                self.assertEqual([a.get_title() for a in axes],
                                 ["P_z30: 30 mm above the floor", "P_z80: 80 mm above the floor"])
                for ax in axes:
                    self.assertIn("P*", ax.get_ylabel())
                    self.assertEqual(legend_texts(ax), ["bsmpm"])
                self.assertEqual(axes[-1].get_xlabel(), "T* = t sqrt(g/H)")
                self.assertIn("bsmpm 0.1.0 (abc123def456)", [t.get_text() for t in fig.texts])

    def test_given_title_and_runs_of_two_grids(self):
        with tempfile.TemporaryDirectory() as d:
            a, b = os.path.join(d, "a"), os.path.join(d, "b")
            make_lobovsky_run(a, True)
            make_lobovsky_run(b, False)
            write_run_h5(a, "Lobovsky", 0.004)
            write_run_h5(b, "Lobovsky", 0.008)
            self.assertEqual(plot_probes.draw([a, b], ["4 mm", "8 mm"])._suptitle.get_text(),
                             "Lobovsky, h = 4 mm and 8 mm")
            fig = plot_probes.draw([a, b], ["4 mm", "8 mm"], title="mine", window=0.5)
            self.assertEqual(fig._suptitle.get_text(), "mine")
            self.assertEqual(legend_texts(fig.get_axes()[0]), ["4 mm, every step", "4 mm, moving average 0.5 T*",
                                                              "8 mm, every step", "8 mm, moving average 0.5 T*"])


class PlotGateTest(unittest.TestCase):
    def test_each_published_method_has_its_own_style_and_legend_entry(self):
        with tempfile.TemporaryDirectory() as d:
            run = os.path.join(d, "gate")
            os.makedirs(run)
            t = np.linspace(0.0, 0.5, 100)
            write_probe_csv(os.path.join(run, "tip.csv"), ["t [s]", "dx [m]", "dy [m]", "x [m]", "y [m]"],
                            np.column_stack([t, 0.04 * np.sin(6 * t), 0 * t, 0.292 + 0 * t, 0.08 + 0 * t]))
            for h in (20, 40, 60):
                write_probe_csv(os.path.join(run, "P_h%d.csv" % h), ["t", "T*", "P", "P*"],
                                np.column_stack([t, 5.8 * t, 100 * t, 0.1 * t]))
            write_run_h5(run, "Elastic gate", 0.002)
            fig = plot_gate.draw([run], ["h = 2 mm"], 0.005)
            top, bottom = fig.get_axes()
            self.assertIn("Elastic gate", fig._suptitle.get_text())
            self.assertIn("Figs. 11, 12 and 14", fig._suptitle.get_text())
            published = [label for label, _ in plot_gate.PUBLISHED.values()]
            self.assertEqual(legend_texts(top), published + ["bsmpm, h = 2 mm"])
            self.assertEqual(len({str(style) for _, style in plot_gate.PUBLISHED.values()}), 5)  # one each
            self.assertIn("[mm]", top.get_ylabel())
            self.assertEqual(top.get_xlabel(), "t [s]")
            self.assertTrue(top.get_title())
            self.assertIn("h = 2 mm", bottom.get_title())
            self.assertIn("5 ms", bottom.get_title())
            self.assertEqual(bottom.get_ylabel(), "P* = P / (rho g H), H = 292 mm")
            self.assertEqual(legend_texts(bottom), ["P_h20: 20 mm above the floor", "P_h40: 40 mm above the floor",
                                                    "P_h60: 60 mm above the floor"])


class PlotStudyTest(unittest.TestCase):
    def plan(self):
        return {"name": "fig8", "title": "Fig. 8: first-impact peak at z = 30 mm against H", "version": "bsmpm 0.1.0",
                "axes": [{"name": "H", "unit": "m"}, {"name": "grid", "unit": "m"}],
                "plots": [{"name": "peak", "type": "metric", "x": "H", "y": ["peak"], "fit": "", "fit_offset": 0,
                           "title": "", "xlabel": "H [m]", "ylabel": "first-impact peak P*", "probes": []},
                          {"name": "cost", "type": "metric", "x": "H", "y": ["wall_seconds"], "fit": "",
                           "fit_offset": 0, "title": "", "xlabel": "H [m]", "ylabel": "wall time per run [s]",
                           "probes": []}]}

    def rows(self):
        rows = []
        for g, g_label in ((0.01, "0.01"), (0.008, "0.008")):
            for H, H_label in ((0.3, "300 mm"), (0.6, "600 mm")):
                rows.append({"H": str(H), "H_label": H_label, "grid": str(g), "grid_label": g_label,
                             "peak": str(H * 3), "wall_seconds": str(H * 100 / g)})
        return rows

    def test_titles_say_what_each_plot_shows_and_legends_give_units(self):
        plan = self.plan()
        peak = plot_study.draw_plot(plan, plan["plots"][0], self.rows(), [])
        cost = plot_study.draw_plot(plan, plan["plots"][1], self.rows(), [])
        self.assertEqual(peak._suptitle.get_text(), plan["title"])
        self.assertEqual(cost._suptitle.get_text(), plan["title"] + ": wall time per run [s] against H [m]")
        self.assertEqual(legend_texts(peak.get_axes()[0]), ["grid = 0.01 m", "grid = 0.008 m"])
        self.assertEqual(cost.get_axes()[0].get_ylabel(), "wall time per run [s]")
        self.assertEqual(peak.get_axes()[0].get_xlabel(), "H [m]")

    def test_a_plot_with_its_own_title_keeps_it(self):
        plan = self.plan()
        plan["plots"][1]["title"] = "Cost of the Fig. 8 study"
        fig = plot_study.draw_plot(plan, plan["plots"][1], self.rows(), [])
        self.assertEqual(fig._suptitle.get_text(), "Cost of the Fig. 8 study")

    def test_labels_that_say_their_unit_are_left_alone(self):
        self.assertEqual(plot_study.value_label({"unit": "m"}, "300 mm"), "300 mm")
        self.assertEqual(plot_study.value_label({"unit": "m"}, "0.004"), "0.004 m")
        self.assertEqual(plot_study.value_label({"unit": ""}, "2"), "2")


class AccuracyCostTest(unittest.TestCase):
    def test_map_from_the_committed_csv_labels_without_overlap_and_a_key_panel(self):
        results = accuracy_cost.cases_from_csv(os.path.join(ROOT, "media", "accuracy_cost.csv"))
        fig = accuracy_cost.draw_map(results, footer="data: media/accuracy_cost.csv")
        axes = fig.get_axes()
        self.assertEqual(len(axes), 6)
        self.assertIn("What accuracy costs", fig._suptitle.get_text())
        renderer = fig.canvas.get_renderer()
        # The problems the incompressible model was measured on draw its cases and front apart.
        with_incompressible = [any("incompressible" in c["label"] for c in cases) for cases in results.values()]
        self.assertEqual(sum(with_incompressible), 3)  # hydrostatic tank, Martin & Moyce, Lobovsky
        for ax, incompressible in zip(axes[:5], with_incompressible):
            self.assertTrue(ax.get_title())
            self.assertIn("[s]", ax.get_xlabel())
            self.assertIn("relative error", ax.get_ylabel())
            self.assertEqual(legend_texts(ax),
                             ["a setting", "incompressible water", "Pareto front (labelled)",
                              "incompressible water's front"] if incompressible
                             else ["a setting", "Pareto front (labelled)"])
            boxes = [accuracy_cost.label_box(t, renderer) for t in ax.texts]
            self.assertGreater(len(boxes), 1)
            for i in range(len(boxes)):
                for j in range(i):
                    self.assertFalse(boxes[i].overlaps(boxes[j]), (ax.get_title(), ax.texts[i].get_text(),
                                                                   ax.texts[j].get_text()))
        key = " ".join(t.get_text() for t in axes[5].texts)
        self.assertIn("How to read the panels", key)
        self.assertIn("The cheapest setting within 5 %", key)


if __name__ == "__main__":
    unittest.main()

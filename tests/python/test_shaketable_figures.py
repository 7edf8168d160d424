"""CTest `shaketable_figures_python`: the shake-table figures from small hand-made inputs whose
answer is known (no simulation; seconds).

- Fragility: a model.csv of four motions on a ten-PGA grid. Three overturn the rock: P rises,
  reaches 1 at three PGAs in a row, and the stop rule infers the rest (p_overturn 1, simulated 0);
  the fourth never overturns (P 0 throughout, simulated). Where the three are inferred, the model
  point is 3/4 by hand (it fell to 0 when inferred cells were left out, only the fourth motion
  being averaged there), while the fit still reads simulated cells only. The figure's title names
  the physics it is given, and its legend says what a lab test's 0 and 1 mean.
- Calibration: a calibration document and likelihood table written here (two variants over five
  headings, three motions, reliability tables) drawn in every format: the file exists, the title
  carries the scan and the physics, each panel draws what the inputs hold.

    /usr/bin/python3 -m pytest tests/python/test_shaketable_figures.py
"""
import json
import os

import pytest

np = pytest.importorskip("numpy")
pytest.importorskip("matplotlib")
pytest.importorskip("scipy")
import figure_checks  # noqa: E402  (measurements of a rendered figure)
from rigidpy import shaketable as sf  # noqa: E402

SCALES = [0.1, 0.2, 0.3, 0.5, 0.7, 1.0, 1.5, 2.0, 2.5, 3.5]
# per motion: P at each PGA, and the PGA index from which the stop rule inferred the rest
OVERTURNING = [0.0, 0.0, 0.25, 0.5, 1.0, 1.0, 1.0]  # three scales at P = 1, then inferred
NEVER = [0.0] * len(SCALES)


def model_rows():
    rows = []
    for r in range(4):
        for s, scale in enumerate(SCALES):
            if r < 3:
                inferred = s >= len(OVERTURNING)
                p = 1.0 if inferred else OVERTURNING[s]
                simulated = 0 if inferred else 1
            else:
                p, simulated = NEVER[s], 1
            rows.append({"record_index": str(r), "scale_g": repr(scale), "p_overturn": repr(p), "cells": "4",
                         "simulated": str(simulated)})
    return rows


def test_inferred_cells_count_as_overturned_in_the_points_not_in_the_fit():
    fit_cells, p, known = sf.model_cells_on_grid(4, np.array(SCALES), model_rows())
    points = sf.model_points(p, known, np.arange(4))
    inferred = np.arange(len(OVERTURNING), len(SCALES))
    assert np.allclose(points[inferred], 0.75), "3 of 4 motions overturned above the stop rule: %s" % points
    assert np.all(points[inferred] > 0), "no model point falls to 0 where the inferred cells say overturned"
    # below: the hand mean of the three rising motions and the one that stands
    assert np.allclose(points[:len(OVERTURNING)], [3 * v / 4 for v in OVERTURNING])
    # the fit: inferred cells left out (weight 0), simulated ones at their P
    assert np.all(fit_cells.n[:3, inferred] == 0) and np.all(fit_cells.n[3, :] == 4)
    assert np.allclose(fit_cells.k[0, :len(OVERTURNING)], 4 * np.array(OVERTURNING))


def fragility_inputs():
    motions = np.arange(4)
    lab = sf.lab_cells([{"record": "m0", "measured_pga_g": 0.3, "overturned": 1}, {"record": "m1", "measured_pga_g": 0.2, "overturned": 0},
                        {"record": "m3", "measured_pga_g": 1.0, "overturned": 0}], {"m%d" % i: i for i in range(4)})
    _, p, known = sf.model_cells_on_grid(4, np.array(SCALES), model_rows())
    rows = [dict(label="all motions", motions=motions, tests=3, overturned=1, lab={}, model={})]
    return rows, lab, p, known


def test_fragility_figure_title_legend_and_points():
    import matplotlib.pyplot as plt
    rows, lab, p, known = fragility_inputs()
    physics = "calibrated physics: flat_5mm penalty K=5e+05 D=4 mu=0.90 (sp1.calibration.json, 3 members)"
    fig = sf.fragility_figure(rows, lab, p, known, np.array(SCALES), physics)
    try:
        assert physics in fig._suptitle.get_text().replace("\n", " "), "the title carries the physics (wrapped to the page)"
        legend = [t.get_text() for lg in fig.legends for t in lg.get_texts()]
        assert "lab test: overturned (P = 1)" in legend and "lab test: stood (P = 0)" in legend, legend
        assert not any("1 overturned, 0 stood" in t for t in legend), "no legend text that reads like counts"
        ax = fig.axes[0]
        points = [l for l in ax.get_lines() if l.get_marker() == "o"][0]
        y = np.asarray(points.get_ydata(), float)
        assert np.allclose(y[len(OVERTURNING):], 0.75), "the drawn model points above the stop rule: %s" % y
        found = figure_checks.problems(fig)
        assert found == [], f"paper-ready (figure_checks.py): {found}"
    finally:
        plt.close(fig)


def test_fragility_figure_written(tmp_path):
    rows, lab, p, known = fragility_inputs()
    for fmt in ("png", "svg"):
        path = str(tmp_path / ("rock.fragility." + fmt))
        sf.draw(rows, lab, p, known, np.array(SCALES), path, [], "uncalibrated: the scene's own physics")
        assert os.path.getsize(path) > 5000
    assert "uncalibrated" in open(str(tmp_path / "rock.fragility.svg")).read()


def reliability(bins):
    """A ten-bin table with the given {bin: (tests, overturned)}."""
    table = []
    for b in range(10):
        n, k = bins.get(b, (0, 0))
        row = {"p_low": b / 10, "p_high": (b + 1) / 10, "tests": n, "overturned": k}
        if n:
            row.update(mean_p=b / 10 + 0.05, frequency=k / n, frequency_interval=[max(0, k / n - 0.2), min(1, k / n + 0.2)])
        else:
            row.update(mean_p=None, frequency=None, frequency_interval=None)
        table.append(row)
    return table


def write_calibration(tmp_path):
    doc = {"format": "rigid calibration", "format_version": 2, "scan": "sp1.obj",
           "physics": "flat_5mm penalty K=5e+05 D=4 mu=0.90", "parameters": {"heading_deg": {"value": 250.0}},
           "in_sample": {"brier": 0.08, "log_loss": 0.28, "reliability": reliability({0: (10, 1), 9: (6, 6)})},
           "cross_validated": {"brier": 0.11, "log_loss": 0.36, "reliability": reliability({0: (9, 1), 5: (2, 1), 9: (5, 4)}),
                               "by_motion": [{"record": r, "tests": 6, "overturned": k, "mean_p": 0.4, "accuracy": a,
                                              "brier": b, "log_loss": 0.3}
                                             for r, k, a, b in (("A", 2, 1.0, 0.05), ("B", 3, 0.5, 0.3), ("C", 0, 1.0, 0.01))]},
           "sha256": "0" * 64}
    cal = tmp_path / "sp1.calibration.json"
    cal.write_text(json.dumps(doc))
    lik = tmp_path / "likelihood.csv"
    lines = ["stage,variant,label,heading_deg,log_likelihood,heading_spread_deg,lapse"]
    for v, label in enumerate(("K=5e5 D=2", "K=5e5 D=4")):
        for h in (230, 240, 250, 260, 270):
            lines.append("2,%d,%s,%d,%g,10,0.05" % (v, label, h, -40 - abs(h - 250) / 5 - 3 * (1 - v)))
    lines.append("1,0,stage one,0,-90,0,0.1")  # the first stage: not drawn
    lik.write_text("\n".join(lines) + "\n")
    return cal, lik


def test_calibration_figure_draws_each_panel(tmp_path):
    import csv
    import matplotlib.pyplot as plt
    cal, lik = write_calibration(tmp_path)
    doc = json.loads(cal.read_text())
    rows = list(csv.DictReader(open(lik)))
    fig = sf.calibration_figure(doc, rows)
    try:
        title = fig._suptitle.get_text()
        assert "sp1.obj" in title and "K=5e+05 D=4 mu=0.90" in title and "250.0" in title, title
        a_lik, a_motion, a_rel = fig.axes[:3]
        labels = [l.get_label() for l in a_lik.get_lines()]
        assert "K=5e5 D=2" in labels and "K=5e5 D=4" in labels and "stage one" not in labels, labels
        best = [l for l in a_lik.get_lines() if l.get_label() == "K=5e5 D=4"][0]
        assert np.allclose(best.get_ydata(), [-44, -42, -40, -42, -44]), "the final stage's likelihood by heading"
        assert [t.get_text() for t in a_motion.get_xticklabels()] == ["A (2/6)", "B (3/6)", "C (0/6)"]
        assert [round(b.get_height(), 3) for b in a_motion.patches] == [0.05, 0.3, 0.01], "Brier by motion"
        legend = [t.get_text() for t in a_rel.get_legend().get_texts()]
        assert any("cross-validated (Brier 0.110, log loss 0.360)" in t for t in legend), legend
        found = figure_checks.problems(fig)
        assert found == [], f"paper-ready (figure_checks.py): {found}"
    finally:
        plt.close(fig)


def test_calibration_figure_without_cross_validation_has_no_empty_panel(tmp_path):
    """Fewer than 3 recorded motions: no cross-validation, so no panel for it (not an empty one);
    the title says why."""
    import csv
    import matplotlib.pyplot as plt
    cal, lik = write_calibration(tmp_path)
    doc = json.loads(cal.read_text())
    doc.pop("cross_validated", None)
    fig = sf.calibration_figure(doc, list(csv.DictReader(open(lik))))
    try:
        assert len([ax for ax in fig.axes if ax.get_visible()]) == 2, "likelihood and reliability only"
        assert "cross-validation by recorded motion: not available" in fig._suptitle.get_text()
        found = figure_checks.problems(fig)
        assert found == [], f"paper-ready (figure_checks.py): {found}"
    finally:
        plt.close(fig)


@pytest.mark.parametrize("fmt", ["png", "pdf", "svg"])
def test_calibration_figure_command_writes_the_file(tmp_path, fmt):
    cal, lik = write_calibration(tmp_path)
    out = tmp_path / ("sp1.calibration." + fmt)
    assert sf.calibration_main([str(cal), "--likelihood", str(lik), "--out", str(out), "--format", fmt]) == 0
    assert out.stat().st_size > 5000


def test_calibration_figure_bad_input(tmp_path, capsys):
    cal, lik = write_calibration(tmp_path)
    other = tmp_path / "other.json"
    other.write_text(json.dumps({"format": "something else"}))
    assert sf.calibration_main([str(other), "--likelihood", str(lik), "--out", str(tmp_path / "x.png")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("rigid: error: ") and "other.json" in err[0], err
    assert sf.calibration_main([str(cal), "--likelihood", str(tmp_path / "none.csv"), "--out", str(tmp_path / "x.png")]) == 2
    assert not (tmp_path / "x.png").exists()

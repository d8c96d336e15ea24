"""`knotmech simulate overhand | clove-hitch`: curves written, knot type reported, bad input."""

import csv
import json

import numpy as np
import pytest

from knotmech.cli.main import main


def test_overhand_short_pull_writes_curves_and_keeps_the_trefoil(tmp_path, capsys):
    out_csv, out_json = tmp_path / "k.csv", tmp_path / "k.json"
    args = ["simulate", "overhand", "--turns", "1", "--mu", "0.3", "--n-nodes", "101",
            "--pull-time", "0.5s", "--dt", "5ms", "--pull-speed", "30mm/s", "--no-progress",
            "--csv", str(out_csv), "--json", str(out_json)]  # fmt: skip
    assert main(args) == 0
    assert "3_1 -> 3_1" in capsys.readouterr().out  # n = 1 closes to the trefoil
    rows = list(csv.DictReader(out_csv.open()))
    e2e = np.array([float(r["end_to_end_m"]) for r in rows])
    # IMC set: end-to-end 0.280 m at the start; after the wait both ends move apart
    assert e2e[0] == pytest.approx(0.280, abs=1e-6)
    assert e2e[-1] > e2e[0]
    data = json.loads(out_json.read_text())
    assert data["knot_preserved"] is True and data["status"] == "success"


@pytest.mark.parametrize(
    "extra, message",
    [
        (["overhand", "--turns", "5", "--mu", "0.3"], "--turns must be 1, 2, 3 or 4"),
        (["overhand", "--turns", "1"], "arguments are required: --mu"),
        (["clove-hitch", "--loading", "asymmetric", "--t-high", "1N"], "--t-low is required"),
        (["clove-hitch", "--t-high", "1kg"], "--t-high"),
        (["clove-hitch", "--loading", "pull", "--speed", "-1mm/s"], "pull_speed"),
        (
            ["clove-hitch", "--loading", "pull", "--mu", "0.3", "--mu-kinetic", "0.5"],
            "mu_kinetic must be <=",
        ),
    ],
)
def test_bad_input_is_one_line_and_exit_2(extra, message, capsys):
    assert main(["simulate", *extra, "--no-progress"]) == 2
    err = capsys.readouterr().err.strip()
    assert message in err and "\n" not in err


@pytest.mark.slow
def test_clove_hitch_free_end_holds_and_tension_vanishes(tmp_path, capsys):
    # clove-hitch paper sec. 7: d, D, L = 4, 30, 374 mm, T_high = 1.47 N, free end: holds,
    # tension dropping to zero past the knot
    out_csv = tmp_path / "h.csv"
    args = ["simulate", "clove-hitch", "--loading", "free", "--t-high", "1.47N", "--mu", "0.3",
            "--n-nodes", "120", "--no-progress", "--csv", str(out_csv)]  # fmt: skip
    assert main(args) == 0
    assert "verdict: HOLD" in capsys.readouterr().out
    rows = list(csv.DictReader(out_csv.open()))
    tension = np.array([float(r["tension_N"]) for r in rows])
    assert tension[0] == pytest.approx(1.47, rel=0.01)
    assert abs(tension[-1]) < 0.01 * 1.47


def test_clove_hitch_pull_writes_the_curve(tmp_path, capsys):
    # clove-hitch paper sect. 5: dead load T_low = 0.069 N, the other end pulled (4 mm here)
    out_csv, out_json = tmp_path / "p.csv", tmp_path / "p.json"
    args = ["simulate", "clove-hitch", "--loading", "pull", "--speed", "20mm/s",
            "--pull-distance", "4mm", "--t-low", "0.069N", "--mu", "0.32", "--n-nodes", "120",
            "--no-progress", "--csv", str(out_csv), "--json", str(out_json)]  # fmt: skip
    assert main(args) == 0
    captured = capsys.readouterr()
    assert "T_high/T_low" in captured.out
    # --csv p.csv: the force curve the run produced in p.csv, the profiles beside it
    err = captured.err
    for name in ("p.csv", "p_tension_profile.csv", "p_curvature.csv", "p.json"):
        assert f"wrote {tmp_path / name}" in err
    rows = list(csv.DictReader(out_csv.open()))
    x = np.array([float(r["displacement_m"]) for r in rows])
    t_high = np.array([float(r["t_high_N"]) for r in rows])
    ratio = np.array([float(r["t_high_over_t_low"]) for r in rows])
    assert x[0] == 0.0 and x[-1] == pytest.approx(4e-3, abs=1e-9)
    assert np.allclose(ratio, t_high / 0.069, rtol=1e-8)
    # starts pre-tensioned (paper: 0.559 N before the extra weight is removed), rises
    assert 0.069 < t_high[0] < 0.559 and t_high[-1] > t_high[0]
    # the profile CSV: the far end carries the dead load
    prof = list(csv.DictReader((tmp_path / "p_tension_profile.csv").open()))
    assert float(prof[-1]["tension_N"]) == pytest.approx(0.069, rel=0.01)
    data = json.loads(out_json.read_text())
    assert data["loading"] == "pull" and data["status"] == "success"
    # scalars only: the curves are in the CSV (and --npz), the counts are integers
    assert "pull_force" not in data and isinstance(data["stats"]["steps"], int)
    assert data["t_low"] == pytest.approx(0.069)

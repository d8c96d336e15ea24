"""``knotmech simulate bend`` and ``knotmech simulate centreline``: options, bad input, runs.

The argument tests stop before any simulation (a bad option, or a stub scene); the real
runs are a tiny centreline (a straight rod pulled 1 mm, 0.1 s once the kernels are
compiled) and one short bend pull (6-9 s).
"""

import json
import math

import pytest

from knotmech.cli import simulate as sim
from knotmech.cli.main import main
from knotmech.errors import InputError

BEND = ["simulate", "bend", "--no-progress"]
ROD = ["--rod-diameter", "4mm", "--youngs-modulus", "1MPa", "--density", "1100kg/m^3",
       "--mu", "0.3", "--no-progress"]  # fmt: skip


def _err(capsys):
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and "Traceback" not in err, err
    return err


def _straight_rod(path, n=20, length_mm=50.0):
    """A straight rod along x, ``x, y, z`` in mm with a header line."""
    lines = ["x, y, z"] + [f"{length_mm * k / (n - 1):.6f}, 0, 0" for k in range(n)]
    path.write_text("\n".join(lines) + "\n")
    return path


@pytest.fixture
def stub(monkeypatch):
    """Replace a scene function by a stub that records its arguments and stops."""
    seen = {}

    def install(module_name, func_name):
        module = __import__(module_name, fromlist=["x"])

        def fake(*args, **kwargs):
            seen["args"], seen["kwargs"] = args, kwargs
            raise InputError("stub reached")

        monkeypatch.setattr(module, func_name, fake)
        return seen

    return install


def test_bend_kinds_are_the_library_bends():
    from knotmech.scenes.bend_curves import BEND_CODES

    assert set(sim.BEND_KINDS) == set(BEND_CODES) | set(sim.TIED_BENDS)


def test_bend_options_reach_the_scene_in_si(stub, capsys):
    seen = stub("knotmech.scenes.bends", "bend")
    argv = BEND + ["--kind", "thief", "--mu", "1", "--rod-diameter", "3mm", "--pull-speed",
                   "20mm/s", "--pull-distance", "2cm", "--n-nodes", "60",
                   "--dt", "2ms"]  # fmt: skip
    assert main(argv) == 2 and "stub reached" in _err(capsys)
    assert seen["args"] == ("thief",)
    kw = seen["kwargs"]
    assert kw["mu_rod_rod"] == 1.0 and kw["rod_diameter"] == pytest.approx(3e-3)
    assert kw["pull_speed"] == pytest.approx(0.02) and kw["pull_distance"] == pytest.approx(0.02)
    assert kw["n_nodes"] == 60 and isinstance(kw["n_nodes"], int)
    assert kw["dt"] == pytest.approx(2e-3) and kw["progress"] is False
    assert "mu_kinetic" not in kw and "density" not in kw  # not given: the scene's defaults


@pytest.mark.parametrize("extra, message", [
    ([], "the following arguments are required: --kind"),
    (["--kind", "bowline"], "invalid choice: 'bowline'"),
    (["--kind", "reef", "--rod-diameter", "4"], "--rod-diameter 4: give a unit, e.g. 4mm"),
    (["--kind", "reef", "--pull-distance", "-3mm"], "pull_distance"),
    (["--kind", "reef", "--n-frames", "5"], "n_frames must be >= 10"),
    (["--kind", "reef", "--turns", "2"], "unrecognized arguments: --turns 2"),  # overhand's
    (["--kind", "reef", "--ends", "pull,free"], "unrecognized arguments"),  # centreline's
    (["--kind", "reef", "--post-diameter", "30mm"], "unrecognized arguments"),
])  # fmt: skip
def test_bend_bad_input_is_one_line_and_exit_2(extra, message, capsys):
    assert main(BEND + extra) == 2
    assert message in _err(capsys)


@pytest.mark.parametrize("name", ["sheet-bend", "double_fishermans", "flat-overhand-bend"])
def test_tied_bend_command_is_bend_with_its_kind(name, stub, capsys):
    """``simulate NAME`` reaches the bend scene as ``bend --kind NAME`` (options in SI)."""
    seen = stub("knotmech.scenes.bends", "bend")
    argv = ["simulate", name, "--no-progress", "--mu", "0.6", "--pull-distance", "3cm"]
    assert main(argv) == 2 and "stub reached" in _err(capsys)
    assert seen["args"] == (name.replace("_", "-"),)
    assert seen["kwargs"]["mu_rod_rod"] == 0.6
    assert seen["kwargs"]["pull_distance"] == pytest.approx(0.03)
    assert "n_nodes" not in seen["kwargs"]  # the record's default


@pytest.mark.parametrize("extra, message", [
    (["--kind", "reef"], "unrecognized arguments: --kind reef"),
    (["--n-nodes", "20"], "n_nodes must be >= 40, got 20"),
    (["--mu", "-1"], "mu_rod_rod"),
])  # fmt: skip
def test_tied_bend_bad_input_is_one_line_and_exit_2(extra, message, capsys):
    assert main(["simulate", "sheet-bend", "--no-progress", *extra]) == 2
    assert message in _err(capsys)


def test_centreline_file_ends_and_unit_reach_the_scene(stub, capsys, tmp_path):
    seen = stub("knotmech.scenes.centreline", "centreline")
    f = str(tmp_path / "knot.csv")
    argv = ["simulate", "centreline", f, "--unit", "mm", "--ends", "free,pull", "--ends",
            " pull , fixed", *ROD, "--post-diameter", "30mm", "--n-nodes", "50"]  # fmt: skip
    assert main(argv) == 2 and "stub reached" in _err(capsys)
    assert seen["args"] == (f,)
    kw = seen["kwargs"]
    assert kw["ends"] == [("free", "pull"), ("pull", "fixed")] and kw["unit"] == "mm"
    assert kw["rod_diameter"] == pytest.approx(4e-3) and kw["youngs_modulus"] == 1e6
    assert kw["density"] == pytest.approx(1100.0) and kw["mu_rod_rod"] == 0.3
    assert kw["post_diameter"] == pytest.approx(0.03) and kw["n_nodes"] == 50


def _file(tmp_path, name, text):
    path = tmp_path / name
    path.write_text(text)
    return str(path)


def _figure_eight(tmp_path):
    """A planar figure 8 (lemniscate, 40 mm wide) from t = -1 to pi + 1: it passes the
    origin at t = 0 and again at t = pi, so it crosses itself."""
    ts = [-1.0 + (math.pi + 2.0) * k / 59 for k in range(60)]
    pts = [(20 * math.sin(t), 10 * math.sin(2 * t), 0.0) for t in ts]
    return _file(tmp_path, "eight.csv", "\n".join(f"{x}, {y}, {z}" for x, y, z in pts))


@pytest.mark.parametrize("case, ends, message", [
    ("nan", ["fixed,pull"], "point 4 is not finite"),
    ("short", ["fixed,pull"], "rod 0 has 5 points, at least 10 are needed"),
    ("malformed", ["fixed,pull"], "columns"),
    ("words", ["fixed,pull"], "is not numbers"),
    ("missing", ["fixed,pull"], "cannot read the centreline file"),
    ("eight", ["free,pull"], "intersects itself"),
    ("good", ["fixed"], "--ends fixed: give FIRST,LAST"),
    ("good", ["fixed,pull,free"], "give FIRST,LAST"),
    ("good", ["fixed,tied"], "ends must be 'pull', 'fixed' or 'free', got 'tied'"),
    ("good", ["free,fixed"], "at least one end must be 'pull'"),
    ("good", ["free,pull", "free,pull"], "for each of the 1 rod(s)"),
    ("good", [None], "the following arguments are required: --ends"),
])  # fmt: skip
def test_centreline_bad_input_is_one_line_and_exit_2(case, ends, message, capsys, tmp_path):
    rows = [f"{k}, 0, 0" for k in range(12)]
    texts = {
        "nan": "\n".join(rows[:3] + ["3, nan, 0"] + rows[4:]),
        "short": "\n".join(rows[:5]),
        "malformed": "\n".join(rows[:4] + ["4, 0"] + rows[5:]),
        "words": "\n".join(rows[:4] + ["4, zero, 0"] + rows[5:]),
        "good": "\n".join(rows),
    }
    if case == "eight":
        path = _figure_eight(tmp_path)
    elif case == "missing":
        path = str(tmp_path / "nowhere.csv")
    else:
        path = _file(tmp_path, f"{case}.csv", texts[case])
    argv = ["simulate", "centreline", path, "--unit", "mm", *ROD]
    for e in ends:
        if e is not None:
            argv += ["--ends", e]
    assert main(argv) == 2
    assert message in _err(capsys)


def test_centreline_output_paths_are_checked_before_reading(stub, capsys, tmp_path):
    seen = stub("knotmech.scenes.centreline", "centreline")
    argv = ["simulate", "centreline", str(tmp_path / "k.csv"), "--ends", "fixed,pull", *ROD,
            "--json", str(tmp_path / "no" / "r.json")]  # fmt: skip
    assert main(argv) == 2 and "does not exist" in _err(capsys)
    assert not seen


def test_centreline_straight_rod_pulled_reads_ea_strain(tmp_path, capsys):
    """A straight rod (50 mm, 20 points, d = 4 mm, E = 1 MPa) fixed at its first end and
    pulled 1 mm at its last: the force is EA delta / L_free, L_free = the length between the
    two clamped end edges (50 mm - 2 x 50/19 mm), plus a drag of ~1 % (quasi-static pull)."""
    f = _straight_rod(tmp_path / "rod.csv")
    out = tmp_path / "rod.json"
    csv = tmp_path / "rod_curve.csv"
    argv = ["simulate", "centreline", str(f), "--unit", "mm", "--ends", "fixed,pull", *ROD,
            "--pull-distance", "1mm", "--settle-time", "20ms", "--n-nodes", "20",
            "--n-frames", "10", "--json", str(out), "--csv", str(csv)]  # fmt: skip
    assert main(argv) == 0
    captured = capsys.readouterr()
    assert "status success; HOLDS up to" in captured.out and "knot type kept" in captured.out
    doc = json.loads(out.read_text())
    assert doc["scene"] == "centreline" and doc["status"] == "success"
    assert doc["verdict"] == "holds" and doc["slip_load"] is None  # NaN -> null, strict JSON
    assert doc["topology_preserved"] is True
    ea = 1e6 * math.pi * 4e-3**2 / 4
    l_free = 50e-3 * (1 - 2 / 19)
    assert doc["max_force"] == pytest.approx(ea * 1e-3 / l_free, rel=0.02)
    header, *rows = csv.read_text().splitlines()
    assert header == "time_s,pull_displacement_m,pull_force_N"  # no free end: no draw-in
    assert float(rows[-1].split(",")[1]) == pytest.approx(1e-3, rel=1e-6)


def test_bend_short_pull_runs_and_reports(tmp_path, capsys):
    """The grief bend (mu = 0.3) pulled 8 mm: a finished run with a verdict, the knot type
    kept, and its curve written (6-9 s once the kernels are compiled)."""
    out = tmp_path / "grief.json"
    csv = tmp_path / "grief.csv"
    argv = BEND + ["--kind", "grief", "--pull-distance", "8mm", "--n-frames", "10",
                   "--json", str(out), "--csv", str(csv)]  # fmt: skip
    assert main(argv) == 0
    assert "bend grief: status success;" in capsys.readouterr().out
    doc = json.loads(out.read_text())
    assert doc["kind"] == "grief" and doc["verdict"] in ("slips", "holds")
    assert doc["topology_preserved"] is True
    assert doc["max_force"] > 0
    header, *rows = csv.read_text().splitlines()
    assert header.split(",")[-2:] == ["draw_in_tail_a_m", "draw_in_tail_b_m"]
    assert float(rows[-1].split(",")[1]) == pytest.approx(8e-3, rel=1e-6)

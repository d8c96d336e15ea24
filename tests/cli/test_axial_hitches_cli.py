"""``knotmech hold prusik`` and ``knotmech simulate prusik`` / ``clove-hitch --loading axial``:
undecided with the full ``--simulate`` command, ``--simulate`` comparing the DER drag's
sliding force with the load (the scene stubbed here: the drag itself is tested in
tests/scenes/test_axial_hitches.py), and one-line errors."""

import json
import math
from types import SimpleNamespace

import pytest

import knotmech
from knotmech import knots
from knotmech.cli.main import main

PRUSIK = ["--rod-diameter", "6mm", "--post-diameter", "12mm", "--mu", "0.3", "--load", "100N"]


def _fake_drag(sliding_force, peak_force, seen=None, slid=True):
    def fake(knot, **kw):
        if seen is not None:
            seen.update(kw, knot=knot)
        return SimpleNamespace(
            knot=knot, wraps=kw["wraps"], sliding_force=sliding_force, peak_force=peak_force,
            slid=slid, status="success", message="", stats={"wall_s": 1.0},
            topology_preserved=True, drag_speed=0.01, slide_distance=kw["rod_diameter"],
        )  # fmt: skip

    return fake


def test_the_prusik_is_one_record_with_its_aliases():
    assert knots.key("Prussik") == knots.key("prusik-knot") == "prusik"
    rec = knots.get("prusik")
    assert rec.family == "hitch" and rec.answered and not rec.has_scene
    assert "10.1016/j.jmps.2026.106628" in " ".join(rec.sources)


def test_hold_prusik_without_simulate_is_undecided_with_the_command(capsys):
    assert main(["hold", "prusik", *PRUSIK, "--material", "nylon", "--json", "-"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["holds"] is None and data["decided_by"] is None
    cmd = ("knotmech hold prusik --rod-diameter 6mm --post-diameter 12mm --mu 0.3 --load 100N "
           "--material nylon --simulate")  # fmt: skip
    assert cmd in data["next_step"] and "minutes of CPU" in data["next_step"]


def test_hold_prusik_simulate_compares_the_sliding_force(monkeypatch):
    from knotmech.scenes import axial

    seen = {}
    monkeypatch.setattr(axial, "axial_pull", _fake_drag(150.0, 160.0, seen))
    v = knotmech.hold("prusik", rod_diameter=6e-3, post_diameter=12e-3, mu=0.3, load=100.0,
                      youngs_modulus=1e8, simulate=True)  # fmt: skip
    assert v.holds is True and v.decided_by == "DER-simulation"
    assert v.margin == pytest.approx(150.0 / 100.0 - 1)
    assert seen["knot"] == "prusik" and seen["wraps"] == 3 and seen["post_diameter"] == 12e-3
    assert seen["normal_load"] == pytest.approx(10.0)  # the set: 0.1 x the load on each leg
    v2 = knotmech.hold("prusik", rod_diameter=6e-3, post_diameter=12e-3, mu=0.3, load=200.0,
                       youngs_modulus=1e8, simulate=True)  # fmt: skip
    assert v2.holds is False and v2.margin == pytest.approx(-0.25)
    # it did not slide up to 160 N: holds 100 N, undecided at 200 N
    monkeypatch.setattr(axial, "axial_pull", _fake_drag(math.nan, 160.0, slid=False))
    v3 = knotmech.hold("prusik", rod_diameter=6e-3, post_diameter=12e-3, mu=0.3, load=200.0,
                       youngs_modulus=1e8, simulate=True)  # fmt: skip
    assert v3.holds is None and "did not slide up to 160 N" in v3.der["message"]


@pytest.mark.parametrize(
    ("argv", "words"),
    [
        (["hold", "prusik", "--rod-diameter", "6mm", "--mu", "0.3", "--load", "100N"],
         "--post-diameter is required for prusik"),
        (["hold", "prusik", *PRUSIK, "--free-end-load", "5N"], "does not apply to the prusik"),
        (["hold", "prusik-knot-xyz", *PRUSIK], "unknown knot 'prusik-knot-xyz'"),
        (["simulate", "prusik", "--post-diameter", "12mm", "--wraps", "1"],
         "wraps must be an integer from 2 to 6"),
        (["simulate", "prusik"], "required: --post-diameter"),
        (["simulate", "clove-hitch", "--loading", "axial"],
         "--normal-load is required with --loading axial"),
        (["simulate", "clove-hitch", "--loading", "axial", "--normal-load", "1N",
          "--t-high", "1N"], "--t-high: not used with --loading axial"),
        (["simulate", "clove-hitch", "--t-high", "1N", "--drag-speed", "1mm/s"],
         "--drag-speed: not used without --loading axial"),
    ],
)  # fmt: skip
def test_bad_input_is_one_line_and_exit_2(argv, words, capsys):
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert words in err and len(err.splitlines()) == 1, err


def test_simulate_prusik_prints_and_writes_the_drag(monkeypatch, tmp_path, capsys):
    import numpy as np

    from knotmech.scenes import axial

    def fake(knot, **kw):
        return axial.AxialResult(
            knot=knot, wraps=kw.get("wraps", 3), normal_load=0.5, drag_speed=0.01,
            drag_distance=0.01, times=np.array([0.0, 1.0]),
            grip_displacement=np.array([0.0, 0.01]), axial_force=np.array([0.0, 3.0]),
            knot_displacement=np.array([0.0, 0.005]), sliding_force=2.5, peak_force=3.0,
            plateau_force=2.8, slid=True, slide_distance=0.004, min_rod_distance=0.004,
            min_post_gap=0.0, winding_start=0.0, winding_end=0.0, invariants_start=None,
            invariants_end=None, invariants_kept=None, positions=np.zeros((2, 3, 3)),
            status="success", message="", rod_diameter=0.004, stats={"wall_s": 1.0},
        )  # fmt: skip

    monkeypatch.setattr(axial, "axial_pull", fake)
    csv = tmp_path / "drag.csv"
    argv = ["simulate", "prusik", "--post-diameter", "12mm", "--wraps", "3", "--no-progress",
            "--csv", str(csv)]  # fmt: skip
    assert main(argv) == 0
    out = capsys.readouterr().out
    assert "slides at 2.5 N" in out and "3 turns" in out and "knot type kept" in out
    lines = csv.read_text().splitlines()
    assert lines[0] == "time_s,grip_displacement_m,axial_force_N,knot_displacement_m"
    assert lines[2].split(",")[2] == "3"


COW = ["--rod-diameter", "4mm", "--post-diameter", "30mm", "--mu", "0.3", "--load", "0.3N",
       "--material", "vps32"]  # fmt: skip


def test_cow_hitch_on_both_legs_is_undecided_with_its_simulate_command(capsys):
    assert main(["hold", "cow-hitch", *COW, "--loading", "both-legs", "--json", "-"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["holds"] is None
    cmd = ("knotmech hold cow-hitch --rod-diameter 4mm --post-diameter 30mm --mu 0.3 "
           "--load 0.3N --free-end-load 0.3N --material vps32 --simulate")  # fmt: skip
    assert cmd in data["next_step"] and "s of CPU" in data["next_step"]
    # one-leg is the default loading; --loading is the cow hitch's only
    assert main(["hold", "cow-hitch", *COW, "--loading", "one-leg", "--json", "-"]) == 0
    assert "--free-end-load" not in json.loads(capsys.readouterr().out)["next_step"]
    assert main(["hold", "clove-hitch", *COW, "--loading", "both-legs"]) == 2
    assert "applies to the cow hitch, not to clove-hitch" in capsys.readouterr().err


def test_cow_hitch_both_legs_simulate_loads_the_other_leg(monkeypatch):
    from knotmech.verdict import build

    seen = {}

    def fake(**kw):
        seen.update(kw)
        return {"holds": True, "verdict": "hold", "message": "", "wall_s": 1.0,
                "time_scale": 1.0, "creep_speed_protocol": 1e-5, "ran_to_end": True,
                "creep_window_s": 0.75}  # fmt: skip

    monkeypatch.setattr(build, "simulate_point", fake)
    v = knotmech.hold("cow-hitch", rod_diameter=4e-3, post_diameter=30e-3, mu=0.3, load=0.3,
                      free_end_load=0.15, material="vps32", simulate=True)  # fmt: skip
    assert seen["knot"] == "cow-hitch" and seen["t_low_fraction"] == pytest.approx(0.5)
    assert v.holds is True and v.der["source"] == "simulation"


# -- the rolling hitch: a made hitch scene with --loading axial, hold along the pole ----------

ROLLING = ["--rod-diameter", "6mm", "--post-diameter", "30mm", "--mu", "0.3", "--load", "100N"]


def test_the_rolling_hitch_is_one_record_with_its_aliases():
    assert knots.key("Magnus hitch") == knots.key("rolling") == "rolling-hitch"
    rec = knots.get("magnus-hitch")
    assert rec.family == "hitch" and rec.answered and rec.has_scene and not rec.scene
    assert rec.pull_angle == pytest.approx(7 * math.pi)  # three and a half turns
    assert "#1735" in " ".join(rec.sources)


def test_hold_rolling_hitch_without_simulate_is_undecided_with_the_command(capsys):
    assert main(["hold", "magnus-hitch", *ROLLING, "--material", "nylon", "--json", "-"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["holds"] is None and data["decided_by"] is None
    cmd = ("knotmech hold rolling-hitch --rod-diameter 6mm --post-diameter 30mm --mu 0.3 "
           "--load 100N --material nylon --simulate")  # fmt: skip
    assert cmd in data["next_step"] and "drag of a rolling hitch" in data["next_step"]


def test_hold_rolling_hitch_simulate_drags_its_standing_part(monkeypatch):
    from knotmech.scenes import axial

    seen = {}
    monkeypatch.setattr(axial, "axial_pull", _fake_drag(80.0, 90.0, seen))
    v = knotmech.hold("rolling", rod_diameter=6e-3, post_diameter=30e-3, mu=0.3, load=100.0,
                      youngs_modulus=1e8, simulate=True)  # fmt: skip
    assert v.holds is False and v.margin == pytest.approx(80.0 / 100.0 - 1)
    assert seen["knot"] == "rolling-hitch" and seen["wraps"] is None
    assert seen["normal_load"] == pytest.approx(10.0)  # the set: 0.1 x the load


@pytest.mark.parametrize(
    ("argv", "words"),
    [
        (["simulate", "rolling-hitch", "--loading", "axial"],
         "--normal-load is required with --loading axial"),
        (["simulate", "rolling-hitch", "--loading", "axial", "--normal-load", "1N",
          "--creep-limit", "1e-3"], "--creep-limit: not used with --loading axial"),
        (["simulate", "rolling-hitch", "--t-high", "1N", "--normal-load", "1N"],
         "--normal-load: not used without --loading axial"),
        (["hold", "rolling-hitch", *ROLLING, "--free-end-load", "5N"],
         "does not apply to the rolling-hitch"),
        (["hold", "rolling-hitch", "--rod-diameter", "6mm", "--mu", "0.3", "--load", "100N"],
         "--post-diameter is required for rolling-hitch"),
    ],
)  # fmt: skip
def test_rolling_hitch_bad_input_is_one_line_and_exit_2(argv, words, capsys):
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert words in err and len(err.splitlines()) == 1, err


def test_simulate_rolling_hitch_axial_runs_the_drag(monkeypatch, capsys):
    from knotmech.scenes import axial

    seen = {}

    def fake(knot, **kw):
        seen.update(kw, knot=knot)
        raise knotmech.InputError("stub reached")

    monkeypatch.setattr(axial, "axial_pull", fake)
    argv = ["simulate", "rolling-hitch", "--loading", "axial", "--normal-load", "0.5N",
            "--drag-speed", "20mm/s", "--n-nodes", "90", "--no-progress"]  # fmt: skip
    assert main(argv) == 2 and "stub reached" in capsys.readouterr().err
    assert seen["knot"] == "rolling-hitch" and seen["normal_load"] == pytest.approx(0.5)
    assert seen["drag_speed"] == pytest.approx(0.02) and seen["n_nodes"] == 90

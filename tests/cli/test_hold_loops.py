"""``knotmech hold`` and ``knotmech simulate`` for the loops (bowline, figure-eight loop,
alpine butterfly: the eye round a pin; the alpine butterfly also end to end): undecided with
the full ``--simulate`` command, ``--simulate`` running the loop scene (stubbed here: the
pull itself is in tests/scenes/test_tied_loops.py), and the one-line errors."""

import json
import math

import numpy as np
import pytest

import knotmech
from knotmech.cli.main import main
from knotmech.errors import InputError
from knotmech.scenes.loops import LoopResult

LOOP = ["--rod-diameter", "4mm", "--pin-diameter", "20mm", "--mu", "0.3", "--load", "0.05N",
        "--youngs-modulus", "1MPa"]  # fmt: skip


def _fake_loop(verdict, slip_load, max_force, seen=None):
    def fake(knot, **kw):
        if seen is not None:
            seen.update(kw, knot=knot)
        n = 3
        return LoopResult(
            knot=knot, verdict=verdict, slip_load=slip_load, max_force=max_force,
            pin_diameter=kw.get("pin_diameter", 0.02), pull_speed=0.04,
            mu_rod_rod=kw.get("mu_rod_rod", 0.3),
            mu_pin=kw.get("mu_rod_rod", 0.3), times=np.arange(n) * 0.1,
            pull_displacement=np.arange(n) * 4e-3, pull_force=np.array([0.01, 0.02, max_force]),
            tail_draw_in=np.array([0.0, 4e-3, 12e-3]), eye_growth=np.zeros(n),
            slipped_by="tail", invariants_start={"alexander": (1, -3, 5, -3, 1)},
            invariants_checked={"alexander": (1, -3, 5, -3, 1)}, frames_checked=n,
            law="anchor", positions=np.zeros((n, 4, 3)), status="success", message="",
            stats={"steps": 10, "wall_s": 1.0}, loading=kw.get("loading", "loop"),
        )  # fmt: skip

    return fake


@pytest.mark.parametrize("knot", ["bowline", "figure-8-loop", "figure eight on a bight"])
def test_loop_without_simulate_is_undecided_with_the_command(knot, capsys):
    assert main(["hold", knot, *LOOP, "--json", "-"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["holds"] is None and data["decided_by"] is None
    key = "bowline" if knot == "bowline" else "figure-eight-loop"
    cmd = (f"knotmech hold {key} --rod-diameter 4mm --pin-diameter 20mm --mu 0.3 --load 0.05N "
           "--youngs-modulus 1MPa --simulate")  # fmt: skip
    assert cmd in data["next_step"] and "minute of CPU" in data["next_step"]


def test_loop_simulate_compares_the_slip_load(monkeypatch, capsys):
    from knotmech.scenes import loops

    seen = {}
    monkeypatch.setattr(loops, "loop", _fake_loop("slips", 0.08, 0.08, seen))
    v = knotmech.hold("bowline", rod_diameter=4e-3, pin_diameter=20e-3, mu=0.3, load=0.05,
                      youngs_modulus=1e6, simulate=True)  # fmt: skip
    assert v.holds is True and v.decided_by == "DER-simulation"
    assert v.margin == pytest.approx(0.08 / 0.05 - 1)
    assert seen["knot"] == "bowline" and seen["pin_diameter"] == 20e-3
    assert seen["mu_rod_rod"] == 0.3 and seen["youngs_modulus"] == 1e6
    assert v.capacity.value == pytest.approx(0.08) and v.capacity.limited_by == "slip"
    assert v.der["slipped_by"] == "tail" and v.der["tail_draw_in"] == pytest.approx(12e-3)
    v2 = knotmech.hold("bowline", rod_diameter=4e-3, pin_diameter=20e-3, mu=0.3, load=0.1,
                       youngs_modulus=1e6, simulate=True)  # fmt: skip
    assert v2.holds is False and v2.margin == pytest.approx(0.08 / 0.1 - 1)
    monkeypatch.setattr(loops, "loop", _fake_loop("holds", math.nan, 0.3))
    v3 = knotmech.hold("figure-eight-loop", rod_diameter=4e-3, pin_diameter=20e-3, mu=1.0,
                       load=0.5, youngs_modulus=1e6, simulate=True)  # fmt: skip
    assert v3.holds is None and "above the largest pull force" in v3.der["message"]
    assert main(["hold", "bowline", *LOOP, "--simulate"]) == 0
    assert capsys.readouterr().out.startswith("verdict: HOLDS")


def test_loop_breaking_load_from_the_strength_tables():
    """Bowline in 10 mm polyester: the breaking load carries the bowline's efficiency."""
    v = knotmech.hold("bowline", rod_diameter=10e-3, pin_diameter=20e-3, mu=0.3, load=500.0,
                      material="polyester")  # fmt: skip
    assert v.holds is None
    brk = v.capacity.breaking
    assert brk is not None and 0 < brk.value < 30e3
    assert v.capacity.efficiency is not None and 0.3 < v.capacity.efficiency[0] < 0.8


@pytest.mark.parametrize(
    ("args", "words"),
    [
        (["bowline", "--rod-diameter", "4mm", "--mu", "0.3", "--load", "1N"],
         "bowline needs --pin-diameter"),
        (["bowline", *LOOP, "--post-diameter", "30mm"], "--post-diameter does not apply to a loop"),
        (["bowline", *LOOP, "--free-end-load", "1N"], "--free-end-load does not apply to a loop"),
        (["bowline", *LOOP[:2], "--pin-diameter", "-1mm", *LOOP[4:]],
         "--pin-diameter must be > 0"),
        (["clove-hitch", "--rod-diameter", "4mm", "--post-diameter", "30mm", "--pin-diameter",
          "20mm", "--mu", "0.3", "--load", "1N"], "--pin-diameter applies to a loop"),
        (["zeppelin-loop", *LOOP], "unknown knot 'zeppelin-loop'"),
    ],
)  # fmt: skip
def test_hold_loop_errors_are_one_line(args, words, capsys):
    assert main(["hold", *args]) == 2
    err = capsys.readouterr().err.strip()
    assert words in err and len(err.splitlines()) == 1


@pytest.mark.parametrize(
    ("args", "words"),
    [
        (["bowline"], "required: --pin-diameter"),
        (["figure-eight-loop", "--pin-diameter", "0mm"], "pin_diameter must be > 0"),
        (["bowline", "--pin-diameter", "nan mm"], "--pin-diameter"),
        (["bowline", "--pin-diameter", "1m"], "pin_diameter must lie in [0.5 d, 40 d]"),
    ],
)
def test_simulate_loop_errors_are_one_line(args, words, capsys):
    assert main(["simulate", *args, "--no-progress"]) == 2
    err = capsys.readouterr().err.strip()
    assert words in err and len(err.splitlines()) == 1


def test_simulate_loop_writes_its_outputs(monkeypatch, tmp_path, capsys):
    from knotmech.scenes import loops

    monkeypatch.setattr(loops, "loop", _fake_loop("slips", 0.08, 0.08))
    out = tmp_path / "b.json"
    csv = tmp_path / "b.csv"
    assert main(["simulate", "bowline", "--pin-diameter", "20mm", "--json", str(out),
                 "--csv", str(csv), "--no-progress"]) == 0  # fmt: skip
    line = capsys.readouterr().out
    assert "bowline: status success; SLIPS at 0.08 N (tail)" in line
    data = json.loads(out.read_text())
    assert data["slip_load"] == 0.08 and data["inputs"]["pin_diameter"] == 0.02
    rows = csv.read_text().splitlines()
    assert rows[0] == "time_s,pull_displacement_m,pull_force_N,tail_draw_in_m,eye_growth_m"
    assert len(rows) == 4


def test_loop_library_errors():
    from knotmech.scenes.loops import loop

    with pytest.raises(InputError, match="bowline needs pin_diameter"):
        loop("bowline")
    with pytest.raises(InputError, match="loop must be one of bowline, figure-eight-loop"):
        loop("sheet-bend", pin_diameter=0.02)
    with pytest.raises(InputError, match="pin_diameter must be a finite number > 0"):
        loop("bowline", pin_diameter=float("nan"))


def test_hold_alpine_butterfly(monkeypatch, capsys):
    """Undecided with its command; with --simulate, one (stubbed) pull on the loop."""
    from knotmech.scenes import loops

    assert main(["hold", "lineman's loop", *LOOP, "--json", "-"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["holds"] is None and "knotmech hold alpine-butterfly" in data["next_step"]
    seen = {}
    monkeypatch.setattr(loops, "loop", _fake_loop("slips", 0.08, 0.08, seen))
    v = knotmech.hold("butterfly", rod_diameter=4e-3, pin_diameter=20e-3, mu=0.3, load=0.05,
                      youngs_modulus=1e6, simulate=True)  # fmt: skip
    assert v.holds is True and seen["knot"] == "alpine-butterfly"
    assert seen["pin_diameter"] == 0.02 and "loading" not in seen  # the default: on the loop


@pytest.mark.parametrize(
    ("args", "loading", "line"),
    [
        (["--pin-diameter", "20mm"], None, "SLIPS at 0.08 N (tail); tail drawn in 12 mm"),
        (["--loading", "end-to-end"], "end-to-end", "end to end: eye drawn in 0 mm"),
    ],
)
def test_simulate_alpine_butterfly_both_loadings(monkeypatch, capsys, args, loading, line):
    from knotmech.scenes import loops

    seen = {}
    monkeypatch.setattr(loops, "loop", _fake_loop("slips", 0.08, 0.08, seen))
    assert main(["simulate", "alpine-butterfly", *args, "--no-progress"]) == 0
    assert line in capsys.readouterr().out
    assert seen.get("loading") == loading and seen["knot"] == "alpine-butterfly"
    assert ("pin_diameter" in seen) == (loading is None)


@pytest.mark.parametrize(
    ("args", "words"),
    [
        ([], "alpine-butterfly needs pin_diameter"),
        (["--loading", "axial", "--pin-diameter", "20mm"],
         "loading of alpine-butterfly must be one of loop, end-to-end, got 'axial'"),
        (["--loading", "end-to-end", "--pin-diameter", "0mm"], "pin_diameter must be > 0"),
    ],
)  # fmt: skip
def test_simulate_alpine_butterfly_errors_are_one_line(args, words, capsys):
    assert main(["simulate", "alpine-butterfly", *args, "--no-progress"]) == 2
    err = capsys.readouterr().err.strip()
    assert words in err and len(err.splitlines()) == 1

"""``knotmech simulate two-half-hitches | round-turn-two-half-hitches | cow-hitch |
rolling-hitch``.

Option parsing is checked with the scene replaced by a stub (no simulation); one short real
run goes through ``python -m knotmech`` and checks the files it writes.
"""

import inspect
import json
import subprocess
import sys
from pathlib import Path

import pytest

from knotmech.cli import simulate as sim
from knotmech.cli.main import main
from knotmech.errors import InputError
from knotmech.units import parse_quantity

ROOT = Path(__file__).resolve().parents[2]
SCENES = {
    "two-half-hitches": "two_half_hitches",
    "round-turn-two-half-hitches": "round_turn_two_half_hitches",
    "cow-hitch": "cow_hitch",
    "rolling-hitch": "rolling_hitch",
}


def _err(capsys):
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and "Traceback" not in err, err
    return err


@pytest.fixture
def stub(monkeypatch):
    """Replace each hitch scene function by a stub recording its keyword arguments."""
    from knotmech import knots
    from knotmech.scenes import hitches

    seen = {}

    def scene_of(knot):
        name = knots.get(knot).identifier

        def fake(*args, **kwargs):
            seen["scene"], seen["kwargs"] = name, kwargs
            raise InputError("stub reached")

        return fake

    monkeypatch.setattr(hitches, "hitch_function", scene_of)
    return seen


def test_the_hitch_scenes_are_sub_commands():
    assert set(SCENES) <= set(sim.SCENES) and set(SCENES) == set(sim.HITCH_SCENES)
    for scene in SCENES:
        if scene in sim.AXIAL_LOADING:  # and --loading axial's options (scenes.axial)
            assert sim.SCENE_OPTIONS[scene] == sim._HITCH + sim._CLOVE_AXIAL
        else:
            assert sim.SCENE_OPTIONS[scene] is sim.SCENE_OPTIONS["two-half-hitches"]


@pytest.mark.parametrize("scene", list(SCENES))
def test_options_reach_the_scene_in_si(scene, stub, capsys):
    code = main(["simulate", scene, "--loading", "free", "--t-high", "300mN", "--mu", "0.5",
                 "--post-diameter", "2cm", "--hold-time", "1.5s", "--creep-limit", "2e-3",
                 "--no-progress"])  # fmt: skip
    assert code == 2 and "stub reached" in _err(capsys)
    kw = stub["kwargs"]
    assert stub["scene"] == SCENES[scene]
    assert kw["loading"] == "free" and kw["t_high"] == pytest.approx(0.3)
    # --mu is the rod-post friction; --mu-rr not given: the scene's own default (0.3), as
    # the API (knotmech.scenes.hitches.hitch_function(scene)(...)) uses
    assert kw["mu_rod_post"] == 0.5 and "mu_rod_rod" not in kw
    assert kw["post_diameter"] == pytest.approx(0.02) and kw["hold_time"] == 1.5
    assert kw["creep_limit"] == 2e-3
    assert "rod_length" not in kw and "n_nodes" not in kw  # the scene's own defaults


@pytest.mark.parametrize("argv, message", [
    (["--t-high", "1"], "--t-high 1: give a unit"),
    (["--loading", "pull", "--t-high", "1N"], "--t-high: not used with --loading pull"),
    (["--loading", "pull", "--creep-limit", "1e-3"], "--creep-limit: not used without"),
    (["--loading", "asymmetric"], "--t-high, --t-low are required with --loading asymmetric"),
    (["--t-high", "1N", "--pull-speed", "1mm/s"], "--pull-speed: not used with --loading free"),
    (["--t-high", "1N", "--turns", "2"], "unrecognized arguments: --turns 2"),
])  # fmt: skip
def test_bad_options_one_line_exit_2(argv, message, stub, capsys):
    assert main(["simulate", "two-half-hitches", *argv, "--no-progress"]) == 2
    assert message in _err(capsys)
    assert not stub  # refused before the scene was called


@pytest.mark.parametrize("scene", list(SCENES))
def test_defaults_shown_are_the_scene_functions_defaults(scene):
    from knotmech.scenes.hitches import hitch_function

    func = hitch_function(scene)
    params = inspect.signature(func).parameters
    checked = 0
    for o in sim.SCENE_OPTIONS[scene]:
        if o in sim._CLOVE_AXIAL:  # --loading axial: knotmech.scenes.axial.axial_pull's
            continue
        default = params[o.kwarg].default
        if o.default in (None, sim.REQUIRED) or not isinstance(default, (int, float)):
            continue
        try:
            shown = parse_quantity(o.default, o.kind)
        except InputError:
            continue  # a sentence ("--mu"), not a value
        assert shown == pytest.approx(default, rel=1e-12), o.flag
        checked += 1
    assert checked >= 10


def test_a_real_run_writes_strict_json_csv_and_plot(tmp_path):
    """Two half hitches, 50 mN on the standing end, working end free, 0.3 s in all."""
    js, cs, png = tmp_path / "h.json", tmp_path / "h.csv", tmp_path / "h.png"
    proc = subprocess.run(
        [sys.executable, "-m", "knotmech", "simulate", "two-half-hitches", "--loading", "free",
         "--t-high", "50mN", "--mu", "0.6", "--settle-time", "0.1s", "--load-time", "0.1s",
         "--hold-time", "0.1s", "--no-progress", "--json", str(js), "--csv", str(cs),
         "--plot", str(png)],
        capture_output=True, text=True, timeout=600, cwd=ROOT,
    )  # fmt: skip
    assert proc.returncode in (0, 1), proc.stderr
    out = proc.stdout
    assert out.startswith("two-half-hitches (free): status ") and "d/s" in out, out

    def no_constants(name):
        raise AssertionError(f"non-strict JSON constant {name}")

    data = json.loads(js.read_text(), parse_constant=no_constants)
    assert data["scene"] == "two-half-hitches" and data["inputs"]["t_high"] == pytest.approx(0.05)
    assert data["knot"] == "two_half_hitches" and data["verdict"] in ("hold", "slip")
    assert data["invariants_start"] == {"alexander": "1 -2 3 -2 1", "linking": -1}
    assert isinstance(data["stats"]["steps"], int) and data["creep_window"] == pytest.approx(0.05)
    rows = cs.read_text().splitlines()
    assert rows[0] == "s_m,tension_N,rod_contact" and len(rows) > 100
    assert (tmp_path / "h_curvature.csv").exists()
    assert png.read_bytes()[:4] == b"\x89PNG"

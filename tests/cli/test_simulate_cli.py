"""``knotmech simulate``: options per scene, units, output files, up-front bounds, start-up.

Most tests here replace the scene function by a stub that records its arguments, so they
check the command line without simulating; the few real runs are pinch pull-outs (~2 s).
"""

import inspect
import json
import subprocess
import sys

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from knotmech.cli import simulate as sim
from knotmech.cli.main import SUBCOMMANDS, SUMMARIES, main
from knotmech.errors import InputError
from knotmech.units import parse_quantity

CAPSTAN = ["simulate", "capstan", "--wrap-angle", "180deg", "--mu", "0.5", "--rod-diameter",
           "4mm", "--post-diameter", "16mm", "--youngs-modulus", "1.26MPa", "--t-low", "0.16N",
           "--no-progress"]  # fmt: skip


class _Called(Exception):
    pass


@pytest.fixture
def capture_scene(monkeypatch):
    """Replace a scene function by a stub that records its keyword arguments and stops."""
    seen = {}

    def install(module_name, func_name):
        module = sys.modules.get(module_name) or __import__(module_name, fromlist=["x"])

        def stub(*args, **kwargs):
            seen["args"], seen["kwargs"] = args, kwargs
            raise InputError("stub reached")

        monkeypatch.setattr(module, func_name, stub)
        return seen

    return install


def _err(capsys):
    err = capsys.readouterr().err.strip()
    assert "\n" not in err and "Traceback" not in err, err
    return err


def test_density_and_bending_stiffness_take_their_units(capture_scene, capsys):
    # issue 13: "--density 1200kg/m^3 and --bending-stiffness 1e-5N*m^2 are refused as
    # 'not dimensionless'"
    seen = capture_scene("knotmech.scenes.capstan", "capstan")
    args = CAPSTAN + ["--density", "1200kg/m^3", "--bending-stiffness", "1e-5N*m^2"]
    assert main(args) == 2 and "stub reached" in _err(capsys)
    kw = seen["kwargs"]
    assert kw["density"] == pytest.approx(1200.0) and kw["bending_stiffness"] == 1e-5
    assert kw["wrap_angle"] == pytest.approx(np.pi) and kw["rod_diameter"] == 0.004
    assert kw["post_diameter"] == pytest.approx(0.016) and kw["youngs_modulus"] == 1.26e6
    assert kw["t_low"] == pytest.approx(0.16) and kw["mu"] == 0.5
    assert "mu_kinetic" not in kw  # not given: the scene's default (mu)


@pytest.mark.parametrize("scene, module, func, extra", [
    ("pinch", "knotmech.scenes.pinch", "pinch", ["--normal-load", "0.3N", "--mu", "0.3"]),
    ("clove-hitch", "knotmech.scenes.clove_hitch", "clove_hitch",
     ["--loading", "free", "--t-high", "1.47N"]),
])  # fmt: skip
def test_density_everywhere(capture_scene, capsys, scene, module, func, extra):
    seen = capture_scene(module, func)
    assert main(["simulate", scene, *extra, "--density", "1.2g/cm^3", "--no-progress"]) == 2
    assert seen["kwargs"]["density"] == pytest.approx(1200.0)


def test_pinch_n_elements_is_passed_on(capture_scene, capsys):
    # issue 13: "simulate pinch --n-elements is accepted and ignored"
    seen = capture_scene("knotmech.scenes.pinch", "pinch")
    main(["simulate", "pinch", "--normal-load", "0.3N", "--mu", "0.3", "--n-elements", "240"])
    assert seen["kwargs"]["n_elements"] == 240 and isinstance(seen["kwargs"]["n_elements"], int)


def test_all_missing_options_at_once(capsys):
    assert main(["simulate", "capstan"]) == 2
    err = _err(capsys)
    for flag in ("--wrap-angle", "--mu", "--rod-diameter", "--post-diameter",
                 "--youngs-modulus", "--t-low"):  # fmt: skip
        assert flag in err


@pytest.mark.parametrize("extra, message", [
    (["--turns", "3"], "unrecognized arguments: --turns 3"),  # overhand's option
    (["--loading", "pull"], "unrecognized arguments: --loading pull"),  # clove-hitch's
    (["--normal-load", "1N"], "unrecognized arguments: --normal-load 1N"),  # pinch's
    (["--t-high", "1N"], "--t-high: not used with --mode pull"),
    (["--mode", "hold"], "--t-high is required with --mode hold"),
    (["--rod-diameter", "4"], "--rod-diameter 4: give a unit, e.g. 4mm"),
    (["--wrap-angle", "360"], "--wrap-angle 360: give a unit, e.g. 360deg"),
    (["--rod-diameter", "4,0mm"], "comma"),
    (["--mu", "0.3 deg"], "--mu: give a plain number"),
    (["--n-elements", "1e3"], "--n-elements must be a whole number"),
    (["--n-elements", "\u0661\u0662\u0660"], "non-ASCII digit"),  # int() reads it as 120
])  # fmt: skip
def test_capstan_bad_options_one_line(extra, message, capsys, capture_scene):
    capture_scene("knotmech.scenes.capstan", "capstan")
    assert main(_with(CAPSTAN, extra)) == 2
    assert message in _err(capsys)


def _with(argv: list, extra: list) -> list:
    """``argv`` with the options of ``extra`` replacing its own (an option is given once)."""
    out = list(argv)
    if extra and extra[0] in out:
        i = out.index(extra[0])
        del out[i : i + 2]
    return out + extra


def test_clove_hitch_conditions_all_at_once(capsys):
    assert main(["simulate", "clove-hitch", "--loading", "asymmetric"]) == 2
    assert "--t-high, --t-low are required with --loading asymmetric" in _err(capsys)


def test_help_marks_required_and_shows_every_default(capsys):
    for scene, opts in sim.SCENE_OPTIONS.items():
        assert main(["simulate", scene, "--help"]) == 0
        out = " ".join(capsys.readouterr().out.split())
        for o in opts:
            assert o.flag in out
            assert o.default, f"{scene} {o.flag}: no default or 'required' in the help"
            if o.default != sim.REQUIRED:
                assert f"[{o.default}]" in out, (scene, o.flag)
        assert ("required:" in out) == any(o.default == sim.REQUIRED for o in opts)


def _scene_function(scene):
    import importlib

    module, func = {"capstan": ("capstan", "capstan"), "pinch": ("pinch", "pinch"),
                    "clove-hitch": ("clove_hitch", "clove_hitch"), "bend": ("bends", "bend"),
                    "centreline": ("centreline", "centreline")}[scene]  # fmt: skip
    return getattr(importlib.import_module(f"knotmech.scenes.{module}"), func)


@pytest.mark.parametrize("scene", ["capstan", "pinch", "clove-hitch", "bend", "centreline"])
def test_defaults_shown_are_the_scene_functions_defaults(scene):
    """A default shown in --help that is a quantity equals the library's default."""
    params = dict(inspect.signature(_scene_function(scene)).parameters)
    if scene == "clove-hitch":  # --loading axial: the drag's options are axial_pull's
        from knotmech.scenes.axial import axial_pull

        axial = inspect.signature(axial_pull).parameters
        params.update({o.kwarg: axial[o.kwarg] for o in sim._CLOVE_AXIAL})
    checked = 0
    for o in sim.SCENE_OPTIONS[scene]:
        default = params[o.kwarg].default
        if o.default in (None, sim.REQUIRED) or not isinstance(default, (int, float)):
            continue
        if o.kind == "count":
            assert int(o.default) == default, o.flag
        else:
            try:
                shown = parse_quantity(o.default, o.kind)
            except InputError:
                continue  # a sentence, not a value
            assert shown == pytest.approx(default, rel=1e-12), o.flag
        checked += 1
    assert (
        checked >= {"capstan": 1, "pinch": 5, "clove-hitch": 9, "bend": 7, "centreline": 5}[scene]
    )


def test_output_paths_are_checked_before_the_run(capture_scene, capsys, tmp_path):
    seen = capture_scene("knotmech.scenes.capstan", "capstan")
    for extra, message in [
        (["--json", str(tmp_path / "no" / "r.json")], "does not exist"),
        (["--plot", str(tmp_path / "fit.xyz")], "unsupported format"),
        (["--csv", str(tmp_path)], "is a directory"),
        (["--npz", str(tmp_path / "a.txt")], "unsupported format"),
    ]:
        assert main(CAPSTAN + extra) == 2
        assert message in _err(capsys)
        assert not seen  # the scene was never called


@pytest.mark.parametrize("extra", [
    ["capstan", "--wrap-angle", "180deg", "--mu", "0.5", "--rod-diameter", "4mm",
     "--post-diameter", "16mm", "--youngs-modulus", "1.26MPa", "--t-low", "1e12N"],
    ["capstan", "--wrap-angle", "180deg", "--mu", "0.5", "--rod-diameter", "4mm",
     "--post-diameter", "16mm", "--youngs-modulus", "1.26MPa", "--t-low", "0.16N",
     "--dt", "1e-12s"],
    ["capstan", "--wrap-angle", "180deg", "--mu", "0.5", "--rod-diameter", "4mm",
     "--post-diameter", "16mm", "--youngs-modulus", "1.26MPa", "--t-low", "0.16N",
     "--n-elements", "100000"],
    ["capstan", "--wrap-angle", "180deg", "--mu", "0.5", "--rod-diameter", "4mm",
     "--post-diameter", "16mm", "--youngs-modulus", "1.26MPa", "--t-low", "0.16N",
     "--pull-speed", "1e6m/s"],
    ["pinch", "--normal-load", "0.3N", "--mu", "0.3", "--dt", "1e-15s"],
    ["pinch", "--normal-load", "0.3N", "--mu", "0.3", "--pull-speed", "1e6m/s"],
    ["clove-hitch", "--loading", "free", "--t-high", "1.47N", "--dt", "1e-12s"],
    ["overhand", "--mu", "0.3", "--dt", "1e-12s"],
])  # fmt: skip
def test_runs_too_large_are_refused_up_front_with_the_estimate(extra, capsys):
    # issue 13: 1.11 PiB allocation; > 120 s with no guard. Refused before the rod is built.
    assert main(["simulate", *extra, "--no-progress"]) == 2
    err = _err(capsys)
    if any(v in extra for v in ("1e12N", "1e6m/s")):
        # a load or speed the rod cannot take may be refused by the scene's own set-up
        # checks (strain, wave speed) before the work estimate: either is one line up front
        assert "node-steps" in err or "T/EA" in err or "wave speed" in err, err
    else:
        assert "node-steps" in err and "max_node_steps" in err


def test_pinch_writes_named_files_strict_json_and_a_plot(tmp_path, capsys):
    js, cs, nz, png = (tmp_path / n for n in ("p.json", "p.csv", "p.npz", "p.png"))
    code = main(["simulate", "pinch", "--normal-load", "0.6N", "--mu", "0.32", "--no-progress",
                 "--json", str(js), "--csv", str(cs), "--npz", str(nz),
                 "--plot", str(png)])  # fmt: skip
    assert code == 0
    err = capsys.readouterr().err
    for path in (js, cs, nz, png):
        assert f"wrote {path}" in err

    def no_constants(name):
        raise AssertionError(f"non-strict JSON constant {name}")

    data = json.loads(js.read_text(), parse_constant=no_constants)
    assert data["scene"] == "pinch" and data["inputs"]["normal_load"] == 0.6
    stats = data["stats"]
    assert isinstance(stats["steps"], int) and isinstance(stats["newton_iterations"], int)
    for value in data.values():  # scalars only (a list may only hold messages: warnings)
        assert not isinstance(value, list) or all(isinstance(x, str) for x in value)
    # x = 0.019 with the default mesh: Amontons within 0.3 % (README's accuracy)
    assert 0.997 <= data["ratio"] <= 1.003
    arrays = np.load(nz)
    assert {"times", "displacement", "pull_force"} <= set(arrays.files)
    rows = cs.read_text().splitlines()
    assert rows[0] == "time_s,displacement_m,pull_force_N" and len(rows) == len(arrays["times"]) + 1
    assert png.stat().st_size > 10_000 and png.read_bytes()[:4] == b"\x89PNG"


def test_json_encoder_is_strict_and_keeps_integers():
    from knotmech import _json

    obj = {"n": np.int64(1091), "x": np.float64(0.5), "bad": float("nan"), "inf": np.inf,
           "flag": np.bool_(True), "arr": np.array([1.0, np.nan]), "t": (1, 2)}  # fmt: skip
    text = _json.dumps(obj)
    assert json.loads(text) == {"n": 1091, "x": 0.5, "bad": None, "inf": None, "flag": True,
                                "arr": [1.0, None], "t": [1, 2]}  # fmt: skip
    assert '"n": 1091,' in text  # an integer, not 1091.0
    scalars, arrays = _json.split_arrays({"a": 1, "v": np.zeros(3), "stats": {"steps": 4}})
    assert scalars == {"a": 1, "stats": {"steps": 4}} and list(arrays) == ["v"]


def test_main_help_lists_what_the_modules_say():
    import argparse
    import importlib

    for name in SUBCOMMANDS:
        parser = argparse.ArgumentParser()
        sub = parser.add_subparsers()
        importlib.import_module(f"knotmech.cli.{name}").register(sub)
        assert sub.choices[name] is not None
        helps = {a.dest: a.help for a in sub._choices_actions}
        assert helps[name] == SUMMARIES[name], name


@pytest.mark.parametrize("argv, banned", [
    (["--version"], ("numba", "scipy", "pint", "matplotlib", "knotmech.rod")),
    (["--help"], ("numba", "scipy", "pint", "matplotlib", "knotmech.rod")),
    (["hold", "clove-hitch", "--rod-diameter", "4mm", "--post-diameter", "30mm", "--mu", "0.3",
      "--load", "1.47N", "--free-end-load", "0N"], ("numba", "pint", "knotmech.rod")),
])  # fmt: skip
def test_start_up_imports_nothing_heavy(argv, banned):
    """`knotmech --help`, `--version` and `hold` from a table start in under 1 s: they do not
    import numba (the DER kernels), SciPy, pint or matplotlib (seconds together)."""
    code = ("import sys, runpy; sys.argv = ['knotmech', *sys.argv[1:]]\n"
            "try:\n    runpy.run_module('knotmech', run_name='__main__')\n"
            "except SystemExit:\n    pass\n"
            "print('MODULES', ' '.join(sorted(sys.modules)), file=sys.stderr)")  # fmt: skip
    proc = subprocess.run([sys.executable, "-c", code, *argv], capture_output=True, text=True,
                          timeout=120)  # fmt: skip
    line = next(x for x in proc.stderr.splitlines() if x.startswith("MODULES"))
    modules = set(line.split()[1:])
    for name in banned:
        assert not any(m == name or m.startswith(name + ".") for m in modules), name


def test_max_node_steps_default_shown_is_the_library_bound():
    from knotmech.scenes._common import MAX_NODE_STEPS

    for scene, opts in sim.SCENE_OPTIONS.items():
        if scene in ("bend", "centreline", *sim.TIED_BENDS, *sim.LOOP_SCENES):  # no bound
            assert "--max-node-steps" not in [o.flag for o in opts]
            continue
        (o,) = [o for o in opts if o.flag == "--max-node-steps"]
        assert float(o.default) == MAX_NODE_STEPS


_SCENE_FUNCS = {
    "capstan": ("knotmech.scenes.capstan", "capstan"),
    "two-loops": ("knotmech.scenes.capstan", "capstan_two_loops"),
    "pinch": ("knotmech.scenes.pinch", "pinch"),
    "overhand": ("knotmech.scenes.overhand", "overhand"),
    "clove-hitch": ("knotmech.scenes.clove_hitch", "clove_hitch"),
    **{name: ("knotmech.scenes.hitches", "hitch_function") for name in sim.HITCH_SCENES},
    "bend": ("knotmech.scenes.bends", "bend"),
    **{name: ("knotmech.scenes.bends", "bend") for name in sim.TIED_BENDS},
    **{name: ("knotmech.scenes.loops", "loop") for name in sim.LOOP_SCENES},
    "centreline": ("knotmech.scenes.centreline", "centreline"),
    "prusik": ("knotmech.scenes.axial", "axial_pull"),
}
_VALUE = st.text(st.sampled_from(list("0123456789.,_-+e mMNkgs/^*%\u2212\uff14")), max_size=8)


@settings(max_examples=80, deadline=None, derandomize=True,
          suppress_health_check=[HealthCheck.function_scoped_fixture])  # fmt: skip
@given(data=st.data())
def test_fuzz_option_values_exit_2_with_one_line(data, monkeypatch, capsys):
    """Any value for any option of any scene: the scene is called with SI floats, or the
    command exits 2 with one line on stderr; never a traceback."""
    scene = data.draw(st.sampled_from(sim.SCENES))
    module_name, func_name = _SCENE_FUNCS[scene]
    module = __import__(module_name, fromlist=["x"])
    seen = {}

    def stub(*args, **kwargs):
        seen.update(kwargs)
        raise InputError("stub reached")

    if func_name == "hitch_function":  # a hitch scene made from its record
        monkeypatch.setattr(module, func_name, lambda knot: stub)
    else:
        monkeypatch.setattr(module, func_name, stub)
    opts = sim.SCENE_OPTIONS[scene]
    argv = ["simulate", scene, "--no-progress"]
    if scene == "centreline":  # the file is read by the (stubbed) scene
        argv += ["knot.csv", "--ends", "fixed,pull"]
    for o in opts:
        if o.default == sim.REQUIRED:
            argv += [o.flag, {"angle": "1rad", "dimensionless": "0.3", "length": "4mm",
                              "pressure": "1MPa", "force": "1N", "density": "1100kg/m^3",
                              "choice": (o.choices or ("",))[0]}[o.kind]]  # fmt: skip
    chosen = data.draw(st.lists(st.sampled_from(opts), max_size=3, unique_by=lambda o: o.flag))
    for o in chosen:
        argv += [f"{o.flag}={data.draw(_VALUE)}"]
    code = main(argv)
    err = capsys.readouterr().err.strip()
    assert code == 2 and err.count("\n") == 0 and "Traceback" not in err, err
    if seen:
        ends = seen.pop("ends", [("fixed", "pull")])
        assert all(isinstance(v, (int, float, str, bool)) for v in seen.values())
        assert all(isinstance(e, tuple) and len(e) == 2 for e in ends)


def test_scene_warnings_are_printed_and_kept_in_the_json(monkeypatch, tmp_path, capsys):
    """A scene's result may carry ``warnings`` (its own checks): one line each on stderr,
    and a list of strings in the JSON (not an array for the NPZ)."""
    import dataclasses

    import knotmech.scenes.pinch as pinch_module  # noqa: F401 - the submodule, for the patch

    @dataclasses.dataclass
    class Fake:
        normal_load: float = 0.3
        mu: float = 0.3
        load_parameter: float = 0.01
        sliding_force: float = 0.18
        ratio: float = 1.0
        status: str = "success"
        message: str = "ok"
        stats: dict = dataclasses.field(default_factory=lambda: {"steps": 3})
        times: np.ndarray = dataclasses.field(default_factory=lambda: np.zeros(2))
        warnings: list = dataclasses.field(default_factory=lambda: ["strain: a", "step: b"])

        def summary(self):
            return {"status": self.status}

    monkeypatch.setattr(sys.modules["knotmech.scenes.pinch"], "pinch", lambda **kw: Fake())
    js, nz = tmp_path / "w.json", tmp_path / "w.npz"
    argv = ["simulate", "pinch", "--normal-load", "0.3N", "--mu", "0.3", "--json", str(js),
            "--npz", str(nz)]  # fmt: skip
    assert main(argv) == 0
    err = capsys.readouterr().err
    assert "warning: strain: a\nwarning: step: b\n" in err
    assert json.loads(js.read_text())["warnings"] == ["strain: a", "step: b"]
    assert set(np.load(nz).files) == {"times"}


def test_clove_hitch_free_prints_creep_distance_and_speed(monkeypatch, capsys):
    """`simulate clove-hitch --loading free` prints the creep over the hold's last half [m]
    and the creep speed over the criterion's window, in d/s and m/s (issue 11's done-when)."""
    import types

    class Fake(types.SimpleNamespace):  # read as a mapping by the CLI's scalar summary
        def keys(self):
            return vars(self).keys()

        def __getitem__(self, key):
            return vars(self)[key]

    fake = Fake(
        loading="free", status="success", t_high=1.47, t_low=0.0, creep=1.23e-11,
        verdict="hold", creep_speed_d=1.6e-9, creep_speed=6.5e-12, creep_window=0.5,
        warnings=[], message="",
    )  # fmt: skip
    module = __import__("knotmech.scenes.clove_hitch", fromlist=["x"])
    monkeypatch.setattr(module, "clove_hitch", lambda **kw: fake)
    code = main(["simulate", "clove-hitch", "--loading", "free", "--t-high", "1.47N",
                 "--mu", "0.3", "--no-progress"])  # fmt: skip
    out = capsys.readouterr().out
    assert code == 0, out
    assert (
        "creep 1.23e-11 m over the hold's last half, 1.6e-09 d/s (6.5e-12 m/s) over the last" in out
    )
    assert "0.5 s; verdict: HOLD" in out

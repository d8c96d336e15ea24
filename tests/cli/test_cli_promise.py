"""The command line's promise, tested with hypothesis over every subcommand (issue 27).

For any argument list a user could type (units right and wrong, magnitudes from 1e-12 to
1e12 and beyond, negative, NaN, infinity, empty, unicode, options given twice, output
paths that collide or cannot be written), ``knotmech`` either

- exits 2 with exactly one line on stderr and no traceback (a refusal), or
- exits 0 or 1 with an honest result: no NaN where a number is printed or written as
  JSON, and no verdict and no ``success`` from a DER run that did not happen,

within a bounded time (:data:`BOUND_S` per command). Every call goes through the entry
point :func:`knotmech.cli.main.main`, in-process.

What the DER runs are here. The solver :func:`knotmech.rod.simulate` is replaced by
:func:`_stub_simulate`: it builds the solver for the system it is given and records the
start frame, exactly as the real one does, then stops with status ``"failed"`` before its
first step. So every scene is set up, checked and built for real (the input checks, the
cost and memory guards, the curves and the contacts), and every accepted run is one that
did not happen: ``simulate`` must say ``failed`` and exit 1, ``hold --simulate`` must not
answer from the DER. What this does not cover: the numbers of runs that do happen (the
scene and golden tests do), and runs that fail later than their first step. The memory
bound is lowered to :data:`TEST_MEMORY` so that an accepted set-up stays small on a shared
machine (the refusal above it is the same code). ``validate`` runs its cases through a stub
as well (its option handling, case lookup, output folder and index page are real).

Seeded by default (``@seed(27)``, about 200 examples, under a minute); a campaign of
more than 2,000 examples under ``-m slow``.
"""

from __future__ import annotations

import contextlib
import io
import json
import math
import re
import signal
import time
from dataclasses import replace

import pytest
from hypothesis import HealthCheck, given, seed, settings
from hypothesis import strategies as st

from knotmech.cli.main import main
from knotmech.cli.simulate import BEND_KINDS, SCENE_OPTIONS, SCENES
from knotmech.errors import SolverError
from knotmech.knots import names as knot_names
from knotmech.materials import material_names
from knotmech.units import HINT_UNITS

#: [s] the longest one command may take with the solver stubbed (its set-up only)
BOUND_S = 30.0
#: [bytes] the memory bound of every scene during these tests (the library's is 4 GB)
TEST_MEMORY = 3e8
STUB_MESSAGE = "stopped by the property test's stub before its first step"


# ------------------------------------------------------------------ the stubbed solver


def _stub(real):
    """``real`` (knotmech.rod.simulate) cut to its start frame, then status "failed"."""

    def simulate(system, state0=None, *, t_end, dt, options=None, throw=None, **kwargs):
        from knotmech.rod import SolverOptions

        opts = SolverOptions() if options is None else options
        t0 = 0.0 if state0 is None else float(state0.t)
        res = real(system, state0, t_end=t0, dt=dt, options=replace(opts, throw=False),
                   throw=False, **kwargs)  # fmt: skip
        res.status, res.message = "failed", STUB_MESSAGE
        if opts.throw if throw is None else throw:
            err = SolverError(STUB_MESSAGE, state=res.final_state)
            err.result = res
            raise err
        return res

    return simulate


def _stub_case(name, *, quick=True, out_dir, root=None, **options):
    """A validation case that passes at once (``knotmech.cli.validate.run_case``)."""
    return {"name": name, "verdict": "pass", "figures": [], "numbers": {}, "checks": {},
            "notes": [], "summary": "", "quick": quick, "seconds": 0.0}  # fmt: skip


@pytest.fixture(scope="module")
def stubbed(tmp_path_factory):
    """The solver and the validation cases stubbed; a folder for the outputs."""
    import knotmech.cli.validate as validate
    import knotmech.rod as rod
    import knotmech.rod.solver as solver
    import knotmech.scenes._common as common
    import knotmech.scenes.pinch as pinch

    fake = _stub(solver.simulate)
    with pytest.MonkeyPatch.context() as mp:
        for module in (rod, solver, pinch):
            mp.setattr(module, "simulate", fake)
        mp.setattr(common, "MAX_MEMORY", TEST_MEMORY)
        mp.setattr(validate, "run_case", _stub_case)
        folder = tmp_path_factory.mktemp("cli_promise")
        _recordings(folder)
        mp.chdir(folder)
        _warm_up()
        with _address_space_cap(EXTRA_MEMORY):
            yield folder


#: address space an example may add to the warmed process [bytes]: an example that builds
#: a huge array fails with MemoryError and its command is shown, where without the cap the
#: CI machine's OOM killer ended the whole slow suite twice (a 7e12-node curve, a 6.6e8-
#: point tail) and said nothing of which command it was
EXTRA_MEMORY = 6 * 2**30


@contextlib.contextmanager
def _address_space_cap(extra: int):
    """RLIMIT_AS at the process's present virtual size plus ``extra`` bytes, restored on
    exit (no cap where ``resource`` or /proc is missing)."""
    try:
        import resource

        with open("/proc/self/status", encoding="ascii") as fh:
            size = next(int(x.split()[1]) * 1024 for x in fh if x.startswith("VmSize"))
        old = resource.getrlimit(resource.RLIMIT_AS)
        cap = size + extra if old[1] == resource.RLIM_INFINITY else min(size + extra, old[1])
        resource.setrlimit(resource.RLIMIT_AS, (cap, old[1]))
    except (ImportError, OSError, StopIteration, ValueError):
        yield
        return
    try:
        yield
    finally:
        resource.setrlimit(resource.RLIMIT_AS, old)


def _warm_up() -> None:
    """Each scene's working command once, without the alarm: numba compiles the kernels on
    a fresh machine (tens of seconds, more under load), which is not the command's run
    time that :data:`BOUND_S` bounds (found on a fresh clone: the first capstan example
    timed out while compiling)."""
    for scene in SCENES:
        argv = ["simulate", scene, "--no-progress", *_BASES.get(scene, _BASES["hitch"])]
        with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
            main(argv)


def _recordings(folder):
    from knotmech.cli.diagnose import template_text

    for kind in ("capstan_hold", "capstan_pull", "pinch", "tension_profile"):
        (folder / f"{kind}.csv").write_text(template_text(kind), encoding="utf-8")
    (folder / "broken.csv").write_text("# kind: pinch\nx,y\n1,\u00e9\n", encoding="utf-8")
    (folder / "knot.csv").write_text(
        "".join(f"{math.cos(a / 7):.6f}, {math.sin(a / 7):.6f}, 0\n" for a in range(20)),
        encoding="utf-8",
    )
    (folder / "adir").mkdir()


# ------------------------------------------------------------------ strategies

_TYPICAL = {
    "length": ("4mm", "30mm", "0.5m", "6mm"),
    "force": ("0.3N", "1.47N", "200N", "0.069N"),
    "angle": ("180deg", "2turn", "6.28rad"),
    "pressure": ("1.26MPa", "0.25GPa"),
    "mass": ("150g",),
    "time": ("2ms", "0.5s", "10ms"),
    "velocity": ("20mm/s", "1cm/s"),
    "density": ("1160kg/m^3", "1.1g/cm^3"),
    "bending_stiffness": ("1e-5N*m^2",),
    "dimensionless": ("0.3", "0.5", "1"),
    "count": ("100", "51", "20"),
}
_UNITS = ("", "mm", "m", "km", "um", "\u00b5m", "in", "N", "kN", "gf", "deg", "\u00b0", "rad",
          "turn", "pi", "Pa", "MPa", "GPa", "g", "kg", "s", "ms", "min", "mm/s", "m/s",
          "kg/m^3", "g/cm^3", "N*m^2", "N*mm^2", " mm", "furlong", "m/s^2", "mm^2", "%",
          "N/m", "1/s")  # fmt: skip
_SPECIAL = (0.0, -0.0, -1.0, 1e-12, 1e12, -1e12, 1e-300, 1e300, math.nan, math.inf, -math.inf)

_numbers = st.one_of(
    st.sampled_from(_SPECIAL),
    st.floats(1e-12, 1e12),
    st.floats(-1e12, -1e-12),
    st.integers(-(10**6), 10**6),
)
_number_text = st.one_of(_numbers.map(lambda x: f"{x:.6g}"), _numbers.map(repr))
_hostile = st.one_of(
    st.builds(lambda x, u: f"{x}{u}", _number_text, st.sampled_from(_UNITS)),
    st.sampled_from(
        (
            "",
            " ",
            "-",
            "--",
            "nan",
            "inf",
            "1e999",
            "0x10",
            "1_000",
            "4 mm",
            "4mm4mm",
            "\u22124mm",
            "\uff14mm",
            "1" * 150,
            "1/0",
            "2**1000mm",
            "4mm\n",
            "\x00",
        )
    ),  # fmt: skip
    st.text(max_size=8),
)


_RIGHT_UNIT = {**HINT_UNITS, "dimensionless": "", "count": "", "choice": ""}


def _pick(often, rarely, one_in: int) -> st.SearchStrategy:
    """``rarely`` once in ``one_in`` draws, else ``often``."""
    return st.tuples(st.integers(1, one_in), often, rarely).map(
        lambda t: t[2] if t[0] == 1 else t[1]
    )


_PATHS = ("out.json", "out.png", "out.svg", "out.csv", "out.npz", "out.txt", "out", "-", "",
          "\u00fcber.json", "nodir/x.json", "adir", "capstan_hold.csv", "same.json")  # fmt: skip
_paths = st.sampled_from(_PATHS)


#: a command line each subcommand accepts (the module docstrings' examples); the
#: strategies mutate these, so that most examples reach deep into the checks
_BASES = {
    "capstan": ["--wrap-angle", "180deg", "--mu", "0.5", "--rod-diameter", "4mm",
                "--post-diameter", "16mm", "--youngs-modulus", "1.26MPa", "--t-low", "0.16N"],
    "two-loops": [],
    "pinch": ["--normal-load", "0.3N", "--mu", "0.5"],
    "overhand": ["--turns", "2", "--mu", "0.3", "--n-nodes", "151", "--pull-time", "5s",
                 "--dt", "5ms"],
    "clove-hitch": ["--loading", "free", "--t-high", "1.47N", "--mu", "0.3"],
    "hitch": ["--loading", "free", "--t-high", "0.1N", "--mu", "0.6", "--hold-time", "0.4s"],
    "bend": ["--kind", "granny", "--mu", "1"],
    "centreline": ["knot.csv", "--unit", "mm", "--ends", "free,pull", "--rod-diameter", "4mm",
                   "--youngs-modulus", "1MPa", "--density", "1100kg/m^3", "--mu", "1",
                   "--pull-distance", "16mm"],
    "hold": ["--rod-diameter", "6mm", "--post-diameter", "40mm", "--mu", "0.4", "--load",
             "200N", "--material", "nylon"],
    "diagnose": ["pinch.csv", "--json", "out.json"],
    "validate": ["--quick", "--out", "vout", "--only", "capstan_decay"],
}  # fmt: skip


def _pairs(tokens: list[str]) -> list[list[str]]:
    """``tokens`` as groups: an option with its value(s), or a lone positional."""
    groups: list[list[str]] = []
    for token in tokens:
        if token.startswith("--") or not groups or not groups[-1][0].startswith("--"):
            groups.append([token])
        else:
            groups[-1].append(token)
    return groups


@st.composite
def _mutated(draw, head: list[str], base: list[str], options: dict, extra) -> list[str]:
    """``head`` + ``base`` after 0 to 3 mutations: an option set to a drawn value (most
    often a hostile one), an option removed, one of ``extra`` (flags without values,
    outputs) added, an option given twice; each option written ``--flag value`` or
    ``--flag=value``."""
    groups = _pairs(base)
    for _ in range(draw(st.integers(0, 3))):
        what = draw(st.sampled_from(("set",) * 6 + ("drop", "extra", "extra", "twice")))
        if what == "set" and options:
            flag = draw(st.sampled_from(sorted(options)))
            groups = [g for g in groups if g[0] != flag] + [[flag, draw(options[flag])]]
        elif what == "drop" and groups:
            groups.pop(draw(st.integers(0, len(groups) - 1)))
        elif what == "extra":
            groups.append(draw(extra))
        elif what == "twice" and groups:
            groups.append(list(groups[draw(st.integers(0, len(groups) - 1))]))
    groups = draw(st.permutations(groups))
    argv = list(head)
    for g in groups:
        joined = len(g) == 2 and g[0].startswith("--") and draw(st.booleans())
        argv += [f"{g[0]}={g[1]}"] if joined else g
    return argv


_OUT = {"--json": "out.json", "--csv": "out.csv", "--npz": "out.npz", "--plot": "out.png"}


def _outputs(flags) -> st.SearchStrategy:
    """One output: its plain path (2 in 3) or any of :data:`_PATHS`."""
    return st.sampled_from(flags).flatmap(
        lambda f: _pick(st.just(_OUT[f]), _paths, 3).map(lambda p: [f, p])
    )


def _choice(typical, hostile) -> st.SearchStrategy:
    return _pick(st.sampled_from(typical), st.sampled_from(hostile), 4)


def _hostile_value(kind: str, choices=None) -> st.SearchStrategy:
    """Most often a hostile value of ``kind``, sometimes a typical one."""
    typical = st.sampled_from(choices or _TYPICAL.get(kind, ("1",)))
    right = st.builds(lambda x: f"{x}{_RIGHT_UNIT.get(kind, '')}", _number_text)
    return _pick(st.one_of(right, right, _hostile), typical, 4)


def _simulate_argv(scene: str) -> st.SearchStrategy:
    options = {
        o.flag: _hostile_value(o.kind, o.choices or (BEND_KINDS if o.kwarg == "kind" else None))
        for o in SCENE_OPTIONS[scene]
    }
    flags = [["--no-progress"]]
    if scene in ("capstan", "two-loops"):
        options["--mode"] = _choice(("pull", "hold"), ("Hold", ""))
        flags.append(["--centreline-friction"])
    elif scene == "overhand":
        options["--params"] = _choice(("imc", "coated"), ("x",))
    elif scene == "centreline":
        options["--ends"] = st.sampled_from(("pull,free", "pull,pull", "fixed,pull", "free",
                                             "x,y", ""))  # fmt: skip
        options["--unit"] = _choice(("m", "cm", "mm"), ("in",))
    elif scene not in ("pinch", "bend"):
        options["--loading"] = _choice(("symmetric", "asymmetric", "free", "pull"), ("none",))
    extra = st.one_of(st.sampled_from(flags), _outputs(tuple(_OUT)))
    base = _BASES.get(scene, _BASES["hitch"])
    head = ["simulate", scene, "--no-progress"]
    if scene == "centreline":  # the file first: another file, or the knot
        file = st.sampled_from(("knot.csv", "knot.csv", "missing.csv", "broken.csv", "adir",
                                "pinch.csv"))  # fmt: skip
        return file.flatmap(lambda f: _mutated(head + [f], base[1:], options, extra))
    return _mutated(head, base, options, extra)


BEND_NAMES = ("reef", "granny", "thief", "grief")
_KNOTS = (*knot_names(), "reef-knot", "", "\u00e9", "clove_hitch")


def _hold_argv() -> st.SearchStrategy:
    materials = (*material_names(), "wood", "")
    options = {
        "--rod-diameter": _hostile_value("length"),
        "--post-diameter": _hostile_value("length"),
        "--mu": _hostile_value("dimensionless"),
        "--mu-rr": _hostile_value("dimensionless"),
        "--load": _hostile_value("force"),
        "--free-end-load": _hostile_value("force"),
        "--wrap-angle": _hostile_value("angle"),
        "--material": _pick(st.sampled_from(materials), _hostile, 4),
        "--youngs-modulus": _hostile_value("pressure"),
        "--bending-scale": _hostile_value("dimensionless", ("1", "0.01", "0.3")),
        "--creep-limit": _hostile_value("dimensionless", ("1e-3", "0.01")),
        "--phase-table": st.sampled_from(("missing.json", "pinch.csv", "adir", "")),
    }
    extra = st.one_of(st.sampled_from((["--simulate"], ["--verbose"])),
                      _outputs(("--json", "--plot")))  # fmt: skip
    knot = _pick(st.sampled_from(knot_names()), st.sampled_from(_KNOTS), 8)
    return knot.flatmap(lambda k: _mutated(["hold", k], _hold_base(k), options, extra))


def _hold_base(knot: str) -> list[str]:
    """The base of ``hold``: the capstan's has a wrap angle, a bend's no post."""
    base = list(_BASES["hold"])
    if knot == "capstan":
        base += ["--wrap-angle", "360deg"]
    elif knot in BEND_NAMES:
        k = base.index("--post-diameter")
        del base[k : k + 2]
    return base


_RECORDINGS = ("capstan_hold.csv", "capstan_pull.csv", "pinch.csv", "tension_profile.csv",
               "broken.csv", "missing.csv", "adir", "knot.csv")  # fmt: skip


def _diagnose_argv() -> st.SearchStrategy:
    options = {
        "--template": st.sampled_from(("pinch", "capstan_hold", "knot", "")),
        "--baseline": st.sampled_from(("closed-form", "der", "x")),
        "--seed": _hostile_value("count", ("0", "7")),
        "--alpha": _hostile_value("dimensionless", ("0.01", "0.05")),
        "--json": _paths,
        "--plot": _paths,
    }
    extra = st.sampled_from(_RECORDINGS).map(lambda r: [r])
    return _mutated(["diagnose"], _BASES["diagnose"], options, extra)


def _validate_argv() -> st.SearchStrategy:
    options = {
        "--out": st.sampled_from(("vout", "out.json", "adir", "", "nodir/deeper")),
        "--only": st.sampled_from(("capstan_decay", "coating", "nope", "", "\u00e9", "--list")),
        "--scheduler": st.sampled_from(("tcp://127.0.0.1:1", "", "\u00e9")),
        "--cases-dir": st.sampled_from(("adir", "missing", "pinch.csv", "")),
    }
    extra = st.sampled_from((["--full"], ["--list"], ["--quick"]))
    return _mutated(["validate"], _BASES["validate"], options, extra)


# ------------------------------------------------------------------ the promise

_NAN = re.compile(r"(?<![A-Za-z])nan(?![A-Za-z])", re.IGNORECASE)


def _strict_json(text: str):
    def refuse(token):
        raise AssertionError(f"JSON holds {token}")

    return json.loads(text, parse_constant=refuse)


class _TooLong(Exception):
    """Raised by the alarm in :func:`_call` when a command runs past :data:`BOUND_S`."""


def _alarm(signum, frame):
    raise _TooLong(f"still running after {BOUND_S:g} s")


def _call(argv: list[str]) -> tuple[int, str, str, float]:
    """(exit status, stdout, stderr, seconds) of ``knotmech argv``, stopped by an alarm
    (a :class:`_TooLong` failure) after :data:`BOUND_S` seconds."""
    out, err = io.StringIO(), io.StringIO()
    start = time.perf_counter()
    previous = signal.signal(signal.SIGALRM, _alarm)
    signal.setitimer(signal.ITIMER_REAL, BOUND_S)
    try:
        with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
            code = main(list(argv))
    finally:
        signal.setitimer(signal.ITIMER_REAL, 0)
        signal.signal(signal.SIGALRM, previous)
    return code, out.getvalue(), err.getvalue(), time.perf_counter() - start


def _output(argv: list[str], flag: str) -> str | None:
    """The value given to ``flag`` in ``argv`` (None when absent)."""
    for k, token in enumerate(argv):
        if token == flag and k + 1 < len(argv):
            return argv[k + 1]
        if token.startswith(flag + "="):
            return token.split("=", 1)[1]
    return None


def check_promise(argv: list[str], folder) -> None:
    """Run ``argv`` and assert the promise of the module docstring."""
    code, out, err, seconds = _call(argv)
    shown = " ".join(argv)
    assert seconds < BOUND_S, f"{shown}: {seconds:.1f} s"
    assert "Traceback" not in out + err, f"{shown}:\n{err}"
    assert code in (0, 1, 2), f"{shown}: exit {code}"
    if code == 2:
        lines = err.strip().splitlines()
        assert len(lines) == 1 and lines[0].startswith("knotmech"), f"{shown}: {err!r}"
        return
    if argv[0] == "simulate":  # every DER run stopped at once: never a success, never a verdict
        assert code == 1, f"{shown}: exit {code} from a run that did not happen\n{out}"
        assert "status failed" in out or "failed" in err, f"{shown}:\n{out}\n{err}"
        for word in ("HOLDS", "SLIPS", "verdict: "):
            assert word not in out, f"{shown}: a verdict from a run that did not happen\n{out}"
    if argv[0] == "hold":
        assert "DER-simulation" not in out.split("warning")[0], f"{shown}:\n{out}"
        if "--json" not in argv or _output(argv, "--json") != "-":
            assert not _NAN.search(out), f"{shown}: NaN printed\n{out}"
    path = _output(argv, "--json")
    if path == "-":
        _strict_json(out)
    elif path and (folder / path).is_file() and argv[0] in ("simulate", "hold", "diagnose"):
        data = _strict_json((folder / path).read_text(encoding="utf-8"))
        if argv[0] == "simulate":
            assert data.get("status") != "success", f"{shown}: {data.get('status')}"
        (folder / path).unlink()  # the next example starts without it


_QUICK = settings(
    deadline=None,
    database=None,
    suppress_health_check=[
        HealthCheck.too_slow,
        HealthCheck.data_too_large,
        HealthCheck.function_scoped_fixture,
    ],  # fmt: skip
)
#: the campaign is seeded too (derandomize): CI is a gate, and the same 2,665 examples run
#: on every machine; explore new seeds with --hypothesis-seed=N
_CAMPAIGN = settings(_QUICK, derandomize=True)

#: examples per scene / command in the default suite (seeded) and in the campaign
_SIMULATE_N, _SIMULATE_SLOW = 12, 150


@pytest.mark.parametrize("scene", SCENES)
@settings(_QUICK, max_examples=_SIMULATE_N)
@given(data=st.data())
@seed(27)
def test_simulate_keeps_the_promise(stubbed, scene, data):
    check_promise(data.draw(_simulate_argv(scene)), stubbed)


@settings(_QUICK, max_examples=60)
@given(argv=_hold_argv())
@seed(27)
def test_hold_keeps_the_promise(stubbed, argv):
    check_promise(argv, stubbed)


@settings(_QUICK, max_examples=15)
@given(argv=_diagnose_argv())
@seed(27)
def test_diagnose_keeps_the_promise(stubbed, argv):
    check_promise(argv, stubbed)


@settings(_QUICK, max_examples=25)
@given(argv=_validate_argv())
@seed(27)
def test_validate_keeps_the_promise(stubbed, argv):
    check_promise(argv, stubbed)


@pytest.mark.slow
@pytest.mark.parametrize("scene", SCENES)
@settings(_CAMPAIGN, max_examples=_SIMULATE_SLOW)
@given(data=st.data())
def test_campaign_simulate(stubbed, scene, data):
    check_promise(data.draw(_simulate_argv(scene)), stubbed)


@pytest.mark.slow
@settings(_CAMPAIGN, max_examples=600)
@given(argv=_hold_argv())
def test_campaign_hold(stubbed, argv):
    check_promise(argv, stubbed)


@pytest.mark.slow
@settings(_CAMPAIGN, max_examples=60)
@given(argv=_diagnose_argv())
def test_campaign_diagnose(stubbed, argv):
    check_promise(argv, stubbed)


@pytest.mark.slow
@settings(_CAMPAIGN, max_examples=200)
@given(argv=_validate_argv())
def test_campaign_validate(stubbed, argv):
    check_promise(argv, stubbed)


@pytest.mark.slow
@pytest.mark.parametrize("out", ["tour_out", "adir", "pinch.csv", "", "nodir/deeper"])
def test_tour_keeps_the_promise(stubbed, out):
    check_promise(["tour", "--out", out], stubbed)


# ------------------------------------------------------------------ regressions found by it


def test_hold_verbose_on_a_bend_names_no_post(capsys):
    """Found by the campaign: ``hold reef --verbose`` raised KeyError 'post_diameter' (a bend
    has no post and no free end)."""
    argv = ["hold", "reef", "--rod-diameter", "6mm", "--mu", "0.4", "--load", "200N",
            "--material", "nylon", "--verbose"]  # fmt: skip
    assert main(argv) == 0
    out = capsys.readouterr().out
    assert "reef: rope d = 6 mm, mu = 0.4, load = 200 N, material nylon" in out


@pytest.mark.parametrize("argv", [
    ["diagnose", "pinch.csv", "--json", "-"],
    ["simulate", "bend", "--kind", "granny", "--mu", "1", "--json", "-"],
    ["simulate", "pinch", "--normal-load", "0.3N", "--mu", "0.5", "--csv=-"],
])  # fmt: skip
def test_a_dash_for_a_file_output_is_refused(stubbed, argv):
    """Found by the campaign: ``--json -`` wrote a file named ``-`` (and said so) where
    ``hold --json -`` prints to standard output; now one line before any work."""
    code, out, err, _ = _call(argv)
    assert code == 2 and out == ""
    assert err.strip().endswith("-: this output is a file, not standard output; give a file name")
    assert not (stubbed / "-").exists()


@pytest.mark.parametrize(
    "argv",
    [
        # found by the campaign on the merged tree: a ZeroDivisionError in the rod frames of
        # a capstan on a 1e297 m post (now refused above 1000 rod diameters, as the hitches)
        ["simulate", "capstan", "--no-progress", "--wrap-angle", "180deg", "--mu", "0.5",
         "--rod-diameter", "4mm", "--youngs-modulus", "1.26MPa", "--t-low", "0.16N",
         "--post-diameter", "1e+300mm"],
        # and an UnboundLocalError in the tied bends' topology check of a run with no frame
        ["simulate", "bend", "--no-progress", "--mu", "1", "--kind", "sheet-bend"],
        # session 12: a 1e12 mm rod on the default 30 mm post built a start curve of 7e12
        # nodes (54 TiB) before any size check; now refused above 10 post diameters
        ["simulate", "cow-hitch", "--no-progress", "--loading", "free", "--t-high", "0.1N",
         "--mu", "0.6", "--hold-time", "0.4s", "--rod-diameter", "1e+12mm"],
        # and a settle of 1e-12 s with the run cut at its start frame
        ["simulate", "cow-hitch", "--no-progress", "--loading", "free", "--t-high", "0.1N",
         "--mu", "0.6", "--hold-time", "0.4s", "--settle-time", "1e-12s"],
        # session 13: a 2.7e5 m clove hitch sampled its straight tails at 0.05 d (6.6e8
        # points, 16 GB) before any size check: the CI's slow suite was OOM-killed again
        ["simulate", "clove-hitch", "--no-progress", "--loading", "free", "--t-high",
         "1.47N", "--mu", "0.3", "--rod-length", "2.67194455e+08mm"],
    ],
)  # fmt: skip
def test_campaign_findings_keep_the_promise(stubbed, argv):
    check_promise(argv, stubbed)
    code, _, err, _ = _call(argv)
    expected = 2 if ("capstan" in argv or "clove-hitch" in argv or "1e+12mm" in argv) else 1
    assert code == expected
    if "capstan" in argv:
        assert "post_diameter / rod_diameter = 2.5e+299 is above 1000" in err
    elif "clove-hitch" in argv:
        assert "a straight tail of 1.34e+05 m is 3.34e+07 rod diameters, above 10000" in err
    elif code == 2:
        assert "rod_diameter / post_diameter = 3.33e+10 is above 10" in err

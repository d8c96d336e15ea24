"""The API's promise for the closed forms, tested with hypothesis (issue 27).

Every public function of :mod:`knotmech.analytic` (discovered from its ``__all__``) and
:func:`knotmech.units.parse_quantity`, called with arguments that mix valid values and
hostile ones (magnitudes 1e-12 to 1e12 of either sign, zero, NaN, infinities, bools,
strings, unicode, lists, None, complex numbers), either

- returns finite numbers (every number in the result, arrays and dataclass fields
  included: never a NaN silently; +inf only where documented, a self-locking hitch, see
  :data:`INFINITY_MEANS_LOCKED`; NaN only in entries a result flags as not applicable), or
- raises :class:`knotmech.errors.InputError` whose message is one line and names an
  argument of the call;

no other exception escapes, numpy emits no overflow or invalid-value RuntimeWarning (a NaN
masked inside a formula is a silently wrong answer), and every call returns within
:data:`CALL_SECONDS`. Deterministic companions: every knot name, and array arguments
that do not broadcast; and every one-number argument of 13 public scene functions
(:data:`SCENE_CALLS`) given a list, an array, a string or a bool, which must give one
InputError line naming it before any run (the solver is stubbed: nothing runs).

The default run is derandomized and small (20 examples per function, about 20 s in
all); ``-m slow`` runs a random campaign of 100 examples per function and 600 texts for
``parse_quantity`` (about 5,000 calls, about 1 min). What it found in ``hitch.py``
(a message naming no argument, bare broadcast ValueErrors, an infinite ideal ratio at
mu >= 57) is fixed (session 13).
"""

from __future__ import annotations

import dataclasses
import functools
import inspect
import time
import warnings

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

import knotmech.analytic as analytic
from knotmech.analytic.hitch import KNOTS
from knotmech.analytic.registry import REGISTRY
from knotmech.errors import InputError
from knotmech.units import KINDS, parse_quantity

CALL_SECONDS = 5.0  #: [s] bound on one call (the slowest valid call takes ~10 ms)

#: public functions of knotmech.analytic, from its __all__
FUNCTIONS = {
    name: getattr(analytic, name)
    for name in analytic.__all__
    if inspect.isfunction(getattr(analytic, name))
}

#: valid keyword arguments of the functions the registry has no sample for
SAMPLES = {
    "capstan_ratio_thick": {"mu": 0.3, "wrap_angle": 2.0, "D_over_d": 5.0},
    "capstan_end_factors": {"mu": 0.5, "D_over_d": 1.0},
    "capstan_tension_profile": {"s": 0.01, "high_tension": 10.0, "mu": 0.3, "radius": 0.02},
    "mu_from_mu_eff": {"mu_effective": 0.2, "D_over_d": 5.0},
    "mu_from_capstan_test": {"high_tension": 10.0, "low_tension": 2.0, "wrap_angle": 3.0},
    "capstan_ratio_bending": {
        "mu": 0.3,
        "wrap_angle": 3.0,
        "bending_stiffness": 1e-5,
        "low_tension": 1.0,
        "high_tension": 2.0,
        "radius": 0.02,
    },
    "bending_parameter": {"bending_stiffness": 1e-5, "tension": 1.0, "radius": 0.02},
    "liftoff_angle": {"epsilon": 0.5},
    "capstan_ratio_nonlinear": {
        "low_tension": 1.0,
        "wrap_angle": 3.0,
        "friction_coefficient": 0.3,
        "friction_exponent": 0.8,
        "radius": 0.02,
    },
    "capstan_high_tension_nonlinear": {
        "low_tension": 1.0,
        "wrap_angle": 3.0,
        "friction_coefficient": 0.3,
        "friction_exponent": 0.8,
        "radius": 0.02,
    },
    "hold_verdict": {
        "knot": "clove-hitch",
        "rod_diameter": 4e-3,
        "post_diameter": 30e-3,
        "mu": 0.3,
        "load": 10.0,
        "free_end_load": 0.5,
    },
    "hitch_holds": {"knot": "clove-hitch", "high_tension": 10.0, "low_tension": 1.0, "mu": 0.3},
    "hitch_critical_mu": {"knot": "clove-hitch", "high_tension": 10.0, "low_tension": 1.0},
    "hitch_margin": {"knot": "clove-hitch", "high_tension": 10.0, "low_tension": 1.0, "mu": 0.3},
    "ideal_hitch_ratio": {"knot": "clove-hitch", "mu": 0.3},
    "thick_hitch_ratio": {
        "knot": "clove-hitch",
        "mu": 0.3,
        "rod_diameter": 4e-3,
        "post_diameter": 30e-3,
    },
    "nip_factor": {"rod_diameter": 4e-3, "support_diameter": 30e-3},
    "capillary_number": {"viscosity": 1e-3, "speed": 5e-3, "surface_tension": 0.0343},
    "pinch_amontons_applies": {
        "normal_force": 1.0,
        "youngs_modulus": 1.3e6,
        "rod_diameter": 4e-3,
        "pinch_diameter": 4e-3,
    },
    "overhand_knot": {
        "end_to_end_shortening": 0.3,
        "turns": 2,
        "mu": 0.3,
        "rod_radius": 1e-3,
        "bending_stiffness": 1e-5,
    },
    "braid_contact_force_per_length": {
        "wavenumber": 100.0,
        "rod_radius": 1e-3,
        "bending_stiffness": 1e-5,
    },
}


def _names():
    """The functions' names, sorted."""
    return sorted(FUNCTIONS)


def _sample(name: str) -> dict:
    return dict(REGISTRY[name].sample) if name in REGISTRY else dict(SAMPLES[name])


def test_every_public_function_has_a_valid_sample_that_returns_finite_numbers():
    """The harness covers all of ``__all__``, and each sample is a valid call."""
    assert len(FUNCTIONS) >= 40
    for name, func in FUNCTIONS.items():
        _assert_finite(name, func(**_sample(name)))


def test_every_knot_name_gives_an_answer_or_a_message_naming_knot():
    """Each function of a knot, at each name of KNOTS: finite numbers or 'knot ...'."""
    for name, func in FUNCTIONS.items():
        if "knot" not in inspect.signature(func).parameters:
            continue
        for knot in KNOTS:
            try:
                _assert_finite(name, func(**{**_sample(name), "knot": knot}))
            except InputError as e:
                assert "knot" in str(e), f"{name}(knot={knot!r}): {e}"


def _numeric_arguments(name):
    return [p for p, v in _sample(name).items() if isinstance(v, (int, float)) and p != "turns"]


@pytest.mark.parametrize(
    "name",
    [n for n in sorted(FUNCTIONS) if len(_numeric_arguments(n)) >= 2 and n != "hold_verdict"],
)
def test_arrays_that_do_not_broadcast_are_refused_naming_both(name):
    """Two array arguments of shapes (2,) and (3,): InputError naming the two."""
    first, second = _numeric_arguments(name)[:2]
    sample = _sample(name)
    kwargs = {**sample, first: [sample[first]] * 2, second: [sample[second]] * 3}
    with pytest.raises(InputError) as e:
        FUNCTIONS[name](**kwargs)
    assert first in str(e.value) and second in str(e.value) and "broadcast" in str(e.value)


# ------------------------------------------------------------------ strategies
_magnitudes = st.floats(1e-12, 1e12)
_hostile = st.one_of(
    _magnitudes,
    _magnitudes.map(lambda x: -x),
    st.sampled_from([0.0, -0.0, float("nan"), float("inf"), -float("inf"), 0, 1, -1]),
    st.booleans(),
    st.sampled_from([np.bool_(True), np.float32("nan"), np.int64(3), np.array(2.0)]),
    st.sampled_from(["0.3", "4mm", "nan", "", " ", "\u0661", "\uff13", "1e400", "clove-hitch"]),
    st.text(max_size=6),
    st.lists(st.one_of(_magnitudes, st.just(float("nan")), st.booleans()), max_size=3),
    st.lists(_magnitudes, min_size=1, max_size=3).map(np.array),
    st.lists(_magnitudes, min_size=2, max_size=3),
    st.none(),
    st.complex_numbers(max_magnitude=10.0),
)


def _arguments(name: str, data) -> dict:
    """Keyword arguments of ``name``: the valid sample with one or two of them hostile.

    One argument at a time is the sharpest probe (the others cannot refuse first); a
    second one, half the time, probes the interplay (two lists that do not broadcast).
    """
    sample = _sample(name)
    params = inspect.signature(FUNCTIONS[name]).parameters
    kwargs = {p: sample[p] for p in params if p in sample}
    names = list(params)
    for _ in range(data.draw(st.integers(1, 2), label="how many hostile")):
        target = data.draw(st.sampled_from(names), label="argument")
        hostile = _hostile
        if target == "knot":
            hostile = st.one_of(st.sampled_from(sorted(KNOTS)), _hostile)
        kwargs[target] = data.draw(hostile, label=target)
    return kwargs


# ------------------------------------------------------------------ the promise
def _numbers(result):
    """Every float in ``result`` (arrays, tuples, dataclasses, dicts), as one flat array."""
    if result is None or isinstance(result, (str, bool, np.bool_)):
        return []
    if dataclasses.is_dataclass(result):
        return [x for f in dataclasses.fields(result) for x in _numbers(getattr(result, f.name))]
    if isinstance(result, dict):
        return [x for v in result.values() for x in _numbers(v)]
    if isinstance(result, (list, tuple)):
        return [x for v in result for x in _numbers(v)]
    arr = np.asarray(result)
    if arr.dtype.kind in "iuf":
        return list(arr.astype(float).ravel())
    if arr.dtype.kind in "bUS":  # flags and labels (e.g. a film's regime per entry)
        return []
    raise AssertionError(f"unexpected result type {type(result).__name__}")


#: functions documented to return +inf: a self-locking hitch holds any load, so its ratio,
#: capacity and margin are +inf and its critical mu may be +inf (hitch.py); NaN never
INFINITY_MEANS_LOCKED = frozenset(
    ("thick_hitch_ratio", "hold_verdict", "hitch_critical_mu", "hitch_margin", "hitch_holds")
)


def _assert_finite(name, result):
    if hasattr(result, "applicable"):  # a flagged result: NaN only where it says so
        assert np.all(np.isnan(result.thickness) == ~result.applicable), name
        assert result.message or np.all(result.applicable), name
        result = dataclasses.replace(result, thickness=result.thickness[result.applicable])
    values = np.asarray(_numbers(result), dtype=float)
    if name in INFINITY_MEANS_LOCKED:
        values = values[values != np.inf]
    assert np.all(np.isfinite(values)), f"{name} returned a non-finite number: {result!r}"


def _call(name, func, kwargs, names_in_message):
    start = time.perf_counter()
    try:
        with warnings.catch_warnings():
            # numpy's overflow / invalid-value warnings are errors here: a NaN masked inside
            # a formula gave a finite but wrong Hertz ellipse (radii 1e24 apart)
            warnings.simplefilter("error", RuntimeWarning)
            result = func(**kwargs)
    except InputError as e:
        msg = str(e)
        assert msg and "\n" not in msg, f"{name}({kwargs!r}): message not one line: {msg!r}"
        assert any(n in msg for n in names_in_message), (
            f"{name}({kwargs!r}): message names no argument: {msg!r}"
        )
    else:
        _assert_finite(name, result)
    elapsed = time.perf_counter() - start
    assert elapsed < CALL_SECONDS, f"{name}({kwargs!r}) took {elapsed:.1f} s"


def _check_function(name, data):
    func = FUNCTIONS[name]
    kwargs = _arguments(name, data)
    params = tuple(inspect.signature(func).parameters)
    _call(name, func, kwargs, params)


_quantity_text = st.one_of(
    st.text(max_size=10),
    st.sampled_from(
        [
            "4mm",
            "1e300deg",
            "1e400mm",
            "-1e400N",
            "inf mm",
            "nan",
            "NaN deg",
            "",
            "   ",
            "2pi",
            "1.5turn",
            "\uff14mm",
            "\u0664mm",
            "4,0mm",
            "1_0mm",
            "5 kg",
            "3 s",
            "1e-5N*m^2",
            "1e308 km",
            "\u22124mm",
            "0",
            "1e12 GPa",
            "1e-12 um",
            "2*3",
            "mm",
            "4 mm mm",
            "1/0 mm",
            "(1+2j) mm",
            "10**400 mm",
            "1e20 turn",
            "4\nmm",
        ]
    ),  # fmt: skip
    _hostile,
)


@functools.lru_cache(maxsize=1)
def _unit_registry_loaded() -> bool:
    """Load pint's unit registry once (2 s idle, 13 s seen on a loaded machine; the first
    text the fast path does not take, e.g. 'NaN deg', loads it): a one-time start-up cost,
    not the time of a call that :data:`CALL_SECONDS` bounds."""
    try:
        parse_quantity("NaN deg", "angle", name="--opt")
    except InputError:
        pass
    return True


def _check_parse_quantity(data):
    _unit_registry_loaded()
    kwargs = {
        "text": data.draw(_quantity_text, label="text"),
        "kind": data.draw(st.sampled_from(list(KINDS)) | st.text(max_size=4), label="kind"),
        "name": "--opt",
        "bare_si": data.draw(st.booleans(), label="bare_si"),
    }
    _call("parse_quantity", parse_quantity, kwargs, ("--opt", "kind"))


_QUICK = settings(
    max_examples=20,
    derandomize=True,
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large],
)
_CAMPAIGN = settings(
    max_examples=100,
    derandomize=False,
    deadline=None,
    suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large],
)


@pytest.mark.parametrize("name", _names())
@_QUICK
@given(data=st.data())
def test_a_closed_form_returns_finite_numbers_or_one_line(name, data):
    _check_function(name, data)


@_QUICK
@given(data=st.data())
def test_parse_quantity_returns_a_finite_float_or_one_line(data):
    _check_parse_quantity(data)


@pytest.mark.slow
@pytest.mark.parametrize("name", _names())
@_CAMPAIGN
@given(data=st.data())
def test_campaign_closed_forms(name, data):
    """About 45 functions x 100 examples (> 4,000 calls)."""
    _check_function(name, data)


@pytest.mark.slow
@settings(_CAMPAIGN, max_examples=600)
@given(data=st.data())
def test_campaign_parse_quantity(data):
    _check_parse_quantity(data)


# ------------------------------------------------------------------ the scene functions

#: a valid call of each public scene function (the README's and the CLI's examples)
SCENE_CALLS = {
    "capstan": dict(wrap_angle=np.pi, mu=0.5, rod_diameter=4e-3, post_diameter=16e-3,
                    youngs_modulus=1.26e6, t_low=0.16),
    "capstan_two_loops": {},
    "pinch": dict(normal_load=0.3, mu=0.5),
    "clove_hitch": dict(mu_rod_post=0.3, t_high=1.47),
    "two_half_hitches": dict(mu_rod_post=0.6, t_high=0.1),
    "round_turn_two_half_hitches": dict(mu_rod_post=0.6, t_high=0.1),
    "cow_hitch": dict(mu_rod_post=0.6, t_high=0.1),
    "bend": dict(kind="reef"),
    "overhand": dict(turns=2, mu=0.3),
    "overhand_knot": dict(turns=2, rod_length=1.0, rod_radius=5e-3, end_to_end_length=0.5,
                          braid_length=0.1, n_nodes=401),
    "bend_curves": dict(kind="reef", rod_diameter=4e-3, n_nodes=80),
    "clove_hitch_curve": dict(post_diameter=0.03, rod_diameter=4e-3, tail_length=0.05,
                              n_nodes=200),
    "coil_curve": dict(post_diameter=0.03, rod_diameter=4e-3, tail_length=0.05, n_nodes=200),
}  # fmt: skip

#: one-number arguments given what is not one number
NOT_ONE_NUMBER = {
    "a list": [1e-3, 2e-3],
    "an array": np.array([1e-3, 2e-3]),
    "a string": "0.3",
    "a bool": True,
}


class _Accepted(Exception):
    """Raised by the stubbed solver: a call got as far as a run."""


def _scene_function(name: str):
    """``knotmech.scenes.<name>``, the function (the attribute becomes the submodule of that
    name, ``knotmech.scenes.capstan``, once the submodule is imported)."""
    import knotmech.scenes as scenes

    found = getattr(scenes, name)
    return found if callable(found) else getattr(found, name)


def _scene_cases():
    for name, call in SCENE_CALLS.items():
        params = inspect.signature(_scene_function(name)).parameters
        for p in params.values():
            numeric = type(p.default) in (int, float) or (
                p.default is p.empty and p.name in call and type(call[p.name]) in (int, float)
            )
            if numeric and p.kind is not p.VAR_KEYWORD:
                for kind in NOT_ONE_NUMBER:
                    yield pytest.param(name, p.name, kind, id=f"{name}-{p.name}-{kind}")


@pytest.fixture(scope="module")
def no_runs():
    """The solver replaced by one that raises :class:`_Accepted` (nothing runs)."""
    import knotmech.rod as rod
    import knotmech.rod.solver as solver
    import knotmech.scenes.pinch as pinch

    def refuse_to_run(*args, **kwargs):
        raise _Accepted

    with pytest.MonkeyPatch.context() as mp:
        for module in (rod, solver, pinch):
            mp.setattr(module, "simulate", refuse_to_run)
        yield


@pytest.mark.parametrize(("name", "arg", "kind"), list(_scene_cases()))
def test_a_scene_refuses_what_is_not_one_number(no_runs, name, arg, kind):
    """Issue 27: ``capstan(rod_diameter=[1e-3, 2e-3])`` raised a bare TypeError from
    ``float()``; every one-number argument of every public scene function now gives one
    InputError line naming it, before any run."""
    call = {**SCENE_CALLS[name], arg: NOT_ONE_NUMBER[kind]}
    with pytest.raises(InputError) as info:
        _scene_function(name)(**call)
    message = str(info.value)
    assert "\n" not in message
    assert arg in message, message


def test_a_fraction_of_a_count_is_refused():
    """Issue 27: ``imc_setup(1.5)`` was read as one turn (``int(1.5)``)."""
    from knotmech.scenes import imc_setup

    with pytest.raises(InputError, match=r"^turns must be an integer in \[1, 4\], got 1.5$"):
        imc_setup(1.5)
    assert imc_setup(2.0) == imc_setup(2)

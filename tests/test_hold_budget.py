"""The CPU budget of a ``hold --simulate`` run (``max_cpu_s``): a run that spends it stops
and gives no verdict, never a slip read from a run cut short (session 19 measured a
kappa-0.003 table point at 1829 s of CPU)."""

from __future__ import annotations

import math
from types import SimpleNamespace

import pytest

from knotmech.errors import InputError
from knotmech.scenes._hitch import HitchScene
from knotmech.verdict import SIMULATE_MAX_CPU_S, hold
from knotmech.verdict.build import simulate_point


def _scene(**kw):
    """What ``HitchScene._verdict`` reads: a free end, its end time, slip and creep limits."""
    base = dict(load=SimpleNamespace(loading="free"), t_end=1.0, slip=1e-3, climit=1e-3, d=1e-3)
    return SimpleNamespace(**{**base, **kw})


def test_a_run_cut_by_its_budget_gives_no_verdict():
    """The scene's own verdict of a free-end run that stopped short with the solver failed
    is "slip" (its creep is not measured; ``build`` then gives no verdict unless the knot
    came apart, ``criterion.solver_gave_verdict``), unless the budget stopped it with the
    knot intact: then none."""
    cut = SimpleNamespace(over_budget=True, status="failed")
    failed = SimpleNamespace(over_budget=False, status="failed")
    args = ([0.0, 0.5], math.nan, math.nan, True)
    assert HitchScene._verdict(_scene(), cut, *args) == ""
    assert HitchScene._verdict(_scene(), failed, *args) == "slip"
    # a knot that had come apart before its budget ran out slipped, budget or not
    apart = ([0.0, 0.5], math.nan, math.nan, False)
    assert HitchScene._verdict(_scene(), cut, *apart) == "slip"


def test_simulate_point_stops_at_its_budget_undecided():
    """The clove hitch that holds 5 N in 11 s of wall (nylon, 4 mm on 30 mm, mu 0.8, kappa
    0.01) with a 1.5 s budget: no verdict, the budget named, its CPU near the budget."""
    p = simulate_point(d_over_2R=4 / 34, t_over_EA=5.0 / (0.25e9 * math.pi * 4e-6),
                       mu=0.8, rod_diameter=4e-3, youngs_modulus=0.25e9, bending_scale=0.01,
                       recheck=True, max_cpu_s=1.5)  # fmt: skip
    assert p["holds"] is None
    assert "CPU budget of 1.5 s" in p["message"]
    assert 1.5 <= p["cpu_s"] < 4.0
    with pytest.raises(InputError, match="max_cpu_s"):
        simulate_point(d_over_2R=0.1, t_over_EA=1e-3, max_cpu_s=-1.0)


def test_hold_with_a_spent_budget_falls_back_to_the_closed_forms():
    """``hold(simulate=True, max_cpu_s=1.5)``: the DER says it failed and why, and does
    not decide; the default budget is 900 s."""
    v = hold("clove-hitch", rod_diameter=4e-3, post_diameter=30e-3, mu=0.8, load=5.0,
             material="nylon", bending_scale=0.01, simulate=True, max_cpu_s=1.5)  # fmt: skip
    assert v.der["message"].startswith("the DER simulation failed")
    assert "CPU budget of 1.5 s" in v.der["message"]
    assert v.decided_by != "DER-simulation"
    assert SIMULATE_MAX_CPU_S == 900.0


@pytest.mark.parametrize(
    "kw, words",
    [
        ({"max_cpu_s": 0.0}, "max_cpu_s must be > 0"),
        ({"max_cpu_s": math.nan}, "max_cpu_s"),
        ({"max_cpu_s": 60.0, "simulate": False}, "give simulate as well"),
        ({"max_cpu_s": 60.0, "knot": "reef"}, "not to reef"),
    ],
)
def test_budget_inputs_are_checked(kw, words):
    args = dict(knot="clove-hitch", rod_diameter=4e-3, post_diameter=30e-3, mu=0.8, load=5.0,
                material="nylon", simulate=True)  # fmt: skip
    args.update(kw)
    knot = args.pop("knot")
    if knot == "reef":
        args.pop("post_diameter")
    with pytest.raises(InputError, match=words):
        hold(knot, **args)

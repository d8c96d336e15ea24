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


def test_a_recheck_gets_the_recheck_factor_times_the_budget(monkeypatch):
    """A recheck holds :data:`RECHECK_HOLD_FACTOR` times as long, so its budget is that many
    budgets: a first run that ended inside its 100 s is not undone by a recheck cut at 100 s
    (the review of session 20 found the recheck on the first run's budget)."""
    import knotmech.verdict.build as build
    from knotmech.verdict.criterion import RECHECK_HOLD_FACTOR

    budgets, holds = [], []

    def scene(**kw):
        if "options" in kw:
            budgets.append(kw["options"].max_cpu_s)
        holds.append(kw["hold_time"])
        t_end = kw["settle_time"] + kw["load_time"] + kw["hold_time"]
        return SimpleNamespace(times=[0.0, t_end], status="success", verdict="hold",
                               message="", topology_preserved=True, creep_speed_d=0.0,
                               creep_window=0.5, stats={}, positions=[[0.0] * 3],
                               creep=0.0)  # fmt: skip

    monkeypatch.setattr(build, "hold_scene", lambda knot: scene)
    calls = iter([True, False])
    monkeypatch.setattr(build, "needs_recheck", lambda *a, **k: next(calls))
    p = simulate_point(d_over_2R=0.1, t_over_EA=1e-3, knot="two-half-hitches",
                       recheck=True, max_cpu_s=100.0)  # fmt: skip
    assert budgets == [100.0, RECHECK_HOLD_FACTOR * 100.0] == [100.0, 200.0]
    assert holds[1] == pytest.approx(RECHECK_HOLD_FACTOR * holds[0])
    assert p["holds"] is True and p["first_hold_time"] == pytest.approx(holds[0])
    # without a budget (the tables) neither run has one
    budgets.clear()
    calls = iter([True, False])
    simulate_point(d_over_2R=0.1, t_over_EA=1e-3, knot="two-half-hitches", recheck=True)
    assert budgets == []

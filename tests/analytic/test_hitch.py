"""Hitch criteria: the free-end statement, monotonicity in mu, critical mu, limits, verdicts."""

import json
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from knotmech.analytic.capstan import capstan_ratio
from knotmech.analytic.hitch import (
    COW_FREE_LEG_STATEMENT,
    FREE_END_STATEMENT,
    KNOTS,
    ModelAnswer,
    hitch_critical_mu,
    hitch_holds,
    hitch_margin,
    hold_verdict,
    ideal_hitch_ratio,
    nip_factor,
    thick_hitch_lock_parameter,
    thick_hitch_ratio,
)
from knotmech.errors import InputError

FAST = settings(max_examples=40, deadline=None)
knots = st.sampled_from(sorted(KNOTS))
#: the hitches with a thick-nip model (not derived for the cow hitch)
thick_knots = st.sampled_from(sorted(k for k, g in KNOTS.items() if g.thick_nip))
mus = st.floats(0.0, 2.0)
diam = st.floats(1e-4, 0.1)


@FAST
@given(knots, diam, diam, mus, st.floats(1e-3, 1e4))
def test_free_end_slips_at_any_load_whatever_d_and_D(knot, d, D, mu, load):
    # Bayman (1977); Maddocks & Keller (1987) as summarised in the clove-hitch paper, Sec. 8
    v = hold_verdict(knot, rod_diameter=d, post_diameter=D, mu=mu, load=load, free_end_load=0.0)
    assert v.decided_by == "ideal-rope"
    assert not v.holds
    assert v.margin == -1.0
    assert math.isinf(v.deciding.critical_mu)
    assert not hitch_holds(knot, high_tension=load, low_tension=0.0, mu=mu)


def test_free_end_statement_is_attached_to_the_clove_hitch_verdict():
    v = hold_verdict(
        "clove-hitch", rod_diameter=4e-3, post_diameter=30e-3, mu=0.3, load=1.47, free_end_load=0
    )
    assert FREE_END_STATEMENT in v.deciding.notes
    assert "T_low = 0" in FREE_END_STATEMENT


@FAST
@given(knots, mus, st.floats(1.0, 3.0), st.floats(0.01, 1.0), st.floats(1.0, 1e4))
def test_ideal_criterion_monotone_in_mu(knot, mu, factor, t_low, ratio):
    t_high = t_low * ratio
    if hitch_holds(knot, high_tension=t_high, low_tension=t_low, mu=mu):
        assert hitch_holds(knot, high_tension=t_high, low_tension=t_low, mu=mu * factor)
    assert hitch_margin(knot, high_tension=t_high, low_tension=t_low, mu=mu * factor) >= (
        hitch_margin(knot, high_tension=t_high, low_tension=t_low, mu=mu)
    )


@FAST
@given(thick_knots, mus, st.floats(1.0, 3.0), diam, st.floats(1.0, 100.0))
def test_thick_model_monotone_in_mu(knot, mu, factor, d, Dt):
    k1 = thick_hitch_ratio(knot, mu, rod_diameter=d, post_diameter=d * Dt)
    k2 = thick_hitch_ratio(knot, mu * factor, rod_diameter=d, post_diameter=d * Dt)
    assert k2 >= k1 * (1 - 1e-12)


@FAST
@given(knots, st.floats(0.01, 1.0), st.floats(1.01, 1e4), st.one_of(st.none(), st.floats(0, 1)))
def test_critical_mu_is_the_threshold(knot, t_low, ratio, mu_rr):
    t_high = t_low * ratio
    mc = float(hitch_critical_mu(knot, high_tension=t_high, low_tension=t_low, mu_rr=mu_rr))
    assert mc >= 0
    assert hitch_holds(
        knot, high_tension=t_high, low_tension=t_low, mu=mc * (1 + 1e-9) + 1e-12, mu_rr=mu_rr
    )
    if mc > 1e-6:
        assert not hitch_holds(
            knot, high_tension=t_high, low_tension=t_low, mu=mc * (1 - 1e-6), mu_rr=mu_rr
        )


def test_round_turn_is_a_one_turn_capstan():
    assert float(ideal_hitch_ratio("round-turn", 0.3)) == pytest.approx(
        float(capstan_ratio(0.3, 2 * math.pi)), rel=1e-15
    )


def test_ideal_ratios_by_hand():
    mu, mrr = 0.3, 0.2
    assert float(ideal_hitch_ratio("clove-hitch", mu, mrr)) == pytest.approx(
        math.exp(4 * math.pi * mu)
    )
    assert float(ideal_hitch_ratio("two-half-hitches", mu, mrr)) == pytest.approx(
        math.exp(math.pi * mu + 4 * math.pi * mrr)
    )
    assert float(ideal_hitch_ratio("round-turn-two-half-hitches", mu, mrr)) == pytest.approx(
        math.exp(2 * math.pi * mu + 4 * math.pi * mrr)
    )


def test_cow_hitch_is_an_ideal_rope_capstan_of_two_turns_and_has_no_thick_nip_model():
    """A zero-thickness rope is a capstan whatever the sense of its turns: the cow hitch's
    two turns in opposite senses give K = exp(4 pi mu), the clove hitch's; with one leg
    free it slips at any load. The thick-nip chain is not derived for it: refused, and
    its verdict carries the ideal rope only."""
    assert float(ideal_hitch_ratio("cow-hitch", 0.3)) == pytest.approx(
        math.exp(4 * math.pi * 0.3), rel=1e-14
    )
    with pytest.raises(InputError, match="not derived for the cow-hitch"):
        thick_hitch_ratio("cow-hitch", 0.3, rod_diameter=4e-3, post_diameter=30e-3)
    with pytest.raises(InputError, match="not derived for the cow-hitch"):
        thick_hitch_lock_parameter("cow-hitch", 0.3, rod_diameter=4e-3, post_diameter=30e-3)
    kw = dict(rod_diameter=4e-3, post_diameter=80e-3, mu=0.3)
    v = hold_verdict("cow-hitch", load=1.0, free_end_load=0.0, **kw)
    assert [a.model for a in v.answers] == ["ideal-rope"]
    assert v.holds is False and v.margin == -1.0
    assert COW_FREE_LEG_STATEMENT in v.deciding.notes
    # both legs loaded: holds up to exp(4 pi 0.3) = 43.38 times the lighter leg
    both = hold_verdict("cow-hitch", load=1.0, free_end_load=1.0, **kw)
    assert both.holds is True and both.deciding.capacity == pytest.approx(43.376, rel=1e-4)
    assert hold_verdict("cow-hitch", load=44.0, free_end_load=1.0, **kw).holds is False


@pytest.mark.parametrize(("knot", "rate"), [("clove-hitch", 0.5), ("round-turn", 1.0)])
@pytest.mark.parametrize("mu", [0.05, 0.3, 0.8])
def test_thick_model_reduces_to_ideal_for_thin_rods(knot, rate, mu):
    d = np.array([1e-12, 1e-14, 1e-16])
    K = thick_hitch_ratio(knot, mu, rod_diameter=d, post_diameter=0.03)
    ideal = float(ideal_hitch_ratio(knot, mu))
    err = np.abs(K / ideal - 1)
    assert err[-1] < 1e-4
    # the nip force ~ 4 sqrt(d/D) dominates the clove hitch (error ~ sqrt(d)); the round
    # turn has no nip and mu - mu_eff ~ mu (1 + mu^2) d/D (error ~ d)
    fitted = np.polyfit(np.log(d), np.log(err), 1)[0]
    assert fitted == pytest.approx(rate, abs=0.05)


def test_nip_factor_limits():
    assert float(nip_factor(1.0, 1.0)) == pytest.approx(math.sqrt(3), rel=1e-14)
    d, D = 1e-6, 1.0
    assert float(nip_factor(d, D)) == pytest.approx(4 * math.sqrt(d / D), rel=1e-5)
    # grows with the rod diameter at fixed post
    n = nip_factor(np.array([1e-3, 2e-3, 4e-3]), 0.03)
    assert np.all(np.diff(n) > 0)


def test_thick_clove_hitch_self_locks_exactly_at_lock_parameter_one():
    kw = dict(rod_diameter=4e-3, post_diameter=30e-3)
    mus = np.linspace(0.05, 0.4, 200)
    lock = thick_hitch_lock_parameter("clove-hitch", mus, **kw)
    K = thick_hitch_ratio("clove-hitch", mus, **kw)
    assert np.all(np.isinf(K) == (lock >= 1))
    assert np.all(np.diff(lock) > 0)


def test_round_turn_never_self_locks():
    K = thick_hitch_ratio("round-turn", 5.0, rod_diameter=0.01, post_diameter=0.01)
    assert np.isfinite(K)


def test_verdict_with_free_end_tension_matches_criterion():
    kw = dict(rod_diameter=4e-3, post_diameter=30e-3, mu=0.3, load=1.47)
    K = float(ideal_hitch_ratio("clove-hitch", 0.3))
    holds = hold_verdict("clove-hitch", free_end_load=1.47 / K * 1.001, **kw)
    slips = hold_verdict("clove-hitch", free_end_load=1.47 / K * 0.999, **kw)
    assert holds.holds and not slips.holds
    assert holds.margin == pytest.approx(0.001, rel=1e-9)


def test_capstan_verdict_uses_mu_eff_and_reports_ideal():
    kw = dict(rod_diameter=4e-3, post_diameter=30e-3, mu=0.3, wrap_angle=2 * math.pi)
    # between the thick-rod capacity (ratio 5.196) and the ideal one (6.586)
    v = hold_verdict("capstan", load=6.0, free_end_load=1.0, **kw)
    assert v.decided_by == "thick-capstan"
    assert not v.holds
    ideal = next(a for a in v.answers if a.model == "ideal-capstan")
    assert ideal.holds and not ideal.decides


def test_verdict_is_json_serialisable_and_extensible():
    v = hold_verdict(
        "clove-hitch", rod_diameter=4e-3, post_diameter=30e-3, mu=0.3, load=1.47, free_end_load=0
    )
    d = v.to_dict()
    text = json.dumps(d, allow_nan=False)
    assert json.loads(text)["holds"] is False
    assert sum(a["decides"] for a in d["answers"]) == 1
    extra = ModelAnswer(
        model="der",
        holds=True,
        margin=0.2,
        capacity=1.8,
        critical_mu=0.1,
        decides=False,
        inside_validity=True,
        assumptions=("simulation",),
        validity=(),
        reference="test",
    )
    v2 = v.with_answer(extra, decides=True)
    assert v2.holds and v2.decided_by == "der" and len(v2.answers) == len(v.answers) + 1
    assert sum(a.decides for a in v2.answers) == 1


@pytest.mark.parametrize(
    ("kwargs", "name"),
    [
        (dict(knot="granny"), "knot"),
        (dict(free_end_load=2.0), "free_end_load"),
        (dict(rod_diameter=0.0), "rod_diameter"),
        (dict(post_diameter=-1.0), "post_diameter"),
        (dict(mu=float("nan")), "mu"),
        (dict(load=0.0), "load"),
        (dict(mu_rr=-0.1), "mu_rr"),
        (dict(wrap_angle=1.0), "wrap_angle"),
        (dict(knot="capstan"), "wrap_angle"),
    ],
)
def test_bad_input_names_the_argument(kwargs, name):
    base = dict(knot="clove-hitch", rod_diameter=4e-3, post_diameter=0.03, mu=0.3, load=1.0)
    base.update(kwargs)
    knot = base.pop("knot")
    with pytest.raises(InputError, match=name):
        hold_verdict(knot, **base)

"""The critical friction coefficient mu* of ``hold`` with a given mu or a published range
(issue 23: "the critical mu is always printed", and right): the least mu at which the whole
verdict holds at the user's load (:func:`knotmech.verdict.friction.critical_mu`, the same
search as the unknown-friction path), not the critical mu of the model deciding at that mu.
"""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

import knotmech
from knotmech.verdict import decide
from knotmech.verdict.friction import MU_RESOLUTION, MU_SEARCH_MAX, MU_STEP

#: the issue's nylon clove hitch: 6 mm rope on a 40 mm post, 200 N, free end
NYLON = dict(rod_diameter=6e-3, post_diameter=40e-3, load=200.0, material="nylon")
#: the thick nip's own critical mu at d/D = 0.15 (holds at and above it; derivations/hitches.py)
NIP_MU = 0.16609797001713242


def _strict(v) -> dict:
    def bad(const):
        raise AssertionError(f"non-strict JSON constant {const}")

    return json.loads(v.to_json(), parse_constant=bad)


def test_the_issue_command_finds_the_whole_verdicts_mu_star():
    """``--mu 0.05``: the DER table decides SLIPS and has no critical mu of its own (it is
    undecided even at 1.5), but the whole verdict holds from the thick nip's 0.166098 (the
    thick nip decides there): mu* = 0.166098, not "none"; the same mu* whatever the mu
    asked at, and without mu (no coefficient published for nylon on steel)."""
    v = knotmech.hold("clove-hitch", mu=0.05, **NYLON)
    f = v.friction
    assert v.state == "SLIPS" and v.decided_by == "DER-table"
    assert f["critical_mu"] == NIP_MU
    assert f["critical_mu_text"] == (
        "the thick-nip model's, where the whole verdict starts to hold: checked there and "
        "0.00073 below"
    )
    assert math.isnan(f["model_critical_mu"])  # the DER table alone: undecided at 1.5
    assert knotmech.hold("clove-hitch", mu=NIP_MU + 1e-3, **NYLON).state == "HOLDS"
    assert knotmech.hold("clove-hitch", mu=NIP_MU - 1e-3, **NYLON).state == "SLIPS"
    for mu in (0.17, 0.4, 1.0, None):
        assert knotmech.hold("clove-hitch", mu=mu, **NYLON).friction["critical_mu"] == NIP_MU
    line = v.friction_line()
    assert line.startswith("friction: critical mu 0.166 (the thick-nip model's")


def test_a_hinted_search_asks_the_verdict_three_times(monkeypatch):
    """Cheap: at mu 0.4 the thick nip decides and its critical mu is mu*: the verdict is
    asked at 0.4, at mu* and MU_STEP below, nothing more (each ask ~10 ms)."""
    calls = []
    real = decide._verdict

    def counted(c, wrap_angle):
        calls.append(c.mu)
        return real(c, wrap_angle)

    monkeypatch.setattr(decide, "_verdict", counted)
    knotmech.hold("clove-hitch", mu=0.4, **NYLON)
    assert calls == [0.4, NIP_MU, NIP_MU - MU_STEP]


def test_the_der_table_decides_at_the_boundary():
    """The paper's clove hitch (4 mm on 30 mm, 1.47 N, VPS32; d/2R 0.1176, 0.0928 EA): the
    DER table decides at 0.3; its lookups alone bisected on the grid give 403 steps of
    1.5/2^11 = 0.295166015625, where the whole verdict holds and 402 steps is undecided."""
    kw = dict(rod_diameter=4e-3, post_diameter=30e-3, load=1.47, material="vps32")
    f = knotmech.hold("clove-hitch", mu=0.3, **kw).friction
    assert f["critical_mu"] == f["model_critical_mu"] == 403 * MU_STEP == 0.295166015625
    assert knotmech.hold("clove-hitch", mu=403 * MU_STEP, **kw).state == "HOLDS"
    assert knotmech.hold("clove-hitch", mu=402 * MU_STEP, **kw).state == "UNDECIDED"
    assert knotmech.hold("clove-hitch", mu=0.2, **kw).state == "SLIPS"


def test_a_table_bisection_alone_was_wrong_for_the_whole_verdict():
    """HMPE clove hitch (6 mm on 25 mm, 50 N, mu_rr 0.3) at kappa 0.01: the DER table decides
    HOLDS at 0.6 and alone would hold only from 0.295, but below it the thick nip decides
    HOLDS down to its own critical mu 0.11118 (d/D 0.24, mu_rr 0.3): mu* is 0.11118. (With
    the preset's kappa range 0.005-0.05 the kappa-0.003 and 0.03 tables are undecided there
    and the thick nip decides at 0.6 as well: tests/test_hold_kappa_range.py.)"""
    kw = dict(rod_diameter=6e-3, post_diameter=25e-3, load=50.0, material="hmpe", mu_rr=0.3,
              bending_scale=0.01)  # fmt: skip
    v = knotmech.hold("clove-hitch", mu=0.6, **kw)
    f = v.friction
    assert v.decided_by == "DER-table" and f["model_critical_mu"] == 403 * MU_STEP
    nip = next(a for a in v.answers if a.model == "thick-nip").critical_mu
    assert f["critical_mu"] == nip == pytest.approx(0.111182, abs=1e-6)
    for mu, by in ((0.2, "thick-nip"), (nip + 1e-3, "thick-nip")):
        at = knotmech.hold("clove-hitch", mu=mu, **kw)
        assert at.state == "HOLDS" and at.decided_by == by
    assert knotmech.hold("clove-hitch", mu=nip - 1e-3, **kw).state == "SLIPS"
    assert "the deciding model alone: critical mu 0.295" in v.friction_line(verbose=True)
    assert "deciding model alone" not in v.friction_line()


@pytest.mark.parametrize(
    ("knot", "kw", "mu", "want"),
    [
        # capstan, one turn, 6 N against 1 N, thick capstan (d/D 4/30): 0.327 > ln 6 / 2 pi
        ("capstan", dict(rod_diameter=4e-3, post_diameter=30e-3, load=6.0, free_end_load=1.0,
                         wrap_angle=2 * math.pi), 0.3, 0.327),
        # manila clove hitch, 300 N against 30 N on a 50 mm post: the thick nip's 0.1205
        ("clove-hitch", dict(rod_diameter=8e-3, post_diameter=50e-3, load=300.0,
                             free_end_load=30.0, material="manila"), 0.3, 0.1205),
        # a round turn, 300 N against 30 N: slips at 0.3, holds from the thick nip's 0.4344
        ("round-turn", dict(rod_diameter=8e-3, post_diameter=50e-3, load=300.0,
                            free_end_load=30.0, material="manila"), 0.3, 0.4344),
        # the cow hitch from its DER table: slips at 0.3, holds from 0.7954 (grid: 1086 steps)
        ("cow-hitch", dict(rod_diameter=4e-3, post_diameter=30e-3, load=1.0,
                           youngs_modulus=1.26e6), 0.3, 1086 * MU_STEP),
    ],
)  # fmt: skip
def test_finite_mu_star_holds_above_and_not_below(knot, kw, mu, want):
    f = knotmech.hold(knot, mu=mu, **kw).friction
    m = f["critical_mu"]
    assert m == pytest.approx(want, abs=5e-4)
    assert knotmech.hold(knot, mu=m + 1e-3, **kw).holds is True
    assert knotmech.hold(knot, mu=m, **kw).holds is True
    assert knotmech.hold(knot, mu=m - 1e-3, **kw).holds is not True


@pytest.mark.parametrize(
    ("knot", "kw"),
    [
        # a capstan loaded equally on both ends holds without friction
        ("capstan", dict(rod_diameter=4e-3, post_diameter=30e-3, load=6.0, free_end_load=6.0,
                         wrap_angle=2 * math.pi)),
        # two half hitches of HMPE with rope-on-rope friction 0.3: the nip alone locks it
        # (kappa 0.2, which no shipped table answers for, so that the thick nip decides; the
        # fibre-rope table, kappa 0.01, puts mu* at 0.305 there)
        ("two-half-hitches", dict(rod_diameter=6e-3, post_diameter=25e-3, load=50.0,
                                  material="hmpe", mu_rr=0.3, bending_scale=0.2)),
    ],
)  # fmt: skip
def test_mu_star_zero_holds_without_friction(knot, kw):
    f = knotmech.hold(knot, mu=0.6, **kw).friction
    assert f["critical_mu"] == 0.0 and f["critical_mu_text"] == "holds without friction"
    assert knotmech.hold(knot, mu=0.0, **kw).holds is True


def test_mu_star_none_slips_and_breaks():
    """A round turn with a free end slips at every mu (thick nip); a steel-wire capstan half
    turn needs mu 2.49 (its own critical mu, kept as model_critical_mu) beyond the search;
    the manila capstan at 3 kN breaks (2.255 kN) whatever the friction."""
    rt = knotmech.hold("round-turn", mu=0.4, **NYLON)
    assert math.isinf(rt.friction["critical_mu"]) and rt.state == "SLIPS"
    assert rt.friction["critical_mu_text"] == "does not hold for any mu up to 1.5"
    assert knotmech.hold("round-turn", mu=MU_SEARCH_MAX, **NYLON).holds is False
    d = _strict(rt)
    assert d["friction"]["critical_mu"] is None and d["critical_mu_none"] is True
    kw = dict(rod_diameter=6e-3, post_diameter=40e-3, load=100.0, free_end_load=1.0,
              wrap_angle=math.pi, material="steel-wire")  # fmt: skip
    cap = knotmech.hold("capstan", mu=0.3, **kw).friction
    assert math.isinf(cap["critical_mu"])
    assert cap["model_critical_mu"] == pytest.approx(2.4875, abs=1e-4)
    assert knotmech.hold("capstan", mu=MU_SEARCH_MAX, **kw).holds is False
    kw = dict(rod_diameter=6e-3, post_diameter=40e-3, load=3000.0, free_end_load=300.0,
              material="manila", wrap_angle=20 * math.pi)  # fmt: skip
    brk = knotmech.hold("capstan", mu=0.3, **kw)
    assert brk.state == "BREAKS" and math.isinf(brk.friction["critical_mu"])
    assert brk.friction["critical_mu_text"] == "the load breaks the rope whatever the friction"


def test_a_published_range_gets_the_same_mu_star():
    """Nylon on aluminium (published 0.221): the verdict at 0.221, mu* the whole verdict's,
    the same as with any --mu."""
    v = knotmech.hold("clove-hitch", **NYLON, post_material="aluminium")
    f = v.friction
    assert f["range"] == [0.221, 0.221] and f["critical_mu"] == NIP_MU
    assert f["words"] == "holds at mu = 0.221"


@pytest.mark.parametrize(
    ("knot", "kw"),
    [
        ("bowline", dict(rod_diameter=10e-3, pin_diameter=20e-3, load=2000.0, material="nylon")),
        ("reef", dict(rod_diameter=10e-3, load=500.0, material="nylon")),
        ("prusik", dict(rod_diameter=8e-3, post_diameter=12e-3, load=2000.0, material="nylon")),
    ],
)
@pytest.mark.parametrize("mu", [0.3, None])
def test_loops_bends_and_the_prusik_say_a_der_run_per_mu(knot, kw, mu):
    """No closed form and no table answers them: no number, the words say why."""
    v = knotmech.hold(knot, mu=mu, **kw)
    f = v.friction
    assert v.state == "UNDECIDED" and math.isnan(f["critical_mu"])
    assert f["critical_mu_text"] == (
        f"not searched: no closed form and no table answers the {knot}, only a DER run, so "
        "mu* needs one DER run per mu (--simulate at each --mu)"
    )
    d = _strict(v)
    assert d["friction"]["critical_mu"] is None and d["critical_mu_none"] is False
    assert "critical mu: not searched: no closed form and no table" in v.friction_line()


def test_simulate_does_not_search_and_gives_the_command(monkeypatch):
    """A DER run answers at one mu: mu* not searched (no more runs), with the command that
    searches it in the table and closed forms."""
    from knotmech.verdict import build

    runs = []

    def fake(**kw):
        runs.append(kw)
        return {"holds": True, "verdict": "hold", "creep_speed": 1e-6, "ran_to_end": True,
                "wall_s": 1.0, "message": "", "reason": ""}  # fmt: skip

    monkeypatch.setattr(build, "simulate_point", fake)
    v = knotmech.hold("clove-hitch", rod_diameter=4e-3, post_diameter=36e-3, mu=0.3,
                      load=1.0, material="vps32", simulate=True)  # fmt: skip
    f = v.friction
    assert len(runs) == 1 and math.isnan(f["critical_mu"])
    assert f["critical_mu_text"] == (
        "not searched: a DER run answers at one mu only, mu* needs one run per mu; knotmech "
        "hold clove-hitch --rod-diameter 4mm --post-diameter 36mm --mu 0.3 --load 1N "
        "--material vps32 searches it in the table and closed forms"
    )


@pytest.mark.parametrize("knot", ["cow-hitch", "two-half-hitches"])
def test_unknown_friction_der_command_asks_for_a_measured_mu(knot):
    """Manila on steel (none published), at kappa 0.2, which no shipped table answers for
    (a factor 5 from the solid rod's, 20 from the fibre rope's): the DER line's command has
    --mu MU and says what MU is, never the search's assumed 1.5 or mu*."""
    v = knotmech.hold(knot, **dict(NYLON, material="manila", bending_scale=0.2))
    msg = v.der["message"]
    assert (
        " --mu MU --load 200N --material manila --bending-scale 0.2 --simulate (MU: this "
        "rope's friction " in msg
    )
    assert "measured; none is published" in msg and "--mu 1.5" not in msg


def test_random_questions_mu_star_agrees_with_hold():
    """Random hitch and capstan questions at a given mu (rope 2-20 mm, post 1-30 d, loads
    1 N-10 kN, every material): a finite mu* holds at mu* and mu* + 1e-3, not at
    mu* - 1e-3; mu* 0 holds at 0; mu* none does not hold at 1.5."""
    rng = np.random.default_rng(2324)
    knots = ("clove-hitch", "two-half-hitches", "round-turn-two-half-hitches", "cow-hitch",
             "round-turn", "capstan")  # fmt: skip
    mats = ("manila", "polypropylene", "steel-wire", "vps32", "nylon", "polyester", "hmpe")
    kinds = set()
    for _ in range(30):
        knot = knots[rng.integers(len(knots))]
        d = 10 ** rng.uniform(math.log10(2e-3), math.log10(2e-2))
        kw = dict(rod_diameter=d, post_diameter=d * rng.uniform(1, 30),
                  load=10 ** rng.uniform(0, 4), material=mats[rng.integers(len(mats))])  # fmt: skip
        if knot == "capstan":
            kw.update(wrap_angle=2 * math.pi * rng.integers(1, 6), free_end_load=kw["load"] / 20)
        mu = float(rng.uniform(0.05, 1.0))
        m = knotmech.hold(knot, mu=mu, **kw).friction["critical_mu"]
        if math.isnan(m):
            kinds.add("nan")
            assert knotmech.hold(knot, mu=MU_SEARCH_MAX, **kw).holds is None
        elif math.isinf(m):
            kinds.add("inf")
            assert knotmech.hold(knot, mu=MU_SEARCH_MAX, **kw).holds is False
        elif m == 0:
            kinds.add("zero")
            assert knotmech.hold(knot, mu=0.0, **kw).holds is True
        else:
            kinds.add("finite")
            assert knotmech.hold(knot, mu=m + MU_RESOLUTION, **kw).holds is True
            assert knotmech.hold(knot, mu=m, **kw).holds is True
            assert knotmech.hold(knot, mu=m - MU_RESOLUTION, **kw).holds is not True
    assert {"finite", "inf"} <= kinds


def _fake(rule):
    """``at(mu)`` returning a stand-in verdict whose ``holds`` is ``rule(mu)``."""
    from types import SimpleNamespace

    return lambda m: SimpleNamespace(holds=rule(m), answers=())


def test_mu_star_is_searched_again_above_a_slip_it_asked():
    # holds on [0.2, 0.4) and from 0.9 up: the published range's high end (0.6) slipped,
    # so the first mu* (0.2) is not where the whole verdict starts to hold for good
    from knotmech.verdict.friction import critical_mu

    at = _fake(lambda m: 0.2 <= m < 0.4 or m >= 0.9)
    asked = {0.3: at(0.3), 0.6: at(0.6)}
    m, text = critical_mu(at, asked)
    assert 0.9 <= m < 0.9 + MU_STEP and "bisection" in text
    assert all(v.holds for k, v in asked.items() if k >= m)


def test_mu_star_not_found_when_more_friction_slips_up_to_the_top():
    from knotmech.verdict.friction import critical_mu

    at = _fake(lambda m: 0.2 <= m < 0.4)
    m, text = critical_mu(at, {0.3: at(0.3), 0.6: at(0.6)})
    assert math.isnan(m)
    assert "not monotone in mu" in text and "mu = 0.6" in text

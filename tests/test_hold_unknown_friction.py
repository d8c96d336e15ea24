"""``hold`` without ``mu`` where no friction coefficient is published for the rope on the
post (``knotmech/data/strength/friction.json`` ``not_found``): the verdict over the whole
searched range [MU_UNKNOWN_LOW, MU_SEARCH_MAX] (issue 23: mu optional for every preset)."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

import knotmech
from knotmech.verdict.friction import MU_RESOLUTION, MU_SEARCH_MAX, MU_UNKNOWN_LOW

POST = dict(rod_diameter=6e-3, post_diameter=40e-3, load=200.0)


def _strict(v) -> dict:
    def bad(const):
        raise AssertionError(f"non-strict JSON constant {const}")

    return json.loads(v.to_json(), parse_constant=bad)


def test_the_low_end_is_below_every_published_coefficient():
    """MU_UNKNOWN_LOW = 0.05 lies below every row of friction.json (lowest: HMPE on HMPE,
    0.08), so a knot that holds there holds at every published rope friction."""
    path = Path(knotmech.__file__).parent / "data" / "strength" / "friction.json"
    rows = json.loads(path.read_text())["rows"]
    assert min(r["mu"][0] for r in rows) == 0.08
    assert MU_UNKNOWN_LOW == 0.05 and MU_SEARCH_MAX == 1.5


def test_holds_at_the_low_end_holds():
    """A 10-turn capstan of manila (no friction row at all) holding 200 N against 20 N: at
    mu 0.05 the thick capstan takes 307 N, so HOLDS for any mu from 0.05 up, with the
    numbers at 0.05 (those of hold(mu=0.05)); mu* is the thick capstan's 0.04215 (above the
    ideal capstan's ln(10) / (20 pi) = 0.03665)."""
    kw = dict(POST, free_end_load=20.0, material="manila", wrap_angle=20 * math.pi)
    v = knotmech.hold("capstan", **kw)
    at = knotmech.hold("capstan", mu=0.05, **kw)
    f = v.friction
    assert v.state == "HOLDS" and f["verdict_at_mu"] == 0.05 and f["verdict_at"] == "low end"
    assert v.capacity.value == at.capacity.value == pytest.approx(306.9785, rel=1e-6)
    assert v.margin == at.margin == pytest.approx(306.9785 / 200 - 1, rel=1e-6)
    thick = next(a for a in at.answers if a.model == "thick-capstan").critical_mu
    assert thick == pytest.approx(0.042152, abs=1e-6) and thick > math.log(10) / (20 * math.pi)
    assert thick <= f["critical_mu"] <= thick + MU_RESOLUTION
    assert v.summary().startswith(
        "verdict: HOLDS: holds for any mu from 0.05 up (no published friction coefficient "
        "for manila on steel); at mu = 0.05: slips near 307 N (thick-capstan model)"
    )


def test_does_not_hold_at_the_top_slips():
    """A round turn of manila with a free end slips at every friction in the thick-nip
    model: SLIPS, 'does not hold for any mu up to 1.5', numbers at 1.5 = hold(mu=1.5)'s;
    mu* none (inf: null in JSON with critical_mu_none)."""
    v = knotmech.hold("round-turn", **POST, material="manila")
    at = knotmech.hold("round-turn", mu=1.5, **POST, material="manila")
    assert v.state == "SLIPS" and v.fails_by == "slip" and v.friction["verdict_at_mu"] == 1.5
    assert v.capacity.value == at.capacity.value == 0.0 and v.margin == at.margin == -1.0
    assert v.summary().startswith(
        "verdict: SLIPS: does not hold for any mu up to 1.5 (no published friction "
        "coefficient for manila on steel); at mu = 1.5: slips at any load at this friction"
    )
    d = _strict(v)
    assert d["friction"]["critical_mu"] is None and d["critical_mu_none"] is True
    assert d["friction"]["holds_at_high"] is False and d["verdict"] == "slips"


def test_a_load_at_the_breaking_load_breaks_at_any_friction():
    """The manila capstan at 3 kN against 300 N: holds by friction at 0.05 already, but
    3 kN is above the rope's 2.255 kN breaking load, so BREAKS (a real verdict: the
    breaking load does not depend on mu), numbers at 1.5 as hold(mu=1.5) gives them."""
    kw = dict(POST, load=3000.0, free_end_load=300.0, material="manila", wrap_angle=20 * math.pi)
    v = knotmech.hold("capstan", **kw)
    at = knotmech.hold("capstan", mu=1.5, **kw)
    assert v.state == at.state == "BREAKS" and v.fails_by == "break"
    assert v.capacity.value == at.capacity.value == pytest.approx(2254.90, rel=1e-5)
    assert v.friction["words"] == "breaks at any friction: the load reaches the breaking load"
    assert math.isinf(v.friction["critical_mu"]) and v.friction["verdict_at_mu"] == 1.5


@pytest.mark.parametrize(
    ("material", "mu_star", "decided_by", "extra"),
    [("polypropylene", 0.166098, "thick-nip", {}),
     ("steel-wire", 0.4951, "DER-table", {"bending_scale": 0.02})],
)  # fmt: skip
def test_holds_only_above_mu_star_is_undecided(material, mu_star, decided_by, extra):
    """A clove hitch (6 mm on 40 mm, 200 N) of a rope with no friction row: UNDECIDED, holds
    only above mu* (polypropylene, kappa 0.02: the thick nip's 0.166098 at d/D 0.15; steel
    wire, E 49 GPa at its preset's kappa 0.02 given: the kappa-0.03 DER table's column; the
    preset's own range 0.009-0.1 reaches beyond every table), never SLIPS; the numbers are
    at mu*, where hold(mu=mu*) holds, and 1e-3 below it it does not."""
    kw = dict(POST, material=material, **extra)
    v = knotmech.hold("clove-hitch", **kw)
    f = v.friction
    assert v.state == "UNDECIDED" and v.fails_by is None and v.decided_by == decided_by
    assert f["critical_mu"] == pytest.approx(mu_star, abs=MU_RESOLUTION)
    at = knotmech.hold("clove-hitch", mu=f["critical_mu"], **kw)
    assert at.holds is True and at.margin == v.margin and v.inputs["mu"] == f["critical_mu"]
    assert knotmech.hold("clove-hitch", mu=f["critical_mu"] - MU_RESOLUTION, **kw).holds is not True
    assert f["holds_at_low"] is False and f["holds_at_high"] is True
    assert v.summary().startswith(
        f"verdict: UNDECIDED: holds only for mu above mu* = {f['critical_mu']:.3g} (no "
        f"published friction coefficient for {material} on steel); at mu* = "
    )
    assert v.next_step == "next: give --mu (mu=) measured for this rope"


def test_json_fields_of_an_unknown_friction():
    """Nylon on steel: the JSON carries the searched range, source null, published false,
    the post materials that have a coefficient and mu* as a number."""
    v = knotmech.hold("clove-hitch", **POST, material="nylon")
    d = _strict(v)
    f = d["friction"]
    assert f["range"] == [0.05, 1.5] and f["source"] is None and f["published"] is False
    assert f["post_material"] == "steel" and f["default_post_material"] is True
    assert f["published_post_materials"] == ["aluminium", "rope"]
    assert f["missing"] == (
        "no published friction coefficient for nylon on steel; published on aluminium, rope"
    )
    assert "nylon on steel and on wood: no measured value found" in f["why"]
    assert f["critical_mu"] == pytest.approx(0.166098, abs=MU_RESOLUTION)
    assert f["verdict_at"] == "critical mu" and f["verdict_at_mu"] == f["critical_mu"]
    assert d["holds"] is None and d["verdict"] == "undecided" and d["critical_mu_none"] is False
    assert d["inputs"]["mu"] == f["critical_mu"]
    # a published pair keeps its source and says so
    p = _strict(knotmech.hold("clove-hitch", **POST, material="polyester"))["friction"]
    assert p["published"] is True and "Delaney" in p["source"] and p["range"] == [0.19, 0.25]


def test_bend_without_rope_on_rope_data():
    """A reef knot of manila: no rope-on-rope coefficient, no post to name instead; the DER
    pull is the only model, so UNDECIDED even at mu 1.5 (numbers there: the breaking load,
    2.636 kN = 0.45 x the rope's 5.858 kN, as at mu 1.5), mu* not found (NaN: null,
    critical_mu_none false)."""
    v = knotmech.hold("reef", rod_diameter=10e-3, load=200, material="manila")
    f = v.friction
    assert v.state == "UNDECIDED" and f["post_material"] == "rope"
    assert f["default_post_material"] is False and f["published_post_materials"] == []
    assert f["verdict_at_mu"] == 1.5 and math.isnan(f["critical_mu"])
    at = knotmech.hold("reef", rod_diameter=10e-3, load=200, material="manila", mu=1.5)
    assert v.capacity.breaking.value == at.capacity.breaking.value
    assert v.capacity.breaking.value == pytest.approx(2636.058, rel=1e-6)
    assert v.capacity.efficiency[0] == pytest.approx(0.45)
    assert v.summary().startswith(
        "verdict: UNDECIDED: friction unknown and no model decides even at mu = 1.5 (no "
        "published friction coefficient for manila on rope); at mu = 1.5: slip load not known"
    )
    assert v.summary().endswith("next: give --mu (mu=) measured for this rope")
    # a bend's rope on rope is never "the default post material" (published or not)
    poly = knotmech.hold("reef", rod_diameter=10e-3, load=200, material="polyester")
    assert poly.friction["range"] == [0.12, 0.2] and poly.friction["default_post_material"] is False
    assert "default post material" not in poly.friction_line()
    d = _strict(v)
    assert d["friction"]["critical_mu"] is None and d["critical_mu_none"] is False


@pytest.mark.parametrize(
    ("knot", "kw"),
    [
        ("bowline", dict(rod_diameter=10e-3, pin_diameter=20e-3, load=2000.0)),
        ("prusik", dict(rod_diameter=6e-3, post_diameter=12e-3, load=200.0)),
    ],
)
def test_loop_and_prusik_answer_without_a_published_coefficient(knot, kw):
    """A loop (its pin) and the Prusik (along its pole) in nylon on steel: no closed form
    decides them, so UNDECIDED with the friction advice; the same breaking load as at
    mu 1.5."""
    v = knotmech.hold(knot, **kw, material="nylon")
    at = knotmech.hold(knot, **kw, material="nylon", mu=1.5)
    assert v.state == "UNDECIDED" and v.friction["published"] is False
    assert v.capacity.breaking.value == at.capacity.breaking.value
    assert v.next_step == (
        "next: give --mu (mu=) measured for this rope on this post, or --post-material "
        "aluminium or rope (post_material=)"
    )


def test_simulate_needs_a_friction_coefficient():
    with pytest.raises(
        knotmech.InputError,
        match="^simulate runs at one friction coefficient and there is no published friction "
        "coefficient for nylon on steel; published on aluminium, rope: give mu \\(measured\\) "
        "or post_material \\(aluminium, rope\\)$",
    ):
        knotmech.hold("clove-hitch", **POST, material="nylon", simulate=True)


def test_random_questions_agree_with_hold_at_a_given_mu():
    """Random questions without mu on every material without a published value (hitches,
    capstan, a bend; rope 2-20 mm, post 1-30 d, loads 1 N-10 kN): HOLDS is the verdict at
    0.05, SLIPS/BREAKS the verdict at 1.5, an UNDECIDED mu* holds at mu* and not 1e-3
    below it; strict JSON throughout."""
    rng = np.random.default_rng(2323)
    knots = ("clove-hitch", "two-half-hitches", "round-turn-two-half-hitches", "cow-hitch",
             "round-turn", "capstan", "reef")  # fmt: skip
    mats = ("manila", "polypropylene", "steel-wire", "vps32", "nylon")
    seen = set()
    for _ in range(24):
        knot = knots[rng.integers(len(knots))]
        d = 10 ** rng.uniform(math.log10(2e-3), math.log10(2e-2))
        mat = mats[rng.integers(len(mats))]
        if knot == "reef" and mat == "nylon":  # nylon on nylon is published
            mat = "manila"
        post = None if knot == "reef" else d * rng.uniform(1, 30)
        kw = dict(rod_diameter=d, post_diameter=post, load=10 ** rng.uniform(0, 4), material=mat)
        if knot == "capstan":
            kw.update(wrap_angle=2 * math.pi * rng.integers(1, 6), free_end_load=kw["load"] / 20)
        v = knotmech.hold(knot, **kw)
        f = v.friction
        _strict(v)
        seen.add(v.state)
        assert f["published"] is False and v.inputs["mu"] == f["verdict_at_mu"]
        if v.state == "HOLDS":
            assert f["verdict_at_mu"] == 0.05 and knotmech.hold(knot, mu=0.05, **kw).holds
        elif v.state in ("SLIPS", "BREAKS"):
            assert knotmech.hold(knot, mu=1.5, **kw).state == v.state
        elif math.isfinite(f["critical_mu"]):
            m = f["critical_mu"]
            assert knotmech.hold(knot, mu=m, **kw).holds is True
            assert knotmech.hold(knot, mu=m - MU_RESOLUTION, **kw).holds is not True
        else:
            assert knotmech.hold(knot, mu=1.5, **kw).holds is None
    assert {"SLIPS", "UNDECIDED"} <= seen

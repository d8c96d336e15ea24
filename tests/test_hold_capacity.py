"""The load a knot takes (issue 23): slip load from the DER hold tables, breaking load from
:mod:`knotmech.strength`, never "unbounded"."""

from __future__ import annotations

import itertools
import math

import numpy as np
import pytest

import knotmech
from knotmech.cli.hold import format_verdict
from knotmech.verdict import capacity as cap
from knotmech.verdict.tables import HoldPoint, HoldTable

# --------------------------------------------------------------------------- the bracket


@pytest.mark.parametrize(
    ("votes", "expected"),
    [
        ("HHsHs", (1e-3, 1e-2)),  # the first hold-to-slip step above the first hold
        ("sHHHs", (0.1, 0.3)),  # a light-load slip below (the rod does not seat) is skipped
        ("ssHHH", (0.3, math.inf)),  # nothing slipped above the holds
        ("sssss", (0.0, 1e-4)),  # slipped at the lightest load
        ("HH?HH", (0.3, math.inf)),  # a failed run below a hold is no evidence: passed over
        ("HH?sH", (1e-3, 0.1)),  # the bracket spans a failed run up to the first slip
        ("H?H?s", (1e-2, 0.3)),  # from the last load held below that slip
        ("?H???", (1e-3, 1e-2)),  # nothing slipped, runs above failed: ends at the first
        ("HHH?H", (0.3, math.inf)),  # a failed run below the last hold: open above
        ("??s??", (0.0, 1e-4)),  # nothing held
    ],
)
def test_column_bracket(votes, expected):
    loads = [1e-4, 1e-3, 1e-2, 0.1, 0.3]
    v = [{"H": True, "s": False, "?": None}[c] for c in votes]
    assert cap.column_bracket(loads, v) == expected
    ends_failed = cap.failed_above(v) is not None
    top = expected[1]
    assert ends_failed == (expected[0] > 0 and math.isfinite(top) and v[loads.index(top)] is None)


def test_a_band_that_ends_at_failed_runs_says_so():
    """The nylon clove hitch at kappa 0.003, 4 mm on 30 mm, mu 0.8: its column held up to
    0.01 EA and the runs at 0.1 and 0.3 EA failed (no verdict), so the band ends at 0.1 EA
    (31.4-314 N), named as where the runs failed, not as a slip."""
    v = knotmech.hold("clove-hitch", rod_diameter=4e-3, post_diameter=30e-3, mu=0.8, load=20.0,
                      material="nylon", bending_scale=0.003)  # fmt: skip
    s = v.capacity.slip
    assert s.low == pytest.approx(0.01 * 0.25e9 * math.pi * 4e-6, rel=1e-9)
    assert s.high == pytest.approx(10 * s.low, rel=1e-9)
    assert "ends where its runs failed (T/EA 0.1" in s.source
    assert v.holds is True


def _table(pattern: dict) -> HoldTable:
    """A hold table on d/2R (0.1, 0.2) x T/EA (1e-3, 1e-2, 0.1) x mu (0.2, 0.4) from a
    {(x, mu): "HHs"} pattern (held: creep 0; slipped: ran off)."""
    pts = []
    for (x, m), col in pattern.items():
        for y, c in zip((1e-3, 1e-2, 0.1), col, strict=True):
            pts.append(HoldPoint(x, y, m, 0.0 if c == "H" else math.nan, c == "H", True))
    return HoldTable("clove-hitch", pts)


def test_slip_from_table_interpolates_in_logs_and_keeps_the_widest_band():
    t = _table({(0.1, 0.2): "Hss", (0.1, 0.4): "HHs", (0.2, 0.2): "HHs", (0.2, 0.4): "HHs"})
    # on a column: the geometric mid-point of (1e-3, 1e-2)
    v, lo, hi, _ = cap.slip_from_table(t, x=0.1, mu=0.2)
    assert (v, lo, hi) == (pytest.approx(math.sqrt(1e-5), rel=1e-12), 1e-3, 1e-2)
    # half way in d/2R and in mu: exp of the mean of the logs of the four mid-points
    v, lo, hi, _ = cap.slip_from_table(t, x=0.15, mu=0.3)
    mids = [math.sqrt(1e-5)] + [math.sqrt(1e-3)] * 3
    assert v == pytest.approx(math.exp(np.mean(np.log(mids))), rel=1e-12)
    assert (lo, hi) == (1e-3, 0.1)
    # below the table's friction: less friction slips earlier, the band opens to 0
    assert cap.slip_from_table(t, x=0.1, mu=0.1)[1] == 0.0
    # above it: more friction slips later, the band opens above
    assert math.isinf(cap.slip_from_table(t, x=0.1, mu=0.6)[2])
    # outside the d/2R range: nothing
    assert cap.slip_from_table(t, x=0.3, mu=0.3) is None


def test_capacity_is_the_lower_of_slip_and_break():
    slip = cap.LoadBand(1400.0, 1100.0, 1900.0, "table")
    c = cap.capacity_of(knot="clove-hitch", slip=slip, material="nylon", d=0.0102, D=0.04,
                        load=200.0)  # fmt: skip
    # nylon 10.2 mm: 3-strand table, interpolated in d^2, x clove hitch 0.75
    assert c.limited_by == "slip" and c.value == 1400.0 and c.fraction(200.0) == 200 / 1400
    assert c.breaking.value == pytest.approx(0.75 * 16.4e3, rel=0.01)
    assert c.efficiency[0] == pytest.approx(0.75)
    strong = cap.LoadBand(50e3, 40e3, 60e3, "table")
    c = cap.capacity_of(knot="clove-hitch", slip=strong, material="nylon", d=0.0102, D=0.04,
                        load=200.0)  # fmt: skip
    assert c.limited_by == "break" and c.value == c.breaking.value
    # open above: HMPE 6 mm breaks at eta F, F = s d^2 (s = 1.088 kN/mm^2, the estimate
    # through two published single breaks) and eta the makers' rule for any knot in HMPE
    # (Marlow 40 %; rund-ums-tauwerk.de 25-50 %: median of mid-points 0.3875)
    open_ = cap.LoadBand(math.inf, 500.0, math.inf, "table")
    c = cap.capacity_of(knot="clove-hitch", slip=open_, material="hmpe", d=0.006, D=0.04,
                        load=200.0)  # fmt: skip
    assert c.limited_by == "break" and c.low == 500.0
    assert c.breaking.value == pytest.approx(0.3875 * 1.08794e9 * 0.006**2, rel=1e-5)
    assert "estimate: d^2 scaling through two published single breaks" in c.breaking.source
    # open above and no breaking load (HMPE 10 mm: outside the law's 3-8 mm): undecided
    c = cap.capacity_of(knot="clove-hitch", slip=open_, material="hmpe", d=0.010, D=0.04,
                        load=200.0)  # fmt: skip
    assert not c.decided and math.isnan(c.fraction(200.0))
    assert c.breaking_note == (
        "breaking load: no published data (rod_diameter 10 mm is outside the breaking-strength"
        " d^2 law for hmpe (3-8 mm)); source needed"
    )
    assert c.rope_strength is None


def test_without_a_knot_efficiency_the_rope_strength_bounds_the_break():
    """Thief knot in 10 mm polyester: no published efficiency; the rope's own MBS
    (19.5 kN, Robline RAPALLO table: 1950 daN at 10 mm) is named as an upper bound, in
    the words and the JSON, and is not taken as a capacity."""
    slip = cap.LoadBand(math.inf, 500.0, math.inf, "table")
    c = cap.capacity_of(knot="thief", slip=slip, material="polyester", d=0.010, D=None,
                        load=200.0)  # fmt: skip
    assert not c.decided and c.breaking is None
    assert c.rope_strength.high == pytest.approx(19.5e3)
    assert "RAPALLO" in c.rope_strength.source
    assert c.breaking_note == (
        "breaks below 20 kN (the rope's own strength; no published knot efficiency for thief)"
    )
    d = c.to_dict(200.0)
    assert d["rope_breaking_upper_bound"]["value_N"] == pytest.approx(19.5e3)
    assert d["value_N"] is None


def test_a_wrong_size_is_named_before_a_missing_friction():
    """A negative rope diameter with a material that has no friction on steel: the size
    is the error (it used to say 'no published friction coefficient')."""
    with pytest.raises(knotmech.InputError, match="^rod_diameter must be > 0, got -0.006$"):
        knotmech.hold("clove-hitch", rod_diameter=-6e-3, post_diameter=40e-3, load=200,
                      material="nylon")  # fmt: skip
    with pytest.raises(knotmech.InputError, match="^load must be > 0, got -200$"):
        knotmech.hold("clove-hitch", rod_diameter=6e-3, post_diameter=40e-3, load=-200,
                      material="nylon")  # fmt: skip


# --------------------------------------------------------------------------- real numbers


def test_issue_example_gives_the_load_it_takes():
    """The issue's command: 6 mm nylon (E 0.25 GPa, EA 7.07 kN) on a 40 mm post, mu 0.4,
    200 N. The kappa-0.01 clove-hitch table held up to its heaviest load (0.01 EA = 70.7 N)
    at every neighbour; the thick nip is self-locking up to its validity's 0.1 EA = 707 N;
    the rope breaks near 5.95 kN x 0.75 = 4.46 kN (nylon 3-strand table x Plymouth/Avery)."""
    v = knotmech.hold("clove-hitch", rod_diameter=6e-3, post_diameter=40e-3, mu=0.4, load=200,
                      material="nylon")  # fmt: skip
    c = v.capacity
    assert v.holds is True and c.limited_by == "break"
    assert c.slip.low == pytest.approx(0.1 * 0.25e9 * math.pi * 0.006**2 / 4, rel=1e-12)
    assert c.value == pytest.approx(4462.17, rel=1e-5)
    assert v.summary() == (
        "verdict: HOLDS: friction alone cannot unlock it up to 707 N, breaks near 4.5 kN (knot "
        "efficiency 75 %); 200 N is 4.5 % of the breaking load; decided by the thick-nip model "
        "(inputs inside its validity)"
    )


def test_solid_rod_table_gives_a_bracketed_slip_load():
    """The solid-rod clove-hitch table at d/2R = 0.2308 (4 mm on 13.3 mm), mu 0.3: the column
    reads slip, hold, hold, hold, slip over 1e-4 ... 0.3 EA, so the slip load lies between
    0.1 and 0.3 EA (geometric mid-point sqrt(0.03) EA); VPS32 E = 1.26 MPa, EA = 15.8 N."""
    EA = 1.26e6 * math.pi * 0.004**2 / 4
    v = knotmech.hold("clove-hitch", rod_diameter=4e-3, post_diameter=4e-3 / 0.2308 - 4e-3,
                      mu=0.3, load=1.0, material="vps32")  # fmt: skip
    s = v.capacity.slip
    assert (s.low, s.high) == (pytest.approx(0.1 * EA, rel=1e-3), pytest.approx(0.3 * EA, rel=1e-3))
    assert s.value == pytest.approx(math.sqrt(0.03) * EA, rel=2e-3)
    assert v.capacity.limited_by == "slip" and v.holds is True
    assert "slips near 2.74 N (1.58-4.75 N)" in v.summary()


# --------------------------------------------------------------------------- the grids
KNOTS = ("clove-hitch", "two-half-hitches", "round-turn-two-half-hitches")
SIZES = ((4, 30), (6, 40), (8, 60), (10, 80), (12, 100))
MUS = (0.1, 0.2, 0.3, 0.5)
LOADS = (50.0, 200.0, 1000.0, 5000.0)
MATERIALS = ("nylon", "polyester", "hmpe")
ISSUE_GRID = list(itertools.product(KNOTS, SIZES, MUS, LOADS, MATERIALS))


def _check(v) -> None:
    """Never unbounded; a finite capacity with its band, or undecided with a command."""
    text = format_verdict(v, verbose=True)
    assert "unbounded" not in text and not math.isinf(v.margin)
    d = v.to_dict()
    assert d["margin_unbounded"] is False
    c = v.capacity
    if c.decided:
        assert math.isfinite(c.value) and c.low <= c.value <= c.high < math.inf
        assert d["capacity"]["value_N"] == c.value
    else:
        assert d["capacity"]["value_N"] is None
        assert "next:" in v.next_step and ("--simulate" in v.next_step or "test the knot" in
                                           v.next_step)  # fmt: skip
    if v.holds is None:
        assert v.next_step
    if c.slip is not None and c.slip.bounded:
        assert c.slip.low <= c.slip.value <= c.slip.high


def _ask(knot, dD, mu, load, mat, free=0.0):
    return knotmech.hold(knot, rod_diameter=dD[0] * 1e-3, post_diameter=dD[1] * 1e-3, mu=mu,
                         load=load, material=mat, free_end_load=free)  # fmt: skip


@pytest.mark.parametrize("case", ISSUE_GRID[::37])
def test_issue_grid_sample(case):
    """A deterministic twentieth of the issue's 720 questions (the full grid is slow)."""
    _check(_ask(*case))


@pytest.mark.slow
def test_issue_grid_full():
    """The issue's 720 questions (3 hitches x 5 sizes x 4 mu x 4 loads x 3 materials, free
    end): none unbounded; a finite capacity or undecided with the command (about 25 s)."""
    states = set()
    for case in ISSUE_GRID:
        v = _ask(*case)
        _check(v)
        states.add(v.state)
    assert {"HOLDS", "SLIPS", "UNDECIDED"} <= states


def test_wider_random_grid():
    """Random questions over a wider range (every hitch, the capstan and a bend; rope 1-30
    mm, post 1-100 d, mu 0-1.5, loads 0.01 N-50 kN, loaded free ends, every material)."""
    rng = np.random.default_rng(23)
    knots = ("clove-hitch", "two-half-hitches", "round-turn-two-half-hitches", "cow-hitch",
             "round-turn", "capstan", "reef")  # fmt: skip
    mats = (None, "nylon", "polyester", "hmpe", "manila", "polypropylene", "steel-wire", "vps32")
    for _ in range(80):
        knot = knots[rng.integers(len(knots))]
        d = 10 ** rng.uniform(-3, math.log10(0.03))
        D = None if knot == "reef" else d * 10 ** rng.uniform(0, 2)
        load = 10 ** rng.uniform(-2, math.log10(5e4))
        free = 0.0 if rng.random() < 0.7 or knot == "reef" else load * rng.uniform(0, 0.5)
        v = knotmech.hold(knot, rod_diameter=d, post_diameter=D, mu=rng.uniform(0, 1.5),
                          load=load, free_end_load=free, material=mats[rng.integers(len(mats))],
                          wrap_angle=2 * math.pi if knot == "capstan" else None)  # fmt: skip
        _check(v)


# --------------------------------------------------------------------------- friction


def test_mu_from_the_material_and_post():
    """No mu: polyester on steel (default) is 0.19-0.25 (Delaney, RopeLab p. 88); the verdict
    is at 0.19. Two half hitches of 10 mm on 80 mm at 1 kN (d/2R 0.111, 0.0064 EA): the
    fibre-rope (kappa 0.01) table slips at mu 0.1 and 0.2 in every neighbouring column, so
    it slips at 0.19; from mu just above 0.2 the table's columns disagree and the thick nip
    (locked above 0.169 at d/D 1/8) decides: it holds only above mu* = 0.205 (at kappa 0.01
    given; over the preset's kappa range every table slips at 0.19). The clove hitch on the
    same post holds over the whole range."""
    v = knotmech.hold("two-half-hitches", rod_diameter=10e-3, post_diameter=80e-3, load=1000,
                      material="polyester", bending_scale=0.01)  # fmt: skip
    f = v.friction
    assert f["range"] == [0.19, 0.25] and f["post_material"] == "steel"
    assert f["default_post_material"] is True and "Delaney" in f["source"]
    assert v.inputs["mu"] == 0.19 and v.holds is False and v.decided_by == "DER-table"
    assert v.der["table_bending_scale"] == 0.01 and f["holds_at_high"] is True
    assert f["words"] == "holds only for mu above mu* = 0.205 (range 0.19-0.25)"
    nip = next(a for a in v.answers if a.model == "thick-nip")
    assert 0.16 < nip.critical_mu < 0.19 < f["critical_mu"] < 0.21
    # over the preset's kappa range 0.003-0.03 (tables at 0.003, 0.01 and 0.03 since session
    # 20) every table slips at 0.19: SLIPS at the range's low end, and the thick nip, which
    # the tables contradict, does not decide; at its high end 0.25 the tables disagree
    r = knotmech.hold("two-half-hitches", rod_diameter=10e-3, post_diameter=80e-3, load=1000,
                      material="polyester")  # fmt: skip
    assert r.holds is False and r.decided_by == "DER-table"
    assert [x["holds"] for x in r.der["kappa_range"]["readings"]] == [False, False, False]
    assert r.friction["words"] == "undecided over mu in [0.19, 0.25]"
    assert 0.25 < r.friction["critical_mu"] < 0.35
    nip = next(a for a in r.answers if a.model == "thick-nip")
    assert not nip.decides
    c = knotmech.hold("clove-hitch", rod_diameter=10e-3, post_diameter=80e-3, load=1000,
                      material="polyester", bending_scale=0.01)  # fmt: skip
    assert c.holds is True and c.friction["words"] == "holds for any mu in [0.19, 0.25]"
    # over the preset's kappa range the kappa-0.003 table slips at mu 0.19 (0.01 and 0.03
    # are undecided there), so the thick nip does not decide there: undecided, mu* 0.205
    cr = knotmech.hold("clove-hitch", rod_diameter=10e-3, post_diameter=80e-3, load=1000,
                       material="polyester")  # fmt: skip
    assert cr.holds is None
    assert cr.friction["words"].startswith("holds only for mu above mu* = 0.205")
    assert [r["holds"] for r in cr.der["kappa_range"]["readings"]] == [False, None, None]
    # on aluminium (0.14-0.221) the low end is below mu*: it holds only above it
    a = knotmech.hold("clove-hitch", rod_diameter=10e-3, post_diameter=80e-3, load=1000,
                      material="polyester", post_material="aluminium",
                      bending_scale=0.01)  # fmt: skip
    assert a.holds is False and a.friction["holds_at_high"] is True
    assert a.friction["words"].startswith("holds only for mu above mu* = 0.169")
    # mu overrides the post material
    m = knotmech.hold("clove-hitch", rod_diameter=10e-3, post_diameter=80e-3, load=1000, mu=0.4,
                      material="polyester", post_material="aluminium")  # fmt: skip
    assert m.inputs["mu"] == 0.4 and m.friction["range"] is None


def test_no_published_friction_answers_over_the_searched_range():
    """Nylon on steel has no published coefficient (friction.json not_found): no error any
    more (issue 23: mu optional for every preset) but UNDECIDED over mu 0.05-1.5, holding
    only above mu* (the thick nip's 0.16610 at d/D 0.15, found by bisection of the whole
    verdict to 1e-3), its numbers at mu*; mu stays required without a material."""
    kw = dict(rod_diameter=6e-3, post_diameter=40e-3, load=200, material="nylon")
    v = knotmech.hold("clove-hitch", **kw)
    f = v.friction
    assert v.state == "UNDECIDED" and f["published"] is False and f["source"] is None
    assert f["range"] == [0.05, 1.5] and f["published_post_materials"] == ["aluminium", "rope"]
    nip = next(a for a in v.answers if a.model == "thick-nip").critical_mu
    assert nip == pytest.approx(0.166098, abs=1e-6)
    assert nip <= f["critical_mu"] <= nip + 1e-3 and v.inputs["mu"] == f["critical_mu"]
    assert knotmech.hold("clove-hitch", mu=f["critical_mu"], **kw).holds is True
    assert knotmech.hold("clove-hitch", mu=f["critical_mu"] - 1e-3, **kw).holds is False
    with pytest.raises(knotmech.InputError, match="mu is required unless material is given"):
        knotmech.hold("clove-hitch", rod_diameter=6e-3, post_diameter=40e-3, load=200)


def test_json_carries_the_capacity_and_friction():
    import json

    v = knotmech.hold("clove-hitch", rod_diameter=6e-3, post_diameter=40e-3, mu=0.4, load=200,
                      material="nylon")  # fmt: skip
    d = json.loads(v.to_json())
    c = d["capacity"]
    assert c["limited_by"] == "break" and c["value_N"] == pytest.approx(4462.17, rel=1e-5)
    assert c["load_fraction"] == pytest.approx(200 / 4462.17, rel=1e-5)
    assert c["knot_efficiency"] == [0.75, 0.75, 0.75] and "Plymouth" in c["breaking"]["source"]
    assert c["slip"]["unbounded_above"] is True and c["slip"]["high_N"] is None
    assert d["friction"]["critical_mu"] == pytest.approx(0.166, abs=1e-3)
    assert d["critical_mu_none"] is False and d["margin_unbounded"] is False


def test_plot_draws_the_capacity_panel(tmp_path):
    """The capacity panel is drawn even where the table refuses (two half hitches in nylon
    at kappa 0.2, a factor 5 from the solid-rod table and 20 from the fibre-rope one): the
    breaking load, load and mu alone."""
    import matplotlib.image

    from knotmech.verdict import plot_verdict

    v = knotmech.hold("two-half-hitches", rod_diameter=6e-3, post_diameter=40e-3, mu=0.4,
                      load=200, material="nylon", bending_scale=0.2)  # fmt: skip
    assert v.der["refused"] == "bending_scale"
    p = plot_verdict(v, tmp_path / "cap.png")
    assert matplotlib.image.imread(p).shape[1] == pytest.approx(5.2 * 100, rel=0.05)
    w = knotmech.hold("clove-hitch", rod_diameter=6e-3, post_diameter=40e-3, mu=0.4, load=200,
                      material="nylon")  # fmt: skip
    # two friction slices and the capacity panel side by side
    q = plot_verdict(w, tmp_path / "cap3.png")
    assert matplotlib.image.imread(q).shape[1] == pytest.approx(3 * 5.2 * 100, rel=0.05)


def test_published_clove_hitch_drop_test_load_is_beyond_every_model():
    """Sterling's 10.2 mm dynamic-rope clove hitch slipped through at a 4.8 kN peak
    (slip_tests.json). On a 12 mm bar, nylon on aluminium (mu 0.221): 4.8 kN is 0.235 EA,
    beyond the thick nip's 10 % strain (it bounds the slip load from below by 0.1 EA =
    2.04 kN) and below the knot's breaking load (0.75 x 16.4 kN): undecided, with the
    command; 2 kN (issue 23's example) holds."""
    kw = dict(rod_diameter=10.2e-3, post_diameter=12e-3, material="nylon",
              post_material="aluminium")  # fmt: skip
    EA = 0.25e9 * math.pi * 0.0102**2 / 4
    v = knotmech.hold("clove-hitch", load=4800, **kw)
    assert v.holds is None and "--simulate" in v.next_step
    assert v.capacity.slip.low == pytest.approx(0.1 * EA, rel=1e-12)
    assert v.capacity.limited_by == "break" and 1.2e4 < v.capacity.value < 1.25e4
    assert knotmech.hold("clove-hitch", load=2000, **kw).holds is True

"""The DER table answer over a rope's estimated bending scale (knotmech.verdict.kappa).

A preset's kappa is an estimate with a range (nylon 0.01, range 0.003-0.03), and the hold
tables' answers depend on kappa inside it (the clove hitch: 15/20 and 17/20 of its points
agree between kappa 0.01 and 0.003 / 0.03, validation._hold_kappa_check). So a table answer
for a preset stands only if the tables read at the range's ends and its nominal value agree;
the slip load is then the band over those tables. Synthetic tables here (every run at
T_high/EA <= y_slip held, the rest ran off); the shipped tables' answers are in the goldens.
"""

from __future__ import annotations

import math

import pytest

import knotmech
from knotmech.verdict import der
from knotmech.verdict.capacity import merge_bands
from knotmech.verdict.kappa import RANGE_REFUSAL, range_points
from knotmech.verdict.tables import HoldPoint, HoldTable

XS, YS, MUS = (0.1, 0.2), (1e-4, 1e-3, 1e-2, 0.1), (0.2, 0.4)
D_ROPE = 6e-3
#: nylon (E 0.25 GPa): EA of a 6 mm rope [N]
EA = 0.25e9 * math.pi * D_ROPE**2 / 4
#: d/2R = 0.15 (between the columns), mu 0.3 (between the tables' 0.2 and 0.4)
Q = dict(rod_diameter=D_ROPE, post_diameter=D_ROPE / 0.15 - D_ROPE, mu=0.3, material="nylon")


def _table(kappa: float, y_slip: float, mu_min: float = 0.0) -> HoldTable:
    """A clove-hitch table at ``kappa``: runs at T_high/EA <= ``y_slip`` and mu >= ``mu_min``
    held (1e-6 d/s), the others ran off."""
    held = [(x, y, m, y <= y_slip and m >= mu_min) for x in XS for y in YS for m in MUS]
    pts = [HoldPoint(x, y, m, 1e-6 if h else math.nan, h, True) for x, y, m, h in held]
    return HoldTable("clove-hitch", pts, {"protocol_clock": "flexural", "bending_scale": kappa})


@pytest.fixture
def shipped(monkeypatch):
    """Replace the shipped clove-hitch tables by {kappa: table} of the test."""

    def use(*tables):
        sets = {"clove-hitch": {t.bending_scale: t for t in tables}}
        monkeypatch.setattr(der, "_shipped_hold_table_sets", lambda: sets)

    return use


def _der(load, **kw):
    v = knotmech.hold("clove-hitch", load=load, **{**Q, **kw})
    return v, v.der


def test_the_points_read_are_the_range_ends_and_the_nominal_once_each():
    assert range_points(0.01, 0.003, 0.03) == (0.003, 0.01, 0.03)
    assert range_points(0.01, 0.01, 0.03) == (0.01, 0.03)


def test_tables_that_agree_over_the_range_decide_and_say_so(shipped):
    shipped(_table(0.003, 1e-2), _table(0.01, 1e-2), _table(0.03, 0.1))
    v, d = _der(3e-3 * EA)  # between the loads 1e-3 and 1e-2: every table held both
    assert d["holds"] is True and "refused" not in d
    rng = d["kappa_range"]
    assert rng["agree"] is True and rng["range"] == [0.003, 0.03]
    assert [r["kappa"] for r in rng["readings"]] == [0.003, 0.01, 0.03]
    assert [r["table_bending_scale"] for r in rng["readings"]] == [0.003, 0.01, 0.03]
    table = next(a for a in v.answers if a.model == "DER-table")
    assert "the same at every kappa of the rope's estimated range 0.003-0.03" in table.validity[-1]


def test_a_softer_rope_that_slips_makes_the_tables_undecided(shipped):
    """At 3e-3 EA: the kappa-0.003 table slipped at every load while the 0.01 and 0.03
    tables held to 0.1 EA: the rope's bending stiffness decides."""
    shipped(_table(0.003, 0.0), _table(0.01, 0.1), _table(0.03, 0.1))
    v, d = _der(3e-3 * EA)
    assert d["holds"] is None and d["refused"] == RANGE_REFUSAL
    assert [r["holds"] for r in d["kappa_range"]["readings"]] == [False, True, True]
    assert d["message"].startswith(
        "not decided by the tables: the answer depends on the rope's bending stiffness inside "
        "its estimated range kappa 0.003-0.03 (kappa 0.003: slips; kappa 0.01: holds; kappa "
        "0.03: holds)"
    )
    assert d["message"].endswith("give --bending-scale (bending_scale=) for a measured rope")
    assert not any(a.model == "DER-table" for a in v.answers)
    # the thick nip (self-locking, inside its own validity) would say holds: the kappa-0.003
    # table contradicts it, so it does not decide either, and the verdict is undecided
    nip = next(a for a in v.answers if a.model == "thick-nip")
    assert nip.holds is True and not nip.inside_validity
    assert "the DER tables at kappa 0.003 of the rope's range say it slips" in nip.validity
    assert v.holds is None and v.decided_by is None
    assert v.summary().startswith("verdict: UNDECIDED: ")
    assert ("no model inside its validity decides; the DER tables' answer depends on the "
            "rope's bending stiffness over its estimated range kappa 0.003-0.03 (kappa 0.003: "
            "slips; kappa 0.01: holds; kappa 0.03: holds)") in v.summary()  # fmt: skip
    assert v.next_step.startswith("next: give --bending-scale (bending_scale=) for a measured "
                                  "rope; knotmech hold clove-hitch")  # fmt: skip
    assert "--simulate runs at the preset's kappa 0.01" in v.next_step


def test_a_given_bending_scale_reads_its_own_table_only(shipped):
    shipped(_table(0.003, 0.0), _table(0.01, 0.1), _table(0.03, 0.1))
    _, d = _der(3e-3 * EA, bending_scale=0.01)
    assert d["holds"] is True and "kappa_range" not in d and d["table_bending_scale"] == 0.01
    _, soft = _der(3e-3 * EA, bending_scale=0.003)
    assert soft["holds"] is False and soft["table_bending_scale"] == 0.003


def test_a_range_end_without_a_table_within_a_factor_3_is_undecided(shipped):
    """Only the 0.01 table: nylon's 0.003 is a factor 3.3 from it, so nothing reads there."""
    shipped(_table(0.01, 0.1))
    _, d = _der(3e-3 * EA)
    assert d["holds"] is None and d["refused"] == RANGE_REFUSAL
    assert d["message"].startswith("not decided by the tables: no answer at every kappa of "
                                   "the rope's estimated range kappa 0.003-0.03")  # fmt: skip
    assert "kappa 0.003: no table within a factor 3" in d["message"]
    assert [r["holds"] for r in d["kappa_range"]["readings"]] == [None, True, True]


def test_the_slip_load_is_the_band_over_the_range_tables(shipped):
    """At 3e-4 EA every table held (1e-4 and 1e-3 EA). The kappa-0.003 table slipped above
    1e-3 EA, the 0.01 and 0.03 tables above 1e-2 EA: the slip band runs from the softest's
    1e-3 EA to the others' 0.1 EA, at the nominal kappa-0.01 table's value (the geometric
    mid-point of 1e-2 and 0.1 EA); with --bending-scale 0.01 the 0.01 table's own band."""
    shipped(_table(0.003, 1e-3), _table(0.01, 1e-2), _table(0.03, 1e-2))
    v, d = _der(3e-4 * EA)
    assert d["kappa_range"]["agree"] is True and d["holds"] is True
    slip = v.capacity.slip
    assert (slip.low, slip.high) == pytest.approx((1e-3 * EA, 0.1 * EA), rel=1e-12)
    assert slip.value == pytest.approx(math.sqrt(1e-3) * EA, rel=1e-12)
    assert "over the rope's kappa range: tables at kappa 0.003, 0.01, 0.03" in slip.source
    one = knotmech.hold("clove-hitch", load=3e-4 * EA, bending_scale=0.01, **Q).capacity.slip
    assert (one.low, one.high) == pytest.approx((1e-2 * EA, 0.1 * EA), rel=1e-12)
    assert "kappa range" not in one.source


def test_merge_bands_takes_the_nominal_value_and_the_widest_band():
    from knotmech.verdict.capacity import LoadBand

    a, b = LoadBand(10.0, 5.0, 20.0, "soft"), LoadBand(40.0, 20.0, 80.0, "stiff")
    m = merge_bands([a, b], [0.003, 0.03], nominal=0.03)
    assert (m.value, m.low, m.high) == (40.0, 5.0, 80.0)
    assert merge_bands([a, b], [0.003, 0.03]).value == 10.0  # no nominal: the lowest
    assert merge_bands([a, None], [0.003, 0.03]) is None
    assert merge_bands([b], [0.01]) is b


def test_a_solid_rod_preset_has_no_range(shipped):
    """VPS32 is a solid rod (kappa 1, range 1-1): one table, no range reading."""
    shipped(_table(1.0, 0.1))
    _, d = _der(3e-3 * 1.26e6 * math.pi * D_ROPE**2 / 4, material="vps32")
    assert d["holds"] is True and "kappa_range" not in d


def test_the_tables_critical_mu_holds_at_every_kappa_of_the_range(shipped):
    """The kappa-0.003 table holds only at its mu 0.4, the others at 0.2 and 0.4: asked at
    mu 0.5, every table holds, and the tables' own critical mu is the 0.003 table's (the
    least mu at which all of them hold): above 0.2, at most 0.4; the 0.01 table alone holds
    from below its 0.2."""
    shipped(_table(0.003, 0.1, mu_min=0.4), _table(0.01, 0.1), _table(0.03, 0.1))
    v = knotmech.hold("clove-hitch", load=3e-3 * EA, **{**Q, "mu": 0.5})
    assert v.decided_by == "DER-table" and v.der["kappa_range"]["agree"] is True
    m = v.friction["model_critical_mu"]
    assert 0.2 < m <= 0.4, v.friction
    assert "at every kappa of the rope's range" in v.friction["model_critical_mu_text"]
    one = knotmech.hold("clove-hitch", load=3e-3 * EA, bending_scale=0.01, **{**Q, "mu": 0.5})
    assert one.decided_by == "DER-table" and one.friction["model_critical_mu"] < 0.2


def test_no_table_band_when_a_range_end_has_no_table(shipped):
    """The kappa-0.01 table alone (nylon's 0.003 a factor 3.3 from it): even where the
    tables' answer is undecided anyway, the slip band does not come from that table (it
    would hold at one kappa only); with --bending-scale 0.01 it does."""
    shipped(_table(0.01, 1e-2))
    v, d = _der(3e-4 * EA)
    assert d["refused"] == RANGE_REFUSAL
    assert v.capacity.slip is None or "DER clove-hitch hold table" not in v.capacity.slip.source
    one = knotmech.hold("clove-hitch", load=3e-4 * EA, bending_scale=0.01, **Q).capacity.slip
    assert "DER clove-hitch hold table" in one.source
    assert (one.low, one.high) == pytest.approx((1e-2 * EA, 0.1 * EA), rel=1e-12)

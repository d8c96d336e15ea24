"""Phase tables at several friction coefficients (knotmech.scenes.phase_table).

Synthetic tables test the bracketing logic of :class:`PhaseTableSet`; the shipped
tables (DER runs, clove-hitch paper sec. 8 / Fig. 4 protocol with a free end) are
tested for the values they hold and for the trend friction must follow.
"""

import json

import pytest

from knotmech.errors import InputError
from knotmech.scenes.phase_table import (
    PhasePoint,
    PhaseTable,
    PhaseTableSet,
    load_table,
    load_tables,
    table_resource,
)

XS = (0.1, 0.2)
YS = (0.1, 0.2, 0.3)


def _table(mu, critical):
    """Columns XS, loads YS; a load holds when it is below the column's critical load."""
    pts = [PhasePoint(x, y, y < c) for x, c in zip(XS, critical, strict=True) for y in YS]
    return PhaseTable(pts, mu=mu, mu_rr=mu)


@pytest.fixture
def tables():
    # mu 0.2: column 0.1 holds up to 0.1, column 0.2 holds nothing
    # mu 0.4: column 0.1 holds up to 0.2, column 0.2 holds up to 0.1
    return PhaseTableSet([_table(0.4, (0.25, 0.15)), _table(0.2, (0.15, 0.05))])


def test_set_on_a_table_uses_that_table(tables):
    assert tables.mus == [0.2, 0.4]
    a = tables.lookup(0.1, 0.2, mu=0.4)
    assert a.holds is True and a.mu_tables == (0.4,)
    assert a.bracket == (0.2, 0.3) and a.critical == pytest.approx(0.25)
    assert "table mu = mu_rr = 0.4" in a.message
    b = tables.lookup(0.1, 0.2, mu=0.2 + 0.004)  # within MU_TOL of 0.2
    assert b.holds is False and b.mu_tables == (0.2,)


def test_set_between_tables_decides_when_both_agree(tables):
    a = tables.lookup(0.1, 0.1, mu=0.3)  # held at 0.2 and at 0.4
    assert a.holds is True and a.inside and a.mu_tables == (0.2, 0.4)
    assert "bracket mu = 0.3" in a.message
    # critical: midpoints 0.15 (mu 0.2) and 0.25 (mu 0.4) interpolated at 0.3
    assert a.critical == pytest.approx(0.2)
    assert a.bracket == (0.1, 0.3)  # conservative: smallest held bound, largest slipped
    s = tables.lookup(0.1, 0.3, mu=0.3)  # slipped at 0.2 and at 0.4
    assert s.holds is False and s.mu_tables == (0.2, 0.4)


def test_set_between_tables_disagreeing_is_undecided(tables):
    a = tables.lookup(0.1, 0.2, mu=0.3)  # slips at 0.2, holds at 0.4
    assert a.holds is None and a.inside and a.mu_tables == (0.2, 0.4)
    assert "do not agree" in a.message and "--simulate" in a.message


def test_set_mu_rr_widens_the_bracket(tables):
    # mu = 0.4 on a table, but mu_rr = 0.3: bracketed by 0.2 (lower) and 0.4 (upper)
    a = tables.lookup(0.2, 0.1, mu=0.4, mu_rr=0.3)
    assert a.mu_tables == (0.2, 0.4) and a.holds is None
    assert tables.lookup(0.2, 0.1, mu=0.4, mu_rr=0.4).holds is True


def test_set_beyond_the_friction_range_decides_one_way(tables):
    # above the largest mu (0.4): a hold there is a hold; a slip there is undecided
    a = tables.lookup(0.1, 0.1, mu=0.5)
    assert a.holds is True and a.inside and a.mu_tables == (0.4,)
    assert "lies above the tables" in a.message and "more friction keeps that" in a.message
    u = tables.lookup(0.1, 0.3, mu=0.5)  # slips at 0.4
    assert u.holds is None and u.inside and "--simulate" in u.message
    # below the smallest mu (0.2): a slip there is a slip; a hold there is undecided
    s = tables.lookup(0.2, 0.1, mu=0.1)  # column 0.2 holds nothing at 0.2
    assert s.holds is False and s.mu_tables == (0.2,) and "less friction" in s.message
    assert tables.lookup(0.1, 0.1, mu=0.1).holds is None  # held at 0.2
    # mu_rr on the other side of the range: one-sided too
    assert tables.lookup(0.1, 0.1, mu=0.3, mu_rr=0.5).holds is True  # 0.2 table holds
    assert tables.lookup(0.2, 0.2, mu=0.3, mu_rr=0.1).holds is False  # 0.4 table slips
    # outside the grid at a covered mu: the table's own message
    assert "outside the DER table" in tables.lookup(0.5, 0.1, mu=0.3).message


def test_set_bad_input(tables):
    with pytest.raises(InputError, match="mu"):
        tables.lookup(0.1, 0.1, mu=-0.1)
    with pytest.raises(InputError, match="mu"):
        tables.lookup(0.1, 0.1, mu=float("nan"))
    with pytest.raises(InputError, match="same mu"):
        PhaseTableSet([_table(0.2, (0.1, 0.1)), _table(0.2, (0.2, 0.2))])
    with pytest.raises(InputError, match="mu = mu_rr"):
        PhaseTableSet([PhaseTable([PhasePoint(0.1, 0.1, True)], mu=0.3, mu_rr=0.2)])
    with pytest.raises(InputError, match="at least one"):
        PhaseTableSet([])
    with pytest.raises(InputError, match="no phase table"):
        tables.table(0.3)


def test_load_tables_from_files(tmp_path, tables):
    paths = []
    for t in tables.tables:
        p = tmp_path / table_resource(t.mu)
        t.write(p)
        paths.append(p)
    assert [p.name for p in paths] == [
        "clove_phase_table_mu0.2.json",
        "clove_phase_table_mu0.4.json",
    ]
    assert table_resource(0.3) == "clove_phase_table.json"
    back = load_tables(paths)
    assert back.mus == [0.2, 0.4]
    assert back.lookup(0.1, 0.1, mu=0.3).holds is True
    assert json.loads(paths[0].read_text())["mu"] == 0.2


def test_shipped_tables_are_backward_compatible():
    """load_table() is still the mu = 0.3 table; the set holds it plus the others."""
    t = load_table()
    assert t.mu == t.mu_rr == 0.3
    s = load_tables()
    assert 0.3 in s.mus
    assert s.table(0.3).to_dict()["points"] == t.to_dict()["points"]
    # the paper's geometry (d/2R = 4/34) at 0.1 EA held in the mu = 0.3 DER runs
    a = s.lookup(0.1176, 0.1, mu=0.3)
    assert a.holds is True and a.mu_tables == (0.3,)


# Shipped DER tables (python -m validation.clove_phase_diagram --write-table --mu <mu>):
# d = 4 mm VPS32 rod, free end, 4 x 4 grid; hold = end 0 creeps < d over the last 0.2 s.
SHIPPED_HOLDS = {0.2: 0, 0.25: 0, 0.3: 6, 0.35: 13, 0.4: 16, 0.5: 16}


def test_shipped_tables_grid_and_meta():
    s = load_tables()
    assert s.mus == sorted(SHIPPED_HOLDS)
    for m in s.mus:
        t = s.table(m)
        assert t.mu == t.mu_rr == m
        assert tuple(t.d_over_2R) == (0.06, 0.1176, 0.2, 0.3)
        assert tuple(t.t_over_EA) == (0.03, 0.1, 0.2, 0.3)
        assert len(t.points) == 16
        assert sum(p.holds for p in t.points) == SHIPPED_HOLDS[m]
        assert t.meta["generator"].startswith("python -m validation.clove_phase_diagram")
        assert (f"--mu {m:g}" in t.meta["generator"]) is (m != 0.3)
        assert t.meta["cpu_s_total"] > 0 and "written" in t.meta


def test_shipped_tables_values():
    s = load_tables()
    # mu = 0.35: everything holds up to 0.2 EA; 0.3 EA slips except at the paper's d/2R
    slips = {(p.d_over_2R, p.t_over_EA) for p in s.table(0.35).points if not p.holds}
    assert slips == {(0.06, 0.3), (0.2, 0.3), (0.3, 0.3)}
    # the paper's d/2R = 4/34 at 0.1 EA: slips at mu <= 0.25, holds from 0.3 on
    got = {m: s.lookup(4 / 34, 0.1, mu=m).holds for m in s.mus}
    assert got == {0.2: False, 0.25: False, 0.3: True, 0.35: True, 0.4: True, 0.5: True}
    # between tables: 0.325 is bracketed by 0.3 and 0.35 (both hold here) ...
    a = s.lookup(4 / 34, 0.1, mu=0.325)
    assert a.holds is True and a.mu_tables == (0.3, 0.35)
    # ... and at (0.2, 0.03) they disagree (0.3 slips, 0.35 holds): undecided
    b = s.lookup(0.2, 0.03, mu=0.325)
    assert b.holds is None and b.mu_tables == (0.3, 0.35) and "do not agree" in b.message
    # 0.22 between two all-slip tables slips; 0.45 between two all-hold tables holds
    assert s.lookup(0.3, 0.3, mu=0.22).holds is False
    assert s.lookup(0.3, 0.3, mu=0.45).holds is True


def test_shipped_tables_more_friction_never_turns_a_hold_into_a_slip():
    """Physically a hitch that holds at some friction must hold at any higher friction
    (same geometry and load). Checked over every pair of shipped tables and every point;
    also per column: the largest load held does not decrease with mu."""
    s = load_tables()
    for i, lo in enumerate(s.tables):
        held = {(p.d_over_2R, p.t_over_EA) for p in lo.points if p.holds}
        for hi in s.tables[i + 1 :]:
            lost = {(p.d_over_2R, p.t_over_EA) for p in hi.points if not p.holds} & held
            assert not lost, f"hold at mu = {lo.mu} but slip at mu = {hi.mu}: {sorted(lost)}"
    for x in (0.06, 0.1176, 0.2, 0.3):
        largest = [s.table(m).column_bracket(x)[0] for m in s.mus]
        assert largest == sorted(largest)

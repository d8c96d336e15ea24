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


def test_set_outside_the_friction_range(tables):
    for mu, mu_rr in ((0.5, None), (0.1, None), (0.3, 0.5), (0.3, 0.1)):
        a = tables.lookup(0.1, 0.1, mu=mu, mu_rr=mu_rr)
        assert a.holds is None and not a.inside and a.mu_tables == ()
        assert "outside the friction range" in a.message and "0.2, 0.4" in a.message
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

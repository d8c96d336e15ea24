"""Validation case 3 (clove hitch with a free end: hold/slip phase diagram).

Reference: the clove-hitch paper (Extreme Mech. Lett., DOI 10.1016/j.eml.2022.101788),
sec. 8 and Fig. 4: ideal-rope theory (Maddocks & Keller) says a clove hitch with a free
end slips at any load; experiments hold it below a critical T_high/EA that depends on
d/2R, with an upper bound near 0.3. The default test draws the diagram from the shipped
DER table (no simulation); the slow test simulates the quick 3 x 3 grid.
"""

import json
from pathlib import Path

import numpy as np
import pytest

from knotmech.cli.validate import load_case
from knotmech.scenes.phase_table import load_table

case = load_case("clove_phase_diagram")


@pytest.fixture(scope="module")
def shipped(tmp_path_factory):
    return case.run(quick=True, out_dir=tmp_path_factory.mktemp("cpd"), der=False)


def test_shipped_table_diagram(shipped):
    assert shipped["verdict"] == "pass", shipped["checks"]
    n = shipped["numbers"]
    assert n["source"].startswith("shipped DER table")
    assert n["n_hold"] > 0  # ideal rope: none
    assert n["EA_N"] == pytest.approx(1.26e6 * np.pi * 0.004**2 / 4)  # 15.83 N
    cols = n["boundary_columns_d_over_2R"]
    i = int(np.argmin(np.abs(np.array(cols) - 4 / 34)))
    # measured (16 DER runs): at the paper's d/2R the hitch holds 0.2 EA and slips at 0.3 EA
    assert n["boundary_lower_t_over_EA"][i] == pytest.approx(0.2)
    assert n["boundary_upper_t_over_EA"][i] == pytest.approx(0.3)
    # the boundary is largest at an interior d/2R, below the paper's bound 0.3
    assert n["boundary_largest_at_papers_d_over_2R"] is True
    assert cols[0] < n["boundary_peak_d_over_2R"] < cols[-1]
    assert 0.1 < n["boundary_peak_t_over_EA"] < 0.3
    png = Path(shipped["figures"][0])
    assert png.read_bytes()[:4] == b"\x89PNG"
    on_disk = json.loads((png.parent / "clove_phase_diagram.json").read_text())
    assert on_disk["numbers"] == shipped["numbers"]


def test_shipped_boundary_per_mu(shipped):
    """The diagram carries every shipped friction's boundary (tables at mu = mu_rr =
    0.2 ... 0.5, DER runs): all slip at 0.2 and 0.25 (midpoint = half of 0.03 EA), all
    hold at 0.4 and 0.5 (no slip above: inf), 0.35 slips only at 0.3 EA off the paper's
    d/2R, and no point that holds at a lower mu slips at a higher one."""
    n = shipped["numbers"]
    assert n["mu_tables"] == [0.2, 0.25, 0.3, 0.35, 0.4, 0.5]
    assert n["mu_tables_source"] == "shipped"
    per = n["boundary_per_mu"]
    assert per["0.2"]["mid_t_over_EA"] == pytest.approx([0.015] * 4)
    assert per["0.25"]["mid_t_over_EA"] == pytest.approx([0.015] * 4)
    assert per["0.3"]["mid_t_over_EA"] == pytest.approx([0.15, 0.25, 0.15, 0.015])
    assert per["0.35"]["lower_t_over_EA"] == pytest.approx([0.2, 0.3, 0.2, 0.2])
    assert per["0.35"]["upper_t_over_EA"][0] == pytest.approx(0.3)
    for key in ("0.4", "0.5"):  # numbers are JSON-ready: inf as "inf"
        assert [float(v) for v in per[key]["mid_t_over_EA"]] == [np.inf] * 4
    assert n["hold_to_slip_as_mu_rises_d_over_2R_t_over_EA_mu_lo_mu_hi"] == []


def test_hold_to_slip_as_mu_rises_finds_a_planted_violation():
    from knotmech.scenes.phase_table import PhasePoint, PhaseTable

    lo = PhaseTable([PhasePoint(0.1, 0.1, True), PhasePoint(0.1, 0.2, False)], mu=0.2, mu_rr=0.2)
    hi = PhaseTable([PhasePoint(0.1, 0.1, False), PhasePoint(0.1, 0.2, True)], mu=0.4, mu_rr=0.4)
    assert case.hold_to_slip_as_mu_rises({0.2: lo, 0.4: hi}) == [[0.1, 0.1, 0.2, 0.4]]


def test_fit_boundary_peak_of_a_known_parabola():
    """Midpoints on T = 0.3 - 10 (x - 0.15)^2 at three columns: the fit finds the peak."""
    from knotmech.scenes.phase_table import PhasePoint, PhaseTable

    pts = []
    for x in (0.05, 0.15, 0.25):
        m = 0.3 - 10 * (x - 0.15) ** 2
        pts += [PhasePoint(x, m - 0.01, True), PhasePoint(x, m + 0.01, False)]
    fit = case.fit_boundary(PhaseTable(pts))
    assert fit["peak_d_over_2R"] == pytest.approx(0.15, abs=1e-9)
    assert fit["peak_t_over_EA"] == pytest.approx(0.3, abs=1e-9)


def test_shipped_table_grid():
    t = load_table()
    assert len(t.points) == 16 and t.mu == t.mu_rr == 0.3
    assert tuple(t.d_over_2R) == case.GRID_FULL["d_over_2R"]
    assert tuple(t.t_over_EA) == case.GRID_FULL["t_over_EA"]


@pytest.mark.slow
def test_quick_spot_checks_reproduce_the_table(tmp_path):
    """Quick mode: 4 new DER runs (about 2.5 CPU-minutes) agree with the shipped table."""
    res = case.run(quick=True, out_dir=tmp_path)
    assert res["verdict"] == "pass", res["checks"]
    spots = res["numbers"]["spot_checks_d_over_2R_t_over_EA_der_table"]
    assert len(spots) == len(case.SPOT_CHECKS)
    assert all(der is table for _, _, der, table in spots)


@pytest.mark.slow
def test_der_grid_3x3(tmp_path):
    """9 DER runs across the boundary (about 15 CPU-minutes): reproduces the table."""
    res = case.run(quick=True, out_dir=tmp_path, grid=case.GRID_QUICK)
    assert res["verdict"] == "pass", res["checks"]
    table = load_table()
    for x, y, holds in res["numbers"]["points"]:
        assert table.lookup(x, y).holds is holds


@pytest.mark.slow
def test_full_mode_simulates_every_friction(tmp_path):
    """Full mode on a one-column grid (d/2R = 0.3; 12 DER runs, about 40 s): every
    shipped friction is simulated and reproduces its table."""
    from knotmech.scenes.phase_table import load_tables

    grid = {"d_over_2R": (0.3,), "t_over_EA": (0.03, 0.3)}
    res = case.run(quick=False, out_dir=tmp_path, grid=grid, processes=1)
    n = res["numbers"]
    assert n["mu_tables_source"] == "DER" and not n["failed"]
    tables = load_tables()
    assert len(n["boundary_per_mu"]) == len(tables.mus)
    for key, b in n["boundary_per_mu"].items():
        t = tables.table(float(key))
        light, heavy = t.lookup(0.3, 0.03).holds, t.lookup(0.3, 0.3).holds
        # bracket of the two simulated loads, as the shipped table's points predict it
        assert b["lower_t_over_EA"][0] == (0.3 if heavy else 0.03 if light else 0.0)
        assert float(b["upper_t_over_EA"][0]) == (np.inf if heavy else 0.3 if light else 0.03)


def test_figure_shows_every_mu_line_clear_of_the_legend(tmp_path, monkeypatch):
    """The legend sits in its own panel, every mu table's line lies inside the plot (the
    mu = 0.5 line used to be hidden under the legend) and no two lines coincide."""
    captured = []
    real_save = case.save_figure

    def keep(fig, out_dir, name, **kw):
        captured.append(fig)
        return real_save(fig, out_dir, name, **kw)

    monkeypatch.setattr(case, "save_figure", keep)
    result = case.run(quick=True, out_dir=tmp_path, der=False)
    (fig,) = captured
    ax = fig.axes[0]
    assert ax.get_legend() is None  # not drawn over the data
    legends = [a.get_legend() for a in fig.axes[1:] if a.get_legend() is not None]
    assert len(legends) == 1
    labels = [t.get_text() for t in legends[0].get_texts()]
    mus = result["numbers"]["mu_tables"]
    lines = [ln for ln in ax.get_lines() if ln.get_label().startswith("mu = ")]
    assert len(lines) == len(mus) >= 2
    lo, hi = ax.get_ylim()
    for ln in lines:
        y = np.asarray(ln.get_ydata(), dtype=float)
        assert np.all((y > lo) & (y < hi)), (ln.get_label(), y, (lo, hi))
        assert ln.get_label() in labels
    ys = [tuple(np.round(np.asarray(ln.get_ydata(), dtype=float), 6)) for ln in lines]
    assert len(set(ys)) == len(ys)  # none hidden under another
    assert any(lab.startswith("mu = 0.5:") for lab in labels)


@pytest.mark.parametrize("flags, what", [
    (["--loads", "0.1,abc"], "--loads: comma-separated numbers"),
    (["--loads", "0,0.1"], "T_high/EA values in (0, 1)"),
    (["--loads", "nan"], "T_high/EA values in (0, 1)"),
    (["--columns", "0.1,x"], "--columns: comma-separated numbers"),
    (["--columns", "0.5"], "d/2R values in (0, 0.5)"),
    (["--knot", "cow-hitch", "--t-low-fraction", "2"], "t_low_fraction must be at most 1"),
    (["--t-low-fraction", "0.5"], "clove-hitch has a free end"),
])  # fmt: skip
def test_write_hold_table_bad_grid_input_is_one_line(flags, what, tmp_path, capsys):
    """``--loads`` and ``--columns`` (the T_high/EA and d/2R values of a hold table's grid)
    and ``--t-low-fraction`` refuse bad values with one line and exit 2 before any run."""
    from validation.clove_phase_diagram import _main

    with pytest.raises(SystemExit) as e:
        _main(["--write-hold-table", str(tmp_path / "t.json"), *flags])
    assert e.value.code == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert what in err[-1] and not (tmp_path / "t.json").exists()

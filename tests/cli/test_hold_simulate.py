"""``knotmech hold`` with the DER phase diagram: table lookup, --simulate, disagreement.

The DER answer needs the rope's E (here ``--material vps32``, the tables' rod, or
``--youngs-modulus``); it is in the JSON key ``der`` and in ``answers``, and decides when
inside its table (knotmech.hold's rule). Tables here are written by the tests, so the
numbers do not depend on the shipped table (except in test_shipped_table_*).
"""

import json
import math

import pytest

from knotmech.cli.main import main
from knotmech.errors import InputError
from knotmech.scenes.phase_table import PhasePoint, PhaseTable, load_table, point_geometry

EA = 1.26e6 * math.pi * 0.004**2 / 4  # VPS32, d = 4 mm: 15.83 N

# column 0.1: holds up to 0.2, slips from 0.3; column 0.2: holds 0.1, slips from 0.2
POINTS = [
    (0.1, 0.1, True),
    (0.1, 0.2, True),
    (0.1, 0.3, False),
    (0.2, 0.1, True),
    (0.2, 0.2, False),
    (0.2, 0.3, False),
]


@pytest.fixture
def table_file(tmp_path):
    t = PhaseTable([PhasePoint(*p) for p in POINTS], mu=0.3, mu_rr=0.3)
    path = tmp_path / "table.json"
    t.write(path)
    return path


def _hold(d, D, load, *extra, mu="0.3"):
    args = ["hold", "clove-hitch", "--rod-diameter", d, "--post-diameter", D, "--mu", mu]
    if "--youngs-modulus" not in extra:
        args += ["--material", "vps32"]
    return args + ["--load", load, *extra]


def test_lookup_from_the_surrounding_grid_points():
    t = PhaseTable([PhasePoint(*p) for p in POINTS])
    assert t.column_bracket(0.1) == (0.2, 0.3)
    assert t.column_bracket(0.2) == (0.1, 0.2)
    a = t.lookup(0.15, 0.1)  # both columns held 0.1
    assert a.inside and a.holds is True
    assert a.bracket == pytest.approx((0.15, 0.25))  # upper boundary, half-way
    assert a.critical == pytest.approx(0.2)
    assert t.lookup(0.15, 0.3).holds is False  # both columns slipped 0.3
    assert t.lookup(0.2, 0.25).holds is False
    assert t.lookup(0.15, 0.2).holds is None  # 0.1 held, 0.2 slipped: near the boundary
    assert t.lookup(0.15, 0.14).holds is None  # corner (0.2, 0.2) slipped
    assert t.lookup(0.1, 0.15).holds is True  # on a column: its two loads held
    out = t.lookup(0.05, 0.1)
    assert not out.inside and out.holds is None and "outside" in out.message
    assert t.lookup(0.15, 0.5).holds is None  # above the largest load simulated
    assert t.lookup(0.15, 0.05).holds is None  # below the smallest
    assert "mu = 0.3 only" in t.lookup(0.15, 0.1, mu=0.5).message


def test_column_with_a_lower_boundary():
    """A light load that slips below loads that hold (a stiff rod not pulled tight)."""
    t = PhaseTable(
        [PhasePoint(0.3, 0.03, False), PhasePoint(0.3, 0.1, True), PhasePoint(0.3, 0.3, False)]
    )
    assert t.low_slip(0.3) == 0.03
    assert t.column_bracket(0.3) == (0.1, 0.3)
    assert t.lookup(0.3, 0.03).holds is False
    assert t.lookup(0.3, 0.1).holds is True
    assert t.lookup(0.3, 0.05).holds is None


def test_table_round_trip_and_bad_file(tmp_path, table_file):
    t = load_table(table_file)
    assert [(p.d_over_2R, p.t_over_EA, p.holds) for p in t.points] == POINTS
    bad = tmp_path / "bad.json"
    bad.write_text('{"points": 3}')
    with pytest.raises(InputError):
        load_table(bad)
    with pytest.raises(InputError):
        load_table(tmp_path / "missing.json")


def test_point_geometry():
    g = point_geometry(4 / 34)  # the paper's d = 4 mm, D = 30 mm
    assert g["post_diameter"] == pytest.approx(0.030)
    R = 0.017
    assert g["rod_length"] == pytest.approx(4 * math.pi * R * 1.15 + 0.128)
    with pytest.raises(InputError):
        point_geometry(0.5)


def test_cli_table_answer_disagrees_with_ideal_rope(table_file, capsys, tmp_path):
    # d = 4 mm, D = 36 mm: d/2R = 4/40 = 0.1; 0.15 EA = 2.37 N: 0.1 and 0.2 held
    out_json = tmp_path / "v.json"
    args = _hold(
        "4mm", "36mm", f"{0.15 * EA!r}N", "--phase-table", str(table_file), "--json", str(out_json)
    )
    assert main(args + ["--verbose"]) == 0
    text = capsys.readouterr().out
    # d/D = 0.11 is outside the ideal rope's validity (d/D <= 0.1): the DER table decides
    assert text.startswith("verdict: HOLDS") and "DER-table" in text.splitlines()[0]
    assert "disagreement: ideal-rope theory says it slips" in text
    data = json.loads(out_json.read_text())
    assert data["holds"] is True and data["decided_by"] == "DER-table"
    der = data["der"]
    assert der["source"] == "table" and der["holds"] is True and der["inside_table"]
    assert der["d_over_2R"] == pytest.approx(0.1)
    assert der["t_over_EA"] == pytest.approx(0.15)
    assert der["agrees_with_ideal_rope"] is False
    ans = next(a for a in data["answers"] if a["model"] == "DER-table")
    assert ans["decides"] is True and ans["holds"] is True
    assert ans["capacity"] == pytest.approx(0.2 * EA)  # largest load held in the column


def test_cli_table_slip_agrees(table_file, capsys):
    # 0.25 EA = 3.96 N at d/2R = 0.2 (D = 16 mm): slipped from 0.2
    args = _hold("4mm", "16mm", f"{0.25 * EA}N", "--phase-table", str(table_file), "--json", "-")
    assert main(args) == 0
    der = json.loads(capsys.readouterr().out)["der"]
    assert der["holds"] is False and der["agrees_with_ideal_rope"] is True


def test_cli_outside_table_and_other_mu(table_file, capsys):
    args = _hold("4mm", "100mm", "1N", "--phase-table", str(table_file), "--json", "-")
    assert main(args) == 0
    der = json.loads(capsys.readouterr().out)["der"]
    assert der["holds"] is None and not der["inside_table"] and "outside" in der["message"]
    # d/2R = 0.1, T_high/EA = 2.37 N / 15.8 N = 0.15: the mu = 0.3 table holds there, so a
    # larger mu holds (more friction keeps a hold) and a smaller one is undecided
    for mu, holds, words in (("0.5", True, "lies above the tables"),
                             ("0.2", None, "lies below the friction range")):  # fmt: skip
        args = _hold("4mm", "36mm", "2.37N", "--phase-table", str(table_file), "--json", "-", mu=mu)
        assert main(args) == 0
        der = json.loads(capsys.readouterr().out)["der"]
        assert der["holds"] is holds and der["mu_tables"] == [0.3] and words in der["message"]


def test_cli_free_end_load_and_youngs_modulus(table_file, capsys):
    args = _hold("4mm", "36mm", "1N", "--free-end-load", "0.5N", "--phase-table", str(table_file))
    assert main(args + ["--json", "-"]) == 0
    data = json.loads(capsys.readouterr().out)
    # the thick-nip model is self-locking (friction alone cannot unlock it) and nothing
    # bounds the slip load without a material (no breaking load, no EA): undecided (issue 23)
    assert data["holds"] is None and data["der"]["holds"] is None
    assert data["capacity"]["breaking"] is None and data["capacity"]["value_N"] is None
    assert "free end only" in data["der"]["message"]
    # a stiffer rod lowers T_high/EA: 4 N on E = 2.52 MPa is 0.126 EA -> holds at d/2R 0.1
    args = _hold("4mm", "36mm", "4N", "--youngs-modulus", "2.52MPa", "--phase-table")
    assert main(args + [str(table_file), "--json", "-"]) == 0
    der = json.loads(capsys.readouterr().out)["der"]
    assert der["t_over_EA"] == pytest.approx(4 / (2 * EA)) and der["holds"] is True


@pytest.mark.parametrize(
    ("extra", "name"),
    [
        (["--simulate", "--free-end-load", "0.1N"], "--simulate"),
        (["--youngs-modulus", "-1MPa"], "--youngs-modulus"),
        (["--youngs-modulus", "3mm"], "--youngs-modulus"),
    ],
)
def test_bad_input(extra, name, capsys):
    assert main(_hold("4mm", "30mm", "1N", *extra)) == 2
    err = capsys.readouterr().err
    assert name in err and len(err.strip().splitlines()) == 1


def test_simulate_only_for_clove_hitch_and_bends(capsys):
    args = ["hold", "round-turn", "--rod-diameter", "4mm", "--post-diameter", "30mm"]
    args += ["--mu", "0.3", "--load", "1N", "--simulate"]
    assert main(args) == 2
    assert "--simulate" in capsys.readouterr().err


def test_shipped_table_answers_the_papers_example(capsys):
    """The shipped DER table at the paper's geometry (d, D = 4, 30 mm, mu = 0.3): the
    paper's FEM (sec. 7) and experiments (Fig. 4) hold 1.47 N with a free end."""
    t = load_table()
    assert len(t.points) >= 9 and t.mu == 0.3
    assert main(_hold("4mm", "30mm", "1.47N", "--json", "-")) == 0
    der = json.loads(capsys.readouterr().out)["der"]
    assert der["source"] == "table" and der["holds"] is True
    assert der["agrees_with_ideal_rope"] is False


def test_simulate_wiring(monkeypatch, capsys):
    """--simulate calls simulate_point with the user's geometry (stubbed: no DER here)."""
    from knotmech.verdict import build as phase_table

    seen = {}

    def fake(**kw):
        seen.update(kw)
        return {"holds": True, "verdict": "hold", "creep": 1e-8, "creep_speed": 2e-5,
                "ran_to_end": True, "wall_s": 1.0, "message": ""}  # fmt: skip

    monkeypatch.setattr(phase_table, "simulate_point", fake)
    assert main(_hold("4mm", "36mm", "2N", "--simulate", "--mu-rr", "0.25", "--verbose")) == 0
    out = capsys.readouterr().out
    assert out.startswith("verdict: HOLDS") and "DER-simulation" in out.splitlines()[0]
    assert "disagreement" in out
    # the creep speed over the last second of the hold, in d/s and mm/s (2e-5 x 4 mm)
    assert (
        "creep: 2e-05 d/s (8e-05 mm/s) over the last 1 s of the hold, slower than the 0.001 d/s"
        in out
    )
    assert seen["d_over_2R"] == pytest.approx(0.1) and seen["t_over_EA"] == pytest.approx(2 / EA)
    assert seen["mu"] == 0.3 and seen["mu_rr"] == 0.25 and seen["progress"] is True
    assert seen["recheck"] is True and seen["creep_limit"] == 1e-3
    # --creep-limit reaches the run
    assert main(_hold("4mm", "36mm", "2N", "--simulate", "--creep-limit", "1e-5")) == 0
    assert seen["creep_limit"] == 1e-5


@pytest.mark.slow
def test_simulate_reproduces_the_shipped_table():
    """One DER run at a grid point of the shipped hold table (d/2R = 0.2308, d/D = 0.3: a
    13.3 mm post, 82 nodes, load 0.3 EA, mu 0.3: the end runs off, a slip, in ~9 s CPU)
    gives the table's answer."""
    from knotmech.scenes.phase_table import load_hold_tables

    D = 4e-3 * (1 / 0.2308 - 1)
    args = _hold("4mm", f"{D!r}m", f"{0.3 * EA!r}N", "--simulate", "--json", "-")
    import contextlib
    import io

    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        assert main(args) == 0
    data = json.loads(buf.getvalue())
    der = data["der"]
    assert der["source"] == "simulation"
    assert der["d_over_2R"] == pytest.approx(0.2308, rel=1e-9)
    expected = load_hold_tables()["clove-hitch"].point(0.2308, 0.3, 0.3).holds()
    assert expected is False
    assert der["holds"] is expected and data["creep"]["ran_off"] is True


def test_shipped_tables_answer_other_friction(capsys):
    """The paper's geometry (d, D = 4, 30 mm: d/2R = 4/34) at 1.47 N (0.093 EA, between the
    grid loads 0.01 and 0.1 EA) with a free end, from the shipped anchor-law clove-hitch
    table at other friction coefficients: mu = 0.1 slips (both loads ran off), 0.4 is
    bracketed by 0.3 and 0.5 (all four points held), 1.0 lies above the table and holds
    from mu = 0.8 (more friction keeps a hold), 0.05 lies below it and slips from 0.1."""
    out = {}
    for mu in ("0.05", "0.1", "0.4", "1.0"):
        assert main(_hold("4mm", "30mm", "1.47N", "--json", "-", mu=mu)) == 0
        data = json.loads(capsys.readouterr().out)
        out[mu] = (data["der"], data["decided_by"], data["holds"])
    der, by, holds = out["0.1"]
    assert der["holds"] is False and der["mu_tables"] == [0.1] and by == "DER-table"
    assert holds is False and der["rule"] == "grid"
    der, by, holds = out["0.4"]
    assert der["holds"] is True and der["mu_tables"] == [0.3, 0.5] and holds
    assert der["rule"] == "grid" and len(der["message"].split(" held")) == 5  # 4 points
    der, by, holds = out["1.0"]
    assert der["holds"] is True and der["mu_tables"] == [0.8] and by == "DER-table" and holds
    assert der["rule"] == "more-friction-holds"
    der, by, holds = out["0.05"]
    assert der["holds"] is False and der["rule"] == "less-friction-slips" and holds is False


def test_simulate_plot_draws_the_knot_coloured_by_tension(monkeypatch, tmp_path, capsys):
    """--simulate --plot draws the simulated centreline (stubbed run: a helix of 40 nodes
    around the 36 mm post, tension falling from 2 N to 0)."""
    from types import SimpleNamespace

    import numpy as np

    from knotmech.verdict import build as phase_table

    s = np.linspace(0, 4 * np.pi, 40)
    helix = np.c_[0.02 * np.cos(s), 0.02 * np.sin(s), 0.002 * s]
    result = SimpleNamespace(positions=helix[None], tension=np.linspace(2.0, 0.0, 39))

    def fake(**kw):
        assert kw["keep_result"] is True
        return {"holds": True, "verdict": "hold", "creep": 1e-5, "wall_s": 1.0, "message": "",
                "result": result}  # fmt: skip

    monkeypatch.setattr(phase_table, "simulate_point", fake)
    out = tmp_path / "knot.png"
    assert main(_hold("4mm", "36mm", "2N", "--simulate", "--plot", str(out))) == 0
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and out.stat().st_size > 10000
    # the verdict's JSON does not carry the arrays
    assert main(_hold("4mm", "36mm", "2N", "--simulate", "--json", "-")) == 0
    assert "positions" not in capsys.readouterr().out


def test_plot_without_a_der_answer_draws_the_capacity(capsys, tmp_path):
    # without E the DER tables (in T_high/EA) are not read, but the capacity against mu is
    # still drawn (issue 23: the closed forms' answer over mu, the user's load marked)
    args = ["hold", "clove-hitch", "--rod-diameter", "4mm", "--post-diameter", "100mm"]
    out = tmp_path / "p.png"
    assert main(args + ["--mu", "0.3", "--load", "1N", "--plot", str(out)]) == 0
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and out.stat().st_size > 10000


def test_simulated_slip_reports_no_creep(monkeypatch, capsys):
    """A run that slipped before the hold's measuring window has no creep (NaN): the
    verdict says so and the JSON has ``creep: null``, not a NaN."""
    from knotmech.verdict import build as phase_table

    def fake(**kw):
        return {"holds": False, "verdict": "slip", "creep": float("nan"),
                "creep_speed": float("nan"), "ran_to_end": False, "wall_s": 9.0,
                "message": "", "reason": "the loaded end ran off (run stopped early)"}  # fmt: skip

    monkeypatch.setattr(phase_table, "simulate_point", fake)
    assert main(_hold("4mm", "9.3333mm", "0.47N", "--simulate", "--json", "-")) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["holds"] is False and data["decided_by"] == "DER-simulation"
    assert data["creep"]["speed_d_per_s"] is None and data["creep"]["ran_off"] is True
    assert "ran off" in data["der"]["message"]
    assert main(_hold("4mm", "9.3333mm", "0.47N", "--simulate")) == 0
    assert "creep: the loaded end ran off" in capsys.readouterr().out


def test_a_run_that_stopped_while_settling_gives_no_verdict(monkeypatch, capsys):
    """Issue 27: a run that stopped before any load was on (in the settling) is a failed
    run, not a slip: the DER does not answer and the verdict names the run's stop."""
    from knotmech.verdict import build

    def fake(**kw):
        return {"holds": False, "verdict": "slip", "creep": float("nan"),
                "creep_speed": float("nan"), "ran_to_end": False, "wall_s": 0.0,
                "stopped_in": "settle", "stopped_at_protocol_s": 0.004,
                "message": "the rod left the post", "reason": "the loaded end ran off"}  # fmt: skip

    monkeypatch.setattr(build, "simulate_point", fake)
    assert main(_hold("4mm", "9.3333mm", "0.47N", "--simulate", "--json", "-")) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["der"]["holds"] is None and data["der"]["failed"] == "settle"
    assert "stopped while the knot settled, at 0.004 protocol s of 0.2" in data["der"]["message"]
    assert all(a["model"] != "DER-simulation" for a in data["answers"])
    assert data["decided_by"] != "DER-simulation"

"""``knotmech.hold`` on the shipped anchor-law hold tables: their real numbers.

The clove-hitch table (knotmech/data/hold_phase_table_clove-hitch.json, built by
``python -m validation.clove_phase_diagram --write-hold-table``; grid, costs and verdict
maps in docs/notes/holdtab.md): d = 4 mm VPS32 rod (E = 1.26 MPa, EA = 15.83 N),
d/2R = 0.01961, 0.04762, 0.1176, 0.2308 (d/D = 0.02, 0.05, 0.133, 0.3), T_high/EA = 1e-4,
1e-3, 1e-2, 0.1, 0.3, mu = mu_rr = 0.1, 0.2, 0.3, 0.5, 0.8.
"""

import json
import math
from pathlib import Path

import pytest

import knotmech
from knotmech.cli.main import main
from knotmech.scenes import phase_table as pt

EA = 1.26e6 * math.pi * 0.004**2 / 4  # 15.83 N


@pytest.fixture(scope="module")
def clove():
    return pt.load_hold_tables()["clove-hitch"]


def _post(d_over_2R, d=4e-3):
    return d * (1 / d_over_2R - 1)


def _hold(d_over_2R, t_over_EA, mu, **kw):
    return knotmech.hold(
        "clove-hitch", rod_diameter=4e-3, post_diameter=_post(d_over_2R), mu=mu,
        load=t_over_EA * EA, material="vps32", **kw,
    )  # fmt: skip


def test_the_shipped_table_covers_real_rope_ranges(clove):
    ax = clove.axes
    assert clove.law == "anchor" and clove.criterion["name"] == "creep-speed"
    assert clove.criterion["limit_d_per_s"] == 1e-3 and clove.criterion["window_s"] == 1.0
    assert ax["t_over_EA"][0] <= 1e-4 and ax["t_over_EA"][-1] >= 0.3 and ax["t_over_EA"].size >= 5
    d_over_D = ax["d_over_2R"] / (1 - ax["d_over_2R"])
    assert d_over_D[0] == pytest.approx(0.02, rel=1e-3) and d_over_D[-1] == pytest.approx(
        0.3, rel=2e-3
    )
    assert ax["d_over_2R"].size >= 4
    assert ax["mu"][0] == 0.1 and ax["mu"][-1] == 0.8 and ax["mu"].size >= 5
    assert len(clove.points) == ax["d_over_2R"].size * ax["t_over_EA"].size * ax["mu"].size
    # every run solved (the table built with cap floor 0 had one failure, the solver's
    # stall guard at d/D 0.05, 0.1 EA, mu 0.8; with the floor rule "min" it holds there)
    failed = [(p.d_over_2R, p.t_over_EA, p.mu) for p in clove.points if not p.solved]
    assert failed == []
    assert clove.lookup(0.04762, 0.1, mu=0.8).holds is True
    assert clove.meta["cpu_s_total"] > 0 and clove.meta["protocol"]["hold_time"] == 1.5


def test_the_table_ships_as_package_data():
    from importlib import resources

    names = [f.name for f in resources.files("knotmech").joinpath("data").iterdir()]
    assert pt.hold_table_resource("clove-hitch") in names
    text = resources.files("knotmech").joinpath("data", "hold_phase_table_clove-hitch.json")
    assert len(text.read_text()) < 20000  # compact


def test_papers_case_holds_from_the_table_with_its_creep():
    """d = 4 mm, D = 30 mm, mu = 0.3, 1.47 N = 0.0928 EA: between the grid loads 0.01 and
    0.1 EA on the paper's column, both held (creep 5.11e-5 and 2.8e-9 d/s)."""
    v = knotmech.hold("clove-hitch", rod_diameter=4e-3, post_diameter=30e-3, mu=0.3,
                      load=1.47, material="vps32")  # fmt: skip
    assert v.holds is True and v.decided_by == "DER-table" and v.der["rule"] == "grid"
    assert v.creep["speed_d_per_protocol_s"] == pytest.approx(5.11e-5, rel=0.01)
    # in the rod's own seconds: the preset's 1160 kg/m^3 against the tables' 1150
    s = (1160 / 1150) ** 0.5
    assert v.creep["limit_d_per_s"] == pytest.approx(1e-3 / s, rel=1e-9)
    assert v.creep["window_s"] == pytest.approx(s, rel=1e-9)
    # the whole column held up to 0.3 EA: margin at least 0.3 EA / 1.47 N - 1
    assert v.margin == pytest.approx(0.3 * EA / 1.47 - 1, rel=1e-6)
    # a stricter limit than the 5.11e-5 d/s crept makes (0.1176, 0.01) a slip, and
    # (0.1176, 0.1) at mu 0.5 (3.05e-5 d/s) a slip where mu 0.3 (2.8e-9 d/s) held: undecided
    w = knotmech.hold("clove-hitch", rod_diameter=4e-3, post_diameter=30e-3, mu=0.3,
                      load=1.47, material="vps32", creep_limit=1e-5)  # fmt: skip
    assert w.der["holds"] is None and "contradict more friction" in w.der["message"]
    assert "(0.1176, 0.01, mu 0.3) slipped, 5.1e-05 d/s" in w.der["message"]
    assert "against mu: held at mu 0.3, slipped at mu 0.5" in w.der["message"]
    assert "contradict" not in v.summary()


def test_an_undecided_first_line_names_runs_that_contradict_each_other_in_mu():
    """4 mm nylon two half hitches on 30 mm, mu 0.5, 50 N: the fibre-rope table's
    (0.1176, 0.01 EA) held at mu 0.5 and slipped at mu 0.8, and no closed form decides."""
    v = knotmech.hold("two-half-hitches", rod_diameter=4e-3, post_diameter=30e-3, mu=0.5,
                      load=50.0, material="nylon")  # fmt: skip
    assert v.holds is None and v.decided_by is None
    assert "against mu: held at mu 0.5, slipped at mu 0.8" in v.der["message"]
    assert v.summary().startswith("verdict: UNDECIDED")
    assert "the DER table's neighbouring runs contradict more friction" in v.summary()
    assert "--simulate" in v.summary()


def test_large_post_slips_where_the_thick_nip_says_it_holds():
    """d/D = 0.05 (D = 80 mm), 1.47 N: both neighbouring loads slipped (0.13 and 0.71 d/s)."""
    v = _hold(4 / 84, 1.47 / EA, 0.3)
    assert v.holds is False and v.decided_by == "DER-table"
    thick = next(a for a in v.answers if a.model == "thick-nip")
    assert thick.holds is True  # the closed form disagrees; the DER decides (the rule)
    assert v.creep["speed_d_per_s"] == pytest.approx(0.130, rel=0.01)


def test_beyond_the_loads(clove):
    # lighter than 1e-4 EA on the paper's column: 1e-4 and 1e-3 held -> holds
    v = _hold(0.1176, 1e-6, 0.3)
    assert v.holds is True and v.der["rule"] == "settled-light-load"
    # heavier than 0.3 EA at d/D = 0.3: 0.3 EA ran off -> slips
    v = _hold(0.2308, 0.5, 0.3)
    assert v.holds is False and v.der["rule"] == "heavier-slips"
    # heavier than 0.3 EA on the paper's column, which held 0.3 EA: undecided, and the
    # next step is the full command that decides
    v = _hold(0.1176, 0.5, 0.3)
    assert v.der["holds"] is None and "says nothing about a heavier load" in v.der["message"]


def test_undecided_gives_the_full_simulate_command():
    v = knotmech.hold("clove-hitch", rod_diameter=4e-3, post_diameter=200e-3, mu=0.3,
                      load=1.47, youngs_modulus=1e6)  # fmt: skip
    # d/D = 0.02 lies on the table; the ideal rope (inside its validity) decides there
    # unless the DER decides first: the DER table at 0.116 EA, between 0.1 and 0.3, slipped
    assert v.holds is False
    u = knotmech.hold("clove-hitch", rod_diameter=4e-3, post_diameter=400e-3, mu=0.3,
                      load=1.47, material="vps32")  # fmt: skip
    assert u.der["holds"] is None and "d/2R is below" in u.der["message"]


def test_cli_prints_the_creep_speed(capsys):
    args = ["hold", "clove-hitch", "--rod-diameter", "4mm", "--post-diameter", "30mm",
            "--mu", "0.3", "--load", "1.47N", "--material", "vps32"]  # fmt: skip
    assert main(args) == 0
    out = capsys.readouterr().out.splitlines()
    assert out[0].startswith("verdict: HOLDS") and "DER-table" in out[0]
    creep = next(line for line in out if line.startswith("creep:"))
    # 5.11e-5 d per protocol s = 5.09e-5 d/s for the preset's 1160 kg/m^3 (tables: 1150)
    assert "5.09e-05 d/s" in creep and "creep-speed criterion" in creep
    assert main(args + ["--json", "-"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["creep"]["speed_d_per_s"] == pytest.approx(5.09e-5, rel=0.01)
    assert data["creep"]["criterion"] == "creep-speed"


def test_two_half_hitches_from_their_table():
    """The two-half-hitches table over the clove hitch's full grid (4 d/2R x 5 T_high/EA x
    5 mu, 100 runs + 20 re-runs, floor rule "min", knotmech/data/hold_phase_table_two-half-
    hitches.json): on a 30 mm post at 0.5 N (0.0316 EA) it holds at mu = 0.5 (neighbours at
    0.01 and 0.1 EA held, 5.9e-7 and -1.6e-5 d/s) and slips at mu = 0.3 (both neighbouring
    loads ran off), where the thick-nip closed form says it holds; at mu = 0.8 both
    neighbours held too (-7.3e-6 and -1.1e-5 d/s; in the table built with cap floor 0 the
    0.1 EA point rang at -1.4e-3 d/s and the table did not decide there)."""
    t = pt.load_hold_tables()["two-half-hitches"]
    assert len(t.points) == 100 and t.mus == [0.1, 0.2, 0.3, 0.5, 0.8]
    kw = dict(rod_diameter=4e-3, post_diameter=30e-3, load=0.5, material="vps32")
    v = knotmech.hold("two-half-hitches", mu=0.5, **kw)
    assert v.holds is True and v.decided_by == "DER-table"
    assert v.creep["speed_d_per_s"] == pytest.approx(-1.559e-5, rel=0.01)
    w = knotmech.hold("two-half-hitches", mu=0.3, **kw)
    assert w.holds is False and w.decided_by == "DER-table" and w.creep["ran_off"] is True
    assert next(a for a in w.answers if a.model == "thick-nip").holds is True
    x = knotmech.hold("two-half-hitches", mu=0.8, **kw)
    assert x.holds is True and x.decided_by == "DER-table"


def test_round_turn_two_half_hitches_from_its_table():
    """The round turn and two half hitches' table (knotmech/data/hold_phase_table_round-turn-
    two-half-hitches.json, docs/notes/tables.md: HOLD_GRID's loads and frictions on the
    d/2R columns built so far, every point of them; 0.1176 and 0.2308 at least): on a 30 mm
    post at 0.5 N (0.0316 EA, between the grid loads 0.01 and 0.1 EA on the 0.1176 column)
    it holds at mu = 0.8 (both held, -8.3e-7 and 5.3e-5 d/s; the whole column held up to
    0.3 EA, so the margin is at least 0.3 EA / 0.5 N - 1) and slips at mu = 0.3 (0.01 EA
    changed topology, 0.1 EA ran off). At 1e-4 EA every point changed topology (the solid
    rod springs the half hitches open): a lighter load slips where the two lightest loads
    agree (mu 0.1) and is undecided where they do not (mu 0.5)."""
    t = pt.load_hold_tables()["round-turn-two-half-hitches"]
    ax = t.axes
    assert len(t.points) == ax["d_over_2R"].size * 25 and {0.1176, 0.2308} <= set(ax["d_over_2R"])
    assert t.mus == [0.1, 0.2, 0.3, 0.5, 0.8] and list(ax["t_over_EA"]) == [1e-4, 1e-3, 1e-2,
                                                                          0.1, 0.3]  # fmt: skip
    assert all(not t.point(x, 1e-4, m).holds() for x in (0.1176, 0.2308) for m in t.mus)
    kw = dict(rod_diameter=4e-3, post_diameter=30e-3, load=0.5, material="vps32")
    v = knotmech.hold("round-turn-two-half-hitches", mu=0.8, **kw)
    assert v.holds is True and v.decided_by == "DER-table" and v.der["rule"] == "grid"
    assert v.creep["speed_d_per_s"] == pytest.approx(5.29e-5, rel=0.02)
    assert v.margin == pytest.approx(0.3 * EA / 0.5 - 1, rel=1e-6)
    w = knotmech.hold("round-turn-two-half-hitches", mu=0.3, **kw)
    assert w.holds is False and w.decided_by == "DER-table"
    light = dict(rod_diameter=4e-3, post_diameter=30e-3, load=1e-5 * EA, material="vps32")
    a = knotmech.hold("round-turn-two-half-hitches", mu=0.1, **light)
    assert a.holds is False and a.der["rule"] == "settled-light-load"
    b = knotmech.hold("round-turn-two-half-hitches", mu=0.5, **light)
    assert b.der["holds"] is None


def test_plot_draws_the_table_of_any_hitch(tmp_path, capsys):
    """--plot draws the hold table that answered, for every hitch with one (here two half
    hitches at mu = 0.4: the mu = 0.3 and 0.5 slices), titled with the knot's name."""
    out = tmp_path / "thh.png"
    args = ["hold", "2hh", "--rod-diameter", "4mm", "--post-diameter", "30mm", "--mu", "0.4",
            "--load", "0.5N", "--material", "vps32", "--plot", str(out)]  # fmt: skip
    assert main(args) == 0
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and out.stat().st_size > 20000
    assert "wrote" in capsys.readouterr().err
    # a hitch with no DER answer (the round turn alone) is refused in one line
    bad = ["hold", "round-turn"] + args[2:]
    assert main(bad) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and "--plot" in err


def test_cow_hitch_from_its_table(capsys):
    """The cow hitch loaded on one leg, the other free (knotmech/data/hold_phase_table_cow-
    hitch.json, docs/notes/tables.md; HOLD_GRID's loads and frictions on the d/2R columns
    built so far, 0.1176 and 0.2308 at least). On a 30 mm post (the 0.1176 column): 0.3 N
    (0.019 EA, between 0.01 and 0.1 EA) holds at mu = 0.8 (both held, creeps 2.1e-5 and
    9.8e-6 d/s; the column held to 0.3 EA; table rebuilt with the floor rule "min"), slips
    at mu = 0.3 (both ran off) and is undecided at mu = 0.5 (0.01 EA held, 0.1 EA ran off),
    with the --simulate command, the ideal rope being outside its validity at d/D = 0.133;
    0.1 N (0.0063 EA) holds at mu = 0.5 (1e-3 and 0.01 EA held, largest creep 7.1e-5 d/s,
    margin 0.01 EA / 0.1 N - 1)."""
    t = pt.load_hold_tables()["cow-hitch"]
    assert len(t.points) == t.axes["d_over_2R"].size * 25 and t.mus == [0.1, 0.2, 0.3, 0.5, 0.8]
    kw = dict(rod_diameter=4e-3, post_diameter=30e-3, material="vps32")
    v = knotmech.hold("cow-hitch", mu=0.8, load=0.3, **kw)
    assert v.holds is True and v.decided_by == "DER-table" and v.der["rule"] == "grid"
    assert v.creep["speed_d_per_s"] == pytest.approx(2.05e-5, rel=0.02)
    assert v.margin == pytest.approx(0.3 * EA / 0.3 - 1, rel=1e-6)
    assert knotmech.hold("cow-hitch", mu=0.3, load=0.3, **kw).holds is False
    u = knotmech.hold("cow-hitch", mu=0.5, load=0.3, **kw)
    assert u.holds is None and u.der["rule"] == "undecided"
    assert u.next_step.startswith("next: knotmech hold cow-hitch --rod-diameter 4mm")
    assert "--mu 0.5 --load 0.3N --material vps32 --simulate" in u.next_step
    w = knotmech.hold("girth hitch", mu=0.5, load=0.1, **kw)
    assert w.holds is True and w.creep["speed_d_per_s"] == pytest.approx(7.08e-5, rel=0.02)
    assert w.margin == pytest.approx(0.01 * EA / 0.1 - 1, rel=1e-6)
    # the CLI says the same, and draws the table
    args = ["hold", "lark's head", "--rod-diameter", "4mm", "--post-diameter", "30mm", "--mu",
            "0.8", "--load", "0.3N", "--material", "vps32", "--json", "-"]  # fmt: skip
    assert main(args) == 0
    data = json.loads(capsys.readouterr().out)
    assert data["holds"] is True and data["decided_by"] == "DER-table"
    assert data["creep"]["window_s"] == pytest.approx(0.75 * (1160 / 1150) ** 0.5, rel=1e-9)


def test_critical_load_figure_reads_the_tables_bands():
    """docs/figures/hold_tables_critical_load.py: every shipped table, and the bands the
    docs' table describes for the solid clove hitch (mu 0.1-0.2 slip at the lightest load
    on every column; mu 0.3 holds the paper's column, d/D 0.133, up to 0.3 EA)."""
    import importlib.util

    path = Path(__file__).resolve().parents[1] / "docs" / "figures" / "hold_tables_critical_load.py"
    spec = importlib.util.spec_from_file_location("hold_tables_critical_load", path)
    fig = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(fig)
    tabs = fig.tables()
    assert "clove-hitch (solid rod)" in tabs and "clove-hitch (fibre rope, kappa 0.01)" in tabs
    b = fig.bands(tabs["clove-hitch (solid rod)"])
    for m in (0.1, 0.2):
        assert all((lo, hi) == (0.0, 1e-4) for _, lo, hi in b[m])
    dD, lo, hi = b[0.3][2]
    assert dD == pytest.approx(0.1176 / (1 - 0.1176), rel=1e-12)
    assert (lo, hi) == (0.3, math.inf)
    # the fibre clove hitch on the paper's column at mu 0.3, by kappa (session 19 tables):
    # held to 0.3 EA at kappa 0.03 and 0.01, slipped between 0.01 and 0.1 EA at 0.003
    for kappa, band in ((0.03, (0.3, math.inf)), (0.01, (0.3, math.inf)), (0.003, (0.01, 0.1))):
        rows = fig.bands(tabs[f"clove-hitch (fibre rope, kappa {kappa:g})"])[0.3]
        assert rows[2][1:] == band, kappa


def _result(status, topology, ran, speed=math.nan):
    """A simulate_point-like result of an anchor run whose point verdict it judged slip."""
    return {"d_over_2R": 0.1176, "t_over_EA": 0.3, "mu": 0.5, "creep_speed": speed,
            "ran_to_end": ran, "topology_preserved": topology, "holds": False,
            "status": status}  # fmt: skip


@pytest.mark.parametrize(
    ("status", "topology", "ran", "expected"),
    [
        ("failed", True, False, None),  # stalled, knot intact: creep never measured
        ("failed", False, False, False),  # the knot came apart before the solver failed
        ("success", True, False, False),  # the loaded end ran off (a run stopped early)
    ],
)
def test_a_failed_run_with_its_topology_kept_is_no_verdict(status, topology, ran, expected):
    from knotmech.verdict.criterion import solver_gave_verdict
    from knotmech.verdict.tables import HoldTable

    t = HoldTable.from_results("clove-hitch", [_result(status, topology, ran)])
    assert t.points[0].holds() is expected
    assert solver_gave_verdict(status, topology) is (expected is not None)


def test_the_rejudged_kappa_0003_table():
    """Session 20 re-judged the clove hitch's kappa-0.003 table from its sweep cache: the
    ten runs that failed in the solver with the knot intact (7 stalled, 3 below dt_min; all
    at 0.1-0.3 EA) are no verdict; the paper's column at mu 0.3 still slips at 0.1 EA (its
    topology changed) and 0.3 EA (ran off), where kappa 0.01 held."""
    from knotmech.verdict.der import shipped_hold_table

    t = shipped_hold_table("clove-hitch", 0.003)
    failed = sorted(tuple(p) for p in t.meta["rejudged"]["points"])
    assert len(failed) == 10
    assert all(y in (0.1, 0.3) and m >= 0.3 for _, y, m in failed)
    assert all(t.point(*p).holds() is None for p in failed)
    assert t.point(0.1176, 0.1, 0.3).holds() is False
    assert not t.point(0.1176, 0.1, 0.3).topology
    assert t.point(0.1176, 0.3, 0.3).holds() is False
    assert shipped_hold_table("clove-hitch", 0.01).point(0.1176, 0.1, 0.3).holds() is True

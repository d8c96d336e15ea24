"""Tests of knotmech.strength: every tabulated number against its source, the
interpolation, the efficiency and friction rules, and bad input.

The source values below are transcribed a second time, by hand, from the source named
in each comment (not read from the JSON), so that a typo in the data fails a test.
"""

from __future__ import annotations

import json
import math
from importlib import resources

import numpy as np
import pytest

from knotmech import strength
from knotmech.errors import InputError
from knotmech.strength import NoDataError

LBF = 4.4482216152605  # N
KGF = 9.80665  # N
INCH = 0.0254  # m


def _table(table_id):
    (t,) = [t for t in strength._mbs_tables() if t.id == table_id]
    return t


# (table id, diameter [m], breaking load [N]) read from each source, one a row.
SOURCE_ROWS = [
    # Bluewater static ratings table, rows II++: 9.5 mm 24.4 kN ... 13 mm 45.6 kN
    ("nylon-kernmantle-bluewater", 9.5e-3, 24.4e3),
    ("nylon-kernmantle-bluewater", 10.5e-3, 31.9e3),
    ("nylon-kernmantle-bluewater", 11.2e-3, 32.9e3),
    ("nylon-kernmantle-bluewater", 13e-3, 45.6e3),
    # Engineering ToolBox, Nylon Ropes - Strengths: 1/2 in 5670 lbf, 1 in 22230 lbf
    ("nylon-3strand-engineeringtoolbox", 0.5 * INCH, 5670 * LBF),
    ("nylon-3strand-engineeringtoolbox", 1.0 * INCH, 22230 * LBF),
    ("nylon-3strand-engineeringtoolbox", 2.0 * INCH, 84600 * LBF),
    # industrialrope.com, NYLON minimum tensile: 1/2 in 5,750 lbf; 13/16 in 15,300 lbf
    ("nylon-3strand-industrialrope", 0.5 * INCH, 5750 * LBF),
    ("nylon-3strand-industrialrope", 13 / 16 * INCH, 15300 * LBF),
    # Robline RAPALLO: 10 mm 1950 daN, 24 mm 10200 daN
    ("polyester-robline-rapallo", 10e-3, 19500.0),
    ("polyester-robline-rapallo", 24e-3, 102000.0),
    # Rope Inc. tensile strength, Polyester column: 3/8 in 3700 lbf, 5/8 in 10000 lbf
    ("polyester-ropeinc", 3 / 8 * INCH, 3700 * LBF),
    ("polyester-ropeinc", 5 / 8 * INCH, 10000 * LBF),
    # Cordage Institute CI 1308-96 (manila): 1/2 in 2385 lbf, 1 5/16 in 13500 lbf
    ("manila-ci1308", 0.5 * INCH, 2385 * LBF),
    ("manila-ci1308", 21 / 16 * INCH, 13500 * LBF),
    # Engineering ToolBox manila: 3/8 in 1212 lbf (CI 1308: 1215), 1 3/8 in 13500 lbf
    ("manila-engineeringtoolbox", 3 / 8 * INCH, 1212 * LBF),
    ("manila-engineeringtoolbox", 11 / 8 * INCH, 13500 * LBF),
    # industrialrope.com POLYPROPYLENE: 3/16 in 720 lbf, 1 1/16 in 14,400 lbf
    ("polypropylene-industrialrope", 3 / 16 * INCH, 720 * LBF),
    ("polypropylene-industrialrope", 17 / 16 * INCH, 14400 * LBF),
    # Engineering ToolBox polypropylene: 1/2 in 3780 lbf, 2 in 46800 lbf
    ("polypropylene-engineeringtoolbox", 0.5 * INCH, 3780 * LBF),
    ("polypropylene-engineeringtoolbox", 2.0 * INCH, 46800 * LBF),
    # Engineering ToolBox 6x19 IPS FC: 5/8 in 33400 lbf, 1 1/2 in 184000 lbf
    ("steel-6x19-ips-fc-engineeringtoolbox", 5 / 8 * INCH, 33400 * LBF),
    ("steel-6x19-ips-fc-engineeringtoolbox", 1.5 * INCH, 184000 * LBF),
]


@pytest.mark.parametrize(("table_id", "diameter", "load"), SOURCE_ROWS)
def test_tabulated_row_reproduces_its_source(table_id, diameter, load):
    t = _table(table_id)
    i = int(np.argmin(abs(t.diameters - diameter)))
    assert t.diameters[i] == pytest.approx(diameter, rel=1e-12)
    assert t.loads[i] == pytest.approx(load, rel=1e-12)
    # the interpolation returns a tabulated point exactly
    assert strength._interp_d2(t, np.array([t.diameters[i]]))[0] == t.loads[i]


@pytest.mark.parametrize("table", strength._mbs_tables(), ids=lambda t: t.id)
def test_every_table_increases_with_diameter_and_cites_its_source(table):
    assert np.all(np.diff(table.diameters) > 0)
    assert np.all(np.diff(table.loads) > 0)
    raw = json.loads(
        resources.files("knotmech").joinpath("data", "strength", "mbs.json").read_text()
    )
    (entry,) = [t for t in raw["tables"] if t["id"] == table.id]
    assert entry["source"] and entry["where"] and entry["url"].startswith("http")


def test_interpolation_is_linear_in_diameter_squared():
    # midway in d^2 between 1/2 in (2385 lbf) and 9/16 in (3105 lbf), CI 1308 manila
    d = math.sqrt(((0.5 * INCH) ** 2 + (9 / 16 * INCH) ** 2) / 2)
    assert strength.breaking_load("manila", d).nominal == pytest.approx(
        (2385 + 3105) / 2 * LBF, rel=1e-12
    )


@pytest.mark.parametrize("material", ["nylon", "polyester", "manila", "polypropylene", "steel"])
def test_nominal_is_monotonic_and_inside_the_range(material):
    tables = strength.breaking_load_tables(material)
    d = np.linspace(min(t.diameters[0] for t in tables), max(t.diameters[-1] for t in tables), 997)
    est = strength.breaking_load(material, d)
    assert est.nominal.shape == d.shape
    assert np.all(np.diff(est.nominal) >= 0)
    assert np.all(est.low <= est.nominal) and np.all(est.nominal <= est.high)


def test_units_newtons_and_metres():
    # CI 1308-96: 1/2 in manila 2385 lbf; the first (nominal) table for manila
    assert strength.breaking_load("manila", 0.0127).nominal == pytest.approx(2385 * LBF)
    # the range spans the sources: nylon 1/2 in, 5670 (ToolBox) to 5750 lbf (industrialrope)
    est = strength.breaking_load("nylon", 0.0127)
    assert est.nominal == pytest.approx(5670 * LBF)
    assert est.low == pytest.approx(5670 * LBF)
    assert est.high >= 5750 * LBF  # Bluewater kernmantle 11.2-13 mm is higher still
    assert "Engineering ToolBox" in est.source and "industrialrope" in est.source


def test_steel_table_agrees_with_the_en12385_breaking_force_formula():
    # F_min = d^2 R_r K / 1000 [kN] with K = 0.330 for 6x19 fibre core and grade 1770
    # (Vornbaeumen technical notes, 'Calculation variables', table of calculation factors)
    d_mm = 5 / 8 * 25.4
    formula = d_mm**2 * 1770 * 0.330  # N
    assert strength.breaking_load("steel-wire", d_mm * 1e-3).nominal == pytest.approx(
        formula, rel=0.02
    )


def test_a_measured_break_exceeds_the_makers_minimum():
    # Marlow's 10 mm 3-strand pre-stretched polyester broke at 2640 kg (Yachting Monthly,
    # Nov. 2017, p. 70); Robline's 10 mm polyester MBL is 1950 daN.
    assert strength.breaking_load("polyester", 0.010).nominal < 2640 * KGF


# HMPE: no maker's table; F = s d^2 through two published single breaks, read again by
# hand: 1/8 in Amsteel "2500 lb bs" (hwstock.org/rope/amsteeltrilene, second paragraph)
# and the 7 mm SK78 core of Marlow D2 Racing 10 mm broken at 5360 kg (Yachting Monthly,
# Nov. 2017, p. 70, row 'D2 Racing', 'Rope Break Load (kg)').
AMSTEEL = (0.125 * INCH, 2500 * LBF)
D2_CORE = (7e-3, 5360 * KGF)
S_POINTS = [f / d**2 for d, f in (AMSTEEL, D2_CORE)]  # 1.103 and 1.073 kN/mm^2


@pytest.mark.parametrize(("d", "f"), [AMSTEEL, D2_CORE])
def test_hmpe_law_passes_each_published_break_within_its_band(d, f):
    est = strength.breaking_load("hmpe", d)
    assert est.low <= f <= est.high
    # nominal s = mean of the two points: 1.4 % below the Amsteel rating, 1.4 % above D2
    assert est.nominal == pytest.approx(np.mean(S_POINTS) * d**2, rel=1e-12)
    assert est.nominal == pytest.approx(f, rel=0.015)
    assert est.nominal != pytest.approx(f, rel=0.01)  # a fit through two points, not one
    assert est.source.startswith(
        "estimate: d^2 scaling through two published single breaks (not a maker's table)"
    )
    assert "hwstock.org" in est.source and "Yachting Monthly" in est.source


def test_hmpe_law_scales_with_d_squared_and_its_band_is_stated():
    est = strength.breaking_load("hmpe", [3e-3, 6e-3, 8e-3])
    assert est.nominal[1] / est.nominal[0] == pytest.approx(4.0, rel=1e-12)
    assert est.nominal[2] / est.nominal[1] == pytest.approx(16 / 9, rel=1e-12)
    # s: nominal 1.088 kN/mm^2; the band 0.88 x 1.073 = 0.944 to 1.14 x 1.103 = 1.258
    # covers the other published single values: lowest 7/64 in Amsteel 1650 lb average
    # (0.951, hwstock.org/rope/sheathed_amsteel), highest Marlow Excel D12 4 mm 2050 kg
    # (1.257, totalwind.net forum)
    assert est.nominal[1] == pytest.approx(1.08794e9 * 36e-6, rel=1e-5)
    assert est.low[1] == pytest.approx(0.88 * min(S_POINTS) * 36e-6, rel=1e-12)
    assert est.high[1] == pytest.approx(1.14 * max(S_POINTS) * 36e-6, rel=1e-12)
    assert est.low[1] < 1650 * LBF / (7 / 64 * INCH) ** 2 * 36e-6 < est.nominal[1]
    assert est.nominal[1] < 2050 * KGF / 4e-3**2 * 36e-6 < est.high[1]


@pytest.mark.parametrize("d", [2.9e-3, 8.1e-3, 10e-3])
def test_hmpe_outside_the_law_range_is_a_one_line_input_error(d):
    with pytest.raises(
        InputError, match=r"outside the breaking-strength d\^2 law for hmpe \(3-8 mm\)"
    ):
        strength.breaking_load("hmpe", d)


def test_hmpe_not_found_says_what_is_used_and_vps32_has_nothing():
    note = strength._data("mbs.json")["not_found"]["hmpe"]
    assert "hmpe-d2-law-amsteel-d2racing" in note and "3-8 mm" in note
    (law,) = strength.breaking_load_laws("dyneema")
    assert (law.d_min, law.d_max) == (3e-3, 8e-3)
    with pytest.raises(NoDataError, match="vps32"):
        strength.breaking_load("vps32", 0.004)


# ----------------------------------------------------------------- knot efficiency


def test_every_efficiency_is_in_zero_one():
    for row in strength._efficiency_rows():
        assert 0 < row.low <= row.high <= 1, row


@pytest.mark.parametrize("knot", strength.knot_names())
@pytest.mark.parametrize("material", [None, "nylon", "polyester", "hmpe", "manila"])
def test_efficiency_estimate_is_ordered(knot, material):
    try:
        eta = strength.knot_efficiency(knot, material)
    except NoDataError:
        return
    assert 0 < eta.low <= eta.nominal <= eta.high <= 1
    assert eta.source


def test_cordage_institute_and_plymouth_values():
    # Practical Sailor quoting the Cordage Institute: sheet bend 48-58 %, reef 43-47 %
    assert strength.knot_efficiency("sheet-bend")[1:3] == (0.48, 0.58)
    # reef 43-47 % (CI) and 45 % (Plymouth Cordage 1946 via Jacobson)
    assert strength.knot_efficiency("square")[1:3] == (0.43, 0.47)
    # clove hitch 75 % (Plymouth via Jacobson; Avery p. 125)
    assert strength.knot_efficiency("clove-hitch")[:3] == (0.75, 0.75, 0.75)
    # bowline: 60 % (Plymouth) to 67-75 % (CI)
    assert strength.knot_efficiency("bowline")[1:3] == (0.60, 0.75)


def test_two_half_hitches_by_post_diameter():
    # CI: 60-70 % on a 5/8 in ring, 65-75 % on a 4 in post; Plymouth (no post) 75 %
    ring = strength.knot_efficiency("two-half-hitches", post_diameter=5 / 8 * INCH)
    post = strength.knot_efficiency("two-half-hitches", post_diameter=4 * INCH)
    assert (ring.low, ring.high) == (0.60, 0.75)
    assert (post.low, post.high) == (0.65, 0.75)
    every = strength.knot_efficiency("two-half-hitches")
    assert (every.low, every.high) == (0.60, 0.75)


def test_hmpe_knots_are_weaker_than_nylon_where_the_sources_say_so():
    # bowline: D2 Racing 39.0 % (Marlow) and ~1/3 (Hartter) against CI/Plymouth 60-75 %
    hmpe = strength.knot_efficiency("bowline", "hmpe")
    nylon = strength.knot_efficiency("bowline", "nylon")
    assert hmpe.high < nylon.low
    assert hmpe.high == pytest.approx(0.39)
    # double fisherman's ~1/3 in HMPE; Marlow's rule for any knot: 40 % HMPE, 50 % nylon
    assert strength.knot_efficiency("double-fishermans", "hmpe").nominal == pytest.approx(0.333)
    assert strength.knot_efficiency("clove-hitch", "hmpe").high <= 0.5
    assert strength.knot_efficiency("figure-eight-loop", "nylon")[:3] == (0.5, 0.5, 0.5)


def test_polyester_bowline_uses_the_marlow_rows_too():
    # Marlow 2017, 10 mm: 3-strand 55.7 %, Marlowbraid 52.3 %, Doublebraid 43.4 %
    eta = strength.knot_efficiency("bowline", "polyester")
    assert eta.low == pytest.approx(0.434)
    assert eta.high == pytest.approx(0.75)


def test_knots_without_a_citable_efficiency_say_so():
    for knot in ("granny", "alpine-butterfly", "prusik", "flat-overhand-bend"):
        with pytest.raises(NoDataError, match="no published knot efficiency"):
            strength.knot_efficiency(knot)


def test_knot_breaking_load_is_efficiency_times_strength():
    eta = strength.knot_efficiency("clove-hitch", "nylon")
    mbs = strength.breaking_load("nylon", [0.010, 0.012])
    kbl = strength.knot_breaking_load("clove-hitch", "nylon", [0.010, 0.012])
    np.testing.assert_array_equal(kbl.nominal, eta.nominal * mbs.nominal)
    np.testing.assert_array_equal(kbl.low, eta.low * mbs.low)
    np.testing.assert_array_equal(kbl.high, eta.high * mbs.high)
    assert "efficiency:" in kbl.source and "breaking load:" in kbl.source


# ------------------------------------------------------------------------ friction


def test_friction_rows_are_physical_and_capstan_values_recompute():
    data = json.loads(
        resources.files("knotmech").joinpath("data", "strength", "friction.json").read_text()
    )
    for row in data["rows"]:
        low, high = row["mu"]
        assert 0 < low <= high < 2, row
        if "inputs" in row:
            eff = np.asarray(row["inputs"]["efficiency"])
            theta = np.asarray(row["inputs"]["wrap_angle_rad"])
            mu = np.log(1 / eff) / theta
            assert sorted(np.round(mu, 3)) == pytest.approx([low, high], abs=1e-3)


def test_friction_ranges_from_delaney_table():
    # RopeLab p. 88: polyester on aluminium 0.14-0.21 (with the carabiner test 0.163-0.221)
    assert strength.friction_range("polyester", "aluminum")[:2] == (0.14, 0.221)
    assert strength.friction_range("pes", "galvanised-steel")[:2] == (0.19, 0.25)
    assert strength.friction_range("polyester", "timber")[:2] == (0.36, 0.37)
    assert strength.friction_range("nylon", "rope")[:2] == (0.40, 0.47)
    hmpe = strength.friction_range("dyneema", "self")
    assert hmpe.high < strength.friction_range("nylon", "rope").low


def test_friction_without_data_says_so():
    with pytest.raises(NoDataError, match="manila on steel"):
        strength.friction_range("manila", "steel")


# ---------------------------------------------------------------------- slip tests


def test_published_slip_tests_in_si():
    tests = {t["id"]: t for t in strength.published_slip_tests()}
    drop = tests["sterlingjim-clove-drop-1"]
    assert drop["load"] == 4800.0 and drop["rod_diameter"] == pytest.approx(0.0102)
    sheet = tests["marlow-ym-2017-sheet-bend"]
    assert sheet["load"] == pytest.approx(200 * KGF)
    # slipped near 2 kN, far below the rope's 2640 kg break
    assert sheet["load"] < 0.1 * 2640 * KGF
    for t in tests.values():
        assert t["source"] and t["url"].startswith("http") and t["where"]


# ------------------------------------------------------------------------ bad input


BAD_CALLS = [
    ("rod_diameter", lambda: strength.breaking_load("nylon", -0.01)),
    ("rod_diameter", lambda: strength.breaking_load("nylon", 0.0)),
    ("rod_diameter", lambda: strength.breaking_load("nylon", float("nan"))),
    ("rod_diameter", lambda: strength.breaking_load("nylon", float("inf"))),
    ("rod_diameter", lambda: strength.breaking_load("nylon", True)),
    ("rod_diameter", lambda: strength.breaking_load("nylon", ["1 cm"])),
    ("rod_diameter", lambda: strength.breaking_load("nylon", 1.0)),
    ("rod_diameter", lambda: strength.breaking_load("nylon", 0.001)),
    ("material", lambda: strength.breaking_load("kevlar", 0.01)),
    ("material", lambda: strength.breaking_load(["nylon"], 0.01)),
    ("material", lambda: strength.breaking_load(True, 0.01)),
    ("knot", lambda: strength.knot_efficiency("monkey-fist")),
    ("knot", lambda: strength.knot_efficiency(["bowline"])),
    ("knot", lambda: strength.knot_efficiency(True)),
    ("post_diameter", lambda: strength.knot_efficiency("bowline", post_diameter=-1)),
    ("post_diameter", lambda: strength.knot_efficiency("bowline", post_diameter=False)),
    ("post_diameter", lambda: strength.knot_efficiency("bowline", post_diameter=[0.01, 0.02])),
    ("counterface", lambda: strength.friction_range("nylon", "glass")),
    ("counterface", lambda: strength.friction_range("nylon", 3)),
    ("material", lambda: strength.friction_range("cotton", "steel")),
]


@pytest.mark.parametrize(("argument", "call"), BAD_CALLS)
def test_bad_input_is_a_one_line_input_error_naming_the_argument(argument, call):
    with pytest.raises(InputError) as err:
        call()
    message = str(err.value)
    assert "\n" not in message
    assert argument.replace("_", " ").split()[0] in message.replace("_", " ")


def test_out_of_table_message_gives_the_range():
    with pytest.raises(InputError, match=r"outside the breaking-strength tables for nylon"):
        strength.breaking_load("nylon", 0.2)


def test_unknown_counterface_lists_the_known_names():
    with pytest.raises(InputError, match="aluminium, rope, steel, wood"):
        strength.friction_range("nylon", "glass")


def test_kernmantle_ratings_meet_the_en1891_minimums():
    # EN 1891: type A >= 22 kN, type B >= 18 kN new, without terminations
    # (hoater-ropes.com 'EN 1891 Standard Explained'; besafety manual: type A MBL 2200 kg)
    t = _table("nylon-kernmantle-bluewater")
    assert np.all(t.loads >= 18e3)
    assert np.all(t.loads[t.diameters >= 10.5e-3] >= 22e3)


def test_a_material_object_is_accepted():
    from knotmech.materials import material

    est = strength.breaking_load(material("nylon"), 0.0127)
    assert est.nominal == strength.breaking_load("polyamide", 0.0127).nominal


def test_friction_counterfaces_are_those_with_a_published_range():
    from knotmech import strength

    for name in ("nylon", "polyester", "hmpe", "vps32"):
        faces = strength.friction_counterfaces(name)
        for face in strength.counterface_names():
            try:
                strength.friction_range(name, face)
                published = True
            except strength.NoDataError:
                published = False
            assert (face in faces) is published, (name, face)
    with pytest.raises(InputError, match="unknown"):
        strength.friction_counterfaces("kevlar-ish")

"""``knotmech.hold``: the library's verdict, identical to the command line's, its rule
(a model outside its validity never decides), materials and the deprecated alias."""

import itertools
import json
import math
import warnings

import pytest

import knotmech
from knotmech.cli.main import main
from knotmech.errors import InputError
from knotmech.materials import MATERIALS, material

# knot, (d, D) [mm], mu, load [N], free end [N], material
GRID = list(
    itertools.product(
        ["clove-hitch", "two-half-hitches", "round-turn-two-half-hitches", "capstan"],
        [(4, 30), (2, 50), (8, 16)],
        [0.15, 0.3],
        [1.47, 200.0],
        [0.0, 0.5],
        [None, "vps32"],
    )
) + [
    ("clove-hitch", (6, 40), 0.4, 200.0, 0.0, "nylon"),
    ("capstan", (4, 30), 0.3, 6.0, 1.0, "hmpe"),
]


def _cli(knot, dD, mu, load, free, mat, capsys):
    args = ["hold", knot, "--rod-diameter", f"{dD[0]}mm", "--post-diameter", f"{dD[1]}mm",
            "--mu", repr(mu), "--load", f"{load!r}N", "--free-end-load", f"{free!r}N"]  # fmt: skip
    if knot == "capstan":
        args += ["--wrap-angle", "540deg"]
    if mat:
        args += ["--material", mat]
    assert main(args + ["--json", "-"]) == 0
    return json.loads(capsys.readouterr().out)


def test_api_and_cli_give_the_same_verdict_on_a_grid(capsys):
    """Every point of a 4 x 3 x 2 x 2 x 2 x 2 grid and two more materials (194 queries):
    the same verdict, deciding model, margin and every other field from ``knotmech.hold``
    and ``knotmech hold --json -``."""
    seen = set()
    for knot, dD, mu, load, free, mat in GRID:
        v = knotmech.hold(
            knot,
            rod_diameter=dD[0] * 1e-3,
            post_diameter=dD[1] * 1e-3,
            mu=mu,
            load=load,
            free_end_load=free,
            wrap_angle=3 * math.pi if knot == "capstan" else None,
            material=mat,
        )
        c = _cli(knot, dD, mu, load, free, mat, capsys)
        where = (knot, dD, mu, load, free, mat)
        assert c["holds"] is v.holds, where
        assert c["decided_by"] == v.decided_by, where
        assert c == v.to_dict(), where
        seen.add((v.decided_by, v.holds))
    # the grid exercises every kind of answer
    assert {"DER-table", "ideal-rope", "thick-nip", "thick-capstan"} <= {s[0] for s in seen}
    assert {True, False, None} <= {s[1] for s in seen}


@pytest.mark.parametrize(("knot", "dD", "mu", "load", "free", "mat"), GRID[::4])
def test_rule_outside_validity_never_decides(knot, dD, mu, load, free, mat):
    v = knotmech.hold(
        knot, rod_diameter=dD[0] * 1e-3, post_diameter=dD[1] * 1e-3, mu=mu, load=load,
        free_end_load=free, wrap_angle=3 * math.pi if knot == "capstan" else None, material=mat,
    )  # fmt: skip
    deciding = [a for a in v.answers if a.decides]
    valid = [a for a in v.answers if a.inside_validity and a.holds is not None]
    if v.holds is None:
        # undecided: no valid answer, or (issue 23) only self-locking closed forms whose slip
        # load nothing bounds (no table, no breaking load)
        assert not deciding and v.next_step
        assert all(math.isinf(a.margin) for a in valid) and not v.capacity.decided
    else:
        assert len(deciding) == 1 and deciding[0].inside_validity
        assert deciding[0].model == v.decided_by and deciding[0].holds is v.holds
        # the first valid answer in the rule's order decides
        order = [m for m in knotmech.verdict.RULE if any(a.model == m for a in valid)]
        assert v.decided_by == order[0]


def test_papers_case_api_equals_cli_and_the_deprecated_alias():
    """Issue 10: ``knotmech.hold_verdict`` said SLIPS for the clove-hitch paper's case
    (d = 4 mm, D = 30 mm, mu = 0.3, 1.47 N, free end) where the command said HOLDS."""
    kw = dict(rod_diameter=4e-3, post_diameter=30e-3, mu=0.3, load=1.47, free_end_load=0.0)
    v = knotmech.hold("clove-hitch", **kw)
    # the thick nip is self-locking here; without a material nothing bounds the slip load
    # (issue 23): undecided, with the command that decides
    assert v.holds is None and v.decided_by is None and "--simulate" in v.next_step
    with warnings.catch_warnings(record=True) as w:
        warnings.simplefilter("always")
        old = knotmech.hold_verdict("clove-hitch", **kw)
    assert any(issubclass(x.category, DeprecationWarning) for x in w)
    assert old.holds is v.holds and old.decided_by == v.decided_by
    # the closed forms' own answer (knotmech.analytic) keeps the ideal rope as reference,
    # and says it is outside its validity here
    cf = knotmech.analytic.hold_verdict("clove-hitch", **kw)
    assert cf.decided_by == "ideal-rope" and not cf.deciding.inside_validity
    # with the paper's rod the DER table decides, as the paper's Fig. 4 does
    der = knotmech.hold("clove-hitch", material="vps32", **kw)
    assert der.holds is True and der.decided_by == "DER-table"
    assert der.der["t_over_EA"] == pytest.approx(0.0928, abs=5e-4)


def test_callable_module_and_verdict_fields():
    import knotmech.verdict as module

    assert knotmech.hold is module.hold and callable(knotmech.hold)
    v = module.hold(
        "capstan", rod_diameter=4e-3, post_diameter=30e-3, mu=0.3, load=6.0,
        free_end_load=1.0, wrap_angle=2 * math.pi,
    )  # fmt: skip
    assert isinstance(v, knotmech.Verdict)
    # finite-thickness capstan: e^(mu_eff 2 pi) = 5.196 N held for 1 N, so 6 N slips
    assert v.holds is False and v.decided_by == "thick-capstan"
    assert v.margin == pytest.approx(5.196 / 6 - 1, abs=5e-4)
    assert v.summary().startswith("verdict: SLIPS") and "thick-capstan" in v.summary()
    json.loads(v.to_json())


def test_youngs_modulus_overrides_the_material_and_says_so():
    v = knotmech.hold(
        "clove-hitch", rod_diameter=4e-3, post_diameter=30e-3, mu=0.3, load=1.47,
        material="nylon", youngs_modulus=1.26e6, bending_scale=1.0,
    )  # fmt: skip
    # the solid-rod check: kappa = 1 (the tables'), not nylon's 0.01, lets the table answer
    assert v.inputs["youngs_modulus"] == 1.26e6 and v.decided_by == "DER-table"
    assert "instead of the nylon preset" in v.assumptions[0]


def test_materials_have_sources_and_consistent_numbers():
    assert set(MATERIALS) == {
        "nylon", "polyester", "hmpe", "manila", "polypropylene", "steel-wire", "vps32",
    }  # fmt: skip
    for m in MATERIALS.values():
        lo, hi = m.youngs_modulus_range
        assert 0 < lo <= m.youngs_modulus <= hi
        assert 300 < m.density < 8000 and m.source and m.key in knotmech.materials.__doc__
    assert material("VPS32").youngs_modulus == 1.26e6  # clove-hitch paper, sec. 2
    assert material("Dyneema") is MATERIALS["hmpe"] and material("steel") is MATERIALS["steel-wire"]
    # 16 mm 6x19 wire: 1 tonne-f stretches it 0.1 %: E = 9806.65 N / 0.001 / (pi 8 mm^2)
    assert MATERIALS["steel-wire"].youngs_modulus == pytest.approx(
        9806.65 / 1e-3 / (math.pi * 0.008**2), rel=0.01
    )
    # EN 1891 type A: <= 5 % between 50 and 150 kg at 10 mm: E >= 0.25 GPa
    assert MATERIALS["nylon"].youngs_modulus == pytest.approx(
        100 * 9.80665 / 0.05 / (math.pi * 0.005**2), rel=0.02
    )
    with pytest.raises(InputError, match="known: nylon, polyester"):
        material("kevlar")


def test_bad_inputs_raise_input_error():
    kw = dict(rod_diameter=4e-3, post_diameter=30e-3, mu=0.3, load=1.47)
    for knot in ("figure-eight", "zeppelin bend"):
        with pytest.raises(InputError, match="hold answers: capstan, clove-hitch"):
            knotmech.hold(knot, **kw)
    with pytest.raises(InputError, match="simulate needs the rope's stiffness"):
        knotmech.hold("clove-hitch", simulate=True, **kw)
    with pytest.raises(InputError, match="mu_rr"):
        knotmech.hold("capstan", wrap_angle=1.0, mu_rr=0.2, **kw)
    with pytest.raises(InputError, match="cannot read phase table"):
        knotmech.hold("clove-hitch", phase_table="/nonexistent.json", material="vps32", **kw)


def test_bending_scale_is_an_input_stated_in_the_assumptions():
    """The material's kappa (nylon 0.01, vps32 1), or 1 for a bare modulus, is stated."""
    kw = dict(rod_diameter=6e-3, post_diameter=40e-3, mu=0.4, load=200.0)
    nylon = knotmech.hold("clove-hitch", material="nylon", **kw)
    assert nylon.inputs["bending_scale"] == 0.01
    assert any(a.startswith("bending scale kappa = 0.01") for a in nylon.assumptions)
    # (the solid table decides at mu 0.5, a column of it; at mu 0.4 its neighbours disagree
    # since the rebuild with the floor rule "min")
    bare = knotmech.hold("clove-hitch", youngs_modulus=0.25e9, **{**kw, "mu": 0.5})
    assert bare.inputs["bending_scale"] == 1.0 and bare.decided_by == "DER-table"
    assert any("kappa = 1 " in a and "no material given" in a for a in bare.assumptions)
    vps = knotmech.hold("clove-hitch", material="vps32", **{**kw, "load": 1.47})
    assert vps.inputs["bending_scale"] == 1.0
    # the material's kappa picks the kappa-0.01 table (to 0.3 EA), whose neighbours of
    # 200 N disagree (the 0.1 EA points at d/2R 0.2308 change topology)
    assert nylon.der["holds"] is None and "disagree" in nylon.der["message"]
    assert nylon.der["table_bending_scale"] == 0.01
    assert nylon.decided_by == "thick-nip" and nylon.holds is True


@pytest.mark.parametrize("mat", ["nylon", "polyester", "steel-wire"])
def test_api_and_cli_agree_with_a_rope_bending_scale(mat, capsys):
    for knot in ("clove-hitch", "two-half-hitches"):
        for kappa in (None, 1.0, 0.5):
            v = knotmech.hold(knot, rod_diameter=6e-3, post_diameter=40e-3, mu=0.4,
                              load=200.0, material=mat, bending_scale=kappa)  # fmt: skip
            args = ["hold", knot, "--rod-diameter", "6mm", "--post-diameter", "40mm",
                    "--mu", "0.4", "--load", "200N", "--material", mat]  # fmt: skip
            if kappa is not None:
                args += ["--bending-scale", repr(kappa)]
            assert main(args + ["--json", "-"]) == 0
            assert json.loads(capsys.readouterr().out) == v.to_dict(), (mat, knot, kappa)


@pytest.mark.parametrize("bad", [0, -1, 2, float("nan"), float("inf")])
def test_bad_bending_scale_is_a_one_line_input_error(bad):
    with pytest.raises(InputError, match="bending_scale") as e:
        knotmech.hold("clove-hitch", rod_diameter=6e-3, post_diameter=40e-3, mu=0.4,
                      load=200.0, material="nylon", bending_scale=bad)  # fmt: skip
    assert "\n" not in str(e.value)


def test_a_table_built_at_the_ropes_bending_scale_answers(tmp_path):
    """A table whose meta says bending_scale 0.01 (here the shipped clove-hitch points
    relabelled, only to test the gate) answers for nylon (0.01) and is refused for a
    solid rod (1, a factor 100 apart)."""
    from knotmech.scenes.phase_table import HoldTable
    from knotmech.verdict.der import shipped_hold_tables as _shipped_hold_tables

    d = _shipped_hold_tables()["clove-hitch"].to_dict()
    d["meta"] = {**d["meta"], "bending_scale": 0.01, "rod": NYLON_ROD}
    path = tmp_path / "rope_table.json"
    HoldTable.from_dict(d).write(path)
    kw = dict(rod_diameter=6e-3, post_diameter=40e-3, mu=0.5, load=200.0, phase_table=path)
    rope = knotmech.hold("clove-hitch", material="nylon", **kw)
    assert rope.decided_by == "DER-table" and rope.der["table_bending_scale"] == 0.01
    solid = knotmech.hold("clove-hitch", material="nylon", bending_scale=1.0, **kw)
    assert solid.der["holds"] is None and "kappa = 0.01" in solid.der["message"]
    assert "this rope's kappa = 1" in solid.der["message"]


#: the rod of a table run for 6 mm nylon rope (the preset's E and density)
NYLON_ROD = {"d_m": 0.006, "E_Pa": 0.25e9, "rho": 800.0}


def test_the_shipped_tables_answer_for_every_material_on_the_flexural_clock(tmp_path):
    """The shipped tables ran on the reference rod (protocol time scale 1), so they answer
    for a solid rod of any material (:func:`protocol_time_scale`: 6 mm nylon at kappa 1,
    E = 0.25 GPa, 800 kg/m^3: s = sqrt(1.26e6/1150 / 2.5e8 x 800) x 6/4 = 0.0888), with the
    creep limit and window converted to the rope's seconds. A table run in seconds on
    another rod (meta without protocol_clock) is refused beyond a factor 3 of its rod's
    time scale."""
    from knotmech.scenes.phase_table import CREEP_LIMIT, HoldTable
    from knotmech.verdict.der import shipped_hold_tables as _shipped_hold_tables

    kw = dict(rod_diameter=6e-3, post_diameter=40e-3, mu=0.5, bending_scale=1.0)
    nyl = knotmech.hold("clove-hitch", material="nylon", load=200.0, **kw)
    s = (1.26e6 / 1150 / (0.25e9 / 800)) ** 0.5 * 1.5
    assert nyl.der["time_scale"] == pytest.approx(s, rel=1e-9)
    assert nyl.decided_by == "DER-table" and nyl.der["table_rod"]["protocol_clock"] == "flexural"
    assert nyl.creep["limit_d_per_s"] == pytest.approx(CREEP_LIMIT / s, rel=1e-9)
    assert nyl.creep["speed_d_per_s"] == pytest.approx(
        nyl.creep["speed_d_per_protocol_s"] / s, rel=1e-9)  # fmt: skip
    # the same table relabelled as run in seconds on a 6 mm nylon rod: refused for silicone
    d = _shipped_hold_tables()["clove-hitch"].to_dict()
    meta = {k: v for k, v in d["meta"].items() if k != "protocol_clock"}
    d["meta"] = {**meta, "rod": {"d_m": 0.006, "E_Pa": 0.25e9, "rho": 800.0}}
    legacy = tmp_path / "legacy.json"
    HoldTable.from_dict(d).write(legacy)
    sil = dict(youngs_modulus=1.26e6, load=1.008, **kw)
    v = knotmech.hold("clove-hitch", phase_table=legacy, **sil)
    assert v.der["refused"] == "rod" and v.der["holds"] is None
    assert v.der["table_rod"]["protocol_clock"] == "seconds" and "--simulate" in v.der["message"]
    d["meta"]["protocol_clock"] = "flexural"
    HoldTable.from_dict(d).write(legacy)
    v = knotmech.hold("clove-hitch", phase_table=legacy, **sil)
    assert v.decided_by == "DER-table" and "refused" not in v.der


@pytest.mark.parametrize("bad", ["abc", None, 0, 2.0, True])
def test_a_table_with_a_bad_bending_scale_is_refused_in_one_line(tmp_path, bad):
    """A table's meta bending_scale that is not a number in (0, 1] is an input error naming
    the file (it was read as 1, a solid rod, before), from the API and the CLI (exit 2)."""
    from knotmech.verdict.der import shipped_hold_tables as _shipped_hold_tables

    d = _shipped_hold_tables()["clove-hitch"].to_dict()
    d["meta"] = {**d["meta"], "bending_scale": bad}
    path = tmp_path / "bad_kappa.json"
    path.write_text(json.dumps(d))
    kw = dict(rod_diameter=6e-3, post_diameter=40e-3, mu=0.4, load=200.0, phase_table=path)
    with pytest.raises(InputError, match="bad_kappa.json.*bending_scale must be a number") as e:
        knotmech.hold("clove-hitch", material="nylon", **kw)
    assert "\n" not in str(e.value)
    args = [
        "hold",
        "clove-hitch",
        "--rod-diameter",
        "6mm",
        "--post-diameter",
        "40mm",
        "--mu",
        "0.4",
        "--load",
        "200N",
        "--material",
        "nylon",
        "--phase-table",
        str(path),
    ]
    assert main(args) == 2


def test_the_shipped_table_nearest_the_ropes_kappa_answers(monkeypatch):
    """With tables shipped at several bending scales, hold takes the one nearest the rope's
    kappa by ratio (kappa 0.01 -> the 0.01 table; kappa 0.2 -> the solid rod's, a factor 5
    from 1 but 20 from 0.01, which is then refused as beyond the factor 3); nylon's preset
    kappa is read over its range (knotmech.verdict.kappa)."""
    import knotmech.verdict.der as h

    solid = h.shipped_hold_tables()["clove-hitch"]
    d = solid.to_dict()
    d["meta"] = {**d["meta"], "bending_scale": 0.01, "rod": NYLON_ROD}
    from knotmech.scenes.phase_table import HoldTable

    rope = HoldTable.from_dict(d)
    monkeypatch.setattr(h, "_shipped_hold_table_sets",
                        lambda: {"clove-hitch": {1.0: solid, 0.01: rope}})  # fmt: skip
    assert h.shipped_hold_table("clove-hitch", 0.01) is rope
    assert h.shipped_hold_table("clove-hitch", 0.05) is rope
    assert h.shipped_hold_table("clove-hitch", 0.2) is solid
    assert h.shipped_hold_table("cow-hitch", 0.01) is None
    kw = dict(rod_diameter=6e-3, post_diameter=40e-3, mu=0.5, load=200.0, material="nylon")
    v = knotmech.hold("clove-hitch", bending_scale=0.01, **kw)
    assert v.decided_by == "DER-table" and v.der["table_bending_scale"] == 0.01
    # the preset's kappa is read over its range 0.003-0.03: 0.003 is a factor 3.3 from the
    # 0.01 table, so no table answers there and the tables do not decide
    p = knotmech.hold("clove-hitch", **kw)
    assert p.der["holds"] is None and p.der["refused"] == "bending_scale_range"
    assert [r["table_bending_scale"] for r in p.der["kappa_range"]["readings"]] == [
        0.01, 0.01, 0.01]  # fmt: skip
    w = knotmech.hold("clove-hitch", bending_scale=0.2, **kw)
    assert w.der["holds"] is None and w.der["table_bending_scale"] == 1.0
    assert w.der["refused"] == "bending_scale"  # a factor 5 from kappa 1


def test_simulate_passes_the_bending_scale_to_the_scene(monkeypatch):
    """--simulate runs the DER scene at the rope's kappa (simulate_point is replaced by a
    recorder: the run itself is tested in tests/cli/test_hold_simulate.py)."""
    from knotmech.verdict import build

    seen = {}

    def fake(**kw):
        seen.update(kw)
        return {"holds": None, "message": "recorded"}

    monkeypatch.setattr(build, "simulate_point", fake)
    v = knotmech.hold("two-half-hitches", rod_diameter=6e-3, post_diameter=40e-3, mu=0.4,
                      load=200.0, material="nylon", simulate=True)  # fmt: skip
    assert seen["bending_scale"] == 0.01 and seen["knot"] == "two-half-hitches"
    assert v.der["holds"] is None


def test_materials_bending_scales_are_sourced_and_in_range():
    for m in MATERIALS.values():
        lo, hi = m.bending_scale_range
        assert 0 < lo <= m.bending_scale <= hi <= 1, m.key
        assert m.bending_source
    assert material("vps32").bending_scale == 1.0
    ropes = [k for k in MATERIALS if k != "vps32"]
    assert all(MATERIALS[k].bending_scale <= 0.05 for k in ropes)


@pytest.mark.parametrize("E", [1e30, 1.0, 1e14])
def test_an_implausible_modulus_is_refused_before_any_model(E):
    """Issue 27: 1e30 Pa gave 'HOLDS margin +2.56e+26 %' from the table's light-load edge."""
    with pytest.raises(InputError, match=r"youngs_modulus .* is outside 100-1e\+13 Pa"):
        knotmech.hold("clove-hitch", rod_diameter=4e-3, post_diameter=0.03, mu=0.3, load=1.47,
                youngs_modulus=E)  # fmt: skip


def test_simulate_on_a_post_thinner_than_the_rope_names_both_sizes():
    """A DER hitch needs d/2R < 0.5: the refusal names the two diameters (issue 27), not
    an internal d_over_2R."""
    with pytest.raises(
        InputError, match=r"rod_diameter 4 mm on post_diameter 1 mm gives d/2R = 0.8"
    ):
        knotmech.hold("clove-hitch", rod_diameter=4e-3, post_diameter=1e-3, mu=0.3, load=1.0,
                      material="vps32", simulate=True)  # fmt: skip

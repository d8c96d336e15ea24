"""The knot registry (knotmech.knots): one record per knot, and every consumer reads it."""

import importlib.util
import math
import re
from importlib import resources

import pytest

from knotmech import knots
from knotmech.errors import InputError


def test_names_and_aliases_are_one_spelling_each():
    seen = {}
    for k in knots.records(answered=None):
        for name in (k.name, *k.aliases):
            assert knots.normalise(name) == name, name  # stored in the canonical spelling
            assert name not in seen, f"{name} is both {seen[name]} and {k.name}"
            seen[name] = k.name
    assert knots.key("Lark's head") == knots.key("GIRTH_HITCH") == "cow-hitch"
    assert knots.key("Round turn & two half hitches") == "round-turn-two-half-hitches"
    assert knots.key("figure-8") == "figure-eight" and not knots.get("figure-8").answered
    assert knots.key("Figure 8 on a bight") == "figure-eight-loop"
    with pytest.raises(InputError, match="unknown knot 'granny-bend'"):
        knots.get("granny-bend")


def test_hold_answers_the_answered_records():
    from knotmech.verdict import KNOT_NAMES, knot_key

    assert KNOT_NAMES == knots.names() == (
        "capstan", "clove-hitch", "two-half-hitches", "round-turn",
        "round-turn-two-half-hitches", "cow-hitch", "reef", "granny", "thief", "grief",
        "bowline", "figure-eight-loop", "alpine-butterfly", "sheet-bend", "double-sheet-bend",
        "flat-overhand-bend", "figure-eight-bend", "double-fishermans", "prusik",
        "rolling-hitch",
    )  # fmt: skip
    for k in knots.records(answered=False):
        with pytest.raises(InputError, match=re.escape(f"is {k.unanswered}")):
            knot_key(k.name)


def test_closed_forms_read_the_wraps():
    from knotmech.analytic.hitch import KNOTS

    hitches = [k for k in knots.records(family="hitch") if k.wraps is not None]
    assert list(KNOTS) == [k.name for k in hitches]
    # the clove hitch: two turns (Bayman's 4 pi), both ends nipped; the cow hitch: no thick nip
    assert KNOTS["clove-hitch"].post_wrap == pytest.approx(4 * math.pi)
    assert KNOTS["clove-hitch"].post_nips and not KNOTS["cow-hitch"].thick_nip
    assert KNOTS["two-half-hitches"].rope_wrap == pytest.approx(4 * math.pi)


def test_curves_and_scenes_resolve_from_the_records():
    from knotmech.scenes.hitch_curves import HITCH_KNOTS
    from knotmech.scenes.hitches import HITCHES

    assert HITCH_KNOTS == {"two_half_hitches": math.pi, "round_turn_two_half_hitches": 3 * math.pi,
                           "cow_hitch": 2 * math.pi, "rolling_hitch": 7 * math.pi}  # fmt: skip
    assert list(HITCHES.values()) == [
        "clove-hitch", "two-half-hitches", "round-turn-two-half-hitches", "cow-hitch",
        "rolling-hitch",
    ]  # fmt: skip
    for k in knots.records(answered=None):
        for ref in (k.curve, k.scene):
            if ref:  # the module exists (not imported: the scenes import numba)
                assert importlib.util.find_spec(ref.partition(":")[0]) is not None, ref


def test_shipped_tables_have_records():
    from knotmech.verdict.tables import hold_table_resource

    data = resources.files("knotmech") / "data"
    files = {p.name for p in data.iterdir()}
    for k in knots.records(family="hitch"):
        assert (hold_table_resource(k.name) in files) == k.hold_table, k.name
    for name in files:
        if name.startswith("hold_phase_table_"):
            knot = name.removeprefix("hold_phase_table_").split("_kappa")[0].removesuffix(".json")
            assert knots.get(knot).hold_table, name


def test_simulate_commands_and_bends_come_from_the_registry():
    from knotmech.cli import simulate as sim
    from knotmech.scenes.bend_curves import BEND_CODES, BEND_ENDS

    assert sim.HITCH_SCENES == ("two-half-hitches", "round-turn-two-half-hitches", "cow-hitch",
                                "rolling-hitch")  # fmt: skip
    assert sim.BEND_KINDS == ("reef", "granny", "thief", "grief", *sim.TIED_BENDS)
    assert sim.TIED_BENDS == ("sheet-bend", "double-sheet-bend", "flat-overhand-bend",
                              "figure-eight-bend", "double-fishermans")  # fmt: skip
    # Patil et al. (2020): reef and thief share a shape, granny and grief the other; the
    # thief and grief pull the diagonal ends
    assert BEND_CODES["reef"] == BEND_CODES["thief"] != BEND_CODES["granny"] == BEND_CODES["grief"]
    assert BEND_ENDS["thief"] == BEND_ENDS["grief"] != BEND_ENDS["reef"]


def test_the_registry_is_light():
    """Reading the registry imports no scene, NumPy-free records, the DER solver untouched."""
    import subprocess
    import sys

    code = ("import sys, knotmech.knots as k; k.names(); "
            "print(any(m.startswith(('numba', 'knotmech.scenes', 'knotmech.rod')) "
            "for m in sys.modules))")  # fmt: skip
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"

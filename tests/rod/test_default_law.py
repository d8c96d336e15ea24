"""The rod-rod anchor law's defaults since issue 24: cap floor 1e-2 and the path guard; since
session 15 the floor rule "min" (min(1e-2 (r_i + r_j), 1/sharpness)), which every scene
uses, the hitches included (the radii floor alone let the paper's free-end clove hitch slip).

The regularised law keeps the displacement guard (the path guard moves its goldens:
tests/golden/speed_golden.json's overhand_imc takes 15 instead of 17 steps with it), and
the law as shipped before stays reachable (cap_floor 0, tunnel_check "displacement").
Shipped hold tables built with that law say so in every answer.
"""

import pytest

from knotmech.errors import InputError
from knotmech.rod.contact import RodContact
from knotmech.rod.friction import CAP_FLOOR, FLOOR_RULE, AnchorFriction, SmoothFriction
from knotmech.verdict import tables


def test_anchor_law_defaults_to_the_floored_cap():
    assert CAP_FLOOR == 1e-2
    assert AnchorFriction(mu_static=0.3).cap_floor == CAP_FLOOR
    assert AnchorFriction(mu_static=0.3).floor_rule == FLOOR_RULE == "min"
    assert AnchorFriction(mu_static=0.3, cap_floor=0.0).cap_floor == 0.0


@pytest.mark.parametrize(
    ("friction", "guard"),
    [
        (AnchorFriction(mu_static=0.3), "path"),
        (AnchorFriction(mu_static=0.3, cap_floor=0.0), "path"),
        (SmoothFriction(0.3), "displacement"),
        (None, "displacement"),
    ],
)
def test_tunnel_check_follows_the_law(friction, guard):
    assert RodContact(stiffness=1.0, sharpness=1.0, friction=friction).tunnel_check == guard


def test_law_as_shipped_stays_reachable():
    c = RodContact(stiffness=1.0, sharpness=1.0, tunnel_check="displacement",
                   friction=AnchorFriction(mu_static=0.3, cap_floor=0.0))  # fmt: skip
    assert (c.tunnel_check, c.friction.cap_floor) == ("displacement", 0.0)
    with pytest.raises(InputError, match="tunnel_check"):
        RodContact(stiffness=1.0, sharpness=1.0, tunnel_check="none")


def test_table_law_text_names_the_hitch_scenes_floor():
    assert f"cap_floor {CAP_FLOOR:g} floor_rule {FLOOR_RULE}," in tables.ANCHOR_LAW
    assert "tunnel_check path" in tables.ANCHOR_LAW


def test_hitch_scenes_build_the_librarys_anchor_law():
    """The hitch scenes' rod-rod law: the library's anchor law (cap floor 1e-2, rule "min",
    since session 15; the smooth law unchanged)."""
    from types import SimpleNamespace

    from knotmech.scenes._hitch import HitchScene

    def law(name):
        return HitchScene._rod_friction(SimpleNamespace(mrr=0.3, fric=SimpleNamespace(law=name)))

    assert isinstance(law("anchor"), AnchorFriction) and law("anchor") == AnchorFriction(0.3)
    assert (law("anchor").cap_floor, law("anchor").floor_rule) == (CAP_FLOOR, "min")
    assert isinstance(law("imc"), SmoothFriction)


def test_old_tables_say_which_law_built_them():
    """The shipped hold tables are built with the hitch scenes' law (no note); a table built
    with the law as shipped before issue 24 (its meta's law names no cap_floor) says so."""
    shipped = tables.load_hold_tables()["two-half-hitches"]
    assert shipped.meta["law"] == tables.ANCHOR_LAW and shipped.law_note == ""
    old_law = "anchor (rod-rod AnchorFriction, rod-post anchor friction)"
    table = tables.HoldTable(shipped.knot, shipped.points, {**shipped.meta, "law": old_law})
    a = table.lookup(0.1, 1e-3, mu=0.3)
    assert a.message.endswith(table.law_note)
    assert "as shipped before issue 24 (cap_floor 0, tunnel_check displacement)" in a.message
    assert "not the hitch scenes' law since" in a.message
    assert shipped.lookup(0.1, 1e-3, mu=0.3).message == a.message[: -len(table.law_note) - 2]

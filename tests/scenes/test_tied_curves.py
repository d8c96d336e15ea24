"""The tied knots' start centrelines: topology (closures' Alexander polynomials, linking and
winding numbers), clearance and smoothness, and the one-line errors for bad input.

Reference polynomials (Rolfsen table; composites as products): unknot 1, trefoil 3_1
1 - t + t^2, figure-eight 4_1 -1 + 3t - t^2, cinquefoil 5_1 1 - t + t^2 - t^3 + t^4,
6_2 -1 + 3t - 3t^2 + 3t^3 - t^4, 6_3 1 - 3t + 5t^2 - 3t^3 + t^4.
"""

import numpy as np
import pytest

from knotmech.errors import InputError
from knotmech.scenes.tied import TIED_KNOTS, knot_name, measure
from knotmech.scenes.tied._common import (
    build_ropes,
    finish,
    invariant,
    join_far,
    long_knot_controls,
    writhe,
)

D = 0.01  # rod diameter [m]
PINNED = {"bowline", "figure_eight_loop", "alpine_butterfly", "prusik"}


def tie(name, **kw):
    if name in PINNED:
        kw.setdefault("pin_diameter", 3 * D)
    return TIED_KNOTS[name](rod_diameter=D, **kw)


@pytest.fixture(scope="module")
def knots():
    return {name: tie(name) for name in TIED_KNOTS}


# the knot each closure is, stated independently of the curve files
EXPECTED = {
    "bowline": {"alexander": "6_3", "winding_pin": 1, "alexander_cut": ("0_1", "0_1")},
    "figure_eight_loop": {
        "alexander": "0_1",
        "winding_pin": 1,
        "alexander_cut": ("4_1", "4_1"),
        "linking_cut": 1,
    },
    # tied in the bight: the ends joined give the unknot; cut at the eye (the butterfly
    # bend, one of the interlocked-overhand bends), two overhand knots linked once
    "alpine_butterfly": {
        "alexander": "0_1",
        "winding_pin": 1,
        "alexander_cut": ("3_1", "3_1"),
        "linking_cut": 1,
    },
    "sheet_bend": {
        "alexander_A": "0_1",
        "alexander_B": "0_1",
        "linking": 1,
        "alexander_joined": "6_2",
    },
    "figure_eight_bend": {
        "alexander_A": "4_1",
        "alexander_B": "4_1",
        "linking": 1,
        "alexander_joined": "0_1",
    },
    "flat_overhand_bend": {
        "alexander_A": "3_1",
        "alexander_B": "3_1",
        "linking": 2,
        "alexander_joined": "0_1",
    },
    "prusik": {"alexander": "0_1", "winding_pin": 0},
    # joined closure not in the table (measured polynomial, determinant 7; see below)
    "double_sheet_bend": {
        "alexander_A": "0_1",
        "alexander_B": "0_1",
        "linking": 1,
        "alexander_joined": "?",
    },
    "double_fishermans": {
        "alexander_A": "5_1",
        "alexander_B": "5_1",
        "linking": 4,
        "alexander_joined": "0_1",
    },
}


def _named(inv: dict) -> dict:
    out = {}
    for k, v in inv.items():
        if k.startswith("alexander"):
            out[k] = tuple(knot_name(p) for p in v) if k.endswith("cut") else knot_name(v)
        else:
            out[k] = abs(v)  # linking / winding: magnitude (a mirror image flips the sign)
    return out


@pytest.mark.parametrize("name", sorted(TIED_KNOTS))
def test_topology_of_the_start_shape(knots, name):
    k = knots[name]
    got = measure(k)
    assert got == k.expected
    assert _named(got) == EXPECTED[name]


@pytest.mark.parametrize("name", sorted(TIED_KNOTS))
def test_clearance_and_smoothness(knots, name):
    k = knots[name]
    assert k.info["min_gap"] >= 1.1 * D  # centrelines at least 1.1 d apart: no overlap
    assert k.info["max_curvature"] <= 2.0 / D  # no bend tighter than radius d/2
    for nodes in k.ropes.values():
        edges = np.linalg.norm(np.diff(nodes, axis=0), axis=1)
        assert np.ptp(edges) < 0.02 * edges.mean()  # equal arc steps: chords within 2 %


@pytest.mark.parametrize("name", sorted(TIED_KNOTS))
def test_scales_with_the_rod_diameter(knots, name):
    k2 = TIED_KNOTS[name](rod_diameter=2 * D, **({"pin_diameter": 6 * D} if name in PINNED else {}))
    for r in k2.ropes:
        np.testing.assert_allclose(k2.ropes[r], 2 * knots[name].ropes[r], atol=1e-12)


@pytest.mark.parametrize("pin", [0.5, 40.0])
@pytest.mark.parametrize("name", ["bowline", "figure_eight_loop", "alpine_butterfly"])
def test_loops_round_any_pin(name, pin):
    k = tie(name, pin_diameter=pin * D)
    assert measure(k) == k.expected
    assert k.info["min_gap"] >= 1.1 * D
    # the eye lies on the pin: its nearest node at (D + d)/2 from the axis, to 0.5 %
    r = np.hypot(*(k.ropes["rope"][:, :2] - np.array(k.pin["point"][:2])).T)
    assert r.min() == pytest.approx(0.5 * (pin * D + D), rel=5e-3)


def test_bowline_is_the_sheet_bend_with_a_tail_joined_to_a_standing_part(knots):
    """Second embedding: the sheet bend's ropes, B's tail joined to A's standing part by a
    path round the far left, A's tail lifted out: the same knot as the bowline's closure."""
    a, b = knots["sheet_bend"].ropes["A"] / D, knots["sheet_bend"].ropes["B"] / D
    xl = min(a[:, 0].min(), b[:, 0].min()) - 15.0
    conn = np.array([[xl, b[-1, 1], b[-1, 2]], [xl, a[0, 1], a[0, 2]]])
    rope = np.vstack([b, conn, a])
    assert invariant(join_far([rope], center=(xl, 0.5 * (a[0, 1] + b[-1, 1]), 0.0))) == (
        1, -3, 5, -3, 1)  # fmt: skip
    assert measure(knots["bowline"])["alexander"] == (1, -3, 5, -3, 1)


@pytest.mark.parametrize(
    ("core", "poly", "w"), [("overhand", (1, -1, 1), -2), ("figure_eight", (-1, 3, -1), 1)]
)
def test_long_knot_cores(core, poly, w):
    """The single-rope cores of the doubled knots: a trefoil (writhe -3) and a figure-eight
    (writhe 0) cut open, plus the tails' kink (+1)."""
    ropes, signed = build_ropes([long_knot_controls(core, 2.0, 8.0)])
    assert invariant(join_far(finish(ropes, 1.0, 200))) == poly
    assert writhe(signed, ropes) == w
    assert len(signed) == {"overhand": 4, "figure_eight": 5}[core]


@pytest.mark.parametrize("name", sorted(TIED_KNOTS))
def test_bad_input_is_one_line(name):
    kw = {"pin_diameter": 3 * D} if name in PINNED else {}
    for bad in ({"rod_diameter": -1.0}, {"rod_diameter": float("nan")}, {"n_nodes": 10},
                {"n_nodes": 250.5}):  # fmt: skip
        args = {"rod_diameter": D, **kw, **bad}
        with pytest.raises(InputError) as e:
            TIED_KNOTS[name](**args)
        assert "\n" not in str(e.value)
    if name in PINNED:
        with pytest.raises(InputError, match="pin_diameter"):
            TIED_KNOTS[name](rod_diameter=D, pin_diameter=0.1 * D)
        with pytest.raises(InputError, match="pin_diameter"):
            TIED_KNOTS[name](rod_diameter=D, pin_diameter=50 * D)
        with pytest.raises(InputError, match="pin_diameter"):
            TIED_KNOTS[name](rod_diameter=D, pin_diameter=-D)


@pytest.mark.parametrize(("pole", "wraps"), [(1.0, 2), (1.7, 3), (3.0, 4), (10.0, 2)])
def test_prusik_on_poles(pole, wraps):
    k = tie("prusik", pin_diameter=pole * D, wraps=wraps)
    x = k.ropes["sling"]
    assert measure(k) == {"alexander": (1,), "winding_pin": 0}
    assert k.info["post_code"] == "U" * 2 * wraps + "O" * 2 * wraps + "U" * wraps + "O" * wraps
    assert k.info["min_gap"] >= 1.1 * D
    assert k.info["max_curvature"] <= 2.0 / D
    # the turns lie on the pole: nodes at (D + d)/2 from the axis, none inside
    r = np.hypot(x[:, 0], x[:, 1])
    assert r.min() == pytest.approx(0.5 * (pole * D + D), rel=5e-3)
    # loaded along the pole: the bottom of the loop hangs below the knot along -z
    assert x[:, 2].min() < -10 * D


@pytest.mark.parametrize("bad", [1, 7, 2.5, True])
def test_prusik_wraps(bad):
    with pytest.raises(InputError, match="wraps"):
        tie("prusik", wraps=bad)


def test_double_sheet_bend_closure_is_a_property_of_its_crossings(knots):
    """A second embedding (every turn and run 1.3 times wider) closes to the same knot,
    determinant 7, which is not the sheet bend's 6_2."""
    other = TIED_KNOTS["double_sheet_bend"](rod_diameter=D, spread=1.3)
    poly = invariant(join_far([other.ropes["A"], other.ropes["B"][::-1]]))
    assert poly == knots["double_sheet_bend"].expected["alexander_joined"]
    assert abs(sum(c * (-1) ** i for i, c in enumerate(poly))) == 7
    assert poly != knots["sheet_bend"].expected["alexander_joined"]
    with pytest.raises(InputError, match="spread"):
        TIED_KNOTS["double_sheet_bend"](rod_diameter=D, spread=0.5)


def test_interleaved_ends_give_no_linking_number():
    """Two straight ropes crossing like + (their ends alternate round the centre): each is
    an unknot and A's end joins B's start without a new crossing, but each rope cannot be
    closed on its own without crossing the other's ends: the linking number is None rather
    than a number that depends on the choice."""
    from knotmech.scenes.tied import TiedKnot

    s = np.linspace(-1.0, 1.0, 50)[:, None]
    a = s * [1.0, 0.0, 0.0]
    b = s * [0.0, 1.0, 0.0] + [0.0, 0.0, 0.3]
    k = TiedKnot("cross", {"A": a, "B": b}, {"A": ("standing", "tail"), "B": ("standing", "tail")},
                 0.05, info={"join": [("A", True), ("B", True)]})  # fmt: skip
    got = measure(k)
    assert got == {"alexander_joined": (1,), "alexander_A": (1,), "alexander_B": (1,),
                   "linking": None}  # fmt: skip


def test_alpine_butterfly_tongue_tucked_under_the_twist(butterfly_tip_over_the_twist):
    """Each cut half is an overhand knot because the tongue's tip is tucked under the
    lower twist (C1) and up through the window: the same curve with the tip laid over the
    twist instead (a false butterfly, which pulls out) gives two unknots, linked once, the
    same closed unknot and winding: the invariants of an eye with its legs twisted once."""
    ab = butterfly_tip_over_the_twist()
    got = measure(ab.alpine_butterfly(rod_diameter=D, pin_diameter=3 * D))
    assert got == {"alexander": (1,), "winding_pin": 1, "alexander_cut": ((1,), (1,)),
                   "linking_cut": 1}  # fmt: skip

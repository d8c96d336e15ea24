"""The four bends of Patil et al. (2020) as start shapes: their knot types and clearances.

Reference values: joined around the outside (bend_closure) the reef and thief shapes close
to the square knot and the granny and grief shapes to the granny knot; both composite knots
have the Alexander polynomial (1 - t + t^2)^2 = 1 - 2t + 3t^2 - 2t^3 + t^4 (determinant 9;
Livingston, Knot Theory, 1993). The granny's six-crossing diagram is reduced alternating
with writhe +-6 (an invariant of reduced alternating diagrams, 0 for the square knot); the
reef's diagram has writhe 0.
"""

import numpy as np
import pytest

from knotmech.errors import InputError
from knotmech.scenes.bend_curves import (
    BEND_ENDS,
    bend_closure,
    bend_curves,
    bend_invariants,
    bend_linking,
)
from knotmech.scenes.topology import knot_determinant, projection_crossings

D = 4e-3
SQUARE = (1, -2, 3, -2, 1)


@pytest.mark.parametrize("kind", ["reef", "granny", "thief", "grief"])
def test_every_bend_closes_to_a_double_trefoil_and_starts_clear(kind):
    c = bend_curves(kind, rod_diameter=D, n_nodes=100)
    alex, lk = bend_invariants(c.rope_a, c.rope_b)
    assert alex == SQUARE
    assert knot_determinant(bend_closure(c.rope_a, c.rope_b), closed=True) == 9
    assert c.info["min_gap_between_ropes"] >= 1.0 * D
    assert c.info["min_gap_within_rope"] >= 1.0 * D
    # equal arc-length spacing: chords within 3 % (shorter where the rope bends)
    e = np.linalg.norm(np.diff(c.rope_a, axis=0), axis=1)
    assert np.ptp(e) < 0.03 * e.mean()


def test_reef_and_granny_differ_by_writhe_and_linking():
    reef = bend_curves("reef", rod_diameter=D, n_nodes=100)
    granny = bend_curves("granny", rod_diameter=D, n_nodes=100)
    w = {}
    for name, c in (("reef", reef), ("granny", granny)):
        cr = projection_crossings(bend_closure(c.rope_a, c.rope_b), direction=(0, 0, 1.0))
        assert len(cr.sign) == 6 and not cr.degenerate
        w[name] = int(cr.sign.sum())
    assert w == {"reef": 0, "granny": -6}
    assert bend_linking(reef.rope_a, reef.rope_b) == pytest.approx(0.0, abs=0.05)
    assert bend_linking(granny.rope_a, granny.rope_b) == pytest.approx(-3.0, abs=0.05)


def test_reef_and_thief_pull_different_ends():
    assert BEND_ENDS["reef"] != BEND_ENDS["thief"]
    assert BEND_ENDS["granny"] == BEND_ENDS["reef"]
    assert BEND_ENDS["grief"] == BEND_ENDS["thief"]


def test_bad_bend_arguments_are_one_line_errors():
    with pytest.raises(InputError, match="kind must be one of"):
        bend_curves("bowline", rod_diameter=D, n_nodes=100)
    with pytest.raises(InputError, match="n_nodes"):
        bend_curves("reef", rod_diameter=D, n_nodes=12)
    with pytest.raises(InputError, match="bight must exceed"):
        bend_curves("reef", rod_diameter=D, n_nodes=100, bight=1.5)

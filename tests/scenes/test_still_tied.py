"""Whether a loop is still tied: the linking of its halves cut at the eye, closed from
outside the knot (:mod:`knotmech.scenes.tied.eye_linking`), and the rope's average crossing
number (:mod:`knotmech.scenes.tied.crossings`), on the alpine butterfly, the same curve
with its tongue's tip laid over the lower twist, a straight rope and two circles."""

import numpy as np
import pytest

from knotmech.scenes.tied import alpine_butterfly, measure
from knotmech.scenes.tied._common import linking_number
from knotmech.scenes.tied.crossings import average_crossings
from knotmech.scenes.tied.eye_linking import crossing_linking, cut_linking

D = 4e-3
T = np.linspace(0.0, 2 * np.pi, 300, endpoint=False)
RING = np.column_stack([np.cos(T), np.sin(T), 0 * T])


def _hopf():
    return RING, np.column_stack([1 + np.cos(T), 0 * T, np.sin(T)])


def test_crossing_count_is_the_gauss_linking_number():
    a, b = _hopf()
    assert crossing_linking(a, b) == -1 == round(linking_number(a, b))
    assert crossing_linking(a, b, view=[0.3, 0.5, 0.2]) == -1  # any generic view
    assert crossing_linking(a, b[::-1]) == 1
    assert crossing_linking(a, b + [5.0, 0, 0]) == 0


@pytest.mark.parametrize("pin", [2, 5, 40])
def test_the_butterfly_is_tied_at_every_pin(pin):
    """Drawn in: the halves cut at the eye link once, about the pin's centre or the rope's
    centroid, and at the nodes next to the tip; gaps >= 1.24 d; average crossing number
    20.0-21.9 (measured at pins 2-40 d)."""
    k = alpine_butterfly(rod_diameter=D, pin_diameter=pin * D)
    x, cut = k.ropes["rope"], k.info["eye_cut"]
    assert cut_linking(x, cut, k.pin["point"]) == 1
    assert [cut_linking(x, cut + j) for j in (-2, 0, 2)] == [1, 1, 1]
    assert k.info["min_gap"] >= 1.24 * D
    assert 19.5 < average_crossings(x) < 22.5
    assert average_crossings(x) > 2 * k.info["min_crossings"]


def test_the_tip_over_the_twist_is_not_tied(butterfly_tip_over_the_twist):
    """The same curve drawn in with the tongue's tip laid over the lower twist: the cut
    halves are unknots (overhand knots when tucked), still linked once, every other
    invariant the butterfly's: the invariants of an eye with its legs twisted once; its
    average crossing number does not see it (11.4, measured)."""
    k = butterfly_tip_over_the_twist().alpine_butterfly(rod_diameter=D, pin_diameter=20e-3)
    x, cut = k.ropes["rope"], k.info["eye_cut"]
    assert cut_linking(x, cut) == 1
    assert measure(k) == {"alexander": (1,), "winding_pin": 1, "alexander_cut": ((1,), (1,)),
                          "linking_cut": 1}  # fmt: skip
    assert average_crossings(x) > 4


def test_a_straight_rope_is_not_tied():
    x = np.column_stack([np.linspace(-50, 50, 151), np.zeros(151), np.zeros(151)]) * D
    assert cut_linking(x, 75) == 0
    assert average_crossings(x) == 0.0
    assert average_crossings(RING) == pytest.approx(0.0, abs=1e-12)  # planar: no crossing


def test_cut_linking_needs_an_inner_node():
    with pytest.raises(ValueError, match="the cut node must be inside the rope"):
        cut_linking(RING, 0)

"""Knot invariants: Alexander polynomial and determinant of standard knots.

Reference values (Rolfsen table; Livingston, Knot Theory, 1993, ch. 6):
unknot 1; trefoil 1 - t + t^2 (det 3); figure-eight -1 + 3t - t^2 (det 5);
(2, m) torus knot sum_i (-t)^i (det m).
"""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from knotmech.errors import InputError
from knotmech.scenes.topology import (
    alexander_polynomial,
    close_curve,
    identify_knot,
    knot_determinant,
    knot_invariant,
    post_crossing_code,
    projection_crossings,
    torus_knot_polynomial,
    winding_number,
)

T = np.linspace(0.0, 2 * np.pi, 300, endpoint=False)
TREFOIL = np.column_stack(
    [np.sin(T) + 2 * np.sin(2 * T), np.cos(T) - 2 * np.cos(2 * T), -np.sin(3 * T)]
)
FIGURE_EIGHT = np.column_stack(
    [(2 + np.cos(2 * T)) * np.cos(3 * T), (2 + np.cos(2 * T)) * np.sin(3 * T), np.sin(4 * T)]
)
CIRCLE = np.column_stack([np.cos(T), np.sin(T), 0 * T])


def torus_2m(m, n=400):
    t = np.linspace(0.0, 2 * np.pi, n, endpoint=False)
    r = 2 + np.cos(m * t)
    return np.column_stack([r * np.cos(2 * t), r * np.sin(2 * t), -np.sin(m * t)])


def rotation(a, b, c):
    ca, sa, cb, sb, cc, sc = np.cos(a), np.sin(a), np.cos(b), np.sin(b), np.cos(c), np.sin(c)
    rz = np.array([[ca, -sa, 0], [sa, ca, 0], [0, 0, 1]])
    ry = np.array([[cb, 0, sb], [0, 1, 0], [-sb, 0, cb]])
    rx = np.array([[1, 0, 0], [0, cc, -sc], [0, sc, cc]])
    return rz @ ry @ rx


def test_standard_knots():
    tre = knot_invariant(TREFOIL, closed=True)
    assert tre.alexander == (1, -1, 1) and tre.determinant == 3 and tre.name == "3_1"
    f8 = knot_invariant(FIGURE_EIGHT, closed=True)
    assert f8.alexander == (-1, 3, -1) and f8.determinant == 5 and f8.name == "4_1"
    assert knot_invariant(CIRCLE, closed=True).alexander == (1,)
    assert knot_determinant(CIRCLE, closed=True) == 1


@pytest.mark.parametrize("m", [1, 3, 5, 7, 9, 11])
def test_torus_knots_2m(m):
    inv = knot_invariant(torus_2m(m), closed=True, n_projections=2)
    assert inv.alexander == torus_knot_polynomial(m)
    assert inv.determinant == m


def test_mirror_image_same_polynomial():
    mirror = TREFOIL * np.array([1.0, 1.0, -1.0])
    assert alexander_polynomial(mirror, closed=True) == (1, -1, 1)


def test_unknot_with_crossings():
    """A (2, 1) torus curve has crossings in most projections but is the unknot."""
    inv = knot_invariant(torus_2m(1), closed=True, n_projections=4)
    assert inv.alexander == (1,)


@settings(max_examples=15, deadline=None)
@given(st.floats(0, 2 * np.pi), st.floats(0, np.pi), st.floats(0, 2 * np.pi), st.integers(0, 10**6))
def test_rotation_invariance(a, b, c, seed):
    R = rotation(a, b, c)
    assert knot_invariant(FIGURE_EIGHT @ R.T, closed=True, seed=seed).alexander == (-1, 3, -1)
    assert knot_invariant(torus_2m(5) @ R.T, closed=True, seed=seed).determinant == 5


def test_pass_through_is_detected():
    """Push the over strand of one crossing of a trefoil through the under strand: unknot."""
    x = torus_2m(3, n=600)
    cr = projection_crossings(x, direction=(0, 0, 1))
    k = int(np.argmin(np.abs(cr.over_pos - 100)))
    i_over, i_under = int(cr.over_pos[k]), int(cr.under_pos[k])
    dz = x[i_over, 2] - x[i_under, 2]
    idx = np.arange(len(x))
    bump = np.exp(-0.5 * ((idx - cr.over_pos[k]) / 6.0) ** 2)
    y = x.copy()
    y[:, 2] -= (dz + 0.6) * bump
    assert knot_determinant(x, closed=True) == 3
    assert knot_invariant(y, closed=True).alexander == (1,)


def test_open_curve_closure():
    """Cut the trefoil open and pull its ends out along an axis: still a trefoil."""
    x = np.roll(TREFOIL, -20, axis=0)[10:]  # open, ends pointing away from each other
    tails = np.linspace(0, 1, 10)[1:, None]
    start = x[0] + tails[::-1] * 4 * (x[0] - x[1]) / np.linalg.norm(x[0] - x[1])
    end = x[-1] + tails * 4 * (x[-1] - x[-2]) / np.linalg.norm(x[-1] - x[-2])
    opened = np.vstack([start, x, end])
    closed = close_curve(opened)
    assert closed.shape == (len(opened) + 3, 3)
    assert knot_invariant(opened).name == "3_1"


def test_identify_and_table():
    assert identify_knot((1, -1, 1, -1, 1)) == "5_1"
    assert identify_knot((2, -3, 2)) == "5_2"
    assert identify_knot((1, 1)) == "?"
    assert torus_knot_polynomial(3) == (1, -1, 1)
    with pytest.raises(InputError):
        torus_knot_polynomial(4)


def test_winding_number_of_helix():
    t = np.linspace(0, 4 * np.pi, 500)
    helix = np.column_stack([np.cos(t), np.sin(t), 0.1 * t])
    assert winding_number(helix) == pytest.approx(2.0, abs=1e-12)
    assert winding_number(helix[::-1]) == pytest.approx(-2.0, abs=1e-12)
    assert winding_number(helix, axis_point=(5.0, 0.0, 0.0)) == pytest.approx(0.0, abs=1e-12)
    # a helix has no self-crossings seen from its axis
    assert post_crossing_code(helix) == ""


def test_bad_input():
    with pytest.raises(InputError):
        knot_invariant(np.zeros((5, 2)))
    with pytest.raises(InputError):
        knot_invariant(np.full((5, 3), np.nan))
    with pytest.raises(InputError):
        close_curve(np.zeros((4, 3)))
    with pytest.raises(InputError):
        winding_number(TREFOIL, axis_direction=(0, 0, 0))
    with pytest.raises(InputError):
        knot_invariant(TREFOIL, n_projections=0)

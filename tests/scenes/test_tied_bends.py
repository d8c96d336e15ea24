"""The tied bends pulled in the bend scene (issue 25): the pieces of
:mod:`knotmech.scenes.tied.pulled` on shapes whose answer is known, and short DER pulls
in which each rope keeps its knot type on every frame.

Default suite: the geometry and the argument checks (about 2 s). Slow: a short pull of
each bend with every frame checked (10-60 s each on the shared machine, the kernels'
compilation included), and the sheet bend pulled to slip at two friction coefficients
(about 15 s of CPU each).
"""

import math

import numpy as np
import pytest

from knotmech.errors import InputError
from knotmech.scenes.bends import TiedBendResult, bend
from knotmech.scenes.tied import TIED_KNOTS
from knotmech.scenes.tied.pulled import (
    NEAR_SET,
    end_direction,
    invariants_changed,
    tail_free_lengths,
    tail_nodes,
)

D = 4e-3
TIED = ["sheet-bend", "double-sheet-bend", "flat-overhand-bend", "figure-eight-bend",
        "double-fishermans"]  # fmt: skip
#: a short pull: settle, a token set, 2 mm of pull, 10 frames each checked
SHORT = dict(settle_time=0.05, set_travel=1e-3, pull_distance=2e-3, n_frames=10)


def _line(start, step, n):
    return np.asarray(start, float) + np.outer(np.arange(n), step)


def test_tail_of_a_rope_crossed_at_its_middle_ends_at_the_crossing():
    """A along x (node 0 at x = -L/2), B along y crossing it at the origin, 1 d above:
    A's tail is free from its end to the first node within NEAR_SET d of B."""
    n, h = 101, 0.2 * D
    a = _line([-50 * h, 0, 0], [h, 0, 0], n)
    b = _line([0, -50 * h, D], [0, h, 0], n)
    x = np.vstack([a, b])
    free = tail_free_lengths(x, n, D, (0, 0))
    # nodes of A within NEAR_SET d of B's node (0, 0, d): |x| < d sqrt(NEAR_SET^2 - 1)
    reach = D * math.sqrt(NEAR_SET**2 - 1)
    first = np.max(a[:, 0][np.abs(a[:, 0]) < reach])
    assert free[0] == pytest.approx(50 * h - first, rel=1e-9)
    assert free[1] == pytest.approx(50 * h - first, rel=1e-9)  # the same seen from B


def test_parallel_neighbour_is_not_the_knot():
    """Two ropes side by side (1.2 d apart) all along: no strand crosses either tail, so each
    tail is free over the whole rope (a tail lying along the other rope is outside)."""
    n, h = 60, 0.5 * D
    a = _line([0, 0, 0], [h, 0, 0], n)
    b = _line([0, 1.2 * D, 0], [h, 0, 0], n)
    x = np.vstack([a, b])
    assert tail_nodes(x, n, D) == (n - 1, n - 1)
    np.testing.assert_allclose(tail_free_lengths(x, n, D, (0, 0)), (n - 1) * h, rtol=1e-12)


def test_end_direction_points_out_of_the_rope():
    a = _line([0, 0, 0], [0.0, 0.0, D], 10)
    np.testing.assert_allclose(end_direction(a, "start"), [0, 0, -1], atol=1e-15)
    np.testing.assert_allclose(end_direction(a, "end"), [0, 0, 1], atol=1e-15)


def test_invariants_changed_ignores_undefined_closures():
    start = {"alexander_A": (1, -1, 1), "linking": -2, "alexander_joined": (1,)}
    assert invariants_changed(start, {**start, "linking": None}) == []
    assert invariants_changed(start, {**start, "linking": -3}) == ["linking"]
    assert invariants_changed(start, {**start, "alexander_A": (1,)}) == ["alexander_A"]


@pytest.mark.parametrize("name", ["sheet_bend", "flat_overhand_bend", "figure_eight_bend"])
def test_start_tails_lie_outside_the_knot(name):
    """Each start tail is free over several diameters (the straight ends of the design)."""
    n = {"sheet_bend": 100, "flat_overhand_bend": 100, "figure_eight_bend": 150}[name]
    k = TIED_KNOTS[name](rod_diameter=D, n_nodes=n)
    x = np.vstack([k.ropes["A"], k.ropes["B"]])
    free = tail_free_lengths(x, n, D, tail_nodes(x, n, D))
    assert np.all(free > 5 * D) and np.all(free < 40 * D)


def test_unknown_bend_and_small_mesh_are_one_line_errors():
    with pytest.raises(InputError, match="kind must be one of reef, .*sheet-bend"):
        bend("zeppelin-bend")
    with pytest.raises(InputError, match="n_nodes must be an integer >= 100"):
        bend("sheet-bend", n_nodes=50)


def _short_pull(kind):
    r = bend(kind, **SHORT)
    assert isinstance(r, TiedBendResult)
    assert r.status == "success", r.message
    assert r.frames_checked == len(r.times) >= 10  # every pull frame's invariants computed
    assert r.topology_preserved
    assert r.alexander_checked == r.alexander_start
    assert r.invariants_start == {  # the start shape is the knot its module derives
        k: v for k, v in _expected(kind).items() if k in r.invariants_start
    }
    assert "cap floor 0.01" in r.law
    return r


def _expected(kind):
    k = TIED_KNOTS[kind.replace("-", "_")](rod_diameter=D)
    return k.expected


@pytest.mark.slow
def test_sheet_bend_keeps_its_knot_type_on_every_frame():
    r = _short_pull("sheet-bend")
    assert r.alexander_start == ((1,), (1,)) and r.linking_start == 1


@pytest.mark.slow
@pytest.mark.parametrize("kind", TIED[1:])
def test_tied_bend_keeps_its_knot_type_on_every_frame(kind):
    _short_pull(kind)


@pytest.mark.slow
def test_sheet_bend_slip_load_rises_with_friction():
    """Pulled to slip at the defaults (d = 4 mm, E = 1 MPa, 100 nodes a rope): the slip load
    is finite, positive, and larger at mu = 1 than at mu = 0.3."""
    low, high = (bend("sheet-bend", mu_rod_rod=mu) for mu in (0.3, 1.0))
    for r in (low, high):
        assert r.status == "success" and r.verdict == "slips", r.message
        assert r.topology_preserved
    assert 0 < low.slip_load < high.slip_load < math.inf

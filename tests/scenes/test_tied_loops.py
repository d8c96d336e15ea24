"""The loop scene (:mod:`knotmech.scenes.loops`): the bowline, the figure-eight loop and the
alpine butterfly with their eye round a fixed pin, pulled by the standing part (the alpine
butterfly also end to end). Default suite: the tail and eye lengths on a drawn curve against
their closed form, the start invariants with the pin moved to the axis, the bowline's longer
tail keeping its knot type, the alpine butterfly's ends clear of the knot and its end-to-end
setup, one-line errors. Slow: a short pull of each loop keeps its knot type on every frame
(the alpine butterfly both ways); the alpine butterfly staying tied and holding at
mu = 0.3, slipping at mu = 0.1; the bowline coming undone at mu = 0.1, its slip load at
mu = 0.3 and what mu = 1 holds."""

import numpy as np
import pytest

from knotmech.errors import InputError
from knotmech.scenes.loops import LoopScene, loop, loop_inside, loop_lengths
from knotmech.scenes.tied import bowline, measure

D4 = 4e-3


def _polyline(points, h):
    """Points [d] joined by straight runs, resampled every h [d]; returned in metres."""
    p = np.asarray(points, float)
    seg = np.linalg.norm(np.diff(p, axis=0), axis=1)
    s = np.r_[0.0, np.cumsum(seg)]
    t = np.arange(0.0, s[-1] + 1e-9, h)
    return np.column_stack([np.interp(t, s, p[:, k]) for k in range(3)]) * D4


def test_straight_rope_is_all_tail_and_all_eye():
    x = _polyline([(0, 0, 0), (40, 0, 0)], 0.5)
    h = 0.5 * D4
    assert not loop_inside(x, D4).any()
    tail, eye = loop_lengths(x, D4, h, eye_cut=40)
    assert tail == pytest.approx(40 * D4) and eye == pytest.approx((len(x) - 1) * D4 * 0.5 + h)


def test_tail_length_up_to_the_strand_it_crosses():
    """A rope along x, round, and down across itself at x = 10 d, 1 d above it: the tail
    (15 d below the crossing) is free up to where it comes within 1.25 d of the crossed
    strand, sqrt(y^2 + 1) < 1.25 d, |y| < 0.75 d: 14.25 d, to a node spacing."""
    h = 0.25
    x = _polyline([(0, 0, 0), (30, 0, 0), (30, 10, 1), (10, 10, 1), (10, -15, 1)], h)
    tail, _ = loop_lengths(x, D4, h * D4, eye_cut=0)
    assert tail == pytest.approx(14.25 * D4, abs=1.01 * h * D4)
    inside = loop_inside(x, D4)
    crossing = np.nonzero(inside[: int(30 / h)])[0] * h  # on the first run, around x = 10 d
    assert crossing.min() == pytest.approx(10 - 0.75, abs=h) and crossing.max() == pytest.approx(
        10 + 0.75, abs=h
    )


def test_eye_length_up_to_the_strands_crossing_it():
    """The same rope, the eye measured round the node at x = 5 d: back to node 0 (5 d) and
    on to where the crossing strand comes within 1.25 d (x = 9.25 d): 9.25 d of eye."""
    h = 0.25
    x = _polyline([(0, 0, 0), (30, 0, 0), (30, 10, 1), (10, 10, 1), (10, -15, 1)], h)
    _, eye = loop_lengths(x, D4, h * D4, eye_cut=int(5 / h))
    assert eye == pytest.approx(9.25 * D4, abs=1.01 * h * D4)


@pytest.mark.parametrize("name", ["bowline", "figure-eight-loop", "alpine-butterfly"])
def test_start_invariants_with_the_pin_on_the_axis(name):
    from knotmech import knots
    from knotmech.scenes._scene import RunControl
    from knotmech.scenes.bends import BendPull, BendRopes

    rec = knots.get(name)
    scene = LoopScene(rec, pin_diameter=20e-3, mu_pin=None,
                      ropes=BendRopes(n_nodes=rec.scene_defaults["n_nodes"]),
                      pull=BendPull(pull_distance=0.08, set_travel=0.08),
                      control=RunControl(dt=4e-3, n_frames=20))  # fmt: skip
    scene.setup()
    inv = scene.inv_start
    expected = {"bowline": (1, -3, 5, -3, 1), "figure-eight-loop": (1,),
                "alpine-butterfly": (1,)}[name]  # fmt: skip
    turns = {"alpine-butterfly": 1}.get(name, -1)  # its eye drawn anticlockwise
    assert inv["alexander"] == expected and inv["winding_pin"] == turns
    assert scene.knot.pin["point"] == (0.0, 0.0, 0.0)
    # the standing part is pulled away from the pin
    assert np.dot(scene.u, scene.x0[0]) > 0


def _butterfly_scene(**kw):
    from knotmech import knots
    from knotmech.scenes._scene import RunControl
    from knotmech.scenes.bends import BendPull, BendRopes

    rec = knots.get("alpine-butterfly")
    scene = LoopScene(rec, mu_pin=None, ropes=BendRopes(n_nodes=rec.scene_defaults["n_nodes"]),
                      pull=BendPull(pull_distance=0.08, set_travel=0.08),
                      control=RunControl(dt=4e-3, n_frames=20), **kw)  # fmt: skip
    scene.setup()
    return scene


def test_alpine_butterfly_ends_leave_clear_of_the_knot():
    """Both ends leave the knot in opposite directions (-x, +x) and run at least 8 d (the
    curve's straight ends) outside it; the eye, round the pin, is outside the knot for more
    than half the pin's circumference."""
    s = _butterfly_scene(pin_diameter=20e-3)
    x = s.x0
    inside = loop_inside(x, D4)
    h = float(np.linalg.norm(np.diff(x, axis=0), axis=1).mean())
    free = int(8 * D4 / h)
    assert not inside[:free].any() and not inside[-free:].any()
    tail, eye = loop_lengths(x, D4, h, s.eye_cut)
    assert tail > 8 * D4 and eye > 0.5 * np.pi * 20e-3
    u0, u1 = s.u, x[-1] - x[-2]
    assert u0 @ u1 / np.linalg.norm(u1) < -0.99  # opposite directions


def test_alpine_butterfly_end_to_end_has_no_pin():
    """End to end: the same curve (start eye 5 d), no pin, the closed rope's knot type
    (unknot: tied in the bight), the cut halves' linking (1: the eye through the window) and
    their knot types (overhand knots, 1 - t + t^2)."""
    s = _butterfly_scene(pin_diameter=20e-3, loading="end-to-end")
    assert s.knot.pin is None
    assert s.inv_start == {"alexander": (1,), "linking_cut": 1,
                           "types_cut": ((1, -1, 1), (1, -1, 1))}  # fmt: skip
    assert len(s.build().interactions) == 1  # the rope's contact with itself only
    assert len(_butterfly_scene(pin_diameter=20e-3).build().interactions) == 2  # and the pin


def test_alpine_butterfly_end_to_end_comes_undone_by_knot_types_or_crossings(
    butterfly_tip_over_the_twist,
):
    """:meth:`LoopScene._undone` end to end: the start is tied (its halves cut at the eye
    are overhand knots, Alexander 1 - t + t^2); a start linking set to 0 changes nothing
    (the linking is not used: a turn of the free eye changes it); the false butterfly, its
    tip over the twist (halves unknots, average crossing number 11.4 > 4), has come
    undone; a straight rope has no crossing at all."""
    s = _butterfly_scene(pin_diameter=20e-3, loading="end-to-end")
    assert s._undone(s.x0) == "" and s.min_crossings == 4.0
    assert s._cut_types(s.x0) == ((1, -1, 1), (1, -1, 1))
    s.inv_start["linking_cut"] = 0
    assert s._undone(s.x0) == ""
    ab = butterfly_tip_over_the_twist()
    x = ab.alpine_butterfly(rod_diameter=D4, pin_diameter=20e-3, n_nodes=len(s.x0)).ropes["rope"]
    assert s._cut_types(x) == ((1,), (1,))
    assert s._undone(x) == (
        "both halves cut at the eye changed their knot type: the tongue drawn out of the window"
    )
    straight = _polyline([(-60, 0, 0), (60, 0, 0)], 120 / (len(s.x0) - 1))
    assert s._undone(straight) == "its average crossing number below 4 (fell apart)"


@pytest.mark.parametrize(
    ("kw", "words"),
    [
        ({}, "alpine-butterfly needs pin_diameter"),
        ({"loading": "axial", "pin_diameter": 0.02},
         "loading of alpine-butterfly must be one of loop, end-to-end, got 'axial'"),
        ({"loading": "end-to-end", "pin_diameter": 0.0}, "pin_diameter must be > 0"),
    ],
)  # fmt: skip
def test_alpine_butterfly_errors(kw, words):
    with pytest.raises(InputError, match=words):
        loop("butterfly", **kw)


def test_only_the_alpine_butterfly_is_pulled_end_to_end():
    with pytest.raises(InputError, match="loading of bowline must be one of loop, got"):
        loop("bowline", loading="end-to-end")


def test_the_set_keeps_a_grip_2d_clear_of_the_pin():
    """The bowline's tail points at the pin: its set travel stops 2 d from the pin's
    surface, where the ray meets the circle of radius (D + d)/2 + 2 d = 5 d (D = 5 d)."""
    s = LoopScene.__new__(LoopScene)
    s.D, s.d = 20e-3, D4
    p = np.array([16.0, 0.95, -0.6]) * D4
    assert s._clear_of_pin(p, np.array([-1.0, 0.0, 0.0])) == pytest.approx(
        (16 - np.sqrt(25 - 0.95**2)) * D4
    )
    assert s._clear_of_pin(p, np.array([1.0, 0.0, 0.0])) == np.inf  # away from it
    assert s._clear_of_pin(p, np.array([0.0, 1.0, 0.0])) == np.inf  # passes it by


def test_bowline_longer_tail_keeps_its_knot():
    k = bowline(rod_diameter=D4, n_nodes=175, pin_diameter=20e-3, tail=15.0)
    assert measure(k) == {"alexander": (1, -3, 5, -3, 1), "winding_pin": -1,
                          "alexander_cut": ((1,), (1,))}  # fmt: skip
    with pytest.raises(InputError, match=r"tail must lie in \[4, 40\]"):
        bowline(rod_diameter=D4, pin_diameter=20e-3, tail=2.0)


@pytest.mark.parametrize(
    ("kw", "words"),
    [
        ({}, "bowline needs pin_diameter"),
        ({"pin_diameter": 0.0}, "pin_diameter must be > 0"),
        ({"pin_diameter": 1.0}, r"pin_diameter must lie in \[0.5 d, 40 d\]"),
        ({"pin_diameter": 0.02, "mu_pin": -1.0}, "mu_pin must be >= 0"),
        ({"pin_diameter": 0.02, "n_frames": 3}, "n_frames"),
    ],
)
def test_loop_errors(kw, words):
    with pytest.raises(InputError, match=words):
        loop("bowline", **kw)


def test_unknown_loop():
    with pytest.raises(
        InputError, match="loop must be one of bowline, figure-eight-loop, alpine-butterfly"
    ):
        loop("reef", pin_diameter=0.02)


@pytest.mark.slow
@pytest.mark.parametrize("name", ["bowline", "figure-eight-loop"])
def test_short_pull_keeps_the_knot_type_on_every_frame(name):
    r = loop(name, pin_diameter=20e-3, settle_time=0.05, set_travel=1e-3, pull_distance=2e-3,
             n_frames=10)  # fmt: skip
    assert r.status == "success", r.message
    assert r.frames_checked == len(r.times) >= 10
    assert r.topology_preserved
    assert r.invariants_checked["winding_pin"] == -1


@pytest.mark.slow
def test_alpine_butterfly_stays_tied_and_holds_at_mu_03():
    """The alpine butterfly (the tongue's tip tucked under the lower twist and up through
    the window) stays tied through the settle and the set and holds to the end of the
    20 d pull at mu 0.3 (measured: largest force 0.228 N, 8 s of CPU;
    docs/notes/knots-and-curves/tied-loops-pulled.md)."""
    r = loop("alpine-butterfly", pin_diameter=20e-3)
    assert r.status == "success" and r.verdict == "holds", r.message
    assert not r.came_undone
    assert r.topology_preserved and r.frames_checked == len(r.times) >= 20
    assert r.invariants_checked["alexander_cut"] == ((1, -1, 1), (1, -1, 1))
    assert r.max_force == pytest.approx(0.228, rel=0.1)


@pytest.mark.slow
def test_alpine_butterfly_end_to_end_stays_tied_on_every_frame_at_mu_03():
    """End to end (no pin, both ends pulled) the butterfly holds the 20 d pull at mu 0.3
    (measured: to 0.85 N, 9 s of CPU; docs/notes/knots-and-curves/tied-loops-pulled.md),
    its knot type and both halves' overhand knots kept on every frame."""
    r = loop("alpine-butterfly", loading="end-to-end")
    assert r.status == "success" and r.verdict == "holds", r.message
    assert not r.came_undone and r.topology_preserved
    assert r.frames_checked == len(r.times) >= 20
    assert r.max_force == pytest.approx(0.85, rel=0.1)


@pytest.mark.slow
def test_alpine_butterfly_slips_at_mu_01():
    """At mu 0.1 the butterfly slips on the loop (measured: 0.0304 N, 10 s of CPU)."""
    r = loop("alpine-butterfly", pin_diameter=20e-3, mu_rod_rod=0.1)
    assert r.status == "success" and r.verdict == "slips", r.message
    assert r.slip_load == pytest.approx(0.0304, rel=0.1)


@pytest.mark.slow
def test_bowline_at_mu_01_comes_undone_a_slip():
    """At mu 0.1 the bowline's tail end swings out of the nip and is drawn through the
    knot (its knot type changes in both closures with the tail end 13.9 d nearer the
    knot): a slip at the largest force before it (measured 0.0197 N, t = 1.700 s), not a
    failure (it was "failed" before the came-undone rule)."""
    r = loop("bowline", pin_diameter=20e-3, mu_rod_rod=0.1)
    assert r.status == "success" and r.verdict == "slips" and r.came_undone, r.message
    assert r.message.startswith("came undone at t = ") and "tail drawn through" in r.message
    assert r.slip_load == pytest.approx(0.0197, rel=0.1)
    assert r.topology_preserved and r.to_dict()["came_undone"] is True


@pytest.mark.slow
def test_bowline_slips_at_mu_03_and_holds_more_at_mu_1():
    """Measured (docs/notes/knots-and-curves/tied-loops-pulled.md): at mu = 0.3 the tail
    runs out at about 0.065 N; at mu = 1 the loop holds to the end of the pull (about
    0.5 N)."""
    low = loop("bowline", pin_diameter=20e-3, mu_rod_rod=0.3)
    assert low.status == "success", low.message
    assert low.verdict == "slips" and 0 < low.slip_load < 0.2
    assert low.tail_draw_in[-1] > 2 * D4
    high = loop("bowline", pin_diameter=20e-3, mu_rod_rod=1.0)
    assert high.status == "success", high.message
    reached = high.slip_load if high.verdict == "slips" else high.max_force
    assert reached > 2 * low.slip_load


@pytest.mark.slow
def test_a_pull_too_short_to_load_the_loop_fails_in_one_line():
    """A 0.1 mm pull after a 0.1 mm set: the grip still pushes (negative force); the run
    fails with its reason instead of raising (the slip rule needs a positive force)."""
    r = loop("bowline", pin_diameter=0.02, settle_time=0.01, set_travel=1e-4,
             pull_distance=1e-4, n_frames=10)  # fmt: skip
    assert r.status == "failed" and "positive pull force" in r.message
    assert r.verdict == "" and np.isnan(r.slip_load)

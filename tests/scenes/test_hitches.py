"""Two half hitches, round turn and two half hitches, cow hitch on a post (scenes.hitches).

Fast: the start curves (clearance, knot invariants, wrap angle), argument errors, one
keyword interface for all four hitches. DER runs (the sticking rod-rod law, d = 4 mm VPS32
rod, D = 30 mm post, the table protocol settle 0.2 s / ramp 0.3 s / hold 1.5 s): a light
load with a free end holds and the knot type is kept; the tension drop over the rod lying
on the post is bounded by the capstan law; the round turn holds what two half hitches hold;
the cow hitch's two legs share a symmetric load.
"""

import inspect

import numpy as np
import pytest

from knotmech.errors import InputError
from knotmech.scenes.clove_hitch import clove_hitch
from knotmech.scenes.hitch_curves import (
    HITCH_KNOTS,
    hitch_curve,
    hitch_invariants,
    hitch_rod_length,
)
from knotmech.scenes.hitches import HITCHES, hitch, hitch_function
from knotmech.scenes.topology import winding_number

D_ROD, D_POST = 4e-3, 30e-3
#: invariants of the start shapes: Alexander polynomial of the closed rod (two overhand
#: knots, granny/square: (1 - t + t^2)^2), linking number with the post
INVARIANTS = {
    "two_half_hitches": ((1, -2, 3, -2, 1), -1),
    "round_turn_two_half_hitches": ((1, -2, 3, -2, 1), -2),
    "cow_hitch": ((1,), 0),
    # the rolling hitch falls apart off the pole (the unknot) and links it four times: three
    # and a half turns, closed far away
    "rolling_hitch": ((1,), 4),
}
PROTOCOL = dict(settle_time=0.2, load_time=0.3, hold_time=1.5, dt=2e-3, n_frames=41)


# ---------------------------------------------------------------------------- fast


@pytest.mark.parametrize("knot", list(HITCH_KNOTS))
@pytest.mark.parametrize("d_over_2R", [0.05, 0.118, 0.3])
def test_start_curves_are_clear_and_of_their_knot_type(knot, d_over_2R):
    post = D_ROD * (1 / d_over_2R - 1)
    c = hitch_curve(knot, post_diameter=post, rod_diameter=D_ROD)
    assert c.info["min_separation"] > 0.99 * D_ROD  # no strand closer than a diameter
    R = 0.5 * (post + D_ROD)
    assert np.hypot(c.nodes[:, 0], c.nodes[:, 1]).min() > R - 1e-3 * D_ROD  # outside the post
    assert hitch_invariants(c.nodes) == INVARIANTS[knot]
    edges = np.linalg.norm(np.diff(c.nodes, axis=0), axis=1)
    # equal arc length per edge: the chords of the tight half hitches are up to 12 % shorter
    assert np.median(edges) == pytest.approx(0.374 / 119, rel=0.02)
    assert edges.min() > 0.85 * np.median(edges)


@pytest.mark.parametrize("knot, turns", [("two_half_hitches", 0.5),
                                         ("round_turn_two_half_hitches", 1.5)])  # fmt: skip
def test_the_wrap_turns_through_its_design_angle(knot, turns):
    c = hitch_curve(knot, post_diameter=D_POST, rod_diameter=D_ROD)
    a, b = c.parts["wrap"]
    # the part boundaries are the nearest nodes: within an edge (0.03 turns) at each end
    assert abs(winding_number(c.nodes[a:b])) == pytest.approx(turns, abs=0.06)


def test_default_rod_lengths():
    got = {k: hitch_rod_length(k, post_diameter=D_POST, rod_diameter=D_ROD) for k in HITCH_KNOTS}
    # the round turn adds 2 pi R = 107 mm of wrap to the two half hitches
    extra = got["round_turn_two_half_hitches"] - got["two_half_hitches"]
    assert extra == pytest.approx(2 * np.pi * 0.017, rel=0.01)
    c = hitch_curve("two_half_hitches", post_diameter=D_POST, rod_diameter=D_ROD)
    assert c.rod_length == pytest.approx(got["two_half_hitches"], rel=0.01)


def test_one_keyword_interface_for_all_hitches():
    ref = list(inspect.signature(clove_hitch).parameters)
    assert set(HITCHES) == {"clove_hitch", *HITCH_KNOTS}
    for name in HITCHES:
        func = hitch_function(name)
        assert func is hitch_function(name.replace("_", "-"))
        assert list(inspect.signature(func).parameters) == ref, name
    assert inspect.signature(hitch_function("cow_hitch")).parameters["loading"].default == "free"


def test_bad_input_is_one_clear_error():
    with pytest.raises(InputError, match="knot must be one of"):
        hitch("bowline")
    with pytest.raises(InputError, match="rod_length must be at least"):
        hitch("two_half_hitches", rod_length=0.2)
    with pytest.raises(InputError, match="rod_length must be at least"):
        hitch("cow_hitch", rod_length=0.2)
    with pytest.raises(InputError, match="unknown keyword"):
        hitch("cow_hitch", turns=3)
    with pytest.raises(InputError, match="t_low must be 0"):
        hitch("two_half_hitches", loading="free", t_low=0.1)
    with pytest.raises(InputError, match="creep_limit"):
        hitch("two_half_hitches", creep_limit=0.0)


# ---------------------------------------------------------------------------- DER runs


def _free(knot, t_high, mu, **kw):
    return hitch(knot, loading="free", t_high=t_high, mu_rod_post=mu, mu_rod_rod=mu,
                 **{**PROTOCOL, **kw})  # fmt: skip


def _capstan_ratios(r):
    """(T_in/T_out, exp(mu_eff theta)) of every stretch of rod on the post without rod-rod
    contact, on its interior (one node in from each end: the lift-off points carry the
    bending's point forces), theta from the centreline, where the lower tension exceeds
    5 B/R^2 (below, the rod's bending stiffness and not the capstan carries the tension)."""
    x = r.positions[-1]
    b = 1.26e6 * np.pi * D_ROD**4 / 64
    out = []
    for w in r.post_wraps():
        i0, i1 = w["i0"] + 1, w["i1"] - 1
        if i1 - i0 < 4 or r.rod_contact[i0:i1].any():
            continue
        phi = np.unwrap(np.arctan2(x[i0 : i1 + 1, 1], x[i0 : i1 + 1, 0]))
        theta = abs(phi[-1] - phi[0])
        hi, lo = sorted((r.tension[i0], r.tension[i1 - 1]), reverse=True)
        if lo > 5 * b / r.wrap_radius**2:
            out.append((hi / lo, float(np.exp(r.mu_eff * theta))))
    return out


@pytest.fixture(scope="module")
def thh_pull():
    """Two half hitches pulled 10 mm by the standing end against 0.069 N on the working end
    (the clove-hitch paper's pull test), mu = 0.3: the rod slides round the post."""
    return hitch("two_half_hitches", loading="pull", t_low=0.069, settle_time=0.2,
                 load_time=0.2, pull_distance=0.01, n_frames=26)  # fmt: skip


def test_two_half_hitches_pulled_slide_at_the_capstan_ratio(thh_pull):
    """Sliding round the post the ratio reaches the capstan law and no more. Measured:
    2.58 against exp(mu_eff theta) = 2.57 (theta = 3.6 rad, mu_eff = 0.262)."""
    r = thh_pull
    assert r.status == "success" and r.topology_preserved
    ratios = _capstan_ratios(r)
    assert len(ratios) == 1
    ((got, bound),) = ratios
    assert 0.85 * bound < got < 1.05 * bound
    # the force rises through the pull; the first frame (grip switched from the lowering to
    # the pull) may sit a few % above the second: 0.313 -> 0.302 N with the solver's
    # stagnation cut-off, monotone without it
    assert np.all(np.diff(r.pull_force[1:]) > 0) and r.pull_force[1] > 0.9 * r.pull_force[0]
    assert r.pull_force[-1] > 3 * r.pull_force[0]
    assert r.tension[-1] == pytest.approx(0.069, rel=0.02)


@pytest.fixture(scope="module")
def thh_light():
    """Two half hitches, 0.3 N (0.019 EA) on the standing end, working end free, mu = 0.45."""
    return _free("two_half_hitches", 0.3, 0.45)


def test_two_half_hitches_hold_a_light_load(thh_light):
    """Measured: end 0 creeps -7.5e-5 d/s over the last 0.75 s, the knot type kept. (At
    0.1 N and mu = 0.6 it also holds, at -8.8e-4 d/s: the bent half hitches still relax,
    too close to the 1e-3 d/s limit for a test.)"""
    r = thh_light
    assert r.status == "success" and r.verdict == "hold"
    assert abs(r.creep_speed_d) < 1e-3 and r.creep_window == pytest.approx(0.75)
    assert r.topology_preserved and r.invariants_kept
    assert r.invariants_end == INVARIANTS["two_half_hitches"]
    assert r.tension[0] == pytest.approx(0.3, rel=0.02) and abs(r.tension[-1]) < 0.01


def _post_exit_tension(r):
    """Tension of the edge where the rod leaves its longest stretch on the post [N]."""
    w = max(r.post_wraps(), key=lambda w: w["i1"] - w["i0"])
    return w["t_out"], w["theta"]


@pytest.mark.slow
def test_round_turn_holds_what_two_half_hitches_hold():
    """1 N on the standing end, mu = 0.6: two half hitches hold (creep 3e-4 d/s), and so does
    the round turn, whose 9.3 rad on the post (against 3.2) leave the half hitches 0.071 N
    instead of 0.152 N."""
    thh = _free("two_half_hitches", 1.0, 0.6)
    rt = _free("round_turn_two_half_hitches", 1.0, 0.6)
    assert thh.verdict == "hold" and rt.verdict == "hold"
    assert thh.topology_preserved and rt.topology_preserved
    (t_thh, th_thh), (t_rt, th_rt) = _post_exit_tension(thh), _post_exit_tension(rt)
    assert th_rt > th_thh + 1.8 * np.pi  # a round turn wraps 2 pi more
    assert t_rt < 0.6 * t_thh


def test_invariants_are_checked_on_every_frame_within_10_d():
    """:func:`knotmech.scenes._hitch._check_invariants` looks at every recorded frame while
    end 0 is within 10 d (was 12 evenly spaced ones: a change on frame 7 of 50 was missed)."""
    from knotmech.scenes._hitch import _check_invariants

    d, n = 4e-3, 50
    pos = np.zeros((n, 3, 3))
    pos[7, 0, 0] = 1.0  # the one frame whose "knot type" differs
    disp = np.zeros(n)
    disp[40:] = 11 * d  # beyond 10 d: not checked
    seen = []

    def inv(x):
        seen.append(x)
        return (2,) if x[0, 0] == 1.0 else (1,)

    assert _check_invariants(inv, pos[0], pos, disp, d) == ((1,), (2,), False)
    pos[7, 0, 0] = 0.0
    seen.clear()
    assert _check_invariants(inv, pos[0], pos, disp, d) == ((1,), (1,), True)
    assert len(seen) == 1 + 40  # the start and the 40 frames within 10 d


@pytest.mark.slow
def test_cow_hitch_loaded_on_both_legs_keeps_its_knot_type_on_every_frame():
    """The cow hitch with both legs loaded (``loading="symmetric"``, 0.3 N each, mu = 0.3,
    the clove-hitch paper's rod and post): the unknot linked 0 times with the post on every
    recorded frame, and each leg carries its load."""
    r = hitch("cow_hitch", loading="symmetric", t_high=0.3, mu_rod_post=0.3, mu_rod_rod=0.3,
              **PROTOCOL)  # fmt: skip
    assert r.status == "success", r.message
    assert r.topology_preserved and r.invariants_kept is True
    assert r.invariants_end == INVARIANTS["cow_hitch"] == ((1,), 0)
    assert r.tension[0] == pytest.approx(0.3, rel=0.05)
    assert r.tension[-1] == pytest.approx(0.3, rel=0.05)

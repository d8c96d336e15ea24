r"""Alpine butterfly (butterfly loop, lineman's loop; ABoK #1053): a mid-line eye round a pin.

Construction: tied in the bight, as by hand (the twist method: G. Budworth and J. Dalton,
*The Little Book of Incredibly Useful Knots*, p. 106). A bight is given two twists the same
way (its legs cross twice: C1 near the ends, C2 below it; between them the *window* W);
the loop beyond C2 (the *tongue*) is brought round and up in front of both arms, over the
two standing parts, and its tip is tucked down under C1 and up through the window to the
front: the tip is the eye, laid west over the window's left arm and the tongue's left
side, round a pin (axis z) of diameter D at centreline radius (D + d)/2, south-west of the
knot. 12 crossings in the loose projection; both ends leave the knot in opposite
directions (along -x and +x). (A tongue passed sideways through the window, or its tip
laid over C1 instead of under it, pulls straight out into an eye with its legs twisted
once: docs/notes/knots-and-curves/tied-loops-pulled.md.)

Drawn in (:func:`_drawn_in`, as the figure-eight loop is drawn in by
:mod:`~knotmech.scenes.tied._snug`): the loose rope without its eye is scaled by
:data:`SCALE` in the plane (the crossings' heights kept, an isotopy) and pushed apart by
repulsion sweeps to a clearance of 1.25 d; both ends are run on by :data:`EXTEND` and the
eye laid for the pin between its legs. 129 d of rope at D = 5 d, its average crossing
number (:func:`~knotmech.scenes.tied.crossings.average_crossings`) 20-22.
``info["min_crossings"]`` (:data:`MIN_CROSSINGS`): the loop scene counts the knot fallen
apart below it. It stays tied through the settle and the set at mu 0.1-1.

Topology, proven in ``tests/scenes/test_tied_curves.py``:

- both ends joined far outside (the eye left as it is): the **unknot**. The knot is tied
  in the bight (no end is passed through anything): every move of the tying is an
  isotopy of the rope with its ends held, so the ends joined far away bound a disk.
- its winding about the pin: **1 turn** (the eye round the pin).
- cut at the far side of the pin (the butterfly bend, one of the interlocked-overhand
  bends: the eye's two legs become two ropes' tails), each half closed on its own: **two
  overhand knots** (3_1), **linked once**. The tip laid over C1 instead of tucked under
  it gives two unknots linked once, the invariants of an eye with its legs twisted once.

Loadings (:func:`knotmech.scenes.loops.loop`): on the loop (the eye round the pin, node 0
pulled, the right end the free tail) or end to end (both ends pulled apart, the eye free,
no pin): the alpine butterfly takes load in all three directions (ABoK #1053).
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from knotmech.scenes.tied._common import (
    TiedKnot,
    bspline,
    build_ropes,
    check_pin,
    check_sizes,
    cut_at,
    eye_controls,
    start_checks,
)
from knotmech.scenes.tied._snug import (
    FINAL_GAP,
    FINAL_SWEEPS,
    GAP,
    SUB,
    _dense,
    _repel,
    _resampled,
    equal_chords,
    run_on,
)

__all__ = ["alpine_butterfly"]

TAIL = 8.0  #: straight ends of the loose rope [d]
EYE_R = 3.0  #: centreline radius of the loose rope's eye while it is drawn in [d]
EXTEND = 12.0  #: both ends run on beyond the drawn-in knot [d]
SCALE = 0.35  #: the loose rope's plane scaled by this to draw it in
EYE_X, EYE_Y = -11.0, -12.5  #: the loose rope's eye: the run with x < EYE_X and y < EYE_Y [d]
ROUNDS = 10  #: rounds of repulsion sweeps after the scaling, each followed by a resampling
#: still tied while the rope's average crossing number
#: (:func:`~knotmech.scenes.tied.crossings.average_crossings`) is at least this: 20-22
#: drawn in, 14-16 set and pulled, about 2 for an eye with its legs twisted once
MIN_CROSSINGS = 4.0
#: leg A, from where the left end leaves the line y = 0 to the top of the eye's first leg
#: [d]: C1 (over), the window's right arm, C2 (under), the tongue's left side (round and up
#: outside the window, over the left standing part), the tip tucked down under C1 into the
#: window (z -2.6) and out of it in front, west over the window's left arm and the
#: tongue's left side to the eye; z orders the strands at the crossings
LEG_A = (
    (-12, 0, 0), (-9, 0, 0), (-6, -0.3, 0), (-2.5, -2.5, 1), (0, -4, 1), (2.5, -5.5, 0.5),
    (5.5, -7, 0), (6.5, -9, 0), (4, -11.5, -0.5), (0, -13, -1), (-2, -15.5, -0.5), (-5, -17, 0),
    (-6.5, -15, 0), (-8.5, -11.5, 0), (-9, -9, 0), (-9, -4, 0), (-8.5, -1.5, 1),
    (-6.5, 1, 2), (-3.5, 1.8, 2), (-1.5, 0.3, 1), (-1.5, -1.8, -1), (-1.5, -3.1, -2.6),
    (-1.5, -4.9, -2.6), (-1.5, -6.2, -1), (-2.8, -7, 1), (-4.5, -7, 2), (-7.5, -7, 2),
    (-11, -7, 1.5), (-15, -7.5, 0.5), (-18.5, -9.5, 0), (-19, -12, 0),
)  # fmt: skip
#: leg B, from the bottom of the eye's second leg (the same way back: over the tongue's left
#: side and the left arm, into the window, up under C1, over the right standing part, down
#: outside the window as the tongue's right side) over C2, up the left arm, under C1 to
#: where the right end joins y = 0 [d]
LEG_B = (
    (-13, -12, 0), (-13, -10.5, 0.5), (-11, -9.5, 1.5), (-8, -9.5, 2), (-3, -9.5, 2),
    (0.5, -9.5, 1.5), (1.5, -8.5, 0), (1.5, -6.5, -1.5), (1.5, -4.9, -2.6),
    (1.5, -3.1, -2.6), (1.5, -1.8, -1), (1.5, 0.3, 1), (3.5, 1.8, 2), (6.5, 1, 2),
    (8.5, -1.5, 1), (9, -4, 0), (9, -9, 0), (8.5, -11.5, 0), (6.5, -15, 0), (5, -17, 0),
    (2, -15.5, 0.5), (0, -13, 1), (-4, -11.5, 0.5), (-6.5, -9, 0), (-6, -7, 0),
    (-2.5, -5.5, -0.5), (0, -4, -1), (2.5, -2.5, -1), (6, -0.3, 0), (9, 0, 0), (12, 0, 0),
)  # fmt: skip


def alpine_butterfly(*, rod_diameter: float, n_nodes: int = 150,
                     pin_diameter: float) -> TiedKnot:  # fmt: skip
    r"""Alpine butterfly, drawn in (snug, not tight; module docstring), with its eye round a
    pin.

    Parameters
    ----------
    rod_diameter : float [m]
        d.
    n_nodes : int
        Nodes of the rope (>= 100).
    pin_diameter : float [m]
        D, between 0.5 d and 40 d (the eye's size; an end-to-end pull has no pin and
        uses the curve with the default pin of its scene).

    Returns
    -------
    TiedKnot
        ``ropes["rope"]``: the left end at node 0 (the standing part of the loop
        loading), the right end at the last node; ``pin``: point, axis (z) and diameter;
        ``expected`` (module docstring); ``info["eye_cut"]``.
    """
    d, n = check_sizes(rod_diameter, n_nodes, 100)
    D = check_pin(pin_diameter, d, 0.5, 40)
    left, right = _drawn_in(tuple(map(tuple, LEG_A)), tuple(map(tuple, LEG_B)))
    left, right = run_on(left, EXTEND, 0.0)[:-1], run_on(right, 0.0, EXTEND)[1:]
    R = 0.5 * (D / d + 1.0)
    p_out, p_back = left[-1], right[0]
    center = np.array([0.5 * (p_out[0] + p_back[0]), min(p_out[1], p_back[1]) - 4.0 - 2.0 * R])
    eye = bspline(_eye_south(p_out, p_back, center, R))
    nodes = equal_chords(np.vstack([left, eye[1:-1], right]) * d, n)
    far = np.array([center[0], center[1] - R, 0.0]) * d
    pin_c = (center[0] * d, center[1] * d, 0.0)
    info = {"pin_center": pin_c, "eye_cut": cut_at(nodes, far), "min_crossings": MIN_CROSSINGS,
            **start_checks([nodes], d)}  # fmt: skip
    return TiedKnot(
        name="alpine_butterfly",
        ropes={"rope": nodes},
        ends={"rope": ("standing", "tail")},
        rod_radius=0.5 * d,
        pin={"point": pin_c, "axis": (0.0, 0.0, 1.0), "diameter": D},
        expected={
            "alexander": (1,),
            "winding_pin": 1,
            "alexander_cut": ((1, -1, 1), (1, -1, 1)),
            "linking_cut": 1,
        },  # fmt: skip
        info=info,
    )


def loose_rope(leg_a=LEG_A, leg_b=LEG_B, eye_radius: float = EYE_R) -> np.ndarray:
    """The loosely tied rope [d] (dense, module docstring's construction) with its eye
    round a pin of centreline radius ``eye_radius`` [d]."""
    a, b = np.array(leg_a, float), np.array(leg_b, float)
    a = np.vstack([[a[0, 0] - TAIL - 3.0, 0, 0], [a[0, 0] - TAIL, 0, 0], a])
    b = np.vstack([b, [b[-1, 0] + TAIL, 0, 0], [b[-1, 0] + TAIL + 3.0, 0, 0]])
    center = np.array([0.5 * (a[-1, 0] + b[0, 0]), a[-1, 1] - 4.0 - 2.0 * eye_radius])
    eye = _eye_south(a[-1], b[0], center, eye_radius)
    (rope,), _ = build_ropes([np.vstack([a[:-1], eye, b[1:]])])
    return rope


@lru_cache(maxsize=4)
def _drawn_in(leg_a: tuple, leg_b: tuple) -> tuple[np.ndarray, np.ndarray]:
    """The rope up to the eye and from it [d], drawn in: the loose rope
    (:func:`loose_rope`) without its eye (the run below the legs' ends, y < -12.5 d and
    x < -7 d), scaled by :data:`SCALE` in the plane (the crossings' heights kept: an
    isotopy), resampled every :data:`~knotmech.scenes.tied._snug.H` and pushed apart by
    :data:`ROUNDS` rounds of :data:`~knotmech.scenes.tied._snug.SUB` repulsion sweeps at
    :data:`~knotmech.scenes.tied._snug.GAP` (each round resampled) and
    :data:`~knotmech.scenes.tied._snug.FINAL_SWEEPS` at
    :data:`~knotmech.scenes.tied._snug.FINAL_GAP` (each push a fraction of the overlap
    along the join of two points: no strand passes through another); each piece drawn as
    a dense spline. :func:`alpine_butterfly` lays the eye for its pin between them."""
    rope = loose_rope(leg_a, leg_b)
    eye = np.flatnonzero((rope[:, 1] < EYE_Y) & (rope[:, 0] < EYE_X))
    ps = [rope[: eye[0] + 1].copy(), rope[eye[-1] :].copy()]
    for p in ps:
        p[:, :2] *= SCALE
    ps = [_resampled(p) for p in ps]
    for _ in range(ROUNDS):
        for _ in range(SUB):
            ps = _repel(ps, GAP)
        ps = [_resampled(p) for p in ps]
    for _ in range(FINAL_SWEEPS):
        ps = _repel(ps, FINAL_GAP)
    return _dense(ps[0]), _dense(ps[1])


def _quarter(p, sign: float) -> np.ndarray:
    """Points (..., 3) turned by sign x 90 deg about z."""
    q = np.array(p, float)
    q[..., 0], q[..., 1] = -sign * p[..., 1], sign * p[..., 0]
    return q


def _eye_south(p_out, p_back, center, radius) -> np.ndarray:
    """Control polygon [d] of an eye heading south (-y) from ``p_out`` round the pin at
    ``center`` and back north to ``p_back``: :func:`eye_controls` in a frame turned by
    90 degrees."""
    c = _quarter(np.array([center[0], center[1], 0.0]), 1.0)[:2]
    eye = eye_controls(_quarter(p_out, 1.0), _quarter(p_back, 1.0), c, radius, 2.0 + radius)
    return _quarter(eye, -1.0)

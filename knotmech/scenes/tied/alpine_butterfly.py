r"""Alpine butterfly (butterfly loop, lineman's loop; ABoK #1053): a mid-line eye round a pin.

Construction: tied in the bight, as by hand. A bight is given a full twist (its two legs
cross twice: C1 near the ends, C2 below it; between them the *window* W), and the loop
beyond C2 (the *tongue*) is laid over the window's right arm and passed through the
window to the back, out under its left arm: the tongue's tip is the eye (Ashley, *The
Ashley Book of Knots*, 1944, #1053; the twist method). In the plane (rod diameters d, the
ends along y = 0)::

      far left  ====\        /====  far right         node 0: the left end (x < 0)
                     \  C1  /                          last node: the right end (x > 0)
                      \/\/                             the eye: south-west, round a pin
          eye <==== (  W   ) ====\                     (axis z) of diameter D at
          legs      \  /\  /     |   the tongue,       centreline radius (D + d)/2
                     C2    ======/   laid over W

Along the rope from node 0: leg A from the far left over C1, down the window's right arm,
under C2, round the tongue's outer track (south, east, north), west over the right arm,
through W and under its left arm, south round the pin (the eye), back north and east as
the tongue's inner track under the left arm and over the right arm, round the tongue's
inner track (south, west, north), over C2, up the window's left arm, under C1 and out to
the far right. Six crossings; both ends leave the knot in opposite directions (along -x
and +x) and the eye sticks out sideways (-y).

Topology, proven in ``tests/scenes/test_tied_curves.py``:

- both ends joined far outside (the eye left as it is): the **unknot**. The knot is tied
  in the bight (no end is passed through anything): every move of the tying is an
  isotopy of the rope with its ends held, so the ends joined far away bound a disk.
- its winding about the pin: **1 turn** (the eye round the pin).
- cut at the far side of the pin (the butterfly bend: the eye's two legs become two
  ropes' tails), each half closed on its own: **two unknots** (each half crosses itself
  once: a kink), **linked once**. The twisted bight alone (the tongue not through the
  window, pulled out) would give two unlinked halves: the linking number is the tongue
  threaded through the window.

Loadings (:func:`knotmech.scenes.loops.loop`): on the loop (the eye round the pin, node 0
pulled, the right end the free tail) or end to end (both ends pulled apart, the eye free,
no pin): the alpine butterfly takes load in all three directions (ABoK #1053).
"""

from __future__ import annotations

import numpy as np

from knotmech.scenes.tied._common import (
    TiedKnot,
    build_ropes,
    check_pin,
    check_sizes,
    cut_at,
    eye_controls,
    finish,
    start_checks,
)

__all__ = ["alpine_butterfly"]

TAIL = 8.0  #: straight ends [d]
#: leg A, from where the left end leaves the line y = 0 to the top of the eye's first leg
#: [d]; z (+/-1) orders the strands at the crossings (C1, the right arm, C2, W)
LEG_A = (
    (-9, 0, 0), (-6, -0.3, 0), (-2.5, -2.5, 1), (0, -4, 1), (2.5, -5.5, 0), (5.5, -6.5, -1),
    (6.5, -8, -1), (5.5, -9.5, -1), (2.5, -11.5, 0), (0, -13, -1), (-2, -15, -1),
    (-2.5, -18, 0), (-2, -21.5, 0), (1, -22.5, 0), (14, -22.5, 0), (17, -21, 0),
    (17.5, -18, 0), (17.5, -9, 0), (16, -6.5, 0), (12, -6.5, 1), (8, -6.5, 1), (5.5, -6.5, 1),
    (0, -6.5, 0), (-6, -6.5, -1), (-9, -6.5, -1), (-13, -6.5, 0), (-15, -8, 0), (-15, -12, 0),
)  # fmt: skip
#: leg B, from the bottom of the eye's second leg to where the right end joins y = 0 [d]
LEG_B = (
    (-9, -12, 0), (-9, -10, 0), (-8, -9.5, 0), (-6, -9.5, -1), (0, -9.5, 0), (5.5, -9.5, 1),
    (9, -9.5, 1), (13, -10, 0), (14, -12, 0), (14, -17, 0), (12.5, -19.2, 0), (4, -19.2, 0),
    (2, -18, 0), (2, -15, 1), (0, -13, 1), (-2.5, -11.5, 0), (-5.5, -9.5, 1), (-6.5, -8, 1),
    (-5.5, -6.5, 1), (-2.5, -5.5, 0), (0, -4, -1), (2.5, -2.5, -1), (6, -0.3, 0), (9, 0, 0),
)  # fmt: skip


def alpine_butterfly(*, rod_diameter: float, n_nodes: int = 400,
                     pin_diameter: float) -> TiedKnot:  # fmt: skip
    r"""Loosely tied alpine butterfly with its eye round a pin.

    Parameters
    ----------
    rod_diameter : float [m]
        d.
    n_nodes : int
        Nodes of the rope (>= 150).
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
    d, n = check_sizes(rod_diameter, n_nodes, 150)
    D = check_pin(pin_diameter, d, 0.5, 40)
    a, b = np.array(LEG_A, float), np.array(LEG_B, float)
    a = np.vstack([[a[0, 0] - TAIL - 3.0, 0, 0], [a[0, 0] - TAIL, 0, 0], a])
    b = np.vstack([b, [b[-1, 0] + TAIL, 0, 0], [b[-1, 0] + TAIL + 3.0, 0, 0]])
    R = 0.5 * (D / d + 1.0)
    center = np.array([0.5 * (a[-1, 0] + b[0, 0]), a[-1, 1] - 4.0 - 2.0 * R])
    eye = _eye_south(a[-1], b[0], center, R)
    (rope,), _ = build_ropes([np.vstack([a[:-1], eye, b[1:]])])
    (nodes,) = finish([rope], d, n)
    far = np.array([center[0], center[1] - R, 0.0]) * d
    pin_c = (center[0] * d, center[1] * d, 0.0)
    info = {"pin_center": pin_c, "eye_cut": cut_at(nodes, far), **start_checks([nodes], d)}
    return TiedKnot(
        name="alpine_butterfly",
        ropes={"rope": nodes},
        ends={"rope": ("standing", "tail")},
        rod_radius=0.5 * d,
        pin={"point": pin_c, "axis": (0.0, 0.0, 1.0), "diameter": D},
        expected={
            "alexander": (1,),
            "winding_pin": 1,
            "alexander_cut": ((1,), (1,)),
            "linking_cut": 1,
        },  # fmt: skip
        info=info,
    )


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

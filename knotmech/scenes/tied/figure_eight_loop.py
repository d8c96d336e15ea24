r"""Figure-eight loop (figure-eight on a bight, ABoK #1047): a fixed eye round a pin.

Construction: a figure-eight knot tied in a doubled rope. The single-rope long figure-eight
(:func:`~knotmech.scenes.tied._common.long_knot_controls`: a parametric 4_1 cut open at its
outermost point, ends to the far left and far right, one kink where the two ends cross) is
split into two parallel strands 1.3 d apart (a flat ribbon, the knot "dressed") and drawn
in by the contract-and-repel pass of :func:`~knotmech.scenes.tied._snug.snug_figure_eight`
(the knot about 9 x 6 x 5 d; the doubled parametric knot was about 40 x 24 d); the two
ends at the left are run on by :data:`EXTEND`; at the right the two strands are one rope,
joined by the eye, a half turn round a pin (axis z) of diameter D at centreline radius
(D + d)/2::

    standing  ======\      figure-eight       /=======\
                     >====  (4 crossings of   ==        (  pin )
    tail      ======/      the doubled rope)  \=======/
              (far left)                         eye

Node 0 is the standing part (upper strand, far left), the last node the tail (lower
strand, far left).

Topology, proven in ``tests/scenes/test_tied_curves.py``:

- standing part joined to the tail far outside: the **unknot**. The knot is tied on a
  bight (no end is passed through anything), so the closed rope is the boundary of the
  doubled rope's ribbon, a disk.
- its winding about the pin: **1 turn** (the eye is closed round the pin).
- cut at the far side of the pin, each half closed on its own is a **figure-eight knot
  4_1** (Alexander polynomial :math:`-1 + 3t - t^2`, determinant 5): each half is one
  strand of the doubled figure-eight; and the two halves link :math:`-w` times, w the
  writhe of the single-rope diagram (two parallel strands of a flat ribbon link as often
  as the core diagram's writhe; the second half runs the other way, hence the sign). The
  diagram here has w = 1 (the 4_1 diagram's writhe 0 plus the kink's +1).
"""

from __future__ import annotations

import numpy as np

from knotmech.scenes.tied._common import (
    TiedKnot,
    bspline,
    check_pin,
    check_sizes,
    cut_at,
    eye_controls,
    start_checks,
)
from knotmech.scenes.tied._snug import equal_chords, run_on, snug_figure_eight

__all__ = ["figure_eight_loop"]

EXTEND = 12.0  #: the standing part and the tail run on beyond the drawn-in knot [d]
LEG = 2.0  #: the eye's legs run on beyond the drawn-in knot before the eye [d]


def figure_eight_loop(*, rod_diameter: float, n_nodes: int = 150,
                      pin_diameter: float) -> TiedKnot:  # fmt: skip
    r"""Figure-eight loop, drawn in (snug, not tight), with its eye round a pin.

    Parameters
    ----------
    rod_diameter : float [m]
        d.
    n_nodes : int
        Nodes of the rope (>= 100).
    pin_diameter : float [m]
        D, between 0.5 d and 40 d.

    Returns
    -------
    TiedKnot
        ``ropes["rope"]``: standing part at node 0, tail at the last node; ``pin``: point,
        axis (z) and diameter; ``expected`` (module docstring); ``info["eye_cut"]``.
    """
    d, n = check_sizes(rod_diameter, n_nodes, 100)
    D = check_pin(pin_diameter, d, 0.5, 40)
    upper, lower, w = snug_figure_eight()
    upper, lower = run_on(upper, EXTEND, LEG), run_on(lower, EXTEND, LEG)
    R = 0.5 * (D / d + 1.0)
    y_mid = 0.5 * (upper[-1, 1] + lower[-1, 1])
    center = np.array([upper[-1, 0] + 4.0 + 2.0 * R, y_mid])
    eye = bspline(eye_controls(upper[-1], lower[-1], center, R, 2.0 + R))
    rope = np.vstack([upper, eye[1:], lower[::-1][1:]])
    nodes = equal_chords(rope * d, n)
    far = np.array([center[0] + R, center[1], 0.0]) * d
    info = {"pin_center": (center[0] * d, center[1] * d, 0.0), "writhe": w,
            "eye_cut": cut_at(nodes, far), **start_checks([nodes], d)}  # fmt: skip
    return TiedKnot(
        name="figure_eight_loop",
        ropes={"rope": nodes},
        ends={"rope": ("standing", "tail")},
        rod_radius=0.5 * d,
        pin={"point": info["pin_center"], "axis": (0.0, 0.0, 1.0), "diameter": D},
        expected={
            "alexander": (1,),
            "winding_pin": -1,
            "alexander_cut": ((-1, 3, -1),) * 2,
            "linking_cut": -w,
        },  # fmt: skip
        info=info,
    )

r"""Bowline (ABoK #1010): a fixed eye round a pin, the standing part loaded, the tail free.

The sheet-bend structure (:mod:`.sheet_bend`, same control polygons) with B's tail joined
to A's standing leg by the eye (Turner & van de Griend, *History and Science of Knots*,
1996, p. 125: a loop knot is a bend with one working end joined to a standing end).
Along the rope from node 0:

1. the **standing part** comes from the far right (+x) along y = 0, passes over the
   collar's apex and under the collar's return leg, and forms the **nipping loop**
   (the "rabbit hole"): down, left, up over both collar legs, right, down under both, over
   its own first run;
2. it leaves the loop to the left along y = -8.5 d (the first **eye leg**), runs a half
   turn round the **pin** (axis z, diameter D, centreline radius (D + d)/2) at the far
   left, and comes back along y = +2.2 d (the second eye leg);
3. the second eye leg goes up through the nipping loop (under its left side, over its
   right side), round the standing part behind it (the **collar**, a half turn about
   x = 7.5 d), back down through the loop (over its right side, under its left side), and
   ends as the **tail** along y = -2.2 d inside the eye (the last node), between the two
   eye legs (a right-handed bowline, not the "cowboy" one).

Topology, proven in ``tests/scenes/test_tied_curves.py``:

- standing part joined to the tail, the tail lifted straight out of the eye (+z) and
  taken over everything: the knot **6_3** (Alexander polynomial
  :math:`1 - 3t + 5t^2 - 3t^3 + t^4`, determinant 13); the test checks it equals the
  closure of :func:`.sheet_bend`'s two ropes with B's tail joined to A's standing part by
  a rectangular path round the far left (a second embedding: other lengths, no pin, no
  eye) and A's tail lifted out the same way;
- the closed rope winds **once** round the pin (clockwise seen from +z: -1);
- cut at the far side of the pin: two unknots (a bight and a kinked loop: the sheet
  bend's two ropes). Their linking number is not checked here: the tail ends inside the
  eye, so it depends on how each half is closed (the sheet bend checks it, +1, with all
  four ends outside).
"""

from __future__ import annotations

import numpy as np

from knotmech.errors import InputError
from knotmech.scenes.tied._common import (
    LEG,
    TiedKnot,
    build_ropes,
    check_pin,
    check_sizes,
    cut_at,
    eye_controls,
    finish,
    sheet_controls,
    start_checks,
)

__all__ = ["bowline"]

EYE_X = -14.0  #: where the eye legs leave the knot [d] (with the default tail)
TAIL_Y = -8.5  #: y of the first eye leg [d]
TAIL = 7.0  #: default straight run of the tail beyond the nipping loop [d]
NIP_LEFT = -3.0  #: the nipping loop's left side [d]


def bowline(
    *, rod_diameter: float, n_nodes: int = 300, pin_diameter: float, tail: float = TAIL
) -> TiedKnot:
    r"""Loosely tied bowline with its eye round a pin.

    Parameters
    ----------
    rod_diameter : float [m]
        d.
    n_nodes : int
        Nodes of the rope (>= 150).
    pin_diameter : float [m]
        D, between 0.5 d and 40 d.
    tail : float
        Straight run of the tail beyond the nipping loop [d], 4-40 (default 7); the eye
        legs are as much longer (the tail lies inside the eye, 4 d short of where they
        leave the knot).

    Returns
    -------
    TiedKnot
        ``ropes["rope"]``: standing part at node 0, tail at the last node; ``pin``: point,
        axis (z) and diameter; ``expected`` (module docstring); ``info["eye_cut"]``.
    """
    d, n = check_sizes(rod_diameter, n_nodes, 150)
    D = check_pin(pin_diameter, d, 0.5, 40)
    eye_x = NIP_LEFT - _tail(tail) - 4.0
    a, b = sheet_controls(left=eye_x + 4.0)
    a = a[1:]  # A's standing leg starts where the eye ends
    a[0, 0] = eye_x
    b[-1, 0] = eye_x
    R = 0.5 * (D / d + 1.0)
    center = np.array([eye_x - 6.0 - 2.0 * R, 0.5 * (TAIL_Y + LEG)])
    eye = eye_controls(b[-1], a[0], center, R, 3.0, direction=-1.0)
    ctrl = np.vstack([b[:-1], eye, a[1:]])
    (rope,), _ = build_ropes([ctrl])
    (nodes,) = finish([rope], d, n)
    pin_c = (center[0] * d, center[1] * d, 0.0)
    far = np.array([center[0] - R, center[1], 0.0]) * d
    info = {"pin_center": pin_c, "eye_cut": cut_at(nodes, far), "cut_linking": False,
            **start_checks([nodes], d)}  # fmt: skip
    return TiedKnot(
        name="bowline",
        ropes={"rope": nodes},
        ends={"rope": ("standing", "tail")},
        rod_radius=0.5 * d,
        pin={"point": pin_c, "axis": (0.0, 0.0, 1.0), "diameter": D},
        expected={
            "alexander": (1, -3, 5, -3, 1),
            "winding_pin": -1,
            "alexander_cut": ((1,), (1,)),
        },  # fmt: skip
        info=info,
    )


def _tail(tail) -> float:
    """The tail's straight run [d], checked to lie in [4, 40]."""
    t = float(tail) if isinstance(tail, (int, float)) else float("nan")
    if not 4.0 <= t <= 40.0:
        raise InputError(f"tail must lie in [4, 40] rod diameters, got {tail!r}")
    return t

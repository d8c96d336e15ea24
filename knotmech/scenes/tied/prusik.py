r"""Prusik knot (ABoK #1763): a closed sling wrapped round a pole and through itself,
loaded along the pole's axis.

Coordinates: the pole is the z axis, diameter D; the sling's centreline lies on the
cylinder of radius :math:`R = (D + d)/2`. On the unrolled cylinder (:math:`\psi` the angle
from the +y direction, turning towards -x; z up) the knot is a girth hitch with ``wraps``
turns a side, as :func:`knotmech.scenes.hitch_curves.cow_hitch_curve`'s core with more
turns:

- the lower leg arrives at :math:`\psi = 0` (from +x, tangent to the pole) at height
  :math:`-z_t`, and winds down ``wraps`` turns (a helix of pitch g d, g = 1.3);
- the **bridge**: at :math:`\psi = 2\pi n + 0.35` the sling turns up, crosses over all the
  turns and the two legs' run-ins lifted 1.3 d off the pole, and turns back;
- the upper half mirrors the lower: ``wraps`` turns back up (the other sense), leaving at
  :math:`\psi = 0`, height :math:`+z_t`, towards +x;
- the two legs then run out 3 d and 5 d along +x and down along -z, side by side 2 d
  apart, and are joined at the bottom by a half turn (the loaded loop, pulled along -z)::

        side view (looking along -y)      unrolled, the bridge over the turns
          pole                               psi ->
          ||  ==== upper turns                ====\\  /====
          ||  ====                            ====|| |====
          ||--legs---+  +                     --->|| |<--- legs in
          ||  ====   |  |                     ====|| |====
          ||  ====   |  |                     ====//  \\====
                     +--+  loaded loop

Node order: the sling is closed (its last node joins its first); node 0 is the lower leg
where it meets the pole.

Topology, proven in ``tests/scenes/test_tied_curves.py``:

- the sling alone: the **unknot** (an untied loop);
- its linking number with the pole axis: **0** (each turn is made by the doubled sling,
  whose two strands pass the pole in opposite senses; the girth hitch itself, a sling put
  behind the pole with one end pulled through the other, does not link the pole either);
- the fingerprint of the hitch on the pole: the over/under code of the sling's
  crossings seen from the pole axis (:func:`knotmech.scenes.topology.post_crossing_code`,
  strands within 3 d of the pole), read along the sling from the lower leg:
  ``"U" * 2n + "O" * 2n + "U" * n + "O" * n`` (3n crossings for n turns a side: the lower
  half passes under the bridge and the lifted last turn, the bridge passes over them, the
  upper half likewise). This code is the construction's own, recorded as a regression
  fingerprint (it changes if a strand passes through another), not derived independently.

Pole diameters from 1 d to 10 d (a Prusik cord on a rope is D of about 1.5 to 2 d).
"""

from __future__ import annotations

import numpy as np

from knotmech.errors import InputError
from knotmech.scenes.tied._common import (
    TiedKnot,
    bspline,
    check_pin,
    check_sizes,
    finish,
    start_checks,
)
from knotmech.scenes.topology import post_crossing_code

__all__ = ["prusik"]

GAP = 1.3  #: axial spacing of the turns and the legs [d]
LIFT = 1.3  #: radial lift of the bridge over the turns [d]
BRIDGE = 0.35  #: angle of the bridge past whole turns [rad]
LEG = 10.0  #: length of the legs along the pole below the knot [d]


def _helix_controls(Rd: float, n: int):
    """(u, z, rho) control points [d] of the lower half, from the leg to the bridge's foot."""
    zt = 0.5 * GAP
    zw = zt + GAP
    psi = np.arange(0.0, 2 * np.pi * n + BRIDGE, 0.35)
    u = np.clip(psi / max(1.2, 2.5 / Rd), 0.0, 1.0)  # run-in over >= 2.5 d of arc
    z = -(zt + ((zw - zt) + GAP * psi / (2 * np.pi)) * u * u * (3.0 - 2.0 * u))
    lo = 2 * np.pi * n - 0.9
    rho = Rd + LIFT * np.clip((psi - lo) / 0.6, 0.0, 1.0)
    return np.column_stack([psi * Rd, z, rho])


def _core_controls(Rd: float, n: int) -> np.ndarray:
    """(u, z, rho) control polygon [d] of the whole wrapped part, lower leg to upper leg."""
    low = _helix_controls(Rd, n)
    ub = (2 * np.pi * n + BRIDGE) * Rd
    zb = low[-1, 1]
    rb = Rd + LIFT
    bridge = [(ub + 1.0, zb + 0.6, rb), (ub + 1.3, zb + 2.0, rb), (ub + 1.3, 0.0, rb),
              (ub + 1.3, -zb - 2.0, rb), (ub + 1.0, -zb - 0.6, rb)]  # fmt: skip
    high = low[::-1] * [1.0, -1.0, 1.0]
    return np.vstack([low, bridge, high])


def _to_xyz(uzr: np.ndarray, Rd: float) -> np.ndarray:
    """Unrolled (u, z, rho) [d] to x, y, z [d] (psi = u / R from +y towards -x)."""
    psi = uzr[:, 0] / Rd
    return np.column_stack([-uzr[:, 2] * np.sin(psi), uzr[:, 2] * np.cos(psi), uzr[:, 1]])


def _loop_controls(Rd: float) -> np.ndarray:
    """Control polygon [d] of the legs and the loaded loop, upper leg to lower leg. The legs
    turn down at x = a and a + 2 (a such that the tangent plane y = R there is 1.5 d off the
    pole's surface, at least 3 d)."""
    zt = 0.5 * GAP
    a = max(3.0, float(np.sqrt((Rd + 1.5) ** 2 - Rd**2)) + 0.5)
    b = a + 2.0
    return np.array([(0.0, Rd, zt), (1.0, Rd, zt), (b - 1.0, Rd, zt), (b, Rd, zt - 1.5),
                     (b, Rd, -LEG), (b, Rd, -LEG - 1.0), (a + 1.0, Rd, -LEG - 2.0),
                     (a, Rd, -LEG - 1.0), (a, Rd, -LEG), (a, Rd, -zt - 2.5),
                     (a - 1.5, Rd, -zt), (1.0, Rd, -zt), (0.0, Rd, -zt)])  # fmt: skip


def prusik(*, rod_diameter: float, n_nodes: int = 400, pin_diameter: float,
           wraps: int = 3) -> TiedKnot:  # fmt: skip
    """Loosely tied Prusik knot of a closed sling on a pole (axis z).

    Parameters
    ----------
    rod_diameter : float [m]
        d, the sling's cord.
    n_nodes : int
        Nodes of the sling (>= 200).
    pin_diameter : float [m]
        D, the pole, between 1 d and 10 d.
    wraps : int
        Turns a side (>= 2; a girth hitch is 1, the Prusik 2 to 4; at most 6).

    Returns
    -------
    TiedKnot
        ``ropes["sling"]`` (closed: the last node joins the first); ``pin``: the pole;
        ``expected`` (module docstring).
    """
    d, n = check_sizes(rod_diameter, n_nodes, 200)
    D = check_pin(pin_diameter, d, 1, 10)
    if isinstance(wraps, bool) or not float(wraps).is_integer() or not 2 <= int(wraps) <= 6:
        raise InputError(f"wraps must be an integer from 2 to 6 (turns a side), got {wraps!r}")
    Rd = 0.5 * (D / d + 1.0)
    core = _to_xyz(bspline(_core_controls(Rd, int(wraps))), Rd)
    loop = bspline(_loop_controls(Rd))
    sling = np.vstack([core, loop[1:-1]])
    (nodes,) = finish([np.vstack([sling, sling[:1]])], d, n + 1)
    nodes = nodes[:-1]
    code = post_crossing_code(nodes, max_radius=0.5 * D + 3.0 * d)
    info = {"wraps": int(wraps), "wrap_radius": 0.5 * (D + d), "post_code": code,
            **start_checks([nodes], d, closed=True)}  # fmt: skip
    return TiedKnot(
        name="prusik",
        ropes={"sling": nodes},
        ends={"sling": ("closed", "closed")},
        rod_radius=0.5 * d,
        pin={"point": (0.0, 0.0, 0.0), "axis": (0.0, 0.0, 1.0), "diameter": D},
        expected={"alexander": (1,), "winding_pin": 0},
        info=info,
    )

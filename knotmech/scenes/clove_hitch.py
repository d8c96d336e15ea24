r"""The clove hitch on a rigid post in simulation: tie, load, read T(s), contacts, Darboux.

Tying (a pre-shaped curve relaxed with contact, instead of the seven-step protocol of the
clove-hitch paper, sec. 4): :func:`knotmech.scenes.curves.clove_hitch_curve` puts two wraps
on the post at centreline radius :math:`R = (D+d)/2` with the diagonal crossing over both
ends; the naturally straight rod is then released with both ends under a small pre-tension
:math:`T_\mathrm{pre}`, so it settles onto the post (rigid cylinder, elasto-plastic friction
on the rod surface, :class:`knotmech.rod.contact.CylinderContact`) and onto itself (the
implicit contact model, :class:`knotmech.rod.contact.RodContact`).

Loading (the clove-hitch paper, sec. 5-8), dead loads along the two tails:

- ``"symmetric"``: both ends pulled with T (:math:`T_\mathrm{high} = T_\mathrm{low}`);
- ``"asymmetric"``: end 0 with :math:`T_\mathrm{high}`, the other end with :math:`T_\mathrm{low}`;
- ``"free"``: :math:`T_\mathrm{low} = 0`, a hanging load :math:`T_\mathrm{high}` on end 0 and the
  other end free; the run decides *hold* (the loaded end stops) or *slip*.
- ``"pull"``: the force-displacement test of the clove-hitch paper (sect. 5, Fig. 1d): the
  hitch settles with both ends at the pre-tension (0.559 N), end 0 is then clamped where it
  settled, the other end's dead load is lowered to :math:`T_\mathrm{low}` (0.069 N), and
  end 0 is pulled at a constant speed; :math:`T_\mathrm{high}(\Delta)` is the clamp's
  reaction along the pull. Rod-post friction with :math:`\mu_s \ge \mu_k`
  (``mu_rod_post``, ``mu_kinetic``); the rod-rod friction has a single coefficient.

Outputs: tension profile :math:`T(s)` (axial force of each edge), rod-post and rod-rod
contact regions, the components of the Darboux vector :math:`\Omega_a(s)` in the material
frame (curvatures :math:`\Omega_1, \Omega_2` and twist :math:`\Omega_3`, the clove-hitch
paper eqs. 1-2), the knot's winding number about the post and its over/under code.

Default parameters: the clove-hitch paper, sec. 7: (d, D, L) = (4, 30, 374) mm, VPS32
(E = 1.26 MPa), :math:`\mu_{rc} = \mu_{rr} = 0.3`, :math:`T_\mathrm{high}` = 1.47 N.
The rod-rod friction is by default the elasto-plastic anchor (``friction="anchor"``,
:class:`knotmech.rod.friction.AnchorFriction`), which sticks: a held hitch does not creep.
``friction="imc"`` selects the regularised law of the coated-rod paper, which does not
stick exactly (a hitch held only by its nips creeps slowly). The hold/slip verdict
compares the creep over the last half of the hold with ``slip_distance`` (the rule of the
shipped phase tables; the creep speed over the last second is reported too,
``creep_speed``, but does not decide, unless ``creep_limit`` is given).

The scene is :func:`knotmech.scenes._hitch.run_hitch` with this module's start curve (the
shape every post hitch shares); this module holds only what is the clove hitch's own.
"""

from __future__ import annotations

import numpy as np

from knotmech.errors import InputError
from knotmech.scenes._hitch import (
    PAPER_PRETENSION,
    HitchKnot,
    HitchResult,
    darboux_profile,
    hitch_scene,
)
from knotmech.scenes.curves import clove_hitch_curve

__all__ = ["CloveHitchResult", "clove_hitch", "darboux_profile", "PAPER_PRETENSION", "CLOVE"]

TAIL = 0.064  #: [m] tail at each end when ``rod_length`` is None (the paper's 374 mm rod)
EDGE = 0.374 / 119  #: [m] edge length when ``n_nodes`` is None


class CloveHitchResult(HitchResult):
    """Recorded output of a clove-hitch run: a :class:`~knotmech.scenes._hitch.HitchResult`
    (see there for the attributes)."""


def _curve(post_diameter, rod_diameter, rod_length, n_nodes):
    """Two wraps round the post (4 pi R plus 15 % for the crossing) and equal tails."""
    R = 0.5 * (post_diameter + rod_diameter)
    wraps = 4 * np.pi * R * 1.15
    L = wraps + 2 * TAIL if rod_length is None else rod_length
    tail = 0.5 * (L - wraps)
    if tail < 4 * rod_diameter:
        raise InputError(
            f"rod_length must exceed about 4 pi R + 8 d = {wraps + 8 * rod_diameter:.3g} m, "
            f"got {L:g}"
        )
    n = int(round(L / EDGE)) + 1 if n_nodes is None else n_nodes
    return clove_hitch_curve(post_diameter=post_diameter, rod_diameter=rod_diameter,
                             tail_length=tail, n_nodes=n)  # fmt: skip


#: the clove hitch as a post hitch: its curve, two wraps for the contact sizing of a pull,
#: no knot invariants beyond the winding (its closure depends on how the tails lie) and the
#: distance rule for the verdict
CLOVE = HitchKnot(
    name="clove_hitch", curve=_curve, pull_angle=4 * np.pi, creep_limit=None, hold_damping=None
)

clove_hitch = hitch_scene(
    CLOVE,
    doc=r"""Tie a clove hitch on a post and load it.

    Parameters
    ----------
    loading : {"symmetric", "asymmetric", "free", "pull"}
        ``"pull"``: the clove-hitch paper's force-displacement test (sect. 5, Fig. 1d). The
        hitch settles with dead loads ``pretension`` on both ends; end 0 is then held by a
        clamp where it settled while the other end's dead load is lowered to ``t_low`` (the
        extra weight removed), and pulled at ``pull_speed`` along its tail for
        ``pull_distance``; T_high is the clamp's reaction along the pull.
    t_high : float [N]
        Load on end 0 (and on both ends when symmetric); ignored by ``"pull"``.
    t_low : float [N], optional
        Load on the other end: ``t_high`` (symmetric), required (asymmetric), 0 (free);
        ``"pull"``: the dead load (default 0.069 N, the paper's 7 g).
    rod_diameter, post_diameter, rod_length : float [m]
        ``rod_length`` None: two wraps (4 pi R plus 15 %) and a 64 mm tail at each end.
    youngs_modulus : float [Pa]; density : float [kg/m^3]
    mu_rod_post, mu_rod_rod : float
        Rod-cylinder (static, mu_s) and rod-rod friction coefficients (the rod-rod one
        static and kinetic alike).
    pretension : float [N], optional
        Load on both ends while the hitch settles (default ``0.1 * t_high``; ``"pull"``:
        the paper's 0.559 N).
    settle_time, load_time, hold_time : float [s]
        Settling under the pre-tension, ramp to the final loads, hold at the final loads
        (``"pull"``: ``load_time`` lowers the dead load to ``t_low``; no hold).
    n_nodes : int or None
        None: edges of about 3.1 mm (120 nodes on 374 mm).
    dt : float [s]
        Nominal step of the settling (and of the dead-load phases).
    slip_distance : float [m], optional
        Free-end loading: slip if end 0 moves more than this during the last half of the
        hold (default one rod diameter); the run stops early once end 0 has moved 0.3 L.
    n_frames : int
    options : knotmech.rod.SolverOptions, optional
    progress : bool
    pull_speed : float [m/s]
        ``"pull"``: speed of end 0 (default 20 mm/s; the run is quasi-static: the drag during
        the pull is 1 % of ``t_low``).
    pull_distance : float [m]
        ``"pull"``: displacement of end 0 (default 40 mm).
    mu_kinetic : float, optional
        Kinetic rod-post coefficient mu_k <= ``mu_rod_post`` (default ``mu_rod_post``:
        kinetic friction only).
    pull_dt : float [s], optional
        ``"pull"``: nominal step of the pull (default: end 0 moves 1/4 of an edge per step,
        at most 0.2 rod radii).
    max_node_steps : float, optional
        Bound on (t_end/dt) x nodes, checked before the rod is built (default
        :data:`knotmech.scenes._common.MAX_NODE_STEPS`; ``inf`` lifts it).
    friction : {"anchor", "imc"}
        Rod-rod friction law: ``"anchor"`` (default) the elasto-plastic anchor per contact
        pair, which sticks below ``mu |F_n|`` (:class:`~knotmech.rod.friction.AnchorFriction`;
        a held hitch does not creep); ``"imc"`` the regularised law of the implicit
        contact model and the coated-rod paper (:class:`~knotmech.rod.friction.
        SmoothFriction`), which vanishes at zero slip, so that a hitch held by its nips
        creeps (the law of the shipped phase tables).

    creep_limit : float or None [d/s]
        Free-end verdict: also slip when end 0 creeps faster than this over the last
        second of the hold (default None: the ``slip_distance`` rule only,
        that of the shipped phase tables).

    Returns
    -------
    CloveHitchResult
    """,
    result_type=CloveHitchResult,
)
clove_hitch.__module__ = __name__  # pickled by reference (a sweep sends it to workers)

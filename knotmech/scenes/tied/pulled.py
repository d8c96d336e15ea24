r"""What a tied bend's pull needs from its curve: grip directions, tail draw-in, topology.

The tied bends (:mod:`knotmech.scenes.tied`: sheet bend, double sheet bend, flat overhand
bend, figure-eight bend, double fisherman's) are pulled by
:class:`knotmech.scenes.bends.TiedBendScene`. Each rope's node 0 is its standing part and
its last node its tail. This module holds the pieces that depend only on the node arrays:

- :func:`end_direction`: the outward unit tangent at a rope end (the direction a grip
  pulls it);
- :func:`tail_free_lengths`: the arc length of each tail outside the knot, whose decrease
  is the tail's *draw-in* (a material measure: it does not move with the knot, so that a
  knot which rolls along its ropes, as the flat overhand bend does, draws both tails in);
- :func:`invariants_changed`: which of a frame's invariants
  (:func:`knotmech.scenes.tied.measure`) differ from the start shape's;
- :func:`rope_types` and :func:`tails_drawn`: each rope's knot type alone and how far each
  tail end moved towards the knot, which tell a tail drawn through the knot (the knot came
  undone: a slip) from a change with the tail not drawn in (not a result).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from knotmech.scenes.tied._common import TiedKnot, invariant, join_far, measure

__all__ = [
    "NEAR",
    "end_direction",
    "tail_nodes",
    "tail_free_lengths",
    "frame_invariants",
    "invariants_changed",
    "rope_types",
    "tails_drawn",
]

#: a node is inside the knot when another strand's node lies within NEAR d of it (1 d is
#: touching; the loose start shapes have their strands 1.1-1.3 d apart)
NEAR = 1.5
#: on the frames of a pull (the bend set, its strands touching at about 1 d): NEAR_SET d
NEAR_SET = 1.25
#: along its own rope, nodes closer than OWN d of arc are neighbours, not another strand
OWN = 4.0
#: |cos| of the angle between two tangents above which strands are parallel (25 deg)
PARALLEL = float(np.cos(np.radians(25.0)))


def end_direction(nodes, end: str) -> np.ndarray:
    """Outward unit tangent (3,) at the ``"start"`` or ``"end"`` of a rope (over its last
    three edges)."""
    x = np.asarray(nodes, float)
    p = x if end == "start" else x[::-1]
    u = p[0] - p[3]
    return u / np.linalg.norm(u)


def _tangents(x) -> np.ndarray:
    t = np.gradient(x, axis=0)
    return t / np.linalg.norm(t, axis=1, keepdims=True)


def _first_inside(x, rope, others, d, *, crossing_only: bool = False, near: float = NEAR) -> int:
    """Nodes of ``rope`` (walking in from its last node) before the first one within
    NEAR d of a node in ``others`` or of its own rope more than OWN d of arc away;
    ``crossing_only``: only strands not parallel to it (tangents less than 25 deg apart
    are parallel) count."""
    xr, xo = x[rope], x[others]
    h = float(np.mean(np.linalg.norm(np.diff(xr, axis=0), axis=1)))
    idx = np.arange(len(rope))
    far_own = np.abs(idx[:, None] - idx[None, :]) >= int(np.ceil(OWN * d / h))
    near_o = np.linalg.norm(xr[:, None, :] - xo[None, :, :], axis=2) < near * d
    near_s = (np.linalg.norm(xr[:, None, :] - xr[None, :, :], axis=2) < near * d) & far_own
    if crossing_only:
        tr = _tangents(xr)
        near_o &= np.abs(tr @ _tangents(xo).T) < PARALLEL
        near_s &= np.abs(tr @ tr.T) < PARALLEL
    inside = (near_o.any(axis=1) | near_s.any(axis=1))[::-1]
    return int(np.argmax(inside)) if inside.any() else len(rope) - 1


def tail_nodes(x0, n_nodes: int, d: float) -> tuple[int, int]:
    """Number of nodes of A's and of B's tail outside the knot in the start shape ``x0``
    ((2 n_nodes, 3) [m]): walking in from the tail end, up to the first strand crossing
    it (a parallel neighbour, as the other rope's tail beside it, does not count)."""
    ropes = (np.arange(n_nodes), np.arange(n_nodes, 2 * n_nodes))
    return tuple(
        _first_inside(np.asarray(x0, float), r, o, d, crossing_only=True)
        for r, o in (ropes, ropes[::-1])
    )


def tail_free_lengths(x, n_nodes: int, d: float, tails: tuple[int, int]) -> np.ndarray:
    r"""Arc length [m] of A's and B's tails outside the knot.

    Walking in from the tail end (the rope's last node), the free length is the arc length
    to the first node inside the knot: within :data:`NEAR_SET` d of a strand crossing it (not
    parallel to it) that is the other rope, except its start tail, or its own rope away
    from it. A tail lying along the other rope's standing part or tail is still outside.

    Parameters
    ----------
    x : (2 n_nodes, 3) array [m]
        Rope A's nodes, then B's.
    n_nodes : int
        Nodes per rope.
    d : float [m]
    tails : (int, int)
        The start tails' node counts (:func:`tail_nodes`).

    Returns
    -------
    (2,) array [m]
    """
    x = np.asarray(x, float)
    ropes = (np.arange(n_nodes), np.arange(n_nodes, 2 * n_nodes))
    out = np.empty(2)
    for i, (rope, other) in enumerate((ropes, ropes[::-1])):
        k_other = tails[1 - i]
        others = other[: len(other) - k_other]
        k = _first_inside(x, rope, others, d, crossing_only=True, near=NEAR_SET)
        seg = np.linalg.norm(np.diff(x[rope][::-1][: k + 1], axis=0), axis=1)
        out[i] = float(seg.sum())
    return out


def frame_invariants(knot: TiedKnot, rope_a, rope_b) -> dict:
    """The invariants (:func:`knotmech.scenes.tied.measure`) of one frame of the two ropes."""
    return measure(replace(knot, ropes={"A": rope_a, "B": rope_b}))


def invariants_changed(start: dict, now: dict) -> list:
    """Keys whose value at ``now`` differs from ``start``; a value of None (a closure not
    defined because the free tails' ends interleave round the knot) is no change."""
    return [k for k, v in now.items() if v is not None and v != start.get(k)]


def rope_types(x, n_nodes: int) -> tuple:
    """Alexander polynomials of rope A and of rope B, each closed alone far outside (the
    closure of :func:`knotmech.scenes.tied.measure`'s ``alexander_A``, ``alexander_B``).

    Parameters
    ----------
    x : (2 n_nodes, 3) array [m]
        Rope A's nodes, then B's.
    n_nodes : int
        Nodes per rope.
    """
    x = np.asarray(x, float)
    return tuple(invariant(join_far([r])) for r in (x[:n_nodes], x[n_nodes:]))


def tails_drawn(x, x0, n_nodes: int) -> np.ndarray:
    """How far [m] A's and B's tail ends (their last nodes) moved towards the knot since
    ``x0``: the displacement against each tail's outward end direction at ``x0``
    (:func:`end_direction`); negative when a tail end moved out.

    Parameters
    ----------
    x, x0 : (2 n_nodes, 3) arrays [m]
        A frame and the reference frame (the pull's start).
    n_nodes : int

    Returns
    -------
    (2,) array [m]
    """
    x, x0 = np.asarray(x, float), np.asarray(x0, float)
    out = np.empty(2)
    for i, sl in enumerate((slice(0, n_nodes), slice(n_nodes, 2 * n_nodes))):
        u = end_direction(x0[sl], "end")
        out[i] = float((x0[sl][-1] - x[sl][-1]) @ u)
    return out

r"""Whether a mid-line loop is still tied: the linking of its halves cut at the eye, closed
from outside the knot.

A loop tied in the bight (the alpine butterfly, ABoK #1053) pulled end to end has no pin
and an unknot for its closed rope: neither the knot type nor a winding tells it from a
rope with a plain loop in it. What does is the linking number of the rope's two halves
cut at the eye's tip (1 for the butterfly: its tongue through the window; 0 for the
twisted bight with the tongue out, and for a straight rope), provided each half is closed
without passing through the knot. :func:`cut_linking` closes them so:

- the cut is a *material* point (the node ``k``, the eye's tip at the start): the halves
  are the nodes before ``k`` and after it (the tip node itself left out, so that the two
  closed curves never touch);
- each half leaves the eye along the ray from the knot's centre through its cut end, out
  to a sphere about that centre (radius 3 x the rope's extent for the first half, 2 x for
  the second), goes round that sphere to the direction of its rope end (the end's
  position run on along its outward end tangent), and comes straight back in to that end;
- the linking number is counted exactly, from the crossings of the two closed polygons
  seen along a fixed generic direction (half the sum of the crossings' signs), not by a
  Gauss integral (the two closures run side by side out of the eye: the integral's
  quadrature is not reliable there).

While the eye's tip is outside the knot nothing lies on its rays and the count is that of
the knot; once the eye has been drawn into the knot (a slip end to end) the rays pass
through strands and the number means nothing. A turn of the free eye about its own axis
(its two legs twisted round each other once) would change the count by one; the pulls
here have not shown one (docs/notes/knots-and-curves/tied-loops-pulled.md).
"""

from __future__ import annotations

import numpy as np

from knotmech.scenes.topology import knot_invariant

__all__ = ["cut_halves", "cut_knot_types", "cut_linking", "crossing_linking"]

#: the direction the closed halves are seen along when their crossings are counted
#: (generic: no segment of the closures along it)
VIEW = np.array([0.1234, -0.2345, 0.9641])


def _unit(v) -> np.ndarray:
    return np.asarray(v, float) / np.linalg.norm(v)


def _end_dir(p, end: str) -> np.ndarray:
    q = p if end == "start" else p[::-1]
    return _unit(q[0] - q[min(3, len(q) - 1)])


def _round(c, r: float, u0, u1, n: int = 64) -> np.ndarray:
    """Points on the sphere (centre ``c``, radius ``r``) from direction ``u0`` to ``u1``
    (not opposite): the normalised chord between them, ``n`` points."""
    t = np.linspace(0.0, 1.0, n)[:, None]
    w = (1 - t) * u0 + t * u1
    return c + r * w / np.linalg.norm(w, axis=1, keepdims=True)


def _closed(piece, c, r: float, out_dir, end_dir, *, eye_first: bool) -> np.ndarray | None:
    """``piece`` closed through the sphere of radius ``r``: from its eye end out radially,
    round to ``end_dir`` and back in to its rope end. ``eye_first``: the piece starts at
    the eye (else it ends there). None when the two directions are (nearly) opposite."""
    if float(out_dir @ end_dir) < -0.98:
        return None
    arc = _round(c, r, out_dir, end_dir)
    return np.vstack([piece, arc[::-1]]) if eye_first else np.vstack([piece, arc])


def crossing_linking(c1, c2, view=VIEW) -> int:
    """Linking number of two closed polygons ((n, 3), (m, 3); the last point joined to the
    first): half the sum of the signs of their crossings seen along ``view``."""
    v = _unit(view)
    e1 = _unit(np.cross(v, [1.0, 0.0, 0.0] if abs(v[0]) < 0.9 else [0.0, 1.0, 0.0]))
    e2 = np.cross(v, e1)
    a0, b0 = np.asarray(c1, float), np.asarray(c2, float)
    da, db = np.roll(a0, -1, axis=0) - a0, np.roll(b0, -1, axis=0) - b0
    p = np.stack([a0 @ e1, a0 @ e2], 1)
    q = np.stack([b0 @ e1, b0 @ e2], 1)
    dp = np.stack([da @ e1, da @ e2], 1)
    dq = np.stack([db @ e1, db @ e2], 1)
    # p + s dp = q + t dq, s and t in [0, 1)
    den = dp[:, None, 0] * dq[None, :, 1] - dp[:, None, 1] * dq[None, :, 0]
    w = q[None, :, :] - p[:, None, :]
    with np.errstate(divide="ignore", invalid="ignore"):
        s = (w[..., 0] * dq[None, :, 1] - w[..., 1] * dq[None, :, 0]) / den
        t = (w[..., 0] * dp[:, None, 1] - w[..., 1] * dp[:, None, 0]) / den
    i, j = np.nonzero((den != 0) & (s >= 0) & (s < 1) & (t >= 0) & (t < 1))
    ha = (a0[i] + s[i, j, None] * da[i]) @ v
    hb = (b0[j] + t[i, j, None] * db[j]) @ v
    sign = np.sign(den[i, j]) * np.where(ha > hb, 1.0, -1.0)
    return int(round(0.5 * float(sign.sum())))


def cut_halves(x, k: int, center=None) -> tuple | None:
    """The rope ``x`` ((n, 3), any unit) cut at node ``k`` (the eye's tip, left out of both
    halves), each half closed from outside the knot (module docstring): two closed
    polygons, or None when a half's closure is not defined (the eye pointing straight back
    along a rope end: its ray and its end's direction opposite). ``center`` (3,): the
    knot's centre (default the mean of the nodes)."""
    x = np.asarray(x, float)
    if not 0 < k < len(x) - 1:
        raise ValueError(f"the cut node must be inside the rope, got {k}")
    c = x.mean(axis=0) if center is None else np.asarray(center, float)
    ext = float(np.ptp(x, axis=0).max())
    a, b = x[:k], x[k + 1 :]
    far_l = _unit(x[0] + ext * _end_dir(x, "start") - c)
    far_r = _unit(x[-1] + ext * _end_dir(x, "end") - c)
    ca = _closed(a, c, 3.0 * ext, _unit(a[-1] - c), far_l, eye_first=False)
    cb = _closed(b, c, 2.0 * ext, _unit(b[0] - c), far_r, eye_first=True)
    if ca is None or cb is None:
        return None
    return ca, cb


def cut_linking(x, k: int, center=None) -> int | None:
    """Linking number of the rope ``x`` ((n, 3), any unit) cut at node ``k`` (the eye's
    tip), each half closed from outside the knot (:func:`cut_halves`).

    Parameters
    ----------
    x : (n, 3) array
        The rope, one end at node 0, the other at the last node.
    k : int
        The cut node (0 < k < n - 1); left out of both halves.
    center : (3,) array, optional
        The knot's centre (default the mean of the nodes); the rays from it through the
        two cut ends carry the closures out of the eye.

    Returns
    -------
    int, or None when a half's closure is not defined (the eye pointing straight back
    along a rope end: its ray and its end's direction opposite).
    """
    halves = cut_halves(x, k, center)
    return None if halves is None else crossing_linking(*halves)


def cut_knot_types(x, k: int, center=None) -> tuple | None:
    """Knot types (Alexander polynomials as coefficient tuples, ``(1,)`` the unknot) of the
    two halves of the rope ``x`` cut at node ``k`` and closed from outside the knot
    (:func:`cut_halves`), or None where those closures are not defined. The alpine
    butterfly's halves are overhand knots while its tongue is through the window, and
    unknots once it is out; unlike :func:`cut_linking`, they do not change when the free
    eye turns about its own axis (each half's type is its own)."""
    halves = cut_halves(x, k, center)
    if halves is None:
        return None
    return tuple(knot_invariant(h, closed=True).alexander for h in halves)

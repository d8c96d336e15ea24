r"""What the hitch centrelines share: smooth steps, the clove core, Hermite connectors, the
resampling of joined pieces, the closure and invariants of a rod round a post.

Coordinates: the post is the z axis (radius D/2), the rod centreline touches it at radius
:math:`R = (D+d)/2`. End 0 (node 0) is the *standing end* (the loaded one), the last node
the *working end* (free or lightly loaded).

Knot type (:func:`hitch_invariants`): the rod closed far away (each end extended along its
tail, the two far points joined at twice that distance without circling the post) has an
Alexander polynomial, and its winding number about the post axis is an integer (the
linking number of rod and post). Both are unchanged unless a strand passes through another
or through the post.
"""

from __future__ import annotations

import numpy as np

from knotmech.errors import InputError, check_positive, check_range
from knotmech.scenes.curves import min_separation, resample_polyline
from knotmech.scenes.topology import knot_invariant, winding_number

__all__ = ["PITCH", "TAIL", "EDGE", "hitch_closure", "hitch_invariants"]

PITCH = 1.15  #: axial distance [d] per turn of the strands that pass side by side


def _check_sizes(post_diameter, rod_diameter, rod_length, n_nodes, *, gap, lift, gap_min=1.0):
    """The sizes every hitch curve takes, checked: (D, d, L [m], n_nodes, gap, lift [d]);
    the gap within [gap_min, 50] d, the lift within [1, 10] d, at least 40 nodes."""
    D = float(check_positive("post_diameter", post_diameter, scalar=True))
    d = float(check_positive("rod_diameter", rod_diameter, scalar=True))
    L = float(check_positive("rod_length", rod_length, scalar=True))
    g = float(check_range("gap", gap, gap_min, 50.0, scalar=True))
    lf = float(check_range("lift", lift, 1.0, 10.0, scalar=True))
    N = int(n_nodes)
    if N < 40:
        raise InputError(f"n_nodes must be >= 40, got {n_nodes!r}")
    return D, d, L, N, g, lf


def _check_room(knotted, L, D, d, ends="leg") -> float:
    """The rod's length beyond the ``knotted`` part [m], refused in one line below 4 d for
    each of the two ``ends`` (legs or tails)."""
    rest = L - knotted
    if rest < 2 * 4 * d:
        raise InputError(
            f"rod_length must be at least {knotted + 8 * d:.3g} m for this hitch (post "
            f"{D:g} m, rod {d:g} m: the knotted part and 4 d of each {ends}), got {L:g}"
        )
    return rest


def _hermite(p0, t0, p1, t1, n):
    """Cubic Hermite curve from p0 (tangent t0) to p1 (tangent t1), n points."""
    s = np.linspace(0.0, 1.0, n)[:, None]
    h00 = 2 * s**3 - 3 * s**2 + 1
    h10 = s**3 - 2 * s**2 + s
    h01 = -2 * s**3 + 3 * s**2
    h11 = s**3 - s**2
    return h00 * p0 + h10 * t0 + h01 * p1 + h11 * t1


def _arc(p):
    return np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(p, axis=0), axis=1))])


def _line(p0, direction, length, ds):
    u = np.asarray(direction, float) / np.linalg.norm(direction)
    k = max(2, int(np.ceil(length / ds)) + 1)
    return p0 + np.linspace(0.0, length, k)[:, None] * u


def _finish(pieces, names, n_nodes, d, info):
    """Join dense pieces (each starting where the previous ended), resample to n_nodes
    equal edges, and map the piece boundaries to node ranges."""
    dense = [pieces[0]] + [p[1:] for p in pieces[1:]]
    lengths = [float(_arc(p)[-1]) for p in pieces]
    p = np.vstack(dense)
    L = float(_arc(p)[-1])
    nodes = resample_polyline(p, n_nodes)
    marks = np.rint(np.cumsum([0.0] + lengths) / L * (n_nodes - 1)).astype(int)
    parts = {nm: (int(marks[k]), int(marks[k + 1]) + (k == len(names) - 1))
             for k, nm in enumerate(names)}  # fmt: skip
    info = {**info, "rod_length": L, "min_separation": min_separation(nodes, rod_radius=0.5 * d)}
    return nodes, parts, info


TAIL = 0.064  #: [m] default extra tail length (the clove-hitch paper's rod: 64 mm tails)
EDGE = 0.374 / 119  #: [m] default edge length (the clove-hitch scene's 120 nodes on 374 mm)


def hitch_closure(nodes, *, reach: float | None = None) -> np.ndarray:
    """The rod closed far away: each end extended away from the rod's centroid (along
    end - centroid, so that a tail that swings keeps pointing out) to ``reach`` (default
    3 x the rod's extent), and the two far points joined through a point a further
    ``reach`` out from the post axis in the direction of their mean, so the closing path
    does not circle the post. (n + 3, 3) [m]."""
    x = np.asarray(nodes, dtype=float)
    R = 3.0 * float(np.ptp(x, axis=0).max()) if reach is None else float(reach)
    c = x.mean(axis=0)
    u0 = x[0] - c
    u0 /= np.linalg.norm(u0)
    u1 = x[-1] - c
    u1 /= np.linalg.norm(u1)
    f0 = x[0] + R * u0
    f1 = x[-1] + R * u1
    mid = 0.5 * (f0 + f1)
    radial = np.array([mid[0], mid[1], 0.0])
    nr = np.linalg.norm(radial)
    via = mid + (R * radial / nr if nr > 1e-9 * R else 0.0)
    return np.vstack([x, f1, via, f0])


def hitch_invariants(nodes) -> tuple[tuple[int, ...], int]:
    """(Alexander polynomial of :func:`hitch_closure`, its winding number about the post
    axis rounded: the rod-post linking number); unchanged unless a strand passes through
    another or through the post."""
    c = hitch_closure(nodes)
    inv = knot_invariant(c, closed=True)
    w = winding_number(np.vstack([c, c[:1]]))
    return inv.alexander, int(round(w))

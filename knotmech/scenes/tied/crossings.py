r"""The average crossing number of a rope: how much of it is still a knot, seen from
everywhere.

The average crossing number (ACN) of a curve is the number of crossings of its
projections averaged over all directions of view (Freedman, He and Wang, *Annals of
Mathematics* 139, 1 (1994), sec. 1: the integral below):

.. math::

    \mathrm{ACN} = \frac{1}{4\pi}\int\!\!\int
        \frac{|(\mathbf t_1 \times \mathbf t_2)\cdot(\mathbf r_1 - \mathbf r_2)|}
             {|\mathbf r_1 - \mathbf r_2|^3}\, ds_1\, ds_2 ,

evaluated here by the midpoint rule over the polyline's edges (neighbouring edges left
out). It is not a topological invariant: it tells a tied knot from the same rope with its
knot pulled apart where no invariant does. The alpine butterfly pulled end to end (no
pin) or with its eye round a pin is, as a tangle, the same as an eye whose two legs are
twisted once round each other (the tongue drawn back out of the window with the eye
turned once): the closed rope's knot type, the winding about the pin and the linking of
the halves cut at the eye are the same for both. Their average crossing numbers are not:
20-22 for the drawn-in butterfly, about 2 for the twisted eye a false one falls into
(docs/notes/knots-and-curves/tied-loops-pulled.md).
"""

from __future__ import annotations

import numpy as np

__all__ = ["average_crossings"]


def average_crossings(x) -> float:
    """Average crossing number of the open polyline ``x`` ((n, 3), any unit; module
    docstring): 0 for a straight rope, about the crossings of a compact knot's diagram."""
    x = np.asarray(x, float)
    t = np.diff(x, axis=0)
    m = 0.5 * (x[1:] + x[:-1])
    n = len(m)
    tot = 0.0
    for k in range(0, n, 400):
        r = m[k : k + 400, None, :] - m[None, :, :]
        num = np.abs(np.einsum("ijk,ijk->ij", np.cross(t[k : k + 400, None, :], t[None]), r))
        dist = np.linalg.norm(r, axis=2)
        far = np.abs(np.arange(k, min(k + 400, n))[:, None] - np.arange(n)[None, :]) > 1
        tot += float((num[far] / dist[far] ** 3).sum())
    return tot / (4 * np.pi)

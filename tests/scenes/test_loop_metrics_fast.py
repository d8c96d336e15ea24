"""loop_metrics finds contacting edges through a k-d tree of edge midpoints (issue 11:
the overhand scene's post-processing); the set must be the dense distance matrix's."""

import numpy as np
import pytest

from knotmech.scenes.curves import _close_edges, _edge_distances, loop_metrics, overhand_knot
from knotmech.scenes.overhand import imc_setup


def _dense_close(x, k, threshold):
    dist = _edge_distances(x)
    idx = np.arange(len(x) - 1)
    dist[np.abs(idx[:, None] - idx[None, :]) < k] = np.inf
    return np.nonzero(dist.min(axis=1) < threshold)[0]


@pytest.mark.parametrize("turns", [1, 2, 3])
def test_close_edges_equal_the_dense_matrix(turns):
    s = imc_setup(turns)
    c = overhand_knot(turns, rod_length=s.rod_length, rod_radius=s.rod_radius,
                      end_to_end_length=s.end_to_end_length, braid_length=s.braid_length,
                      n_nodes=301)  # fmt: skip
    rng = np.random.default_rng(turns)
    h = s.rod_radius
    for scale in (1.0, 0.7, 0.5):  # squeezed towards the centre: more strands in contact
        x = c.nodes * scale + rng.normal(scale=0.2 * h, size=c.nodes.shape)
        for factor in (1.0, 1.3, 3.0, 10.0):
            got = _close_edges(x, 5, factor * 2 * h)
            ref = _dense_close(x, 5, factor * 2 * h)
            np.testing.assert_array_equal(got, ref)
    m = loop_metrics(c.nodes, rod_radius=h)
    assert np.isfinite(m["loop_diameter"]) and m["loop"][1] > m["loop"][0]


def test_close_edges_of_far_apart_and_degenerate_polylines():
    x = np.stack([np.linspace(0, 1, 11), np.zeros(11), np.zeros(11)], 1)
    assert _close_edges(x, 3, 0.05).size == 0  # a straight rod touches nothing
    hairpin = np.concatenate([x, x[::-1] + [0, 0.01, 0]])
    got = _close_edges(hairpin, 3, 0.02)
    np.testing.assert_array_equal(got, _dense_close(hairpin, 3, 0.02))
    assert got.size > 10
    assert _close_edges(x[:1], 3, 0.05).size == 0

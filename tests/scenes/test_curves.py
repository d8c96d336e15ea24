"""Knot-curve generators: lengths, clearances, knot types, cross-check with IMC start shapes."""

import numpy as np
import pytest

from knotmech.errors import InputError
from knotmech.scenes.curves import (
    OVERHAND_COATED_TABLE1,
    clove_hitch_curve,
    coil_curve,
    end_to_end,
    loop_metrics,
    min_separation,
    overhand_coated,
    overhand_imc,
    overhand_knot,
)
from knotmech.scenes.topology import knot_invariant, post_crossing_code, winding_number

TORUS_NAMES = {1: "3_1", 2: "5_1", 3: "7_1", 4: "9_1"}


@pytest.mark.parametrize("turns", [1, 2, 3, 4])
def test_overhand_imc_geometry(turns):
    """Choi, Tong & Jawed 2021: L = 1 m, 301 nodes, h = 1.6 mm, E = 0.280 / 0.330 m."""
    c = overhand_imc(turns)
    x = c.nodes
    assert x.shape == (301, 3)
    edges = np.linalg.norm(np.diff(x, axis=0), axis=1)
    assert edges.sum() == pytest.approx(1.0, rel=1e-8)
    assert edges.std() / edges.mean() < 1e-4
    assert end_to_end(x) == pytest.approx(0.280 if turns == 1 else 0.330, rel=1e-9)
    sep = min_separation(x, rod_radius=1.6e-3)
    assert 2 * 1.6e-3 <= sep <= 2.4 * 1.6e-3
    # overhand with n turns closes to the (2, 2n+1) torus knot
    assert knot_invariant(x).name == TORUS_NAMES[turns]
    # the parts tile the rod and the tails lie on the pull axis
    p = c.parts
    assert p["tail1"][0] == 0 and p["tail2"][1] == 301
    half = p["tail1"][1] // 2
    assert np.allclose(x[:half, 1:], 0.0, atol=1e-9)
    assert np.allclose(x[-half:, 1:], 0.0, atol=1e-9)


@pytest.mark.parametrize("turns", [1, 2, 3, 4])
def test_overhand_coated_table1(turns):
    """Coated-rod paper, table 1 (t, b, l, end-to-end) and total length 300/600 mm."""
    t, b, lo, e2e = OVERHAND_COATED_TABLE1[turns]
    c = overhand_coated(turns)
    assert c.rod_length == pytest.approx(0.300 if turns <= 2 else 0.600, rel=1e-8)
    assert end_to_end(c.nodes) == pytest.approx(e2e, rel=1e-9)
    assert c.rod_radius == pytest.approx(0.795e-3)
    # tails and loop take up the helix's axial shortening: within 2.5 mm and 5 mm
    assert abs(c.info["tail_length"] - t) < 2.5e-3
    assert abs(c.info["loop_length"] - lo) < 5e-3
    assert min_separation(c.nodes, rod_radius=c.rod_radius) >= 2 * c.rod_radius
    assert knot_invariant(c.nodes).name == TORUS_NAMES[turns]


@pytest.mark.parametrize("turns", [1, 2, 3, 4])
def test_against_imc_start_shapes(shared_reference, turns):
    """Compare with knot_configurations/n1..n4 of the imc-der code (reference only)."""
    ref = np.loadtxt(shared_reference / "imc-der-knots" / f"n{turns}.txt")[:, :3]
    ours = overhand_imc(turns).nodes
    h = 1.6e-3
    assert end_to_end(ours) == pytest.approx(end_to_end(ref), abs=2e-4)
    s_ref = min_separation(ref, rod_radius=h)
    s_ours = min_separation(ours, rod_radius=h)
    assert s_ref / (2 * h) == pytest.approx(s_ours / (2 * h), abs=0.15)
    assert knot_invariant(ref).name == knot_invariant(ours).name == TORUS_NAMES[turns]
    m_ref, m_ours = loop_metrics(ref, rod_radius=h), loop_metrics(ours, rod_radius=h)
    assert m_ours["loop_length"] == pytest.approx(m_ref["loop_length"], rel=0.15)
    assert m_ours["loop_diameter"] == pytest.approx(m_ref["loop_diameter"], rel=0.20)
    assert m_ours["braid_length"] == pytest.approx(m_ref["braid_length"], rel=0.08)


@pytest.mark.parametrize("turns, n_nodes", [(1, 101), (2, 101), (3, 151)])
def test_coarse_mesh_edges_clear(turns, n_nodes):
    """Chords of a coarse helix cut inside it: the generator widens the helix so that
    non-adjacent edges stay a rod diameter apart (edge-edge distance)."""
    from knotmech.scenes.curves import _edge_distances

    c = overhand_coated(turns, n_nodes=n_nodes)
    idx = np.arange(n_nodes - 1)
    far = np.abs(idx[:, None] - idx[None, :]) >= 3
    assert _edge_distances(c.nodes)[far].min() >= 2 * c.rod_radius
    assert c.info["helix_radius"] > 1.05 * c.rod_radius
    assert knot_invariant(c.nodes).name == TORUS_NAMES[turns]


def test_overhand_node_count_and_clearance():
    c = overhand_knot(
        2,
        rod_length=0.5,
        rod_radius=1e-3,
        end_to_end_length=0.15,
        braid_length=0.08,
        n_nodes=401,
        clearance=0.2,
    )
    assert len(c.nodes) == 401
    assert min_separation(c.nodes, rod_radius=1e-3) >= 2.2e-3 * 0.99
    assert c.info["helix_radius"] == pytest.approx(1.2e-3)


@pytest.mark.parametrize(
    "kwargs",
    [
        {"turns": 0},
        {"turns": 1.5},
        {"braid_length": 0.005},  # shorter than (2n+1) pi h
        {"end_to_end_length": 0.03},  # tails would be negative
        {"rod_length": 0.2},  # loop too short
        {"n_nodes": 10},
        {"rod_radius": -1.0},
        {"clearance": float("nan")},
        {"n_nodes": 60},  # too coarse: strands closer than 2h
    ],
)
def test_overhand_bad_input(kwargs):
    args = dict(
        turns=1,
        rod_length=1.0,
        rod_radius=1.6e-3,
        end_to_end_length=0.28,
        braid_length=0.118,
        n_nodes=301,
    )
    args.update(kwargs)
    turns = args.pop("turns")
    with pytest.raises(InputError):
        overhand_knot(turns, **args)


def test_clove_hitch_curve():
    """Clove-hitch paper geometry (d, D) = (4, 30) mm: two wraps, diagonal over both ends."""
    d, D = 4e-3, 30e-3
    c = clove_hitch_curve(post_diameter=D, rod_diameter=d, tail_length=0.08, n_nodes=240)
    x = c.nodes
    rho = np.hypot(x[:, 0], x[:, 1])
    R = 0.5 * (D + d)
    assert rho.min() == pytest.approx(R, abs=1e-3 * d)  # touches the post, never inside
    assert min_separation(x, rod_radius=0.5 * d) >= d
    assert post_crossing_code(x) == "UOOU"
    w = winding_number(x)
    assert 2.0 < w < 2.6  # two wraps plus the tails' sweep
    # the wraps sit on the post
    i0, i1 = c.parts["wrap1"]
    assert np.allclose(rho[i0 + 5 : i1 - 12], R, atol=1e-3 * d)
    # the two ends leave in opposite directions
    t0 = x[1] - x[0]
    t1 = x[-1] - x[-2]
    assert np.dot(t0, t1) / np.linalg.norm(t0) / np.linalg.norm(t1) > 0.95


def test_clove_hitch_any_axis():
    axis = np.array([1.0, 2.0, -0.5])
    center = np.array([0.1, -0.2, 0.3])
    c = clove_hitch_curve(
        post_diameter=0.025,
        rod_diameter=0.008,
        tail_length=0.05,
        n_nodes=200,
        post_axis=axis,
        post_center=center,
    )
    assert post_crossing_code(c.nodes, axis_point=center, axis_direction=axis) == "UOOU"


def test_coil_curve():
    """Two loops (4 pi) of the clove-hitch paper: no self-crossing, winding 2 on the wraps."""
    d, D = 4e-3, 30e-3
    c = coil_curve(post_diameter=D, rod_diameter=d, tail_length=0.05, n_nodes=200)
    i0, i1 = c.parts["wrap"]
    assert winding_number(c.nodes[i0:i1]) == pytest.approx(2.0, abs=0.03)
    assert post_crossing_code(c.nodes) == ""
    assert min_separation(c.nodes, rod_radius=0.5 * d) >= d
    with pytest.raises(InputError):
        coil_curve(post_diameter=-1, rod_diameter=d, tail_length=0.05, n_nodes=200)

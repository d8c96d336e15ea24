"""Kernels of the speed work (issue 24): same results as the code they replace."""

import numpy as np

from knotmech import rod
from knotmech.rod._kernels import frames as fr
from knotmech.rod._kernels.contact_broadphase import sort_pairs
from knotmech.rod._kernels.elastic_eval import elastic_frames, elastic_frames_cs
from knotmech.rod._kernels.envelope import env_factor, env_last, env_solve, pattern_first


def test_sort_pairs_is_the_lexsort_order():
    rng = np.random.default_rng(3)
    for _ in range(50):
        n = int(rng.integers(2, 300))
        i = rng.integers(0, 200, n)
        pairs = np.unique(np.c_[i, i + 1 + rng.integers(0, 40, n)], axis=0)
        rng.shuffle(pairs)
        want = pairs[np.lexsort((pairs[:, 1], pairs[:, 0]))]
        np.testing.assert_array_equal(sort_pairs(pairs, 250), want)


def test_elastic_frames_is_the_four_frame_kernels_bit_for_bit():
    r = rod.Rod.straight(length=0.1, n_nodes=12, radius=1e-3, youngs_modulus=1e6, density=1e3)
    s = rod.RodSystem([r])
    st = s.initial_state()
    rng = np.random.default_rng(5)
    q = st.q + 1e-3 * rng.standard_normal(st.q.size)
    ne, ns = s.n_edges, s.n_stencils
    a = [np.empty((ne, 3)), np.empty(ne), np.empty((ne, 3)), np.empty((ne, 3)), np.empty(ns),
         np.empty((ne, 3)), np.empty((ne, 3))]  # fmt: skip
    b = [x.copy() for x in a]
    t, ln, d1, d2, rt, m1, m2 = a
    fr.edge_tangents(q, s.edge_dof0, t, ln)
    fr.transport_frames(st.tangents, st.d1, t, d1, d2)
    fr.reference_twist(s.stencil_edge, t, d1, st.ref_twist, rt)
    fr.material_frames(q, s.edge_dof0, d1, d2, m1, m2)
    elastic_frames(q, s.edge_dof0, s.stencil_edge, st.tangents, st.d1, st.ref_twist, *b)
    for x, y in zip(a, b, strict=True):
        assert np.array_equal(x, y)
    assert np.max(np.abs(rt)) > 0.0  # the perturbation twisted the frames


def test_elastic_frames_with_the_step_cosines_is_elastic_frames_bit_for_bit():
    """The cosines and sines of the step start's reference twist computed once per step
    (:func:`cos_sin`) give the frames of :func:`elastic_frames`, bit for bit."""
    r = rod.Rod.straight(length=0.1, n_nodes=30, radius=1e-3, youngs_modulus=1e6, density=1e3)
    s = rod.RodSystem([r])
    st = s.initial_state()
    rng = np.random.default_rng(7)
    q = st.q + 1e-3 * rng.standard_normal(st.q.size)
    rt_old = 2.0 * rng.standard_normal(s.n_stencils)  # beyond +-pi too
    ne, ns = s.n_edges, s.n_stencils
    a = [np.empty((ne, 3)), np.empty(ne), np.empty((ne, 3)), np.empty((ne, 3)), np.empty(ns),
         np.empty((ne, 3)), np.empty((ne, 3))]  # fmt: skip
    b = [x.copy() for x in a]
    elastic_frames(q, s.edge_dof0, s.stencil_edge, st.tangents, st.d1, rt_old, *a)
    c, sn = np.empty(ns), np.empty(ns)
    fr.cos_sin(rt_old, c, sn)
    elastic_frames_cs(q, s.edge_dof0, s.stencil_edge, st.tangents, st.d1, rt_old, c, sn, *b)
    for x, y in zip(a, b, strict=True):
        assert np.array_equal(x, y)
    assert np.max(np.abs(a[4] - rt_old)) > 1e-6  # the perturbation moved the twist


def test_envelope_lu_solves_a_band_system():
    """A diagonally dominant band matrix with a sparse envelope: x to 1e-12 of numpy's."""
    n, kd = 60, 7
    rng = np.random.default_rng(11)
    a = np.zeros((n, n))
    for i in range(n):
        for j in range(max(0, i - kd), min(n, i + kd + 1)):
            if i == j or rng.random() < 0.3:
                a[i, j] = a[j, i] = rng.standard_normal()
        a[i, i] = 10.0 + abs(a[i, i])
    ab = np.zeros((2 * kd + 1, n), order="F")
    rows, cols = np.nonzero(a)
    ab[kd + rows - cols, cols] = a[rows, cols]
    first = np.arange(n, dtype=np.int64)
    pattern_first(rows.astype(np.int64), cols.astype(np.int64), first)
    last = np.empty(n, dtype=np.int64)
    env_last(first, last)
    orig = ab.copy(order="F")
    assert env_factor(ab, kd, last, orig, 1e-13, np.empty(2 * kd + 2)) == 0
    b = rng.standard_normal(n)
    x = b.copy()
    env_solve(ab, kd, first, last, x)
    want = np.linalg.solve(a, b)
    assert np.max(np.abs(x - want)) <= 1e-12 * np.max(np.abs(want))


def test_pattern_csr_is_scipys_canonical_structure_of_a_plus_a_transpose():
    """pattern_csr gives the indptr and indices of scipy's canonical CSR A + A.T (A: the
    mapped entries of two lists, constrained dofs mapped to -1 dropped), so RCM of it in
    symmetric mode is the RCM of A the solver used before, permutation for permutation."""
    import scipy.sparse as sp
    from scipy.sparse.csgraph import reverse_cuthill_mckee

    from knotmech.rod._kernels.assembly import pattern_csr

    rng = np.random.default_rng(13)
    for _ in range(20):
        n_dof = int(rng.integers(5, 80))
        fmap = -np.ones(n_dof, dtype=np.int64)
        free = np.flatnonzero(rng.random(n_dof) < 0.8)
        fmap[free] = rng.permutation(free.size)
        lists = [rng.integers(0, n_dof, (2, int(rng.integers(0, 300)))) for _ in range(2)]
        indptr, ind = pattern_csr(lists[0][0], lists[0][1], lists[1][0], lists[1][1], fmap,
                                  free.size)  # fmt: skip
        rows = fmap[np.concatenate([lists[0][0], lists[1][0]])]
        cols = fmap[np.concatenate([lists[0][1], lists[1][1]])]
        keep = (rows >= 0) & (cols >= 0)
        a = sp.csr_matrix((np.ones(int(keep.sum())), (rows[keep], cols[keep])),
                          shape=(free.size, free.size))  # fmt: skip
        want = a + a.T
        np.testing.assert_array_equal(indptr, want.indptr)
        np.testing.assert_array_equal(ind, want.indices)
        pat = sp.csr_matrix((np.ones(ind.size), ind, indptr), shape=a.shape)
        np.testing.assert_array_equal(
            reverse_cuthill_mckee(pat, symmetric_mode=True),
            reverse_cuthill_mckee(a, symmetric_mode=False),
        )

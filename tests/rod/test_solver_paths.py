"""The fast paths of the contact Newton solver agree with the plain ones.

Envelope LU (no pivoting) against a dense solve and against the pivoted/SuperLU paths,
pruning of distant contact pairs, the second-order predictor, Jacobian reuse (chord
iterations) and the tunnelling-guard kernel (issue #4, overhand benchmark speed); the
continuity of near-parallel contact forces and the stall guards (issue 11).
"""

import numpy as np
import pytest

from knotmech import rod
from knotmech.errors import InputError, SolverError
from knotmech.rod import contact as contact_mod
from knotmech.rod import solver as solver_mod
from knotmech.rod._kernels import envelope as env
from knotmech.rod._kernels.contact_rodrod import (
    edge_distance_hessian,
    max_pair_displacement,
    segment_params,
)
from knotmech.rod.constraints import Clamp, MovingNodes
from knotmech.rod.contact import RodContact
from knotmech.rod.friction import SmoothFriction
from knotmech.rod.jacobian import Triplets

R = 1e-3


def _random_envelope_matrix(n, kd, rng):
    """Structurally symmetric band matrix with a ragged envelope, unsymmetric values,
    diagonally dominant; returns (dense A, band storage (2 kd + 1, n), first)."""
    width = rng.integers(0, kd + 1, n)
    a = np.zeros((n, n))
    for i in range(n):
        j0 = max(0, i - width[i])
        for j in range(j0, i):
            if rng.random() < 0.6:
                a[i, j] = rng.normal()
                a[j, i] = rng.normal()
    a += np.diag(np.abs(a).sum(axis=1) + 1.0)
    ab = np.zeros((2 * kd + 1, n), order="F")
    for j in range(n):
        for i in range(max(0, j - kd), min(n, j + kd + 1)):
            ab[kd + i - j, j] = a[i, j]
    rows, cols = np.nonzero(a)
    first = np.arange(n, dtype=np.int64)
    env.pattern_first(rows.astype(np.int64), cols.astype(np.int64), first)
    return a, ab, first


def test_envelope_lu_solves_like_a_dense_solver_with_less_work():
    rng = np.random.default_rng(3)
    n, kd = 300, 25
    a, ab, first = _random_envelope_matrix(n, kd, rng)
    orig = ab.copy(order="F")
    last = np.empty(n, dtype=np.int64)
    env.env_last(first, last)
    # a ragged envelope: the LU does far fewer multiply-adds than the full band's n kd^2
    assert env.env_work(last) < 0.6 * n * kd * kd
    anorm = env.copy_band(ab, np.empty_like(ab, order="F"))
    assert anorm == pytest.approx(np.abs(a).sum(axis=0).max(), rel=1e-14)
    assert env.env_factor(ab, kd, last, orig, 1e-13, np.empty(kd + 1)) == 0
    b = rng.normal(size=n)
    x = b.copy()
    env.env_solve(ab, kd, first, last, x)
    x_ref = np.linalg.solve(a, b)
    assert np.max(np.abs(x - x_ref)) <= 1e-12 * np.max(np.abs(x_ref))
    assert env.band_residual(orig, kd, x, b, anorm, np.empty(n)) < 1e-15
    # a wrong solution has a large backward error
    assert env.band_residual(orig, kd, x + 1e-3, b, anorm, np.empty(n)) > 1e-6


def test_envelope_lu_reports_a_vanishing_pivot():
    """[[0, 1], [1, 0]] needs pivoting: the envelope LU must give up, not divide by 0."""
    kd = 1
    ab = np.zeros((3, 2), order="F")
    ab[kd + 1, 0] = 1.0  # A[1, 0]
    ab[kd - 1, 1] = 1.0  # A[0, 1]
    last = np.array([1, 1], dtype=np.int64)
    assert env.env_factor(ab, kd, last, ab.copy(order="F"), 1e-13, np.empty(2)) == 1


def test_triplets_reserve_and_commit():
    t = Triplets(capacity=4)
    t.add([0], [1], [2.0])
    r, c, v = t.reserve(10)  # grows the buffer, keeps the first entry
    r[:2], c[:2], v[:2] = [3, 4], [5, 6], [7.0, 8.0]
    t.commit(2)
    assert list(t.rows) == [0, 3, 4] and list(t.cols) == [1, 5, 6]
    assert list(t.vals) == [2.0, 7.0, 8.0]
    with pytest.raises(InputError):
        t.commit(10**6)


def _crossing(push=4e-3, t_end=0.2, dt=0.01, options=None, friction=0.3):
    """Two crossing rods (41 nodes each), the upper one pushed down on the lower one."""
    n = 41
    s = np.linspace(-0.05, 0.05, n)
    a = np.stack([s, 0 * s, 0 * s], 1)
    b = np.stack([0 * s + 0.0013, s, 0 * s + 2.5 * R], 1)
    rods = [rod.Rod(positions=p, radius=R, youngs_modulus=1e6, density=1000.0) for p in (a, b)]
    system = rod.RodSystem(rods)
    cons = (
        Clamp(nodes=[0, n - 1], edges=[0, n - 2]),
        MovingNodes(nodes=[n, 2 * n - 1], velocity=(0.01, 0.0, -push / t_end)),
        Clamp(edges=[n - 1, 2 * n - 3]),
    )
    contact = RodContact(
        stiffness=200.0,
        sharpness=1.0 / (0.02 * R),
        friction=SmoothFriction(friction) if friction else None,
    )
    return rod.simulate(
        system,
        t_end=t_end,
        dt=dt,
        constraints=cons,
        interactions=[contact],
        options=options or rod.SolverOptions(),
    )


def test_linear_solver_paths_and_jacobian_reuse_agree(monkeypatch):
    """The envelope LU, the pivoted band LU (forced fallback) and SuperLU (forced by a
    zero band limit) give the same trajectory; chord iterations (forced on this small
    band) converge to it within the Newton tolerance."""
    plain = rod.SolverOptions(jacobian_reuse=0.0, jacobian_reuse_steps=0.0)
    ref = _crossing(options=plain)
    assert ref.status == "success"
    extent = np.abs(ref.positions).max()

    with monkeypatch.context() as m:
        m.setattr(solver_mod._env, "env_factor", lambda *args: 1)  # every pivot "too small"
        pivoted = _crossing(options=plain)
    with monkeypatch.context() as m:
        m.setattr(solver_mod, "_KD_MAX", 0)
        superlu = _crossing(options=plain)
    for res in (pivoted, superlu):
        assert res.stats["newton_iterations"] == ref.stats["newton_iterations"]
        assert np.max(np.abs(res.positions - ref.positions)) < 1e-12 * extent

    with monkeypatch.context() as m:
        m.setattr(solver_mod, "_KD_REUSE", 0)
        chord = _crossing()
        # evaluations that may be followed by a chord step skip the Hessians (redone when
        # a fresh Jacobian is needed): the same iterates as evaluating them every time
        m.setattr(solver_mod.Stepper, "_hessian_may_wait", lambda self: False)
        eager = _crossing()
    assert chord.stats["newton_iterations"] != ref.stats["newton_iterations"]  # it acted
    assert np.max(np.abs(chord.positions - ref.positions)) < 1e-6 * extent
    assert eager.stats["newton_iterations"] == chord.stats["newton_iterations"]
    assert np.max(np.abs(eager.positions - chord.positions)) <= 1e-14 * extent


def test_pruned_contact_pairs_give_the_unpruned_force_and_jacobian(monkeypatch):
    """Pairs beyond k(2h - Delta) = -20 are skipped and beyond -10 get no Jacobian block:
    the force is unchanged to round-off, the Jacobian to below 1e-8 of its largest entry."""
    n = 41
    s = np.linspace(-0.05, 0.05, n)
    a = np.stack([s, 0 * s, 0 * s], 1)
    # a slightly tilted rod above the first: pairs from overlapping (z = 5) to far apart,
    # z falling by 2.5 per node
    b = np.stack([s, 0 * s + 1e-4, 1.9 * R + 0.02 * (s - s[0])], 1)
    system = rod.RodSystem(
        [rod.Rod(positions=p, radius=R, youngs_modulus=1e6, density=1000.0) for p in (a, b)]
    )
    q = system.initial_state().q
    q_old = q.copy()
    q_old[system.node_dofs[n:, 0]] -= 2e-6  # the upper rod slides: friction acts

    def run(z_cut, z_jac, mu=0.3):
        monkeypatch.setattr(contact_mod, "Z_CUTOFF", z_cut)
        monkeypatch.setattr(contact_mod, "Z_JACOBIAN", z_jac)
        c = RodContact(stiffness=200.0, sharpness=1.0 / (0.02 * R), margin=3e-3,
                       friction=SmoothFriction(mu) if mu else None)  # fmt: skip
        c.begin_step(system, q_old, np.zeros_like(q), 0.01)
        f, t = np.zeros(system.n_dof), Triplets()
        c.assemble(system, q, q_old, 0.01, f, t)
        jac = np.zeros((system.n_dof, system.n_dof))
        np.add.at(jac, (t.rows, t.cols), t.vals)
        return c, f, jac

    c_all, f_all, j_all = run(-1e300, -1e300)
    c_fast, f_fast, j_fast = run(-20.0, -10.0)
    z = c_fast.sharpness * (2 * R - np.array([_pair_distance(system, q, p) for p in c_fast.pairs]))
    assert np.sum(z < -20) > 10 and np.sum(z > 0) > 0
    assert np.sum((z >= -20) & (z < -10)) > 2 and np.sum((z >= -10) & (z < 0)) > 2
    assert np.max(np.abs(f_fast - f_all)) <= 1e-14 * np.max(np.abs(f_all))
    assert np.max(np.abs(j_fast - j_all)) <= 1e-8 * np.max(np.abs(j_all))
    # the penalty Hessian alone (the stuck-friction block dwarfs it above)
    _, _, j_all = run(-1e300, -1e300, mu=0.0)
    _, _, j_fast = run(-20.0, -10.0, mu=0.0)
    assert np.max(np.abs(j_fast - j_all)) <= 1e-8 * np.max(np.abs(j_all))
    assert c_fast.energy(system, q) == pytest.approx(c_all.energy(system, q), rel=1e-14)


def _pair_distance(system, q, pair):
    from knotmech.rod._kernels.contact_rodrod import edge_distance

    en = system.edge_nodes
    x = q[system.node_dofs[[en[pair[0], 0], en[pair[0], 1], en[pair[1], 0], en[pair[1], 1]]]]
    return edge_distance(np.ascontiguousarray(x.ravel()))


def test_tunnelling_guard_kernel_matches_its_definition():
    rng = np.random.default_rng(0)
    n_nodes = 30
    node_dofs = np.arange(3 * n_nodes, dtype=np.int64).reshape(n_nodes, 3)
    edge_nodes = np.stack([np.arange(n_nodes - 1), np.arange(1, n_nodes)], 1).astype(np.int64)
    rad = rng.uniform(0.5e-3, 2e-3, n_nodes - 1)
    pairs = np.array([[0, 5], [3, 20], [7, 9]], dtype=np.int64)
    q_old = rng.normal(size=3 * n_nodes)
    q_new = q_old + rng.normal(scale=1e-3, size=3 * n_nodes)
    ref = max(
        np.linalg.norm(q_new[node_dofs[v]] - q_old[node_dofs[v]]) / rad[e]
        for e in np.unique(pairs)
        for v in edge_nodes[e]
    )
    got = max_pair_displacement(pairs, edge_nodes, node_dofs, rad, q_new, q_old)
    assert got == pytest.approx(ref, rel=1e-14)


def test_second_order_predictor_is_exact_in_free_fall():
    """Under gravity alone a free straight rod falls rigidly: implicit Euler gives
    v_{n+1} = v_n + g dt, which the second-order predictor extrapolates exactly, so from the
    third step on Newton has nothing left to do; the constant-velocity guess needs an
    iteration every step."""
    r = rod.Rod.straight(length=0.1, n_nodes=11, radius=1e-3, youngs_modulus=1e6,
                         density=1000.0)  # fmt: skip
    system = rod.RodSystem([r])
    kw = dict(t_end=0.01, dt=1e-3, loads=rod.Gravity())
    quad = rod.simulate(system, **kw, options=rod.SolverOptions(predictor="quadratic"))
    lin = rod.simulate(system, **kw, options=rod.SolverOptions(predictor="linear"))
    assert quad.stats["steps"] == lin.stats["steps"] == 10
    assert quad.stats["newton_iterations"] <= 2
    assert lin.stats["newton_iterations"] >= 10
    # same trajectory: z(t) of implicit Euler, -g dt^2 n(n+1)/2
    z_exact = -9.81 * 1e-6 * 10 * 11 / 2
    for res in (quad, lin):
        assert res.positions[-1][:, 2] == pytest.approx(z_exact, rel=1e-9)


@pytest.mark.parametrize(
    "kw",
    [
        {"predictor": "cubic"},
        {"jacobian_reuse": -0.1},
        {"jacobian_reuse": 1.5},
        {"jacobian_reuse_steps": 2.0},
    ],
)
def test_solver_option_errors(kw):
    with pytest.raises(InputError):
        rod.SolverOptions(**kw)


# --- issue 11: the crawl's cause (near-parallel edge pairs) and the stall guards -----------


def _gap_gradient(theta):
    """Gradient of the edge-edge distance for edge i = (0,0,0)-(1,0,0) and an edge j of
    the same length 0.2 above it, shifted by 0.3 along x and turned by ``theta`` about z
    (about its middle): the configuration of two strands lying side by side in a nip."""
    c, s = np.cos(theta), np.sin(theta)
    mid = np.array([0.8, 0.0, 0.2])
    half = 0.5 * np.array([c, s, 0.0])
    x = np.concatenate([[0, 0, 0], [1, 0, 0], mid - half, mid + half])
    g = np.empty(12)
    d = edge_distance_hessian(x, g, np.empty((12, 12)))
    return d, g


@pytest.mark.parametrize("theta0", [1e-5, 1e-7, 0.0])
def test_near_parallel_edge_forces_are_continuous(theta0):
    """The nodal distribution of the contact force (the gradient of Delta) is continuous
    when a pair of overlapping edges turns through parallel. Here the projections cross at
    s = 0.8 on edge i for any theta != 0; the former rule (s = 0, then clamping, once
    sin^2 theta <= 1e-10) put the contact at the start of the overlap, s = 0.7, below
    theta = 1e-5: node 1 of edge i carried 0.8 of the force on one side of that surface
    and 0.7 on the other, and a settling clove hitch stayed on it (Newton 2-cycles at any
    dt). Now s moves continuously (steeply near theta ~ 1e-5) from 0.8 to 0.7."""
    d0, g0 = _gap_gradient(theta0 * (1 - 1e-3))
    d1, g1 = _gap_gradient(theta0 * (1 + 1e-3) + 1e-15)
    assert d0 == pytest.approx(0.2, abs=1e-10)  # 0.2 + (theta l)^2 / (2 * 0.2) at most
    assert abs(d1 - d0) < 1e-12
    assert np.abs(g1 - g0).max() < 0.01
    # each edge carries the unit normal force (+z on j, -z on i) split over its nodes
    assert g0[[2, 5]].sum() == pytest.approx(-1.0, abs=1e-9)
    assert g0[[8, 11]].sum() == pytest.approx(1.0, abs=1e-9)
    # far from parallel the contact is at the crossing, s = 0.8
    _, g = _gap_gradient(0.1)
    assert g[5] == pytest.approx(-0.8, abs=1e-6)


def test_parallel_edges_meet_at_the_overlap_point_nearest_the_middle_of_edge_i():
    """For exactly parallel edges the regularised closest-point problem is strictly convex:
    s is the point of the overlap [0.7, 1] nearest s = 1/2, i.e. s = 0.7, t = 0."""
    s, t, free_s, free_t = segment_params(
        np.zeros(3), np.array([1.0, 0, 0]), np.array([0.7, 0, 0.2]), np.array([0.9, 0, 0.2])
    )
    assert (s, t) == pytest.approx((0.7, 0.0), abs=1e-9)
    assert free_s and not free_t


class _Rejector:
    """An interaction that exerts no force and rejects any converged step longer than
    ``max_dt`` (while ``t_from <= t < t_to``), as a tunnelling guard would."""

    def __init__(self, max_dt, t_from=0.0, t_to=np.inf):
        self.max_dt, self.t_from, self.t_to = max_dt, t_from, t_to
        self.t = 0.0

    def begin_step(self, system, q_old, v_old, dt):
        pass

    def assemble(self, system, q, q_old, dt, force, triplets):
        pass

    def end_step(self, system, q_new, q_old, dt):
        self.t += dt

    def energy(self, system, q):
        return 0.0

    def check_step(self, system, q_new, q_old, dt):
        if self.t_from <= self.t < self.t_to and dt > self.max_dt:
            return f"test guard: dt {dt:.3g} s > {self.max_dt:g} s"
        return None


def _falling_rod():
    r = rod.Rod.straight(length=0.1, n_nodes=11, radius=1e-3, youngs_modulus=1e6,
                         density=1000.0)  # fmt: skip
    return rod.RodSystem([r])


def test_stalled_step_fails_with_a_message_and_the_last_good_state():
    """A guard that only accepts steps of 1e-7 s (nominal 1e-3 s) drives dt below
    stall_fraction dt = 1e-6 s for good: after stall_steps attempts the run stops, status
    failed, saying why and what to try, with the last accepted state (not 22 minutes of
    crawling)."""
    system = _falling_rod()
    opts = rod.SolverOptions(throw=False, stall_steps=200)
    res = rod.simulate(system, t_end=1.0, dt=1e-3, loads=rod.Gravity(),
                       interactions=[_Rejector(1e-7)], options=opts)  # fmt: skip
    assert res.status == "failed"
    assert "stalled at t = " in res.message
    assert "stayed below 0.001 of the nominal dt (1e-06 s) for 200 attempts" in res.message
    assert "last rejection: test guard" in res.message
    assert "more nodes" in res.message and "smaller nominal dt" in res.message
    st = res.final_state
    # the last good state: the accepted steps add up to its time, which is far from t_end
    assert 0.0 < st.t < 200 * 1e-7
    assert np.all(np.isfinite(st.q))
    # an accepted implicit-Euler state of a rigidly falling rod (all nodes at one height)
    z = system.positions(st.q)[:, 2]
    assert np.ptp(z) < 1e-12 and z[0] < 0.0
    with pytest.raises(SolverError, match="stalled") as info:
        rod.simulate(system, t_end=1.0, dt=1e-3, loads=rod.Gravity(),
                     interactions=[_Rejector(1e-7)],
                     options=rod.SolverOptions(stall_steps=200))  # fmt: skip
    assert info.value.state.t == pytest.approx(st.t, rel=1e-12)


def test_a_transient_drop_of_the_step_does_not_trip_the_stall_guard():
    """The same guard active only for 2e-6 s of simulated time: dt falls to ~1e-7 s, then
    grows back (doubling every grow_after = 4 steps), within far fewer than the default
    500 attempts below 1e-3 dt: the run succeeds."""
    system = _falling_rod()
    res = rod.simulate(system, t_end=0.02, dt=1e-3, loads=rod.Gravity(),
                       interactions=[_Rejector(1e-7, 0.005, 0.005 + 2e-6)],
                       options=rod.SolverOptions(throw=False))  # fmt: skip
    assert res.status == "success", res.message
    assert res.stats["rejected_steps"] >= 13  # 1e-3 / 2^13 < 1.3e-7: it did fall
    assert res.final_state.t == pytest.approx(0.02, rel=1e-12)


def test_wall_time_per_simulated_second_guard():
    """max_wall_per_sim_second: a bound no run can meet (1 ms of CPU per simulated
    second) over a 0.05 s window stops the run with a message naming the rate."""
    system = _falling_rod()
    opts = rod.SolverOptions(throw=False, max_wall_per_sim_second=1e-3, stall_wall_window=0.05)
    res = rod.simulate(system, t_end=1e3, dt=1e-3, loads=rod.Gravity(), options=opts)
    assert res.status == "failed"
    assert "s of CPU time per simulated second" in res.message
    assert "max_wall_per_sim_second = 0.001" in res.message
    assert 0.0 < res.final_state.t < 1e3
    # off by default for this run's rate: the same run with the defaults succeeds
    ok = rod.simulate(system, t_end=0.05, dt=1e-3, loads=rod.Gravity())
    assert ok.status == "success"


class _FakeCPU:
    """A process clock that advances ``tick`` seconds at every reading (deterministic)."""

    def __init__(self, tick):
        self.now, self.tick = 0.0, tick

    def __call__(self):
        self.now += self.tick
        return self.now


def test_cpu_budget_stops_the_run_with_the_last_good_state(monkeypatch):
    """max_cpu_s: with a clock that advances 1 ms per reading, a 0.05 s budget stops a
    falling rod long before its end, status failed, the message naming the budget, the
    last accepted state finite and at a time the accepted 1 ms steps reach (25-60 of them:
    one or two clock readings per step). Without a budget the same run ends."""
    import time

    monkeypatch.setattr(time, "process_time", _FakeCPU(1e-3))
    system = _falling_rod()
    opts = rod.SolverOptions(throw=False, max_cpu_s=0.05, max_wall_per_sim_second=None)
    res = rod.simulate(system, t_end=1.0, dt=1e-3, loads=rod.Gravity(), options=opts)
    assert res.status == "failed"
    assert "spent its CPU budget, max_cpu_s = 0.05 s" in res.message
    assert "last good state kept" in res.message
    st = res.final_state
    assert 0.025 <= st.t <= 0.06
    assert abs(st.t / 1e-3 - round(st.t / 1e-3)) < 1e-6  # whole accepted steps
    assert np.all(np.isfinite(st.q))
    plain = rod.SolverOptions(throw=False, max_wall_per_sim_second=None)
    free = rod.simulate(system, t_end=0.2, dt=1e-3, loads=rod.Gravity(), options=plain)
    assert free.status == "success"
    with pytest.raises(InputError, match="max_cpu_s"):
        rod.SolverOptions(max_cpu_s=0.0)


def test_scene_budget_is_shared_by_its_phases(monkeypatch):
    """A scene's max_cpu_s bounds all its phases together: a first phase that spends 60 %
    of it leaves the second 40 %, and once spent the next phase fails before it starts;
    the run is marked over budget."""
    import time

    from knotmech.scenes._scene import SceneRun

    clock = _FakeCPU(1e-3)
    monkeypatch.setattr(time, "process_time", clock)
    run = SceneRun(_falling_rod(), options=rod.SolverOptions(max_cpu_s=0.1,
                   max_wall_per_sim_second=None))  # fmt: skip
    assert run.phase("one", 0.02, dt=1e-3, loads=[rod.Gravity()])
    used = clock.now - run.cpu0
    assert 0.02 <= used < 0.1
    assert not run.phase("two", 10.0, dt=1e-3, loads=[rod.Gravity()])
    assert run.over_budget
    assert "two: stopped at" in run.message and "CPU budget of 0.1 s" in run.message
    assert clock.now - run.cpu0 == pytest.approx(0.1, abs=0.005)
    assert not run.phase("three", 1.0, dt=1e-3)  # a failed run runs nothing more
    fresh = SceneRun(_falling_rod(), options=rod.SolverOptions(max_cpu_s=1e-4))
    clock.now += 1.0
    assert not fresh.phase("late", 0.01, dt=1e-3)
    assert fresh.over_budget and fresh.phases[-1].status == "failed"


def test_stall_guard_reads_cpu_time_so_a_paused_run_is_not_failed():
    """The rate guard reads the process's CPU time: a run whose wall clock runs on while it
    does no work (a paused build, here 20 ms of sleep after every 1 ms step: 20 s of wall
    per simulated second, against a bound of 5) is not failed; the falling rod's own CPU
    rate is far below 5 s/s (11 nodes). The same sleeps failed it when the guard read
    the wall clock (two false failures of the session-17 fibre-table builds)."""
    import time

    system = _falling_rod()
    opts = rod.SolverOptions(throw=False, max_wall_per_sim_second=5.0, stall_wall_window=0.05)
    t0 = time.perf_counter()
    res = rod.simulate(system, t_end=0.03, dt=1e-3, loads=rod.Gravity(), options=opts,
                       callback=lambda state: time.sleep(0.02))  # fmt: skip
    wall = time.perf_counter() - t0
    assert wall / 0.03 > 5.0  # the wall-clock rate would have failed it
    assert res.status == "success", res.message
    assert res.final_state.t == pytest.approx(0.03, rel=1e-12)


@pytest.mark.parametrize(
    "kw",
    [
        {"stall_fraction": -0.1},
        {"stall_fraction": 1.5},
        {"stall_steps": 0},
        {"stall_steps": 2.5},
        {"max_wall_per_sim_second": 0.0},
        {"stall_wall_window": -1.0},
    ],
)
def test_stall_option_errors(kw):
    with pytest.raises(InputError):
        rod.SolverOptions(**kw)

"""Implicit Euler + Newton-Raphson time stepping of a rod system (the ``simulate`` entry point).

Each step solves, for q = q_new (coated-rod paper eqs. (7)-(9); Bergou et al. 2010),

    f(q) = M/dt^2 (q - q_old - dt v_old) + dE/dq - F_ext(q) - sum F_interaction(q) = 0,
    J = M/dt^2 + d2E/dq2 - dF_ext/dq - sum dF_interaction/dq,

with the reference frames carried from the step start by time-parallel transport. Newton
iterations use a backtracking line search on ``|f|``; constrained dofs are eliminated (their rows
and columns replaced by the identity), and the residual left on them is the reaction. The
Jacobian is solved in LAPACK band storage (half bandwidth 10: Cholesky dpbsv, falling back to
LU dgbsv when J is not positive definite) unless interactions add triplets; then the free
dofs are reordered (reverse Cuthill-McKee) and the band matrix is factored by an envelope
LU without pivoting (checked: pivot size and backward error, else LAPACK's pivoted dgbtrf),
or, for very wide bands, as a sparse CSC matrix with SuperLU; on such contact-widened bands
the LU factors are reused (chord iterations, within a step and into the next one) while
they still cut the residual fast (``SolverOptions.jacobian_reuse``,
``jacobian_reuse_steps``): the converged state satisfies the same tolerances. Newton
starts from a second-order predictor (the last change of velocity; see
``SolverOptions.predictor``). A failed step is retried with half the step (interactions'
``begin_step`` is called again); below ``dt_min`` the run stops with status "failed" and
the last good state.

The elastic part of J is the symmetric Hessian of the DER energy with parallel-transported
reference frames (verified against finite differences in tests/rod/test_rod_gradients.py).
The exact derivative of the residual also holds a small antisymmetric "holonomy" term
proportional to the unbalanced torques on the twist angles (zero at equilibrium), which is
left out, as in Bergou et al. 2010: Newton stays symmetric and positive definite (Cholesky)
at the price of slightly less than quadratic convergence while those torques are large.
Static equilibria: use a step much longer than the rod's periods (inertia negligible),
ramped loads (``ramp_time``) and, for dynamics that must settle, ViscousDamping.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

import numpy as np
import scipy.sparse as sp
from scipy.linalg import lapack
from scipy.sparse.csgraph import reverse_cuthill_mckee
from scipy.sparse.linalg import splu

from ..errors import InputError, SolverError, check_positive, check_range
from ._kernels import assembly as _asm
from ._kernels import envelope as _env
from ._kernels import frames as _fr
from .elastic import ElasticWorkspace
from .interactions import interaction_state, restore_interaction_state
from .jacobian import Triplets
from .results import Result
from .system import RodSystem, State

__all__ = ["SolverOptions", "simulate"]

_B = _asm.BAND
# widest half bandwidth of the reordered sparse Jacobian still solved as a band matrix
# (beyond it, SuperLU with a minimum-degree ordering is faster)
_KD_MAX = 64
# Jacobians assembled on one RCM ordering before it is recomputed: contacts come and go,
# and an ordering made for an older contact pattern lets the band (and the LU cost, which
# grows like its square) creep up long before the 25 % widening test below triggers
_REORDER_EVERY = 100
# chord iterations (SolverOptions.jacobian_reuse) only when contacts have made the reordered
# band this much wider than a plain rod's (then the LU, growing like kd^2, dominates a
# Newton iteration; below, a fresh Jacobian is cheaper than the extra iterations)
_KD_REUSE = 2 * _B


@dataclass(frozen=True)
class SolverOptions:
    """Options of :func:`simulate`.

    Parameters
    ----------
    dt_min : float [s]  smallest step before the run is declared failed (default 1e-9)
    max_newton : int  Newton iterations per attempt before the step is halved (default 25)
    rtol : float  residual tolerance relative to the force scale of the step (default 1e-8)
    xtol : float  step tolerance relative to the mean rest edge length (default 1e-12)
    line_search : bool  backtracking on ``|f|`` (default True)
    max_backtracks : int  halvings of the Newton step before the attempt fails (default 8)
    grow_after : int  accepted steps before a reduced dt doubles back toward dt (default 4)
    save_every : float or None [s]  frame interval (default: every nominal dt)
    linear_solver : {"auto", "banded", "sparse"}  "auto": banded unless interactions add
        Jacobian triplets
    throw : bool  raise SolverError on failure (default True); else return status "failed"
    predictor : {"quadratic", "linear"}  Newton's start: q + dt v + dt (dt + h) a / 2 with
        the last change of velocity a (default; falls back to the linear guess if Newton
        fails from it), or q + dt v
    jacobian_reuse : float  with interaction triplets that widen the reordered band beyond
        twice a plain rod's (rod-rod contact): reuse the step's last LU factors for the
        next Newton iteration while the last iteration cut the residual by at least this
        factor (default 0.1; 0: always a fresh Jacobian); a chord iteration that converges
        slower brings a fresh Jacobian back
    jacobian_reuse_steps : float  likewise across steps: the next step (same dt) starts
        with the last factors if their last iteration cut the residual by at least this
        factor (default 0.03; 0: every step starts with a fresh Jacobian)
    stall_fraction, stall_steps : float, int  stall guard: the run stops with status
        "failed" (last good state kept) when the step stays below ``stall_fraction`` times
        the nominal dt for ``stall_steps`` consecutive attempts (default 1e-3 and 500:
        ten halvings, then 500 attempts that together advance at most half a nominal step;
        a step cut by a transient recovers within ~4 steps per halving, see
        ``grow_after``); ``stall_steps=None`` turns it off
    max_wall_per_sim_second : float or None [s/s]  stall guard on the clock: the run
        stops with status "failed" when, over a window of ``stall_wall_window`` seconds,
        it spent more than this many seconds per simulated second (default 3600: less
        than 1/60 s simulated in a minute; None: off). The clock is this process's CPU
        time (:func:`time.process_time`), not the wall clock, so a paused process
        (``kill -STOP``) or a shared machine does not fail a run that is not crawling;
        the name is kept from when it read the wall clock
    stall_wall_window : float [s]  window of that rate, in CPU seconds (default 60)
    max_cpu_s : float or None [s]  CPU budget of the run: it stops with status "failed"
        (last good state kept) once it has spent this many seconds of this process's CPU
        time (default None: no budget). The rate guard above bounds a crawl per simulated
        second, so a long simulated span (a soft rope's stretched protocol) can still take
        hours; a budget bounds the whole run. In a scene (``knotmech.scenes``) it is the
        budget of all its phases together
    max_strain : float or None  an accepted step whose largest edge strain ``|l/l0 - 1|``
        exceeds this ends the run with status "failed" (last good state kept): a rod
        stretched to many times its length, or crushed to a point, is no longer a result of
        the model (default 1.0; None turns the check off)
    stagnation : int, "auto" or None  an attempt whose residual has not halved in this
        many Newton iterations fails at once ("Newton stagnated"; the step is then retried
        from the linear predictor, then with dt/2) instead of spending the rest of
        ``max_newton`` iterations, each with a fresh LU, on a Newton cycle; "auto"
        (default): the smallest ``newton_stagnation`` hint of the interactions (rod-rod
        anchor friction: 4, see :class:`knotmech.rod.RodContact`), else off; None: off
    rescue : bool  stagnation fallback (default True). It engages only where the run
        would otherwise fail: when the stall guard (``stall_steps`` or
        ``max_wall_per_sim_second``, not ``max_cpu_s``) or ``dt_min`` would stop the run
        and the last rejected attempt stagnated, and only if an interaction would hold a
        switch at the last good state (a nearly parallel rod-rod pair in reach; else the
        run fails as it would without it). The run then goes on from its last good
        state at the nominal dt, and from there on a step whose Newton attempts
        stagnate is tried once more (from the linear predictor) with the interactions'
        discontinuous switches held for that attempt (``hold_switches``: the closest
        points of nearly parallel rod-rod edge pairs, at the step start; see
        docs/notes/contact-and-friction/parallel-edge-stall.md) before dt is halved. A
        run that succeeds without it never engages it (bit-identical); a second stall
        fails the run as before (its message says the fallback was on)
    """

    dt_min: float = 1e-9
    max_newton: int = 25
    rtol: float = 1e-8
    xtol: float = 1e-12
    line_search: bool = True
    max_backtracks: int = 8
    grow_after: int = 4
    save_every: float | None = None
    linear_solver: str = "auto"
    throw: bool = True
    predictor: str = "quadratic"
    jacobian_reuse: float = 0.1
    jacobian_reuse_steps: float = 0.03
    stall_fraction: float = 1e-3
    stall_steps: int | None = 500
    max_wall_per_sim_second: float | None = 3600.0
    stall_wall_window: float = 60.0
    max_cpu_s: float | None = None
    max_strain: float | None = 1.0
    stagnation: int | str | None = "auto"
    rescue: bool = True

    def __post_init__(self):
        check_positive("dt_min", self.dt_min)
        check_positive("rtol", self.rtol)
        check_positive("xtol", self.xtol)
        check_range("jacobian_reuse", self.jacobian_reuse, 0.0, 1.0)
        check_range("jacobian_reuse_steps", self.jacobian_reuse_steps, 0.0, 1.0)
        for name in ("max_newton", "max_backtracks", "grow_after"):
            v = getattr(self, name)
            if int(v) != v or v < 1:
                raise InputError(f"{name} must be an integer >= 1, got {v!r}")
        if self.save_every is not None:
            check_positive("save_every", self.save_every)
        self._check_guards()
        self._check_choices()

    def _check_guards(self) -> None:
        """The stall, strain and stagnation guards' options."""
        check_range("stall_fraction", self.stall_fraction, 0.0, 1.0)
        if not isinstance(self.rescue, bool):
            raise InputError(f"rescue must be True or False, got {self.rescue!r}")
        if self.stall_steps is not None and (
            int(self.stall_steps) != self.stall_steps or self.stall_steps < 1
        ):
            raise InputError(
                f"stall_steps must be an integer >= 1 or None, got {self.stall_steps!r}"
            )
        if self.max_wall_per_sim_second is not None:
            check_positive("max_wall_per_sim_second", self.max_wall_per_sim_second)
        check_positive("stall_wall_window", self.stall_wall_window)
        if self.max_cpu_s is not None:
            check_positive("max_cpu_s", self.max_cpu_s)
        if self.max_strain is not None:
            check_positive("max_strain", self.max_strain)
        sg = self.stagnation
        if (
            sg is not None
            and sg != "auto"
            and (isinstance(sg, (str, bool)) or int(sg) != sg or sg < 1)
        ):
            raise InputError(f"stagnation must be an integer >= 1, 'auto' or None, got {sg!r}")

    def _check_choices(self) -> None:
        """The options that name a method."""
        if self.predictor not in ("quadratic", "linear"):
            raise InputError(f"predictor must be 'quadratic' or 'linear', got {self.predictor!r}")
        if self.linear_solver not in ("auto", "banded", "sparse"):
            raise InputError(
                f"linear_solver must be 'auto', 'banded' or 'sparse', got {self.linear_solver!r}"
            )


class _StepFailed(Exception):
    """A step attempt failed; ``iterations`` spent on it; ``guard``: rejected by an
    interaction's step check (a smaller dt is needed, not a better start)."""

    def __init__(self, msg, iterations: int = 0, guard: bool = False, stalled: bool = False):
        super().__init__(msg)
        self.iterations = iterations
        self.guard = guard
        self.stalled = stalled


class Stepper:
    """One implicit-Euler step with Newton iterations (internal; simulate and benchmarks)."""

    def __init__(self, system, loads=(), constraints=(), interactions=(), options=SolverOptions()):
        self.system = system
        self.loads = tuple(loads)
        self.constraints = tuple(constraints)
        self.interactions = tuple(interactions)
        self.opt = options
        self.last_iterate = None  # the configuration the last Newton evaluation was at
        self.ws = ElasticWorkspace(system)
        n = system.n_dof
        cd = [c.dofs(system) for c in self.constraints]
        self._cdof_list = cd
        self.cdofs = np.concatenate(cd).astype(np.int64) if cd else np.zeros(0, dtype=np.int64)
        if np.unique(self.cdofs).size != self.cdofs.size:
            raise InputError(
                "constraints name the same dof twice (a node or edge constrained twice)"
            )
        self.free = np.ones(n, dtype=bool)
        self.free[self.cdofs] = False
        self.free_idx = np.flatnonzero(self.free)
        th = system.is_theta
        self.fx = self.free & ~th
        self.ft = self.free & th
        self.pb = np.zeros((_B + 1, n), order="F")  # upper band (dpbsv layout)
        self.gb = np.zeros((3 * _B + 1, n), order="F")  # full band for the LU fallback
        self.trip = Triplets()
        self.fext = np.zeros(n)
        self.jdiag = np.zeros(n)
        self.diag = np.zeros(n)
        self.f = np.zeros(n)
        self._mass = system.mass
        self._mass_dt = (None, None)
        self._trig = (None, None, None)
        self._is_theta = system.is_theta
        self._rest_length = system.rest_length
        self.length_scale = float(np.mean(system.rest_length))
        self.radius_scale = float(np.mean(system.rod_radius_edge))
        self.ea_max = float(np.max(system.ea))
        # round-off floors of the residual: strains are known to ~ machine epsilon, so the
        # stretching forces carry an absolute error ~ EA eps (twisting: GJ/l eps)
        eps = np.finfo(float).eps
        self.floor_x = 64.0 * eps * self.ea_max
        self.floor_t = 64.0 * eps * float(np.max(system.gj / system.voronoi))
        self.n_evals = 0
        self._jac_pending = False
        self._factors_valid = False
        self._lcol = np.empty(0)
        self._force_hessian = False
        self._hess_missing = False
        self._eval_args = None
        self._factors_dt = None
        self._last_ratio = np.inf
        self._n_on_order = 0
        self._work_ordered = 0
        self._mode = "band"
        self._order_stale = True
        self._order_fresh = False
        self._kd_ordered = 0
        self._kd = 0
        self._anorm = 0.0
        self._lu_checked = False
        self._lu_piv = None
        self._ab = self._ab_orig = self._env_first = self._env_last = self._work = None
        nf = self.free_idx.size
        sg = options.stagnation
        if sg == "auto":
            hints = [getattr(it, "newton_stagnation", None) for it in self.interactions]
            hints = [int(h) for h in hints if h is not None]
            sg = min(hints) if hints else None
        self._stagnation = sg
        self.rescue = False  # the stagnation fallback is on (set by the time loop)
        self.n_held_steps = 0  # steps converged with switches held
        self._fmap = -np.ones(n, dtype=np.int64)
        self._fmap[self.free_idx] = np.arange(nf)
        self._gmap = None  # dof -> row of the reordered free system (-1: constrained)
        self._elastic_rc = None  # elastic COO pattern mapped through _gmap (fixed)

    # ------------------------------------------------------------ evaluation
    def evaluate(self, q, st: State, dt: float, t_new: float, jacobian: bool = True) -> float:
        """Residual f(q) into ``self.f`` (and the Jacobian, if asked); return the scales
        (force scale, torque scale, max |f| on free positions, on free angles)."""
        s, ws = self.system, self.ws
        self.n_evals += 1
        # while chord iterations may follow, the Hessians wait until solve() needs them
        lazy = jacobian and self._hessian_may_wait()
        trig = self._trig  # cos, sin of the step start's reference twist (see step())
        ws.frames(
            q, st.tangents, st.d1, st.ref_twist, trig[1:] if trig[0] is st.ref_twist else None
        )
        ws.grad_hess(q, hessian=jacobian and not lazy)
        fext, jd = self.fext, self.jdiag
        fext[:] = 0.0
        jd[:] = 0.0
        for load in self.loads:
            load.apply(s, t_new, q, st.q, dt, fext, jd)
        self.trip.clear()
        self.trip.wanted = jacobian and not lazy
        for it in self.interactions:
            it.assemble(s, q, st.q, dt, fext, self.trip)
        pot, sx, sth, rx, rt = _asm.residual_and_scales(
            self._mass, dt, q, st.q, st.v, ws.grad, fext, self._is_theta, self.free, self.f
        )
        # incremental potential (the merit of the line search): its gradient is f for
        # conservative loads and interactions
        phi = pot + sum(ws.energy_parts)
        for load in self.loads:
            pot_fn = getattr(load, "step_potential", None)
            phi += pot_fn(s, q, st.q, dt) if pot_fn is not None else load.energy(s, q, t_new)
        for it in self.interactions:
            phi += it.energy(s, q)
        self.phi = phi
        self.rnorm = _asm.masked_norm(self.f, self.free)  # |f| on the free dofs
        self._eval_dt = dt
        if jacobian:  # the matrix itself is built lazily, by solve()
            if self._mass_dt[0] != dt:  # M / dt^2, computed once per step size
                self._mass_dt = (dt, self._mass / (dt * dt))
            np.subtract(self._mass_dt[1], jd, out=self.diag)
            self._jac_pending = True
            self._hess_missing = lazy
            self._eval_args = (q, st, dt, t_new) if lazy else None
        tens = self.ea_max * _asm.max_abs_strain(ws.lengths, self._rest_length)
        return max(sx, tens), sth, rx, rt

    def _hessian_may_wait(self) -> bool:
        """True when the next solve may reuse LU factors (reordered contact band wider than
        _KD_REUSE, factors at hand, reuse enabled): the evaluation then skips the Hessians
        and Jacobian triplets, and solve() redoes it with them only if it needs a fresh
        Jacobian after all (same residual, bit for bit)."""
        return (
            self._force_hessian is False
            and self._factors_reusable()
            and (self.opt.jacobian_reuse > 0 or self.opt.jacobian_reuse_steps > 0)
        )

    def _factors_reusable(self) -> bool:
        """LU factors of a contact-widened reordered band (wider than _KD_REUSE) at hand."""
        return self._factors_valid and self._mode == "sparse-band" and self._kd > _KD_REUSE

    def _use_band(self) -> bool:
        if self.opt.linear_solver == "banded":
            if self.trip.size:
                raise InputError("linear_solver='banded' cannot take interaction Jacobian triplets")
            return True
        return self.opt.linear_solver == "auto" and self.trip.size == 0

    def _assemble(self) -> None:
        self._jac_pending = False
        if self._use_band():
            pb = self.pb
            pb[:] = 0.0
            self.ws.band_add(pb)  # upper triangle: enough for Cholesky
            _asm.band_add_diagonal(self.diag, pb, _B)
            _asm.band_constrain(self.cdofs, pb, _B)
            self._mode = "band"
        else:
            self._assemble_sparse()

    def _reorder(self, er, ec) -> None:
        """Reverse Cuthill-McKee ordering of the free dofs for the current contact pattern:
        contacts couple nodes far apart along the rods, and RCM brings the matrix back to a
        narrow band. Redone when new contacts widen the band by more than 25 %, when the
        LU work of the envelope has grown by 25 % (see :meth:`_factor_band`), and after
        _REORDER_EVERY Jacobians."""
        nf = self.free_idx.size
        # the structure of P + P^T (P: the elastic and interaction entries on the free
        # dofs), as the canonical CSR matrix scipy builds from them (sorted, no
        # duplicates): RCM of it in symmetric mode is RCM of P in non-symmetric mode
        indptr, ind = _asm.pattern_csr(er, ec, self.trip.rows, self.trip.cols, self._fmap, nf)
        pat = sp.csr_matrix((np.ones(ind.size), ind, indptr), shape=(nf, nf))
        perm = reverse_cuthill_mckee(pat, symmetric_mode=True)
        iperm = np.empty(nf, dtype=np.int64)
        iperm[perm] = np.arange(nf)
        gm = -np.ones(self.system.n_dof, dtype=np.int64)
        gm[self.free_idx] = iperm
        self._gmap = gm
        self._elastic_rc = None
        self._order_stale = False
        self._order_fresh = True
        self._n_on_order = 0

    def _assemble_sparse(self) -> None:
        """Jacobian with interaction triplets, restricted to the free dofs and reordered
        (RCM). Stored as a (2 kd + 1)-row band matrix when the reordered half bandwidth kd
        is at most _KD_MAX, factored by :meth:`_factor_band` (envelope LU, pivoted LAPACK
        dgbtrf as the fallback; the blocked band Cholesky dpbtrf once used at these widths
        was erratic, up to seconds per call, with threaded OpenBLAS on a loaded machine);
        wider bands go to SuperLU as CSC. The band matrix is filled straight from the
        elastic Hessian blocks and the triplets through the dof map (no COO temporaries),
        and the envelope (first non-zero column of each row) from their patterns."""
        self._n_on_order += 1
        if self._n_on_order > _REORDER_EVERY and self.trip.size:
            self._order_stale = True
        if self._order_stale or self._gmap is None:
            er, ec, _ = self.ws.coo()
            self._reorder(er, ec)
        gm = self._gmap
        s, ws = self.system, self.ws
        if self._elastic_rc is None:  # the elastic pattern never changes
            er, ec, _ = ws.coo()
            r0, c0 = gm[er], gm[ec]
            d0 = gm[self.free_idx]
            first0 = np.arange(self.free_idx.size, dtype=np.int64)
            _env.pattern_first(r0, c0, first0)
            kd0 = _asm.max_band_mapped(er, ec, gm)
            self._elastic_rc = (r0, c0, d0, kd0, first0)
        r0, c0, d0, kd0, first0 = self._elastic_rc
        trip = self.trip
        kd = max(kd0, _asm.max_band_mapped(trip.rows, trip.cols, gm), 1)
        if not self._order_fresh and kd > 1.25 * self._kd_ordered + 4:
            # the contact pattern changed enough to widen the band: new ordering
            self._order_stale = True
            return self._assemble_sparse()
        if self._order_fresh:
            self._kd_ordered = kd
            self._order_fresh = False
        nf = self.free_idx.size
        dv = self.diag[self.free_idx]
        if kd <= _KD_MAX:
            # (2 kd + 1, nf) band, A[i, j] at ab[kd + i - j, j]: envelope LU (no pivoting)
            ab = self._band_buffer(2 * kd + 1, nf)
            _asm.band_add_hessians_mapped(
                s.edge_dof0, s.stencil_edge, ws.hess_s, ws.hess8, gm, kd, ab
            )
            fi = self.free_idx
            _asm.band_scatter_mapped(fi, fi, dv, gm, 1.0, kd, ab)
            _asm.band_scatter_mapped(trip.rows, trip.cols, trip.vals, gm, -1.0, kd, ab)
            self._ab, self._kd = ab, kd
            first = self._env_first = first0.copy()  # new: the last one may be held
            _env.pattern_first_mapped(trip.rows, trip.cols, gm, first)
            self._factor_band()
            self._mode = "sparse-band"
        else:
            er, ec, ev = ws.coo()
            tr, tc = gm[trip.rows], gm[trip.cols]
            tv = trip.vals
            k0 = (r0 >= 0) & (c0 >= 0)
            kt = (tr >= 0) & (tc >= 0)
            rows = np.concatenate([r0[k0], d0, tr[kt]])
            cols = np.concatenate([c0[k0], d0, tc[kt]])
            vals = np.concatenate([ev[k0], dv, -tv[kt]])
            self._J = sp.csc_matrix((vals, (rows, cols)), shape=(nf, nf))
            self._mode = "sparse"

    def _factor_band(self) -> None:
        """Factor the (2 kd + 1)-row band matrix ``self._ab``: envelope LU without pivoting
        (:mod:`._kernels.envelope`, a fraction of the cost of the pivoted band LU on the
        RCM-ordered contact Jacobian), or, when a pivot falls below 1e-13 of its diagonal
        entry, LAPACK's pivoted band LU (dgbtrf) on the kept copy of the matrix."""
        ab, kd = self._ab, self._kd
        nf = ab.shape[1]
        # new arrays for each factorization: the last ones may be held by a State
        orig = np.empty_like(ab, order="F")
        self._ab_orig = orig
        self._env_last = np.empty(nf, dtype=np.int64)
        if getattr(self, "_work", None) is None or self._work.size != nf:
            self._work = np.empty(nf)
        if self._lcol.size < kd + 1:
            self._lcol = np.empty(2 * kd + 2)
        self._anorm = _env.copy_band(ab, orig)
        _env.env_last(self._env_first, self._env_last)
        # the envelope grows as contacts move away from those the ordering was made for:
        # reorder at the next Jacobian once the LU work has grown by a quarter
        work = _env.env_work(self._env_last)
        if self._n_on_order == 0:  # first Jacobian on a fresh ordering
            self._work_ordered = work
        elif work > 1.25 * self._work_ordered:
            self._order_stale = True
        self._lu_piv = None
        self._lu_checked = False
        if _env.env_factor(ab, kd, self._env_last, orig, 1e-13, self._lcol) != 0:
            self._factor_pivoted()

    def _factor_pivoted(self) -> None:
        """LU with partial pivoting (LAPACK dgbtrf) of the kept copy of the band matrix."""
        kd, orig = self._kd, self._ab_orig
        gb = np.zeros((3 * kd + 1, orig.shape[1]), order="F")
        gb[kd:] = orig
        lu, piv, info = lapack.dgbtrf(gb, kd, kd, overwrite_ab=1)
        if info != 0:
            raise _StepFailed("singular Jacobian")
        self._lu_piv = (lu, piv)

    def _solve_band(self, b: np.ndarray) -> np.ndarray:
        """Solve with the factors of :meth:`_factor_band`; an envelope solution whose
        backward error is too large (element growth without pivoting) is
        redone with the pivoted LU (normwise backward error above 1e-11; pivoted LU
        reaches ~1e-16)."""
        kd = self._kd
        if self._lu_piv is None:
            y = b.copy()
            _env.env_solve(self._ab, kd, self._env_first, self._env_last, y)
            if self._lu_checked:  # these factors passed the check on their first solve
                return y
            if _env.band_residual(self._ab_orig, kd, y, b, self._anorm, self._work) <= 1e-11:
                self._lu_checked = True
                return y
            self._factor_pivoted()
        lu, piv = self._lu_piv
        y, info = lapack.dgbtrs(lu, kd, kd, b, piv)
        if info != 0:
            raise _StepFailed("singular Jacobian")
        return y

    def _band_buffer(self, nrow: int, ncol: int) -> np.ndarray:
        """A zeroed Fortran-ordered (nrow, ncol) band matrix. A new one each time (as cheap
        as zeroing the last one): the factors of earlier Jacobians may be held by a
        :class:`State` (:meth:`linear_state`) and are never written into."""
        return np.zeros((nrow, ncol), order="F")

    # the solver's linear-algebra state carried by State.linear (see linear_state)
    _LIN_SCALARS = ("n_on_order", "kd_ordered", "work_ordered", "order_stale",
                    "order_fresh", "factors_valid", "factors_dt", "last_ratio", "kd",
                    "anorm", "lu_checked")  # fmt: skip
    _LIN_ARRAYS = ("gmap", "ab", "ab_orig", "env_first", "env_last")

    def linear_state(self) -> dict | None:
        """The ordering and reusable LU factors of the contact Jacobian as {name: array or scalar}
        (for :attr:`State.linear`; the arrays are shared: the solver only ever replaces
        them), or None while the plain band solver is in use (it keeps no state)."""
        if self._gmap is None:
            return None
        # plain scalars (State.save turns them into arrays): this runs after every step
        d = {k: getattr(self, "_" + k) for k in self._LIN_SCALARS}
        if self._factors_dt is None:
            d["factors_dt"] = np.nan
        d["mode"] = self._mode
        for k in self._LIN_ARRAYS:
            v = getattr(self, "_" + k, None)
            if v is not None:
                d[k] = v
        if self._lu_piv is not None:
            d["lu"], d["piv"] = self._lu_piv
        return d

    def load_linear_state(self, d: dict | None) -> None:
        """Restore what :meth:`linear_state` returned (None, or written for other free
        dofs: keep the fresh solver's)."""
        if not d:
            return
        gm = np.asarray(d["gmap"])
        if gm.shape != (self.system.n_dof,) or not np.array_equal(gm >= 0, self.free):
            # another system or other constrained dofs (e.g. the next phase of a scene):
            # that ordering and those factors do not apply, start afresh
            return
        for k in self._LIN_SCALARS:
            v = np.asarray(d[k]).item()
            setattr(self, "_" + k, v)
        self._mode = str(np.asarray(d["mode"]))
        for k in self._LIN_ARRAYS:
            if k in d:
                setattr(self, "_" + k, np.array(d[k], order="F" if k.startswith("ab") else "C"))
        self._lu_piv = (np.array(d["lu"], order="F"), np.array(d["piv"])) if "lu" in d else None
        self._elastic_rc = None  # derived from the ordering
        kd = int(self._kd)
        if self._lcol.size < kd + 1:
            self._lcol = np.empty(2 * kd + 2)
        if "ab" in d:
            self._work = np.empty(self._ab.shape[1])

    def solve(self, rhs: np.ndarray, reuse: bool = False) -> np.ndarray:
        """Solve J x = rhs with x = 0 on constrained dofs; ``reuse``: with the factors of
        the last Jacobian of this step (reordered band only) instead of the current one."""
        if reuse and self._factors_reusable():
            self._jac_pending = False
        elif self._jac_pending:
            if self._hess_missing:  # the evaluation skipped the Hessians: redo it with them
                self._force_hessian = True
                try:
                    self.evaluate(*self._eval_args)
                finally:
                    self._force_hessian = False
            self._assemble()
            self._factors_valid = self._mode == "sparse-band"
            self._factors_dt = self._eval_dt
        if self._mode == "band":
            b = rhs.copy()
            b[self.cdofs] = 0.0
            _, x, info = lapack.dpbsv(self.pb, b, lower=0, overwrite_ab=0, overwrite_b=0)
            if info != 0:  # not positive definite: LU with pivoting on the full matrix
                _asm.upper_to_general(self.pb, self.gb)
                _, _, x, info = lapack.dgbsv(_B, _B, self.gb, b, overwrite_ab=1, overwrite_b=1)
                if info != 0:
                    raise _StepFailed("singular Jacobian")
            return x
        b = np.empty(self.free_idx.size)
        _asm.permute_in(rhs, self.free_idx, self._gmap, b)
        if self._mode == "sparse-band":
            y = self._solve_band(b)
        else:
            try:
                lu = splu(self._J, permc_spec="MMD_AT_PLUS_A", diag_pivot_thresh=0.1,
                          options={"SymmetricMode": True})  # fmt: skip
                y = lu.solve(b)
            except RuntimeError as exc:  # singular factor
                raise _StepFailed(f"sparse solve failed: {exc}") from None
        x = np.empty_like(rhs)
        _asm.permute_out(y, self.free_idx, self._gmap, x)
        return x

    def _check(self, q, st: State, dt: float) -> None:
        """Interactions' optional step checks (``check_step``, e.g. the contact tunnelling
        guard): a reason returned rejects the converged step (it is retried with dt/2)."""
        for it in self.interactions:
            chk = getattr(it, "check_step", None)
            if chk is not None:
                why = chk(self.system, q, st.q, dt)
                if why:
                    raise _StepFailed(why, guard=True)

    def _converged(self, scales) -> tuple[bool, float]:
        sx, st_, rx, rt = scales
        st_ = max(st_, sx * self.radius_scale)
        tx = self.opt.rtol * sx + self.floor_x
        tt = self.opt.rtol * st_ + self.floor_t
        return rx <= tx and rt <= tt, max(rx / tx, rt / tt)

    # ------------------------------------------------------------ one step
    def step(self, st: State, dt: float):
        """Attempt one step; return (q_new, iterations) or raise _StepFailed.

        Predictor: second order, q_old + dt v_old + dt (dt + h_last)/2 a_old with a_old the
        change of velocity over the last two steps (``State.accel``), which starts Newton
        closer to the solution than the constant-velocity guess q_old + dt v_old (the
        converged step satisfies the same tolerances either way). If Newton fails from it,
        the step is retried once from the constant-velocity guess before the solver halves
        dt (``SolverOptions.predictor = "linear"`` always uses the latter)."""
        t_new = st.t + dt
        q_lin = st.q + dt * st.v
        if self._trig[0] is not st.ref_twist:  # once per step, for every evaluation of it
            rt = st.ref_twist
            self._trig = (rt, np.empty(rt.shape), np.empty(rt.shape))
            _fr.cos_sin(rt, self._trig[1], self._trig[2])
        for it in self.interactions:  # once per attempt: it depends on the step start only
            it.begin_step(self.system, st.q, st.v, dt)
        try:
            return self._predicted(st, dt, t_new, q_lin)
        except _StepFailed as exc:
            if not (self.rescue and exc.stalled):
                raise
            return self._held_attempt(st, dt, t_new, exc)

    def _predicted(self, st: State, dt: float, t_new: float, q_lin):
        """Newton from the quadratic predictor, then from the linear one (see :meth:`step`)."""
        if self.opt.predictor == "quadratic" and st.accel is not None and np.isfinite(st.h_last):
            q0 = q_lin + (0.5 * dt * (dt + st.h_last)) * st.accel
            try:
                return self._newton(q0, st, dt, t_new)
            except _StepFailed as exc:
                if exc.guard:
                    raise
                wasted = exc.iterations
            q, k = self._newton(q_lin, st, dt, t_new)
            return q, k + wasted
        return self._newton(q_lin, st, dt, t_new)

    def _held_attempt(self, st: State, dt: float, t_new: float, exc: _StepFailed):
        """Stagnation fallback (``SolverOptions.rescue``): Newton once more from the linear
        predictor with the interactions' switches held at the step start
        (``hold_switches``); re-raises ``exc`` when no interaction holds anything."""
        held = self.holders()
        n = sum(it.hold_switches(self.system, st.q) for it in held)
        try:
            if n == 0:
                raise exc
            q, k = self._newton(st.q + dt * st.v, st, dt, t_new)
        finally:
            for it in held:
                it.release_switches()
        self.n_held_steps += 1
        return q, k + exc.iterations

    def holders(self) -> list:
        """The interactions that can hold their switches (the stagnation fallback)."""
        return [it for it in self.interactions if getattr(it, "hold_switches", None)]

    def would_hold(self, st: State, dt: float) -> bool:
        """Dry run of the fallback's hold at the step start ``st`` (step ``dt`` [s]): True
        when an interaction holds any switch there (e.g. a nearly parallel rod-rod pair in
        reach). The holders begin a step from ``st`` (as the next attempt does again) and
        are released at once: nothing else changes."""
        held = self.holders()
        try:
            for it in held:
                it.begin_step(self.system, st.q, st.v, dt)
            return sum(it.hold_switches(self.system, st.q) for it in held) > 0
        finally:
            for it in held:
                it.release_switches()

    def _newton(self, q, st: State, dt: float, t_new: float):
        opt = self.opt
        for c, dofs in zip(self.constraints, self._cdof_list, strict=True):
            q[dofs] = c.values(self.system, t_new, dt, st.q)
        try:
            # the last factors of the previous step start this one if their last iteration
            # still cut the residual by jacobian_reuse_steps (and dt is the same); decided
            # before the first evaluation, so that a step which needs a fresh Jacobian
            # builds its Hessians there instead of evaluating twice (same residual)
            cross = (
                self._factors_valid
                and self._factors_dt == dt
                and self._last_ratio <= opt.jacobian_reuse_steps
            )
            if not cross:
                self._factors_valid = False
            self.last_iterate = q
            scales = self.evaluate(q, st, dt, t_new)
            return self._iterate(q, st, dt, t_new, scales, cross)
        except _StepFailed:
            self._factors_valid = False
            raise
        except ArithmeticError as exc:
            # an iterate the energy is not defined at (a kernel's division by zero on a
            # collapsed edge or a folded-back stencil, an overflow, numpy errors raised
            # under np.errstate): the attempt failed like a non-finite residual, and the
            # step is retried with dt/2
            self._factors_valid = False
            raise _StepFailed(f"evaluation failed ({type(exc).__name__}: {exc})") from None

    def _iterate(self, q, st, dt, t_new, scales, cross):
        """Newton iterations from the evaluated start ``q``: return (q_new, iterations) or
        raise _StepFailed. ``cross``: the first solve may reuse the last step's factors."""
        opt = self.opt
        rel_prev = np.inf
        best, k_best = np.inf, 0
        for k in range(opt.max_newton + 1):
            ok, rel = self._assess(scales, k, rel_prev)
            if ok:
                self._check(q, st, dt)
                return q, k
            if k == opt.max_newton:
                break
            best, k_best = self._watch_stagnation(rel, k, best, k_best)
            # chord step (the last factors of this step) while they still cut the
            # residual by the factor jacobian_reuse per iteration
            reuse = cross if k == 0 else rel <= opt.jacobian_reuse * rel_prev
            dq = self.solve(-self.f, reuse=reuse)
            rel_prev = rel
            if not _asm.all_finite(dq):
                raise _StepFailed("non-finite Newton step", k)
            q, alpha, scales = self._line_search(q, dq, st, dt, t_new, rel, k)
            if self._step_small(dq, alpha):
                self._check(q, st, dt)
                return q, k + 1
        raise _StepFailed(
            f"Newton did not converge in {opt.max_newton} iterations (residual {rel:.2e})",
            opt.max_newton,
        )

    def _assess(self, scales, k: int, rel_prev: float) -> tuple[bool, float]:
        """(converged, residual relative to the tolerance) of iteration ``k``; records the
        residual's ratio to the last iteration's (the reuse test of the next step)."""
        if not _asm.all_finite(self.f):
            raise _StepFailed("non-finite residual", k)
        ok, rel = self._converged(scales)
        if k > 0:
            self._last_ratio = rel / rel_prev
        return ok, rel

    def _watch_stagnation(self, rel: float, k: int, best: float, k_best: int):
        """The best residual so far and its iteration; raise _StepFailed when it has not
        halved in ``SolverOptions.stagnation`` iterations."""
        stag = self._stagnation
        if rel <= 0.5 * best:
            return rel, k
        if stag is not None and k - k_best >= stag:
            raise _StepFailed(
                f"Newton stagnated: the residual did not halve in {stag} iterations "
                f"(residual {rel:.2e} of the tolerance)",
                k,
                stalled=True,
            )
        return best, k_best

    def _line_search(self, q, dq, st, dt, t_new, rel, k):
        """Backtracking along the Newton step ``dq``: accept when the incremental potential
        decreases (Armijo, with a round-off slack) or the residual norm does. Returns
        (q_new, alpha, scales); after ``max_backtracks`` halvings the last try is kept
        (alpha then halved once more) unless the residual is not finite or far from
        converged (``rel`` >= 1e3), which fails the attempt."""
        opt = self.opt
        r0 = self.rnorm
        p0 = self.phi
        slope = float(np.dot(self.f, dq))
        slack = 1e-13 * (abs(p0) + 1.0)
        alpha = 1.0
        for _ in range(opt.max_backtracks + 1):
            q_try = q + alpha * dq
            self.last_iterate = q_try  # what a failed attempt reached (strain check)
            scales = self.evaluate(q_try, st, dt, t_new)
            r1 = self.rnorm
            if np.isfinite(r1) and (
                not opt.line_search
                or r1 <= (1.0 - 1e-4 * alpha) * r0
                or (slope < 0 and self.phi <= p0 + 1e-4 * alpha * slope + slack)
            ):
                return q_try, alpha, scales
            alpha *= 0.5
        if not (np.isfinite(r1) and rel < 1e3):
            raise _StepFailed("line search found no decrease of the residual", k)
        return q_try, alpha, scales

    def _step_small(self, dq, alpha: float) -> bool:
        """The Newton step below ``xtol`` (positions relative to the mean rest edge length,
        angles absolute) and a finite residual: converged."""
        opt = self.opt
        stepx, stept = _asm.max_abs_split(dq, alpha, self.fx, self.ft)
        return (
            stepx <= opt.xtol * self.length_scale and stept <= opt.xtol and _asm.all_finite(self.f)
        )


def _worst_strain(system, q) -> tuple[int, float]:
    """(edge, strain l/l0 - 1) of the edge strained most at configuration ``q``."""
    k, e = _asm.worst_strain(np.asarray(q, dtype=float), system.node_dofs, system.edge_nodes,
                             system.rest_length)  # fmt: skip
    return int(k), float(e)


def _strain_message(k: int, e: float, t: float, limit: float, how: str) -> str:
    return (
        f"edge {k} would reach a strain of {e:.3g}{how} at t = {t:.6g} s, beyond "
        f"max_strain = {limit:g}: the loads are too large for the rod (a rod model result "
        "no longer); last good state kept"
    )


class _StallGuard:
    """The stall guards of :func:`simulate` (``SolverOptions.stall_fraction``,
    ``stall_steps``, ``max_wall_per_sim_second``) and its CPU budget (``max_cpu_s``):
    :meth:`check` is called before every step attempt and returns the failure message once
    the run crawls or has spent its budget, else ""."""

    def __init__(self, opt: SolverOptions, dt: float, t0: float, cpu0: float):
        self.opt = opt
        self.cpu0 = cpu0
        self.dt = dt
        self.small_dt = opt.stall_fraction * dt
        self.n_small = 0
        self.win_cpu = cpu0  # [s of process CPU time]
        self.win_t = t0
        self.last_reason = ""
        self.budget_spent = False

    def check(self, dt_cur: float, t: float) -> str:
        opt = self.opt
        if opt.max_cpu_s is not None:
            used = time.process_time() - self.cpu0
            if used > opt.max_cpu_s:
                self.budget_spent = True
                return (
                    f"stopped at t = {t:.6g} s: the run spent its CPU budget, max_cpu_s = "
                    f"{opt.max_cpu_s:g} s ({used:.4g} s of CPU time; step now {dt_cur:.3g} s); "
                    "last good state kept"
                )
        self.n_small = self.n_small + 1 if dt_cur < self.small_dt else 0
        why = ""
        if opt.stall_steps is not None and self.n_small >= opt.stall_steps:
            why = (
                f"the step stayed below {opt.stall_fraction:g} of the nominal dt "
                f"({self.small_dt:.3g} s) for {self.n_small} attempts (now {dt_cur:.3g} s)"
            )
        elif opt.max_wall_per_sim_second is not None:
            now = time.process_time()
            if now - self.win_cpu >= opt.stall_wall_window:
                rate = (now - self.win_cpu) / max(t - self.win_t, 1e-300)
                if rate > opt.max_wall_per_sim_second:
                    why = (
                        f"{rate:.3g} s of CPU time per simulated second over the last "
                        f"{now - self.win_cpu:.3g} s (bound max_wall_per_sim_second = "
                        f"{opt.max_wall_per_sim_second:g}; step now {dt_cur:.3g} s)"
                    )
                self.win_cpu, self.win_t = now, t
        if not why:
            return ""
        last = f"; last rejection: {self.last_reason}" if self.last_reason else ""
        return (
            f"stalled at t = {t:.6g} s: {why}{last}. Try more nodes (a finer mesh) or a "
            f"smaller nominal dt; last good state kept"
        )


def _as_tuple(x, name):
    if x is None:
        return ()
    if isinstance(x, (list, tuple)):
        return tuple(x)
    return (x,)


def simulate(
    system: RodSystem,
    state0: State | None = None,
    *,
    t_end: float,
    dt: float,
    loads=(),
    constraints=(),
    interactions=(),
    options: SolverOptions = SolverOptions(),
    progress: bool = False,
    callback=None,
    throw: bool | None = None,
) -> Result:
    """Integrate a rod system from ``state0`` to ``t_end`` with implicit Euler.

    Parameters
    ----------
    system : RodSystem (or a single Rod)
    state0 : State, optional  start state (default ``system.initial_state()``); pass a
        previous ``Result.final_state`` (or ``State.load(path)``) to resume bit-identically
    t_end : float [s]  end time (absolute, >= state0.t)
    dt : float [s]  nominal step; halved on Newton failure, grown back after success
    loads : Gravity, NodeForce, EdgeTorque, ViscousDamping (one or a sequence)
    constraints : Clamp, MovingNodes, RotatingEdges (one or a sequence)
    interactions : objects following :class:`knotmech.rod.Interaction`
    options : SolverOptions
    progress : bool  show a tqdm progress bar
    callback : callable(state) -> bool or None, called after every accepted step; returning
        True stops the run (status "success", message says so)
    throw : bool, optional  overrides ``options.throw``

    Returns
    -------
    Result  (raises SolverError on failure unless ``options.throw`` is False; the error's
    ``state`` is the last good state and its ``result`` the partial Result)
    """
    system, st, dt, t_end = _checked_start(system, state0, dt, t_end)
    opt = options
    stepper = Stepper(system, _as_tuple(loads, "loads"), _as_tuple(constraints, "constraints"),
                      _as_tuple(interactions, "interactions"), opt)  # fmt: skip
    restore_interaction_state(stepper.interactions, st.interactions)  # friction anchors
    stepper.load_linear_state(st.linear)  # ordering and LU factors (bit-identical resume)
    recorder = _Recorder(stepper)
    # frame 0: static reaction (no inertia known yet)
    stepper.evaluate(st.q, st, dt, st.t, jacobian=False)
    f0 = stepper.ws.grad - stepper.fext  # interactions excluded: they have not begun
    recorder.record(st, f0)
    wall0 = time.perf_counter()
    run = _Run(stepper, recorder, st, dt=dt, t_end=t_end, callback=callback)
    bar = None
    if progress:
        from tqdm.auto import tqdm

        bar = tqdm(total=t_end - st.t, unit="s", unit_scale=True, desc="simulate")
    try:
        run.loop(bar)
    finally:
        if bar is not None:
            bar.close()
    run.stats["wall_s"] = time.perf_counter() - wall0
    if stepper.rescue:  # only a run the stagnation fallback rescued has these
        run.stats["held_steps"] = stepper.n_held_steps
    if run.stall.budget_spent:  # only a run its CPU budget stopped has this
        run.stats["budget_spent"] = 1
    res = recorder.result(run.status, run.message, run.stats, run.st)
    if run.status != "success" and (opt.throw if throw is None else throw):
        err = SolverError(run.message, state=run.st)
        err.result = res
        raise err
    return res


def _checked_start(system, state0, dt, t_end):
    """(system, start state, dt, t_end) of :func:`simulate`, checked: a lone Rod becomes a
    one-rod system."""
    from .system import Rod

    if isinstance(system, Rod):
        system = RodSystem((system,))
    if not isinstance(system, RodSystem):
        raise InputError("system must be a knotmech.rod.RodSystem or Rod")
    st = system.initial_state() if state0 is None else state0
    if not isinstance(st, State) or st.q.shape != (system.n_dof,):
        raise InputError(f"state0 must be a State with q of shape ({system.n_dof},)")
    dt = float(check_positive("dt", dt, scalar=True))
    t_end = float(t_end)
    if not np.isfinite(t_end) or t_end < st.t:
        raise InputError(f"t_end must be finite and >= the start time {st.t:g}, got {t_end!r}")
    return system, st, dt, t_end


_FRAMES = ("times", "positions", "thetas", "reactions", "reaction_torques", "tension",
           "bending_moment", "twisting_moment")  # fmt: skip
_ENERGIES = ("stretch", "bend", "twist", "kinetic", "external", "interaction")


class _Recorder:
    """The frames of a :func:`simulate` run: :meth:`record` one state, :meth:`result` the
    :class:`Result`. Reactions are the residual on the constrained nodes and edges."""

    def __init__(self, stepper: Stepper):
        self.stepper = stepper
        system = stepper.system
        node_lists = [c.node_indices(system) for c in stepper.constraints]
        edge_lists = [c.edge_indices(system) for c in stepper.constraints]
        empty = np.zeros(0, dtype=np.int64)
        self.r_nodes = np.concatenate(node_lists) if node_lists else empty
        self.r_edges = np.concatenate(edge_lists) if edge_lists else empty
        self.frames = {k: [] for k in _FRAMES}
        self.energies = {k: [] for k in _ENERGIES}

    def record(self, state: State, residual: np.ndarray) -> None:
        """Append the frame of ``state`` (``residual``: f at that state, for the reactions)."""
        stepper, frames = self.stepper, self.frames
        system, ws, q = stepper.system, stepper.ws, state.q
        ws.frames(q, state.tangents, state.d1, state.ref_twist)
        frames["times"].append(state.t)
        frames["positions"].append(system.positions(q))
        frames["thetas"].append(system.thetas(q))
        frames["reactions"].append(residual[system.node_dofs[self.r_nodes]])
        frames["reaction_torques"].append(residual[system.edge_theta_dof[self.r_edges]])
        frames["tension"].append(ws.tension(q))
        mb, mt = ws.moments(q)
        frames["bending_moment"].append(mb)
        frames["twisting_moment"].append(mt)
        self._record_energies(state)

    def _record_energies(self, state: State) -> None:
        stepper, energies = self.stepper, self.energies
        system, q = stepper.system, state.q
        es, eb, et = stepper.ws.energies(q)
        energies["stretch"].append(es)
        energies["bend"].append(eb)
        energies["twist"].append(et)
        energies["kinetic"].append(0.5 * float(np.sum(system.mass * state.v**2)))
        energies["external"].append(sum(ld.energy(system, q, state.t) for ld in stepper.loads))
        energies["interaction"].append(sum(it.energy(system, q) for it in stepper.interactions))

    def _stack(self, name, shape):
        v = self.frames[name]
        return np.array(v) if v else np.zeros((0,) + shape)

    def result(self, status: str, message: str, stats: dict, final: State) -> Result:
        """The :class:`Result` of the recorded frames."""
        system, stack = self.stepper.system, self._stack
        return Result(
            status=status,
            message=message,
            stats=stats,
            times=np.array(self.frames["times"]),
            positions=stack("positions", (system.n_nodes, 3)),
            thetas=stack("thetas", (system.n_edges,)),
            reaction_nodes=self.r_nodes,
            reactions=stack("reactions", (self.r_nodes.size, 3)),
            reaction_edges=self.r_edges,
            reaction_torques=stack("reaction_torques", (self.r_edges.size,)),
            tension=stack("tension", (system.n_edges,)),
            bending_moment=stack("bending_moment", (system.n_stencils, 2)),
            twisting_moment=stack("twisting_moment", (system.n_stencils,)),
            energies={k: np.array(v) for k, v in self.energies.items()},
            final_state=final,
        )


class _Run:
    """The time loop of :func:`simulate`: step size control (halving on a failed step,
    doubling back after ``grow_after`` good ones), frames at multiples of ``save_every``,
    the strain and stall guards, the callback. ``status``, ``message``, ``stats`` and the
    last good state ``st`` are its outcome."""

    def __init__(self, stepper, recorder, st, *, dt, t_end, callback):
        opt = stepper.opt
        self.stepper, self.recorder, self.opt = stepper, recorder, opt
        self.st, self.dt, self.t_end, self.callback = st, dt, t_end, callback
        self.save_every = dt if opt.save_every is None else float(opt.save_every)
        self.stats = {"steps": 0, "newton_iterations": 0, "rejected_steps": 0, "wall_s": 0.0}
        self.dt_cur = dt if not np.isfinite(st.dt_next) else min(st.dt_next, dt)
        self.n_good = st.n_good
        self.k_save = int(np.floor(st.t / self.save_every + 1e-9)) + 1
        self.status, self.message = "success", f"reached t_end = {t_end:g} s"
        # largest edge strain of the failed attempts since the last step
        self.worst = (0, 0.0, st.t)
        stepper.last_iterate = None
        self.last_stalled = False  # the last rejected attempt stagnated
        self.stall = _StallGuard(opt, dt, st.t, time.process_time())

    def _fail(self, message: str) -> bool:
        self.status, self.message = "failed", message
        return True

    def loop(self, bar) -> None:
        """Step from ``st`` to ``t_end`` (or until a failure or the callback stops it)."""
        while self.st.t < self.t_end:
            st = self.st
            t_save = self.k_save * self.save_every
            target = min(t_save, self.t_end)
            gap = target - st.t
            hit = gap <= self.dt_cur * (1.0 + 1e-6)
            h = gap if hit else self.dt_cur
            why = self.stall.check(self.dt_cur, st.t)
            if why and not self._rescue() and self._fail(self._rescued_text(why)):
                break
            try:
                q_new, iters = self.stepper.step(st, h)
            except _StepFailed as exc:
                if self._rejected(exc, h):
                    break
                continue
            if self._strain_exceeded(q_new, h) or self._accept(q_new, iters, h, hit, bar):
                break
            if hit and target == t_save:
                self.k_save += 1

    def _rejected(self, exc: _StepFailed, h: float) -> bool:
        """Count a failed attempt and halve the step; True when that went below dt_min
        (the run then fails)."""
        opt, st = self.opt, self.st
        self.stall.last_reason = str(exc)
        self.stats["rejected_steps"] += 1
        if opt.max_strain is not None and self.stepper.last_iterate is not None:
            k, e = _worst_strain(self.stepper.system, self.stepper.last_iterate)
            if np.isfinite(e) and abs(e) > abs(self.worst[1]):
                self.worst = (k, e, st.t + h)
        self.dt_cur = 0.5 * min(self.dt_cur, h)
        self.n_good = 0
        self.last_stalled = exc.stalled
        if self.dt_cur >= opt.dt_min or self._rescue():
            return False
        if opt.max_strain is not None and not abs(self.worst[1]) <= opt.max_strain:
            # every attempt down to dt_min failed and Newton's iterates went beyond the
            # strain limit: the loads, not the step size, are the cause (numerics may
            # differ in how the attempts fail: a converged step beyond the limit or an
            # evaluation error on the way there)
            return self._fail(_strain_message(*self.worst, opt.max_strain, " (on the way)"))
        return self._fail(
            self._rescued_text(
                f"step failed at t = {st.t:.6g} s with dt = {2 * self.dt_cur:.3g} s < "
                f"2 dt_min ({exc}); last good state kept"
            )
        )

    def _rescue(self) -> bool:
        """Engage the stagnation fallback (``SolverOptions.rescue``) where the run would
        fail: the last rejected attempt stagnated, the fallback is not on yet, the stop is
        not the CPU budget, and an interaction holds a switch at the last good state (a
        dry :meth:`Stepper.would_hold`: with nothing to hold, the fallback's attempts
        would be the failed ones again). The run goes on from the last good state at the
        nominal dt; True when engaged."""
        stepper = self.stepper
        if not (self.opt.rescue and self.last_stalled and not stepper.rescue):
            return False
        if self.stall.budget_spent or not stepper.would_hold(self.st, self.dt):
            return False
        stepper.rescue = True
        self.stats["rescues"] = 1  # a count: a scene sums its phases' stats
        self.stats["rescue_t"] = float(self.st.t)
        self.dt_cur = self.dt
        self.n_good = 0
        self.stall.n_small = 0
        return True

    def _rescued_text(self, message: str) -> str:
        """``message`` of a failure, noting the stagnation fallback when it was on (not when
        the CPU budget stopped the run)."""
        if not self.stepper.rescue or self.stall.budget_spent:
            return message
        return (
            f"{message} (the stagnation fallback, engaged at t = {self.stats['rescue_t']:.6g} s, "
            f"did not recover the run)"
        )

    def _strain_exceeded(self, q_new, h: float) -> bool:
        """A converged step beyond ``max_strain``: True (the run fails)."""
        self.worst = (0, 0.0, self.st.t)
        if self.opt.max_strain is None:
            return False
        k_max, e_max = _worst_strain(self.stepper.system, q_new)
        if abs(e_max) <= self.opt.max_strain:
            return False
        return self._fail(_strain_message(k_max, e_max, self.st.t + h, self.opt.max_strain, ""))

    def _accept(self, q_new, iters: int, h: float, hit: bool, bar) -> bool:
        """Commit the converged step (interactions' end_step, the new State, its frame if
        it hit a save time); True when the callback stops the run."""
        st = self.st
        self.stats["steps"] += 1
        self.stats["newton_iterations"] += iters
        t_new = min(self.k_save * self.save_every, self.t_end) if hit else st.t + h
        self._grow_dt()
        for it in self.stepper.interactions:
            it.end_step(self.stepper.system, q_new, st.q, h)
        new = self._new_state(q_new, t_new, h)
        residual = self.stepper.f.copy()
        if bar is not None:
            bar.update(t_new - st.t)
        self.st = new
        if hit:
            self.recorder.record(new, residual)
        if self.callback is not None and self.callback(new):
            self.message = f"stopped by callback at t = {new.t:g} s"
            if not hit:
                self.recorder.record(new, residual)
            return True
        return False

    def _grow_dt(self) -> None:
        """After ``grow_after`` good steps a reduced step doubles back toward dt."""
        self.n_good += 1
        if self.dt_cur < self.dt and self.n_good >= self.opt.grow_after:
            self.dt_cur = min(2.0 * self.dt_cur, self.dt)
            self.n_good = 0

    def _new_state(self, q_new, t_new: float, h: float) -> State:
        """The State at the end of an accepted step of length ``h`` (velocity: the mean
        rate over the step; acceleration: its centred difference with the last step's)."""
        st, stepper = self.st, self.stepper
        ws = stepper.ws
        h_step = t_new - st.t
        v_new = (q_new - st.q) / h
        accel = None
        if np.isfinite(st.h_last):  # v is the mean rate over a step: centred difference
            accel = (v_new - st.v) / (0.5 * (h_step + st.h_last))
        return State(
            t=t_new,
            q=q_new,
            v=v_new,
            tangents=ws.tangents.copy(),
            d1=ws.d1.copy(),
            ref_twist=ws.ref_twist.copy(),
            dt_next=self.dt_cur,
            n_good=self.n_good,
            accel=accel,
            h_last=h_step,
            interactions=interaction_state(stepper.interactions),
            linear=stepper.linear_state(),
        )

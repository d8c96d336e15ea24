r"""Overhand knots pulled tight: pull force versus end-to-end length, loop size, snapshots.

Two parameter sets reproduce the two source experiments:

- :func:`imc_setup`, the implicit-contact-model paper (Choi, Tong & Jawed, "Implicit
  contact model for discrete elastic rods in knot tying", J. Appl. Mech. 88, 051010,
  2021; its option file): L = 1 m, 301 nodes, h = 1.6 mm, E = 0.18 MPa,
  :math:`\rho` = 1180 kg/m^3, Poisson 0.5, dt = 2.5 ms, contact distance tolerance
  :math:`\delta` = 0.5 mm, slip-speed tolerance :math:`\nu` = 1e-4 m/s, no gravity; wait 2 s,
  then both ends pulled apart at 6 mm/s each for 60 s; mu = 0.3.
- :func:`coated_setup`, the coated-rod paper (sec. 3-4, table 1): natural rubber,
  d = 1.59 mm, E = 1.83 MPa, the table-1 knot geometry, one end clamped and the other
  pulled at 200 mm/min; mu in {0.2, 0.5, 0.6, 0.7, 0.9} (0, 1, 4, 7, 13 % particles).
  The density is not given in the paper; 930 kg/m^3 (natural rubber) is assumed (inertia
  is negligible at these speeds).

The knot is the generator :func:`knotmech.scenes.curves.overhand_knot` relaxed under
rod-rod contact (:class:`knotmech.rod.contact.RodContact`: the smooth penalty of the
implicit contact model with the regularised friction of the coated-rod paper, eqs. 10-12).
The rod is naturally straight (the knot starts stressed, as in the experiments). The pull
force is the axial reaction at the gripped ends; its normalised form is :math:`F h^2/B`
with :math:`B = E\pi h^4/4` (coated-rod paper, Fig. 10).
At the end the knot type of the centreline (closed far away) is compared with the start
(:mod:`knotmech.scenes.topology`): a strand passing through another would change it.
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, field, replace

import numpy as np

from knotmech import rod
from knotmech.errors import InputError, check_count, check_nonnegative, check_positive
from knotmech.materials import IMC_DENSITY
from knotmech.rod.contact import RodContact
from knotmech.rod.friction import AnchorFriction, SmoothFriction
from knotmech.scenes._common import (
    check_memory,
    check_pull_step,
    check_run_size,
    fail,
    frames_bytes,
    measured_strain,
)
from knotmech.scenes._scene import RunControl, Scene
from knotmech.scenes.curves import (
    OVERHAND_COATED_TABLE1,
    OVERHAND_IMC,
    KnotCurve,
    loop_metrics,
    overhand_knot,
)
from knotmech.scenes.topology import knot_invariant

__all__ = [
    "OverhandSetup",
    "OverhandResult",
    "OverhandScene",
    "imc_setup",
    "coated_setup",
    "overhand",
    "inversion_points",
]

#: Friction coefficients fitted in the coated-rod paper for 0, 1, 4, 7, 13 % particles.
COATED_MU = (0.2, 0.5, 0.6, 0.7, 0.9)


@dataclass(frozen=True)
class OverhandSetup:
    """Physical and numerical parameters of an overhand-knot pull (SI units).

    Attributes
    ----------
    rod_length, rod_radius : float [m]
    youngs_modulus : float [Pa]
    density : float [kg/m^3]
    poisson_ratio : float
    end_to_end_length, braid_length : float [m]
        Start shape (see :func:`knotmech.scenes.curves.overhand_knot`).
    n_nodes : int
    pull_speed : float [m/s]
        Speed of each pulled end.
    pull_both_ends : bool
        True: both ends move apart at ``pull_speed``; False: the first end is clamped.
    wait_time, pull_time : float [s]
        Relaxation with the ends held, then pulling.
    dt : float [s]
        Nominal time step (the solver halves it on Newton failure).
    contact_distance : float [m]
        :math:`\\delta`, the range of the contact penalty; its sharpness is :math:`15/\\delta`.
    slip_speed : float or None [m/s]
        :math:`\\nu`, the speed over which friction rises from 0 to :math:`\\mu N`; None: the
        coated-rod paper's stick-slip weight (k = 50/h, c = 0.15 h, eq. 12).
    contact_stiffness : float or None [N/m]
        :math:`K_c`; None: :math:`2.5 B/h^3` (overlap about 0.2 h under a contact force
        :math:`B/h^2`).
    source : str
    """

    rod_length: float
    rod_radius: float
    youngs_modulus: float
    density: float
    poisson_ratio: float
    end_to_end_length: float
    braid_length: float
    n_nodes: int
    pull_speed: float
    pull_both_ends: bool
    wait_time: float
    pull_time: float
    dt: float
    contact_distance: float
    slip_speed: float | None
    contact_stiffness: float | None = None
    source: str = ""

    @property
    def bending_stiffness(self) -> float:
        """B = E pi h^4 / 4 [N m^2]."""
        return self.youngs_modulus * np.pi * self.rod_radius**4 / 4


def imc_setup(turns: int = 1, **overrides) -> OverhandSetup:
    """Parameters of the implicit-contact-model paper's knot tying (see module docstring)."""
    n = check_count("turns", turns, 1, 4)  # OVERHAND_IMC's rows
    e2e, b = OVERHAND_IMC[n]
    base = OverhandSetup(
        rod_length=1.0,
        rod_radius=1.6e-3,
        youngs_modulus=0.18e6,
        density=IMC_DENSITY,
        poisson_ratio=0.5,
        end_to_end_length=e2e,
        braid_length=b,
        n_nodes=301,
        pull_speed=6e-3,
        pull_both_ends=True,
        wait_time=2.0,
        pull_time=60.0,
        dt=2.5e-3,
        contact_distance=5e-4,
        slip_speed=1e-4,
        source="implicit contact model (Choi, Tong & Jawed 2021)",
    )
    return replace(base, **overrides)


def coated_setup(turns: int = 1, **overrides) -> OverhandSetup:
    """Parameters of the coated-rod paper's knot pulls (table 1, natural rubber)."""
    n = check_count("turns", turns, 1, 4)  # table 1's rows
    t, b, lo, e2e = OVERHAND_COATED_TABLE1[n]
    L = 2 * t + 2 * b + lo
    h = 0.5 * 1.59e-3
    pull_speed = 0.200 / 60.0
    # pull until the knot is tight: at most the loop length, at the paper's speed
    base = OverhandSetup(
        rod_length=L,
        rod_radius=h,
        youngs_modulus=1.83e6,
        density=930.0,
        poisson_ratio=0.5,
        end_to_end_length=e2e,
        braid_length=b,
        n_nodes=int(round(L / 0.0015)) + 1,
        pull_speed=pull_speed,
        pull_both_ends=False,
        wait_time=1.0,
        pull_time=0.9 * lo / pull_speed,
        dt=2.5e-3,
        contact_distance=0.3125 * h,
        slip_speed=None,
        source="coated-rod paper, table 1",
    )
    return replace(base, **overrides)


@dataclass
class OverhandResult:
    """Recorded curves of an overhand-knot pull.

    Attributes
    ----------
    turns, mu : int, float
    setup : OverhandSetup
    times : (n_frames,) [s]
    end_to_end : (n_frames,) [m]  distance between the two ends
    pull_force : (n_frames,) [N]  mean axial reaction of the two gripped ends
    loop_diameter, loop_length, braid_length : (n_frames,) [m]  from
        :func:`knotmech.scenes.curves.loop_metrics` (NaN when no braid is detected)
    snapshot_times : (k,) [s]; snapshots : (k, n_nodes, 3) [m]
    knot_start, knot_end : str  knot names of the closed centreline (e.g. "3_1")
    alexander_start, alexander_end : tuple of int
    status, message : str  solver outcome ("failed" also when the rod's strain exceeded
        50 %); stats : dict (steps, newton_iterations, wall_s)
    warnings : list of str  one line each (a strain above 10 %)
    friction : str  rod-rod friction law, "imc" or "anchor"
    """

    turns: int
    mu: float
    setup: OverhandSetup
    times: np.ndarray
    end_to_end: np.ndarray
    pull_force: np.ndarray
    loop_diameter: np.ndarray
    loop_length: np.ndarray
    braid_length: np.ndarray
    snapshot_times: np.ndarray
    snapshots: np.ndarray
    knot_start: str
    knot_end: str
    alexander_start: tuple
    alexander_end: tuple
    status: str
    message: str
    stats: dict = field(default_factory=dict)
    warnings: list = field(default_factory=list)
    friction: str = "imc"

    @property
    def knot_preserved(self) -> bool:
        """True if the Alexander polynomial is the same at the start and at the end."""
        return self.alexander_start == self.alexander_end

    @property
    def end_to_end_shortening(self) -> np.ndarray:
        """e = L - D [m], the rod length held in the knot (Jawed et al. 2015)."""
        return self.setup.rod_length - self.end_to_end

    @property
    def normalized_force(self) -> np.ndarray:
        """F h^2 / B (coated-rod paper, Fig. 10)."""
        return self.pull_force * self.setup.rod_radius**2 / self.setup.bending_stiffness

    def to_dict(self) -> dict:
        """Plain-JSON dictionary (curves as lists; snapshots left out)."""
        out = {
            "scene": "overhand",
            "turns": self.turns,
            "mu": self.mu,
            "friction": self.friction,
            "setup": asdict(self.setup),
            "status": self.status,
            "message": self.message,
            "warnings": list(self.warnings),
            "stats": {k: float(v) for k, v in self.stats.items()},
            "knot_start": self.knot_start,
            "knot_end": self.knot_end,
            "knot_preserved": self.knot_preserved,
        }
        for name in ("times", "end_to_end", "pull_force", "loop_diameter", "loop_length"):
            out[name] = [None if not np.isfinite(v) else float(v) for v in getattr(self, name)]
        return out


def _start_curve(setup: OverhandSetup, turns: int) -> KnotCurve:
    return overhand_knot(
        turns,
        rod_length=setup.rod_length,
        rod_radius=setup.rod_radius,
        end_to_end_length=setup.end_to_end_length,
        braid_length=setup.braid_length,
        n_nodes=setup.n_nodes,
    )


def overhand(
    turns: int = 1,
    mu: float = 0.3,
    *,
    params="imc",
    n_frames: int = 100,
    n_snapshots: int = 6,
    progress: bool = False,
    options: rod.SolverOptions | None = None,
    max_node_steps: float | None = None,
    friction: str = "imc",
    **overrides,
) -> OverhandResult:
    r"""Pull an overhand knot with ``turns`` braid turns tight at constant speed.

    Parameters
    ----------
    turns : int
        Braid turns n = 1 .. 4 (the closed knot is the (2, 2n+1) torus knot).
    mu : float
        Rod-rod friction coefficient (>= 0).
    params : {"imc", "coated"} or OverhandSetup
        Parameter set; ``overrides`` replace fields of the named set (e.g.
        ``n_nodes=151, pull_time=10, dt=5e-3`` for a quick run).
    n_frames : int
        Number of recorded frames (>= 2).
    n_snapshots : int
        Number of stored node arrays, evenly spread in time (>= 1).
    progress : bool
        Show a progress bar.
    options : knotmech.rod.SolverOptions, optional
        Solver options (``save_every`` is set from ``n_frames``; ``throw`` defaults to False
        so that a failed run returns what it recorded, with ``status = "failed"``).
    max_node_steps : float, optional
        Bound on (t_end/dt) x nodes, checked before the rod is built (default
        :data:`knotmech.scenes._common.MAX_NODE_STEPS`; ``inf`` lifts it).
    friction : {"imc", "anchor"}
        Rod-rod friction law: ``"imc"`` (default) the regularised law of the implicit
        contact model and the coated-rod paper (:class:`~knotmech.rod.friction.
        SmoothFriction`, the papers' own, which these scenes reproduce); ``"anchor"`` the
        elasto-plastic anchor that truly sticks (:class:`~knotmech.rod.friction.
        AnchorFriction`, mu_s = mu_k = ``mu``, with the library's defaults since issue 24:
        cap floor :data:`~knotmech.rod.friction.CAP_FLOOR` and the contact's path
        tunnelling guard; ``validation/_overhand_mu_laws.py`` compares the two laws).

    Returns
    -------
    OverhandResult

    Notes
    -----
    The ends are the first and last two nodes (and the end edges' twist), held during
    ``wait_time`` and then moved along the end-to-end axis at ``pull_speed``.
    Cost: the full implicit-contact-model case (301 nodes, 62 s, dt = 2.5 ms) needs about
    24 800 steps and about 39 000 Newton iterations, about 30 s on one core
    (``benchmarks/overhand.py`` measures it). Quick runs: 151 nodes, 5 ms,
    30 mm/s reproduce the Jawed law within 20 % (see the slow tests).
    """
    return OverhandScene(
        turns,
        mu,
        params=params,
        overrides=overrides,
        friction=friction,
        n_snapshots=n_snapshots,
        control=RunControl(
            dt=None,
            n_frames=n_frames,
            options=options,
            progress=progress,
            max_node_steps=max_node_steps,
        ),
    ).run()


def _overhand_setup(n: int, params, overrides) -> OverhandSetup:
    """The parameter set ``params`` with ``overrides``, checked."""
    if isinstance(params, OverhandSetup):
        setup = replace(params, **overrides)
    elif params == "imc":
        setup = imc_setup(n, **overrides)
    elif params == "coated":
        setup = coated_setup(n, **overrides)
    else:
        raise InputError(f"params must be 'imc', 'coated' or an OverhandSetup, got {params!r}")
    for name in ("pull_speed", "dt", "contact_distance"):
        check_positive(name, getattr(setup, name))
    for name in ("wait_time", "pull_time"):
        check_nonnegative(name, getattr(setup, name))
    return setup


def _friction_law(friction: str, mu: float, setup: OverhandSetup):
    """The rod-rod friction object of ``friction`` ("imc" or "anchor")."""
    if friction not in ("imc", "anchor"):
        raise InputError(f"friction must be 'imc' or 'anchor', got {friction!r}")
    if friction == "anchor":
        return AnchorFriction(mu_static=mu)
    if setup.slip_speed is None:
        return SmoothFriction(mu)
    nu = float(check_positive("slip_speed", setup.slip_speed, scalar=True))
    return SmoothFriction(mu, sharpness=10.0 / nu, threshold=0.5 * nu)


class OverhandScene(Scene):
    """An overhand knot pulled tight: the phases of :func:`overhand` (one solver call: the
    wait and the pull are in the grips' path)."""

    def __init__(self, turns, mu, *, params, overrides, friction, n_snapshots, control):
        self.turns, self.mu_arg, self.params, self.overrides = turns, mu, params, overrides
        self.friction, self.n_snapshots, self.control = friction, n_snapshots, control

    def setup(self) -> None:
        """Turns, mu, the parameter set, frames and the cost checked."""
        self.n = n = check_count("turns", self.turns, 1, 4)
        self.mu = float(check_nonnegative("mu", self.mu_arg, scalar=True))
        self.s = s = _overhand_setup(n, self.params, self.overrides)
        c = self.control
        check_count("n_frames", c.n_frames, 2)
        check_count("n_snapshots", self.n_snapshots, 1)
        check_run_size(
            n_nodes=s.n_nodes,
            t_end=s.wait_time + s.pull_time,
            dt=s.dt,
            max_node_steps=c.max_node_steps,
            hint="use a larger dt, fewer nodes or a shorter pull",
        )
        check_memory(
            frames_bytes(c.n_frames, s.n_nodes),
            what=f"{int(c.n_frames)} recorded frames of {s.n_nodes} nodes",
            hint="use fewer nodes or frames (n_frames)",
        )
        check_pull_step(s.dt, speed=s.pull_speed, edge_length=s.rod_length / (int(s.n_nodes) - 1))

    def build(self):
        """The rod on the start curve, the grips and the rod-rod contact."""
        s = self.s
        self.x0 = x0 = _start_curve(s, self.n).nodes
        N = len(x0)
        self.h = h = s.rod_radius
        r = rod.Rod(
            positions=x0,
            radius=h,
            youngs_modulus=s.youngs_modulus,
            density=s.density,
            poisson_ratio=s.poisson_ratio,
            natural="straight",
        )
        self.system = rod.RodSystem([r])
        self.axis = (x0[-1] - x0[0]) / np.linalg.norm(x0[-1] - x0[0])
        self.constraints = self._grips(x0, N)
        friction = _friction_law(self.friction, self.mu, s)
        kc = (
            s.contact_stiffness
            if s.contact_stiffness is not None
            else 2.5 * s.bending_stiffness / h**3
        )
        self.contact = RodContact(
            stiffness=kc,
            sharpness=15.0 / s.contact_distance,
            friction=friction if self.mu > 0 else None,
        )
        return self.system

    def _grips(self, x0, N) -> list:
        """The right end pulled along the end-to-end axis after the wait; the left end
        pulled the other way or clamped."""
        left0, right0 = x0[:2].copy(), x0[-2:].copy()
        v, tw, axis = self.s.pull_speed, self.s.wait_time, self.axis

        def shift(t):
            return v * max(t - tw, 0.0) * axis

        constraints = [
            rod.MovingNodes([N - 2, N - 1], path=lambda t: right0 + shift(t)),
            rod.Clamp(edges=[0, N - 2]),
        ]
        if self.s.pull_both_ends:
            constraints.append(rod.MovingNodes([0, 1], path=lambda t: left0 - shift(t)))
        else:
            constraints.append(rod.Clamp(nodes=[0, 1]))
        return constraints

    def run_phases(self, system) -> None:
        """One solver call: wait, then pull."""
        s, c = self.s, self.control
        t_end = s.wait_time + s.pull_time
        base = c.options if c.options is not None else rod.SolverOptions(throw=False, rtol=1e-6)
        opts = replace(base, save_every=t_end / (int(c.n_frames) - 1))
        self.res = rod.simulate(
            system,
            t_end=t_end,
            dt=s.dt,
            constraints=self.constraints,
            interactions=[self.contact],
            options=opts,
            progress=c.progress,
        )

    def measure(self, system) -> OverhandResult:
        """Pull force, end-to-end distance, loop metrics, snapshots and knot type."""
        res, s, h = self.res, self.s, self.h
        pos = np.asarray(res.positions)
        times = np.asarray(res.times)
        force = self._force(res, len(self.x0))
        metrics = [loop_metrics(p, rod_radius=h) for p in pos]
        k_snap = np.unique(
            np.linspace(0, len(times) - 1, int(self.n_snapshots)).round().astype(int)
        )
        reason, warnings = measured_strain(
            res.tension, s.youngs_modulus * np.pi * h * h, warned=False
        )
        status, message = fail(res.status, res.message, reason)
        inv0 = knot_invariant(self.x0)
        try:
            inv1 = knot_invariant(pos[-1])
        except InputError:  # projections disagree: strands overlap in 3-D
            inv1 = None
        return OverhandResult(
            turns=self.n,
            mu=self.mu,
            setup=s,
            times=times,
            end_to_end=np.linalg.norm(pos[:, -1] - pos[:, 0], axis=1),
            pull_force=force,
            loop_diameter=np.array([m["loop_diameter"] for m in metrics]),
            loop_length=np.array([m["loop_length"] for m in metrics]),
            braid_length=np.array([m["braid_length"] for m in metrics]),
            snapshot_times=times[k_snap],
            snapshots=pos[k_snap],
            knot_start=inv0.name,
            knot_end=inv1.name if inv1 is not None else "?",
            alexander_start=inv0.alexander,
            alexander_end=inv1.alexander if inv1 is not None else (),
            status=status,
            message=message,
            stats=dict(res.stats),
            warnings=warnings,
            friction=self.friction,
        )

    def _force(self, res, N) -> np.ndarray:
        """Mean of the two grips' reactions along the end-to-end axis [N]."""
        rn = list(np.asarray(res.reaction_nodes))
        react = np.asarray(res.reactions)
        axis = self.axis
        right = react[:, [rn.index(N - 2), rn.index(N - 1)], :].sum(axis=1) @ axis
        left = -(react[:, [rn.index(0), rn.index(1)], :].sum(axis=1) @ axis)
        return 0.5 * (right + left)


def inversion_points(end_to_end, force, *, window: int = 9, drop: float = 0.2, span: float = 0.02):
    r"""End-to-end lengths at which the pull force drops suddenly (the knot's inversion).

    The force is smoothed by a centred moving average over ``window`` frames (this removes
    the stick-slip ripple); an *inversion* is a local maximum of the smoothed force after
    which it falls by more than ``drop`` (relative) within an end-to-end increase of
    ``span`` :math:`\times` the total range pulled (coated-rod paper, sec. 4: "a sudden
    drop in pull force can be observed at the inversion point").

    Parameters
    ----------
    end_to_end : (n,) array [m]
        Increasing end-to-end length.
    force : (n,) array [N]
    window : int
        Frames of the moving average (odd, >= 1).
    drop : float
        Relative fall that counts as an inversion (0 to 1).
    span : float
        Largest end-to-end increase over which the fall must happen, as a fraction of
        the range pulled (0 to 1).

    Returns
    -------
    (k,) array [m]
        End-to-end lengths at the force peaks before each drop (empty: no inversion).
    """
    e = np.asarray(end_to_end, dtype=float)
    f = np.asarray(force, dtype=float)
    if e.shape != f.shape or e.ndim != 1:
        raise InputError("end_to_end and force must be 1-D arrays of the same length")
    w = int(window)
    if w < 1 or w % 2 == 0:
        raise InputError(f"window must be an odd integer >= 1, got {window!r}")
    if not (0 < drop < 1) or not (0 < span <= 1):
        raise InputError("drop must lie in (0, 1) and span in (0, 1]")
    if f.size < w + 2:
        return np.zeros(0)
    fs = np.convolve(f, np.ones(w) / w, mode="same")
    h = w // 2
    if h:
        fs[:h] = np.nan
        fs[-h:] = np.nan
    de = span * (np.nanmax(e) - np.nanmin(e))
    peaks = []
    i = h
    n = f.size
    while i < n - h:
        if not np.isfinite(fs[i]) or fs[i] <= 0:
            i += 1
            continue
        ahead = np.nonzero((e > e[i]) & (e <= e[i] + de) & np.isfinite(fs))[0]
        if (
            ahead.size
            and np.min(fs[ahead]) < (1 - drop) * fs[i]
            and fs[i] >= np.nanmax(fs[max(h, i - w) : i + 1])
        ):
            peaks.append(e[i])
            i = int(ahead[-1]) + 1
        else:
            i += 1
    return np.array(peaks)

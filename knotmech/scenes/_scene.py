r"""The shape every DER scene shares: build rods (and a post), run phases, measure.

A scene is three steps, and only the first is specific to a knot:

1. **build**: a centreline per rod (a :class:`~knotmech.scenes.curves.KnotCurve` or a node
   array), the rods' material, the contacts (:func:`rod_contact` for rod-rod contact with
   sticking friction, :func:`post_contact` for a rigid post);
2. **run phases** on a :class:`SceneRun`: each phase (``"settle"``, ``"load"``, ``"pull"``,
   ``"hold"``) is one :func:`knotmech.rod.simulate` call that resumes from the previous
   phase's last state, with its own loads, constraints and nominal step; frames, reactions
   and solver statistics are concatenated, a failed phase stops the run (status
   ``"failed"``, its message, the last good state kept) and a watcher (the topology or
   distance check of the knot) is called after every accepted step;
3. **measure** from the concatenated frames (pull force at a gripped end, end draw-in,
   invariants at the start and the end).

The loads and moving grips every scene needs are written once here: :class:`RampedEndLoad`
(a dead load on one node, ramped), :func:`grip_path` (a gripped end moved at constant speed
along a direction after a delay).

Every scene is a :class:`Scene`: its parameters arrive as small frozen option objects
(:class:`RunControl` for the solver and the frames, one or two of the scene's own), and
:meth:`Scene.run` calls its phases in order, each a short method: ``setup`` (inputs checked,
the cost bounded, before anything is allocated), ``build`` (the rods, the contacts, a
:class:`SceneRun`), ``run_phases`` (settle, load, pull or hold), ``measure`` (the result,
with its status checked). The post hitches (:mod:`knotmech.scenes._hitch`), ``capstan``,
``bend`` and ``centreline`` run so; ``overhand`` and ``pinch`` keep their own one-call
solver runs (see docs/notes/knots.md).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field, replace

import numpy as np

from knotmech import rod
from knotmech.errors import InputError, check_nonnegative, check_positive
from knotmech.rod.contact import Cylinder, CylinderContact, RodContact
from knotmech.rod.friction import AnchorFriction

__all__ = [
    "Scene",
    "RunControl",
    "RampedEndLoad",
    "grip_path",
    "rod_contact",
    "post_contact",
    "SceneRun",
    "Phase",
]


@dataclass(frozen=True)
class RunControl:
    """How a scene runs, apart from its physics: step, frames, solver options, limits.

    Attributes
    ----------
    dt : float or None [s]
        Nominal step (None: the scene's default).
    n_frames : int
        Frames recorded (the scene's meaning: of the whole run or of its pull).
    options : knotmech.rod.SolverOptions or None
    progress : bool
        Show a progress bar.
    max_node_steps : float or None
        Bound on (t_end/dt) x nodes checked before the run (None:
        :data:`knotmech.scenes._common.MAX_NODE_STEPS`; ``inf`` lifts it).
    """

    dt: float | None = None
    n_frames: int = 100
    options: rod.SolverOptions | None = None
    progress: bool = False
    max_node_steps: float | None = None


class Scene:
    """A DER experiment as phases; a subclass writes the four steps of :meth:`run`.

    1. :meth:`setup`: check the inputs and bound the cost (InputError, nothing allocated);
    2. :meth:`build`: the rod system and contacts, returned as a :class:`SceneRun`;
    3. :meth:`run_phases`: settle, load, pull or hold on that run (a failed phase stops it:
       status ``"failed"`` with the phase's name and reason, the last good state kept);
    4. :meth:`measure`: the result object, its status checked against what the scene
       simulates.
    """

    def setup(self) -> None:
        """Check the inputs and the cost before anything is allocated."""

    def build(self) -> SceneRun:
        """The rods, contacts and the :class:`SceneRun` the phases run on."""
        raise NotImplementedError

    def run_phases(self, run: SceneRun) -> None:
        """Run the scene's phases on ``run``."""
        raise NotImplementedError

    def measure(self, run: SceneRun):
        """The scene's result from what ``run`` recorded."""
        raise NotImplementedError

    def run(self):
        """setup, build, run_phases, measure; returns the scene's result."""
        self.setup()
        run = self.build()
        self.run_phases(run)
        return self.measure(run)


@dataclass(frozen=True)
class RampedEndLoad:
    """Dead force on one node, ramped linearly from 0 to ``force`` over [delay, delay + ramp].

    A load for :func:`knotmech.rod.simulate` (same interface as ``knotmech.rod.NodeForce``).

    Parameters
    ----------
    node : int
        Global node index.
    force : (3,) array [N]
    ramp_time : float [s]
        Duration of the linear ramp (> 0).
    delay : float [s]
        Start of the ramp (absolute time).
    """

    node: int
    force: np.ndarray
    ramp_time: float
    delay: float = 0.0

    def _w(self, t) -> float:
        return min(max((t - self.delay) / self.ramp_time, 0.0), 1.0)

    def apply(self, system, t, q, q_old, dt, force, jac_diag) -> None:
        force[system.node_dofs[self.node]] += self._w(t) * np.asarray(self.force)

    def energy(self, system, q, t=np.inf) -> float:
        return float(-self._w(t) * np.dot(q[system.node_dofs[self.node]], self.force))


def grip_path(start, direction, speed: float, t_start: float = 0.0):
    """Path ``t -> start + speed max(t - t_start, 0) direction`` for :class:`rod.MovingNodes`.

    Parameters
    ----------
    start : (k, 3) array [m]
        Positions of the gripped nodes at ``t_start``.
    direction : (3,) array
        Pull direction (normalised here).
    speed : float [m/s]
    t_start : float [s]
    """
    x0 = np.array(start, dtype=float)
    u = np.asarray(direction, dtype=float)
    u = u / np.linalg.norm(u)
    v = float(check_nonnegative("pull_speed", speed, scalar=True))

    def path(t):
        return x0 + u * v * max(t - t_start, 0.0)

    return path


def _mu_pair(name: str, mu_static, mu_kinetic) -> tuple[float, float]:
    """(mu_s, mu_k) checked: both >= 0, mu_k <= mu_s (``mu_kinetic`` None: mu_s);
    ``name`` is how the user gave mu_s."""
    ms = float(check_nonnegative(name, mu_static, scalar=True))
    if mu_kinetic is None:
        return ms, ms
    mk = float(check_nonnegative("mu_kinetic", mu_kinetic, scalar=True))
    if mk > ms:
        raise InputError(f"mu_kinetic must be <= {name} ({ms:g}), got {mk:g}")
    return ms, mk


def rod_contact(
    *, rod_diameter: float, force_scale: float, mu_static: float, mu_kinetic=None, width=0.05
):
    r"""Rod-rod contact with sticking (anchor) friction, sized for a force scale.

    Penalty stiffness :math:`K_c = 20 F/d` (overlap about 2.5 % of d under ``force_scale``),
    sharpness :math:`k = 15/(w d)` with w = ``width`` (0.05: the clove-hitch scene's choice);
    friction :class:`knotmech.rod.AnchorFriction` (true sticking below :math:`\mu_s N`,
    sliding at :math:`\mu_k N`; the library's default cap floor and, through
    :class:`knotmech.rod.RodContact`, the path tunnelling guard), none when
    :math:`\mu_s = 0`.

    Parameters
    ----------
    rod_diameter : float [m]
    force_scale : float [N]
        Largest contact force expected (the largest load of the scene).
    mu_static, mu_kinetic : float
        Static and kinetic rod-rod coefficients (``mu_kinetic`` None: equal to mu_s).
    width : float
        Range of the penalty in rod diameters (its force rises over about w d).
    """
    d = float(check_positive("rod_diameter", rod_diameter, scalar=True))
    f = float(check_positive("force_scale", force_scale, scalar=True))
    ms, mk = _mu_pair("mu_rod_rod", mu_static, mu_kinetic)
    fr = AnchorFriction(mu_static=ms, mu_kinetic=mk) if ms > 0 else None
    w = float(check_positive("width", width, scalar=True))
    return RodContact(stiffness=20.0 * f / d, sharpness=15.0 / (w * d), friction=fr)


def post_contact(
    *,
    post_diameter: float,
    rod_diameter: float,
    force_scale: float,
    mu_static,
    mu_kinetic=None,
    stiffness: float | None = None,
    surface_friction: bool = True,
):
    r"""Rigid post on the z axis through the origin, with sticking friction on the rod surface.

    Stiffness :math:`K = 200 F/(R d)` (R = (D + d)/2; ``stiffness`` overrides it),
    sharpness 400/d, tangential stiffness K: the clove-hitch scene's choice.
    ``surface_friction`` False applies the friction at the centreline (the ideal rope's
    :math:`e^{\mu\theta}`) instead of the rod surface.
    """
    D = float(check_positive("post_diameter", post_diameter, scalar=True))
    d = float(check_positive("rod_diameter", rod_diameter, scalar=True))
    f = float(check_positive("force_scale", force_scale, scalar=True))
    ms, mk = _mu_pair("mu_rod_post", mu_static, mu_kinetic)
    K = 200.0 * f / (0.5 * (D + d) * d) if stiffness is None else float(stiffness)
    post = Cylinder(point=(0.0, 0.0, 0.0), axis=(0.0, 0.0, 1.0), radius=0.5 * D)
    return CylinderContact(
        (post,),
        stiffness=K,
        sharpness=400.0 / d,
        friction=AnchorFriction(mu_static=ms, mu_kinetic=mk, tangential_stiffness=K),
        surface_friction=bool(surface_friction),
        rod_radius=0.5 * d,
    )


@dataclass
class Phase:
    """What one phase of a scene ran: name, [t0, t1] [s], status and frame range.

    ``start_reactions`` maps each node constrained in the phase to the static reaction
    [N] the solver reports at the phase's start (its frame 0, not kept in the run's
    frames: the previous phase's last frame stands there).
    """

    name: str
    t0: float
    t1: float
    status: str
    message: str
    frames: tuple
    start_reactions: dict = field(default_factory=dict)


@dataclass
class SceneRun:
    """Runs the phases of a scene on one rod system and concatenates what they record.

    Parameters
    ----------
    system : knotmech.rod.RodSystem
    interactions : sequence
        Contacts shared by every phase (their friction state carries over).
    options : knotmech.rod.SolverOptions, optional
        Base options (``throw`` is forced False: a failed phase is reported, not raised).
        Their ``max_cpu_s`` is the CPU budget of the whole run: each phase gets what the
        earlier ones left; a run that spends it fails with :attr:`over_budget` set (a scene
        gives no verdict from it).
    watch : callable(positions) -> str or None, optional
        Called after every accepted step with the (n_nodes, 3) positions; a returned string
        stops the run with status ``"failed"`` and that message (e.g. strands passed
        through each other).
    progress : bool
    """

    system: rod.RodSystem
    interactions: tuple = ()
    options: rod.SolverOptions | None = None
    watch: object = None
    progress: bool = False
    state: rod.State | None = None
    status: str = "success"
    message: str = ""
    phases: list = field(default_factory=list)
    times: list = field(default_factory=list)
    positions: list = field(default_factory=list)
    reactions: dict = field(default_factory=dict)
    tension: np.ndarray | None = None
    tensions: list = field(default_factory=list)
    stats: dict = field(default_factory=dict)
    live: rod.State | None = None
    cpu0: float = field(init=False, default=0.0)  # [s] process CPU time at the start
    over_budget: bool = False

    def __post_init__(self):
        self.cpu0 = time.process_time()
        self.interactions = tuple(self.interactions)
        base = self.options if self.options is not None else rod.SolverOptions(rtol=1e-6)
        self.options = replace(base, throw=False)
        if self.state is None:
            self.state = self.system.initial_state()
        self.times.append(float(self.state.t))
        self.positions.append(self.system.positions(self.state.q))

    @property
    def ok(self) -> bool:
        """True while every phase so far succeeded."""
        return self.status == "success"

    @property
    def t(self) -> float:
        """Current time [s]."""
        return float(self.state.t)

    def phase(
        self,
        name: str,
        duration: float,
        *,
        dt: float,
        loads=(),
        constraints=(),
        save_every: float | None = None,
        stop=None,
    ) -> bool:
        """Run one phase for ``duration`` [s] from the current state; False if it failed.

        Parameters
        ----------
        name : str
        duration : float [s]
        dt : float [s]
            Nominal step of this phase.
        loads, constraints : sequences for :func:`knotmech.rod.simulate`
            Times inside them are absolute (the phase starts at :attr:`t`).
        save_every : float [s], optional
            Frame interval (default ``duration / 50``).
        stop : callable(positions) -> bool, optional
            Ends the phase early (successfully) when it returns True.

        Returns
        -------
        bool
            True if the phase ran to its end (or to ``stop``).
        """
        if not self.ok:
            return False
        dur = float(check_positive(f"{name} duration", duration, scalar=True))
        t0 = self.t
        every = (
            dur / 50
            if save_every is None
            else float(check_positive("save_every", save_every, scalar=True))
        )
        opts = replace(self.options, save_every=every)
        budget = self.options.max_cpu_s
        if budget is not None:
            left = budget - (time.process_time() - self.cpu0)
            if left <= 0:
                return self._out_of_budget(name, budget)
            opts = replace(opts, max_cpu_s=left)
        verdict = {"msg": None}

        def callback(state):
            self.live = state
            x = self.system.positions(state.q)
            if self.watch is not None:
                msg = self.watch(x)
                if msg:
                    verdict["msg"] = msg
                    return True
            return bool(stop(x)) if stop is not None else False

        res = rod.simulate(
            self.system,
            self.state,
            t_end=t0 + dur,
            dt=float(check_positive("dt", dt, scalar=True)),
            loads=list(loads),
            constraints=list(constraints),
            interactions=list(self.interactions),
            options=opts,
            progress=self.progress,
            callback=callback,
        )
        k0 = len(self.times)
        start = self._record(res)
        status, message = res.status, res.message
        if verdict["msg"]:
            status, message = "failed", f"{name}: {verdict['msg']}"
        elif res.stats.get("budget_spent"):
            message = f"{name}: {self._budget_text(budget)}"
            self.over_budget = True
        elif status != "success":
            message = f"{name}: {message}"
        self.phases.append(Phase(name, t0, self.t, status, message, (k0, len(self.times)), start))
        if status != "success":
            self.status, self.message = status, message
            return False
        return True

    def _budget_text(self, budget: float) -> str:
        return (
            f"stopped at t = {self.t:.6g} s: the run spent its CPU budget of {budget:g} s "
            "(max_cpu_s, over all its phases); last good state kept"
        )

    def _out_of_budget(self, name: str, budget: float) -> bool:
        """Fail ``name`` before it starts: the earlier phases spent the budget."""
        msg = f"{name}: {self._budget_text(budget)}"
        self.over_budget = True
        self.phases.append(Phase(name, self.t, self.t, "failed", msg, (len(self.times),) * 2, {}))
        self.status, self.message = "failed", msg
        return False

    def _record(self, res) -> dict:
        """Append a phase's frames, reactions, tensions and statistics to the run's, and
        resume from its last state; returns the static reactions at the phase's start."""
        k0 = len(self.times)
        tt = np.asarray(res.times)[1:]
        self.times.extend(tt.tolist())
        self.positions.extend(list(np.asarray(res.positions)[1:]))
        rn = np.asarray(res.reaction_nodes)
        rx_all = np.asarray(res.reactions)
        start = {int(node): rx_all[0, j] for j, node in enumerate(rn)} if len(rx_all) else {}
        rx = rx_all[1:]
        for j, node in enumerate(rn):
            self.reactions.setdefault(int(node), {})
            for t, f in zip(tt, rx[:, j], strict=True):
                self.reactions[int(node)][float(t)] = f
        if len(res.tension):
            self.tension = np.asarray(res.tension[-1])
            # every frame's edge tensions; the first phase keeps its frame 0 (the start)
            self.tensions.extend(list(np.asarray(res.tension)[0 if k0 == 1 else 1 :]))
        for k, v in res.stats.items():
            self.stats[k] = self.stats.get(k, 0) + v
        if res.final_state is not None:
            self.state = res.final_state
        return start

    def tension_frames(self) -> np.ndarray:
        """Edge tensions [N] at every recorded frame, (n_frames, n_edges) (the first
        phase's frame 0 included, as in :meth:`frames`)."""
        return np.asarray(self.tensions)

    def frames(self):
        """(times (n_frames,) [s], positions (n_frames, n_nodes, 3) [m]) of all phases."""
        return np.asarray(self.times), np.asarray(self.positions)

    def reaction(self, nodes, times=None) -> np.ndarray:
        """Summed constraint reaction on ``nodes`` [N] at each recorded time (NaN where a
        node was not constrained), (n_times, 3)."""
        t = np.asarray(self.times if times is None else times)
        out = np.zeros((t.size, 3))
        if t.size == 0:
            return out
        for node in np.atleast_1d(nodes):
            rec = self.reactions.get(int(node), {})
            out += np.array([rec.get(float(x), (np.nan,) * 3) for x in t])
        return out

    def phase_mask(self, name: str) -> np.ndarray:
        """Boolean mask of the frames recorded by the phase(s) called ``name``."""
        m = np.zeros(len(self.times), dtype=bool)
        for p in self.phases:
            if p.name == name:
                m[p.frames[0] : p.frames[1]] = True
        return m

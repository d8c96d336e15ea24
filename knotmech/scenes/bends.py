r"""Two ropes joined by a bend and pulled apart until it slips: the four bends of Patil et
al. (reef, granny, thief, grief) and the bends of :mod:`knotmech.scenes.tied` (sheet bend,
double sheet bend, flat overhand bend, figure-eight bend, double fisherman's).

The experiment of Patil, Sandt, Kolle & Dunkel (Science 367, 71, 2020), on the DER solver:
the bend is tied loosely from :func:`knotmech.scenes.bend_curves.bend_curves` (two naturally
straight elastic rods), settles for ``settle_time`` with all four ends held, is *set* (all
four ends pulled outwards along x at ``pull_speed`` until the mean tension of the end edges
reaches ``set_tension``) and is then pulled: the two standing ends move apart along x, each
at ``pull_speed``, while the two tails are free. Rod-rod contact is the implicit contact
model with sticking (anchor) friction, :func:`knotmech.scenes._scene.rod_contact`.

Measured: the pull force :math:`F(t)` (mean of the two grips' reactions along the pull) and
the *draw-in* of each tail (how far its free end moved towards the knot, along x). The bend
**slips** when a tail is drawn in by more than ``slip_draw_in`` (default 2 d) while the
pull force stays within 10 % of its largest value (sliding at a plateau or a falling
force; tightening draws the tails in while the force still rises), or when a tail has run
out of the knot; the **slip load** is the largest pull force before that moment. A bend
that has not slipped when the pull ends *holds* up to the largest force reached. A tied
bend's pull also ends when a pulled end reaches :data:`STRAIN_LIMIT` EA (the rod model's
strain limit, :class:`StrainStop`): a bend that has not slipped by then holds to at least
the force there (``held_to_strain_limit``).

The topology is checked on every recorded frame up to the slip: the Alexander polynomial of
the two ropes joined around the outside (:func:`~knotmech.scenes.bend_curves.bend_closure`)
and the linking number of the ropes closed each on its own side must stay those of the
start shape; a change means a strand passed through another and the run is ``failed``.
Every accepted step also checks that no two strands overlap by more than half a diameter.

The tied bends (:class:`TiedBendScene`, a registry record each in :mod:`knotmech.knots`)
run the same phases from their tied start curves, with these differences: every grip
moves along its rope's outward end tangent (the flat overhand bend's standing parts, which
leave the knot side by side, are pulled apart sideways: ring-loaded, as on an abseil
anchor); a tail's draw-in is material (the decrease of its length outside the knot,
:func:`knotmech.scenes.tied.pulled.tail_free_lengths`), so that a knot that rolls along
its ropes draws both tails in (``roll``); every pull frame's invariants are checked
(each rope's knot type must stay: a change fails the run; the two ropes' linking number
and joined closure are reported when they change, since free tails can wind round the
other rope without any strand passing through another); the friction is the anchor law
with its cap floored at :data:`TIED_CAP_FLOOR` (stated in the result's ``law``).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field, fields
from functools import partial

import numpy as np

from knotmech import knots, rod
from knotmech.errors import InputError, check_count, check_nonnegative, check_positive
from knotmech.materials import DEMO_ROD_DENSITY, STRAIN_LIMIT
from knotmech.rod.constraints import Clamp, MovingNodes
from knotmech.scenes._common import check_memory, check_run_size, frames_bytes, pair_check_bytes
from knotmech.scenes._scene import RunControl, Scene, SceneRun, grip_path, rod_contact
from knotmech.scenes.bend_curves import BEND_CODES, BendCurves, bend_curves, bend_invariants
from knotmech.scenes.curves import _edge_distances
from knotmech.scenes.tied.pulled import (
    end_direction,
    frame_invariants,
    invariants_changed,
    rope_types,
    tail_free_lengths,
    tail_nodes,
    tails_drawn,
)

__all__ = [
    "BendResult",
    "BendScene",
    "BendRopes",
    "BendPull",
    "TiedBendResult",
    "TiedBendScene",
    "bend",
    "PATIL_ORDER",
    "STRAIN_LIMIT",
    "StrainStop",
    "GripEdgeStrains",
]

#: Stability order of the four bends attributed to Patil et al. (2020), most secure first,
#: as recalled in docs/notes/knots.md. Only reef above granny is confirmed by a source we
#: could read (the authors' summary, Patil & Dunkel, SIAM News 2020: the granny "slips and
#: unravels easily when pulled, whereas the reef knot is more secure"); the place of thief
#: and grief was not checked against the paper (docs/notes/tables.md).
PATIL_ORDER = ("reef", "thief", "granny", "grief")


def pull_summary(r) -> dict:
    """The plain-JSON row of a pull's result (a bend's or a loop's) that the benchmark and
    the slip table print: the solver's cost (steps, Newton iterations, rejected steps,
    nodes), status and message, verdict, slip load [N] (None unless it slips), largest
    force [N] and the frames checked. The caller adds its CPU time."""
    return {
        "steps": int(r.stats.get("steps", 0)),
        "newton_iterations": int(r.stats.get("newton_iterations", 0)),
        "rejected_steps": int(r.stats.get("rejected_steps", 0)),
        "nodes": int(r.positions.shape[1]),
        "status": r.status,
        "message": r.message,
        "verdict": r.verdict,
        "slip_load_N": r.slip_load if r.verdict == "slips" else None,
        "max_force_N": r.max_force,
        "frames_checked": int(getattr(r, "frames_checked", 0)),
        "held_to_strain_limit": bool(getattr(r, "held_to_strain_limit", False)),
    }


@dataclass
class BendResult:
    """What a bend pull measured (SI units).

    Attributes
    ----------
    kind : str
    verdict : {"slips", "holds", ""}
        ``""`` when the run failed.
    slip_load : float [N]
        Largest pull force before the slip (NaN if it held).
    max_force : float [N]
        Largest pull force of the whole pull.
    pull_speed, mu_rod_rod : float
    times : (n_frames,) [s]
    pull_displacement : (n_frames,) [m]
        Displacement of each grip (0 before the pull).
    pull_force : (n_frames,) [N]
    draw_in : (n_frames, 2) [m]
        Draw-in of A's and B's tail ends.
    alexander_start, alexander_checked : tuple
        Of the closed bend at the start and at the last frame checked (the slip or the end).
    linking_start, linking_checked : int
    positions : (n_frames, 2 n_nodes, 3) [m]
    status, message : str; stats : dict (steps, newton_iterations, wall_s)
    """

    kind: str
    verdict: str
    slip_load: float
    max_force: float
    pull_speed: float
    mu_rod_rod: float
    times: np.ndarray
    pull_displacement: np.ndarray
    pull_force: np.ndarray
    draw_in: np.ndarray
    alexander_start: tuple
    alexander_checked: tuple
    linking_start: int
    linking_checked: int
    positions: np.ndarray
    status: str
    message: str
    stats: dict = field(default_factory=dict)

    @property
    def topology_preserved(self) -> bool:
        """Same Alexander polynomial and linking number at the start and where checked."""
        return (self.alexander_start, self.linking_start) == (
            self.alexander_checked,
            self.linking_checked,
        )

    def to_dict(self) -> dict:
        """Plain-JSON summary (curves as lists, positions left out)."""

        def num(v):
            return float(v) if np.isfinite(v) else None

        return {
            "scene": "bend",
            "kind": self.kind,
            "verdict": self.verdict,
            "slip_load": num(self.slip_load),
            "max_force": num(self.max_force),
            "pull_speed": self.pull_speed,
            "mu_rod_rod": self.mu_rod_rod,
            "topology_preserved": self.topology_preserved,
            "status": self.status,
            "message": self.message,
            "stats": {k: (float(v) if k == "wall_s" else int(v)) for k, v in self.stats.items()},
            "pull_displacement": [float(v) for v in self.pull_displacement],
            "pull_force": [num(v) for v in self.pull_force],
        }


def _grip(system, rope: int, end: str):
    """Global indices of a rope end's two nodes (end node first) and its end edge."""
    nodes = system.rod_nodes(rope)
    edges = system.rod_edges(rope)
    if end == "start":
        return [int(nodes[0]), int(nodes[1])], int(edges[0])
    return [int(nodes[-1]), int(nodes[-2])], int(edges[-1])


def inner_edge(system, grip) -> int:
    """The first free edge next to a grip ``(nodes, end edge)`` of :func:`_grip` (the
    edge that shares the grip's inner node; the end edge itself is rigid)."""
    nodes, edge = grip
    touching = np.nonzero((system.edge_nodes == nodes[1]).any(axis=1))[0]
    return int(touching[touching != edge][0])


class GripEdgeStrains:
    r"""The strain of the first free edge next to each grip (:func:`inner_edge`): how the
    set phases (:class:`BendScene`, :class:`knotmech.scenes.loops.LoopScene`) and the
    pull's stop (:class:`StrainStop`) read a gripped end's tension from positions.

    Called with positions ``x`` (n_nodes, 3) [m], it returns the strains
    :math:`l/l_0 - 1` [-] of those edges, one a grip in the order of ``grips``; the
    tension of an end is ``ea`` times its strain [N] (axial stiffness :math:`EA` of the
    edge). The end edge itself is not read: both its nodes are gripped, it is rigid.

    Parameters
    ----------
    system : knotmech.rod.RodSystem
    grips : sequence of (nodes, end edge)
        The gripped ends (:func:`_grip`).

    Attributes
    ----------
    edges : ndarray of int
        The edges read, one a grip.
    ea : ndarray
        Their axial stiffness :math:`EA` [N].
    """

    def __init__(self, system, grips):
        self.edges = e = np.array([inner_edge(system, g) for g in grips])
        self.ea, self.rest, self.en = system.ea[e], system.rest_length[e], system.edge_nodes[e]

    def __call__(self, x) -> np.ndarray:
        x = np.asarray(x)
        length = np.linalg.norm(x[self.en[:, 1]] - x[self.en[:, 0]], axis=1)
        return length / self.rest - 1.0


class StrainStop:
    r"""The stop of a tied pull (bends and loops): a tail run out, or a pulled end at the
    rod model's strain limit.

    Called with the positions after every accepted step of the pull; True ends the pull.
    ``tail_out(x)`` is asked first (a tail running out wins when both happen on one step).
    Then the tension of each pulled end is read from positions as the set phase reads it
    (:class:`GripEdgeStrains`): the strain :math:`l/l_0 - 1` of the first free edge next to
    the grip (the end edge is rigid); when the largest reaches :data:`STRAIN_LIMIT` (tension
    :math:`0.1 EA`) the pull stops, ``reached`` is set, and a knot that has not slipped
    by then *held to at least* the pull force of that frame.

    Why the end edge and not the rod's largest edge strain: the pull force is the grips'
    reaction, the end's tension (the drag is 1 % of :math:`B/d^2`), and in the knot the
    tension falls from the pulled end by friction; on the figure-eight bend at mu = 1 the
    two agree at the stop (largest edge strain 0.1005, the stopping edge's 0.1002;
    docs/notes/knots-and-curves/tied-slip-over-mu.md).

    Parameters
    ----------
    system : knotmech.rod.RodSystem
    grips : sequence of (nodes, end edge)
        The pulled ends (:func:`_grip`).
    tail_out : callable(positions) -> bool
    """

    def __init__(self, system, grips, tail_out):
        self.strains = GripEdgeStrains(system, grips)
        self.tail_out, self.reached = tail_out, False

    def strain(self, x) -> float:
        """Largest strain of the pulled ends' first free edges at positions ``x``."""
        return float(np.max(self.strains(x)))

    def __call__(self, x) -> bool:
        if self.tail_out(x):
            return True
        self.reached = self.strain(x) >= STRAIN_LIMIT
        return self.reached


def _held_to(max_force: float) -> str:
    """The one sentence of a hold to the strain limit, :func:`held_note`'s and
    :func:`held_words`' both: ``"to at least F N (0.1 EA, the rod model's strain limit)"``
    (``max_force`` F [N])."""
    return f"to at least {max_force:.4g} N ({STRAIN_LIMIT:g} EA, the rod model's strain limit)"


def held_note(max_force: float) -> str:
    """The words of a pull stopped at the strain limit that had not slipped: ``"holds to at
    least F N (0.1 EA, the rod model's strain limit): a lower bound of the slip load"``
    (``max_force`` F [N])."""
    return f"holds {_held_to(max_force)}: a lower bound of the slip load"


def held_words(r) -> str:
    """How a pull's result ``r`` that held is told (the CLI's line): ``"HOLDS to at least F
    N (0.1 EA, the rod model's strain limit)"`` (:func:`held_note`'s sentence) when it
    stopped there (``held_to_strain_limit``), else ``"HOLDS up to F N (the pull ended)"``."""
    if getattr(r, "held_to_strain_limit", False):
        return f"HOLDS {_held_to(r.max_force)}"
    return f"HOLDS up to {r.max_force:.4g} N (the pull ended)"


@dataclass(frozen=True)
class BendRopes:
    """The two ropes and their contact (SI units; :func:`bend` documents them)."""

    rod_diameter: float = 4e-3
    youngs_modulus: float = 1.0e6
    density: float = DEMO_ROD_DENSITY
    bending_scale: float = 1.0
    mu_rod_rod: float = 0.3
    mu_kinetic: float | None = None
    n_nodes: int = 80
    force_scale: float | None = None
    contact_width: float = 0.2


@dataclass(frozen=True)
class BendPull:
    """Settling, setting and pulling [s], [m/s], [m], [N] (:func:`bend` documents them)."""

    pull_speed: float = 0.04
    pull_distance: float | None = None
    settle_time: float = 0.2
    slip_draw_in: float | None = None
    set_tension: float | None = None
    set_travel: float | None = None


def bend(
    kind: str,
    *,
    rod_diameter: float = 4e-3,
    youngs_modulus: float = 1.0e6,
    density: float = DEMO_ROD_DENSITY,
    bending_scale: float = 1.0,
    mu_rod_rod: float = 0.3,
    mu_kinetic: float | None = None,
    pull_speed: float = 0.04,
    pull_distance: float | None = None,
    settle_time: float = 0.2,
    n_nodes: int | None = None,
    dt: float = 4e-3,
    slip_draw_in: float | None = None,
    set_tension: float | None = None,
    set_travel: float | None = None,
    force_scale: float | None = None,
    contact_width: float = 0.2,
    n_frames: int | None = None,
    options: rod.SolverOptions | None = None,
    progress: bool = False,
) -> BendResult:
    r"""Tie a bend between two ropes, pull the standing ends apart, report the slip load.

    Parameters
    ----------
    kind : str
        A bend of the registry with this scene: ``"reef"``, ``"granny"``, ``"thief"``,
        ``"grief"``, or a tied bend (``"sheet-bend"``, ``"double-sheet-bend"``,
        ``"flat-overhand-bend"``, ``"figure-eight-bend"``, ``"double-fishermans"``, or
        an alias), which returns a :class:`TiedBendResult`.
    rod_diameter : float [m]
        Diameter d of both ropes (default 4 mm).
    youngs_modulus : float [Pa]
        Of the (solid, elastic) rods (default 1 MPa, a soft elastomer; the bending
        stiffness is :math:`B = E\pi d^4/64`).
    density : float [kg/m^3]
    bending_scale : float
        kappa in (0, 1]: the rods' bending (and twisting) stiffness is kappa times the
        solid rod's (:class:`knotmech.rod.Rod`; a fibre rope is of order 0.01).
    mu_rod_rod, mu_kinetic : float
        Static and kinetic rod-rod friction (``mu_kinetic`` None: equal to the static).
    pull_speed : float [m/s]
        Speed of each grip (the ends separate at twice this).
    pull_distance : float [m], optional
        Travel of each grip (default 12 d; a tied bend 20 d).
    settle_time : float [s]
        All four ends held while the contacts settle.
    n_nodes : int, optional
        Nodes per rope (default 80; a tied bend: its record's, 100-150).
    dt : float [s]
        Nominal step (the solver halves it when Newton fails).
    slip_draw_in : float [m], optional
        Tail draw-in at (near) the largest force that counts as a slip (default 2 d).
    set_tension : float [N], optional
        Before the pull the bend is *set*: all four ends are pulled outwards at
        ``pull_speed`` until the mean tension next to the four grips reaches this
        (default :math:`0.1 B/d^2`, a hand-set bend), or for ``set_travel``; then the
        tails are let go.
    set_travel : float [m], optional
        Largest travel of each end while setting (default 10 d; a tied bend 20 d).
    force_scale : float [N], optional
        Sizes the contact penalty (default :math:`2 B/d^2`; overlap d/40 under B/d^2).
    contact_width : float
        Range of the contact penalty in rod diameters (see
        :func:`knotmech.scenes._scene.rod_contact`).
    n_frames : int, optional
        Recorded frames of the pull (>= 10; default 120, a tied bend 20: each is checked).
    options : knotmech.rod.SolverOptions, optional
    progress : bool

    Returns
    -------
    BendResult
        ``status`` "failed" with the phase and the reason when the settling, the setting
        or the pull stopped (the verdict is then ""), or when the topology changed.

    Raises
    ------
    InputError
        A bad argument, or a run whose steps x nodes or memory is above the bound
        (:func:`knotmech.scenes._common.check_run_size`,
        :func:`~knotmech.scenes._common.check_memory`), before anything is allocated.

    Notes
    -----
    Cost at the defaults (80 nodes per rope, 2 x 48 mm at 40 mm/s): about 800 steps and
    6000 Newton iterations, 1-2 minutes on a free core (docs/notes/knots.md gives the times).
    A tied bend at its defaults: 5-53 s of CPU; the figure-eight bend 7-16 s, its pull
    stopped at the strain limit at mu >= 0.6 (71 s at mu = 1 before the stop;
    ``benchmarks/tied.py``; docs/notes/knots-and-curves/tied-slip-over-mu.md).
    """
    record = _record(kind)
    defaults = {"n_nodes": 80, "n_frames": 120, **record.scene_defaults}
    n_nodes = defaults["n_nodes"] if n_nodes is None else n_nodes
    n_frames = defaults["n_frames"] if n_frames is None else n_frames
    if pull_distance is None and "pull_distance_d" in defaults:
        pull_distance = defaults["pull_distance_d"] * check_positive("rod_diameter", rod_diameter)
    if set_travel is None and "set_travel_d" in defaults:
        set_travel = defaults["set_travel_d"] * check_positive("rod_diameter", rod_diameter)
    scene = BendScene if kind in BEND_CODES else partial(TiedBendScene, record=record)
    return scene(
        kind,
        ropes=BendRopes(
            rod_diameter=rod_diameter,
            youngs_modulus=youngs_modulus,
            density=density,
            bending_scale=bending_scale,
            mu_rod_rod=mu_rod_rod,
            mu_kinetic=mu_kinetic,
            n_nodes=n_nodes,
            force_scale=force_scale,
            contact_width=contact_width,
        ),
        pull=BendPull(
            pull_speed=pull_speed,
            pull_distance=pull_distance,
            settle_time=settle_time,
            slip_draw_in=slip_draw_in,
            set_tension=set_tension,
            set_travel=set_travel,
        ),
        control=RunControl(dt=dt, n_frames=n_frames, options=options, progress=progress),
    ).run()


_EX = np.array([1.0, 0.0, 0.0])


class BendScene(Scene):
    """Two ropes tied in a bend, set and pulled apart: the phases of :func:`bend`."""

    def __init__(self, kind, *, ropes, pull, control):
        self.kind, self.ropes, self.pull, self.control = kind, ropes, pull, control

    # -- setup -----------------------------------------------------------------------
    def setup(self) -> None:
        """Inputs and cost checked; the start curves tied."""
        self._check_kind()
        o, p = self.ropes, self.pull
        self.d = d = float(check_positive("rod_diameter", o.rod_diameter, scalar=True))
        self.E = float(check_positive("youngs_modulus", o.youngs_modulus, scalar=True))
        self.rho = float(check_positive("density", o.density, scalar=True))
        self.mu = float(check_nonnegative("mu_rod_rod", o.mu_rod_rod, scalar=True))
        self.v = float(check_positive("pull_speed", p.pull_speed, scalar=True))
        self.dist = (
            12 * d
            if p.pull_distance is None
            else float(check_positive("pull_distance", p.pull_distance, scalar=True))
        )
        self.slip = (
            2 * d
            if p.slip_draw_in is None
            else float(check_positive("slip_draw_in", p.slip_draw_in, scalar=True))
        )
        check_count("n_frames", self.control.n_frames, 10)
        check_positive("contact_width", o.contact_width, scalar=True)
        self.B = B = self.E * np.pi * d**4 / 64
        self.f_set = (
            0.1 * B / d**2
            if p.set_tension is None
            else float(check_positive("set_tension", p.set_tension, scalar=True))
        )
        self.set_travel = (
            10 * d
            if p.set_travel is None
            else float(check_positive("set_travel", p.set_travel, scalar=True))
        )
        self.fs = (
            2 * B / d**2
            if o.force_scale is None
            else float(check_positive("force_scale", o.force_scale, scalar=True))
        )
        self.settle_time = float(check_positive("settle_time", p.settle_time, scalar=True))
        self.dt = float(check_positive("dt", self.control.dt, scalar=True))
        self._check_cost()
        self._tie()

    def _tie(self) -> None:
        """The start curves and the directions of the grips: A's ends pulled along -x, B's
        along +x (set: standing part and tail of each; pull: the standing parts)."""
        self.curves = bend_curves(self.kind, rod_diameter=self.d, n_nodes=self.ropes.n_nodes)
        self.set_dirs = (-_EX, -_EX, _EX, _EX)
        self.pull_dirs = (-_EX, _EX)

    def _check_kind(self) -> None:
        if self.kind not in BEND_CODES:
            raise InputError(f"kind must be one of {', '.join(BEND_CODES)}, got {self.kind!r}")

    def _check_cost(self) -> None:
        """Steps x nodes of settle, set and pull, and the memory of the overlap watch."""
        n = self.ropes.n_nodes
        N = check_count("n_nodes", n, 40)
        t_end = self.settle_time + (self.set_travel + self.dist) / self.v
        check_run_size(
            n_nodes=2 * N,
            t_end=t_end,
            dt=self.dt,
            hint="use fewer nodes (n_nodes), a larger dt or a shorter pull",
        )
        check_memory(
            pair_check_bytes(2 * N) + frames_bytes(self.control.n_frames + 100, 2 * N),
            what=f"the strands' overlap check on {2 * N} nodes",
            hint="use fewer nodes (n_nodes)",
        )

    # -- build -----------------------------------------------------------------------
    def build(self) -> SceneRun:
        """The two ropes, their contact, the overlap watch and the grips."""
        o, d = self.ropes, self.d
        rods = [
            rod.Rod(
                positions=x,
                radius=0.5 * d,
                youngs_modulus=self.E,
                density=self.rho,
                natural="straight",
                bending_scale=o.bending_scale,
            )
            for x in (self.curves.rope_a, self.curves.rope_b)
        ]
        self.system = system = rod.RodSystem(rods)
        self.N = N = int(o.n_nodes)
        contact = self._contact()
        idx = np.arange(2 * N - 2)
        far = np.abs(idx[:, None] - idx[None, :]) >= 3
        far[N - 1 :, : N - 1] = far[: N - 1, N - 1 :] = True  # edges of different ropes
        self.far = far
        self.edge_rows = np.r_[np.arange(N - 1), np.arange(N, 2 * N - 1)]
        # drag on the whole length moving at v: 1 % of B/d^2
        c = 0.01 * self.B / d**2 / (float(system.rest_length.sum()) * self.v)
        self.drag = rod.ViscousDamping(coefficient=c)
        self._ends()
        ctl = self.control
        return SceneRun(
            system,
            interactions=[contact],
            options=ctl.options,
            watch=self._watch,
            progress=ctl.progress,
        )

    def _contact(self):
        """Rod-rod contact with the anchor (sticking) friction law, the library's default."""
        o = self.ropes
        return rod_contact(
            rod_diameter=self.d,
            force_scale=self.fs,
            mu_static=self.mu,
            mu_kinetic=o.mu_kinetic,
            width=o.contact_width,
        )

    def _ends(self) -> None:
        """The four ends' grips, the pulled standing ends and the tails."""
        system = self.system
        self.ends = [_grip(system, 0, "start"), _grip(system, 0, "end")]
        self.ends += [_grip(system, 1, "start"), _grip(system, 1, "end")]
        pa, pb = self.curves.pulled
        self.ga, self.gb = _grip(system, 0, pa), _grip(system, 1, pb)
        self.tail_a = _grip(system, 0, "end" if pa == "start" else "start")
        self.tail_b = _grip(system, 1, "end" if pb == "start" else "start")
        self.ta, self.tb = self.tail_a[0][0], self.tail_b[0][0]

    def _watch(self, x):
        gap = _edge_distances(x)[np.ix_(self.edge_rows, self.edge_rows)][self.far].min()
        if gap < 0.5 * self.d:
            return f"strands overlap by more than half a diameter (gap {gap / self.d:.2f} d)"
        return None

    # -- phases ----------------------------------------------------------------------
    def run_phases(self, run: SceneRun) -> None:
        """Settle (four ends held), set (four ends pulled out), pull (standing ends)."""
        ends = self.ends
        hold_all = Clamp(nodes=[n for e in ends for n in e[0]], edges=[e[1] for e in ends])
        mass = self.rho * np.pi * self.d * self.d / 4
        self.t_wall = time.perf_counter()
        run.phase(
            "settle",
            self.settle_time,
            dt=self.dt,
            loads=[rod.ViscousDamping(coefficient=20.0 * mass / self.pull.settle_time)],
            constraints=[hold_all],
        )
        self._set(run)
        self._pull(run)

    def _set(self, run: SceneRun) -> None:
        """Set (dress) the bend: all four ends pulled outwards until their mean tension
        reaches set_tension, as a rigger sets a bend before loading it; the tension is read
        on the first free edge of each end (the end edge itself is rigid: both its nodes
        are gripped)."""
        system, ga, gb = self.system, self.ga, self.gb
        strains = GripEdgeStrains(system, self.ends)

        def end_tension(x):
            return float(np.mean(strains.ea * strains(x)))

        x_set = system.positions(run.state.q)
        t_set = run.t
        moving = [
            MovingNodes(nodes=g[0], path=grip_path(x_set[g[0]], u, self.v, t_set))
            for g, u in zip((ga, self.tail_a, gb, self.tail_b), self.set_dirs, strict=True)
        ]
        if run.ok:
            # the tails' twist is left free: twist stored against a held tail would whirl
            # it into curls when it is let go
            run.phase(
                "set",
                self.set_travel / self.v,
                dt=self.dt,
                loads=[self.drag],
                constraints=[*moving, Clamp(edges=[ga[1], gb[1]])],
                stop=lambda x: end_tension(x) >= self.f_set,
            )

    def _pull(self, run: SceneRun) -> None:
        """The standing ends pulled apart, the tails free; stops when a tail runs out."""
        ga, gb, v = self.ga, self.gb, self.v
        ua, ub = self.pull_dirs
        x_settled = self.system.positions(run.state.q)
        self.t0 = t0 = run.t
        grips = [
            MovingNodes(nodes=ga[0], path=grip_path(x_settled[ga[0]], ua, v, t0)),
            MovingNodes(nodes=gb[0], path=grip_path(x_settled[gb[0]], ub, v, t0)),
            Clamp(edges=[ga[1], gb[1]]),
        ]
        if run.ok:
            run.phase(
                "pull",
                self.dist / v,
                dt=self.dt,
                loads=[self.drag],
                constraints=grips,
                save_every=self.dist / v / int(self.control.n_frames),
                stop=self._stop(),
            )

    def _stop(self):
        """The pull's stop: a tail run out (the tied bends: or an end at the strain limit,
        :class:`StrainStop`)."""
        return self._tail_out

    def _tail_out(self, x) -> bool:
        """Whether a tail end has run into the knot (within 1 d of its middle along x)."""
        d = self.d
        return (abs(x[self.ta, 0]) < 1.0 * d) or (abs(x[self.tb, 0]) < 1.0 * d)

    def _draw_in(self, pm, x0):
        """Draw-in [m] of A's and B's tail ends along x on each pull frame, and whether a
        tail has run out (its end within 1 d of the knot's middle)."""
        ta, tb, d = self.ta, self.tb, self.d
        draw = np.column_stack([pm[:, ta, 0] - x0[ta, 0], -(pm[:, tb, 0] - x0[tb, 0])])
        out = (np.abs(pm[:, ta, 0]) < 1.0 * d) | (np.abs(pm[:, tb, 0]) < 1.0 * d)
        return draw, out

    # -- measure ---------------------------------------------------------------------
    def measure(self, run: SceneRun) -> BendResult:
        """Pull force, draw-in, verdict and topology; the status checked."""
        times, pos = run.frames()
        m = run.phase_mask("pull")
        tp, pm = times[m], pos[m]
        force = self._force(run, tp)
        k0 = int(np.argmax(m))
        draw, out = self._draw_in(pm, pos[k0])
        verdict, slip_load, k_check = _bend_verdict(force, draw, out, self.slip)
        max_force = float(np.nanmax(force)) if force.size else float("nan")
        alex0, lk0 = self._start_invariants()
        status, message, (alex1, lk1) = self._topology(run, pm, tp, k_check, (alex0, lk0))
        if status == "success" and not force.size:
            status, message = "failed", "no pull frames recorded"
        if status != "success":
            verdict = ""
        stats = dict(run.stats)
        stats["wall_s"] = time.perf_counter() - self.t_wall
        return BendResult(
            kind=self.kind,
            verdict=verdict,
            slip_load=slip_load,
            max_force=max_force,
            pull_speed=self.v,
            mu_rod_rod=self.mu,
            times=tp,
            pull_displacement=self.v * (tp - self.t0),
            pull_force=force,
            draw_in=draw,
            alexander_start=alex0,
            alexander_checked=alex1,
            linking_start=lk0,
            linking_checked=lk1,
            positions=pos,
            status=status,
            message=message,
            stats=stats,
        )

    def _force(self, run, tp) -> np.ndarray:
        """Mean of the two grips' reactions along the pull [N]; both gripped nodes of an
        end carry part of the pull: their reactions are summed."""
        ga, gb = self.ga, self.gb
        ua, ub = self.pull_dirs
        force = 0.5 * (run.reaction([ga[0][0]], tp) @ ua + run.reaction([gb[0][0]], tp) @ ub)
        return force + 0.5 * (run.reaction([ga[0][1]], tp) @ ua + run.reaction([gb[0][1]], tp) @ ub)

    def _start_invariants(self):
        """(Alexander polynomial of the closed bend, linking number) of the start shape."""
        return bend_invariants(self.curves.rope_a, self.curves.rope_b)

    def _topology(self, run, pm, tp, k_check, start):
        """Status, message and the invariants at the last frame checked (every recorded
        frame up to the slip, at most about 30)."""
        status, message, got = run.status, run.message, start
        N = self.N
        for k in range(0, k_check + 1, max(1, (k_check + 1) // 30)):
            try:
                got = bend_invariants(pm[k][:N], pm[k][N:])
            except InputError:
                got = ((), start[1])
            if got != start:
                msg = f"topology changed at t = {tp[k]:.3f} s: a strand passed through another"
                return "failed", msg, got
        return status, message, got


#: the tied bends' friction law: the anchor law with its cap floored at 1e-2 (r_i + r_j),
#: several times fewer steps in tight knots
#: (docs/notes/contact-and-friction/sticking-law-cap-width.md); the library's default
#: since issue 24 (:data:`knotmech.rod.friction.CAP_FLOOR`), kept as a name for the tied
#: bends' results
TIED_CAP_FLOOR = rod.friction.CAP_FLOOR
#: interval [s of simulated time] at which a tied bend's pull looks whether a tail was
#: drawn through the knot (the pull's frame interval at the defaults: 20 d in 20 frames)
UNDONE_EVERY = 0.1


def undone_now(scene, x) -> bool:
    """Whether ``scene._undone(x)`` finds the knot undone, looked at no more often than every
    :data:`UNDONE_EVERY` s of simulated time (the check closes the rope and computes its
    knot type: too dear for every step). ``scene`` has ``_run`` (the live run), ``_t_undone``
    (the time of the last look, -inf at the pull's start) and ``_undone``."""
    t = scene._run.live.t
    if t - scene._t_undone < UNDONE_EVERY:
        return False
    scene._t_undone = t
    return bool(scene._undone(x))


def _record(kind):
    """The registry record of a bend ``kind`` with a scene here; a one-line InputError
    naming the bends otherwise."""
    names = knots.names(family="bend")
    key = knots.key(kind) if isinstance(kind, str) else ""
    if key not in names or knots.get(key).scene != "knotmech.scenes.bends:bend":
        raise InputError(f"kind must be one of {', '.join(names)}, got {kind!r}")
    return knots.get(key)


@dataclass
class TiedBendResult(BendResult):
    """A tied bend's pull: :class:`BendResult` and what the tied knots add (SI units).

    ``alexander_*`` are the pair (rope A alone, rope B alone) and ``linking_*`` the ropes'
    linking number; ``draw_in`` is material (the decrease of each tail's length outside
    the knot, :func:`knotmech.scenes.tied.pulled.tail_free_lengths`).

    Attributes
    ----------
    tail_drawn : {"A", "B", "both", ""}
        The tail drawn in more (by more than d/2) at the last pull frame, or both.
    roll : float [m]
        The smaller of the two tails' draw-in at the last pull frame: how far the knot
        moved along both ropes towards the tails (the flat overhand bend "rolls").
    came_undone : {"", "A", "B", "AB"}
        The rope(s) whose tail was drawn through the knot (its knot type alone changed
        with the tail end drawn in by more than the slip draw-in): the knot came undone,
        a slip at that frame (``verdict`` "slips"; frames after it are not checked).
    invariants_start, invariants_checked : dict
        :func:`knotmech.scenes.tied.measure` of the start shape and the last values
        defined on the frames checked.
    frames_checked : int
        Pull frames whose invariants were computed (all of them, unless the topology
        changed).
    law : str
        The rod-rod friction law.
    held_to_strain_limit : bool
        The pull stopped when a pulled end reached :data:`STRAIN_LIMIT` EA
        (:class:`StrainStop`) and the bend had not slipped: it held to at least
        ``max_force``, a lower bound of its slip load (``verdict`` "holds").
    """

    tail_drawn: str = ""
    roll: float = float("nan")
    came_undone: str = ""
    invariants_start: dict = field(default_factory=dict)
    invariants_checked: dict = field(default_factory=dict)
    frames_checked: int = 0
    law: str = ""
    held_to_strain_limit: bool = False

    @property
    def topology_preserved(self) -> bool:
        """Each rope's knot type the same at the start and on every frame checked (the
        linking number of two ropes with free tails is not invariant: see ``message``)."""
        return self.alexander_start == self.alexander_checked

    def summary(self, rod_diameter: float) -> dict:
        """:func:`pull_summary` and the tied bend's draw-in: ``tail_drawn``,
        ``came_undone``, ``roll_d`` (the roll in diameters of the run's ``rod_diameter``
        [m])."""
        row = pull_summary(self)
        row.update(tail_drawn=self.tail_drawn, came_undone=self.came_undone,
                   roll_d=self.roll / rod_diameter)  # fmt: skip
        return row

    def to_dict(self) -> dict:
        """:meth:`BendResult.to_dict` and the tied bend's fields."""
        out = super().to_dict()
        out.update(
            tail_drawn=self.tail_drawn,
            came_undone=self.came_undone,
            roll=float(self.roll) if np.isfinite(self.roll) else None,
            frames_checked=int(self.frames_checked),
            law=self.law,
            held_to_strain_limit=bool(self.held_to_strain_limit),
            invariants_start=_plain(self.invariants_start),
            invariants_checked=_plain(self.invariants_checked),
        )
        return out


def _plain(inv: dict) -> dict:
    return {k: (list(v) if isinstance(v, tuple) else v) for k, v in inv.items()}


class TiedBendScene(BendScene):
    """A bend of :mod:`knotmech.scenes.tied` set and pulled: :class:`BendScene`'s phases
    with the tied knot's start curves, its grips along the ropes' end tangents (the flat
    overhand bend: its standing parts pulled apart sideways, ring-loaded), the tails'
    draw-in measured along the rope and every pull frame's invariants checked."""

    def __init__(self, kind, *, ropes, pull, control, record):
        super().__init__(record.name, ropes=ropes, pull=pull, control=control)
        self.record = record

    def _check_kind(self) -> None:
        """The kind is the record's (checked by :func:`bend`)."""

    def _tie(self) -> None:
        """The tied knot, its start invariants and the grips' directions."""
        self.knot = knot = self.record.curve_function()(
            rod_diameter=self.d, n_nodes=self.ropes.n_nodes
        )
        a, b = knot.ropes["A"], knot.ropes["B"]
        self.curves = BendCurves(self.kind, a, b, 0.5 * self.d, ("start", "start"), "", knot.info)
        self.inv_start = frame_invariants(knot, a, b)
        self.tails = tail_nodes(np.vstack([a, b]), len(a), self.d)
        ends = [end_direction(r, e) for r in (a, b) for e in ("start", "end")]
        self.set_dirs = tuple(ends)
        if self.record.curve_params.get("pull") == "apart":
            u = (a[0] - b[0]) / np.linalg.norm(a[0] - b[0])
            self.pull_dirs = (u, -u)
        else:
            self.pull_dirs = (ends[0], ends[2])

    def _contact(self):
        """Rod-rod contact with the anchor law, its cap floored (:data:`TIED_CAP_FLOOR`)."""
        o = self.ropes
        mk = (
            self.mu
            if o.mu_kinetic is None
            else float(check_nonnegative("mu_kinetic", o.mu_kinetic))
        )
        if mk > self.mu:
            raise InputError(f"mu_kinetic must be <= mu_rod_rod ({self.mu:g}), got {mk:g}")
        fr = None
        if self.mu > 0:
            fr = rod.AnchorFriction(mu_static=self.mu, mu_kinetic=mk, cap_floor=TIED_CAP_FLOOR)
        w = float(check_positive("contact_width", o.contact_width))
        contact = rod.RodContact(stiffness=20.0 * self.fs / self.d,
                                 sharpness=15.0 / (w * self.d), friction=fr)  # fmt: skip
        self.contact_tunnel_check = contact.tunnel_check
        return contact

    def _pull(self, run: SceneRun) -> None:
        """:meth:`BendScene._pull`, the tails' free lengths at its start kept."""
        x = self.system.positions(run.state.q)
        self.free0 = tail_free_lengths(x, self.N, self.d, self.tails)
        self.x_pull0, self._run, self._t_undone = x, run, -np.inf
        super()._pull(run)

    def _stop(self):
        """A tail run out, or a pulled end at the strain limit (:class:`StrainStop`)."""
        self.strain_stop = StrainStop(self.system, (self.ga, self.gb), self._tail_out)
        return self.strain_stop

    def _ran_out(self, free) -> np.ndarray:
        """(..., 2) bool: a tail with less than 1 d outside the knot, drawn in by more than
        the slip draw-in since the pull began (a tail that lay against a crossing strand
        from the start has not run out)."""
        return (free < 1.0 * self.d) & (self.free0 - free > self.slip)

    def _tail_out(self, x) -> bool:
        """Whether a tail has run out of the knot (:meth:`_ran_out`) or, looked at every
        :data:`UNDONE_EVERY` s, been drawn through it (:meth:`_undone`)."""
        if self._ran_out(tail_free_lengths(x, self.N, self.d, self.tails)).any():
            return True
        return undone_now(self, x)

    def _undone(self, x) -> tuple:
        """The ropes (``"A"``, ``"B"``) whose tail was drawn through the knot at ``x``: the
        rope's knot type alone differs from the start's while its tail end has moved
        towards the knot by more than the slip draw-in since the pull began (the knot
        came undone; the overlap watch of every step excludes a strand passing through
        another). A rope whose type changed with its tail not drawn in is not here: that
        fails the run (:meth:`_topology`)."""
        drawn = tails_drawn(x, self.x_pull0, self.N)
        if not (drawn > self.slip).any():
            return ()
        types, start = rope_types(x, self.N), self._start_invariants()[0]
        return tuple("AB"[i] for i in range(2) if drawn[i] > self.slip and types[i] != start[i])

    def _draw_in(self, pm, x0):
        """Material draw-in [m] of A's and B's tails on each pull frame (from the pull's
        start), and whether a tail has run out (:meth:`_ran_out`) or been drawn through
        the knot (:meth:`_undone`; from the first such frame ``self.k_undone`` on)."""
        free = np.array([tail_free_lengths(x, self.N, self.d, self.tails) for x in pm])
        free = free.reshape(-1, 2)
        out = self._ran_out(free).any(axis=1)
        self.k_undone, self.undone = None, ()
        for k, x in enumerate(pm):
            undone = self._undone(x)
            if undone:
                self.k_undone, self.undone = k, undone
                out[k:] = True
                break
        return self.free0 - free, out

    def _start_invariants(self):
        inv = self.inv_start
        return (inv["alexander_A"], inv["alexander_B"]), inv["linking"]

    def _topology(self, run, pm, tp, k_check, start):
        """Every pull frame's invariants against the start shape's: a rope whose knot type
        changed fails the run; a changed linking number or joined closure is reported (the
        two ropes' tails are free: an end winding round the other rope, or the knot
        capsizing, changes them without a strand passing through another, which the
        overlap watch of every step excludes)."""
        self.inv_checked = got = dict(self.inv_start)
        self.frames_checked, moved = 0, {}
        pair = self._start_invariants()  # a run with no pull frame keeps the start's
        before = self._changed_before_pull(pair[0])
        if before:
            return "failed", before, pair
        for k in range(len(pm)):
            if self.k_undone is not None and k >= self.k_undone:
                return run.status, self._undone_note(tp[k]), pair
            try:
                now = frame_invariants(self.knot, pm[k][: self.N], pm[k][self.N :])
            except InputError as e:
                return "failed", f"t = {tp[k]:.3f} s: the frame does not close ({e})", start
            self.frames_checked += 1
            changed = invariants_changed(self.inv_start, now)
            got.update({key: v for key, v in now.items() if v is not None})
            pair = (got["alexander_A"], got["alexander_B"]), got["linking"]
            for key in changed:
                moved.setdefault(key, (tp[k], now[key]))
            if {"alexander_A", "alexander_B"} & set(changed):
                return "failed", (
                    f"knot type of a rope changed at t = {tp[k]:.3f} s "
                    f"({', '.join(changed)}): a tail drawn out through a loop, or a strand "
                    "through another; not a result"), pair  # fmt: skip
        note = "; ".join(
            f"{key} {self.inv_start[key]} -> {v} at t = {t:.3f} s (free tails wound round)"
            for key, (t, v) in moved.items()
        )
        return run.status, run.message or note, pair

    def _changed_before_pull(self, start) -> str:
        """The failure message when a rope's knot type at the pull's start differs from
        ``start`` (changed while all four ends were held), else ``""``."""
        if not hasattr(self, "x_pull0"):
            return ""
        now = rope_types(self.x_pull0, self.N)
        ropes = ", ".join(r for r, a, b in zip("AB", now, start, strict=True) if a != b)
        if not ropes:
            return ""
        return (f"knot type of rope {ropes} changed before the pull (settle or set, all "
                "four ends held): a loop passed over a held end (ends too short for the "
                "loose knot), or a strand through another; not a result")  # fmt: skip

    def _undone_note(self, t) -> str:
        ropes = " and ".join(self.undone)
        return (f"rope {ropes} came undone at t = {t:.3f} s: its tail drawn through the "
                "knot (a slip; frames after it not checked)")  # fmt: skip

    def measure(self, run: SceneRun) -> TiedBendResult:
        """:meth:`BendScene.measure`, the tail drawn in and the roll."""
        res = super().measure(run)
        base = {f.name: getattr(res, f.name) for f in fields(BendResult)}
        draw = np.asarray(res.draw_in)
        tail, roll = "", float("nan")
        if draw.size:
            da, db = draw[-1]
            roll = float(min(da, db))
            tail = "A" if da > db + 0.5 * self.d else "B" if db > da + 0.5 * self.d else "both"
        law = (
            f"anchor (sticking) friction, cap floor {TIED_CAP_FLOOR:g} (r_i + r_j), "
            f"tunnel check {self.contact_tunnel_check}"
        )
        stop = getattr(self, "strain_stop", None)
        held = bool(stop is not None and stop.reached and res.verdict == "holds")
        if held:
            base["message"] = "; ".join(filter(None, (held_note(res.max_force),
                                                      base["message"])))  # fmt: skip
        return TiedBendResult(**base, tail_drawn=tail, roll=roll, law=law,
                              held_to_strain_limit=held,
                              came_undone="".join(getattr(self, "undone", ())),
                              invariants_start=self.inv_start,
                              invariants_checked=getattr(self, "inv_checked", {}),
                              frames_checked=getattr(self, "frames_checked", 0))  # fmt: skip


def _bend_verdict(force, draw, out, slip) -> tuple[str, float, int]:
    """(verdict, slip load [N], frame checked): slip when the tails are drawn in by more
    than ``slip`` while the force is within 10 % of its largest value (a knot that tightens
    draws its tails in while the force still rises; one that slides does so at a plateau
    or a falling force), or when a tail ran ``out``."""
    if not force.size:
        return "", float("nan"), len(force) - 1
    max_force = float(np.nanmax(force))
    # within 10 % of the largest force (a pull that never pulled, all forces <= 0, too)
    near = max_force - 0.1 * abs(max_force) if max_force <= 0 else 0.9 * max_force
    k_near = int(np.nonzero(force >= near)[0][0])
    beyond = draw.max(axis=1) - draw[k_near].max()
    slipped = np.nonzero(((beyond > slip) & (np.arange(force.size) >= k_near)) | out)[0]
    if slipped.size:
        k = int(slipped[0])
        # a knot that slipped before the pull force was ever positive slipped at no load
        top = float(np.nanmax(force[: k + 1]))
        return "slips", max(top, 0.0), int(np.nanargmax(force[: k + 1]))
    return "holds", float("nan"), len(force) - 1

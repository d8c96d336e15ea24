r"""A loop knot with its eye round a fixed pin, the standing part pulled away until it slips:
the bowline, the figure-eight loop and the alpine butterfly of :mod:`knotmech.scenes.tied`
(issue 25); the alpine butterfly also end to end (``loading="end-to-end"``, below).

The loop is tied loosely from its curve (one naturally straight elastic rod, node 0 the
standing part, the last node the tail), its eye round a rigid pin (a cylinder along z,
diameter D, with sticking friction: :func:`knotmech.scenes._scene.post_contact`). Phases,
as the tied bends' (:class:`knotmech.scenes.bends.TiedBendScene`):

1. **settle** ``settle_time`` with both ends held;
2. **set**: the standing end pulled away from the pin along its outward end tangent and
   the tail along its own, each at ``pull_speed`` (a hand dressing the knot), until the
   tension next to each grip reaches ``set_tension`` (default
   :math:`0.1 B/d^2`) or for ``set_travel``;
3. **release** ``settle_time``: the standing end held where the set left it, the tail let
   go (damped as the settling: a tail let go at the set tension would otherwise snap
   into a loose knot and count as a slip at the set tension);
4. **pull**: the standing end pulled on along the same direction for ``pull_distance``,
   the tail free, or until the standing end reaches 0.1 EA (the rod model's strain limit,
   :class:`knotmech.scenes.bends.StrainStop`: the loop then held to at least that force,
   ``held_to_strain_limit``).

Measured: the pull force (the grip's reaction along the pull), and two *material*
draw-ins (lengths of rope, not positions, so that a knot moving along its rope counts):
the **tail draw-in** (the decrease of the tail's length outside the knot) and the **eye
growth** (the increase of the eye's length outside the knot, both legs from the pin to
the first strand crossing them). A node is *inside the knot* when a strand crossing it
(tangents more than 25 deg apart) of the rope more than 4 d of arc away lies within
1.25 d (:data:`knotmech.scenes.tied.pulled.NEAR_SET`). The loop **slips** by the tied
bends' rule (:func:`knotmech.scenes.bends._bend_verdict`): the tail drawn in, or the eye
grown, by more than ``slip_draw_in`` (2 d) beyond the frame where the force first reaches
90 % of its largest value, or the tail run out (< 1 d outside after > 2 d of draw-in);
the **slip load** is the largest force before that frame.

Topology on every pull frame: :func:`knotmech.scenes.tied.measure` of the rope (standing
part closed to the tail far outside, the tail lifted out of the eye for the bowline: 6_3;
the unknot for the figure-eight loop), its winding about the pin, and the rope cut at the
pin with each half closed alone. The closed rope's knot type counts as kept when either
closure keeps its start value: the ends lifted up (+z) or down (-z) before being joined
far outside (the free tail end of a bowline swings out of its eye under or over an eye
leg, which changes one closure and not the other; a strand through another changes
both). Up to the slip, a change of the knot type or of the winding fails the run
(``status`` failed, the time and the invariant in ``message``), unless the knot **came
undone** (:meth:`LoopScene._undone`, looked at in the pull every
:data:`~knotmech.scenes.bends.UNDONE_EVERY` s and on every frame): the type changed in
both closures with the tail end drawn towards the knot by more than the slip draw-in (the
tail drawn through the knot, as the tied bends'), or, for a knot whose curve sets
``info["min_crossings"]`` (the alpine butterfly), the rope's average crossing number
(:func:`~knotmech.scenes.tied.crossings.average_crossings`) fallen below it: a slip at the
largest force before that frame, ``came_undone`` True, the message "came undone at t =
...", frames after it not checked. A butterfly fallen apart before the pull fails the run
("came apart before the pull": no slip load). After the slip and for the cut halves a
change is reported. The overlap watch of every accepted step (no two strands closer than
d/2) excludes a strand passing through another.
Friction: the tied bends' law (anchor, cap floored at
:data:`knotmech.scenes.bends.TIED_CAP_FLOOR`), with the path tunnelling guard.

End to end (the alpine butterfly, a mid-line loop isolating a damaged stretch: its record's
``scene_defaults["loadings"]``): no pin; the eye held where it is in the settle and the set
(drawn out with the ends, it withdraws the tongue from the loose window and the knot comes
undone in the set), let go in the release (both ends held), free in the pull, where both
ends are pulled apart along their end tangents (the force: the mean of the two grips'
reactions). The draw-ins are then the eye drawn into the knot and the rope drawn out of the
knot into the right end; the invariants, the closed rope's knot type and the knot types
of the rope's halves cut at the eye's tip, each closed from outside the knot
(:data:`END_KEYS`, :func:`~knotmech.scenes.tied.eye_linking.cut_knot_types`: two overhand
knots while the tongue passes through the window; their change up to the slip is the knot
coming undone), both in ``topology_preserved`` (the halves' linking, reported only). Neither
sees the butterfly fall apart into
an eye with its legs twisted once (the same invariants); its average crossing number does
(:mod:`knotmech.scenes.tied.crossings`).
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field, replace

import numpy as np

from knotmech import knots, rod
from knotmech.errors import InputError, check_count, check_nonnegative, check_positive
from knotmech.materials import DEMO_ROD_DENSITY
from knotmech.rod.constraints import Clamp, MovingNodes
from knotmech.scenes._common import check_memory, check_run_size, frames_bytes, pair_check_bytes
from knotmech.scenes._scene import RunControl, Scene, SceneRun, grip_path, post_contact
from knotmech.scenes.bends import (
    TIED_CAP_FLOOR,
    BendPull,
    BendRopes,
    GripEdgeStrains,
    StrainStop,
    _bend_verdict,
    _plain,
    held_note,
    pull_summary,
    undone_now,
)
from knotmech.scenes.curves import _edge_distances
from knotmech.scenes.tied import measure
from knotmech.scenes.tied._common import invariant, join_far
from knotmech.scenes.tied.crossings import average_crossings
from knotmech.scenes.tied.eye_linking import cut_knot_types, cut_linking
from knotmech.scenes.tied.pulled import NEAR_SET, OWN, PARALLEL, end_direction, invariants_changed

__all__ = ["LoopResult", "LoopScene", "loop", "LOOPS", "loop_inside", "loop_lengths"]

#: the loop knots with this scene (the registry's loops with a scene)
LOOPS = tuple(k.name for k in knots.records(family="loop") if k.scene.endswith("loops:loop"))

#: the start eye's size [d] of an end-to-end pull (no pin)
EYE_D = 5.0

#: invariants whose change fails a run: the closed rope's knot type and its turns round the pin
FAIL_KEYS = ("alexander", "winding_pin")  # alexander: kept by either closure (up or down)
#: end to end (no pin): the knot types of the rope's halves cut at the eye's tip, each
#: closed from outside the knot (:func:`~knotmech.scenes.tied.eye_linking.cut_knot_types`;
#: the butterfly's: two overhand knots while the tongue is through the window, unknots once
#: it has been drawn out: the knot came undone), kept with the closed rope's knot type in
#: ``topology_preserved``; the halves' linking (``linking_cut``) is reported only: a turn
#: of the free eye about its own axis changes it with the knot still tied
END_KEYS = ("types_cut",)


@dataclass
class LoopResult:
    """What a loop pull measured (SI units).

    Attributes
    ----------
    knot : str
    verdict : {"slips", "holds", ""}
        ``""`` when the run failed.
    slip_load : float [N]
        Largest pull force before the slip (NaN if it held).
    max_force : float [N]
        Largest pull force of the whole pull.
    pin_diameter, pull_speed, mu_rod_rod, mu_pin : float [m], [m/s], -, -
        (end to end: ``pin_diameter`` the eye's start size, no pin; ``mu_pin`` unused)
    times : (n_frames,) [s]
    pull_displacement : (n_frames,) [m]
        Travel of the standing end since the pull began.
    pull_force : (n_frames,) [N]
    tail_draw_in, eye_growth : (n_frames,) [m]
        Material draw-in of the tail and growth of the eye since the pull began (end to
        end: the growth of the right end's length outside the knot, and the eye's
        decrease: the eye drawn in).
    slipped_by : {"tail", "eye", "both", ""}
        Which grew by more than d/2 at the last frame ("both": both did); end to end:
        ``"eye"`` the eye drawn into the knot, ``"tail"`` the right end's length outside
        the knot grown (rope drawn out of the knot), ``"both"``.
    invariants_start, invariants_checked : dict
        :func:`knotmech.scenes.tied.measure` of the start shape and the last values defined
        on the frames checked.
    frames_checked : int
    law : str
    positions : (n_frames, n_nodes, 3) [m]
    status, message : str; stats : dict (steps, newton_iterations, wall_s)
    loading : {"loop", "end-to-end"}
    held_to_strain_limit : bool
        The pull stopped when a pulled end reached
        :data:`knotmech.scenes.bends.STRAIN_LIMIT` EA
        (:class:`~knotmech.scenes.bends.StrainStop`) and the loop had not slipped: it held
        to at least ``max_force``, a lower bound of its slip load (``verdict`` "holds").
    came_undone : bool
        The knot came undone in the pull (:meth:`LoopScene._undone`): the tail drawn
        through the knot (end to end: the eye's halves unlinked, the tongue out of the
        window); a slip at that frame (``verdict`` "slips", the slip load the largest
        force before it; frames after it not checked).
    """

    knot: str
    verdict: str
    slip_load: float
    max_force: float
    pin_diameter: float
    pull_speed: float
    mu_rod_rod: float
    mu_pin: float
    times: np.ndarray
    pull_displacement: np.ndarray
    pull_force: np.ndarray
    tail_draw_in: np.ndarray
    eye_growth: np.ndarray
    slipped_by: str
    invariants_start: dict
    invariants_checked: dict
    frames_checked: int
    law: str
    positions: np.ndarray
    status: str
    message: str
    stats: dict = field(default_factory=dict)
    loading: str = "loop"
    held_to_strain_limit: bool = False
    came_undone: bool = False

    @property
    def topology_preserved(self) -> bool:
        """The closed rope's knot type and its winding about the pin kept on every frame
        checked (end to end: the knot type and the cut halves' knot types, :data:`END_KEYS`;
        a knot that came undone is checked up to that frame, ``came_undone``)."""
        s, c = self.invariants_start, self.invariants_checked
        keys = ("alexander", *END_KEYS) if self.loading == "end-to-end" else FAIL_KEYS
        return all(s.get(k) == c.get(k) for k in keys)

    def summary(self, rod_diameter: float) -> dict:
        """:func:`knotmech.scenes.bends.pull_summary` and the loop's: ``loading``,
        ``slipped_by``, the last frame's ``tail_draw_in_d``, ``eye_growth_d`` and
        ``pull_travel_d`` in diameters of the run's ``rod_diameter`` [m] (None without
        frames), ``topology_preserved`` and ``pin_diameter_m``."""

        def last(a):
            return float(a[-1] / rod_diameter) if a.size else None

        row = pull_summary(self)
        row.update(
            loading=self.loading, slipped_by=self.slipped_by,
            tail_draw_in_d=last(self.tail_draw_in), eye_growth_d=last(self.eye_growth),
            pull_travel_d=last(self.pull_displacement),
            topology_preserved=bool(self.topology_preserved), pin_diameter_m=self.pin_diameter,
            came_undone=bool(self.came_undone),
        )  # fmt: skip
        return row

    def to_dict(self) -> dict:
        """Plain-JSON summary (curves as lists, positions left out)."""

        def num(v):
            return float(v) if np.isfinite(v) else None

        return {
            "scene": "loop",
            "knot": self.knot,
            "loading": self.loading,
            "verdict": self.verdict,
            "slip_load": num(self.slip_load),
            "max_force": num(self.max_force),
            "slipped_by": self.slipped_by,
            "tail_draw_in_end": num(self.tail_draw_in[-1]) if self.tail_draw_in.size else None,
            "eye_growth_end": num(self.eye_growth[-1]) if self.eye_growth.size else None,
            "pin_diameter": self.pin_diameter,
            "pull_speed": self.pull_speed,
            "mu_rod_rod": self.mu_rod_rod,
            "mu_pin": self.mu_pin,
            "topology_preserved": self.topology_preserved,
            "came_undone": bool(self.came_undone),
            "frames_checked": int(self.frames_checked),
            "law": self.law,
            "held_to_strain_limit": bool(self.held_to_strain_limit),
            "invariants_start": _plain(self.invariants_start),
            "invariants_checked": _plain(self.invariants_checked),
            "status": self.status,
            "message": self.message,
            "stats": {k: (float(v) if k == "wall_s" else int(v)) for k, v in self.stats.items()},
            "pull_displacement": [float(v) for v in self.pull_displacement],
            "pull_force": [num(v) for v in self.pull_force],
            "tail_draw_in": [float(v) for v in self.tail_draw_in],
            "eye_growth": [float(v) for v in self.eye_growth],
        }


def loop_inside(x, d: float, ignore=None) -> np.ndarray:
    """(n,) bool: the nodes of one rope ``x`` ((n, 3) [m]) inside the knot: within
    :data:`~knotmech.scenes.tied.pulled.NEAR_SET` d of a node of the rope more than
    :data:`~knotmech.scenes.tied.pulled.OWN` d of arc away whose tangent crosses it (more
    than 25 deg apart); nodes in the bool mask ``ignore`` are not counted as such strands."""
    x = np.asarray(x, float)
    h = float(np.mean(np.linalg.norm(np.diff(x, axis=0), axis=1)))
    idx = np.arange(len(x))
    far = np.abs(idx[:, None] - idx[None, :]) >= int(np.ceil(OWN * d / h))
    near = np.linalg.norm(x[:, None, :] - x[None, :, :], axis=2) < NEAR_SET * d
    t = np.gradient(x, axis=0)
    t /= np.linalg.norm(t, axis=1, keepdims=True)
    crossing = near & far & (np.abs(t @ t.T) < PARALLEL)
    if ignore is not None:
        crossing[:, np.asarray(ignore, bool)] = False
    return crossing.any(axis=1)


def _run_from(inside, k: int, step: int) -> int:
    """Nodes from ``k`` (included) walking by ``step`` before the first inside node."""
    n, j = len(inside), k
    while 0 <= j < n and not inside[j]:
        j += step
    return abs(j - k)


def loop_lengths(x, d: float, h: float, eye_cut: int) -> tuple[float, float]:
    """(tail length outside the knot, eye length outside the knot) [m] of one frame.

    Material lengths: node counts times the rest edge length ``h`` [m]. The tail is the run
    of outside nodes from the last node inwards; the eye, the run of outside nodes either
    side of the node ``eye_cut`` (the eye's farthest point round the pin), the free tail
    not counted as a strand crossing it.
    """
    inside = loop_inside(x, d)
    n = len(inside)
    tail = _run_from(inside, n - 1, -1)
    free_tail = np.arange(n) >= n - tail  # a free tail swinging across the eye is no knot
    inside = loop_inside(x, d, ignore=free_tail)
    eye = _run_from(inside, eye_cut, -1) + _run_from(inside, eye_cut, 1) - 1
    return h * max(tail - 1, 0), h * max(eye, 0)


def loop(
    knot: str,
    *,
    loading: str = "loop",
    pin_diameter: float | None = None,
    rod_diameter: float = 4e-3,
    youngs_modulus: float = 1.0e6,
    density: float = DEMO_ROD_DENSITY,
    bending_scale: float = 1.0,
    mu_rod_rod: float = 0.3,
    mu_kinetic: float | None = None,
    mu_pin: float | None = None,
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
) -> LoopResult:
    r"""Tie a loop round a pin, pull its standing part away from the pin, report the slip load.

    Parameters
    ----------
    knot : str
        ``"bowline"``, ``"figure-eight-loop"`` or ``"alpine-butterfly"`` (or an alias).
    loading : {"loop", "end-to-end"}
        ``"loop"`` (default): the eye round the pin, node 0 (the standing part) pulled, the
        tail free. ``"end-to-end"`` (the alpine butterfly only: a mid-line knot isolating a
        damaged stretch): no pin, the eye free, both ends set and then pulled apart along
        their end tangents, each at ``pull_speed`` for ``pull_distance``; the pull force
        is the mean of the two grips' reactions (as the tied bends').
    pin_diameter : float [m]
        Diameter D of the pin the eye goes round (required for the loop loading; 0.5-40
        d). End to end: the size of the start eye only (default 5 d), no pin.
    rod_diameter : float [m]
        d (default 4 mm).
    youngs_modulus : float [Pa]
        Of the solid elastic rod (default 1 MPa; :math:`B = E\pi d^4/64`).
    density : float [kg/m^3]
    bending_scale : float
        kappa in (0, 1]: bending and twisting stiffness times the solid rod's.
    mu_rod_rod, mu_kinetic : float
        Static and kinetic rope-rope friction (``mu_kinetic`` None: the static).
    mu_pin : float, optional
        Rope-pin friction (default ``mu_rod_rod``).
    pull_speed : float [m/s]
        Speed of the standing end (set and pull).
    pull_distance : float [m], optional
        Travel of the standing end in the pull (default 20 d).
    settle_time : float [s]
        Both ends held while the contacts settle; also the length of the release (the
        standing end held, the tail let go) between the set and the pull.
    n_nodes : int, optional
        Nodes of the rope (default: its record's, 175 bowline, 130 figure-eight loop and
        alpine butterfly).
    dt : float [s]
        Nominal step.
    slip_draw_in : float [m], optional
        Tail draw-in or eye growth near the largest force that counts as a slip (2 d).
    set_tension : float [N], optional
        The standing part and the tail are pulled outwards until the tension next to each
        grip reaches this (default :math:`0.1 B/d^2`) or for ``set_travel``.
    set_travel : float [m], optional
        Largest travel of each end while setting (default 20 d).
    force_scale : float [N], optional
        Sizes the contact penalties (default :math:`2 B/d^2`).
    contact_width : float
        Range of the rod-rod penalty in rod diameters.
    n_frames : int, optional
        Recorded frames of the pull (>= 10; default 20: each is checked).
    options : knotmech.rod.SolverOptions, optional
    progress : bool

    Returns
    -------
    LoopResult

    Raises
    ------
    InputError
        A bad argument (no pin diameter for the loop loading, D <= 0 or NaN, D outside
        0.5-40 d, an unknown loop or loading), or a run above the size bounds.

    Notes
    -----
    Cost at the defaults (d = 4 mm, E = 1 MPa, D = 20 mm): bowline 10-11 s of CPU (175
    nodes), figure-eight loop 10-27 s over mu = 0.1-1 (130 nodes, drawn-in start; at
    mu >= 0.6 stopped at the strain limit, 56 s at mu = 1 before the stop), alpine
    butterfly 2-10 s (130 nodes, drawn-in start);
    ``benchmarks/tied.py --loops``, docs/notes/knots-and-curves/tied-loops-pulled.md.
    """
    rec = _record(knot)
    defaults = {"n_nodes": 150, "n_frames": 20, "pull_distance_d": 20.0, "set_travel_d": 20.0,
                "loadings": ("loop",), **rec.scene_defaults}  # fmt: skip
    if loading not in defaults["loadings"]:
        raise InputError(f"loading of {rec.name} must be one of "
                         f"{', '.join(defaults['loadings'])}, got {loading!r}")  # fmt: skip
    d = float(check_positive("rod_diameter", rod_diameter, scalar=True))
    if loading == "end-to-end" and pin_diameter is None:
        pin_diameter = EYE_D * d
    if pin_diameter is None:
        raise InputError(
            f"{rec.name} needs pin_diameter: the diameter of the pin its eye goes round"
        )
    ropes = BendRopes(
        rod_diameter=d, youngs_modulus=youngs_modulus, density=density,
        bending_scale=bending_scale, mu_rod_rod=mu_rod_rod, mu_kinetic=mu_kinetic,
        n_nodes=defaults["n_nodes"] if n_nodes is None else n_nodes,
        force_scale=force_scale, contact_width=contact_width,
    )  # fmt: skip
    pull = BendPull(
        pull_speed=pull_speed,
        pull_distance=defaults["pull_distance_d"] * d if pull_distance is None else pull_distance,
        settle_time=settle_time,
        slip_draw_in=slip_draw_in,
        set_tension=set_tension,
        set_travel=defaults["set_travel_d"] * d if set_travel is None else set_travel,
    )
    control = RunControl(
        dt=dt, n_frames=defaults["n_frames"] if n_frames is None else n_frames,
        options=options, progress=progress,
    )  # fmt: skip
    return LoopScene(rec, pin_diameter=pin_diameter, mu_pin=mu_pin, ropes=ropes, pull=pull,
                     control=control, loading=loading).run()  # fmt: skip


def _record(knot):
    """The registry record of a loop with this scene; a one-line InputError otherwise."""
    names = LOOPS
    key = knots.key(knot) if isinstance(knot, str) else ""
    if key not in names:
        raise InputError(f"loop must be one of {', '.join(names)}, got {knot!r}")
    return knots.get(key)


def _slip_frame(force, draw, out, slip) -> int:
    """The first pull frame where :func:`~knotmech.scenes.bends._bend_verdict` sees the
    slip (the last frame if it held)."""
    if not force.size:
        return -1
    k_near = int(np.nonzero(force >= 0.9 * np.nanmax(force))[0][0])
    beyond = draw.max(axis=1) - draw[k_near].max()
    slipped = np.nonzero(((beyond > slip) & (np.arange(force.size) >= k_near)) | out)[0]
    return int(slipped[0]) if slipped.size else len(force) - 1


class LoopScene(Scene):
    """A loop round a fixed pin, set and pulled by its standing part: the phases of
    :func:`loop`."""

    def __init__(self, record, *, pin_diameter, mu_pin, ropes, pull, control, loading="loop"):
        self.record, self.ropes, self.pull, self.control = record, ropes, pull, control
        self.pin_diameter, self.mu_pin_in = pin_diameter, mu_pin
        self.loading = loading
        self.ends = loading == "end-to-end"  # both ends pulled, the eye free, no pin

    # -- setup -----------------------------------------------------------------------
    def setup(self) -> None:
        """Inputs and cost checked; the loop tied, its pin moved to the origin."""
        o, p = self.ropes, self.pull
        self.d = d = float(check_positive("rod_diameter", o.rod_diameter, scalar=True))
        self.E = float(check_positive("youngs_modulus", o.youngs_modulus, scalar=True))
        self.rho = float(check_positive("density", o.density, scalar=True))
        self.mu = float(check_nonnegative("mu_rod_rod", o.mu_rod_rod, scalar=True))
        mp = self.mu_pin_in
        self.mu_pin = self.mu if mp is None else float(check_nonnegative("mu_pin", mp, scalar=True))
        self.v = float(check_positive("pull_speed", p.pull_speed, scalar=True))
        self.dist = float(check_positive("pull_distance", p.pull_distance, scalar=True))
        self.set_travel = float(check_positive("set_travel", p.set_travel, scalar=True))
        self.slip = 2 * d if p.slip_draw_in is None else float(
            check_positive("slip_draw_in", p.slip_draw_in, scalar=True))  # fmt: skip
        check_count("n_frames", self.control.n_frames, 10)
        check_positive("contact_width", o.contact_width, scalar=True)
        self.B = B = self.E * np.pi * d**4 / 64
        self.f_set = 0.1 * B / d**2 if p.set_tension is None else float(
            check_positive("set_tension", p.set_tension, scalar=True))  # fmt: skip
        self.fs = 2 * B / d**2 if o.force_scale is None else float(
            check_positive("force_scale", o.force_scale, scalar=True))  # fmt: skip
        self.settle_time = float(check_positive("settle_time", p.settle_time, scalar=True))
        self.dt = float(check_positive("dt", self.control.dt, scalar=True))
        self._check_cost()
        self._tie()

    def _check_cost(self) -> None:
        n = check_count("n_nodes", self.ropes.n_nodes, 40)
        t_end = self.settle_time + (self.set_travel + self.dist) / self.v
        check_run_size(n_nodes=n, t_end=t_end, dt=self.dt,
                       hint="use fewer nodes (n_nodes), a larger dt or a shorter pull")  # fmt: skip
        check_memory(pair_check_bytes(n) + frames_bytes(self.control.n_frames + 100, n),
                     what=f"the strands' overlap check on {n} nodes",
                     hint="use fewer nodes (n_nodes)")  # fmt: skip

    def _tie(self) -> None:
        """The loop's start curve, shifted so that its pin's axis is the z axis."""
        knot = self.record.curve_function()(
            rod_diameter=self.d,
            n_nodes=int(self.ropes.n_nodes),
            pin_diameter=self.pin_diameter,
            **self.record.curve_params,
        )
        c = np.array(knot.pin["point"], float)
        x = knot.ropes["rope"] - c
        pin = dict(knot.pin, point=(0.0, 0.0, 0.0))
        info = dict(knot.info, pin_center=(0.0, 0.0, 0.0))
        self.eye_cut = int(knot.info["eye_cut"])
        self.min_crossings = knot.info.get("min_crossings")
        if self.ends:  # no pin: the closed rope's knot type only (no winding, no cut halves)
            pin, info = None, {k: v for k, v in info.items() if k != "eye_cut"}
        self.knot = replace(knot, ropes={"rope": x}, pin=pin, info=info)
        self.x0 = x
        self.D = float(knot.pin["diameter"])
        self.inv_start = self._measure(x)
        self.alex_down0 = self._alexander_down(x)
        self.u = end_direction(x, "start")

    # -- build -----------------------------------------------------------------------
    def build(self) -> SceneRun:
        """The rope, its contacts with itself and with the pin, the overlap watch."""
        o, d = self.ropes, self.d
        r = rod.Rod(positions=self.x0, radius=0.5 * d, youngs_modulus=self.E, density=self.rho,
                    natural="straight", bending_scale=o.bending_scale)  # fmt: skip
        self.system = system = rod.RodSystem([r])
        self.N = N = int(o.n_nodes)
        self.h = float(system.rest_length.mean())
        idx = np.arange(N - 1)
        self.far = np.abs(idx[:, None] - idx[None, :]) >= 3
        c = 0.01 * self.B / d**2 / (float(system.rest_length.sum()) * self.v)
        self.drag = rod.ViscousDamping(coefficient=c)
        nodes, edges = system.rod_nodes(0), system.rod_edges(0)
        self.grip = ([int(nodes[0]), int(nodes[1])], int(edges[0]))
        self.tail = ([int(nodes[-1]), int(nodes[-2])], int(edges[-1]))
        k = self.eye_cut
        self.eye_grip = ([int(nodes[k]), int(nodes[k + 1])], int(edges[k]))
        pin = post_contact(post_diameter=self.D, rod_diameter=d, force_scale=self.fs,
                           mu_static=self.mu_pin)  # fmt: skip
        ctl = self.control
        inter = [self._contact()] if self.ends else [self._contact(), pin]
        return SceneRun(system, interactions=inter, options=ctl.options,
                        watch=self._watch, progress=ctl.progress)  # fmt: skip

    def _contact(self):
        """Rope-rope contact: the tied bends' law (anchor, cap floored), path tunnel guard."""
        mk = self.mu if self.ropes.mu_kinetic is None else float(
            check_nonnegative("mu_kinetic", self.ropes.mu_kinetic, scalar=True))  # fmt: skip
        if mk > self.mu:
            raise InputError(f"mu_kinetic must be <= mu_rod_rod ({self.mu:g}), got {mk:g}")
        fr = None
        if self.mu > 0:
            fr = rod.AnchorFriction(mu_static=self.mu, mu_kinetic=mk, cap_floor=TIED_CAP_FLOOR)
        w = float(self.ropes.contact_width)
        return rod.RodContact(stiffness=20.0 * self.fs / self.d, sharpness=15.0 / (w * self.d),
                              friction=fr, tunnel_check="path")  # fmt: skip

    def _watch(self, x):
        gap = _edge_distances(x)[self.far].min()
        if gap < 0.5 * self.d:
            return f"strands overlap by more than half a diameter (gap {gap / self.d:.2f} d)"
        return None

    # -- phases ----------------------------------------------------------------------
    def run_phases(self, run: SceneRun) -> None:
        """Settle (both ends held), set (both ends pulled out), release (the standing end
        held, the tail let go), pull (the tail free). End to end: the eye held in the
        settle and the set too, let go in the release (both ends held), free in the pull
        (both ends pulled)."""
        g, t = self.grip, self.tail
        mass = self.rho * np.pi * self.d * self.d / 4
        self.t_wall = time.perf_counter()
        held = [g, t, self.eye_grip] if self.ends else [g, t]
        run.phase("settle", self.settle_time, dt=self.dt,
                  loads=[rod.ViscousDamping(coefficient=20.0 * mass / self.settle_time)],
                  constraints=[Clamp(nodes=[n for h in held for n in h[0]],
                                     edges=[h[1] for h in held])])  # fmt: skip
        self._set(run)
        if run.ok:  # the tail (end to end: the eye) let go, the loaded end(s) held: it seats
            ends = [g, t] if self.ends else [g]
            run.phase("release", self.settle_time, dt=self.dt,
                      loads=[rod.ViscousDamping(coefficient=20.0 * mass / self.settle_time)],
                      constraints=[Clamp(nodes=[n for h in ends for n in h[0]],
                                         edges=[h[1] for h in ends])])  # fmt: skip
        self._pull(run)

    def _moving(self, run, ends):
        """Grips moving at ``pull_speed`` along the outward end tangents of ``ends``."""
        x = self.system.positions(run.state.q)
        return [MovingNodes(nodes=g[0], path=grip_path(x[g[0]], u, self.v, run.t))
                for g, u in ends]  # fmt: skip

    def _set(self, run: SceneRun) -> None:
        """Set (dress) the loop as a rigger does: the standing part and the tail pulled
        outwards along their end tangents until the tension next to each grip reaches
        ``set_tension`` (read on the first free edge: the end edges are rigid). A loose
        loop pulled by its standing part alone, the tail free, does not set: it capsizes
        and unties (docs/notes/knots-and-curves/tied-loops-pulled.md)."""
        strains = GripEdgeStrains(self.system, [self.grip, self.tail])

        def tension(x):
            return float(np.min(strains.ea * strains(x)))

        if run.ok:
            x = self.system.positions(run.state.q)
            u_tail = end_direction(x, "end")
            travel = self.set_travel
            if not self.ends:
                travel = min(travel, self._clear_of_pin(x[self.tail[0][0]], u_tail))
            grips = [(self.grip, self.u), (self.tail, u_tail)]
            # end to end: the eye held where it is (drawn out, it withdraws the tongue
            # from the loose window: the knot comes undone in the set)
            eye = self.eye_grip if self.ends else ([], None)
            edges = [g[1] for g, _ in grips] + ([eye[1]] if self.ends else [])
            run.phase("set", travel / self.v, dt=self.dt, loads=[self.drag],
                      constraints=[*self._moving(run, grips), Clamp(nodes=eye[0], edges=edges)],
                      stop=lambda x: tension(x) >= self.f_set)  # fmt: skip

    def _clear_of_pin(self, p, u) -> float:
        """Travel [m] of a grip from ``p`` along ``u`` that stays 2 d clear of the pin (the
        bowline's tail, inside the eye, points at it); inf if the path misses the pin."""
        p, u = np.asarray(p[:2], float), np.asarray(u[:2], float)
        a = float(u @ u)
        R = 0.5 * (self.D + self.d) + 2.0 * self.d
        b, c = float(p @ u), float(p @ p) - R * R
        disc = b * b - a * c
        if a == 0.0 or disc < 0.0 or -b - np.sqrt(disc) < 0.0:
            return float("inf")
        return max((-b - np.sqrt(disc)) / a, 0.0) * float(np.sqrt(a))

    def _pull(self, run: SceneRun) -> None:
        """The standing end pulled on, the tail free; stops when the tail runs out."""
        if not run.ok:
            return
        x = self.system.positions(run.state.q)
        if self._apart(x):  # fell apart in the settle or the set: nothing to pull
            self.apart_before = average_crossings(x)
            return
        self.lengths0 = np.array(loop_lengths(x, self.d, self.h, self.eye_cut))
        self.t0 = run.t
        self.x_pull0, self._run, self._t_undone = x, run, -np.inf
        cons = [*self._moving(run, [(self.grip, self.u)]), Clamp(edges=[self.grip[1]])]
        pulled = [self.grip]
        if self.ends:  # the right end pulled too, along its end tangent now
            self.u_end = end_direction(x, "end")
            cons = [*self._moving(run, [(self.grip, self.u), (self.tail, self.u_end)]),
                    Clamp(edges=[self.grip[1], self.tail[1]])]  # fmt: skip
            pulled = [self.grip, self.tail]
        # stops when the tail runs out or a pulled end reaches the rod model's strain limit
        self.strain_stop = StrainStop(self.system, pulled, self._tail_out)
        run.phase("pull", self.dist / self.v, dt=self.dt, loads=[self.drag], constraints=cons,
                  save_every=self.dist / self.v / int(self.control.n_frames),
                  stop=self.strain_stop)  # fmt: skip

    def _tail_out(self, x) -> bool:
        """Whether the tail has run out of the knot (end to end: the eye drawn into it) or,
        looked at every :data:`~knotmech.scenes.bends.UNDONE_EVERY` s, the knot came undone
        (:meth:`_undone`)."""
        tail, eye = loop_lengths(x, self.d, self.h, self.eye_cut)
        if self.ends:  # the eye drawn into the knot
            out = eye < self.d and self.lengths0[1] - eye > self.slip
        else:
            out = tail < self.d and self.lengths0[0] - tail > self.slip
        return bool(out) or undone_now(self, x)

    def _undone(self, x) -> str:
        """Why the knot came undone at ``x`` [m] (``""``: it did not). A knot with
        ``info["min_crossings"]`` (the alpine butterfly): :meth:`_apart`. On the loop: the
        closed rope's knot type differs from the start's in both closures (lifted up and down:
        :meth:`_frame_invariants`) while the tail end has moved towards the knot by more
        than the slip draw-in since the pull began (the tail drawn through the knot, as
        :meth:`knotmech.scenes.bends.TiedBendScene._undone`). End to end: the knot types
        of both halves of the rope cut at the eye (:meth:`_cut_types`) differ from the
        start's (the tongue drawn out of the window: the butterfly's overhand halves become
        unknots; their linking is not used, as a turn of the free eye about its own axis
        changes it with the knot still tied). The
        overlap watch of every step excludes a strand passing through another; a knot type
        changed with the tail not drawn in fails the run (:meth:`_topology`)."""
        if self._apart(x):
            return f"its average crossing number below {self.min_crossings:g} (fell apart)"
        if self.ends:
            now, start = self._cut_types(x), self.inv_start.get("types_cut")
            if now is None or start is None:
                return ""
            if all(a != b for a, b in zip(now, start, strict=True)):
                return ("both halves cut at the eye changed their knot type: the tongue "
                        "drawn out of the window")  # fmt: skip
            return ""
        u = end_direction(self.x_pull0, "end")
        if float((self.x_pull0[-1] - x[-1]) @ u) <= self.slip:
            return ""
        if self._frame_invariants(x, cut=False)["alexander"] != self.inv_start["alexander"]:
            return "its tail drawn through the knot"
        return ""

    # -- measure ---------------------------------------------------------------------
    def measure(self, run: SceneRun) -> LoopResult:
        """Pull force, draw-in and eye growth, verdict, topology; the status checked."""
        times, pos = run.frames()
        m = run.phase_mask("pull")
        tp, pm = times[m], pos[m]
        force = self._force(run, tp)
        draw, out = self._draw(pm)
        pulled = bool(np.isfinite(force).any() and np.nanmax(force) > 0)
        self.k_undone = None
        if pulled:  # came undone up to the slip: a slip there (later: the slip's aftermath)
            self.k_undone = self._first_undone(pm, _slip_frame(force, draw, out, self.slip))
            if self.k_undone is not None:
                out[self.k_undone :] = True
            verdict, slip_load, _ = _bend_verdict(force, draw, out, self.slip)
            k_slip = _slip_frame(force, draw, out, self.slip)
        else:  # no pull frame, or no positive pull force recorded
            verdict, slip_load, k_slip = "", float("nan"), len(force) - 1
        status, message = self._topology(run, pm, tp, k_slip)
        if hasattr(self, "apart_before"):
            status, message = "failed", (
                f"came apart before the pull (settle and set): average crossing number "
                f"{self.apart_before:.1f} < {self.min_crossings:g} (a twisted eye, not the "
                "knot); no slip load")  # fmt: skip
        if status == "success" and not pulled:
            status, message = "failed", "no pull frame with a positive pull force recorded"
        if status != "success":
            verdict = ""
        stop = getattr(self, "strain_stop", None)
        held = bool(stop is not None and stop.reached and verdict == "holds")
        if held:
            message = "; ".join(filter(None, (held_note(float(np.nanmax(force))), message)))
        stats = dict(run.stats)
        stats["wall_s"] = time.perf_counter() - self.t_wall
        return LoopResult(
            knot=self.record.name, verdict=verdict, slip_load=slip_load,
            max_force=float(np.nanmax(force)) if force.size else float("nan"),
            pin_diameter=self.D, pull_speed=self.v, mu_rod_rod=self.mu, mu_pin=self.mu_pin,
            times=tp, pull_displacement=self.v * (tp - getattr(self, "t0", 0.0)),
            pull_force=force, tail_draw_in=draw[:, 0], eye_growth=draw[:, 1],
            slipped_by=self._slipped_by(draw), invariants_start=self.inv_start,
            invariants_checked=getattr(self, "inv_checked", dict(self.inv_start)),
            frames_checked=getattr(self, "frames_checked", 0), law=self._law(),
            positions=pos, status=status, message=message, stats=stats, loading=self.loading,
            held_to_strain_limit=held,
            came_undone=status == "success" and getattr(self, "k_undone", None) is not None,
        )  # fmt: skip

    def _force(self, run, tp):
        """Pull force [N]: the standing grip's reaction along its pull (both gripped nodes);
        end to end, the mean of the two grips'."""
        g = self.grip[0]
        force = run.reaction(g[:1], tp) @ self.u + run.reaction(g[1:], tp) @ self.u
        if self.ends and hasattr(self, "u_end"):
            t = self.tail[0]
            other = run.reaction(t[:1], tp) @ self.u_end + run.reaction(t[1:], tp) @ self.u_end
            force = 0.5 * (force + other)
        return force

    def _early(self, key: str) -> str:
        """Why the invariant ``key`` reported may change before the slip: the free tail
        swinging; end to end, the eye drawn out of the window (the knot came undone: the
        halves' knot types), or a turn of the free eye (their linking alone)."""
        if not self.ends:
            return " (free tail)"
        if key in END_KEYS:
            return " (the knot came undone)"
        return " (reported only: a turn of the free eye changes it)"

    def _law(self) -> str:
        if self.ends:
            return (f"anchor (sticking) friction, cap floor {TIED_CAP_FLOOR:g} (r_i + r_j), "
                    "path tunnelling guard; no pin (end to end)")  # fmt: skip
        return (f"anchor (sticking) friction, cap floor {TIED_CAP_FLOOR:g} (r_i + r_j), "
                f"path tunnelling guard; pin: anchor friction mu = {self.mu_pin:g}")  # fmt: skip

    def _draw(self, pm):
        """(n, 2) [m] tail draw-in and eye growth since the pull began; (n,) tail run out
        (end to end: the eye drawn into the knot)."""
        if not len(pm):
            return np.zeros((0, 2)), np.zeros(0, bool)
        k = self.eye_cut
        now = np.array([loop_lengths(x, self.d, self.h, k) for x in pm])
        draw = np.column_stack([self.lengths0[0] - now[:, 0], now[:, 1] - self.lengths0[1]])
        if self.ends:  # rope drawn out of the knot into the right end, the eye drawn in
            draw, out = -draw, (now[:, 1] < self.d) & (-draw[:, 1] > self.slip)
        else:
            out = (now[:, 0] < self.d) & (draw[:, 0] > self.slip)
        return draw, out

    def _apart(self, x) -> bool:
        """Whether a knot whose curve sets ``info["min_crossings"]`` (the alpine butterfly)
        fell apart at ``x``: its average crossing number
        (:func:`~knotmech.scenes.tied.crossings.average_crossings`) below that (a twisted
        eye, whose invariants are the butterfly's)."""
        least = self.min_crossings
        return least is not None and average_crossings(x) < least

    def _first_undone(self, pm, last: int):
        """The first pull frame up to ``last`` where the knot came undone (:meth:`_undone`),
        or None."""
        for j in range(min(last + 1, len(pm))):
            self.undone_why = self._undone(pm[j])
            if self.undone_why:
                return j
        return None

    def _undone_note(self, t) -> str:
        return (f"came undone at t = {t:.3f} s: {self.undone_why} (a slip; frames after it "
                "not checked)")  # fmt: skip

    def _slipped_by(self, draw) -> str:
        if not draw.size:
            return ""
        grew = draw[-1] > 0.5 * self.d
        return {(True, False): "tail", (False, True): "eye", (True, True): "both"}.get(
            (bool(grew[0]), bool(grew[1])), "")  # fmt: skip

    def _alexander(self, x) -> tuple:
        """Alexander polynomial of the rope at ``x`` closed far outside (ends lifted up, the
        far circle about the pin's axis; end to end about the rope's centroid): the
        ``alexander`` of :func:`~knotmech.scenes.tied.measure`."""
        centre = None if self.knot.pin is None else self.knot.pin["point"]
        return invariant(join_far([x], center=centre))

    def _alexander_down(self, x) -> tuple:
        """Alexander polynomial of the rope closed with its ends lifted down (-z): the
        frame mirrored in z and closed as usual (the polynomial does not see the mirror)."""
        return self._alexander(x * np.array([1.0, 1.0, -1.0]))

    def _cut_linking(self, x) -> int | None:
        """End to end: the linking of the rope's halves cut at the eye's tip (the node
        ``eye_cut``, material), each closed from outside the knot along the ray from the
        knot's centre (the mean of the nodes inside it, :func:`loop_inside`) through its
        cut end (:func:`~knotmech.scenes.tied.eye_linking.cut_linking`)."""
        inside = loop_inside(x, self.d)
        centre = x[inside].mean(axis=0) if inside.any() else None
        return cut_linking(x, self.eye_cut, centre)

    def _cut_types(self, x) -> tuple | None:
        """End to end: the knot types of the rope's halves cut at the eye's tip, closed as
        in :meth:`_cut_linking` (:func:`~knotmech.scenes.tied.eye_linking.cut_knot_types`;
        the butterfly's: two overhand knots while tied)."""
        inside = loop_inside(x, self.d)
        centre = x[inside].mean(axis=0) if inside.any() else None
        return cut_knot_types(x, self.eye_cut, centre)

    def _measure(self, x) -> dict:
        """:func:`~knotmech.scenes.tied.measure` of the rope at ``x``; end to end (no pin)
        with ``linking_cut`` (:meth:`_cut_linking`) and ``types_cut`` (:meth:`_cut_types`)."""
        out = measure(replace(self.knot, ropes={"rope": x}))
        if self.ends:
            out["linking_cut"] = self._cut_linking(x)
            out["types_cut"] = self._cut_types(x)
        return out

    def _frame_invariants(self, x, *, cut: bool = True) -> dict:
        """:func:`~knotmech.scenes.tied.measure` of one frame (``cut`` False: the closed
        rope's ``alexander`` alone); ``alexander`` the start's when either closure keeps
        its start value: the ends lifted up (+z, the curve's closure) or down. A free tail
        end passing under a strand changes the first, over one the second; a strand
        through another changes both."""
        now = self._measure(x) if cut else {"alexander": self._alexander(x)}
        if now.get("alexander") != self.inv_start.get("alexander"):
            if self._alexander_down(x) == self.alex_down0:
                now["alexander"] = self.inv_start["alexander"]
        return now

    def _topology(self, run, pm, tp, k_slip):
        """Every pull frame's invariants against the start's. Up to the slip frame
        ``k_slip``, a change of the closed rope's knot type or winding fails the run; after
        it (the tail end travelling through the knot, where the closure of the open rope
        lifted from the tail end is not defined) and for the cut halves, a change is
        reported in the message."""
        self.inv_checked = got = dict(self.inv_start)
        self.frames_checked, moved = 0, {}
        for k in range(len(pm)):
            if self.k_undone is not None and k >= self.k_undone:
                return run.status, run.message or self._undone_note(tp[k])
            try:
                now = self._frame_invariants(pm[k])
            except InputError as e:
                return "failed", f"t = {tp[k]:.3f} s: the frame does not close ({e})"
            self.frames_checked += 1
            changed = invariants_changed(self.inv_start, now)
            for key in changed:
                moved.setdefault(key, (tp[k], now[key]))
            bad = [key for key in changed if key in FAIL_KEYS]
            if bad and k <= k_slip:
                return "failed", (f"knot type changed at t = {tp[k]:.3f} s ({', '.join(bad)}) "
                                  "before the loop slipped: a strand through another, or the "
                                  "tail out through the closure; not a result")  # fmt: skip
            if k <= k_slip:
                got.update({key: v for key, v in now.items() if v is not None})
                if self.ends:  # a change up to the slip stays recorded (kept on every frame)
                    got.update({key: v for key, (_, v) in moved.items() if key in END_KEYS})
        note = "; ".join(f"{key} {self.inv_start[key]} -> {v} at t = {t:.3f} s"
                         + (" (after the slip)" if t > tp[k_slip] else self._early(key))
                         for key, (t, v) in moved.items())  # fmt: skip
        return run.status, run.message or note

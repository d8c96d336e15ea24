r"""Hitches pulled along the pole's axis: the clove hitch under a normal load, the Prusik.

The sliding test of Sabater, Park, Crassous, Neukirch & Reis (JMPS 2026, arXiv 2604.06962):
a filament tied round a cylinder, its legs tensioned perpendicular to the cylinder, and the
cylinder translated along its own axis; the sliding strength is the axial force at which the
knot slides along the cylinder. Here the pole is fixed (the z axis) and the knot is dragged
along +z instead (the same relative motion):

1. **settle**: both legs under a small pre-tension along their tails (the start curve's end
   tangents), with the settling drag;
2. **load**: the legs' dead loads ramped to the normal load ``normal_load`` T (both legs);
3. **drag**: the legs' two end nodes are gripped where the loads left them (the legs are
   clamped, as a filament whose pre-tensioned ends are fixed while the cylinder moves) and
   moved along the pole at ``drag_speed`` for ``drag_distance``. The **axial force** F is
   the sum of the grips' reactions along the pull, the **knot travel** the mean axial
   displacement of the nodes that started on the pole. As the grips move, the legs tilt and
   stretch, F rises, and the knot is dragged along. The **sliding force** :math:`F_s` is F
   when the knot has travelled ``slide_distance`` (default one rod diameter); the peak and
   the plateau (mean over the last third of the travel) of F are reported too. A knot that
   never travelled that far held (``slid`` False, :math:`F_s` nan).

   With ``legs="dead"`` (the clove hitch) the legs keep their dead loads T along the tails
   and only their ends' axial position is driven (:class:`AxialGrip`): F = 2 T tan of the
   legs' tilt rises to a plateau while the knot slides with the grips; the plateau is then
   the sliding force at a normal load that stays T.

The Prusik (:func:`knotmech.scenes.tied.prusik.prusik`, a closed sling) is opened at its
loaded loop: the half turn at the bottom of the loop is cut out and each of the two legs'
ends carries half of the axial load along -z, as the two strands of a loop pulled by a
carabiner. It has no separate normal load: the axial load is what grips (its ``normal_load``
is the pre-tension of the settling, per leg).

The rolling hitch (:mod:`knotmech.scenes.hitch_curves.rolling_hitch`) has its standing part
along the pole (towards -z, the riding turns' side) and its working end perpendicular to it.
Both are set at T along their tails, the standing part's end kept on the pole's line
(:class:`LineGuide`: a free end along the pole swings round it and unwinds the turns of the
stiff rod); in the drag only the standing part's end is gripped and moved along -z, the
working end keeping its load T. F starts at T (the standing part's set).

The Prusik's drag ends once the grips have moved 0.5 d further after its knot slid
(:data:`PLATEAU_WINDOW_D`): past the slide its legs only stretch (the default 8 d drag
stalled at 18 % strain).

Contacts: rigid pole with sticking (anchor) friction on the rod surface
(:func:`~knotmech.scenes._scene.post_contact`), rod-rod contact with the anchor law at
``cap_floor = 1e-2`` and the path tunnelling guard (``tunnel_check="path"``), sized for the
largest force of the run. The knot type is checked on frames of the run (the invariants of
:func:`~knotmech.scenes.hitch_curves.hitch_invariants`: Alexander polynomial of the rod closed
far away and its linking number with the pole) and the strands' distance and the pole gap on
every step.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from knotmech import rod
from knotmech.errors import InputError, check_bending_scale, check_nonnegative, check_positive
from knotmech.materials import PHASE_TABLE_DENSITY, VPS32_YOUNGS_MODULUS
from knotmech.rod.constraints import MovingNodes, NodeConstraint
from knotmech.rod.contact import RodContact
from knotmech.rod.friction import AnchorFriction
from knotmech.scenes._common import check_post_size, check_run_size, fail, measured_strain
from knotmech.scenes._hitch import _check_invariants
from knotmech.scenes._scene import (
    RampedEndLoad,
    RunControl,
    Scene,
    SceneRun,
    grip_path,
    post_contact,
)
from knotmech.scenes.curves import _edge_distances
from knotmech.scenes.hitch_curves._parts import hitch_invariants
from knotmech.scenes.topology import winding_number

__all__ = ["AXIAL_KNOTS", "AxialGrip", "AxialResult", "axial_pull", "axial_curve"]

#: knots this scene drags along the pole
AXIAL_KNOTS = ("clove-hitch", "prusik", "rolling-hitch")
#: knots whose drag ends ``plateau_window`` (default, in rod diameters of the grips' travel)
#: after the knot has slid: the Prusik, whose legs along the pole only stretch as the drag
#: goes on past the slide (the three-turn Prusik at 0.5 N slid at 22.6 mm of the grips'
#: travel and its default 8 d drag stalled at 26.8 mm, 18 % strain); the clove hitch's clamped
#: curve keeps rising and its T-kept plateau comes late, and the rolling hitch's drag ran its
#: 8 d, so they run the whole drag_distance
PLATEAU_WINDOW_D = {"prusik": 0.5}
#: the anchor law's cap floor (docs/notes/contact-and-friction/sticking-law-cap-width.md)
CAP_FLOOR = 1e-2


@dataclass(frozen=True)
class AxialGrip(NodeConstraint):
    """Move the z coordinate of ``nodes`` at ``speed`` [m/s] along ``sense`` (+1: +z) from
    ``t_start`` [s], from ``z_start`` [m]; their x and y stay free (a constraint for
    :func:`knotmech.rod.simulate`: the reactions on ``nodes`` carry the grip's force in z)."""

    nodes: tuple
    z_start: tuple
    speed: float
    sense: float
    t_start: float

    def dofs(self, system) -> np.ndarray:
        return system.node_dofs[self.node_indices(system), 2]

    def values(self, system, t_new, dt, q_old) -> np.ndarray:
        shift = self.sense * self.speed * max(t_new - self.t_start, 0.0)
        return np.asarray(self.z_start, dtype=float) + shift


@dataclass(frozen=True)
class LineGuide(NodeConstraint):
    """Hold the x and y coordinates of ``nodes`` at ``xy`` [m] (their z free): a guide that
    keeps the rolling hitch's standing part on the pole's line while its dead load sets the
    knot (a free end along the pole would swing round it and unwind the turns)."""

    nodes: tuple
    xy: tuple

    def dofs(self, system) -> np.ndarray:
        return system.node_dofs[self.node_indices(system), :2].ravel()

    def values(self, system, t_new, dt, q_old) -> np.ndarray:
        return np.asarray(self.xy, dtype=float).ravel()


@dataclass
class AxialResult:
    """Recorded output of an axial pull (:func:`axial_pull`).

    Attributes
    ----------
    knot : str
    wraps : int  turns on the pole (the clove hitch: 2; the Prusik: turns a side)
    normal_load : float [N]  dead load on each leg along its tail (the Prusik: pre-tension)
    drag_speed : float [m/s]; drag_distance : float [m]  the grip's speed and travel
    times : (n,) [s]  frames of the drag phase
    grip_displacement : (n,) [m]  travel of the grip along the pull
    axial_force : (n,) [N]  the grip's force along the pull (sum over both legs)
    knot_displacement : (n,) [m]  mean travel of the nodes that started on the pole
    sliding_force : float [N]  axial force when the knot had travelled ``slide_distance``
        (linearly interpolated between frames; nan when it never did: it held)
    peak_force : float [N]  largest axial force over the drag
    plateau_force : float [N]  mean axial force over the last third of the travel
    slid : bool  the knot travelled more than ``slide_distance`` [m]
    min_rod_distance, min_post_gap : float [m]  over every accepted step
    winding_start, winding_end : float  turns about the pole
    invariants_start, invariants_end : tuple or None; invariants_kept : bool or None
    positions : (m, n_nodes, 3) [m]  every frame of the run
    status, message : str; stats : dict; warnings : list of str
    """

    knot: str
    wraps: int
    normal_load: float
    drag_speed: float
    drag_distance: float
    times: np.ndarray
    grip_displacement: np.ndarray
    axial_force: np.ndarray
    knot_displacement: np.ndarray
    sliding_force: float
    peak_force: float
    plateau_force: float
    slid: bool
    slide_distance: float
    min_rod_distance: float
    min_post_gap: float
    winding_start: float
    winding_end: float
    invariants_start: tuple | None
    invariants_end: tuple | None
    invariants_kept: bool | None
    positions: np.ndarray
    status: str
    message: str
    rod_diameter: float
    stats: dict = field(default_factory=dict)
    warnings: list = field(default_factory=list)

    @property
    def topology_preserved(self) -> bool:
        """No strand through another or the pole: distances above d/2, pole gap above
        -d/4, winding changed by less than a quarter turn, invariants kept."""
        d = self.rod_diameter
        return bool(
            self.min_rod_distance > 0.5 * d
            and self.min_post_gap > -0.25 * d
            and abs(self.winding_end - self.winding_start) < 0.25
            and self.invariants_kept is not False
        )

    def to_dict(self) -> dict:
        """Plain-JSON dictionary of the scalars and the drag's curves (no positions)."""
        return {
            "scene": "axial_pull",
            "knot": self.knot,
            "wraps": self.wraps,
            "normal_load": self.normal_load,
            "drag_speed": self.drag_speed,
            "drag_distance": self.drag_distance,
            "sliding_force": _num(self.sliding_force),
            "peak_force": _num(self.peak_force),
            "plateau_force": _num(self.plateau_force),
            "slid": self.slid,
            "slide_distance": self.slide_distance,
            "topology_preserved": self.topology_preserved,
            "invariants_start": _inv(self.invariants_start),
            "invariants_kept": self.invariants_kept,
            "winding": [self.winding_start, self.winding_end],
            "min_rod_distance": self.min_rod_distance,
            "min_post_gap": self.min_post_gap,
            "status": self.status,
            "message": self.message,
            "warnings": list(self.warnings),
            "stats": {k: float(v) for k, v in self.stats.items()},
            "grip_displacement": self.grip_displacement.tolist(),
            "axial_force": self.axial_force.tolist(),
            "knot_displacement": self.knot_displacement.tolist(),
        }


def _num(v):
    v = float(v)
    return v if np.isfinite(v) else None


def _inv(v):
    if v is None:
        return None
    return {"alexander": " ".join(str(int(c)) for c in v[0]), "linking": int(v[1])}


def axial_curve(knot: str, *, rod_diameter: float, post_diameter: float, wraps: int | None,
                n_nodes: int | None, leg_length: float | None = None):  # fmt: skip
    """Start centreline of ``knot`` in :data:`AXIAL_KNOTS` round the pole (z axis).

    ``leg_length`` [m]: the clove hitch's tails and the rolling hitch's standing part and
    working end (default 8 d); the Prusik's legs are its curve's (10 d down the pole).

    Returns
    -------
    nodes : (n, 3) array [m]
        Node 0 and the last node are the loaded legs' ends (the rolling hitch: node 0 the
        standing part's end, the last node the working end's).
    sense : float
        +1: the knot is dragged along +z (the clove hitch), -1: along -z (the Prusik's loop,
        the rolling hitch's standing part).
    wraps : int
        The clove hitch's turns (2), the Prusik's turns a side, the rolling hitch's riding
        turns (2).
    """
    return _axial_start(knot, rod_diameter=rod_diameter, post_diameter=post_diameter,
                        wraps=wraps, n_nodes=n_nodes, leg_length=leg_length)[:3]  # fmt: skip


def _axial_start(knot, *, rod_diameter, post_diameter, wraps, n_nodes, leg_length):
    """:func:`axial_curve` and the first node of the knot (the rolling hitch's standing
    part, which lies along the pole, is not the knot: 0 for the others)."""
    if knot == "rolling-hitch":
        from knotmech.scenes.hitch_curves import EDGE
        from knotmech.scenes.hitch_curves.rolling_hitch import knotted_length, rolling_hitch_curve

        if wraps not in (None, 2):
            raise InputError(f"wraps must be 2 for the rolling hitch (two riding turns), got "
                             f"{wraps!r}")  # fmt: skip
        leg = 8.0 * rod_diameter if leg_length is None else leg_length
        length = knotted_length(post_diameter, rod_diameter) + 2 * leg
        n = int(round(length / EDGE)) + 1 if n_nodes is None else n_nodes
        c = rolling_hitch_curve(post_diameter=post_diameter, rod_diameter=rod_diameter,
                                rod_length=length, n_nodes=n)  # fmt: skip
        return c.nodes, -1.0, 2, c.parts["standing"][1]
    if knot == "clove-hitch":
        from knotmech.scenes.clove_hitch import CLOVE

        if wraps not in (None, 2):
            raise InputError(f"wraps must be 2 for the clove hitch (two turns), got {wraps!r}")
        leg = 8.0 * rod_diameter if leg_length is None else leg_length
        length = 4 * np.pi * 0.5 * (post_diameter + rod_diameter) * 1.15 + 2 * leg
        return CLOVE.curve(post_diameter, rod_diameter, length, n_nodes).nodes, 1.0, 2, 0
    if knot == "prusik":
        from knotmech.scenes.tied.prusik import prusik

        w = 3 if wraps is None else wraps
        t = prusik(rod_diameter=rod_diameter, pin_diameter=post_diameter, wraps=w,
                   n_nodes=200 if n_nodes is None else n_nodes)  # fmt: skip
        return _open_sling(t.ropes["sling"], rod_diameter), -1.0, int(w), 0
    raise InputError(f"knot must be one of {', '.join(AXIAL_KNOTS)}, got {knot!r}")


def _open_sling(nodes, d) -> np.ndarray:
    """The closed sling cut open at its loaded loop: the nodes less than 1.5 d above the
    lowest point (the half turn) removed, the rest rolled so that the legs are the ends."""
    x = np.asarray(nodes, dtype=float)
    low = x[:, 2] < x[:, 2].min() + 1.5 * d
    cut = np.flatnonzero(low)
    # the removed run is contiguous on the closed sling: start just after it
    start = int(cut[-1]) + 1 if cut[-1] - cut[0] == cut.size - 1 else int(cut[0])
    y = np.roll(x, -start, axis=0)
    return y[~(y[:, 2] < x[:, 2].min() + 1.5 * d)]


def axial_pull(
    knot: str = "clove-hitch",
    *,
    normal_load: float = 0.5,
    wraps: int | None = None,
    rod_diameter: float = 4e-3,
    post_diameter: float = 30e-3,
    youngs_modulus: float = VPS32_YOUNGS_MODULUS,
    density: float = PHASE_TABLE_DENSITY,
    bending_scale: float = 1.0,
    mu_rod_post: float = 0.3,
    mu_rod_rod: float = 0.3,
    drag_speed: float = 0.01,
    drag_distance: float | None = None,
    leg_length: float | None = None,
    legs: str = "clamped",
    force_scale: float | None = None,
    settle_time: float = 0.4,
    load_time: float = 0.3,
    slide_distance: float | None = None,
    plateau_window: float | None = None,
    n_nodes: int | None = None,
    dt: float = 2e-3,
    n_frames: int = 80,
    options: rod.SolverOptions | None = None,
    progress: bool = False,
    max_node_steps: float | None = None,
) -> AxialResult:
    r"""Tie ``knot`` on a fixed pole, load its legs and drag it along the pole's axis.

    Parameters
    ----------
    knot : {"clove-hitch", "prusik"}
    normal_load : float [N]
        T: dead load on each leg along its tail, held while the knot is dragged (the
        Prusik: along the legs, i.e. down the pole).
    wraps : int, optional
        The Prusik's turns a side (2 to 6, default 3); the clove hitch: 2 (or None).
    rod_diameter, post_diameter : float [m]
    youngs_modulus : float [Pa]; density : float [kg/m^3]
    bending_scale : float
        kappa in (0, 1] (1: a solid rod).
    mu_rod_post, mu_rod_rod : float
        Rod-pole and rod-rod friction coefficients (static = kinetic).
    drag_speed : float [m/s]
        Speed of the grip along the pole (default 10 mm/s).
    drag_distance : float [m], optional
        Travel of the grip (default 8 rod diameters).
    leg_length : float [m], optional
        The clove hitch's legs from the pole to the grips (default 8 rod diameters).
    legs : {"clamped", "dead"}
        During the drag, the legs' ends are ``"clamped"`` where the loads left them and
        moved along the pole (the legs' tension rises as they tilt and stretch), or keep
        their ``"dead"`` loads T along the tails while only their axial position is driven
        (the normal load stays T; the clove hitch only).
    force_scale : float [N], optional
        Largest force expected, which sizes the contact penalties (default 10 T).
    settle_time, load_time : float [s]
        Settling under 0.2 T, then the ramp to T.
    slide_distance : float [m], optional
        Travel of the knot that counts as sliding (default one rod diameter).
    plateau_window : float [m], optional
        The drag ends (successfully) once the grips have moved this much further after the
        knot slid (its sliding force read, the plateau recorded over the window); default
        :data:`PLATEAU_WINDOW_D`: half a rod diameter for the Prusik; ``inf`` (the other knots'
        default): the whole ``drag_distance``.
    n_nodes : int, optional
        Nodes (default: the clove hitch's edges of about 3.1 mm; the Prusik's 200-node sling).
    dt : float [s]
        Nominal step.
    n_frames : int
        Frames of the drag phase.
    options : knotmech.rod.SolverOptions, optional
    progress : bool
    max_node_steps : float, optional
        Bound on (t_end/dt) x nodes (``inf`` lifts it).

    Returns
    -------
    AxialResult
    """
    return AxialScene(
        knot,
        dict(normal_load=normal_load, wraps=wraps, rod_diameter=rod_diameter,
             post_diameter=post_diameter, youngs_modulus=youngs_modulus, density=density,
             bending_scale=bending_scale, mu_rod_post=mu_rod_post, mu_rod_rod=mu_rod_rod,
             drag_speed=drag_speed, drag_distance=drag_distance, leg_length=leg_length, legs=legs,
             force_scale=force_scale,
             settle_time=settle_time, load_time=load_time, slide_distance=slide_distance,
             plateau_window=plateau_window,
             n_nodes=n_nodes),
        RunControl(dt=dt, n_frames=n_frames, options=options, progress=progress,
                   max_node_steps=max_node_steps),
    ).run()  # fmt: skip


class AxialScene(Scene):
    """The phases of :func:`axial_pull`: settle and load, then drag."""

    def __init__(self, knot: str, params: dict, control: RunControl):
        self.knot, self.p, self.control = str(knot), params, control

    # -- setup -----------------------------------------------------------------------
    def setup(self) -> None:
        """Check the inputs, tie the start curve and bound the cost."""
        p = self.p
        if self.knot not in AXIAL_KNOTS:
            raise InputError(f"knot must be one of {', '.join(AXIAL_KNOTS)}, got {self.knot!r}")
        self.d = float(check_positive("rod_diameter", p["rod_diameter"], scalar=True))
        self.D = float(check_positive("post_diameter", p["post_diameter"], scalar=True))
        check_post_size(self.D, self.d, "hitch")
        self.E = float(check_positive("youngs_modulus", p["youngs_modulus"], scalar=True))
        self.rho = float(check_positive("density", p["density"], scalar=True))
        self.kappa = check_bending_scale(p["bending_scale"])
        self.mrc = float(check_nonnegative("mu_rod_post", p["mu_rod_post"], scalar=True))
        self.mrr = float(check_nonnegative("mu_rod_rod", p["mu_rod_rod"], scalar=True))
        self.T = float(check_positive("normal_load", p["normal_load"], scalar=True))
        self.v = float(check_positive("drag_speed", p["drag_speed"], scalar=True))
        if p["legs"] not in ("clamped", "dead"):
            raise InputError(f"legs must be 'clamped' or 'dead', got {p['legs']!r}")
        if p["legs"] == "dead" and self.knot != "clove-hitch":
            raise InputError("legs='dead' applies to the clove hitch (the Prusik's legs and "
                             "the rolling hitch's standing part run along the pole)")  # fmt: skip
        self.dist = self._length("drag_distance", 8.0)
        self.slide = self._length("slide_distance", 1.0)
        v = self.p["plateau_window"]
        if v is None:
            self.window = PLATEAU_WINDOW_D.get(self.knot, np.inf) * self.d
        else:
            self.window = np.inf if v == np.inf else self._length("plateau_window", 0.0)
        fs = 10.0 * self.T if p["force_scale"] is None else p["force_scale"]
        self.fscale = float(check_positive("force_scale", fs, scalar=True))
        self.t1 = float(check_positive("settle_time", p["settle_time"], scalar=True))
        self.t2 = self.t1 + float(check_positive("load_time", p["load_time"], scalar=True))
        self.step = float(check_positive("dt", self.control.dt, scalar=True))
        if int(self.control.n_frames) < 2:
            raise InputError(f"n_frames must be >= 2, got {self.control.n_frames!r}")
        self.x0, self.sense, self.wraps, first = _axial_start(
            self.knot, rod_diameter=self.d, post_diameter=self.D, wraps=p["wraps"],
            n_nodes=p["n_nodes"], leg_length=self._length("leg_length", 8.0),
        )  # fmt: skip
        self.N = len(self.x0)
        check_run_size(n_nodes=self.N, t_end=self.t2 + self.dist / self.v, dt=self.step,
                       max_node_steps=self.control.max_node_steps,
                       hint="use a larger dt, fewer nodes or a shorter drag_distance")  # fmt: skip
        self.ea = self.E * np.pi * self.d**2 / 4
        r = np.hypot(self.x0[:, 0], self.x0[:, 1])
        self.on_pole = np.flatnonzero(r < 0.5 * (self.D + self.d) + 0.5 * self.d)
        self.on_pole = self.on_pole[self.on_pole >= first]
        # the gripped ends: both legs, or the rolling hitch's standing part alone (its
        # working end keeps its set load, as a tail dressed by hand)
        self.grips = [0] if self.knot == "rolling-hitch" else [0, self.N - 1]

    def _length(self, name: str, in_d: float) -> float:
        """A length option [m], default ``in_d`` rod diameters."""
        v = self.p[name]
        return float(check_positive(name, in_d * self.d if v is None else v, scalar=True))

    # -- build -----------------------------------------------------------------------
    def build(self) -> SceneRun:
        """The rod, the pole, the rod-rod contact (anchor law, cap floor 1e-2, path guard)."""
        d, x0 = self.d, self.x0
        r = rod.Rod(positions=x0, radius=0.5 * d, youngs_modulus=self.E, density=self.rho,
                    natural="straight", bending_scale=self.kappa)  # fmt: skip
        self.system = rod.RodSystem([r])
        pole = post_contact(post_diameter=self.D, rod_diameter=d, force_scale=self.fscale,
                            mu_static=self.mrc)  # fmt: skip
        fr = AnchorFriction(mu_static=self.mrr, cap_floor=CAP_FLOOR) if self.mrr > 0 else None
        rr = RodContact(stiffness=20.0 * self.fscale / d, sharpness=15.0 / (0.05 * d),
                        friction=fr, tunnel_check="path")  # fmt: skip
        self.closest = {"rod": np.inf, "post": np.inf}
        idx = np.arange(self.N - 1)
        self.far = np.abs(idx[:, None] - idx[None, :]) >= 3
        c = self.control
        base = c.options if c.options is not None else rod.SolverOptions(throw=False, rtol=1e-6)
        return SceneRun(self.system, interactions=[pole, rr], options=base, watch=self._watch,
                        progress=c.progress)  # fmt: skip

    def _watch(self, x) -> None:
        c = self.closest
        c["rod"] = min(c["rod"], float(_edge_distances(x)[self.far].min()))
        R = 0.5 * (self.D + self.d)
        c["post"] = min(c["post"], float(np.min(np.hypot(x[:, 0], x[:, 1])) - R))

    def _knot_z(self, x) -> float:
        """Axial position of the knot along the pull [m]: mean z of the start's pole nodes."""
        return float(self.sense * np.mean(x[self.on_pole, 2]))

    # -- phases ----------------------------------------------------------------------
    def run_phases(self, run: SceneRun) -> None:
        """Settle under 0.2 T and ramp to T (dead loads along the tails), then drag."""
        x, N, T, t1 = self.x0, self.N, self.T, self.t1
        u0 = (x[0] - x[1]) / np.linalg.norm(x[0] - x[1])
        u1 = (x[-1] - x[-2]) / np.linalg.norm(x[-1] - x[-2])
        self.legs = [
            RampedEndLoad(0, 0.2 * T * u0, 0.3 * t1),
            RampedEndLoad(N - 1, 0.2 * T * u1, 0.3 * t1),
            RampedEndLoad(0, 0.8 * T * u0, self.t2 - t1, delay=t1),
            RampedEndLoad(N - 1, 0.8 * T * u1, self.t2 - t1, delay=t1),
        ]
        self.drag = 2.0 * self.rho * np.pi * self.d**2 / 4 / (0.1 * t1)
        loads = [*self.legs, rod.ViscousDamping(coefficient=self.drag)]
        self.k0 = None
        guide = []
        if self.knot == "rolling-hitch":  # the standing part's end kept on the pole's line
            guide = [LineGuide(nodes=(0,), xy=(tuple(x[0, :2]),))]
        if run.phase("settle-load", self.t2, dt=self.step, loads=loads, constraints=guide,
                     save_every=self.t2 / 8):  # fmt: skip
            self._drag(run)

    def _drag(self, run: SceneRun) -> None:
        """The legs' ends' z moved at the drag speed; the grip's reaction is recorded."""
        xs = run.positions[-1]
        self.k0 = len(run.times) - 1
        self.z0 = self._knot_z(xs)
        self.slid_at = None  # the grips' position along the pull when the knot slid
        # a light drag (1 % of the settling's): quasi-static at the drag speed
        loads = [rod.ViscousDamping(coefficient=0.01 * self.drag)]
        if self.p["legs"] == "dead":  # T kept along the tails, the ends' z driven
            grip = AxialGrip(nodes=(0, self.N - 1), z_start=(xs[0, 2], xs[-1, 2]),
                             speed=self.v, sense=self.sense, t_start=self.t2)  # fmt: skip
            loads = [*self.legs, *loads]
        else:  # the ends gripped where the loads left them and moved along the pole
            ends = xs[self.grips]
            path = grip_path(ends, (0.0, 0.0, self.sense), self.v, t_start=self.t2)
            grip = MovingNodes(nodes=list(self.grips), path=path)
            if len(self.grips) == 1:  # the rolling hitch: the working end's load kept
                loads = [self.legs[1], self.legs[3], *loads]
        t_drag = self.dist / self.v
        every = t_drag / (int(self.control.n_frames) - 1)
        h = float(np.mean(np.linalg.norm(np.diff(self.x0, axis=0), axis=1)))
        step = min(self.step, 0.25 * min(h, 0.2 * self.d) / self.v)
        run.phase("drag", t_drag, dt=step, loads=loads, constraints=[grip], save_every=every,
                  stop=self._stop if np.isfinite(self.window) else None)  # fmt: skip

    def _stop(self, x) -> bool:
        """The grips have moved ``plateau_window`` since the knot slid: the drag has read
        what it is for."""
        grip = self.sense * float(x[self.grips[0], 2])
        if self.slid_at is None and self._knot_z(x) - self.z0 > self.slide:
            self.slid_at = grip
        return self.slid_at is not None and grip - self.slid_at >= self.window

    # -- measure ---------------------------------------------------------------------
    def measure(self, run: SceneRun) -> AxialResult:
        """Axial force and knot travel of the drag, the sliding force, topology."""
        times, pos = run.frames()
        k0 = len(times) - 1 if self.k0 is None else self.k0
        tt = times[k0:]
        force = np.zeros(tt.size)
        if self.k0 is not None and tt.size > 1:
            ph = run.phases[-1]
            rx = np.vstack([sum(ph.start_reactions[k] for k in self.grips),
                            run.reaction(self.grips, tt[1:])])  # fmt: skip
            force = self.sense * rx[:, 2]
        z0 = getattr(self, "z0", self._knot_z(pos[k0]))
        disp = np.array([self._knot_z(x) - z0 for x in pos[k0:]])
        grip = self.v * (tt - tt[0])
        third = grip >= grip[-1] * 2.0 / 3.0
        inv0, inv1, kept = _invariants(self.x0, pos, np.concatenate([np.zeros(k0), disp]), self.d)
        reason, warns = measured_strain(run.tension, self.ea, warned=False)
        status, message = fail(run.status, run.message, reason)
        return AxialResult(
            knot=self.knot, wraps=self.wraps, normal_load=self.T, drag_speed=self.v,
            drag_distance=self.dist, times=tt, grip_displacement=grip, axial_force=force,
            knot_displacement=disp, sliding_force=_crossing(force, disp, self.slide),
            peak_force=float(np.max(force)),
            plateau_force=float(np.mean(force[third])), slid=bool(disp[-1] > self.slide),
            slide_distance=self.slide, min_rod_distance=self.closest["rod"],
            min_post_gap=self.closest["post"], winding_start=winding_number(self.x0),
            winding_end=winding_number(pos[-1]), invariants_start=inv0, invariants_end=inv1,
            invariants_kept=kept, positions=pos, status=status, message=message,
            rod_diameter=self.d, stats=run.stats, warnings=warns,
        )  # fmt: skip


def _crossing(force, disp, level) -> float:
    """The force [N] where ``disp`` [m] first exceeds ``level`` [m] (linear between
    frames); nan when it never does."""
    above = np.flatnonzero(np.asarray(disp) > level)
    if above.size == 0:
        return float("nan")
    k = int(above[0])
    if k == 0:
        return float(force[0])
    w = (level - disp[k - 1]) / (disp[k] - disp[k - 1])
    return float(force[k - 1] + w * (force[k] - force[k - 1]))


def _invariants(x0, pos, disp, d):
    """Knot invariants of the start and of frames while the knot moved less than 10 d
    (:func:`knotmech.scenes._hitch._check_invariants`); (None, None, None) when the start's
    closure cannot be read."""
    try:
        return _check_invariants(hitch_invariants, x0, pos, disp, d)
    except InputError:
        return None, None, None

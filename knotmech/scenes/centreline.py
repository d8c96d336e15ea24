r"""A user's own knot from a CSV of centreline points: relax it, pull it, say if it holds.

The file gives one or two rods as points (``x, y, z`` per line, or ``rod, x, y, z`` with rod
0 or 1; a header line is allowed; lengths in ``unit``). Each rod end is ``"pull"`` (gripped
and pulled outwards along the rod's end tangent at ``pull_speed``), ``"fixed"`` (clamped,
or tied to a post) or ``"free"``. An optional rigid post of diameter ``post_diameter``
stands on the z axis through the origin. The rods are resampled to equal edges, settle for
``settle_time`` with the pulled and fixed ends held, and are then pulled for
``pull_distance``; the knot *slips* when a free end is drawn in by more than
``slip_draw_in`` after the force peak, else it *holds* up to the largest force.

The topology is checked as in the parametrised scenes: every rod's knot type (Alexander
polynomial of the rod closed far away along its end-to-end axis) and, for two rods, their
linking number must be the same at the start and at the last frame checked.

Bad input (unreadable file, a non-number, NaN, fewer than 10 points per rod, a rod whose
strands come closer than half a diameter, i.e. a centreline that intersects itself, or a
post that cuts the rod) raises :class:`knotmech.errors.InputError` with one line naming the
problem.
"""

from __future__ import annotations

import csv
import io
import time
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from knotmech import rod
from knotmech.errors import InputError, check_nonnegative, check_positive
from knotmech.rod.constraints import Clamp, MovingNodes
from knotmech.scenes._common import check_memory, check_run_size, frames_bytes, pair_check_bytes
from knotmech.scenes._scene import (
    RunControl,
    Scene,
    SceneRun,
    grip_path,
    post_contact,
    rod_contact,
)
from knotmech.scenes.curves import _edge_distances, resample_polyline
from knotmech.scenes.topology import close_curve, knot_invariant

__all__ = [
    "CentrelineResult",
    "CentrelineScene",
    "CentrelineRod",
    "CentrelinePull",
    "read_centreline",
    "centreline",
]

_UNITS = {"m": 1.0, "cm": 1e-2, "mm": 1e-3}
_END_KINDS = ("pull", "fixed", "free")


#: largest |coordinate| of a centreline point [m]: a knot larger than a kilometre is not a
#: rod this scene can simulate (and squared lengths of 1e300 overflow)
MAX_COORDINATE = 1e3


def read_centreline(source, *, unit: str = "m") -> list[np.ndarray]:
    """Read one or two rods' centreline points from a CSV file (or its text).

    Parameters
    ----------
    source : str or path-like
        A file path, or the CSV text itself (if it contains a newline).
    unit : {"m", "cm", "mm"}
        Unit of the coordinates in the file.

    Returns
    -------
    list of (n_i, 3) arrays [m]
        One array per rod, in rod order.

    Raises
    ------
    InputError
        One line naming the file and the line at fault (also for a field too long for
        CSV, a coordinate beyond :data:`MAX_COORDINATE` metres, a file that is not text).
    """
    _check_unit(unit)
    name, text = _source_text(source)
    rows = _csv_rows(text, name)
    width = len(rows[0])
    if width not in (3, 4):
        raise InputError(f"{name}: expected 3 columns (x, y, z) or 4 (rod, x, y, z), got {width}")
    pts: dict[int, list] = {}
    for k, r in enumerate(rows, start=1):
        rid, xyz = _parse_row(r, k, width, name)
        pts.setdefault(rid, []).append(xyz)
    if set(pts) == {1}:
        raise InputError(f"{name}: rod 1 given without rod 0")
    return [
        _rod_points(np.array(pts[rid]) * _UNITS[unit], f"{name}: rod {rid}") for rid in sorted(pts)
    ]


def _check_unit(unit) -> None:
    if unit not in _UNITS:
        raise InputError(f"unit must be one of {', '.join(_UNITS)}, got {unit!r}")


def _source_text(source) -> tuple[str, str]:
    """(name for messages, CSV text) of a path or of the text itself."""
    if isinstance(source, str) and "\n" in source:
        return "centreline", source
    name = str(source)
    try:
        return name, Path(source).read_text()
    except (OSError, UnicodeDecodeError, ValueError) as exc:
        raise InputError(f"{name}: cannot read the centreline file ({exc})") from None


def _csv_rows(text: str, name: str) -> list[list[str]]:
    """The non-empty CSV rows, the header dropped; InputError if there are none or a field
    is too long for the CSV reader."""
    try:
        rows = [r for r in csv.reader(io.StringIO(text)) if r and any(c.strip() for c in r)]
    except csv.Error as exc:
        raise InputError(f"{name}: not a CSV of points ({exc})") from None
    if rows and not _numeric(rows[0][0]):
        rows = rows[1:]  # header
    if not rows:
        raise InputError(f"{name}: no points (expected lines 'x, y, z' or 'rod, x, y, z')")
    return rows


def _parse_row(r, k: int, width: int, name: str) -> tuple[int, list[float]]:
    """(rod id, [x, y, z]) of row ``k`` (1-based), checked."""
    if len(r) != width:
        raise InputError(f"{name}: point {k} has {len(r)} columns, expected {width}")
    try:
        vals = [float(c) for c in r]
    except ValueError:
        shown = ", ".join(r)
        shown = shown if len(shown) <= 60 else shown[:57] + "..."
        raise InputError(f"{name}: point {k} is not numbers: {shown}") from None
    if not np.all(np.isfinite(vals)):
        raise InputError(f"{name}: point {k} is not finite (NaN or infinity)")
    rid = 0 if width == 3 else vals[0]
    if rid not in (0, 1):
        raise InputError(f"{name}: point {k}: rod must be 0 or 1, got {r[0].strip()[:20]}")
    return int(rid), vals[-3:]


def _rod_points(x: np.ndarray, what: str) -> np.ndarray:
    """One rod's (n, 3) points [m], checked: finite, within :data:`MAX_COORDINATE`, at
    least 10, no point repeated."""
    with np.errstate(over="ignore", invalid="ignore"):
        big = float(np.max(np.abs(x))) if x.size else 0.0
    if not np.isfinite(big) or big > MAX_COORDINATE:
        raise InputError(
            f"{what}: a coordinate is {big:.3g} m from the origin, beyond the "
            f"{MAX_COORDINATE:g} m a centreline may span (check the unit)"
        )
    if len(x) < 10:
        raise InputError(f"{what} has {len(x)} points, at least 10 are needed")
    if np.any(np.linalg.norm(np.diff(x, axis=0), axis=1) == 0):
        raise InputError(f"{what} repeats a point")
    return x


def _numeric(s: str) -> bool:
    try:
        float(s)
    except ValueError:
        return False
    return True


@dataclass
class CentrelineResult:
    """What a user-centreline pull measured (SI units).

    Attributes
    ----------
    verdict : {"slips", "holds", ""}
    slip_load : float [N]  largest pull force before the slip (NaN if it held)
    max_force : float [N]
    times, pull_displacement, pull_force : (n_frames,) arrays [s], [m], [N]
    draw_in : (n_frames, k) [m]  draw-in of each free end (k may be 0)
    knots_start, knots_checked : tuple of str  knot names of each rod (closed far away)
    linking_start, linking_checked : int or None  linking number of the two rods
    positions : (n_frames, n_nodes, 3) [m]
    status, message : str; stats : dict
    """

    verdict: str
    slip_load: float
    max_force: float
    times: np.ndarray
    pull_displacement: np.ndarray
    pull_force: np.ndarray
    draw_in: np.ndarray
    knots_start: tuple
    knots_checked: tuple
    linking_start: int | None
    linking_checked: int | None
    positions: np.ndarray
    status: str
    message: str
    stats: dict = field(default_factory=dict)

    @property
    def topology_preserved(self) -> bool:
        return (self.knots_start, self.linking_start) == (self.knots_checked, self.linking_checked)


def _gauss_linking(ca, cb) -> float:
    def seg(c):
        c1 = np.roll(c, -1, axis=0)
        return 0.5 * (c + c1), c1 - c

    am, da = seg(ca)
    bm, db = seg(cb)
    r = am[:, None, :] - bm[None, :, :]
    num = np.einsum("ijk,ijk->ij", np.cross(da[:, None, :], db[None, :, :]), r)
    return float((num / np.linalg.norm(r, axis=2) ** 3).sum() / (4 * np.pi))


def _topology(rods_x):
    """(knot names per rod, linking number of two rods or None)."""
    names = []
    for x in rods_x:
        inv = knot_invariant(x)
        names.append(str(inv.alexander))
    lk = None
    if len(rods_x) == 2:
        lk = int(round(_gauss_linking(close_curve(rods_x[0]), close_curve(rods_x[1]))))
    return tuple(names), lk


def _min_gap(x, exclude):
    ed = _edge_distances(x)
    i = np.arange(len(x) - 1)
    ed[np.abs(i[:, None] - i[None, :]) < exclude] = np.inf
    return float(ed.min())


@dataclass(frozen=True)
class CentrelineRod:
    """The rods' material, contacts and resolution (SI units; :func:`centreline` documents
    them)."""

    rod_diameter: float
    youngs_modulus: float
    density: float
    mu_rod_rod: float
    post_diameter: float | None = None
    mu_rod_post: float | None = None
    n_nodes: int = 100
    force_scale: float | None = None


@dataclass(frozen=True)
class CentrelinePull:
    """The settling and the pull [s], [m/s], [m] (:func:`centreline` documents them)."""

    pull_speed: float = 0.02
    pull_distance: float | None = None
    settle_time: float = 0.2
    slip_draw_in: float | None = None


def centreline(
    points,
    *,
    ends,
    rod_diameter: float,
    youngs_modulus: float,
    density: float,
    mu_rod_rod: float,
    unit: str = "m",
    post_diameter: float | None = None,
    mu_rod_post: float | None = None,
    pull_speed: float = 0.02,
    pull_distance: float | None = None,
    settle_time: float = 0.2,
    n_nodes: int = 100,
    dt: float = 2e-3,
    slip_draw_in: float | None = None,
    force_scale: float | None = None,
    n_frames: int = 100,
    options: rod.SolverOptions | None = None,
    progress: bool = False,
) -> CentrelineResult:
    r"""Relax and pull a knot given as centreline points.

    Parameters
    ----------
    points : path, CSV text, (n, 3) array or list of one or two (n_i, 3) arrays
        The centreline(s); files and text are read with :func:`read_centreline`.
    ends : sequence of (str, str)
        For each rod, what its (first, last) point is: ``"pull"``, ``"fixed"`` or
        ``"free"``. At least one end is pulled.
    rod_diameter : float [m]
    youngs_modulus : float [Pa]; density : float [kg/m^3]
    mu_rod_rod : float
        Rod-rod friction (sticking anchor law, static = kinetic).
    unit : {"m", "cm", "mm"}
        Unit of the points (files, text and arrays alike).
    post_diameter : float [m], optional
        A rigid post on the z axis through the origin.
    mu_rod_post : float, optional
        Rod-post friction (default ``mu_rod_rod``).
    pull_speed : float [m/s]
        Speed of each pulled end, outwards along its end tangent.
    pull_distance : float [m], optional
        Travel of each pulled end (default 12 d).
    settle_time : float [s]
    n_nodes : int
        Nodes per rod after resampling (>= 10). Edges of one rod closer along it than
        about 1.25 d never touch (the contact skips them), so that a finely resampled
        smooth curve does not push against itself.
    dt : float [s]
    slip_draw_in : float [m], optional
        Free-end draw-in after the force peak that counts as a slip (default 4 d).
    force_scale : float [N], optional
        Sizes the contact penalties (default :math:`20 B/d^2`, B = E pi d^4/64).
    n_frames : int
    options : knotmech.rod.SolverOptions, optional
    progress : bool

    Returns
    -------
    CentrelineResult
        ``status`` "failed" with the phase and the reason when the settling or the pull
        stopped (the verdict is then ""), or when the topology changed.

    Raises
    ------
    InputError
        Bad points (see the module docstring), an ``ends`` entry per rod missing or not one
        of pull/fixed/free, no pulled end, a physical argument out of range, or a run whose
        steps x nodes or memory is above the bound
        (:func:`knotmech.scenes._common.check_run_size`, :func:`~knotmech.scenes._common.
        check_memory`).
    """
    return CentrelineScene(
        points,
        ends=ends,
        unit=unit,
        rod=CentrelineRod(
            rod_diameter=rod_diameter,
            youngs_modulus=youngs_modulus,
            density=density,
            mu_rod_rod=mu_rod_rod,
            post_diameter=post_diameter,
            mu_rod_post=mu_rod_post,
            n_nodes=n_nodes,
            force_scale=force_scale,
        ),
        pull=CentrelinePull(
            pull_speed=pull_speed,
            pull_distance=pull_distance,
            settle_time=settle_time,
            slip_draw_in=slip_draw_in,
        ),
        control=RunControl(dt=dt, n_frames=n_frames, options=options, progress=progress),
    ).run()


def _array_points(points, unit: str) -> list[np.ndarray]:
    """One or two rods' (n, 3) points [m] from arrays, checked."""
    arrs = [points] if np.ndim(points) == 2 else list(points)
    if not 1 <= len(arrs) <= 2:
        raise InputError(f"points must give one or two rods, got {len(arrs)}")
    raw = []
    for k, a in enumerate(arrs):
        try:
            x = np.asarray(a, dtype=float) * _UNITS[unit]
        except (TypeError, ValueError):
            raise InputError(f"points of rod {k} must be numbers") from None
        if x.ndim != 2 or x.shape[1] != 3:
            raise InputError(f"points of rod {k} must be an (n, 3) array, got {x.shape}")
        if not np.all(np.isfinite(x)):
            raise InputError(f"points of rod {k} are not finite (NaN or infinity)")
        big = float(np.max(np.abs(x))) if x.size else 0.0
        if big > MAX_COORDINATE:
            raise InputError(
                f"rod {k}: a coordinate is {big:.3g} m from the origin, beyond the "
                f"{MAX_COORDINATE:g} m a centreline may span (check the unit)"
            )
        if len(x) < 10:
            raise InputError(f"rod {k} has {len(x)} points, at least 10 are needed")
        raw.append(x)
    return raw


def _check_ends(ends, n_rods: int) -> list[tuple]:
    ends = [tuple(e) for e in ends]
    if len(ends) != n_rods or any(len(e) != 2 for e in ends):
        raise InputError(f"ends must give (first, last) for each of the {n_rods} rod(s)")
    for e in ends:
        for k in e:
            if k not in _END_KINDS:
                raise InputError(f"ends must be 'pull', 'fixed' or 'free', got {k!r}")
    if not any("pull" in e for e in ends):
        raise InputError("ends: at least one end must be 'pull'")
    return ends


class CentrelineScene(Scene):
    """A user's centreline relaxed and pulled: the phases of :func:`centreline`."""

    def __init__(self, points, *, ends, unit, rod, pull, control):
        self.points, self.ends_arg, self.unit = points, ends, unit
        self.rod_opts, self.pull_opts, self.control = rod, pull, control

    # -- setup -----------------------------------------------------------------------
    def setup(self) -> None:
        """Points, numbers, ends and cost checked; the rods resampled and checked clear."""
        _check_unit(self.unit)
        if isinstance(self.points, (str, Path)):
            raw = read_centreline(self.points, unit=self.unit)
        else:
            raw = _array_points(self.points, self.unit)
        self._check_numbers()
        self.ends = _check_ends(self.ends_arg, len(raw))
        self._check_cost(len(raw))
        self.rods_x = [resample_polyline(x, self.N) for x in raw]
        self._check_clear()

    def _check_numbers(self) -> None:
        o, p = self.rod_opts, self.pull_opts
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
            4 * d
            if p.slip_draw_in is None
            else float(check_positive("slip_draw_in", p.slip_draw_in, scalar=True))
        )
        self.settle_time = float(check_positive("settle_time", p.settle_time, scalar=True))
        self.dt = float(check_positive("dt", self.control.dt, scalar=True))
        n = o.n_nodes
        try:
            self.N = int(n)
        except (TypeError, ValueError, OverflowError):
            raise InputError(f"n_nodes must be an integer >= 10, got {n!r}") from None
        if self.N != n or self.N < 10:
            raise InputError(f"n_nodes must be an integer >= 10, got {n!r}")
        n_frames = self.control.n_frames
        if int(n_frames) != n_frames or n_frames < 2:
            raise InputError(f"n_frames must be an integer >= 2, got {n_frames!r}")

    def _check_cost(self, n_rods: int) -> None:
        """Steps x nodes and the memory of the all-pairs checks, before any allocation."""
        n = n_rods * self.N
        hint = "use fewer nodes (n_nodes), a larger dt or a shorter pull (pull_distance)"
        check_run_size(
            n_nodes=n, t_end=self.settle_time + self.dist / self.v, dt=self.dt, hint=hint
        )
        check_memory(
            pair_check_bytes(n) + frames_bytes(self.control.n_frames + 50, n),
            what=f"the strands' pair-distance checks on {n} nodes",
            hint="use fewer nodes (n_nodes)",
        )

    def _check_clear(self) -> None:
        """No strand within half a diameter of another (a self-intersecting centreline)."""
        d, N = self.d, self.N
        self.edge = [float(np.linalg.norm(x[1] - x[0])) for x in self.rods_x]
        for k, x in enumerate(self.rods_x):
            exclude = max(3, int(np.ceil(2.0 * d / self.edge[k])) + 1)
            gap = _min_gap(x, exclude)
            if gap < 0.5 * d:
                raise InputError(
                    f"rod {k}: strands come {gap / d:.2f} d apart (< 0.5 d): the centreline "
                    "intersects itself (or give a smaller rod_diameter)"
                )
        if len(self.rods_x) == 2:
            both = np.vstack(self.rods_x)
            gap = float(_edge_distances(both)[: N - 1, N:].min())
            if gap < 0.5 * d:
                raise InputError(
                    f"the two rods come {gap / d:.2f} d apart (< 0.5 d): they intersect"
                )

    # -- build -----------------------------------------------------------------------
    def build(self) -> SceneRun:
        """The rods, rod-rod contact (and the post), the grips; a :class:`SceneRun`."""
        d, E, o = self.d, self.E, self.rod_opts
        self.B = E * np.pi * d**4 / 64
        fs = (
            20 * self.B / d**2
            if o.force_scale is None
            else float(check_positive("force_scale", o.force_scale, scalar=True))
        )
        interactions = [rod_contact(rod_diameter=d, force_scale=fs, mu_static=self.mu)]
        if o.post_diameter is not None:
            interactions.append(self._post(fs))
        rods = [
            rod.Rod(
                positions=x, radius=0.5 * d, youngs_modulus=E, density=self.rho, natural="straight"
            )
            for x in self.rods_x
        ]
        self.system = rod.RodSystem(rods, contact_exclusion=_exclusion(d, min(self.edge)))
        self._grips()
        self.x0 = self.system.positions(self.system.initial_state().q)
        c = self.control
        self.t_wall = time.perf_counter()
        return SceneRun(
            self.system, interactions=interactions, options=c.options, progress=c.progress
        )

    def _post(self, fs):
        d, o = self.d, self.rod_opts
        D = float(check_positive("post_diameter", o.post_diameter, scalar=True))
        for k, x in enumerate(self.rods_x):
            rmin = float(np.min(np.hypot(x[:, 0], x[:, 1])))
            if rmin < 0.5 * D + 0.25 * d:
                raise InputError(
                    f"rod {k} cuts the post: it comes {rmin:.4g} m from the axis, inside "
                    f"D/2 + d/4 = {0.5 * D + 0.25 * d:.4g} m"
                )
        mrp = (
            self.mu
            if o.mu_rod_post is None
            else float(check_nonnegative("mu_rod_post", o.mu_rod_post, scalar=True))
        )
        return post_contact(post_diameter=D, rod_diameter=d, force_scale=fs, mu_static=mrp)

    def _grips(self) -> None:
        """Held nodes and edges, pulled (node pair, edge) and free end nodes."""
        system = self.system
        self.held_nodes, self.held_edges, self.pulls, self.free = [], [], [], []
        for r_id, e in enumerate(self.ends):
            nodes, edges = system.rod_nodes(r_id), system.rod_edges(r_id)
            for side, kind in zip(("start", "end"), e, strict=True):
                if side == "start":
                    pair, ed = [int(nodes[0]), int(nodes[1])], int(edges[0])
                else:
                    pair, ed = [int(nodes[-1]), int(nodes[-2])], int(edges[-1])
                if kind == "free":
                    self.free.append(pair[0])
                    continue
                self.held_nodes += pair
                self.held_edges.append(ed)
                if kind == "pull":
                    self.pulls.append((pair, ed))

    # -- phases ----------------------------------------------------------------------
    def run_phases(self, run: SceneRun) -> None:
        """Settle with the pulled and fixed ends held, then pull."""
        mass = self.rho * np.pi * self.d * self.d / 4
        run.phase(
            "settle",
            self.settle_time,
            dt=self.dt,
            loads=[rod.ViscousDamping(coefficient=20.0 * mass / self.pull_opts.settle_time)],
            constraints=[Clamp(nodes=self.held_nodes, edges=self.held_edges)],
        )
        self.t0 = run.t
        cons = self._pull_constraints(self.system.positions(run.state.q))
        # drag of the whole length moving at v: 1 % of B/d^2 (quasi-static pull)
        c = 0.01 * self.B / self.d**2 / (float(self.system.rest_length.sum()) * self.v)
        if run.ok:
            t = self.dist / self.v
            run.phase(
                "pull",
                t,
                dt=self.dt,
                loads=[rod.ViscousDamping(coefficient=c)],
                constraints=cons,
                save_every=t / self.control.n_frames,
            )

    def _pull_constraints(self, xs) -> list:
        cons, self.dirs = [], []
        pulled = {p for pr, _ in self.pulls for p in pr}
        fixed_nodes = [n for n in self.held_nodes if n not in pulled]
        if fixed_nodes:
            cons.append(Clamp(nodes=fixed_nodes))
        for pair, _ed in self.pulls:
            u = xs[pair[0]] - xs[pair[1]]
            u /= np.linalg.norm(u)
            self.dirs.append(u)
            cons.append(MovingNodes(nodes=pair, path=grip_path(xs[pair], u, self.v, self.t0)))
        cons.append(Clamp(edges=self.held_edges))
        return cons

    # -- measure ---------------------------------------------------------------------
    def measure(self, run: SceneRun) -> CentrelineResult:
        """Pull force, draw-in, verdict and topology; the status checked."""
        times, pos = run.frames()
        m = run.phase_mask("pull")
        tp, pm = times[m], pos[m]
        force = self._force(run, tp)
        draw = self._draw_in(pm)
        verdict, slip_load, k_check = _verdict(force, draw, self.slip, bool(self.free))
        max_force = float(np.nanmax(force)) if force.size else float("nan")
        top0 = _topology(self.rods_x)
        status, message, top1 = self._check_topology(run, pm, force, k_check, top0)
        if status != "success":
            verdict = ""
        stats = dict(run.stats)
        stats["wall_s"] = time.perf_counter() - self.t_wall
        return CentrelineResult(
            verdict=verdict,
            slip_load=slip_load,
            max_force=max_force,
            times=tp,
            pull_displacement=self.v * (tp - self.t0),
            pull_force=force,
            draw_in=draw,
            knots_start=top0[0],
            knots_checked=top1[0],
            linking_start=top0[1],
            linking_checked=top1[1],
            positions=pos,
            status=status,
            message=message,
            stats=stats,
        )

    def _force(self, run, tp) -> np.ndarray:
        force = np.zeros(tp.size)
        for (pair, _ed), u in zip(self.pulls, self.dirs, strict=True):
            force += run.reaction(pair, tp) @ u
        return force / max(len(self.pulls), 1)

    def _draw_in(self, pm) -> np.ndarray:
        """Draw-in [m] of each free end towards the centroid of the start shape."""
        x0 = self.x0
        draw = np.zeros((len(pm), len(self.free)))
        for j, node in enumerate(self.free):
            c = x0.mean(axis=0)
            draw[:, j] = np.linalg.norm(x0[node] - c) - np.linalg.norm(pm[:, node] - c, axis=1)
        return draw

    def _check_topology(self, run, pm, force, k_check, top0):
        status, message, top1 = run.status, run.message, top0
        if force.size:
            split = np.cumsum([len(x) for x in self.rods_x])[:-1]
            try:
                top1 = _topology(np.split(pm[k_check], split))
            except InputError:
                top1 = ((), None)
            if top1 != top0:
                status, message = "failed", "topology changed: a strand passed through another"
        elif status == "success":
            status, message = "failed", "no pull frames recorded"
        return status, message, top1


def _exclusion(d: float, edge: float) -> int:
    """Contact exclusion of the resampled rods: edges of one rod within about 1.25 d of
    each other along it are never paired (at least the solver's default of 2 edges)."""
    return max(2, int(np.ceil(1.25 * d / edge)))


def _verdict(force, draw, slip: float, has_free: bool) -> tuple[str, float, int]:
    """(verdict, slip load [N], frame whose topology is checked) of a pull."""
    verdict, slip_load, k_check = "", float("nan"), force.size - 1
    if not force.size:
        return verdict, slip_load, k_check
    if has_free:
        k_peak = int(np.nanargmax(force))
        beyond = draw.max(axis=1) - draw[: k_peak + 1].max()
        hit = np.nonzero(beyond > slip)[0]
        if hit.size:
            k = int(hit[0])
            return "slips", float(np.nanmax(force[: k + 1])), int(np.nanargmax(force[: k + 1]))
    return "holds", slip_load, k_check

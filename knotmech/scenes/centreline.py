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
from knotmech.scenes._scene import SceneRun, grip_path, post_contact, rod_contact
from knotmech.scenes.curves import _edge_distances, resample_polyline
from knotmech.scenes.topology import close_curve, knot_invariant

__all__ = ["CentrelineResult", "read_centreline", "centreline"]

_UNITS = {"m": 1.0, "cm": 1e-2, "mm": 1e-3}
_END_KINDS = ("pull", "fixed", "free")


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
        One line naming the file and the line at fault.
    """
    if unit not in _UNITS:
        raise InputError(f"unit must be one of {', '.join(_UNITS)}, got {unit!r}")
    text_given = isinstance(source, str) and "\n" in source
    name = "centreline" if text_given else str(source)
    if text_given:
        text = source
    else:
        try:
            text = Path(source).read_text()
        except (OSError, UnicodeDecodeError) as exc:
            raise InputError(f"{name}: cannot read the centreline file ({exc})") from None
    rows = [r for r in csv.reader(io.StringIO(text)) if r and any(c.strip() for c in r)]
    if rows and not _numeric(rows[0][0]):
        rows = rows[1:]  # header
    if not rows:
        raise InputError(f"{name}: no points (expected lines 'x, y, z' or 'rod, x, y, z')")
    width = len(rows[0])
    if width not in (3, 4):
        raise InputError(f"{name}: expected 3 columns (x, y, z) or 4 (rod, x, y, z), got {width}")
    pts: dict[int, list] = {}
    for k, r in enumerate(rows, start=1):
        if len(r) != width:
            raise InputError(f"{name}: point {k} has {len(r)} columns, expected {width}")
        try:
            vals = [float(c) for c in r]
        except ValueError:
            raise InputError(f"{name}: point {k} is not numbers: {', '.join(r)}") from None
        if not np.all(np.isfinite(vals)):
            raise InputError(f"{name}: point {k} is not finite (NaN or infinity)")
        rid = 0 if width == 3 else vals[0]
        if rid not in (0, 1):
            raise InputError(f"{name}: point {k}: rod must be 0 or 1, got {r[0].strip()}")
        pts.setdefault(int(rid), []).append(vals[-3:])
    if set(pts) == {1}:
        raise InputError(f"{name}: rod 1 given without rod 0")
    out = []
    for rid in sorted(pts):
        x = np.array(pts[rid]) * _UNITS[unit]
        if len(x) < 10:
            raise InputError(f"{name}: rod {rid} has {len(x)} points, at least 10 are needed")
        if np.any(np.linalg.norm(np.diff(x, axis=0), axis=1) == 0):
            raise InputError(f"{name}: rod {rid} repeats a point")
        out.append(x)
    return out


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
        Nodes per rod after resampling (>= 10).
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

    Raises
    ------
    InputError
        Bad points (see the module docstring), an ``ends`` entry per rod missing or not one
        of pull/fixed/free, no pulled end, or a physical argument out of range.
    """
    if unit not in _UNITS:
        raise InputError(f"unit must be one of {', '.join(_UNITS)}, got {unit!r}")
    if isinstance(points, (str, Path)):
        raw = read_centreline(points, unit=unit)
    else:
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
            if len(x) < 10:
                raise InputError(f"rod {k} has {len(x)} points, at least 10 are needed")
            raw.append(x)
    d = float(check_positive("rod_diameter", rod_diameter))
    E = float(check_positive("youngs_modulus", youngs_modulus))
    rho = float(check_positive("density", density))
    mu = float(check_nonnegative("mu_rod_rod", mu_rod_rod))
    v = float(check_positive("pull_speed", pull_speed))
    dist = (
        12 * d if pull_distance is None else float(check_positive("pull_distance", pull_distance))
    )
    slip = 4 * d if slip_draw_in is None else float(check_positive("slip_draw_in", slip_draw_in))
    N = int(n_nodes)
    if N != n_nodes or N < 10:
        raise InputError(f"n_nodes must be an integer >= 10, got {n_nodes!r}")
    ends = [tuple(e) for e in ends]
    if len(ends) != len(raw) or any(len(e) != 2 for e in ends):
        raise InputError(f"ends must give (first, last) for each of the {len(raw)} rod(s)")
    for e in ends:
        for k in e:
            if k not in _END_KINDS:
                raise InputError(f"ends must be 'pull', 'fixed' or 'free', got {k!r}")
    if not any("pull" in e for e in ends):
        raise InputError("ends: at least one end must be 'pull'")
    rods_x = [resample_polyline(x, N) for x in raw]
    edge = [float(np.linalg.norm(x[1] - x[0])) for x in rods_x]
    for k, x in enumerate(rods_x):
        exclude = max(3, int(np.ceil(2.0 * d / edge[k])) + 1)
        gap = _min_gap(x, exclude)
        if gap < 0.5 * d:
            raise InputError(
                f"rod {k}: strands come {gap / d:.2f} d apart (< 0.5 d): the centreline "
                "intersects itself (or give a smaller rod_diameter)"
            )
    if len(rods_x) == 2:
        both = np.vstack(rods_x)
        gap = float(_edge_distances(both)[: N - 1, N:].min())
        if gap < 0.5 * d:
            raise InputError(f"the two rods come {gap / d:.2f} d apart (< 0.5 d): they intersect")
    B = E * np.pi * d**4 / 64
    fs = 20 * B / d**2 if force_scale is None else float(check_positive("force_scale", force_scale))
    interactions = [rod_contact(rod_diameter=d, force_scale=fs, mu_static=mu)]
    if post_diameter is not None:
        D = float(check_positive("post_diameter", post_diameter))
        for k, x in enumerate(rods_x):
            rmin = float(np.min(np.hypot(x[:, 0], x[:, 1])))
            if rmin < 0.5 * D + 0.25 * d:
                raise InputError(
                    f"rod {k} cuts the post: it comes {rmin:.4g} m from the axis, inside "
                    f"D/2 + d/4 = {0.5 * D + 0.25 * d:.4g} m"
                )
        mrp = mu if mu_rod_post is None else float(check_nonnegative("mu_rod_post", mu_rod_post))
        interactions.append(
            post_contact(post_diameter=D, rod_diameter=d, force_scale=fs, mu_static=mrp)
        )
    system = rod.RodSystem(
        [
            rod.Rod(positions=x, radius=0.5 * d, youngs_modulus=E, density=rho, natural="straight")
            for x in rods_x
        ]
    )
    held_nodes, held_edges, pulls, free = [], [], [], []
    for r_id, e in enumerate(ends):
        nodes, edges = system.rod_nodes(r_id), system.rod_edges(r_id)
        for side, kind in zip(("start", "end"), e, strict=True):
            pair = (
                [int(nodes[0]), int(nodes[1])]
                if side == "start"
                else [
                    int(nodes[-1]),
                    int(nodes[-2]),
                ]
            )
            ed = int(edges[0] if side == "start" else edges[-1])
            if kind == "free":
                free.append(pair[0])
                continue
            held_nodes += pair
            held_edges.append(ed)
            if kind == "pull":
                pulls.append((pair, ed))
    x0 = system.positions(system.initial_state().q)
    mass = rho * np.pi * d * d / 4
    run = SceneRun(system, interactions=interactions, options=options, progress=progress)
    t_wall = time.perf_counter()
    run.phase(
        "settle",
        float(check_positive("settle_time", settle_time)),
        dt=dt,
        loads=[rod.ViscousDamping(coefficient=20.0 * mass / settle_time)],
        constraints=[Clamp(nodes=held_nodes, edges=held_edges)],
    )
    xs = system.positions(run.state.q)
    t0 = run.t
    cons, dirs = [], []
    fixed_nodes = [n for n in held_nodes if n not in {p for pr, _ in pulls for p in pr}]
    if fixed_nodes:
        cons.append(Clamp(nodes=fixed_nodes))
    for pair, _ed in pulls:
        u = xs[pair[0]] - xs[pair[1]]
        u /= np.linalg.norm(u)
        dirs.append(u)
        cons.append(MovingNodes(nodes=pair, path=grip_path(xs[pair], u, v, t0)))
    cons.append(Clamp(edges=held_edges))
    # drag of the whole length moving at v: 1 % of B/d^2 (quasi-static pull)
    drag = rod.ViscousDamping(coefficient=0.01 * B / d**2 / (float(system.rest_length.sum()) * v))
    if run.ok:
        run.phase(
            "pull", dist / v, dt=dt, loads=[drag], constraints=cons, save_every=dist / v / n_frames
        )
    times, pos = run.frames()
    m = run.phase_mask("pull")
    tp, pm = times[m], pos[m]
    force = np.zeros(tp.size)
    for (pair, _ed), u in zip(pulls, dirs, strict=True):
        force += run.reaction(pair, tp) @ u
    force /= max(len(pulls), 1)
    draw = np.zeros((tp.size, len(free)))
    for j, node in enumerate(free):
        # towards the centroid of the start shape
        c = x0.mean(axis=0)
        draw[:, j] = np.linalg.norm(x0[node] - c) - np.linalg.norm(pm[:, node] - c, axis=1)
    verdict, slip_load, k_check = "", float("nan"), tp.size - 1
    max_force = float(np.nanmax(force)) if force.size else float("nan")
    if force.size:
        verdict = "holds"
        if free:
            k_peak = int(np.nanargmax(force))
            beyond = draw.max(axis=1) - draw[: k_peak + 1].max()
            hit = np.nonzero(beyond > slip)[0]
            if hit.size:
                k = int(hit[0])
                slip_load = float(np.nanmax(force[: k + 1]))
                verdict, k_check = "slips", int(np.nanargmax(force[: k + 1]))
    split = np.cumsum([len(x) for x in rods_x])[:-1]
    top0 = _topology(rods_x)
    top1 = top0
    status, message = run.status, run.message
    if force.size:
        try:
            top1 = _topology(np.split(pm[k_check], split))
        except InputError:
            top1 = ((), None)
        if top1 != top0:
            status, message = "failed", "topology changed: a strand passed through another"
    elif status == "success":
        status, message = "failed", "no pull frames recorded"
    if status != "success":
        verdict = ""
    stats = dict(run.stats)
    stats["wall_s"] = time.perf_counter() - t_wall
    return CentrelineResult(
        verdict=verdict,
        slip_load=slip_load,
        max_force=max_force,
        times=tp,
        pull_displacement=v * (tp - t0),
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

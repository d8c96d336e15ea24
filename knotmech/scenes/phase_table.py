r"""Clove hitch with a free end: DER hold/slip phase table, one point or a shipped grid.

The clove-hitch paper (Extreme Mech. Lett., DOI 10.1016/j.eml.2022.101788, sec. 8 and
Fig. 4) maps whether a clove hitch with a free end (:math:`T_\mathrm{low} = 0`) holds a
dead load :math:`T_\mathrm{high}` as a function of the rescaled load
:math:`T_\mathrm{high}/EA` (:math:`A = \pi d^2/4`) and the rescaled diameter
:math:`d/2R`, with :math:`R = (D+d)/2` the radius of the rod centreline on the post.
Ideal-rope theory (Maddocks & Keller 1987) predicts a slip at any load; the
experiments find a load-dependent boundary with an upper bound near
:math:`T_\mathrm{high}/EA \approx 0.3`.

This module

- simulates one point of that diagram with the DER scene
  :func:`knotmech.scenes.clove_hitch.clove_hitch` (:func:`simulate_point`, a module-level
  function for :func:`knotmech.sweep.sweep`),
- loads the precomputed table shipped in ``knotmech/data/clove_phase_table.json``
  (:func:`load_table`, mu = mu_rr = 0.3; regenerate with ``python -m
  validation.clove_phase_diagram --write-table``) or every shipped table, one per
  friction coefficient mu = mu_rr (``clove_phase_table_mu<mu>.json``, written by
  ``--write-table --mu <mu>``; :func:`load_tables`),
- answers a query from that table (:meth:`PhaseTable.lookup`): the simulated points
  around the query decide when they agree (all held or all slipped), otherwise the
  query is near a boundary and the table does not decide; per d/2R column the upper
  boundary lies between the largest load that held and the smallest that slipped
  above it, interpolated linearly in d/2R. Outside the grid (or at another friction
  coefficient) the table gives no answer and says so,
- answers for any friction from the set of tables (:meth:`PhaseTableSet.lookup`): the
  tables bracketing the user's (mu, mu_rr) decide when they agree, assuming that more
  friction does not turn a hold into a slip (true of every shipped table pair).

Shipped smooth-law tables (``friction="imc"``, d = 4 mm VPS32 rod, 4 x 4 grid, kept
for validation): mu = 0.2 and 0.25 slip at every point, 0.3 holds 6 of 16 (interior
boundary), 0.35 holds 13 (slips only at 0.3 EA off the paper's d/2R), 0.4 and 0.5 hold
all 16.

**Hold tables** (what ``knotmech hold`` reads): the sticking (anchor) rod-rod law, three
axes (d/2R, T_high/EA, mu = mu_rr; :data:`HOLD_GRID`, real-rope ranges), one file per knot
(``knotmech/data/hold_phase_table_<knot>.json``, :class:`HoldTable`,
:func:`load_hold_tables`), built by :func:`build_hold_table` from one
:func:`simulate_point` per point (the scene of each knot is one entry of
:data:`HOLD_SCENE_NAMES`). Each point stores the creep speed of its loose end over the last
second of the hold (:func:`creep_speed`), so the hold criterion (:func:`creep_verdict`,
:data:`CREEP_CRITERION`: slower than :data:`CREEP_LIMIT` = 1e-3 d/s, topology kept, the
run not stopped by a runaway end) can be applied at another limit when read.
:meth:`HoldTable.lookup` decides between points only where the neighbours agree and
beyond the grid only one way where monotonicity says so.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path

import numpy as np

from knotmech.errors import InputError, check_positive

__all__ = [
    "PhasePoint",
    "PhaseTable",
    "PhaseAnswer",
    "simulate_point",
    "point_geometry",
    "load_table",
    "load_tables",
    "PhaseTableSet",
    "TABLE_RESOURCE",
    "HoldPoint",
    "HoldTable",
    "HoldAnswer",
    "HOLD_GRID",
    "HOLD_SCENE_NAMES",
    "hold_scene",
    "build_hold_table",
    "load_hold_tables",
    "load_hold_table_sets",
    "meta_bending_scale",
    "read_hold_table",
    "creep_speed",
    "creep_verdict",
    "PROTOCOL",
    "CREEP_LIMIT",
    "ROD_DIAMETER",
    "YOUNGS_MODULUS",
    "DENSITY",
    "MU",
]

TABLE_RESOURCE = "clove_phase_table.json"  #: the mu = mu_rr = 0.3 table (the first one shipped)
#: every shipped table: ``clove_phase_table.json`` and ``clove_phase_table_mu<mu>.json``
TABLE_GLOB = "clove_phase_table*.json"
MU_TOL = 0.005  #: a friction coefficient within this of a table's is that table's
ROD_DIAMETER = 4e-3  #: [m] the clove-hitch paper's rod (VPS32)
YOUNGS_MODULUS = 1.26e6  #: [Pa] VPS32
DENSITY = 1150.0  #: [kg/m^3]
MU = 0.3  #: rod-post and rod-rod friction of the table (the paper's sec. 7 value)
TAIL = 0.064  #: [m] straight tail at each end (the paper's L = 374 mm at D = 30 mm)
EDGE = 0.374 / 119  #: [m] rest edge length (120 nodes on 374 mm)
SNAP = 1e-3  #: relative distance in d/2R within which a query lies on a table column
#: run protocol of a point with the sticking (anchor) rod-rod law: settle, ramp, hold [s];
#: time step [s]; frames every 0.05 s. The hold is long enough for the creep-speed
#: criterion's window (:data:`CREEP_WINDOW`) after a loaded hitch has re-seated (a finite
#: slide of up to ~0.5 s, then it locks).
PROTOCOL = dict(settle_time=0.2, load_time=0.3, hold_time=1.5, dt=2e-3, n_frames=41)
#: the protocol of the smooth-law (``friction="imc"``) tables shipped first, kept so those
#: tables can be reproduced (hold: end 0 creeps less than d over the last half of the hold)
IMC_PROTOCOL = dict(settle_time=0.2, load_time=0.2, hold_time=0.4, dt=2e-3, n_frames=21)
#: name of the hold criterion of the anchor-law tables and of ``hold --simulate``
CREEP_CRITERION = "creep-speed"
CREEP_LIMIT = 1e-3  #: [d/s] default: holds when the loose end creeps slower than this
CREEP_WINDOW = 1.0  #: [s] the creep speed is measured over the last this-long of the hold
#: meta ``protocol_clock`` of a table whose points ran on the flexural clock below
PROTOCOL_CLOCK = "flexural"
#: the protocol's clock: its times (and its drag rate, set by the settle time) are in units of
#: this rod's flexural time d / (sqrt(kappa) sqrt(E/rho)), the clove-hitch paper's VPS32 rod
#: (:data:`ROD_DIAMETER`, :data:`YOUNGS_MODULUS`, :data:`DENSITY`, kappa = 1): 0.121 ms
REFERENCE_FLEXURAL_TIME = ROD_DIAMETER / (YOUNGS_MODULUS / DENSITY) ** 0.5
MAX_NODES = 200  #: node cap of :func:`point_geometry` (large posts get longer edges)


def protocol_time_scale(
    *, rod_diameter=ROD_DIAMETER, youngs_modulus=YOUNGS_MODULUS, density=DENSITY, bending_scale=1.0
) -> float:
    r"""The factor s by which :func:`simulate_point` stretches :data:`PROTOCOL`'s seconds.

    .. math:: s = \frac{d / (\sqrt{\kappa}\,\sqrt{E/\rho})}{t_\mathrm{ref}}

    with :math:`t_\mathrm{ref}` = :data:`REFERENCE_FLEXURAL_TIME` (the tables' VPS32 rod, s = 1).
    A rod's motion under the protocol depends on its material only through the time in units
    of its own elastic time (there is no gravity, and the contact penalties, the friction
    anchors and the solver tolerances scale with the loads and d); the bending waves that
    let a hitch re-seat are slower by 1/sqrt(kappa). Run in units of d/(sqrt(kappa) c),
    with the creep limit in d per protocol second, every rod of the same kappa, d/2R,
    T_high/EA and mu is the same dimensionless run, so one table per kappa serves every
    material. A 6 mm nylon rope (E = 0.25 GPa, 1140 kg/m^3, kappa 0.01) has s = 1.06; a
    solid nylon rod (kappa 1) 0.11; a 6 mm steel wire rope (80 GPa, 5000 kg/m^3, 0.02) 0.09.
    """
    d = float(check_positive("rod_diameter", rod_diameter))
    E = float(check_positive("youngs_modulus", youngs_modulus))
    rho = float(check_positive("density", density))
    from knotmech.errors import check_bending_scale

    kappa = check_bending_scale(bending_scale)
    return float(d / (kappa * E / rho) ** 0.5 / REFERENCE_FLEXURAL_TIME)


def creep_speed(times, end_displacement, *, rod_diameter, window=CREEP_WINDOW) -> float:
    r"""Mean creep speed of the loaded end along its load over the last ``window`` s [d/s].

    :math:`(u(t_\mathrm{end}) - u(t_\mathrm{end} - w)) / (w\,d)`, with :math:`u` the
    displacement of end 0 along its load [m] (the frame nearest to
    :math:`t_\mathrm{end} - w` at or after it) and :math:`d` the rod diameter [m].
    Positive when the rope is drawn out along the load (through the knot: a slip);
    negative when the end moves back (the knot settling). NaN when the run has fewer
    than two frames in the window.
    """
    t = np.asarray(times, dtype=float)
    u = np.asarray(end_displacement, dtype=float)
    d = float(check_positive("rod_diameter", rod_diameter))
    w = float(check_positive("window", window))
    if t.size < 2:
        return float("nan")
    sel = np.flatnonzero(t >= t[-1] - w - 1e-9)
    if sel.size < 2:
        return float("nan")
    i = int(sel[0])
    return float((u[-1] - u[i]) / (t[-1] - t[i]) / d)


def creep_verdict(
    speed: float,
    *,
    ran_to_end: bool,
    topology_preserved: bool,
    solver_ok: bool = True,
    limit: float = CREEP_LIMIT,
):
    """The creep-speed criterion (:data:`CREEP_CRITERION`) of one run.

    Holds when the run reached the end of its hold (a slipping end that runs off stops the
    run early: a slip), kept the knot's topology, and its loaded end crept slower than
    ``limit`` [d/s] either way over the last :data:`CREEP_WINDOW` of the hold (at rest: an
    end still moving back fast, a stiff rod springing open, is not a hold). Returns ``(holds,
    reason)``; ``holds`` is None when the solver failed (no verdict).
    """
    lim = float(check_positive("creep limit", limit))
    if not solver_ok:
        return None, "solver failed"
    if not ran_to_end:
        return False, "the loaded end ran off (run stopped early)"
    if not topology_preserved:
        return False, "the knot's topology changed"
    if not math.isfinite(speed):
        return None, "no creep speed measured"
    if abs(speed) < lim:
        return True, f"creep {speed:.3g} d/s, slower than {lim:g} d/s"
    return False, f"creep {speed:.3g} d/s, not slower than {lim:g} d/s"


#: a point whose creep speed lies between limit/RECHECK_BAND[0] and limit*RECHECK_BAND[1]
#: is run again with a hold :data:`RECHECK_HOLD_FACTOR` times as long, and the longer run
#: decides: light loads and thick rods settle slowly (a settling hitch's creep decays by
#: ~80x per second at 1e-4 EA; at d/2R 0.23, 1e-3 EA, mu 0.3 it read 4.5e-3 d/s after the
#: 1.5 s hold and 8e-7 d/s after 3 s)
RECHECK_BAND = (10.0, 100.0)
RECHECK_HOLD_FACTOR = 2.0


def needs_recheck(speed: float, *, limit: float = CREEP_LIMIT) -> bool:
    """Whether a creep speed [d/s] lies in the recheck band around the limit
    (:data:`RECHECK_BAND`: a decade below it to two decades above it)."""
    lo, hi = limit / RECHECK_BAND[0], limit * RECHECK_BAND[1]
    return bool(math.isfinite(speed) and lo <= abs(speed) < hi)


def point_geometry(
    d_over_2R: float, *, rod_diameter: float = ROD_DIAMETER, max_nodes: int | None = MAX_NODES
) -> dict:
    r"""Post diameter, rod length and node count of a phase point.

    :math:`d/2R = d/(D+d)` gives :math:`D = d(1/(d/2R) - 1)`; the rod is two wraps
    (:math:`4\pi R` plus 15 % slack for the crossing, as the scene requires) plus a
    64 mm tail at each end (the paper's 374 mm rod at D = 30 mm), discretised with an
    edge length of about 3.1 mm (0.78 d at d = 4 mm), capped at ``max_nodes`` nodes
    (default :data:`MAX_NODES`; None: no cap): on a large post (d/2R < 0.05) the edges
    grow, to 2 d at d/2R = 0.0196 (checked there: 200 and 300 nodes give the same
    verdict, creep speeds within 7 %).
    """
    x = float(d_over_2R)
    if not 0.0 < x < 0.5:
        raise InputError(f"d_over_2R must be in (0, 0.5), got {x:g}")
    d = float(check_positive("rod_diameter", rod_diameter))
    D = d * (1.0 / x - 1.0)
    R = 0.5 * (D + d)
    L = 4 * np.pi * R * 1.15 + 2 * TAIL
    n = int(round(L * (ROD_DIAMETER / d) / EDGE)) + 1
    if max_nodes is not None:
        n = min(n, int(max_nodes))
    return {"post_diameter": D, "rod_length": L, "n_nodes": n}


def _hold_scene_names() -> dict:
    from knotmech.scenes.hitches import HITCHES

    return {name: ident for ident, name in HITCHES.items()}


#: knot -> name of its DER scene function (keywords of
#: :func:`~knotmech.scenes.clove_hitch.clove_hitch`): the registry's hitches with a scene
#: (:mod:`knotmech.knots`)
HOLD_SCENE_NAMES = _hold_scene_names()


def hold_scene(knot: str):
    """The DER scene function of ``knot`` (one of :data:`HOLD_SCENE_NAMES`)."""
    if knot not in HOLD_SCENE_NAMES:
        raise InputError(f"no DER hold scene for {knot!r}; known: {', '.join(HOLD_SCENE_NAMES)}")
    from knotmech.scenes.hitches import hitch_function

    return hitch_function(knot)


def has_hold_scene(knot: str) -> bool:
    """Whether ``knot`` has a DER scene (its registry record; nothing is imported)."""
    return knot in HOLD_SCENE_NAMES


def simulate_point(
    *,
    d_over_2R: float,
    t_over_EA: float,
    mu: float = MU,
    mu_rr: float | None = None,
    rod_diameter: float = ROD_DIAMETER,
    youngs_modulus: float = YOUNGS_MODULUS,
    density: float = DENSITY,
    friction: str = "anchor",
    n_nodes: int | None = None,
    bending_scale: float = 1.0,
    creep_limit: float = CREEP_LIMIT,
    hold_time: float | None = None,
    recheck: bool = False,
    time_scale: float | None = None,
    knot: str = "clove-hitch",
    progress: bool = False,
    keep_result: bool = False,
) -> dict:
    r"""One DER run of a clove hitch with a free end: does it hold :math:`T_\mathrm{high}`?

    Ties the hitch on a post of diameter :math:`D = d(1/(d/2R) - 1)`, hangs
    :math:`T_\mathrm{high} = (T_\mathrm{high}/EA)\,E\pi d^2/4` on end 0 and leaves the
    other end free.

    ``friction`` is the rod-rod law passed to the scene: ``"anchor"`` (the scene's
    default, the law of the anchor tables and of ``hold --simulate``) runs
    :data:`PROTOCOL` and decides by the creep-speed criterion (:func:`creep_verdict`:
    holds when end 0 creeps slower than ``creep_limit`` d/s over the last
    :data:`CREEP_WINDOW` of the hold, topology kept, run not stopped by a runaway end);
    ``"imc"`` (the law of the first shipped tables) runs :data:`IMC_PROTOCOL` and keeps
    those tables' criterion (end 0 creeps less than d over the second half of the hold),
    so they can be reproduced. It is passed explicitly so a change of the scene's
    default does not silently change a table.

    ``bending_scale`` kappa in (0, 1] scales the rod's bending (and twisting) stiffness,
    :math:`B = \kappa E\pi d^4/64` (:class:`knotmech.rod.Rod`; 1, the solid rod of the
    shipped tables); it is returned as ``bending_scale``.

    ``time_scale`` s stretches the protocol's times, its step and its creep window, and
    divides its settling drag rate and the creep limit (which is in d per protocol second)
    by s. None (the default): :func:`protocol_time_scale` of the rod, so a run is the same
    dimensionless run for every material (1 for the tables' VPS32 rod at kappa 1).
    The returned ``creep_speed`` is in d per real second; ``creep_speed_protocol`` = s x
    ``creep_speed`` is what is compared with ``creep_limit``.

    ``hold_time`` [protocol s] replaces the protocol's hold. With ``recheck`` (what ``hold
    --simulate`` uses), a run whose creep speed lies in :data:`RECHECK_BAND` around the
    limit (:func:`needs_recheck`) is run again with a hold :data:`RECHECK_HOLD_FACTOR`
    times as long, and that run decides (``first_creep_speed`` keeps the first speed).

    Returns
    -------
    dict
        ``d_over_2R, t_over_EA, t_high [N], post_diameter [m], n_nodes, mu, mu_rr,
        friction, criterion, creep_limit [d/s], verdict ("hold"/"slip"), holds (bool),
        reason, creep [m] (end 0 over the last half of the hold), creep_speed [d/s]
        (:func:`creep_speed` over the last :data:`CREEP_WINDOW`; NaN when the run stopped
        early), ran_to_end, status, message, topology_preserved, wall_s, cpu_s``. A run
        whose solver failed has ``holds = None``. With ``keep_result``, also ``result``:
        the scene's :class:`~knotmech.scenes.clove_hitch.CloveHitchResult`.
    """
    import time

    d = float(check_positive("rod_diameter", rod_diameter))
    E = float(check_positive("youngs_modulus", youngs_modulus))
    tea = float(check_positive("t_over_EA", t_over_EA))
    lim = float(check_positive("creep_limit", creep_limit))
    from knotmech.errors import check_bending_scale

    kappa = check_bending_scale(bending_scale)
    if friction not in ("anchor", "imc"):
        raise InputError(f"friction must be 'anchor' or 'imc', got {friction!r}")
    if time_scale is None:
        ts = protocol_time_scale(rod_diameter=d, youngs_modulus=E, density=density,
                                 bending_scale=kappa)  # fmt: skip
    else:
        ts = float(check_positive("time_scale", time_scale))
    scene = hold_scene(knot)
    geo = point_geometry(d_over_2R, rod_diameter=d)
    if knot == "clove-hitch":
        nn = geo["n_nodes"] if n_nodes is None else int(n_nodes)
        length = geo["rod_length"]
    else:  # the knot's curve picks its length and (n_nodes None) its edges
        nn = None if n_nodes is None else int(n_nodes)
        length = None
    proto = dict(PROTOCOL if friction == "anchor" else IMC_PROTOCOL)
    if hold_time is not None:
        h = float(check_positive("hold_time", hold_time))
        proto["hold_time"] = h
        proto["n_frames"] = int(round((proto["settle_time"] + proto["load_time"] + h) / 0.05)) + 1
    t_high = tea * E * np.pi * d * d / 4
    run_proto = {k: (v * ts if k in ("settle_time", "load_time", "hold_time", "dt") else v)
                 for k, v in proto.items()}  # fmt: skip
    window = min(CREEP_WINDOW, proto["hold_time"]) * ts
    if knot != "clove-hitch":  # the hitch scenes' own window: at most half the hold
        run_proto["creep_window"] = min(CREEP_WINDOW, 0.5 * proto["hold_time"]) * ts
    c0 = time.process_time()
    r = scene(
        loading="free",
        t_high=t_high,
        rod_diameter=d,
        post_diameter=geo["post_diameter"],
        rod_length=length,
        n_nodes=nn,
        youngs_modulus=E,
        density=float(density),
        **({} if kappa == 1.0 else {"bending_scale": kappa}),
        mu_rod_post=float(mu),
        mu_rod_rod=float(mu if mu_rr is None else mu_rr),
        friction=friction,
        progress=progress,
        **run_proto,
    )
    cpu = time.process_time() - c0
    t_end = sum(run_proto[k] for k in ("settle_time", "load_time", "hold_time"))
    times = np.asarray(r.times, dtype=float)
    ran = bool(times.size and times[-1] >= t_end - 1e-9 * ts)
    solver_ok = r.status == "success" or r.verdict == "slip"
    if not ran:
        speed = float("nan")
    elif knot == "clove-hitch":
        speed = creep_speed(r.times, r.end_displacement, rod_diameter=d, window=window)
    else:  # the hitch scenes' own creep speed: the least-squares slope over the window
        speed = float(r.creep_speed_d)  # (their hold runs with a tenth of the drag and rings)
        window = float(r.creep_window)  # the scene's window: the last half of a 1.5 s hold
    if friction == "anchor":
        holds, reason = creep_verdict(
            speed * ts, ran_to_end=ran, topology_preserved=bool(r.topology_preserved),
            solver_ok=solver_ok, limit=lim,
        )  # fmt: skip
        criterion = CREEP_CRITERION
    else:
        holds = (r.verdict == "hold") if solver_ok else None
        reason = "end 0 moved less than d over the last half of the hold" if holds else (
            "end 0 moved d or more over the last half of the hold (or ran off)")  # fmt: skip
        criterion = "distance"
    out = {
        "d_over_2R": float(d_over_2R),
        "t_over_EA": tea,
        "t_high": float(t_high),
        "post_diameter": geo["post_diameter"],
        "n_nodes": int(np.asarray(r.positions).shape[1]) if nn is None else nn,
        "knot": knot,
        "mu": float(mu),
        "mu_rr": float(mu if mu_rr is None else mu_rr),
        "friction": friction,
        "bending_scale": kappa,
        "criterion": criterion,
        "creep_limit": lim,
        "creep_window_s": window,
        "hold_time": proto["hold_time"],
        "time_scale": ts,
        "creep_speed_signed": True,
        "verdict": "" if holds is None else ("hold" if holds else "slip"),
        "holds": holds,
        "reason": reason,
        "creep": float(r.creep),
        "creep_speed": speed,
        "creep_speed_protocol": speed * ts,
        "ran_to_end": ran,
        "status": r.status,
        "message": r.message,
        "topology_preserved": bool(r.topology_preserved),
        "wall_s": float(r.stats.get("wall_s", float("nan"))),
        "cpu_s": float(cpu),
    }
    if keep_result:
        out["result"] = r
    if recheck and friction == "anchor" and ran and needs_recheck(speed * ts, limit=lim):
        again = simulate_point(
            d_over_2R=d_over_2R, t_over_EA=t_over_EA, mu=mu, mu_rr=mu_rr, rod_diameter=d,
            youngs_modulus=E, density=density, friction=friction, n_nodes=n_nodes,
            bending_scale=kappa, creep_limit=lim,
            hold_time=RECHECK_HOLD_FACTOR * proto["hold_time"], time_scale=time_scale,
            knot=knot, progress=progress, keep_result=keep_result,
        )  # fmt: skip
        again["first_creep_speed"] = speed
        again["first_hold_time"] = proto["hold_time"]
        again["cpu_s"] += out["cpu_s"]
        return again
    return out


#: 4: the protocol runs on the rod's flexural clock (:func:`protocol_time_scale`; the same
#: as 3 for the reference rod at kappa 1, different for every other rod)
simulate_point.__sweep_version__ = "4"


@dataclass(frozen=True)
class PhasePoint:
    """One simulated point: rescaled diameter, rescaled load, held or not."""

    d_over_2R: float
    t_over_EA: float
    holds: bool


@dataclass(frozen=True)
class PhaseAnswer:
    """Answer of :meth:`PhaseTable.lookup`.

    ``holds`` is None when the query lies outside the table (``inside`` False) or in a
    column where the boundary is not bracketed by the simulated loads; ``critical`` is
    the interpolated critical load :math:`T_\\mathrm{high}/EA` (midpoint of the bracket;
    ``bracket`` its (largest held, smallest slipped) bounds, inf when nothing slipped).
    """

    holds: bool | None
    inside: bool
    critical: float
    bracket: tuple
    message: str
    mu_tables: tuple = ()

    def to_dict(self) -> dict:
        def num(v):
            return v if math.isfinite(v) else str(v)

        return {
            "holds": self.holds,
            "inside_table": self.inside,
            "critical_t_over_EA": num(self.critical),
            "bracket_t_over_EA": [num(float(v)) for v in self.bracket],
            "message": self.message,
            "mu_tables": list(self.mu_tables),
        }


@dataclass
class PhaseTable:
    """Hold/slip points of the DER clove hitch with a free end, on a (d/2R, T/EA) grid."""

    points: list
    mu: float = MU
    mu_rr: float = MU
    meta: dict = field(default_factory=dict)

    @property
    def d_over_2R(self) -> np.ndarray:
        """Sorted distinct d/2R columns."""
        return np.unique([p.d_over_2R for p in self.points])

    @property
    def t_over_EA(self) -> np.ndarray:
        """Sorted distinct loads T_high/EA."""
        return np.unique([p.t_over_EA for p in self.points])

    def _column(self, x: float) -> list:
        return sorted(
            (p for p in self.points if math.isclose(p.d_over_2R, x, rel_tol=1e-9)),
            key=lambda p: p.t_over_EA,
        )

    def column_bracket(self, x: float) -> tuple:
        """Upper boundary in the column d/2R = x: (largest load held, smallest slipped above it).

        0 when nothing held (then the smallest load that slipped is the upper bound), inf
        when nothing above the largest hold slipped.
        """
        col = self._column(x)
        held = [p.t_over_EA for p in col if p.holds]
        lo = max(held) if held else 0.0
        above = [p.t_over_EA for p in col if not p.holds and p.t_over_EA > lo]
        return lo, (min(above) if above else math.inf)

    def low_slip(self, x: float) -> float:
        """Largest load that slipped *below* the smallest load held in the column (0 if none).

        A light load may not tighten a stiff rod onto a thin post: such a column has a
        lower boundary too.
        """
        col = self._column(x)
        held = [p.t_over_EA for p in col if p.holds]
        if not held:
            return 0.0
        below = [p.t_over_EA for p in col if not p.holds and p.t_over_EA < min(held)]
        return max(below) if below else 0.0

    def boundary(self):
        """(d/2R columns, lower bounds, upper bounds, midpoints) of the upper hold/slip boundary.

        The midpoint is inf where nothing slipped above the holds.
        """
        xs = self.d_over_2R
        lo = np.empty(xs.size)
        hi = np.empty(xs.size)
        for i, x in enumerate(xs):
            lo[i], hi[i] = self.column_bracket(float(x))
        mid = np.where(np.isfinite(hi), 0.5 * (lo + hi), np.inf)
        return xs, lo, hi, mid

    def _corners(self, x: float, y: float) -> list:
        """Grid points around (x, y): the columns at or on each side of x, the loads at or
        on each side of y in each column."""
        xs = self.d_over_2R
        i = int(np.searchsorted(xs, x))
        # a query within 0.1 % of a column is on it (the grid's 0.1176 is the paper's 4/34)
        if i < xs.size and math.isclose(xs[i], x, rel_tol=SNAP):
            cols = [xs[i]]
        elif i > 0 and math.isclose(xs[i - 1], x, rel_tol=SNAP):
            cols = [xs[i - 1]]
        else:
            cols = [xs[max(i - 1, 0)], xs[min(i, xs.size - 1)]]
        out = []
        for c in cols:
            col = self._column(float(c))
            loads = np.array([p.t_over_EA for p in col])
            j = int(np.searchsorted(loads, y))
            if j < loads.size and math.isclose(loads[j], y, rel_tol=1e-9):
                out.append(col[j])
            else:
                out += [col[k] for k in (j - 1, j) if 0 <= k < loads.size]
        return out

    def lookup(self, d_over_2R: float, t_over_EA: float, *, mu=None, mu_rr=None) -> PhaseAnswer:
        """Hold or slip at (d/2R, T_high/EA), from the grid points around the query.

        The simulated points at or around the query (up to two columns in d/2R, two loads
        in each) decide when they agree: all held -> holds, all slipped -> slips; a mix
        means the query lies near a boundary and the table does not decide (None). The
        reported critical load is the upper boundary (midpoint between the largest load
        held and the smallest slipped), interpolated linearly in d/2R. Outside the table's
        d/2R or load range, or at a friction coefficient other than the table's
        (tolerance 0.005), the answer is None with a message saying why.
        """
        x = float(d_over_2R)
        y = float(t_over_EA)
        if not (math.isfinite(x) and math.isfinite(y)) or y < 0:
            raise InputError(f"d_over_2R and t_over_EA must be finite, >= 0; got {x}, {y}")
        xs, lo, hi, _ = self.boundary()
        ys = self.t_over_EA
        nan = (float("nan"), float("nan"))

        def outside(msg):
            return PhaseAnswer(None, False, float("nan"), nan, msg)

        for name, val, ref in (("mu", mu, self.mu), ("mu_rr", mu_rr, self.mu_rr)):
            if val is not None and abs(float(val) - ref) > 0.005:
                return outside(
                    f"the DER table was computed at {name} = {ref:g} only, not {float(val):g}"
                )
        if not (xs[0] * (1 - SNAP) <= x <= xs[-1] * (1 + SNAP)):
            return outside(f"d/2R = {x:.4g} is outside the DER table ({xs[0]:.4g} to {xs[-1]:.4g})")
        if not (ys[0] * (1 - 1e-9) <= y <= ys[-1] * (1 + 1e-9)):
            return outside(
                f"T_high/EA = {y:.4g} is outside the simulated loads ({ys[0]:.4g} to {ys[-1]:.4g})"
            )
        big = 1e30
        lo_i = float(np.interp(x, xs, lo))
        hi_i = float(np.interp(x, xs, np.where(np.isfinite(hi), hi, big)))
        if hi_i >= big / 2:
            hi_i = math.inf
        crit = 0.5 * (lo_i + hi_i) if math.isfinite(hi_i) else math.inf
        corners = self._corners(x, y)
        votes = {p.holds for p in corners}
        pts = ", ".join(
            f"({p.d_over_2R:.3g}, {p.t_over_EA:.3g}) {'held' if p.holds else 'slipped'}"
            for p in corners
        )
        where = f"d/2R = {x:.4g}, T_high/EA = {y:.4g}"
        if votes == {True}:
            holds, msg = True, f"holds in the DER table at {where} (grid points: {pts})"
        elif votes == {False}:
            holds, msg = False, f"slips in the DER table at {where} (grid points: {pts})"
        else:
            holds = None
            msg = (
                f"{where} lies near a hold/slip boundary of the DER table (grid points: "
                f"{pts}): undecided, use --simulate"
            )
        return PhaseAnswer(holds, True, crit, (lo_i, hi_i), msg, (self.mu,))

    def to_dict(self) -> dict:
        return {
            "mu": self.mu,
            "mu_rr": self.mu_rr,
            "meta": self.meta,
            "points": [[p.d_over_2R, p.t_over_EA, bool(p.holds)] for p in self.points],
        }

    @classmethod
    def from_dict(cls, data: dict) -> PhaseTable:
        try:
            pts = [PhasePoint(float(a), float(b), bool(c)) for a, b, c in data["points"]]
            return cls(pts, float(data["mu"]), float(data["mu_rr"]), dict(data.get("meta", {})))
        except (KeyError, TypeError, ValueError) as exc:
            raise InputError(f"not a clove-hitch phase table: {exc}") from None

    def write(self, path) -> None:
        text = json.dumps(self.to_dict(), indent=None, allow_nan=False)
        Path(path).write_text(text.replace("], [", "],\n [") + "\n")


def load_table(path=None) -> PhaseTable:
    """The shipped table (``knotmech/data/clove_phase_table.json``) or one from ``path``."""
    if path is None:
        try:
            text = resources.files("knotmech").joinpath("data", TABLE_RESOURCE).read_text()
        except (FileNotFoundError, OSError) as exc:
            raise InputError(f"the shipped phase table is missing: {exc}") from None
    else:
        try:
            text = Path(path).read_text()
        except OSError as exc:
            raise InputError(f"cannot read phase table {str(path)!r}: {exc.strerror}") from None
    try:
        data = json.loads(text)
    except json.JSONDecodeError as exc:
        raise InputError(f"phase table is not JSON: {exc}") from None
    return PhaseTable.from_dict(data)


def table_resource(mu: float) -> str:
    """File name in ``knotmech/data`` of the shipped table at mu = mu_rr = ``mu``."""
    return TABLE_RESOURCE if abs(float(mu) - MU) <= MU_TOL else f"clove_phase_table_mu{mu:g}.json"


def _fmt_mus(mus) -> str:
    return ", ".join(f"{m:g}" for m in mus)


@dataclass
class PhaseTableSet:
    r"""Phase tables at several friction coefficients mu = mu_rr, answering for any mu.

    :meth:`lookup` brackets the user's friction by the tables: with
    :math:`\mu_- = \min(\mu, \mu_{rr})` and :math:`\mu_+ = \max(\mu, \mu_{rr})`,
    the largest table coefficient :math:`\le \mu_-` and the smallest :math:`\ge \mu_+`
    (one table when the query is on a table's coefficient, within :data:`MU_TOL`). The
    answer is decided when both tables decide the same way; this rests on the hold
    being monotonic in friction (a hold at lower friction stays a hold at higher
    friction), which the shipped tables are tested for. Beyond the tables' friction range
    the same assumption decides one way only: above the largest coefficient a hold in
    that table is a hold; below the smallest a slip in that table is a slip; otherwise
    the answer is None and says so.
    """

    tables: list

    def __post_init__(self):
        if not self.tables:
            raise InputError("a phase-table set needs at least one table")
        for t in self.tables:
            if abs(t.mu - t.mu_rr) > MU_TOL:
                raise InputError(
                    f"a phase-table set holds tables with mu = mu_rr only, got mu = {t.mu:g}, "
                    f"mu_rr = {t.mu_rr:g}"
                )
        self.tables = sorted(self.tables, key=lambda t: t.mu)
        mus = [t.mu for t in self.tables]
        if any(b - a <= MU_TOL for a, b in zip(mus, mus[1:], strict=False)):
            raise InputError(f"two phase tables at the same mu: {_fmt_mus(mus)}")

    @property
    def mus(self) -> list:
        """Friction coefficients (mu = mu_rr) of the tables, ascending."""
        return [t.mu for t in self.tables]

    def table(self, mu: float) -> PhaseTable:
        """The table at ``mu`` (within :data:`MU_TOL`)."""
        for t in self.tables:
            if abs(t.mu - float(mu)) <= MU_TOL:
                return t
        raise InputError(f"no phase table at mu = {float(mu):g} (tables: {_fmt_mus(self.mus)})")

    def lookup(self, d_over_2R: float, t_over_EA: float, *, mu: float, mu_rr=None) -> PhaseAnswer:
        r"""Hold or slip at (d/2R, T_high/EA) and friction (mu, mu_rr) from the bracketing tables.

        ``mu_rr`` defaults to ``mu``. The answer's ``mu_tables`` names the tables used;
        ``bracket`` is (smallest largest-load-held, largest smallest-load-slipped) of
        those tables, ``critical`` the upper boundary interpolated linearly in mu at
        :math:`(\mu + \mu_{rr})/2`.
        """
        m = float(mu)
        mr = m if mu_rr is None else float(mu_rr)
        if not (math.isfinite(m) and math.isfinite(mr)) or m < 0 or mr < 0:
            raise InputError(f"mu and mu_rr must be finite, >= 0; got {m}, {mr}")
        lo_m, hi_m = min(m, mr), max(m, mr)
        mus = self.mus
        nan = (float("nan"), float("nan"))
        which = f"mu = {m:g}" + ("" if mr == m else f", mu_rr = {mr:g}")
        below = max((t for t in self.tables if t.mu <= lo_m + MU_TOL), key=lambda t: t.mu,
                    default=None)  # fmt: skip
        above = min((t for t in self.tables if t.mu >= hi_m - MU_TOL), key=lambda t: t.mu,
                    default=None)  # fmt: skip
        if below is None and above is None:
            return PhaseAnswer(
                None,
                False,
                float("nan"),
                nan,
                f"{which} is outside the friction range of the DER tables (computed at "
                f"mu = mu_rr = {_fmt_mus(mus)} only)",
            )
        if below is None or above is None:
            # one side only: a hold at less friction stays a hold at more, a slip at more
            # friction stays a slip at less (the assumption the bracketing rests on)
            one = below if above is None else above
            a = one.lookup(d_over_2R, t_over_EA)
            if not a.inside:
                return a
            side = "above" if above is None else "below"
            decides = a.holds is (above is None)  # holds from below, slips from above
            if decides:
                msg = (
                    f"{'holds' if a.holds else 'slips'} in the DER table at mu = mu_rr = "
                    f"{one.mu:g}, and {which} lies {side} the tables (computed at mu = mu_rr = "
                    f"{_fmt_mus(mus)}): {'more' if a.holds else 'less'} friction keeps that "
                    f"(assumed; true of every pair of shipped tables); {a.message}"
                )
                return PhaseAnswer(a.holds, True, a.critical, a.bracket, msg, (one.mu,))
            state = {True: "holds", False: "slips", None: "undecided"}[a.holds]
            msg = (
                f"{which} lies {side} the friction range of the DER tables (computed at "
                f"mu = mu_rr = {_fmt_mus(mus)}) and the nearest, mu = {one.mu:g}, {state}: "
                f"undecided, use --simulate ({a.message})"
            )
            return PhaseAnswer(None, True, float("nan"), nan, msg, (one.mu,))
        if below is above:
            a = below.lookup(d_over_2R, t_over_EA)
            if not a.inside:
                return a
            return PhaseAnswer(
                a.holds,
                True,
                a.critical,
                a.bracket,
                f"{a.message}; table mu = mu_rr = {below.mu:g}",
                (below.mu,),
            )
        a = below.lookup(d_over_2R, t_over_EA)
        b = above.lookup(d_over_2R, t_over_EA)
        for r in (a, b):
            if not r.inside:
                return r
        used = (below.mu, above.mu)

        def say(r):
            return {True: "holds", False: "slips", None: "undecided"}[r.holds]

        w = (0.5 * (lo_m + hi_m) - below.mu) / (above.mu - below.mu)
        if math.isfinite(a.critical) and math.isfinite(b.critical):
            crit = (1 - w) * a.critical + w * b.critical
        else:
            crit = math.inf if math.isinf(a.critical) and math.isinf(b.critical) else float("nan")
        bracket = (min(a.bracket[0], b.bracket[0]), max(a.bracket[1], b.bracket[1]))
        tabs = f"the DER tables at mu = mu_rr = {below.mu:g} ({say(a)}) and {above.mu:g} ({say(b)})"
        if a.holds is not None and a.holds == b.holds:
            msg = (
                f"{say(a)} in {tabs}, which bracket {which} (assumes friction does not turn a "
                f"hold into a slip); {below.mu:g}: {a.message}; {above.mu:g}: {b.message}"
            )
            return PhaseAnswer(a.holds, True, crit, bracket, msg, used)
        msg = (
            f"{tabs}, which bracket {which}, do not agree: undecided, use --simulate "
            f"({below.mu:g}: {a.message}; {above.mu:g}: {b.message})"
        )
        return PhaseAnswer(None, True, crit, bracket, msg, used)


def load_tables(paths=None) -> PhaseTableSet:
    """Every shipped table (``knotmech/data/clove_phase_table*.json``) or those in ``paths``."""
    if paths is not None:
        return PhaseTableSet([load_table(p) for p in paths])
    try:
        folder = resources.files("knotmech").joinpath("data")
        names = sorted(
            f.name for f in folder.iterdir() if Path(f.name).match(TABLE_GLOB) and f.is_file()
        )
    except (FileNotFoundError, OSError) as exc:
        raise InputError(f"the shipped phase tables are missing: {exc}") from None
    if not names:
        raise InputError("the shipped phase tables are missing")
    return PhaseTableSet([_read_table(folder.joinpath(n).read_text(), n) for n in names])


def _read_table(text: str, name: str) -> PhaseTable:
    try:
        data = json.loads(text)
    except json.JSONDecodeError as exc:
        raise InputError(f"phase table {name} is not JSON: {exc}") from None
    return PhaseTable.from_dict(data)


# --------------------------------------------------------------------------- hold tables
#: file names of the shipped anchor-law hold tables, one per knot:
#: ``hold_phase_table_<knot>.json`` (three axes d/2R, T_high/EA, mu = mu_rr)
HOLD_TABLE_GLOB = "hold_phase_table_*.json"
HOLD_TABLE_FORMAT = "knotmech-hold-table"
#: the columns of a hold table's points
HOLD_COLUMNS = ("d_over_2R", "t_over_EA", "mu", "creep_speed", "ran_to_end", "topology", "solved")
_AXES = ("d_over_2R", "t_over_EA", "mu")
_AXIS_TEXT = {"d_over_2R": "d/2R", "t_over_EA": "T_high/EA", "mu": "mu = mu_rr"}


@dataclass(frozen=True)
class HoldPoint:
    """One DER run of a hold table.

    ``creep_speed`` [d/s] over the last :data:`CREEP_WINDOW` of the hold (NaN when the run
    stopped early), ``ran_to_end`` (False: the loaded end ran off), ``topology`` (the knot
    kept its topology), ``solved`` (the solver did not fail).
    """

    d_over_2R: float
    t_over_EA: float
    mu: float
    creep_speed: float
    ran_to_end: bool
    topology: bool
    solved: bool = True

    def holds(self, limit: float = CREEP_LIMIT):
        """The creep-speed criterion at ``limit`` [d/s] (:func:`creep_verdict`)."""
        return creep_verdict(
            self.creep_speed, ran_to_end=self.ran_to_end, topology_preserved=self.topology,
            solver_ok=self.solved, limit=limit,
        )[0]  # fmt: skip

    def describe(self, limit: float = CREEP_LIMIT) -> str:
        h = self.holds(limit)
        state = {True: "held", False: "slipped", None: "failed"}[h]
        if not self.ran_to_end:
            why = "ran off"
        elif not self.topology:
            why = "topology changed"
        elif math.isfinite(self.creep_speed):
            why = f"{self.creep_speed:.2g} d/s"
        else:
            why = "no creep"
        return f"({self.d_over_2R:.4g}, {self.t_over_EA:.3g}, mu {self.mu:g}) {state}, {why}"


@dataclass(frozen=True)
class HoldAnswer:
    """Answer of :meth:`HoldTable.lookup`.

    ``holds`` True / False / None (undecided); ``rule``: ``"grid"`` (the neighbouring
    points agree), ``"settled-light-load"`` (below the lightest load: the two lightest agree),
    ``"heavier-slips"`` (above the heaviest load, which slipped), ``"more-friction-holds"``,
    ``"less-friction-slips"``, or ``"undecided"``; ``corners`` the grid points used;
    ``creep_speed`` the largest creep speed measured among those points that held [d/s]
    (NaN if none); ``capacity_t_over_EA`` the largest tabulated load held in every corner
    column, with every lighter tabulated load above the query's also held (a lower bound of
    the capacity; NaN if none), ``first_slip_t_over_EA`` the smallest load above the query
    that slipped in any corner column (inf if none).
    """

    holds: bool | None
    inside: bool
    rule: str
    message: str
    corners: tuple = ()
    creep_speed: float = float("nan")
    capacity_t_over_EA: float = float("nan")
    first_slip_t_over_EA: float = float("inf")
    mu_tables: tuple = ()

    @property
    def critical(self) -> float:
        """Midpoint of (capacity, first slip) [T_high/EA]; inf when nothing slipped above."""
        lo, hi = self.capacity_t_over_EA, self.first_slip_t_over_EA
        if not math.isfinite(lo):
            return float("nan")
        return 0.5 * (lo + hi) if math.isfinite(hi) else math.inf

    @property
    def bracket(self) -> tuple:
        return (self.capacity_t_over_EA, self.first_slip_t_over_EA)


def _axis(values, lo, hi, *, rel=SNAP):
    """Grid indices around [lo, hi] on one sorted axis and where the query lies.

    Returns (indices, where): where is "on" (one grid value), "between", "below" or
    "above" the axis (then the indices are the end value(s)).
    """
    v = np.asarray(values, dtype=float)
    near_lo = np.flatnonzero(np.isclose(v, lo, rtol=rel, atol=0))
    near_hi = np.flatnonzero(np.isclose(v, hi, rtol=rel, atol=0))
    if near_lo.size and near_hi.size and near_lo[0] == near_hi[0]:
        return [int(near_lo[0])], "on"
    if hi < v[0] * (1 - rel):
        return [0], "below"
    if lo > v[-1] * (1 + rel):
        return [v.size - 1], "above"
    i = int(near_lo[0]) if near_lo.size else int(np.searchsorted(v, lo) - 1)
    j = int(near_hi[0]) if near_hi.size else int(np.searchsorted(v, hi))
    if i < 0:
        return [0], "below"
    if j >= v.size:
        return [v.size - 1], "above"
    return sorted({i, j}), "between"


@dataclass
class HoldTable:
    r"""DER hold/slip runs of one knot with a free end on a (d/2R, T_high/EA, mu) grid.

    Every point stores the creep speed it measured, so the criterion's limit can be
    changed at lookup (:meth:`lookup`, ``creep_limit``). mu is the rope-post and the
    rope-rope coefficient alike (mu = mu_rr).

    **Deciding** (:meth:`lookup`). Between grid points the answer is decided only where
    every neighbouring point (up to two values on each axis) agrees. Beyond the grid only
    where monotonicity says so:

    - a load lighter than the lightest tabulated one takes that load's answer when the
      two lightest loads agree at every neighbouring (d/2R, mu) (the verdict has settled as
      the load falls);
    - a load heavier than the heaviest: slips where that load slipped (a hold there says
      nothing about heavier loads);
    - a friction above the largest: holds where that friction held; below the smallest:
      slips where that friction slipped;
    - outside the d/2R range: never decided (no monotonicity in d/2R is assumed).

    A rope-rope friction ``mu_rr`` other than ``mu`` brackets the mu axis by
    ``[min(mu, mu_rr), max(mu, mu_rr)]`` (assumes more friction of either kind does not
    turn a hold into a slip). Everything else is undecided, with the reason.
    """

    knot: str
    points: list
    meta: dict = field(default_factory=dict)
    law: str = "anchor"
    criterion: dict = field(
        default_factory=lambda: {
            "name": CREEP_CRITERION, "limit_d_per_s": CREEP_LIMIT, "window_s": CREEP_WINDOW,
        }
    )  # fmt: skip

    def __post_init__(self):
        if not self.points:
            raise InputError(f"hold table of {self.knot}: no points")
        self._index = {}
        for p in self.points:
            if not (0 < p.d_over_2R < 0.5 and p.t_over_EA > 0 and p.mu >= 0):
                raise InputError(
                    f"hold table of {self.knot}: point ({p.d_over_2R:g}, {p.t_over_EA:g}, "
                    f"{p.mu:g}) is outside 0 < d/2R < 0.5, T_high/EA > 0, mu >= 0"
                )
            key = self._key(p.d_over_2R, p.t_over_EA, p.mu)
            if key in self._index:
                raise InputError(f"hold table of {self.knot}: point {key} appears twice")
            self._index[key] = p
        self.axes = {a: np.unique([getattr(p, a) for p in self.points]) for a in _AXES}
        n = int(np.prod([v.size for v in self.axes.values()]))
        if n != len(self.points):
            raise InputError(
                f"hold table of {self.knot}: {len(self.points)} points do not fill the "
                f"{' x '.join(str(v.size) for v in self.axes.values())} grid"
            )

    @staticmethod
    def _key(x, y, m):
        return (round(float(x), 9), round(float(y), 12), round(float(m), 9))

    def point(self, x, y, m) -> HoldPoint:
        """The grid point at (d/2R, T_high/EA, mu) (exact grid values)."""
        return self._index[self._key(x, y, m)]

    @property
    def mus(self) -> list:
        return [float(m) for m in self.axes["mu"]]

    def slice(self, mu: float, *, creep_limit: float = CREEP_LIMIT) -> PhaseTable:
        """The (d/2R, T_high/EA) slice at a tabulated ``mu`` as a :class:`PhaseTable`."""
        m = [v for v in self.mus if abs(v - float(mu)) <= MU_TOL]
        if not m:
            raise InputError(f"no mu = {float(mu):g} in the {self.knot} hold table ({self.mus})")
        pts = [PhasePoint(p.d_over_2R, p.t_over_EA, bool(p.holds(creep_limit)))
               for p in self.points if p.mu == m[0]]  # fmt: skip
        return PhaseTable(pts, m[0], m[0], {"law": self.law, "knot": self.knot})

    def lookup(
        self,
        d_over_2R: float,
        t_over_EA: float,
        *,
        mu: float,
        mu_rr: float | None = None,
        creep_limit: float = CREEP_LIMIT,
    ) -> HoldAnswer:
        """Hold, slip or undecided at (d/2R, T_high/EA, mu, mu_rr) by the rules above."""
        x, y, m = float(d_over_2R), float(t_over_EA), float(mu)
        mr = m if mu_rr is None else float(mu_rr)
        lim = float(check_positive("creep_limit", creep_limit))
        for name, v in (("d_over_2R", x), ("t_over_EA", y), ("mu", m), ("mu_rr", mr)):
            if not math.isfinite(v) or v < 0:
                raise InputError(f"{name} must be finite and >= 0, got {v}")
        ax = self.axes
        xi, xw = _axis(ax["d_over_2R"], x, x)
        yi, yw = _axis(ax["t_over_EA"], y, y, rel=1e-9)
        mi, mw = _axis(ax["mu"], min(m, mr), max(m, mr), rel=MU_TOL / max(m, mr, 1e-9))
        if yw == "below":
            yi = [0, 1] if ax["t_over_EA"].size > 1 else [0]
        where = f"d/2R = {x:.4g}, T_high/EA = {y:.3g}, mu = {m:g}" + (
            "" if mr == m else f", mu_rr = {mr:g}")  # fmt: skip
        mus_used = tuple(float(ax["mu"][k]) for k in mi)
        if xw in ("below", "above"):
            return HoldAnswer(
                None, False, "undecided",
                f"{where}: d/2R is {xw} the {self.knot} table ({ax['d_over_2R'][0]:.4g} to "
                f"{ax['d_over_2R'][-1]:.4g}), where nothing is assumed about how d/2R "
                "changes the verdict: undecided", mu_tables=mus_used,
            )  # fmt: skip
        corners = [self.point(ax["d_over_2R"][i], ax["t_over_EA"][j], ax["mu"][k])
                   for i in xi for j in yi for k in mi]  # fmt: skip
        votes = [p.holds(lim) for p in corners]
        pts = "; ".join(p.describe(lim) for p in corners)
        speeds = [p.creep_speed for p, v in zip(corners, votes, strict=True) if v]
        speed = max(speeds, key=abs) if speeds else float("nan")
        cap, first_slip = self._capacity(xi, mi, y, lim)
        common = dict(corners=tuple(corners), creep_speed=speed, capacity_t_over_EA=cap,
                      first_slip_t_over_EA=first_slip, mu_tables=mus_used)  # fmt: skip
        inside = yw in ("on", "between") and mw in ("on", "between")
        if None in votes:
            return HoldAnswer(None, inside, "undecided",
                              f"{where}: a neighbouring DER run failed ({pts}): undecided",
                              **common)  # fmt: skip
        if len(set(votes)) > 1:
            return HoldAnswer(
                None, inside, "undecided",
                f"{where} lies between DER points that disagree ({pts}): undecided", **common,
            )  # fmt: skip
        v = votes[0]
        state = "holds" if v else "slips"
        rules = []
        if yw == "below":
            rules.append(
                (
                    "settled-light-load",
                    True,
                    f"the load is below the lightest tabulated ({ax['t_over_EA'][0]:.3g} "
                    "EA), where the two lightest loads agree (the verdict has settled)",
                )
            )
        if yw == "above":
            rules.append(
                (
                    "heavier-slips",
                    not v,
                    f"the load is above the heaviest tabulated ({ax['t_over_EA'][-1]:.3g} "
                    "EA)"
                    + (
                        ", which slipped: a heavier load slips"
                        if not v
                        else ", which held: that says nothing about a heavier load"
                    ),
                )
            )
        if mw == "above":
            rules.append(
                (
                    "more-friction-holds",
                    v,
                    f"the friction is above the largest tabulated (mu = {ax['mu'][-1]:g})"
                    + (
                        ", which held: more friction holds"
                        if v
                        else ", which slipped: that says nothing about more friction"
                    ),
                )
            )
        if mw == "below":
            rules.append(
                (
                    "less-friction-slips",
                    not v,
                    f"the friction is below the smallest tabulated (mu = {ax['mu'][0]:g})"
                    + (
                        ", which slipped: less friction slips"
                        if not v
                        else ", which held: that says nothing about less friction"
                    ),
                )
            )
        bad = [text for _, ok, text in rules if not ok]
        if bad:
            return HoldAnswer(None, False, "undecided",
                              f"{where}: {'; '.join(bad)}: undecided (DER points: {pts})",
                              **common)  # fmt: skip
        rule = rules[0][0] if rules else "grid"
        why = "; ".join(text for _, _, text in rules)
        msg = (f"{state} in the DER {self.knot} table at {where} (" + (why + "; " if why else "")
               + f"DER points: {pts})")  # fmt: skip
        return HoldAnswer(v, inside, rule, msg, **common)

    def _capacity(self, xi, mi, y, lim):
        """(largest tabulated load held in every corner column with every tabulated load
        from the query's up to it held; smallest load >= the query's that slipped in any)."""
        ys = self.axes["t_over_EA"]
        cap = math.inf
        first = math.inf
        for i in xi:
            for k in mi:
                col_cap = float("nan")
                for y_t in ys:
                    if y_t < y * (1 - 1e-9) and y_t != ys[-1]:
                        # loads below the query do not bound it (except the heaviest)
                        continue
                    h = self.point(self.axes["d_over_2R"][i], y_t, self.axes["mu"][k]).holds(lim)
                    if h:
                        col_cap = float(y_t)
                    else:
                        first = min(first, float(y_t))
                        break
                cap = min(cap, col_cap) if math.isfinite(col_cap) else float("nan")
                if math.isnan(cap):
                    break
        return (cap if math.isfinite(cap) else float("nan")), first

    # ----------------------------------------------------------------- file format
    def to_dict(self) -> dict:
        def num(v):
            return None if not math.isfinite(v) else float(f"{v:.4g}")

        return {
            "format": HOLD_TABLE_FORMAT,
            "version": 1,
            "knot": self.knot,
            "law": self.law,
            "criterion": dict(self.criterion),
            "axes": {a: [float(v) for v in self.axes[a]] for a in _AXES},
            "columns": list(HOLD_COLUMNS),
            "points": [
                [
                    p.d_over_2R,
                    p.t_over_EA,
                    p.mu,
                    num(p.creep_speed),
                    int(p.ran_to_end),
                    int(p.topology),
                    int(p.solved),
                ]
                for p in self.points
            ],  # fmt: skip
            "meta": self.meta,
        }

    @classmethod
    def from_dict(cls, data: dict, *, name: str = "hold table") -> HoldTable:
        try:
            if data.get("format") != HOLD_TABLE_FORMAT:
                raise ValueError(f"format is not {HOLD_TABLE_FORMAT!r}")
            if list(data["columns"]) != list(HOLD_COLUMNS):
                raise ValueError(f"columns must be {list(HOLD_COLUMNS)}")
            pts = []
            for row in data["points"]:
                x, y, m, s, ran, topo, ok = row
                pts.append(
                    HoldPoint(
                        float(x),
                        float(y),
                        float(m),
                        float("nan") if s is None else float(s),
                        bool(ran),
                        bool(topo),
                        bool(ok),
                    )
                )
            meta = dict(data.get("meta", {}))
            meta_bending_scale(meta, "its meta")  # an InputError is a ValueError: wrapped below
            return cls(str(data["knot"]), pts, meta, str(data["law"]),
                       dict(data["criterion"]))  # fmt: skip
        except (KeyError, TypeError, ValueError, AttributeError) as exc:
            raise InputError(f"{name}: not a knotmech hold table: {exc}") from None

    @property
    def bending_scale(self) -> float:
        """The rods' bending scale kappa the table was built with (meta, 1 when absent)."""
        return meta_bending_scale(self.meta)

    def write(self, path) -> None:
        """Compact JSON (one point per line)."""
        d = self.to_dict()
        pts = d.pop("points")
        text = json.dumps(d, separators=(",", ":"), allow_nan=False)
        rows = ",\n".join(json.dumps(r, separators=(",", ":")) for r in pts)
        Path(path).write_text(text[:-1] + ',"points":[\n' + rows + "]}\n")

    @classmethod
    def from_results(cls, knot: str, results, *, meta=None) -> HoldTable:
        """A table from :func:`simulate_point`-like result dicts (anchor law)."""
        pts = []
        for r in results:
            pts.append(HoldPoint(
                float(r["d_over_2R"]), float(r["t_over_EA"]), float(r["mu"]),
                float(r["creep_speed"]), bool(r["ran_to_end"]), bool(r["topology_preserved"]),
                r["holds"] is not None,
            ))  # fmt: skip
        pts.sort(key=lambda p: (p.mu, p.d_over_2R, p.t_over_EA))
        return cls(knot, pts, dict(meta or {}))


def meta_bending_scale(meta, name: str = "the DER table") -> float:
    """A table's bending scale kappa from its meta (``bending_scale``, 1 when absent).

    Raises
    ------
    InputError
        It is not a number in (0, 1] (one line naming ``name``).
    """
    k = (meta or {}).get("bending_scale", 1.0)
    if isinstance(k, bool) or not isinstance(k, (int, float)) or not 0 < k <= 1:
        raise InputError(f"{name}: meta bending_scale must be a number in (0, 1], got {k!r}")
    return float(k)


def _num(v):
    v = float(v)
    return float(f"{v:.4g}") if math.isfinite(v) else None


def read_hold_table(path) -> HoldTable:
    """A hold table from a file (one-line :class:`InputError` when it does not read)."""
    try:
        text = Path(path).read_text()
    except OSError as exc:
        raise InputError(f"cannot read hold table {str(path)!r}: {exc.strerror}") from None
    try:
        data = json.loads(text)
    except json.JSONDecodeError as exc:
        raise InputError(f"hold table {str(path)!r} is not JSON: {exc}") from None
    return HoldTable.from_dict(data, name=f"hold table {str(path)!r}")


def load_hold_tables() -> dict:
    """The shipped solid-rod (kappa = 1) hold tables: {knot: table}
    (:func:`load_hold_table_sets` has those of every bending scale)."""
    out = {}
    for knot, by_kappa in load_hold_table_sets().items():
        out[knot] = by_kappa.get(1.0, by_kappa[max(by_kappa)])
    return out


def load_hold_table_sets() -> dict:
    """Every shipped hold table (``knotmech/data/hold_phase_table_*.json``):
    {knot: {bending scale kappa: table}}."""
    try:
        folder = resources.files("knotmech").joinpath("data")
        names = sorted(
            f.name for f in folder.iterdir() if Path(f.name).match(HOLD_TABLE_GLOB) and f.is_file()
        )
    except (FileNotFoundError, OSError) as exc:
        raise InputError(f"the shipped hold tables are missing: {exc}") from None
    out = {}
    for n in names:
        try:
            data = json.loads(folder.joinpath(n).read_text())
        except json.JSONDecodeError as exc:
            raise InputError(f"hold table {n} is not JSON: {exc}") from None
        t = HoldTable.from_dict(data, name=f"hold table {n}")
        out.setdefault(t.knot, {})[t.bending_scale] = t
    return out


# --------------------------------------------------------------------------- building
#: rope-size ratios d/D of the shipped hold tables (d/2R = (d/D)/(1 + d/D), rounded)
HOLD_GRID_D_OVER_D = (0.02, 0.05, 4 / 30, 0.3)
#: the shipped hold tables' grid: d/2R (d/D = 0.02, 0.05, 0.133 (the paper's), 0.3),
#: T_high/EA (decades from 1e-4, and 0.3, the paper's upper bound), mu = mu_rr
HOLD_GRID = {
    "d_over_2R": (0.01961, 0.04762, 0.1176, 0.2308),
    "t_over_EA": (1e-4, 1e-3, 1e-2, 0.1, 0.3),
    "mu": (0.1, 0.2, 0.3, 0.5, 0.8),
}


def hold_table_resource(knot: str, bending_scale: float = 1.0) -> str:
    """File name in ``knotmech/data`` of the shipped hold table of ``knot`` built with the
    bending scale ``bending_scale`` (``hold_phase_table_<knot>.json`` for the solid rod,
    kappa = 1; ``hold_phase_table_<knot>_kappa<kappa>.json`` otherwise)."""
    k = float(bending_scale)
    return f"hold_phase_table_{knot}" + ("" if k == 1.0 else f"_kappa{k:g}") + ".json"


def hold_table_params(grid=None, knot: str = "clove-hitch", bending_scale: float = 1.0) -> list:
    """The :func:`knotmech.sweep.sweep` parameter sets of a hold-table grid (mu outermost).

    ``knot`` enters the parameters only for knots other than the clove hitch, and
    ``bending_scale`` only when it is not 1 (so the solid-rod tables' cached points keep
    their keys).
    """
    g = HOLD_GRID if grid is None else grid
    extra = {} if knot == "clove-hitch" else {"knot": knot}
    if float(bending_scale) != 1.0:
        extra["bending_scale"] = float(bending_scale)
    return [
        {"d_over_2R": float(x), "t_over_EA": float(y), "mu": float(m), "friction": "anchor",
         **extra}
        for m in g["mu"]
        for x in g["d_over_2R"]
        for y in g["t_over_EA"]
    ]  # fmt: skip


def build_hold_table(
    knot: str = "clove-hitch",
    grid=None,
    *,
    processes: int | None = 2,
    scheduler=None,
    cache_dir=None,
    progress: bool = False,
    meta=None,
    bending_scale: float = 1.0,
) -> HoldTable:
    """Run the DER points of a hold table through :func:`knotmech.sweep.sweep` and tabulate.

    Every point is one :func:`simulate_point` of ``knot``'s scene (anchor law, :data:`PROTOCOL`,
    creep-speed criterion); with ``cache_dir`` each result is stored as it arrives, so an
    interrupted build recomputes only what is missing. The table's meta records the grid,
    protocol, rod, criterion, the CPU time per point and in total. ``bending_scale`` kappa
    (in (0, 1]) is the rods' bending scale (B = kappa E pi d^4/64) of every run;
    it is kept in the meta as ``bending_scale``, which ``knotmech.hold`` reads to decide
    whether the table may answer for a rope.

    Raises
    ------
    InputError
        An unknown knot; a point whose run raised (the message names it).
    """
    from knotmech.errors import check_bending_scale
    from knotmech.sweep import sweep

    hold_scene(knot)  # InputError for an unknown knot or a missing scene
    kappa = check_bending_scale(bending_scale)
    params = hold_table_params(grid, knot, kappa)
    res = sweep(
        simulate_point,
        params,
        processes=processes,
        scheduler=scheduler,
        cache_dir=cache_dir,
        progress=progress,
        on_error="return",
    )
    if res.failures:
        f = res.failures[0]
        raise InputError(f"hold table of {knot}: {len(res.failures)} runs raised; first: {f}")
    results = [_on_protocol_clock(_signed(r)) for r in res]
    # second pass: points within a decade of the limit, with a hold twice as long
    again = [
        i
        for i, r in enumerate(results)
        if r["ran_to_end"] and r["topology_preserved"] and needs_recheck(r["creep_speed"])
    ]
    if again:
        hold2 = RECHECK_HOLD_FACTOR * PROTOCOL["hold_time"]
        res2 = sweep(
            simulate_point,
            [{**params[i], "hold_time": hold2} for i in again],
            processes=processes, scheduler=scheduler, cache_dir=cache_dir, progress=progress,
            on_error="return",
        )  # fmt: skip
        if res2.failures:
            raise InputError(f"hold table of {knot}: a recheck run raised: {res2.failures[0]}")
        for i, r2 in zip(again, res2, strict=True):
            r2 = dict(_on_protocol_clock(_signed(r2)))
            r2["first_creep_speed"] = results[i]["creep_speed"]
            r2["cpu_s"] = float(r2.get("cpu_s", 0.0)) + float(results[i].get("cpu_s", 0.0))
            results[i] = r2
    return hold_table_from_results(knot, results, meta={"bending_scale": kappa, **(meta or {})})


def _signed(r: dict) -> dict:
    """A point result with a signed creep speed (results of ``__sweep_version__`` 3 from
    before ``creep_speed_signed`` stored |speed|: the sign is that of ``creep``, end 0's
    creep over the last half of the hold, which ends with the same window)."""
    if r.get("creep_speed_signed") or not math.isfinite(r.get("creep_speed", math.nan)):
        return r
    c = float(r.get("creep", math.nan))
    s = abs(float(r["creep_speed"]))
    return {**r, "creep_speed": math.copysign(s, c) if math.isfinite(c) and c != 0 else s,
            "creep_speed_signed": True}  # fmt: skip


def _on_protocol_clock(r: dict) -> dict:
    """A point result with its creep speed [d per protocol s] and window [protocol s] on the
    protocol's clock (``time_scale`` s: real seconds per protocol second; a result without
    it ran on the reference rod, s = 1). A table stores these, so it is the same for every
    material."""
    s = float(r.get("time_scale", 1.0))
    if s == 1.0:
        return r
    out = {**r, "creep_speed": float(r["creep_speed"]) * s}
    if "creep_window_s" in r:
        out["creep_window_s"] = float(r["creep_window_s"]) / s
    return out


def hold_table_from_results(knot: str, results, *, meta=None) -> HoldTable:
    """A hold table (with its cost and grid in the meta) from point result dicts."""
    results = list(results)
    cpu = [float(r.get("cpu_s", float("nan"))) for r in results]
    g = {a: sorted({float(r[a]) for r in results}) for a in _AXES}
    rechecked = [[r["d_over_2R"], r["t_over_EA"], r["mu"], _num(r["first_creep_speed"]),
                  _num(r["creep_speed"])] for r in results if "first_creep_speed" in r]  # fmt: skip
    m = {
        "rechecked": {
            "rule": f"creep speed from limit/{RECHECK_BAND[0]:g} to limit x "
            f"{RECHECK_BAND[1]:g} after the "
            f"{PROTOCOL['hold_time']:g} s hold: run again with a "
            f"{RECHECK_HOLD_FACTOR * PROTOCOL['hold_time']:g} s hold, which decides",
            "points": rechecked,
            "columns": ["d_over_2R", "t_over_EA", "mu", "first_d_per_s", "final_d_per_s"],
        },
        "what": f"DER {knot} with a free end: creep speed of the loaded end at "
        "(d/2R, T_high/EA, mu = mu_rr)",
        "law": "anchor (rod-rod AnchorFriction, rod-post anchor friction)",
        "generator": "knotmech.scenes.phase_table.build_hold_table (simulate_point per point)",
        "grid": g,
        "rod": {"d_m": ROD_DIAMETER, "E_Pa": YOUNGS_MODULUS, "rho": DENSITY},
        "protocol": dict(PROTOCOL),
        "protocol_clock": PROTOCOL_CLOCK,
        "protocol_clock_note": "times in protocol seconds: real seconds / protocol_time_scale "
        "(d / (sqrt(kappa) sqrt(E/rho)) over the VPS32 rod's); creep speeds in d per "
        "protocol second",
        "n_nodes": {
            f"{float(r['d_over_2R']):g}": int(r["n_nodes"]) for r in results if "n_nodes" in r
        },  # fmt: skip
        "runs": len(results),
        "cpu_s_total": round(float(np.nansum(cpu)), 1),
        "cpu_s_per_point": [round(float(np.nanmin(cpu)), 1), round(float(np.nanmax(cpu)), 1)],
    }
    m.update(meta or {})
    table = HoldTable.from_results(knot, results, meta=m)
    windows = sorted({float(r["creep_window_s"]) for r in results if "creep_window_s" in r})
    if knot != "clove-hitch" and windows:  # the hitch scenes measure over their own window
        table.criterion = {**table.criterion, "window_s": windows[0],
                           "window_note": "the scene's window: the last half of the hold, "
                           "1 s for the longer re-runs"}  # fmt: skip
    return table

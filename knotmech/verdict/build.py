r"""Building the DER hold tables: one point (:func:`simulate_point`, a module-level function
for :func:`knotmech.sweep.sweep`), its geometry (:func:`point_geometry`), the knots with a
DER scene (:data:`HOLD_SCENE_NAMES`, from the registry :mod:`knotmech.knots`), and a whole
grid through :func:`knotmech.sweep.sweep` (:func:`build_hold_table`, with a second, longer
run of the points whose creep lies near the limit).
"""

from __future__ import annotations

import math

import numpy as np

from knotmech.errors import InputError, check_nonnegative, check_positive
from knotmech.verdict.criterion import (
    CREEP_CRITERION,
    CREEP_LIMIT,
    CREEP_WINDOW,
    DENSITY,
    IMC_PROTOCOL,
    MU,
    PROTOCOL,
    PROTOCOL_CLOCK,
    RECHECK_BAND,
    RECHECK_HOLD_FACTOR,
    ROD_DIAMETER,
    YOUNGS_MODULUS,
    creep_speed,
    creep_verdict,
    needs_recheck,
    protocol_time_scale,
    solver_gave_verdict,
)
from knotmech.verdict.scope import BOTH_LEGS_KNOTS
from knotmech.verdict.tables import _AXES, ANCHOR_LAW, HoldTable, _num

__all__ = [
    "HOLD_GRID",
    "HOLD_SCENE_NAMES",
    "MAX_NODES",
    "build_hold_table",
    "has_hold_scene",
    "hold_scene",
    "hold_table_from_results",
    "hold_table_params",
    "point_geometry",
    "simulate_point",
]

TAIL = 0.064  #: [m] straight tail at each end (the paper's L = 374 mm at D = 30 mm)
EDGE = 0.374 / 119  #: [m] rest edge length (120 nodes on 374 mm)
MAX_NODES = 200  #: node cap of :func:`point_geometry` (large posts get longer edges)


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
    d = check_positive("rod_diameter", rod_diameter, scalar=True)
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


def _budget_options(max_cpu_s) -> dict:
    """The scene's ``options`` with a CPU budget: the hitch scenes' own default solver
    options (:data:`knotmech.scenes._hitch.DEFAULT_OPTIONS`) plus ``max_cpu_s``; {}
    without a budget."""
    if max_cpu_s is None:
        return {}
    from dataclasses import replace

    from knotmech.scenes._hitch import DEFAULT_OPTIONS

    cpu = check_positive("max_cpu_s", max_cpu_s, scalar=True)
    return {"options": replace(DEFAULT_OPTIONS, max_cpu_s=float(cpu))}


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
    t_low_fraction: float = 0.0,
    max_cpu_s: float | None = None,
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

    ``t_low_fraction`` > 0 loads the other end too, with :math:`T_\mathrm{low}` = that
    fraction of :math:`T_\mathrm{high}` (the scene's ``"asymmetric"`` loading: the cow hitch
    loaded on both legs, issue 25); the verdict is the same creep criterion on end 0.

    ``max_cpu_s`` [s]: the run's CPU budget (:class:`knotmech.rod.SolverOptions`; None, the
    default and the tables': none). A run that spends it stops with ``holds = None`` and
    the solver's message. A recheck gets its own budget, :data:`RECHECK_HOLD_FACTOR` times
    ``max_cpu_s`` (its hold is that many times longer), so a first run that ended inside
    its budget is not undone by a recheck cut short; a point then costs up to
    1 + :data:`RECHECK_HOLD_FACTOR` budgets.

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
        early), ran_to_end, stopped_in ("" when it ran to the end, else the phase it stopped
        in: "settle", "load" or "hold"), stopped_at_protocol_s, status, message,
        topology_preserved, wall_s, cpu_s``. A run whose solver failed has ``holds = None``.
        With ``keep_result``, also ``result``: the scene's
        :class:`~knotmech.scenes.clove_hitch.CloveHitchResult`.
    """
    import time

    d = check_positive("rod_diameter", rod_diameter, scalar=True)
    E = check_positive("youngs_modulus", youngs_modulus, scalar=True)
    tea = check_positive("t_over_EA", t_over_EA, scalar=True)
    lim = check_positive("creep_limit", creep_limit, scalar=True)
    from knotmech.errors import check_bending_scale

    kappa = check_bending_scale(bending_scale)
    if friction not in ("anchor", "imc"):
        raise InputError(f"friction must be 'anchor' or 'imc', got {friction!r}")
    ts = _time_scale(time_scale, d=d, E=E, density=density, kappa=kappa)
    scene = hold_scene(knot)
    geo = point_geometry(d_over_2R, rod_diameter=d)
    nn, length = _nodes_and_length(knot, geo, n_nodes)
    proto, run_proto, window = _point_protocol(friction, hold_time, ts, knot)
    t_high = tea * E * np.pi * d * d / 4
    frac = float(check_nonnegative("t_low_fraction", t_low_fraction, scalar=True))
    legs = {"loading": "asymmetric", "t_low": frac * t_high} if frac > 0 else {"loading": "free"}
    c0 = time.process_time()
    r = scene(
        **legs,
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
        **_budget_options(max_cpu_s),
        **run_proto,
    )
    cpu = time.process_time() - c0
    t_end = sum(run_proto[k] for k in ("settle_time", "load_time", "hold_time"))
    times = np.asarray(r.times, dtype=float)
    ran = bool(times.size and times[-1] >= t_end - 1e-9 * ts)
    stopped_in, stopped_at = _stop(times, run_proto, ts, ran=ran)
    speed, window = _point_speed(r, knot, ran=ran, d=d, window=window)
    holds, reason, criterion = _point_judgement(r, friction, speed * ts, ran=ran, limit=lim)
    out = {
        "d_over_2R": float(d_over_2R),
        "t_over_EA": tea,
        "t_high": float(t_high),
        "t_low": frac * float(t_high),
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
        "stopped_in": stopped_in,
        "stopped_at_protocol_s": stopped_at,
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
            knot=knot, progress=progress, keep_result=keep_result, t_low_fraction=frac,
            max_cpu_s=None if max_cpu_s is None else RECHECK_HOLD_FACTOR * max_cpu_s,
        )  # fmt: skip
        again["first_creep_speed"] = speed
        again["first_hold_time"] = proto["hold_time"]
        again["cpu_s"] += out["cpu_s"]
        return again
    return out


def _stop(times, run_proto: dict, ts: float, *, ran: bool):
    """(the phase a run that stopped early stopped in: ``"settle"`` (before any load),
    ``"load"`` (the ramp) or ``"hold"``; ``""`` when it ran to the end, and its last time
    [protocol s])."""
    t = float(times[-1]) if times.size else 0.0
    if ran:
        return "", t / ts
    if t < run_proto["settle_time"] - 1e-9 * ts:
        return "settle", t / ts
    if t < run_proto["settle_time"] + run_proto["load_time"] - 1e-9 * ts:
        return "load", t / ts
    return "hold", t / ts


def _time_scale(time_scale, *, d, E, density, kappa) -> float:
    """The given ``time_scale`` (> 0), or the rod's :func:`protocol_time_scale`."""
    if time_scale is None:
        return protocol_time_scale(rod_diameter=d, youngs_modulus=E, density=density,
                                   bending_scale=kappa)  # fmt: skip
    return check_positive("time_scale", time_scale, scalar=True)


def _nodes_and_length(knot: str, geo: dict, n_nodes):
    """(node count, rod length [m]) of a point: the clove hitch's from
    :func:`point_geometry`; another knot's curve picks its length and (None) its edges."""
    if knot == "clove-hitch":
        return (geo["n_nodes"] if n_nodes is None else int(n_nodes)), geo["rod_length"]
    return (None if n_nodes is None else int(n_nodes)), None


def _point_protocol(friction: str, hold_time, ts: float, knot: str):
    """(protocol [protocol s], the run's protocol [s of this rod], the creep window [s]):
    :data:`PROTOCOL` (anchor law) or :data:`IMC_PROTOCOL`, its hold replaced by
    ``hold_time``, its times stretched by the time scale ``ts``."""
    proto = dict(PROTOCOL if friction == "anchor" else IMC_PROTOCOL)
    if hold_time is not None:
        h = check_positive("hold_time", hold_time, scalar=True)
        proto["hold_time"] = h
        proto["n_frames"] = int(round((proto["settle_time"] + proto["load_time"] + h) / 0.05)) + 1
    run_proto = {k: (v * ts if k in ("settle_time", "load_time", "hold_time", "dt") else v)
                 for k, v in proto.items()}  # fmt: skip
    window = min(CREEP_WINDOW, proto["hold_time"]) * ts
    if knot != "clove-hitch":  # the hitch scenes' own window: at most half the hold
        run_proto["creep_window"] = min(CREEP_WINDOW, 0.5 * proto["hold_time"]) * ts
    return proto, run_proto, window


def _point_speed(r, knot: str, *, ran: bool, d: float, window: float):
    """(creep speed of end 0 [d/s], its window [s]); NaN when the run stopped early."""
    if not ran:
        return float("nan"), window
    if knot == "clove-hitch":
        return creep_speed(r.times, r.end_displacement, rod_diameter=d, window=window), window
    # the hitch scenes' own creep speed: the least-squares slope over the window (their hold
    # runs with a tenth of the drag and rings); the window: the last half of a 1.5 s hold
    return float(r.creep_speed_d), float(r.creep_window)


def _point_judgement(r, friction: str, speed_protocol: float, *, ran: bool, limit: float):
    """(holds, reason, criterion name) of one run: the creep-speed criterion (anchor law;
    ``speed_protocol`` [d per protocol s]) or the smooth-law tables' distance rule."""
    slip_or_ok = r.status == "success" or r.verdict == "slip"  # "": it never got its load
    if friction == "anchor":
        solver_ok = slip_or_ok and solver_gave_verdict(r.status, r.topology_preserved)
        holds, reason = creep_verdict(
            speed_protocol, ran_to_end=ran, topology_preserved=bool(r.topology_preserved),
            solver_ok=solver_ok, limit=limit,
        )  # fmt: skip
        return holds, reason, CREEP_CRITERION
    holds = (r.verdict == "hold") if slip_or_ok else None  # the imc tables' rule, kept
    reason = "end 0 moved less than d over the last half of the hold" if holds else (
        "end 0 moved d or more over the last half of the hold (or ran off)")  # fmt: skip
    return holds, reason, "distance"


#: 4: the protocol runs on the rod's flexural clock (:func:`protocol_time_scale`; the same
#: as 3 for the reference rod at kappa 1, different for every other rod)
simulate_point.__sweep_version__ = "4"


#: rope-size ratios d/D of the shipped hold tables (d/2R = (d/D)/(1 + d/D), rounded)
HOLD_GRID_D_OVER_D = (0.02, 0.05, 4 / 30, 0.3)
#: the shipped hold tables' grid: d/2R (d/D = 0.02, 0.05, 0.133 (the paper's), 0.3),
#: T_high/EA (decades from 1e-4, and 0.3, the paper's upper bound), mu = mu_rr
HOLD_GRID = {
    "d_over_2R": (0.01961, 0.04762, 0.1176, 0.2308),
    "t_over_EA": (1e-4, 1e-3, 1e-2, 0.1, 0.3),
    "mu": (0.1, 0.2, 0.3, 0.5, 0.8),
}


def hold_table_params(
    grid=None, knot: str = "clove-hitch", bending_scale: float = 1.0, t_low_fraction: float = 0.0
) -> list:
    """The :func:`knotmech.sweep.sweep` parameter sets of a hold-table grid (mu outermost).

    ``knot`` enters the parameters only for knots other than the clove hitch,
    ``bending_scale`` only when it is not 1 and ``t_low_fraction`` (T_low / T_high on the
    other end: the cow hitch loaded on both legs) only when it is not 0, so the tables'
    cached points keep their keys.
    """
    g = HOLD_GRID if grid is None else grid
    extra = {} if knot == "clove-hitch" else {"knot": knot}
    if float(bending_scale) != 1.0:
        extra["bending_scale"] = float(bending_scale)
    if float(t_low_fraction) != 0.0:
        extra["t_low_fraction"] = float(t_low_fraction)
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
    t_low_fraction: float = 0.0,
) -> HoldTable:
    """Run the DER points of a hold table through :func:`knotmech.sweep.sweep` and tabulate.

    Every point is one :func:`simulate_point` of ``knot``'s scene (anchor law, :data:`PROTOCOL`,
    creep-speed criterion); with ``cache_dir`` each result is stored as it arrives, so an
    interrupted build recomputes only what is missing. The table's meta records the grid,
    protocol, rod, criterion, the CPU time per point and in total. ``bending_scale`` kappa
    (in (0, 1]) is the rods' bending scale (B = kappa E pi d^4/64) of every run;
    it is kept in the meta as ``bending_scale``, which ``knotmech.hold`` reads to decide
    whether the table may answer for a rope. ``t_low_fraction`` (in [0, 1]; 0, a free
    end, by default) loads the other end with that fraction of T_high in every run (the
    cow hitch loaded on both legs, :func:`simulate_point`); kept in the meta as
    ``t_low_fraction`` when it is not 0.

    Raises
    ------
    InputError
        An unknown knot; a ``t_low_fraction`` outside [0, 1], or above 0 for a knot other
        than the cow hitch; a point whose run raised (the message names it).
    """
    from knotmech.errors import check_bending_scale
    from knotmech.sweep import sweep

    hold_scene(knot)  # InputError for an unknown knot or a missing scene
    kappa = check_bending_scale(bending_scale)
    frac = _check_t_low_fraction(knot, t_low_fraction)
    params = hold_table_params(grid, knot, kappa, frac)
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
    legs = {"t_low_fraction": frac} if frac > 0 else {}
    meta = {"bending_scale": kappa, **legs, **(meta or {})}
    return hold_table_from_results(knot, results, meta=meta)


def _check_t_low_fraction(knot: str, t_low_fraction) -> float:
    """T_low / T_high of a hold table's runs: in [0, 1]; above 0 only for a knot whose other
    end is a second standing part (:data:`~knotmech.verdict.scope.BOTH_LEGS_KNOTS`)."""
    frac = float(check_nonnegative("t_low_fraction", t_low_fraction, scalar=True))
    if frac > 1.0:
        raise InputError(f"t_low_fraction must be at most 1 (T_low <= T_high), got {frac:g}")
    if frac > 0 and knot not in BOTH_LEGS_KNOTS:
        raise InputError(
            f"t_low_fraction > 0 loads the cow hitch's second leg; {knot} has a free end "
            f"(got t_low_fraction = {frac:g})"
        )
    return frac


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
        "law": ANCHOR_LAW,
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

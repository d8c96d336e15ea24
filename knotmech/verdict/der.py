"""The DER answer of the hold verdict for a hitch with a free end: one DER run of the user's
geometry, a table the user names, or the shipped hold table of the knot (nearest the rope's
bending scale), each refused where it does not apply (another bending scale; a table run in
seconds on a rod of another elastic-wave rate). :func:`der_answer` returns the details the
verdict reports, the model answer (None when the DER does not decide), the creep measured
and, after a simulation, the knot's shape.
"""

from __future__ import annotations

import functools
import json
import math
from dataclasses import dataclass, field
from pathlib import Path

from knotmech import knots
from knotmech.errors import InputError
from knotmech.verdict import build as _build
from knotmech.verdict.command import SIMULATE_MAX_CPU_S
from knotmech.verdict.criterion import (
    CREEP_CRITERION,
    CREEP_LIMIT,
    CREEP_WINDOW,
    DENSITY,
    PROTOCOL,
    PROTOCOL_CLOCK,
    ROD_DIAMETER,
    YOUNGS_MODULUS,
    protocol_time_scale,
)
from knotmech.verdict.tables import (
    HOLD_TABLE_FORMAT,
    HoldTable,
    PhaseTableSet,
    load_hold_table_sets,
    load_legs_table_sets,
    load_table,
    load_tables,
    meta_bending_scale,
    read_hold_table,
    read_shipped_hold_tables,
)

__all__ = [
    "BENDING_SCALE_FACTOR",
    "ROD_RATE_FACTOR",
    "der_answer",
    "load_user_table",
    "shipped_hold_table",
    "shipped_hold_tables",
    "shipped_legs_tables",
    "simulate_holds",
]

#: the DER table answers only when the table's bending scale kappa is within this factor of
#: the rope's (a rope's kappa is of order 0.01; the shipped tables are solid rods, kappa = 1)
BENDING_SCALE_FACTOR = 3.0


#: a DER table built before the protocol ran on the rod's own clock (its meta has no
#: ``protocol_clock``) answers only for a rope whose protocol time scale
#: (:func:`knotmech.scenes.phase_table.protocol_time_scale`) is within this factor of its
#: rod's: such a table ran in seconds, and a run in seconds is not in T_high/EA, d/2R, mu and
#: kappa alone (at d/2R 0.118, 0.1 EA, mu 0.3, kappa 1 a 6 mm nylon rod ran off in seconds
#: where the silicone table held). The shipped tables ran on the reference rod (time scale
#: 1), so they are on the flexural clock and answer for every material.
ROD_RATE_FACTOR = 3.0


def _table_rod(table):
    """(d [m], E [Pa], rho [kg/m^3]) of the rod a DER table was run on (its meta ``rod``;
    the scene's silicone defaults when absent)."""
    meta = getattr(table, "meta", None) or {}
    rod = meta.get("rod") or {}
    try:
        return (float(rod.get("d_m", ROD_DIAMETER)), float(rod.get("E_Pa", YOUNGS_MODULUS)),
                float(rod.get("rho", DENSITY)))  # fmt: skip
    except (TypeError, ValueError):
        raise InputError("a DER table's meta rod must hold numbers d_m, E_Pa, rho") from None


def _table_time_scale(table, kappa) -> tuple[float, bool]:
    """(protocol time scale of the rod the table ran on, whether the table is on the
    flexural clock: meta ``protocol_clock`` == "flexural", or a time scale of 1, the
    reference rod, on which seconds and protocol seconds are the same)."""
    td, tE, trho = _table_rod(table)
    ts = protocol_time_scale(rod_diameter=td, youngs_modulus=tE, density=trho,
                                bending_scale=kappa)  # fmt: skip
    meta = getattr(table, "meta", None) or {}
    return ts, meta.get("protocol_clock") == PROTOCOL_CLOCK or abs(ts - 1.0) < 1e-9


def _table_kappa(table, name="the DER table") -> float:
    """The bending scale a DER table was built with (meta ``bending_scale``, 1 if absent;
    :func:`knotmech.scenes.phase_table.meta_bending_scale`: a one-line InputError naming
    ``name`` when it is not a number in (0, 1])."""
    return meta_bending_scale(getattr(table, "meta", None), name)


def load_user_table(path):
    """A DER table the user names: a 3-axis hold table, or a smooth-law phase table (as a
    one-table set); a one-line InputError when it does not read or is out of range."""
    try:
        head = json.loads(Path(path).read_text())
    except (OSError, ValueError):
        head = None  # load_table says what is wrong
    if isinstance(head, dict) and head.get("format") == HOLD_TABLE_FORMAT:
        return read_hold_table(path)  # a 3-axis hold table (checked when read)
    t = load_table(path)  # InputError when missing or not a table
    pts = t.points
    if not pts:
        raise InputError(f"phase table {str(path)!r} has no points")
    for p in pts:
        if not (0 < p.d_over_2R < 0.5 and math.isfinite(p.t_over_EA) and p.t_over_EA > 0):
            raise InputError(
                f"phase table {str(path)!r}: point ({p.d_over_2R:g}, {p.t_over_EA:g}) is "
                "outside 0 < d/2R < 0.5, T_high/EA > 0"
            )
    if not (math.isfinite(t.mu) and t.mu >= 0 and math.isfinite(t.mu_rr) and t.mu_rr >= 0):
        raise InputError(f"phase table {str(path)!r}: mu and mu_rr must be finite, >= 0")
    return PhaseTableSet([t])


def _shape(result, *, d, D):
    """The last frame's centreline and tension of a DER result, or None."""
    try:
        pos = result.positions[-1]
        tension = result.tension
    except (AttributeError, IndexError, TypeError):
        return None
    return {"positions": pos, "tension": tension, "rod_diameter": d, "post_diameter": D}


@functools.lru_cache(maxsize=1)
def _shipped_tables():
    """The shipped smooth-law (imc) DER tables, read once per process (package data)."""
    return load_tables()


def shipped_hold_tables():
    """The shipped anchor-law solid-rod hold tables {knot: HoldTable} (those nearest kappa = 1
    of :func:`_shipped_hold_table_sets`, which reads the files once per process)."""
    return {knot: shipped_hold_table(knot, 1.0) for knot in _shipped_hold_table_sets()}


@functools.lru_cache(maxsize=1)
def _shipped_tables() -> tuple:
    """Every shipped hold table, its file read once per process."""
    return tuple(read_shipped_hold_tables())


@functools.lru_cache(maxsize=1)
def _shipped_hold_table_sets():
    """The shipped anchor-law hold tables with a free end {knot: {kappa: HoldTable}}."""
    return load_hold_table_sets(_shipped_tables())


def shipped_hold_table(knot, kappa=1.0):
    """The shipped hold table of ``knot`` whose bending scale is nearest ``kappa`` (by
    ratio), or None when none is shipped."""
    by_kappa = _shipped_hold_table_sets().get(knot)
    if not by_kappa:
        return None
    best = min(by_kappa, key=lambda k: abs(math.log(k / float(kappa))))
    return by_kappa[best]


@functools.lru_cache(maxsize=1)
def _shipped_legs_table_sets():
    """The shipped tables of the cow hitch on both legs {knot: {kappa: {f: HoldTable}}}."""
    return load_legs_table_sets(_shipped_tables())


def shipped_legs_tables(knot, kappa=1.0) -> dict:
    """The shipped tables that answer ``knot`` loaded on both legs, {T_low/T_high f: table}:
    the free-end table (f = 0) and those whose runs load the other leg, each of the bending
    scale nearest ``kappa`` (by ratio); empty when none is shipped."""
    out = {}
    free = shipped_hold_table(knot, kappa)
    if free is not None:
        out[0.0] = free
    by_kappa = _shipped_legs_table_sets().get(knot)
    if by_kappa:
        best = min(by_kappa, key=lambda k: abs(math.log(k / float(kappa))))
        out.update(by_kappa[best])
    return out


def _criterion_text(limit: float, window: float | None = None, time_scale: float = 1.0) -> str:
    """The criterion in words; ``limit`` [d per protocol s] and ``window`` [protocol s], with
    ``time_scale`` the rope's real seconds per protocol second."""
    w = CREEP_WINDOW if window is None else float(window)
    s = float(time_scale)
    clock = "" if s == 1.0 else (
        f" (the protocol's {limit:g} d/s over {w:g} s, on the rod's flexural clock "
        f"d/(sqrt(kappa) sqrt(E/rho)): 1 protocol s = {s:.3g} s for this rope)"
    )  # fmt: skip
    return (
        f"{CREEP_CRITERION} criterion: holds when the loose end creeps slower than "
        f"{limit / s:.3g} d/s over the last {w * s:.3g} s of the hold once the load is "
        f"on{clock}, topology kept"
    )


def _creep_dict(source, speed, d, *, limit, ran_to_end=True, window=None, time_scale=1.0):
    """The measured creep as the verdict reports it, in real seconds for this rope.

    ``speed`` [d per protocol s], ``limit`` [d per protocol s] and ``window`` [protocol s,
    default the clove hitch's :data:`~knotmech.scenes.phase_table.CREEP_WINDOW`] are on the
    protocol's clock; ``time_scale`` is the rope's real seconds per protocol second
    (:func:`knotmech.scenes.phase_table.protocol_time_scale`). The dict has the speed in
    d/s and m/s, the limit in d/s and the window in s (real), and the protocol's values."""
    ok = ran_to_end and speed is not None and math.isfinite(speed)
    w = CREEP_WINDOW if window is None else float(window)
    s = float(time_scale)
    return {
        "source": source,
        "criterion": CREEP_CRITERION,
        "limit_d_per_s": limit / s,
        "window_s": w * s,
        "speed_d_per_s": float(speed) / s if ok else None,
        "speed_m_per_s": float(speed) / s * d if ok else None,
        "creep_m": float(speed) * d * w if ok else None,
        "ran_off": not ran_to_end,
        "time_scale": s,
        "limit_d_per_protocol_s": limit,
        "speed_d_per_protocol_s": float(speed) if ok else None,
    }


def _table_validity_imc(tables, a):
    used = [tables.table(m) for m in a.mu_tables]
    xs, ys = used[0].d_over_2R, used[0].t_over_EA
    return (
        f"table grid d/2R {xs[0]:.3g}-{xs[-1]:.3g}, T_high/EA {ys[0]:.3g}-{ys[-1]:.3g}, "
        f"mu = mu_rr = {' and '.join(f'{t.mu:g}' for t in used)}"
        + (" (bracketing the user's friction)" if len(used) > 1 else "")
        + "; boundary resolved to one grid step"
    )


@dataclass
class _Query:
    """One DER question: the geometry [m], friction, load [N], the rope (E [Pa], kappa,
    density [kg/m^3] or None: the reference rod's) and the criterion (limit [d per protocol
    s]); ``x`` = d/2R, ``y`` = T_high/EA, ``ts`` the rope's seconds per protocol second, and
    ``out`` the details the verdict reports (filled as the sources answer)."""

    knot: str
    d: float
    D: float
    mu: float
    mu_rr: float
    load: float
    E: float
    kappa: float
    lim: float
    command: str
    density: float | None
    x: float = math.nan
    y: float = math.nan
    EA: float = math.nan
    ts: float = 1.0
    out: dict = field(default_factory=dict)
    #: [N] T_low on the other end (the cow hitch loaded on both legs; 0: a free end)
    free: float = 0.0
    #: [s] the CPU budget of a simulation (:data:`SIMULATE_MAX_CPU_S`)
    max_cpu_s: float = SIMULATE_MAX_CPU_S


@dataclass
class _Found:
    """What a DER source found: ``validity`` (None: it does not decide), the capacity [N],
    the rod-rod law of its runs, the creep measured and the simulated shape."""

    validity: str | None = None
    capacity: float = math.nan
    law: str = "anchor"
    creep: dict | None = None
    shape: dict | None = None


def _start(q: _Query) -> _Query:
    """``q`` with d/2R (R = (D + d)/2), T_high/EA, the time scale and the empty details."""
    q.x = q.d / (q.D + q.d)
    q.EA = q.E * math.pi * q.d * q.d / 4
    q.y = q.load / q.EA
    q.out = {
        "source": "none",
        "holds": None,
        "d_over_2R": q.x,
        "t_over_EA": q.y,
        "youngs_modulus": q.E,
        "inside_table": False,
        "critical_t_over_EA": None,
        "mu_tables": [],
        "message": "",
        "agrees_with_ideal_rope": None,
        "criterion": _criterion_text(q.lim),
        "bending_scale": q.kappa,
    }
    # the rope's real seconds per protocol second (the DER runs on the rod's flexural clock)
    q.ts = protocol_time_scale(
        rod_diameter=q.d,
        youngs_modulus=q.E,
        bending_scale=q.kappa,
        density=DENSITY if q.density is None else float(q.density),
    )
    q.out["time_scale"] = q.ts
    q.out["criterion"] = _criterion_text(q.lim, None, q.ts)
    return q


def der_answer(
    *, knot="clove-hitch", d, D, mu, mu_rr, load, E, simulate, phase_table, progress,
    ideal_holds, creep_limit=None, bending_scale=1.0, command="", density=None,
    free_end_load=0.0, max_cpu_s=SIMULATE_MAX_CPU_S,
):  # fmt: skip
    """The DER answer for a hitch with a free end (or, simulated, the cow hitch on both legs).

    Parameters
    ----------
    knot : str
        Canonical name of a hitch with a DER answer.
    d, D : float
        Rope and post diameters [m].
    mu, mu_rr : float
        Rope-post and rope-rope friction coefficients [-].
    load : float
        T_high [N].
    E : float
        Young's modulus [Pa].
    simulate : bool
        One DER run of this geometry instead of the tables (at ``density`` [kg/m^3]; None:
        the reference rod's), on the rope's clock.
    phase_table : path or None
        A table to read instead of the shipped one.
    progress : bool
        Progress bar of a simulation.
    ideal_holds : bool or None
        The ideal-rope answer (the details say whether the DER agrees).
    creep_limit : float, optional
        Limit of the creep criterion [d per protocol s].
    bending_scale : float
        The rope's kappa: a table answers only within :data:`BENDING_SCALE_FACTOR` of it and,
        unless it ran on the protocol's flexural clock (every shipped table does), its rod's
        protocol time scale within :data:`ROD_RATE_FACTOR` of the rope's.
    command : str
        The command that decides a case the table refuses.
    free_end_load : float
        T_low [N] on the other end: 0 (a free end) or, with ``simulate``, the cow hitch's
        other leg (the scene's asymmetric loading).
    max_cpu_s : float
        [s] The simulation's CPU budget (default :data:`SIMULATE_MAX_CPU_S`): a run that
        spends it stops, and the DER does not decide.

    Returns
    -------
    details : dict
        What the DER said (source, holds, d/2R, T_high/EA, message, ...).
    answer : ModelAnswer or None
        None when the DER does not decide.
    creep : dict or None
        The creep measured, in the rope's real seconds.
    shape : dict or None
        The simulated knot.
    """
    q = _start(_Query(
        knot=knot, d=d, D=D, mu=mu, mu_rr=mu_rr, load=load, E=E, kappa=float(bending_scale),
        lim=CREEP_LIMIT if creep_limit is None else float(creep_limit), command=command,
        density=density, free=float(free_end_load), max_cpu_s=float(max_cpu_s),
    ))  # fmt: skip
    found = _from_simulation(q, progress) if simulate else _from_tables(q, phase_table)
    if found.validity is None:
        return q.out, None, found.creep, found.shape
    return q.out, _model_answer(q, found, simulate, ideal_holds), found.creep, found.shape


def _refusal(q: _Query, table, name: str) -> str:
    """The reason a table built at another kappa, or for a rod of another elastic-wave rate,
    may not answer; "" when it may."""
    tk = _table_kappa(table, name)
    q.out["table_bending_scale"] = tk
    then = f"; decide with: {q.command}" if q.command else ""
    if max(tk / q.kappa, q.kappa / tk) > BENDING_SCALE_FACTOR:
        kind = "solid rods" if tk == 1.0 else "rods"
        q.out["refused"] = "bending_scale"
        return (
            f"not decided by the table: the tables are for {kind} (kappa = {tk:g}); this "
            f"rope's kappa = {q.kappa:g} (more than a factor {BENDING_SCALE_FACTOR:g} apart)" + then
        )
    return _rate_refusal(q, table, tk, then)


def _rate_refusal(q: _Query, table, tk: float, then: str) -> str:
    """A table run in seconds answers only for a rope whose clock ticks like its rod's."""
    td, tE, trho = _table_rod(table)
    ts_table, clocked = _table_time_scale(table, tk)
    q.out["table_rod"] = {
        "d_m": td,
        "E_Pa": tE,
        "rho": trho,
        "time_scale": ts_table,
        "protocol_clock": PROTOCOL_CLOCK if clocked else "seconds",
    }
    if clocked or max(q.ts / ts_table, ts_table / q.ts) <= ROD_RATE_FACTOR:
        return ""
    q.out["refused"] = "rod"
    return (
        f"not decided by the table: it ran in seconds on a rod of E = {tE / 1e6:.3g} "
        f"MPa, d = {td * 1e3:.3g} mm, {trho:g} kg/m^3 (protocol time scale "
        f"{ts_table:.3g}); this rope's is {q.ts:.3g} (more than a factor "
        f"{ROD_RATE_FACTOR:g} apart), so its answer is not in T_high/EA alone" + then
    )


def _from_simulation(q: _Query, progress) -> _Found:
    """One DER run of the user's geometry (:func:`knotmech.verdict.build.simulate_point`)."""
    if not q.x < 0.5:
        raise InputError(
            f"simulate ties the hitch with the rope thinner than the post's radius: "
            f"rod_diameter {q.d * 1e3:.3g} mm on post_diameter {q.D * 1e3:.3g} mm gives "
            f"d/2R = {q.x:.3g} (must be below 0.5)"
        )
    p = _run(q, q.y, progress, keep_result=True)
    shape = _shape(p.get("result"), d=q.d, D=q.D)
    if p["holds"] is None:
        q.out["message"] = f"the DER simulation failed: {p['message']}"
        return _Found(shape=shape)
    if p.get("stopped_in") == "settle":  # no load was on: no verdict (issue 27)
        q.out["failed"] = "settle"
        q.out["message"] = (
            "the DER simulation failed: the run stopped while the knot settled, at "
            f"{p.get('stopped_at_protocol_s', 0.0):.3g} protocol s of "
            f"{PROTOCOL['settle_time']:g}, before any load was on: no verdict "
            f"({p.get('message') or p.get('reason', '')})"
        )
        return _Found(shape=shape)
    ts = float(p.get("time_scale", 1.0))
    speed = float(p.get("creep_speed_protocol", ts * p.get("creep_speed", math.nan)))
    ran = bool(p.get("ran_to_end", math.isfinite(speed)))
    win = float(p.get("creep_window_s", ts * CREEP_WINDOW)) / ts
    creep = _creep_dict("DER simulation of this geometry", speed, q.d, limit=q.lim,
                        ran_to_end=ran, window=win, time_scale=ts)  # fmt: skip
    q.out["time_scale"] = ts
    q.out["criterion"] = _criterion_text(q.lim, win, ts)
    q.out.update(source="simulation", holds=bool(p["holds"]), message=_run_message(q, p, creep))
    run_s = sum(PROTOCOL[k] for k in ("settle_time", "load_time", "hold_time"))
    validity = (
        f"one run of the user's geometry ({run_s:g} protocol s of simulated time"
        + ("" if ts == 1.0 else f", {run_s * ts:.3g} s for this rope")
        + ")"
    )
    return _Found(validity=validity, creep=creep, shape=shape)


def _run(q: _Query, y: float, progress, keep_result=False) -> dict:
    """One DER run of ``q``'s geometry at T_high/EA = ``y``
    (:func:`knotmech.verdict.build.simulate_point`, rechecked near the creep limit)."""
    return _build.simulate_point(
        d_over_2R=q.x, t_over_EA=y, mu=q.mu, mu_rr=q.mu_rr, rod_diameter=q.d,
        youngs_modulus=q.E, bending_scale=q.kappa, creep_limit=q.lim, recheck=True,
        progress=progress, keep_result=keep_result, max_cpu_s=q.max_cpu_s,
        **({} if q.knot == "clove-hitch" else {"knot": q.knot}),
        **({"t_low_fraction": q.free / q.load} if q.free > 0 else {}),
        **({} if q.density is None else {"density": float(q.density)}),
    )  # fmt: skip


def simulate_holds(
    *, knot, d, D, mu, mu_rr, load, E, bending_scale=1.0, creep_limit=None, density=None,
    progress=False, max_cpu_s=SIMULATE_MAX_CPU_S,
):  # fmt: skip
    """Does one DER run of this hitch (free end) hold ``load`` [N]? True, False, or None when
    the run failed or stopped before the load was on (the bisection of ``hold --bisect``).

    Same geometry, law, protocol and criterion as ``hold --simulate``
    (:func:`der_answer` with ``simulate``); ``d``, ``D`` [m], ``E`` [Pa], ``density``
    [kg/m^3] (None: the reference rod's), ``creep_limit`` [d per protocol s],
    ``max_cpu_s`` [s] the run's CPU budget (a run that spends it: None).
    """
    q = _start(_Query(
        knot=knot, d=d, D=D, mu=mu, mu_rr=mu_rr, load=load, E=E, kappa=float(bending_scale),
        lim=CREEP_LIMIT if creep_limit is None else float(creep_limit), command="",
        density=density, max_cpu_s=float(max_cpu_s),
    ))  # fmt: skip
    p = _run(q, q.y, progress)
    if p["holds"] is None or p.get("stopped_in") == "settle":
        return None
    return bool(p["holds"])


def _run_message(q: _Query, p: dict, creep: dict) -> str:
    """The simulation's answer in one line: verdict, creep, reason, wall time."""
    if creep["speed_d_per_s"] is not None:
        crept = (
            f"loaded end creeps {creep['speed_d_per_s']:.3g} d/s over the last "
            f"{creep['window_s']:.3g} s of the hold"
        )
        reason = ""
    else:
        crept = "the loaded end ran off before the hold's measuring window"
        reason = p.get("reason", "")
    return (
        f"DER simulation at d/2R = {q.x:.4g}, T_high/EA = {q.y:.4g}: {p['verdict']} "
        f"({crept}{'; ' + reason if reason else ''}; {p['wall_s']:.0f} s)"
    )


def _from_tables(q: _Query, phase_table) -> _Found:
    """The table the user names (a hold table or a smooth-law phase table), else the shipped
    hold table of the knot nearest the rope's kappa."""
    user = None if phase_table is None else load_user_table(phase_table)
    if user is not None and not isinstance(user, HoldTable):
        if q.free > 0:
            q.out["message"] = (
                f"not decided by the phase table {str(phase_table)!r}: a smooth-law phase "
                "table covers a free end only (T_low = 0)"
            )
            return _Found(law="imc")
        return _from_phase_table(q, user, str(phase_table))
    if q.free > 0:
        return _from_legs_tables(q, user, phase_table)
    if user is not None and user.t_low_fraction > 0:
        q.out.update(source="table", table=str(phase_table), refused="loading", message=(
            f"not decided by the table {str(phase_table)!r}: its runs load the other leg "
            f"(T_low = {user.t_low_fraction:g} T_high); this hitch has a free end"))  # fmt: skip
        return _Found(law=user.law)
    return _from_hold_table(q, user, phase_table)


#: within this, a question's T_low / T_high is a table's
LEGS_TOL = 1e-6


def _from_legs_tables(q: _Query, user, phase_table) -> _Found:
    """The cow hitch loaded on both legs, T_low = ``q.free`` on the other leg, from the tables
    at fixed T_low / T_high = f (the free-end table, f = 0, and those whose runs load the
    other leg). Reading: more load on the lighter leg never turns a hold into a slip (the
    capstan's T_high / T_low <= K, K = exp(4 pi mu) for the ideal rope), so a table that
    holds at f <= r, r the question's T_low / T_high, says it holds, and one that slips at
    f >= r says it slips; both, neither, or only tables on the wrong side: undecided
    (``--load`` is T_high: the API refuses a larger ``free_end_load``)."""
    r, y = q.free / q.load, q.y
    tables = {user.t_low_fraction: user} if user is not None else shipped_legs_tables(
        q.knot, q.kappa)  # fmt: skip
    where = "shipped" if user is None else str(phase_table)
    q.out.update(t_low_fraction=r, table=where, legs_tables=[])
    if not tables:
        q.out["message"] = f"no DER hold table for {q.knot} is shipped"
        return _Found()
    asked = []
    for f in sorted(tables):
        t = tables[f]
        name = f"the {q.knot} table at T_low = {f:g} T_high"
        why = _refusal(q, t, name if user is None else f"phase table {where!r}")
        a = None if why else t.lookup(q.x, y, mu=q.mu, mu_rr=q.mu_rr, creep_limit=q.lim)
        q.out["legs_tables"].append(
            {"t_low_fraction": f, "holds": None if a is None else a.holds,
             "message": why or a.message})  # fmt: skip
        if a is not None:
            asked.append((f, t, a))
    if not asked:  # every table refused: say why (kappa, rod), keep ``refused``
        q.out.update(source="table", message="; ".join(e["message"] for e in q.out["legs_tables"]))
        return _Found()
    q.out.pop("refused", None)  # one refused table does not refuse the others
    return _legs_reading(q, r, asked)


def _legs_reading(q: _Query, r: float, asked: list) -> _Found:
    """The both-legs verdict from the tables' answers ``asked`` [(f, table, answer)]."""
    held = [(f, t, a) for f, t, a in asked if a.holds is True and f <= r + LEGS_TOL]
    slipped = [(f, t, a) for f, t, a in asked if a.holds is False and f >= r - LEGS_TOL]
    said = "; ".join(f"{_legs_name(f)}: {_say_holds(a.holds)}" for f, _, a in asked)
    head = f"both legs loaded, T_low/T_high = {r:.3g} ({said or 'no table applies'})"
    against = [(f1, f2) for f1, _, a1 in asked for f2, _, a2 in asked
               if f1 < f2 and a1.holds is True and a2.holds is False]  # fmt: skip
    if against:
        f1, f2 = against[0]
        q.out.update(source="table", holds=None, message=(
            f"{head}: undecided: the tables contradict more load on the lighter leg never "
            f"turning a hold into a slip ({_legs_name(f1)} holds, {_legs_name(f2)} "
            "slips)"))  # fmt: skip
        return _Found()
    pick = held[-1] if held else (slipped[0] if slipped else None)
    if pick is None:
        q.out.update(source="table", holds=None, message=(
            f"{head}: undecided: no table holds at T_low/T_high <= {r:.3g} or slips at "
            f">= {r:.3g}"))  # fmt: skip
        return _Found()
    f, table, a = pick
    side = "or more" if held else "or less"
    q.out.update(
        source="table", holds=bool(a.holds), inside_table=bool(a.inside), rule=a.rule,
        message=f"{head}: {_say_holds(a.holds)} at T_low/T_high = {r:.3g} "
        f"({_legs_name(f)} {_say_holds(a.holds)}, so any T_low/T_high of {f:g} {side} "
        f"{'does' if a.holds else 'slips'}); {a.message}",
        mu_tables=[float(m) for m in a.mu_tables], mu_tables_available=table.mus,
        law=table.law, t_low_fraction_table=f,
    )  # fmt: skip
    creep = _table_creep(q, table, a)
    # the table's own slip load only at its own T_low/T_high
    same = abs(f - r) <= LEGS_TOL and a.holds and math.isfinite(a.capacity_t_over_EA)
    ax = table.axes
    validity = (
        f"{q.knot} tables at T_low/T_high = {', '.join(f'{g:g}' for g, _, _ in asked)}, grid "
        f"d/2R {ax['d_over_2R'][0]:.3g}-{ax['d_over_2R'][-1]:.3g}, T_high/EA "
        f"{ax['t_over_EA'][0]:.3g}-{ax['t_over_EA'][-1]:.3g}, mu = mu_rr {ax['mu'][0]:g}-"
        f"{ax['mu'][-1]:g} ({table.law} rod-rod law); decided by {_legs_name(f)} (rule "
        f"{a.rule!r}) and more load on the lighter leg never turning a hold into a slip"
    )
    capacity = a.capacity_t_over_EA * q.EA if same else math.nan
    return _Found(validity=validity, capacity=capacity, law=table.law, creep=creep)


def _legs_name(f: float) -> str:
    return "the free-end table (T_low = 0)" if f == 0 else f"the table at T_low = {f:g} T_high"


def _say_holds(h) -> str:
    return "holds" if h is True else ("slips" if h is False else "undecided")


def _from_phase_table(q: _Query, user, path: str) -> _Found:
    """A smooth-law phase table the user names (mu = mu_rr tables bracketing the friction)."""
    law = "imc"
    why = _refusal(q, user, f"phase table {path!r}")
    if why:
        q.out.update(source="table", table=path, law=law, message=why)
        return _Found(law=law)
    a = user.lookup(q.x, q.y, mu=q.mu, mu_rr=q.mu_rr)
    q.out.update(
        source="table", holds=a.holds, inside_table=bool(a.inside), message=a.message,
        critical_t_over_EA=a.critical if math.isfinite(a.critical) else None,
        mu_tables=[float(m) for m in a.mu_tables],
        mu_tables_available=[float(m) for m in user.mus], table=path, law=law,
        criterion="distance: end 0 creeps less than d over the last half of the hold "
        "(the smooth-law tables' criterion)",
    )  # fmt: skip
    capacity = a.bracket[0] * q.EA if a.inside and a.bracket[0] > 0 else math.nan
    if a.holds is None:
        return _Found(law=law)
    return _Found(validity=_table_validity_imc(user, a), capacity=capacity, law=law)


def _from_hold_table(q: _Query, user, phase_table) -> _Found:
    """A 3-axis hold table: the user's, or the shipped one of the knot."""
    table = user if user is not None else shipped_hold_table(q.knot, q.kappa)
    if table is None:
        q.out["message"] = f"no DER hold table for {q.knot} is shipped"
        return _Found()
    law = table.law
    where = "shipped" if user is None else str(phase_table)
    name = f"phase table {where!r}" if user is not None else f"the shipped {q.knot} hold table"
    why = _refusal(q, table, name)
    if why:
        q.out.update(source="table", law=law, message=why, table=where)
        return _Found(law=law)
    a = table.lookup(q.x, q.y, mu=q.mu, mu_rr=q.mu_rr, creep_limit=q.lim)
    _report_lookup(q, table, a, where)
    creep = _table_creep(q, table, a)
    capacity = (
        a.capacity_t_over_EA * q.EA if a.holds and math.isfinite(a.capacity_t_over_EA) else math.nan
    )
    if a.holds is None:
        return _Found(law=law, creep=creep)
    ax = table.axes
    validity = (
        f"{q.knot} table grid d/2R {ax['d_over_2R'][0]:.3g}-{ax['d_over_2R'][-1]:.3g}, "
        f"T_high/EA {ax['t_over_EA'][0]:.3g}-{ax['t_over_EA'][-1]:.3g}, mu = mu_rr "
        f"{ax['mu'][0]:g}-{ax['mu'][-1]:g} ({law} rod-rod law); decided by the rule "
        f"{a.rule!r} (neighbours agree, or beyond the grid where monotonicity says so)"
    )
    return _Found(validity=validity, capacity=capacity, law=law, creep=creep)


def _report_lookup(q: _Query, table, a, where: str) -> None:
    """The hold table's answer into the details."""
    ax = table.axes
    clock = "" if q.ts == 1.0 else (
        f" (grid creep speeds in d per protocol s; 1 protocol s = {q.ts:.3g} s for this "
        "rope)")  # fmt: skip
    q.out.update(
        source="table", holds=a.holds, inside_table=bool(a.inside),
        message=a.message + clock,
        rule=a.rule,
        critical_t_over_EA=a.critical if math.isfinite(a.critical) else None,
        capacity_t_over_EA=(a.capacity_t_over_EA
                            if math.isfinite(a.capacity_t_over_EA) else None),
        mu_tables=[float(m) for m in a.mu_tables], mu_tables_available=table.mus,
        table=where, law=table.law,
        grid={k: [float(v) for v in ax[k]] for k in ax},
    )  # fmt: skip


def _table_creep(q: _Query, table, a):
    """The creep the table's neighbouring points measured: the largest of those that held
    when it holds, else the smallest measured; None without neighbours."""
    if not a.corners:
        return None
    n = len(a.corners)
    src = f"DER {q.knot} table, {n} neighbouring grid point{'s' if n > 1 else ''}"
    win = table.criterion.get("window_s")
    q.out["criterion"] = _criterion_text(q.lim, win, q.ts)
    kw = {"limit": q.lim, "window": win, "time_scale": q.ts}
    if a.holds and math.isfinite(a.creep_speed):
        return _creep_dict(src + " (largest creep of the points that held)", a.creep_speed,
                           q.d, **kw)  # fmt: skip
    finite = [c.creep_speed for c in a.corners if math.isfinite(c.creep_speed)]
    if finite:
        return _creep_dict(src + " (smallest creep measured)", min(finite), q.d, **kw)
    return _creep_dict(src, math.nan, q.d, ran_to_end=False, **kw)


def _model_answer(q: _Query, f: _Found, simulate: bool, ideal_holds):
    """The DER's :class:`~knotmech.analytic.hitch.ModelAnswer` (not yet deciding)."""
    from knotmech.analytic.hitch import ModelAnswer

    holds = bool(q.out["holds"])
    if ideal_holds is not None:
        q.out["agrees_with_ideal_rope"] = holds == bool(ideal_holds)
    return ModelAnswer(
        model=f"DER-{q.out['source']}",
        holds=holds,
        margin=(f.capacity / q.load - 1) if math.isfinite(f.capacity) else math.nan,
        capacity=f.capacity,
        critical_mu=math.nan,
        decides=False,
        inside_validity=True,
        assumptions=_assumptions(q, f.law, simulate),
        validity=(f.validity,),
        reference=(
            "clove-hitch paper (Extreme Mech. Lett., DOI 10.1016/j.eml.2022.101788), "
            "sec. 8 and Fig. 4; knotmech.scenes.phase_table"
        ),
        notes=(q.out["message"],),
    )


def _assumptions(q: _Query, law: str, simulate: bool) -> tuple:
    """The DER model's assumptions: the rod, its bending stiffness, the hold criterion and
    the loading the knot's record names."""
    if q.kappa == 1.0:
        solid = " (a solid rod; a fibre rope bends far more easily, kappa ~ 0.01)"
    else:
        k = q.kappa if simulate else q.out.get("table_bending_scale", 1.0)
        solid = f" (the {'run' if simulate else 'table'}'s kappa {k:g})"
    hold_rule = (
        q.out["criterion"]
        if law == "anchor"
        else "free end: held if the end creeps less than d over the last half of the hold"
    )
    loading = knots.get(q.knot).loading
    if q.free > 0:  # the cow hitch on both legs: not the record's one-ended loading
        r = q.free / q.load
        loading = (f"{q.knot} loaded on both legs: T_high on one, T_low = {r:.3g} T_high on "
                   "the other (the girth hitch of a sling)")  # fmt: skip
    return (
        "discrete elastic rod (centreline, circular cross-section, no flattening in "
        "the nips), rigid post, Coulomb-type friction at the rod surface"
        + (" (sticking rod-rod anchor law)" if law == "anchor" else " (smooth rod-rod law)"),
        f"bending stiffness B = kappa E pi d^4/64 with kappa = {q.kappa:g}" + solid,
        hold_rule,
    ) + ((loading,) if loading else ())

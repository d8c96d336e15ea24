r"""Does a rope tied to a post hold a load? The verdict of knotmech, in one place.

:func:`hold` is the one entry point (``knotmech.hold(knot, ...)``; the command
``knotmech hold`` and the tour call it and only print). It collects every model's
answer and decides by one rule (:data:`RULE`):

- the closed forms of :mod:`knotmech.analytic.hitch` (ideal rope, thick nip;
  ideal and finite-thickness capstan), always;
- for the hitches with a free end (clove hitch, two half hitches, round turn and two half
  hitches, cow hitch with one leg free), the DER hold/slip diagram (the clove-hitch paper,
  Extreme Mech. Lett., DOI 10.1016/j.eml.2022.101788, sec. 8 and Fig. 4): the shipped
  anchor-law hold tables over real-rope ranges (:class:`knotmech.scenes.phase_table.
  HoldTable`; d/2R, T_high/EA from 1e-4 to 0.3, mu = mu_rr from 0.1 to 0.8), a table the
  user names, or with ``simulate=True`` one DER run of the user's geometry. The hold
  criterion is a creep speed: the hitch holds when its loaded end creeps slower than
  ``creep_limit`` (default 1e-3 rope diameters per second) at the end of the hold (the
  clove hitch: over the last second; the other hitches: over the last half of the 1.5 s
  hold) once the load is on, with its topology kept; the verdict reports the creep speed
  measured and its window. The tables are in :math:`T_\mathrm{high}/EA`, so they need the rope's
  Young's modulus: from ``youngs_modulus`` or ``material`` (:mod:`knotmech.materials`);
  with neither, the DER is not consulted and the verdict says so;
- for the bends (reef, granny, thief, grief) no closed form and no table: undecided with
  the command that decides, or with ``simulate=True`` one DER pull of the bend (its slip
  load against the load).

**The rule.** The most faithful model whose inputs lie inside its validity and that
gives a definite answer decides, in the order DER simulation, DER table, then the
closed forms (hitches: ideal rope, then thick nip; capstan: finite-thickness, then
ideal capstan). A model outside its validity never decides; when no model inside its
validity answers, the verdict is undecided (``holds is None``) and ``next_step``
names what decides it (the full ``knotmech hold ... --simulate`` command where a DER
scene exists).

Validity used by the rule (beyond each closed form's own statement):

- ideal rope: d/D <= 0.1, and never for hitches with half hitches (they wrap the
  standing part, of diameter d itself);
- thick nip: a rope no thicker than its post, and a strain :math:`T_\mathrm{high}/EA
  \le 10\,\%` (the model's inextensible rope) when E is known;
- DER table: between grid points decided only where every neighbouring point agrees;
  beyond the grid only one way, where monotonicity says so (a load lighter than the
  lightest where the two lightest agree; a heavier load where the heaviest slipped; more
  friction where the largest held; less where the smallest slipped); outside the d/2R
  range never (:meth:`knotmech.scenes.phase_table.HoldTable.lookup`).

Implausible inputs (mu or mu_rr > 2, strain above 10 %, a wrap beyond 20 turns, a
rope thicker than its post) give an :class:`InputWarning` naming the input.

The module is callable: ``knotmech.hold(...)`` is :func:`hold` whether ``knotmech.hold``
was reached as the module or as the function.
"""

from __future__ import annotations

import functools
import inspect
import json
import math
import sys
import types
import warnings
from dataclasses import dataclass, field, replace
from pathlib import Path

from knotmech import knots
from knotmech.errors import InputError

__all__ = [
    "hold",
    "Verdict",
    "InputWarning",
    "KNOT_NAMES",
    "RULE",
    "knot_key",
    "hold_verdict",
    "plot_verdict",
    "STRAIN_LIMIT",
    "MU_PLAUSIBLE",
    "WRAP_TURNS_PLAUSIBLE",
]

#: the order in which models decide (the first inside its validity with an answer)
RULE = (
    "DER-simulation",
    "DER-table",
    "ideal-rope",
    "thick-nip",
    "thick-capstan",
    "ideal-capstan",
)
STRAIN_LIMIT = 0.10  #: T_high/EA above this is implausible and outside the thick-nip model
MU_PLAUSIBLE = 2.0  #: a friction coefficient above this is implausible for rope
WRAP_TURNS_PLAUSIBLE = 20.0  #: a capstan wrap beyond this many turns is implausible
#: what one ``simulate=True`` run of a hitch costs, as the answers quote it (measured: the
#: clove hitch at the paper's size 7.3 s wall on an idle machine; the hold-table runs of the
#: hitches 3-30 s of CPU per point, up to ~2 min on large posts, d/D ~ 0.02, where the rod
#: is long)
SIMULATE_COST = (
    "typically 10-30 s of CPU, up to ~2 min on a large post (d/D ~ 0.02); a second run "
    "with a 3 s hold when the creep lies near the limit"
)

_HITCHES = knots.names(family="hitch")
#: the bends of Patil et al. (Science 2020): two ropes joined and pulled apart
_BENDS = knots.names(family="bend")
#: hitches that may have a DER answer (a hold table or a DER scene): the registry's hitches
#: with a scene or a shipped table; the clove hitch always has one
_DER_HITCHES = tuple(k.name for k in knots.records(family="hitch", answered=True)
                     if k.has_scene or k.hold_table)  # fmt: skip


#: the hitches whose free-end case can have a DER answer (public name for the CLI)
DER_HITCHES = _DER_HITCHES


def has_der_answer(knot) -> bool:
    """Whether ``knot`` (a canonical name) has a DER answer: a shipped hold table or a scene."""
    return _der_knot(knot)


def _der_knot(key) -> bool:
    """Whether ``key`` has a DER answer here: a shipped hold table or an importable scene."""
    if key == "clove-hitch":
        return True
    if key not in _DER_HITCHES:
        return False
    from knotmech.scenes import phase_table as pt

    return key in _shipped_hold_tables() or pt.has_hold_scene(key)


#: knots :func:`hold` answers (the registry's answered records: capstan, hitches, bends)
KNOT_NAMES = knots.names()


def is_bend(knot) -> bool:
    """Whether ``knot`` (a canonical name) is a bend: two ropes pulled apart, no post."""
    return knot in _BENDS


def can_simulate(knot) -> bool:
    """Whether ``simulate=True`` runs a DER scene for ``knot`` (a canonical name)."""
    if knot in _BENDS or knot == "clove-hitch":
        return True
    if knot not in _DER_HITCHES:
        return False
    from knotmech.scenes import phase_table as pt

    return pt.has_hold_scene(knot)


def knot_key(knot) -> str:
    """Canonical knot name, or a one-line :class:`InputError` listing what is answered."""
    key = knots.key(knot) or knots.normalise(knot)
    if key in KNOT_NAMES:
        return key
    supported = ", ".join(KNOT_NAMES)
    if key in knots.REGISTRY:
        why = knots.REGISTRY[key].unanswered
        raise InputError(f"{knot!r} is {why}; hold answers: {supported}")
    raise InputError(f"unknown knot {str(knot)!r}; hold answers: {supported}")


@dataclass(frozen=True)
class InputWarning:
    """An implausible input: ``name`` (the parameter) and what is implausible about it."""

    name: str
    message: str

    def __str__(self) -> str:
        return f"{self.name}: {self.message}"


@dataclass(frozen=True)
class Verdict:
    r"""Answer of :func:`hold`.

    Attributes
    ----------
    knot : str
    holds : bool or None
        None when no model inside its validity answers (undecided).
    margin : float
        Load margin of the deciding model, ``capacity/load - 1`` (>= 0 holds; ``inf``
        when self-locking; NaN when undecided or not computed, e.g. a DER slip).
    decided_by : str or None
        The deciding model (one of :data:`RULE`), None when undecided.
    inside_validity : bool
        Whether the deciding model's inputs lie inside its validity (always True when
        decided: the rule lets no model outside its validity decide).
    answers : tuple of ModelAnswer
        Every model's answer (:class:`knotmech.analytic.hitch.ModelAnswer`); the
        deciding one has ``decides=True``.
    validity : tuple of str
        The deciding model's validity statements.
    assumptions : tuple of str
        What the verdict assumed (the material and where E came from; the deciding
        model's own assumptions are in its answer).
    warnings : tuple of InputWarning
        Implausible inputs.
    next_step : str
        What to do next (e.g. the command that decides an undecided case).
    creep : dict or None
        Creep of the loaded end measured by the DER (simulation, or the nearest grid
        point that held): ``creep_m`` over ``window_s``, ``speed_m_per_s``,
        ``speed_d_per_s``, ``limit_d_per_s`` (in the rope's own seconds) and ``source``;
        the DER runs on the rod's flexural clock, so also ``time_scale`` (real seconds per
        protocol second, :func:`knotmech.scenes.phase_table.protocol_time_scale`),
        ``speed_d_per_protocol_s`` and ``limit_d_per_protocol_s``.
    inputs : dict
        The inputs in SI units.
    der : dict or None
        The DER answer's details (clove hitch), None for other knots.
    notes : tuple of str
    """

    knot: str
    holds: bool | None
    margin: float
    decided_by: str | None
    inside_validity: bool
    answers: tuple
    validity: tuple = ()
    assumptions: tuple = ()
    warnings: tuple = ()
    next_step: str = ""
    creep: dict | None = None
    inputs: dict = field(default_factory=dict)
    der: dict | None = None
    notes: tuple = ()
    #: the simulated knot (``positions`` (n, 3) [m], ``tension`` (n - 1,) [N], ``rod_diameter``,
    #: ``post_diameter``) when a DER simulation answered; not part of :meth:`to_dict`
    shape: dict | None = field(default=None, repr=False, compare=False)

    @property
    def deciding(self):
        """The deciding :class:`~knotmech.analytic.hitch.ModelAnswer`, None when undecided."""
        return next((a for a in self.answers if a.decides), None)

    @property
    def state(self) -> str:
        """``"HOLDS"``, ``"SLIPS"`` or ``"UNDECIDED"``."""
        return {True: "HOLDS", False: "SLIPS", None: "UNDECIDED"}[self.holds]

    def summary(self) -> str:
        """The answer in one line: verdict, margin, deciding model."""
        if self.holds is None:
            return f"verdict: UNDECIDED (no model inside its validity answers); {self.next_step}"
        return (
            f"verdict: {self.state}  margin {format_margin(self.margin)}; decided by the "
            f"{self.decided_by} model (inputs inside its validity)"
        )

    def to_dict(self) -> dict:
        """Strict JSON-ready dict: non-finite numbers are null (with a flag where it matters)."""
        return _strict(
            {
                "knot": self.knot,
                "holds": self.holds,
                "verdict": self.state.lower(),
                "margin": self.margin,
                "margin_unbounded": bool(math.isinf(self.margin) and self.margin > 0),
                "decided_by": self.decided_by,
                "inside_validity": self.inside_validity,
                "validity": list(self.validity),
                "assumptions": list(self.assumptions),
                "warnings": [{"input": w.name, "message": w.message} for w in self.warnings],
                "next_step": self.next_step,
                "creep": self.creep,
                "inputs": dict(self.inputs),
                "answers": [_answer_dict(a) for a in self.answers],
                "der": self.der,
                "notes": list(self.notes),
            }
        )

    def to_json(self) -> str:
        """:meth:`to_dict` as strict JSON text (``allow_nan=False``)."""
        return json.dumps(self.to_dict(), indent=2, allow_nan=False)


def format_margin(margin: float) -> str:
    """``+12.3 %``, ``unbounded (self-locking)`` or ``not computed``."""
    if math.isnan(margin):
        return "not computed"
    if math.isinf(margin):
        return "unbounded (self-locking)" if margin > 0 else "-inf"
    pct = margin * 100
    return f"{pct:+.1f} %" if abs(pct) < 1e5 else f"{pct:+.3g} %"


def _answer_dict(a) -> dict:
    return {
        "model": a.model,
        "holds": a.holds,
        "decides": a.decides,
        "inside_validity": a.inside_validity,
        "margin": a.margin,
        "margin_unbounded": bool(math.isinf(a.margin) and a.margin > 0),
        "capacity": a.capacity,
        "capacity_unbounded": bool(math.isinf(a.capacity)),
        "critical_mu": a.critical_mu,
        "critical_mu_none": bool(math.isinf(a.critical_mu)),
        "assumptions": list(a.assumptions),
        "validity": list(a.validity),
        "reference": a.reference,
        "notes": list(a.notes),
    }


def _strict(obj):
    """Recursively: non-finite floats -> None, tuples -> lists, numpy scalars -> Python."""
    if isinstance(obj, dict):
        return {str(k): _strict(v) for k, v in obj.items()}
    if isinstance(obj, list | tuple):
        return [_strict(v) for v in obj]
    if isinstance(obj, bool) or obj is None or isinstance(obj, str):
        return obj
    if hasattr(obj, "item") and not isinstance(obj, int | float):
        obj = obj.item()  # numpy scalar
    if isinstance(obj, bool):
        return obj
    if isinstance(obj, int):
        return obj
    if isinstance(obj, float):
        if not math.isfinite(obj):
            return None
        return float(obj)
    return obj


# --------------------------------------------------------------------------- inputs
def _youngs_modulus(material, youngs_modulus):
    """(E [Pa] or None, material or None, what was assumed)."""
    from knotmech.materials import format_modulus as fm
    from knotmech.materials import material as get_material

    mat = None if material is None else get_material(material)
    if youngs_modulus is not None:
        E = float(youngs_modulus)
        if not (math.isfinite(E) and E > 0):
            raise InputError(f"youngs_modulus must be > 0, got {E:g}")
        src = f"Young's modulus E = {fm(E)}, as given"
        if mat is not None:
            src += f" (instead of the {mat.key} preset's {fm(mat.youngs_modulus)})"
        return E, mat, src
    if mat is not None:
        lo, hi = mat.youngs_modulus_range
        rng = "" if lo == hi else f" (range {fm(lo)} to {fm(hi)} over constructions)"
        return (
            mat.youngs_modulus,
            mat,
            f"{mat.description}: effective axial modulus E = {fm(mat.youngs_modulus)}{rng}; "
            f"source: {mat.source}",
        )
    return None, None, ""


#: the DER table answers only when the table's bending scale kappa is within this factor of
#: the rope's (a rope's kappa is of order 0.01; the shipped tables are solid rods, kappa = 1)
BENDING_SCALE_FACTOR = 3.0


def _bending_scale(mat, bending_scale):
    """(kappa, what was assumed): ``bending_scale`` if given, else the material's, else 1."""
    from knotmech.errors import check_bending_scale

    if bending_scale is not None:
        k = check_bending_scale(bending_scale)
        src = f"bending scale kappa = {k:g} (B = kappa E pi d^4/64), as given"
        if mat is not None and mat.bending_scale != k:
            src += f" (instead of the {mat.key} preset's {mat.bending_scale:g})"
        return k, src
    if mat is not None:
        k = float(mat.bending_scale)
        lo, hi = mat.bending_scale_range
        rng = "" if lo == hi else f", range {lo:g}-{hi:g}"
        return k, (
            f"bending scale kappa = {k:g} (B = kappa E pi d^4/64{rng}); source: "
            f"{mat.bending_source}"
        )
    return 1.0, (
        "bending scale kappa = 1 (B = E pi d^4/64, a solid rod): no material given, so no "
        "rope bending stiffness; a fibre rope is of order 0.01 (give --bending-scale)"
    )


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
    from knotmech.scenes import phase_table as pt

    meta = getattr(table, "meta", None) or {}
    rod = meta.get("rod") or {}
    try:
        return (float(rod.get("d_m", pt.ROD_DIAMETER)), float(rod.get("E_Pa", pt.YOUNGS_MODULUS)),
                float(rod.get("rho", pt.DENSITY)))  # fmt: skip
    except (TypeError, ValueError):
        raise InputError("a DER table's meta rod must hold numbers d_m, E_Pa, rho") from None


def _table_time_scale(table, kappa) -> tuple[float, bool]:
    """(protocol time scale of the rod the table ran on, whether the table is on the
    flexural clock: meta ``protocol_clock`` == "flexural", or a time scale of 1, the
    reference rod, on which seconds and protocol seconds are the same)."""
    from knotmech.scenes import phase_table as pt

    td, tE, trho = _table_rod(table)
    ts = pt.protocol_time_scale(rod_diameter=td, youngs_modulus=tE, density=trho,
                                bending_scale=kappa)  # fmt: skip
    meta = getattr(table, "meta", None) or {}
    return ts, meta.get("protocol_clock") == pt.PROTOCOL_CLOCK or abs(ts - 1.0) < 1e-9


def _table_kappa(table, name="the DER table") -> float:
    """The bending scale a DER table was built with (meta ``bending_scale``, 1 if absent;
    :func:`knotmech.scenes.phase_table.meta_bending_scale`: a one-line InputError naming
    ``name`` when it is not a number in (0, 1])."""
    from knotmech.scenes import phase_table as pt

    return pt.meta_bending_scale(getattr(table, "meta", None), name)


def _warnings(mu, mu_rr, d, D, load, E, theta):
    out = []
    for name, v in (("mu", mu), ("mu_rr", mu_rr)):
        if v is not None and v > MU_PLAUSIBLE:
            out.append(
                InputWarning(
                    name,
                    f"{v:g} is implausible for rope (> {MU_PLAUSIBLE:g}; rope on a post is "
                    "typically 0.1-0.8)",
                )
            )
    if d > D:
        out.append(
            InputWarning(
                "rod_diameter",
                f"the rope (d = {d * 1e3:.4g} mm) is thicker than its post "
                f"(D = {D * 1e3:.4g} mm): the models here assume a rope wrapped on a post",
            )
        )
    if E is not None:
        strain = load / (E * math.pi * d * d / 4)
        if strain > STRAIN_LIMIT:
            out.append(
                InputWarning(
                    "load",
                    f"strain T_high/EA = {strain:.3g} ({strain * 100:.3g} %) with "
                    f"E = {E:.3g} Pa is implausible (> {STRAIN_LIMIT * 100:g} %): check the "
                    "load, the diameter and the material",
                )
            )
    if theta is not None and theta > WRAP_TURNS_PLAUSIBLE * 2 * math.pi:
        out.append(
            InputWarning(
                "wrap_angle",
                f"{theta / (2 * math.pi):.4g} turns is implausible (> "
                f"{WRAP_TURNS_PLAUSIBLE:g}); an angle without a unit is in radians",
            )
        )
    return tuple(out)


# --------------------------------------------------------------------------- DER
def _load_user_table(path):
    from knotmech.scenes import phase_table as pt

    try:
        head = json.loads(Path(path).read_text())
    except (OSError, ValueError):
        head = None  # load_table says what is wrong
    if isinstance(head, dict) and head.get("format") == pt.HOLD_TABLE_FORMAT:
        return pt.read_hold_table(path)  # a 3-axis hold table (checked when read)
    t = pt.load_table(path)  # InputError when missing or not a table
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
    return pt.PhaseTableSet([t])


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
    from knotmech.scenes import phase_table as pt

    return pt.load_tables()


def _shipped_hold_tables():
    """The shipped anchor-law solid-rod hold tables {knot: HoldTable} (those nearest kappa = 1
    of :func:`_shipped_hold_table_sets`, which reads the files once per process)."""
    return {knot: _shipped_hold_table(knot, 1.0) for knot in _shipped_hold_table_sets()}


@functools.lru_cache(maxsize=1)
def _shipped_hold_table_sets():
    """The shipped anchor-law hold tables {knot: {kappa: HoldTable}}, read once per process."""
    from knotmech.scenes import phase_table as pt

    return pt.load_hold_table_sets()


def _shipped_hold_table(knot, kappa=1.0):
    """The shipped hold table of ``knot`` whose bending scale is nearest ``kappa`` (by
    ratio), or None when none is shipped."""
    by_kappa = _shipped_hold_table_sets().get(knot)
    if not by_kappa:
        return None
    best = min(by_kappa, key=lambda k: abs(math.log(k / float(kappa))))
    return by_kappa[best]


def _q(value: float, unit: str) -> str:
    """A quantity as a command-line token with its unit (4mm, 1.47N, 1.26MPa)."""
    if unit == "m":
        return f"{value * 1e3:.6g}mm"
    if unit == "Pa":
        return f"{value / 1e6:.6g}MPa"
    return f"{value:.6g}{unit}"


def simulate_command(
    knot, *, d, D, mu, mu_rr=None, load, material=None, youngs_modulus=None, creep_limit=None,
    bending_scale=None,
) -> str:  # fmt: skip
    """The full ``knotmech hold ... --simulate`` command that decides this case by one DER run."""
    parts = ["knotmech", "hold", knot, "--rod-diameter", _q(d, "m")]
    if D is not None:
        parts += ["--post-diameter", _q(D, "m")]
    parts += ["--mu", f"{mu:g}"]
    if mu_rr is not None and mu_rr != mu:
        parts += ["--mu-rr", f"{mu_rr:g}"]
    parts += ["--load", _q(load, "N")]
    if youngs_modulus is not None:
        parts += ["--youngs-modulus", _q(youngs_modulus, "Pa")]
    elif material is not None:
        parts += ["--material", str(material)]
    else:  # a DER run needs the stiffness: the user picks it
        parts += ["--material", "MATERIAL"]
    if bending_scale is not None:
        parts += ["--bending-scale", f"{float(bending_scale):g}"]
    if creep_limit is not None:
        parts += ["--creep-limit", f"{creep_limit:g}"]
    return " ".join(parts + ["--simulate"])


def _criterion_text(limit: float, window: float | None = None, time_scale: float = 1.0) -> str:
    """The criterion in words; ``limit`` [d per protocol s] and ``window`` [protocol s], with
    ``time_scale`` the rope's real seconds per protocol second."""
    from knotmech.scenes import phase_table as pt

    w = pt.CREEP_WINDOW if window is None else float(window)
    s = float(time_scale)
    clock = "" if s == 1.0 else (
        f" (the protocol's {limit:g} d/s over {w:g} s, on the rod's flexural clock "
        f"d/(sqrt(kappa) sqrt(E/rho)): 1 protocol s = {s:.3g} s for this rope)"
    )  # fmt: skip
    return (
        f"{pt.CREEP_CRITERION} criterion: holds when the loose end creeps slower than "
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
    from knotmech.scenes import phase_table as pt

    ok = ran_to_end and speed is not None and math.isfinite(speed)
    w = pt.CREEP_WINDOW if window is None else float(window)
    s = float(time_scale)
    return {
        "source": source,
        "criterion": pt.CREEP_CRITERION,
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


def _der(
    *,
    knot="clove-hitch",
    d,
    D,
    mu,
    mu_rr,
    load,
    E,
    simulate,
    phase_table,
    progress,
    ideal_holds,
    creep_limit=None,
    bending_scale=1.0,
    command="",
    density=None,
):
    """The DER answer for a hitch with a free end: (details dict, ModelAnswer or None,
    creep dict or None, shape). A table answers only when its bending scale is within
    :data:`BENDING_SCALE_FACTOR` of ``bending_scale`` and, unless it ran on the protocol's
    flexural clock (every shipped table does), its rod's protocol time scale within
    :data:`ROD_RATE_FACTOR` of the rope's (``density`` [kg/m^3]: the material's; None, the
    reference rod's); else undecided, ``command`` decides. ``simulate`` runs at that
    density, on the rope's clock. Creep is reported in the rope's real seconds."""
    from knotmech.analytic.hitch import ModelAnswer
    from knotmech.scenes import phase_table as pt

    lim = pt.CREEP_LIMIT if creep_limit is None else float(creep_limit)
    x = d / (D + d)  # d/2R with R = (D + d)/2
    EA = E * math.pi * d * d / 4
    y = load / EA
    out = {
        "source": "none",
        "holds": None,
        "d_over_2R": x,
        "t_over_EA": y,
        "youngs_modulus": E,
        "inside_table": False,
        "critical_t_over_EA": None,
        "mu_tables": [],
        "message": "",
        "agrees_with_ideal_rope": None,
        "criterion": _criterion_text(lim),
        "bending_scale": float(bending_scale),
    }
    kappa = float(bending_scale)
    # the rope's real seconds per protocol second (the DER runs on the rod's flexural clock)
    ts = pt.protocol_time_scale(
        rod_diameter=d,
        youngs_modulus=E,
        bending_scale=kappa,
        density=pt.DENSITY if density is None else float(density),
    )
    out["time_scale"] = ts
    out["criterion"] = _criterion_text(lim, None, ts)

    def refused(table, name):
        """The reason a table built at another kappa, or for a rod of another elastic-wave
        rate, may not answer; "" when it may."""
        tk = _table_kappa(table, name)
        out["table_bending_scale"] = tk
        then = f"; decide with: {command}" if command else ""
        if max(tk / kappa, kappa / tk) > BENDING_SCALE_FACTOR:
            kind = "solid rods" if tk == 1.0 else "rods"
            out["refused"] = "bending_scale"
            return (
                f"not decided by the table: the tables are for {kind} (kappa = {tk:g}); this "
                f"rope's kappa = {kappa:g} (more than a factor {BENDING_SCALE_FACTOR:g} apart)"
                + then
            )
        td, tE, trho = _table_rod(table)
        ts_table, clocked = _table_time_scale(table, tk)
        out["table_rod"] = {
            "d_m": td,
            "E_Pa": tE,
            "rho": trho,
            "time_scale": ts_table,
            "protocol_clock": pt.PROTOCOL_CLOCK if clocked else "seconds",
        }
        if clocked:
            return ""
        # a table run in seconds: only for a rope whose clock ticks like its rod's
        if max(ts / ts_table, ts_table / ts) > ROD_RATE_FACTOR:
            out["refused"] = "rod"
            return (
                f"not decided by the table: it ran in seconds on a rod of E = {tE / 1e6:.3g} "
                f"MPa, d = {td * 1e3:.3g} mm, {trho:g} kg/m^3 (protocol time scale "
                f"{ts_table:.3g}); this rope's is {ts:.3g} (more than a factor "
                f"{ROD_RATE_FACTOR:g} apart), so its answer is not in T_high/EA alone" + then
            )
        return ""

    creep = None
    shape = None
    capacity = math.nan
    law = "anchor"
    if simulate:
        p = pt.simulate_point(
            d_over_2R=x, t_over_EA=y, mu=mu, mu_rr=mu_rr, rod_diameter=d, youngs_modulus=E,
            bending_scale=kappa, creep_limit=lim, recheck=True, progress=progress, keep_result=True,
            **({} if knot == "clove-hitch" else {"knot": knot}),
            **({} if density is None else {"density": float(density)}),
        )  # fmt: skip
        shape = _shape(p.get("result"), d=d, D=D)
        if p["holds"] is None:
            out["message"] = f"the DER simulation failed: {p['message']}"
            return out, None, None, shape
        ts = float(p.get("time_scale", 1.0))
        speed = float(p.get("creep_speed_protocol", ts * p.get("creep_speed", math.nan)))
        ran = bool(p.get("ran_to_end", math.isfinite(speed)))
        win = float(p.get("creep_window_s", ts * pt.CREEP_WINDOW)) / ts
        creep = _creep_dict("DER simulation of this geometry", speed, d, limit=lim,
                            ran_to_end=ran, window=win, time_scale=ts)  # fmt: skip
        out["time_scale"] = ts
        out["criterion"] = _criterion_text(lim, win, ts)
        crept = (
            f"loaded end creeps {creep['speed_d_per_s']:.3g} d/s over the last "
            f"{creep['window_s']:.3g} s of the hold"
            if creep["speed_d_per_s"] is not None
            else "the loaded end ran off before the hold's measuring window"
        )
        reason = "" if creep["speed_d_per_s"] is not None else p.get("reason", "")
        out.update(
            source="simulation",
            holds=bool(p["holds"]),
            message=(
                f"DER simulation at d/2R = {x:.4g}, T_high/EA = {y:.4g}: {p['verdict']} "
                f"({crept}{'; ' + reason if reason else ''}; {p['wall_s']:.0f} s)"
            ),
        )
        run_s = sum(pt.PROTOCOL[k] for k in ("settle_time", "load_time", "hold_time"))
        validity = (
            f"one run of the user's geometry ({run_s:g} protocol s of simulated time"
            + ("" if ts == 1.0 else f", {run_s * ts:.3g} s for this rope")
            + ")"
        )
    else:
        user = None if phase_table is None else _load_user_table(phase_table)
        if user is not None and not isinstance(user, pt.HoldTable):
            law = "imc"
            why = refused(user, f"phase table {str(phase_table)!r}")
            if why:
                out.update(source="table", table=str(phase_table), law=law, message=why)
                return out, None, None, shape
            a = user.lookup(x, y, mu=mu, mu_rr=mu_rr)
            out.update(
                source="table", holds=a.holds, inside_table=bool(a.inside), message=a.message,
                critical_t_over_EA=a.critical if math.isfinite(a.critical) else None,
                mu_tables=[float(m) for m in a.mu_tables],
                mu_tables_available=[float(m) for m in user.mus], table=str(phase_table),
                law=law,
                criterion="distance: end 0 creeps less than d over the last half of the hold "
                "(the smooth-law tables' criterion)",
            )  # fmt: skip
            if a.inside and a.bracket[0] > 0:
                capacity = a.bracket[0] * EA
            if a.holds is None:
                return out, None, None, shape
            validity = _table_validity_imc(user, a)
        else:
            table = user if user is not None else _shipped_hold_table(knot, kappa)
            if table is None:
                out["message"] = f"no DER hold table for {knot} is shipped"
                return out, None, None, shape
            law = table.law
            why = refused(table, (f"phase table {str(phase_table)!r}" if user is not None
                                  else f"the shipped {knot} hold table"))  # fmt: skip
            if why:
                out.update(source="table", law=law, message=why,
                           table=("shipped" if user is None else str(phase_table)))  # fmt: skip
                return out, None, None, shape
            a = table.lookup(x, y, mu=mu, mu_rr=mu_rr, creep_limit=lim)
            ax = table.axes
            clock = "" if ts == 1.0 else (
                f" (grid creep speeds in d per protocol s; 1 protocol s = {ts:.3g} s for this "
                "rope)")  # fmt: skip
            out.update(
                source="table", holds=a.holds, inside_table=bool(a.inside),
                message=a.message + clock,
                rule=a.rule,
                critical_t_over_EA=a.critical if math.isfinite(a.critical) else None,
                capacity_t_over_EA=(a.capacity_t_over_EA
                                    if math.isfinite(a.capacity_t_over_EA) else None),
                mu_tables=[float(m) for m in a.mu_tables], mu_tables_available=table.mus,
                table=("shipped" if user is None else str(phase_table)), law=law,
                grid={k: [float(v) for v in ax[k]] for k in ax},
            )  # fmt: skip
            finite = [c.creep_speed for c in a.corners if math.isfinite(c.creep_speed)]
            if a.corners:
                n = len(a.corners)
                src = f"DER {knot} table, {n} neighbouring grid point{'s' if n > 1 else ''}"
                win = table.criterion.get("window_s")
                out["criterion"] = _criterion_text(lim, win, ts)
                if a.holds and math.isfinite(a.creep_speed):
                    creep = _creep_dict(
                        src + " (largest creep of the points that held)", a.creep_speed, d,
                        limit=lim, window=win, time_scale=ts,
                    )  # fmt: skip
                elif finite:
                    creep = _creep_dict(src + " (smallest creep measured)", min(finite), d,
                                        limit=lim, window=win, time_scale=ts)  # fmt: skip
                else:
                    creep = _creep_dict(src, math.nan, d, limit=lim, ran_to_end=False,
                                        window=win, time_scale=ts)  # fmt: skip
            if a.holds and math.isfinite(a.capacity_t_over_EA):
                capacity = a.capacity_t_over_EA * EA
            if a.holds is None:
                return out, None, creep, shape
            validity = (
                f"{knot} table grid d/2R {ax['d_over_2R'][0]:.3g}-{ax['d_over_2R'][-1]:.3g}, "
                f"T_high/EA {ax['t_over_EA'][0]:.3g}-{ax['t_over_EA'][-1]:.3g}, mu = mu_rr "
                f"{ax['mu'][0]:g}-{ax['mu'][-1]:g} ({law} rod-rod law); decided by the rule "
                f"{a.rule!r} (neighbours agree, or beyond the grid where monotonicity says so)"
            )
    holds = bool(out["holds"])
    if ideal_holds is not None:
        out["agrees_with_ideal_rope"] = holds == bool(ideal_holds)
    hold_rule = (
        out["criterion"]
        if law == "anchor"
        else "free end: held if the end creeps less than d over the last half of the hold"
    )
    answer = ModelAnswer(
        model=f"DER-{out['source']}",
        holds=holds,
        margin=(capacity / load - 1) if math.isfinite(capacity) else math.nan,
        capacity=capacity,
        critical_mu=math.nan,
        decides=False,
        inside_validity=True,
        assumptions=(
            "discrete elastic rod (centreline, circular cross-section, no flattening in "
            "the nips), rigid post, Coulomb-type friction at the rod surface"
            + (" (sticking rod-rod anchor law)" if law == "anchor" else " (smooth rod-rod law)"),
            f"bending stiffness B = kappa E pi d^4/64 with kappa = {kappa:g}"
            + (
                " (a solid rod; a fibre rope bends far more easily, kappa ~ 0.01)"
                if kappa == 1.0
                else f" (the {'run' if simulate else 'table'}'s kappa "
                f"{kappa if simulate else out.get('table_bending_scale', 1.0):g})"
            ),
            hold_rule,
        )
        + ((knots.get(knot).loading,) if knots.get(knot).loading else ()),
        validity=(validity,),
        reference=(
            "clove-hitch paper (Extreme Mech. Lett., DOI 10.1016/j.eml.2022.101788), "
            "sec. 8 and Fig. 4; knotmech.scenes.phase_table"
        ),
        notes=(out["message"],),
    )
    return out, answer, creep, shape


# --------------------------------------------------------------------------- policy
def _with_validity(answer, inside: bool, extra: str):
    return replace(
        answer,
        inside_validity=bool(answer.inside_validity and inside),
        validity=tuple(answer.validity) + ((extra,) if extra else ()),
    )


def _decide(answers):
    """Index of the deciding answer by :data:`RULE`, None when none qualifies."""
    for model in RULE:
        for i, a in enumerate(answers):
            if a.model == model and a.inside_validity and a.holds is not None:
                return i
    return None


def hold(
    knot,
    *,
    rod_diameter,
    post_diameter=None,
    mu,
    load,
    free_end_load=0.0,
    mu_rr=None,
    wrap_angle=None,
    material=None,
    youngs_modulus=None,
    simulate=False,
    phase_table=None,
    progress=False,
    creep_limit=None,
    bending_scale=None,
) -> Verdict:
    r"""Does a rope tied to a post hold a load? The verdict, every model's answer and why.

    Parameters
    ----------
    knot : str
        One of :data:`KNOT_NAMES` (``capstan``, ``clove-hitch``, ``two-half-hitches``,
        ``round-turn``, ``round-turn-two-half-hitches``, ``cow-hitch`` (also girth hitch,
        lark's head), and the bends ``reef``, ``granny``, ``thief``, ``grief``). Other
        knots (bowline, figure-eight, sheet bend, ...) raise a one-line
        :class:`~knotmech.errors.InputError` listing these.
    rod_diameter, post_diameter : float
        Rope diameter d and post diameter D [m], > 0 (no post for a bend: None).
    mu : float
        Rope-post friction coefficient [-], >= 0.
    load : float
        Tension on the loaded end :math:`T_\mathrm{high}` [N], > 0.
    free_end_load : float
        Tension on the other end :math:`T_\mathrm{low}` [N], 0 (free end) to ``load``.
        Cow hitch: ``load`` is on one leg, ``free_end_load`` on the other (0: the hitch
        loaded on one leg only, the case its DER table and ``simulate`` model; a girth
        hitch whose legs share the load has ``free_end_load = load``).
    mu_rr : float, optional
        Rope-rope friction coefficient [-] (hitches; default ``mu``). Refused for capstan.
    wrap_angle : float, optional
        Wrap angle [rad], > 0: required for capstan, refused for hitches.
    material : str or Material, optional
        A preset of :mod:`knotmech.materials` (``nylon``, ``polyester``, ``hmpe``,
        ``manila``, ``polypropylene``, ``steel-wire``, ``vps32``): gives E.
    youngs_modulus : float, optional
        The rope's effective axial modulus E [Pa] (overrides the material's).
    bending_scale : float, optional
        The rope's bending scale kappa in (0, 1]: bending stiffness B = kappa E pi d^4/64
        (overrides the material's; default the material's, 1 (a solid rod) without a
        material; stated in the assumptions). A DER table answers only when its own
        kappa (meta ``bending_scale``, 1 for the shipped solid-rod tables) is within a
        factor :data:`BENDING_SCALE_FACTOR` of it. The DER protocol runs on the rod's
        flexural clock (:func:`knotmech.scenes.phase_table.protocol_time_scale`), so a table
        answers for every material; a table run in seconds on another rod (meta without
        ``protocol_clock``) only within :data:`ROD_RATE_FACTOR` of its rod's time scale;
        otherwise the DER answer is undecided (``der["refused"]``: ``"bending_scale"`` or
        ``"rod"``) and the other models decide as for an undecided table. ``simulate`` runs
        at the rope's kappa and density.
    simulate : bool
        One DER run of this geometry instead of the tables (:data:`SIMULATE_COST`): the
        hitches with a DER scene (clove hitch, two half hitches, round turn and two half
        hitches, cow hitch) with a free end, or a bend's pull (its slip load against the
        load, 1-3 minutes); needs E.
    phase_table : path, optional
        A hitch with a DER answer: read the DER table from this file instead of the
        shipped one (it must exist and parse).
    progress : bool
        Progress bar on stderr for ``simulate``.
    creep_limit : float, optional
        The DER hold criterion's limit [rod diameters per second]: the hitch holds when
        its loose end creeps slower than this over the last second of the hold once the
        load is on (default :data:`knotmech.scenes.phase_table.CREEP_LIMIT`, 1e-3 d/s),
        in protocol seconds: the DER runs on the rod's flexural clock
        (:func:`knotmech.scenes.phase_table.protocol_time_scale`); the verdict's creep
        gives the limit in the rope's own seconds too.
        The tables store each point's measured creep speed, so they are re-judged at
        this limit.

    Returns
    -------
    Verdict

    Raises
    ------
    InputError
        Bad or inconsistent inputs, an unknown knot or material, a phase table that
        does not read.

    Examples
    --------
    >>> v = hold("clove-hitch", rod_diameter=6e-3, post_diameter=40e-3, mu=0.4,
    ...          load=200.0, material="nylon")
    >>> v.holds, v.decided_by, v.der["rule"]
    (True, 'DER-table', 'grid')
    >>> round(v.creep["speed_d_per_s"], 6)
    6.5e-05
    """
    from knotmech.analytic.hitch import hold_verdict as closed_forms
    from knotmech.errors import check_nonnegative, check_positive

    key = knot_key(knot)
    if key in _BENDS:
        return _hold_bend(
            key, rod_diameter=rod_diameter, post_diameter=post_diameter, mu=mu, load=load,
            free_end_load=free_end_load, mu_rr=mu_rr, wrap_angle=wrap_angle, material=material,
            youngs_modulus=youngs_modulus, simulate=simulate, phase_table=phase_table,
            progress=progress, bending_scale=bending_scale,
        )  # fmt: skip
    if post_diameter is None:
        raise InputError(f"post_diameter is required for {key}")
    d = float(check_positive("rod_diameter", rod_diameter))
    D = float(check_positive("post_diameter", post_diameter))
    mu = float(check_nonnegative("mu", mu))
    load = float(check_positive("load", load))
    free = float(check_nonnegative("free_end_load", free_end_load))
    if creep_limit is not None:
        creep_limit = float(check_positive("creep_limit", creep_limit))
    if key == "capstan" and mu_rr is not None:
        raise InputError("mu_rr (rope-on-rope friction) applies to hitches, not to capstan")
    if simulate and not can_simulate(key):
        raise InputError(
            f"simulate is available for the clove hitch, the hitches with a DER scene and the "
            f"bends, not for {key}"
        )
    if simulate and free > 0:
        raise InputError(
            "simulate covers the hitches with a free end only (free_end_load 0; cow hitch: one "
            "leg loaded, the other free)"
        )
    if simulate and phase_table is not None:
        raise InputError("give either simulate or phase_table, not both")
    if phase_table is not None and not _der_knot(key):
        raise InputError(
            f"phase_table applies to the hitches with a DER answer "
            f"({', '.join(_DER_HITCHES)}), not to {key}"
        )
    E, mat, e_source = _youngs_modulus(material, youngs_modulus)
    kappa, k_source = _bending_scale(mat, bending_scale)
    if simulate and E is None:
        from knotmech.materials import material_names

        raise InputError(
            "simulate needs the rope's stiffness: give material (one of "
            f"{', '.join(material_names())}) or youngs_modulus"
        )
    if phase_table is not None and E is None:
        raise InputError(
            "phase_table is read in T_high/EA: give material or youngs_modulus as well"
        )
    base = closed_forms(
        key,
        rod_diameter=d,
        post_diameter=D,
        mu=mu,
        load=load,
        free_end_load=free,
        mu_rr=mu_rr,
        wrap_angle=wrap_angle,
    )
    inputs = dict(base.inputs)
    if key == "capstan":
        inputs.pop("mu_rr", None)
    theta = inputs.get("wrap_angle")
    if mat is not None:
        inputs["material"] = mat.key
    if E is not None:
        inputs["youngs_modulus"] = E
    inputs["bending_scale"] = kappa
    strain = None if E is None else load / (E * math.pi * d * d / 4)
    answers = []
    for a in base.answers:
        a = replace(a, decides=False)
        if a.model == "thick-nip":
            ok = d <= D and (strain is None or strain <= STRAIN_LIMIT)
            a = _with_validity(
                a,
                ok,
                f"rope no thicker than the post; strain T_high/EA <= {STRAIN_LIMIT * 100:g} % "
                "(inextensible rope)"
                + ("" if strain is None else f": here {strain:.3g}")
                + ("" if strain is not None else " (not checked: E not given)"),
            )
        answers.append(a)
    assumptions = [e_source] if e_source else []
    if key != "capstan":
        assumptions.append(k_source)
    notes = list(base.notes)
    der = None
    creep = None
    shape = None
    next_step = ""
    # the one DER run that decides this case (the table's refusal and the next step name it)
    simulable = can_simulate(key) and free == 0
    cmd = simulate_command(
        key, d=d, D=D, mu=mu, mu_rr=None if mu_rr is None else float(mu_rr), load=load,
        material=None if mat is None else mat.key, youngs_modulus=youngs_modulus,
        creep_limit=creep_limit, bending_scale=bending_scale,
    ) if simulable else ""  # fmt: skip
    if _der_knot(key):
        ideal = next((a.holds for a in answers if a.model == "ideal-rope"), None)
        if free > 0:
            der = {
                "source": "none",
                "holds": None,
                "message": "the DER phase diagram covers the free end only (T_low = 0)",
            }
        elif E is None:
            der = {
                "source": "none",
                "holds": None,
                "message": "not consulted: the DER tables are in T_high/EA and E was not given",
            }
            assumptions.append(
                "nothing about the rope's stiffness: E was not given, so the DER phase table "
                "(in T_high/EA) was not consulted"
            )
        else:
            der, der_answer, creep, shape = _der(
                knot=key, d=d, D=D, mu=mu, mu_rr=mu if mu_rr is None else float(mu_rr),
                load=load, E=E, simulate=bool(simulate), phase_table=phase_table,
                progress=progress, ideal_holds=ideal, creep_limit=creep_limit,
                bending_scale=kappa, command=cmd,
                density=None if mat is None else mat.density,
            )  # fmt: skip
            if der_answer is not None:
                answers.append(der_answer)
    i = _decide(answers)
    if i is not None:
        answers[i] = replace(answers[i], decides=True)
    dec = None if i is None else answers[i]
    # next step
    der_silent = der is not None and der.get("holds") is None and free == 0
    if dec is None:
        if simulable:
            next_step = (
                f"next: {cmd} (one DER run of this geometry, {SIMULATE_COST}) decides it"
                + ("" if E is not None else "; MATERIAL: one of the presets, or give "
                   "--youngs-modulus")
            )  # fmt: skip
        else:
            next_step = "next: no model here applies inside its validity; test the knot"
    elif _der_knot(key) and free == 0 and E is None:
        next_step = (
            "next: give --material or --youngs-modulus (material=, youngs_modulus=) to "
            "check against the DER phase table"
        )
    elif simulable and der_silent and not simulate and dec.model != "DER-table":
        next_step = f"next: {cmd} checks it with one DER run of this geometry"
    warns = _warnings(mu, mu_rr, d, D, load, E, theta)
    return Verdict(
        knot=key,
        holds=None if dec is None else bool(dec.holds),
        margin=math.nan if dec is None else float(dec.margin),
        decided_by=None if dec is None else dec.model,
        inside_validity=dec is not None,
        answers=tuple(answers),
        validity=() if dec is None else tuple(dec.validity),
        assumptions=tuple(assumptions),
        warnings=warns,
        next_step=next_step,
        creep=creep,
        inputs=inputs,
        der=der,
        notes=tuple(notes),
        shape=shape,
    )


def _hold_bend(
    key, *, rod_diameter, post_diameter, mu, load, free_end_load, mu_rr, wrap_angle, material,
    youngs_modulus, simulate, phase_table, progress, bending_scale=None,
):  # fmt: skip
    """A bend (two ropes joined, pulled apart): no closed form and no table; with
    ``simulate`` one DER pull of the bend scene, its slip load against the load."""
    from knotmech.analytic.hitch import ModelAnswer
    from knotmech.errors import check_nonnegative, check_positive

    d = float(check_positive("rod_diameter", rod_diameter))
    mu = float(check_nonnegative("mu", mu))
    load = float(check_positive("load", load))
    for name, val in (("post_diameter", post_diameter), ("mu_rr", mu_rr),
                      ("wrap_angle", wrap_angle), ("phase_table", phase_table)):  # fmt: skip
        if val is not None:
            raise InputError(
                f"{name} does not apply to a bend ({key}: two ropes pulled apart, no post; "
                "mu is the rope-rope friction)"
            )
    if float(free_end_load or 0.0) != 0.0:
        raise InputError(f"free_end_load does not apply to a bend ({key}: no free end)")
    E, mat, e_source = _youngs_modulus(material, youngs_modulus)
    kappa, k_source = _bending_scale(mat, bending_scale)
    inputs = {"rod_diameter": d, "mu": mu, "load": load, "bending_scale": kappa}
    if mat is not None:
        inputs["material"] = mat.key
    if E is not None:
        inputs["youngs_modulus"] = E
    cmd = simulate_command(key, d=d, D=None, mu=mu, load=load,
                           material=None if mat is None else mat.key,
                           youngs_modulus=youngs_modulus,
                           bending_scale=bending_scale)  # fmt: skip
    warns = _warnings(mu, None, d, math.inf, load, E, None)
    assumptions = ([e_source] if e_source else []) + [k_source]
    note = (
        f"{key} is a bend (Patil et al., Science 2020): no closed form and no DER table; "
        "one DER pull of the bend scene (knotmech.scenes.bends.bend) gives its slip load"
    )
    if not simulate:
        return Verdict(
            knot=key, holds=None, margin=math.nan, decided_by=None, inside_validity=False,
            answers=(), assumptions=tuple(assumptions), warnings=warns,
            next_step=f"next: {cmd} (one DER pull of the bend, 1-3 minutes) decides it",
            inputs=inputs, notes=(note,),
        )  # fmt: skip
    if E is None:
        from knotmech.materials import material_names

        raise InputError(
            "simulate needs the rope's stiffness: give material (one of "
            f"{', '.join(material_names())}) or youngs_modulus"
        )
    from knotmech.scenes.bends import bend

    kw = {"density": mat.density} if mat is not None else {}
    if kappa != 1.0:
        kw["bending_scale"] = kappa
    r = bend(key, rod_diameter=d, youngs_modulus=E, mu_rod_rod=mu, progress=progress, **kw)
    der = {
        "source": "simulation", "scene": "knotmech.scenes.bends.bend", "kind": key,
        "verdict": r.verdict, "slip_load": r.slip_load, "max_force": r.max_force,
        "pull_speed": r.pull_speed, "status": r.status, "message": r.message,
        "topology_preserved": bool(r.topology_preserved),
        "wall_s": float(r.stats.get("wall_s", math.nan)),
    }  # fmt: skip
    if r.verdict == "slips" and math.isfinite(r.slip_load):
        holds, capacity = load < r.slip_load, float(r.slip_load)
        der["message"] = (f"DER pull of the {key}: slips at {r.slip_load:.4g} N "
                          f"(the largest pull force before its tail drew in)")  # fmt: skip
    elif r.verdict == "holds" and load <= r.max_force:
        holds, capacity = True, float(r.max_force)
        der["message"] = (f"DER pull of the {key}: did not slip up to {r.max_force:.4g} N, "
                          "the largest force of the pull")  # fmt: skip
    else:
        holds, capacity = None, math.nan
        der["message"] = (
            f"DER pull of the {key}: {r.verdict or 'failed'} ({r.message}); the load "
            + (f"{load:.4g} N is above the largest pull force {r.max_force:.4g} N"
               if r.verdict == "holds" else "is not decided")
        )  # fmt: skip
    der["holds"] = holds
    answers = ()
    if holds is not None:
        answers = (
            ModelAnswer(
                model="DER-simulation", holds=bool(holds), margin=capacity / load - 1,
                capacity=capacity, critical_mu=math.nan, decides=True, inside_validity=True,
                assumptions=(
                    f"two elastic rods (B = kappa E pi d^4/64, kappa = {kappa:g}), sticking "
                    "rod-rod friction, "
                    f"set by hand then pulled apart at {r.pull_speed * 1e3:g} mm/s",
                    "slip: a tail draws in by more than 2 d while the pull force stays "
                    "within 10 % of its largest value",
                ),
                validity=("one DER pull of the bend at this d, E and mu",),
                reference="Patil, Sandt, Kolle & Dunkel, Science 367, 71 (2020); "
                "knotmech.scenes.bends",
                notes=(der["message"],),
            ),
        )  # fmt: skip
    return Verdict(
        knot=key, holds=holds, margin=answers[0].margin if answers else math.nan,
        decided_by="DER-simulation" if answers else None, inside_validity=bool(answers),
        answers=answers, validity=answers[0].validity if answers else (),
        assumptions=tuple(assumptions), warnings=warns,
        next_step="" if answers else "next: test the knot (the DER pull did not decide)",
        inputs=inputs, der=der, notes=(note,),
    )  # fmt: skip


def hold_verdict(
    knot,
    *,
    rod_diameter,
    post_diameter,
    mu,
    load,
    free_end_load=0.0,
    mu_rr=None,
    wrap_angle=None,
) -> Verdict:
    """Deprecated alias of :func:`hold` (same verdict; use ``knotmech.hold``)."""
    warnings.warn(
        "knotmech.hold_verdict is deprecated; use knotmech.hold (same verdict, more answers)",
        DeprecationWarning,
        stacklevel=2,
    )
    return hold(
        knot,
        rod_diameter=rod_diameter,
        post_diameter=post_diameter,
        mu=mu,
        load=load,
        free_end_load=free_end_load,
        mu_rr=mu_rr,
        wrap_angle=wrap_angle,
    )


# --------------------------------------------------------------------------- plot
PLOT_FORMATS = ("png", "pdf", "svg")


def check_plot_path(path) -> Path:
    """Refuse a plot path whose folder is missing or whose format is not png/pdf/svg."""
    p = Path(path)
    fmt = p.suffix.lower().lstrip(".")
    if fmt not in PLOT_FORMATS:
        raise InputError(
            f"plot {str(path)!r}: the format must be one of {', '.join(PLOT_FORMATS)} "
            "(from the file name)"
        )
    if not p.parent.is_dir():
        raise InputError(f"plot {str(path)!r}: folder {str(p.parent)!r} does not exist")
    return p


def plot_verdict(verdict: Verdict, path, *, phase_table=None) -> Path:
    """Draw the DER answer: the query on the phase diagram, or the simulated knot.

    Table answer: one panel per friction table used, grid points held (dots) and
    slipped (crosses), the interpolated upper boundary and the query (star, labelled with
    the verdict). Simulation: the knot's centreline at the end of the hold in 3-D,
    coloured by the tension T(s), with the post (axis z through the origin).

    Raises
    ------
    InputError
        The verdict has neither a table answer nor a simulated knot, or a bad path.
    """
    p = check_plot_path(path)
    if verdict.shape is not None:
        return _plot_knot(verdict, p)
    der = verdict.der or {}
    if der.get("source") != "table" or not der.get("mu_tables"):
        raise InputError(
            "plot: there is no DER answer to draw (a hitch with a DER table, free end, E "
            "given, inside the table's reach, or simulate)"
        )
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt
    import matplotlib.ticker
    import numpy as np

    tables = (_shipped_hold_table(verdict.knot, der.get("table_bending_scale", 1.0))
              if phase_table is None else _load_user_table(phase_table))  # fmt: skip
    from knotmech.scenes import phase_table as pt

    if isinstance(tables, pt.HoldTable):
        lim = (verdict.creep or {}).get("limit_d_per_protocol_s") or pt.CREEP_LIMIT
        used = [tables.slice(m, creep_limit=lim) for m in der["mu_tables"]]
    else:
        used = [tables.table(m) for m in der["mu_tables"]]
    fig, axes = plt.subplots(1, len(used), figsize=(5.2 * len(used), 4.2), squeeze=False)
    for ax, t in zip(axes[0], used, strict=True):
        held = [(q.d_over_2R, q.t_over_EA) for q in t.points if q.holds]
        slip = [(q.d_over_2R, q.t_over_EA) for q in t.points if not q.holds]
        if held:
            ax.scatter(*zip(*held, strict=True), marker="o", color="tab:green", label="held")
        if slip:
            ax.scatter(*zip(*slip, strict=True), marker="x", color="tab:red", label="slipped")
        xs, lo, hi, _ = t.boundary()
        ok = np.isfinite(hi)
        if ok.any():
            ax.plot(xs[ok], 0.5 * (lo[ok] + hi[ok]), "k--", lw=1, label="upper boundary")
        ax.scatter([der["d_over_2R"]], [der["t_over_EA"]], marker="*", s=220,
                   color="tab:blue", zorder=5, label=f"query: {verdict.state}")  # fmt: skip
        ax.set_xscale("log")
        ax.set_yscale("log")
        cols = sorted({q.d_over_2R for q in t.points})  # ticks at the table's columns
        ax.xaxis.set_major_locator(matplotlib.ticker.FixedLocator(cols))
        ax.xaxis.set_major_formatter(matplotlib.ticker.FixedFormatter([f"{c:.3g}" for c in cols]))
        ax.xaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())
        ax.set_xlabel("d/2R")
        ax.set_ylabel("T_high/EA")
        ax.set_title(f"{verdict.knot}, free end, mu = mu_rr = {t.mu:g}", fontsize=10)
        ax.legend(loc="best", fontsize=8, framealpha=0.6)
    fig.tight_layout()
    fig.savefig(p)
    plt.close(fig)
    return p


def _plot_knot(verdict: Verdict, p: Path) -> Path:
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt
    import numpy as np
    from mpl_toolkits.mplot3d.art3d import Line3DCollection

    sh = verdict.shape
    x = np.asarray(sh["positions"], dtype=float)
    t = np.asarray(sh["tension"], dtype=float)
    segs = np.stack([x[:-1], x[1:]], axis=1) * 1e3  # mm
    fig = plt.figure(figsize=(6.4, 5.6))
    ax = fig.add_subplot(projection="3d")
    lc = Line3DCollection(segs, cmap="viridis", linewidths=3)
    lc.set_array(t[: len(segs)])
    ax.add_collection3d(lc)
    R = 0.5 * float(sh["post_diameter"]) * 1e3
    zlo, zhi = segs[..., 2].min(), segs[..., 2].max()
    phi = np.linspace(0, 2 * np.pi, 41)
    for z in np.linspace(zlo, zhi, 5):
        ax.plot(R * np.cos(phi), R * np.sin(phi), np.full_like(phi, z), color="0.7", lw=0.6)
    lim = np.abs(segs[..., :2]).max() * 1.05
    ax.set_xlim(-lim, lim)
    ax.set_ylim(-lim, lim)
    ax.set_zlim(zlo, zhi)
    ax.set_box_aspect((1.0, 1.0, max(0.25, min(1.0, (zhi - zlo) / (2 * lim)))))
    ax.set_xlabel("x [mm]")
    ax.set_ylabel("y [mm]")
    ax.set_zlabel("z [mm] (post axis)")
    fig.colorbar(lc, ax=ax, shrink=0.7, pad=0.12, label="tension T(s) [N]")
    ax.set_title(f"{verdict.knot}: {verdict.state} (DER simulation, last frame)")
    fig.tight_layout()
    fig.savefig(p)
    plt.close(fig)
    return p


def __getattr__(name: str):
    """``COW_LOADING``: the loading the cow hitch's DER scene, table and ``simulate`` model
    (its registry record's ``loading``)."""
    if name == "COW_LOADING":
        return knots.get("cow-hitch").loading
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


# ``knotmech.hold(...)``: the module itself is callable (the package attribute
# ``knotmech.hold`` is this module once it is imported, so the call must work on it).
class _CallableModule(types.ModuleType):
    def __call__(self, *args, **kwargs):
        return hold(*args, **kwargs)


_module = sys.modules[__name__]
_module.__class__ = _CallableModule
_module.__signature__ = inspect.signature(hold)

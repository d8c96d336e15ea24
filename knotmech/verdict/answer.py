"""The verdict object of :func:`knotmech.hold`: :class:`Verdict`, :class:`InputWarning` and
the margin in words (:func:`format_margin`); :meth:`Verdict.to_dict` writes strict JSON through
:mod:`knotmech._json` (a non-finite number is null, with a flag where it matters)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from knotmech import _json

__all__ = ["InputWarning", "Verdict", "format_force", "format_margin"]


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
    capacity : Capacity or None
        The load the knot takes (:class:`knotmech.verdict.capacity.Capacity`): the lower of
        its slip load and its breaking load [N], with bands and sources.
    friction : dict or None
        The friction: ``range`` [low, high] of the material on ``post_material`` when mu was
        not given (with its ``source``; the verdict is at the low end), the verdict over it
        (``words``, ``holds_at_low``, ``holds_at_high``) and ``critical_mu``, the least mu
        at which the whole verdict holds at this load
        (:func:`knotmech.verdict.friction.critical_mu`; 0: without friction; inf, null in
        JSON with ``critical_mu_none``: none up to 1.5; NaN, null: not found or not searched,
        ``critical_mu_text`` says why), also with a given mu; a hitch's
        ``model_critical_mu`` (and its text): the deciding model's own. ``published`` says
        whether the range is
        published; where it is not (``published`` False, ``source`` None), ``range`` is the
        searched 0.05-1.5, ``missing`` and ``why`` say what is missing,
        ``published_post_materials`` where a coefficient exists, and ``verdict_at_mu``
        (``verdict_at``: ``low end``, ``critical mu`` or ``top of the search``) the mu at
        which the verdict's numbers (slip load, margin, capacity) are computed
        (:func:`knotmech.verdict.friction.unknown_friction_verdict`).
    fails_by : str or None
        ``"slip"`` or ``"break"`` when it does not hold (``"break"``: the load is at or above
        the knot's breaking load; the state is then ``BREAKS``).
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
    capacity: object = None
    fails_by: str | None = None
    friction: dict | None = None

    @property
    def deciding(self):
        """The deciding :class:`~knotmech.analytic.hitch.ModelAnswer`, None when undecided."""
        return next((a for a in self.answers if a.decides), None)

    @property
    def state(self) -> str:
        """``"HOLDS"``, ``"SLIPS"``, ``"BREAKS"`` or ``"UNDECIDED"``."""
        if self.holds is False and self.fails_by == "break":
            return "BREAKS"
        return {True: "HOLDS", False: "SLIPS", None: "UNDECIDED"}[self.holds]

    def summary(self) -> str:
        """The answer in one line: verdict, slip load, breaking load, the load's fraction of
        the capacity and the deciding model (or, undecided, the next step)."""
        f = self.friction or {}
        if f.get("published") is False:
            return self._unknown_friction_summary(f)
        head = f"verdict: {self.state}: " + capacity_words(self.capacity, self.inputs.get("load"))
        if self.holds is None:
            why = "" if self.decided_by is not None else f" ({self._undecided_why()})"
            return f"{head}{why}; {self.next_step}" if self.next_step else head + why
        return f"{head}; decided by the {self.decided_by} model (inputs inside its validity)"

    def _undecided_why(self) -> str:
        """Why no model decides, for the first line: the DER table's neighbouring runs that
        contradict each other in mu are named (:meth:`HoldTable.against_mu`), and the tables'
        answer at each kappa of the rope's range when it depends on kappa
        (:mod:`knotmech.verdict.kappa`)."""
        from knotmech.verdict.tables import AGAINST_MU

        der = self.der or {}
        why = "no model inside its validity decides"
        if AGAINST_MU in str(der.get("message", "")):
            why += f"; the DER table's neighbouring runs {AGAINST_MU}"
        rng = der.get("kappa_range")
        if rng and not rng["agree"] and any(r["holds"] is not None for r in rng["readings"]):
            what = ("' answer depends on the rope's bending stiffness over its" if rng["depends"]
                    else " do not answer at every kappa of the rope's")  # fmt: skip
            why += (f"; the DER tables{what} estimated range kappa "
                    f"{rng['range'][0]:g}-{rng['range'][1]:g} ({rng['words']})")  # fmt: skip
        return why

    def _unknown_friction_summary(self, f: dict) -> str:
        """The first line without a published friction coefficient: the verdict over the
        searched range, why the friction is unknown, the mu the numbers are at and, when
        undecided, how to decide (:func:`knotmech.verdict.friction.unknown_friction_verdict`)."""
        at = f"at mu = {f['verdict_at_mu']:.3g}"
        if f["verdict_at"] == "critical mu":
            at = f"at mu* = {f['verdict_at_mu']:.3g}"
        cap = capacity_words(self.capacity, self.inputs.get("load"))
        head = f"verdict: {self.state}: {f['words']} ({f['missing']}); {at}: {cap}"
        if self.holds is None:
            return f"{head}; {self.next_step}" if self.next_step else head
        return f"{head}; decided by the {self.decided_by} model (inputs inside its validity)"

    def to_dict(self) -> dict:
        """Strict JSON-ready dict: non-finite numbers are null (with a flag where it matters)."""
        return _json.jsonable(
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
                "fails_by": self.fails_by,
                "friction": self.friction,
                "critical_mu_none": bool(
                    self.friction is not None
                    and math.isinf(self.friction.get("critical_mu", math.nan))
                ),
                "capacity": (
                    None
                    if self.capacity is None
                    else self.capacity.to_dict(float(self.inputs.get("load", math.nan)))
                ),
            }
        )

    def friction_line(self, verbose: bool = False) -> str:
        """The friction in one line: the range and where it comes from, the verdict over it
        and the critical mu ("" when not computed); ``verbose`` adds the deciding model's own
        critical mu (``model_critical_mu``) where it differs from the whole verdict's."""
        f = self.friction
        if not f:
            return ""
        parts = []
        if f.get("published") is False:
            lo, hi = f["range"]
            dflt = ", the default post material" if f.get("default_post_material") else ""
            parts.append(f"unknown for {self.inputs.get('material', 'the rope')} on "
                         f"{f['post_material']} (none published{dflt}), searched over mu "
                         f"{lo:.3g}-{hi:.3g}; {f['words']}; numbers at mu = "
                         f"{f['verdict_at_mu']:.3g}, the {f['verdict_at']}")  # fmt: skip
        elif f.get("range"):
            lo, hi = f["range"]
            mat = self.inputs.get("material", "the rope")
            dflt = " (default post material)" if f.get("default_post_material") else ""
            rng = f"{lo:.3g}" if lo == hi else f"{lo:.3g}-{hi:.3g}"
            parts.append(f"mu {rng} for {mat} on {f['post_material']}{dflt}, "
                         f"verdict at mu = {lo:.3g}")  # fmt: skip
            if "words" in f:
                parts.append(f["words"])
        m = f.get("critical_mu", math.nan)
        if math.isinf(m):
            parts.append(f"critical mu: none ({f.get('critical_mu_text', '')})")
        elif not math.isnan(m):
            parts.append(f"critical mu {m:.3g} ({f.get('critical_mu_text', '')})")
        elif "critical_mu_text" in f:
            parts.append(f"critical mu: {f['critical_mu_text']}")
        if verbose and _adds(f.get("model_critical_mu", math.nan), m):
            mm = f["model_critical_mu"]
            val = "none" if math.isinf(mm) else f"{mm:.3g}"
            parts.append(f"the deciding model alone: critical mu {val} "
                         f"({f['model_critical_mu_text']})")  # fmt: skip
        return "friction: " + "; ".join(parts) if parts else ""

    def to_json(self) -> str:
        """:meth:`to_dict` as strict JSON text (``allow_nan=False``)."""
        return _json.dumps(self.to_dict(), indent=2)


def format_force(value: float) -> str:
    """A load in words: ``0.5 N``, ``200 N``, ``1.4 kN``, ``13 kN`` (three figures below
    1 kN, two above)."""
    v = float(value)
    if abs(v) < 1e3:
        return f"{v:.3g} N"
    return f"{v / 1e3:.2g} kN" if abs(v) < 1e5 else f"{v / 1e3:.3g} kN"


def _band(lo: float, hi: float) -> str:
    """``1.1-1.9 kN`` (one unit when both are in kN or both in N)."""
    a, b = format_force(lo), format_force(hi)
    if a.split()[1] == b.split()[1]:
        return f"{a.split()[0]}-{b}"
    return f"{a} to {b}"


def _slip_words(slip) -> str:
    if slip is None:
        return "slip load not known"
    if slip.bounded:
        if slip.value == 0:
            return "slips at any load at this friction"
        if slip.low == slip.high:
            return f"slips near {format_force(slip.value)} ({slip.source.split(' (')[0]})"
        if slip.low == 0 and slip.value >= slip.high:  # slipped at the lightest load run
            return f"slips at or below {format_force(slip.high)}"
        return f"slips near {format_force(slip.value)} ({_band(slip.low, slip.high)})"
    if "self-locking" in slip.source:
        up = f" up to {format_force(slip.low)}" if slip.low > 0 else ""
        return f"friction alone cannot unlock it{up}"
    if slip.source.startswith("the DER pull"):  # a bend's or loop's pull that held
        return f"no slip up to {format_force(slip.low)} ({slip.source})"
    return f"no slip up to {format_force(slip.low)} (nothing slipped in the DER table)"


def _break_words(cap) -> str:
    b = cap.breaking
    if b is None:
        return cap.breaking_note
    if cap.efficiency is None:
        return f"breaks near {format_force(b.value)} (the rope's own strength)"
    eta = cap.efficiency[0] * 100
    return f"breaks near {format_force(b.value)} (knot efficiency {eta:.0f} %)"


def capacity_words(cap, load) -> str:
    """The capacity in words: slip load and band, breaking load and knot efficiency, and the
    load as a percentage of whichever comes first."""
    if cap is None:
        return "capacity not computed"
    text = f"{_slip_words(cap.slip)}, {_break_words(cap)}"
    if not cap.decided or load is None:
        return text
    f = cap.fraction(float(load))
    which = "slip load" if cap.limited_by == "slip" else "breaking load"
    if math.isinf(f):
        return f"{text}; any load exceeds the {which}"
    if f >= 10:
        return f"{text}; {format_force(float(load))} is {f:.3g} times the {which}"
    pct = f * 100
    return (
        f"{text}; {format_force(float(load))} is {pct:.0f} % of the {which}"
        if pct >= 10
        else (f"{text}; {format_force(float(load))} is {pct:.2g} % of the {which}")
    )


def format_margin(margin: float) -> str:
    """``+12.3 %``, ``self-locking (friction alone cannot unlock it)`` or ``not computed``
    (issue 23: never "unbounded": the load a self-locking knot takes is its capacity)."""
    if math.isnan(margin):
        return "not computed"
    if math.isinf(margin):
        return "self-locking (friction alone cannot unlock it)" if margin > 0 else "-inf"
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


def _adds(model_mu: float, mu_star: float) -> bool:
    """Whether the deciding model's own critical mu says more than the verdict's mu*: it
    is a number (or none) and differs from mu* by more than the search's resolution."""
    from knotmech.verdict.friction import MU_RESOLUTION

    if math.isnan(model_mu):
        return False
    if math.isinf(model_mu) or math.isinf(mu_star) or math.isnan(mu_star):
        return not (math.isinf(model_mu) and math.isinf(mu_star))
    return abs(model_mu - mu_star) > MU_RESOLUTION

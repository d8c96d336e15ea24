"""The verdict object of :func:`knotmech.hold`: :class:`Verdict`, :class:`InputWarning` and
the margin in words (:func:`format_margin`); :meth:`Verdict.to_dict` writes strict JSON through
:mod:`knotmech._json` (a non-finite number is null, with a flag where it matters)."""

from __future__ import annotations

import math
from dataclasses import dataclass, field

from knotmech import _json

__all__ = ["InputWarning", "Verdict", "format_margin"]


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
            }
        )

    def to_json(self) -> str:
        """:meth:`to_dict` as strict JSON text (``allow_nan=False``)."""
        return _json.dumps(self.to_dict(), indent=2)


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

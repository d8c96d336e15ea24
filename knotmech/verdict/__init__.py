r"""Does a rope tied to a post hold a load? The verdict of knotmech, in one place.

:func:`hold` is the one entry point (``knotmech.hold(knot, ...)``; the command
``knotmech hold`` and the tour call it and only print). It collects every model's
answer and decides by one rule (:data:`RULE`):

- the closed forms of :mod:`knotmech.analytic.hitch` (ideal rope, thick nip;
  ideal and finite-thickness capstan), always;
- for the hitches with a free end (clove hitch, two half hitches, round turn and two half
  hitches, cow hitch with one leg free), the DER hold/slip diagram (the clove-hitch paper,
  Extreme Mech. Lett., DOI 10.1016/j.eml.2022.101788, sec. 8 and Fig. 4): the shipped
  anchor-law hold tables over real-rope ranges (:class:`knotmech.verdict.tables.
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

**The capacity** (issue 23; :mod:`~knotmech.verdict.capacity`): every verdict carries the
load the knot takes, the lower of its slip load (the DER hold table's critical load at the
user's d/2R and friction, with its band, or the deciding closed form's) and its breaking
load (:func:`knotmech.strength.knot_breaking_load`); a self-locking closed form bounds the
slip load from below only, so without a table or a breaking load above it the verdict is
undecided, never "unbounded". Without ``mu``, the material's published friction range on
``post_material`` (:mod:`~knotmech.verdict.friction`); where none is published, the
verdict over mu 0.05-1.5 (HOLDS only if it holds at 0.05, else undecided with the critical
mu unless it slips at 1.5); the critical mu is always given.

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
  range never (:meth:`knotmech.verdict.tables.HoldTable.lookup`).

Implausible inputs (mu or mu_rr > 2, strain above 10 %, a wrap beyond 20 turns, a
rope thicker than its post) give an :class:`InputWarning` naming the input.

The subpackage, one room each: :mod:`~knotmech.verdict.criterion` (the creep criterion, its
limit and the protocol, defined once), :mod:`~knotmech.verdict.tables` (the table types and
their lookups), :mod:`~knotmech.verdict.build` (one DER point, a table through
:func:`knotmech.sweep.sweep`), :mod:`~knotmech.verdict.rule` (the deciding rule),
:mod:`~knotmech.verdict.answer` (the :class:`Verdict` object), :mod:`~knotmech.verdict.der`
(the DER answer), :mod:`~knotmech.verdict.decide` (:func:`hold` itself),
:mod:`~knotmech.verdict.bend` (the bends), :mod:`~knotmech.verdict.scope` (which knots and
models, from the registry :mod:`knotmech.knots`), :mod:`~knotmech.verdict.plot` (drawing it).
``knotmech.hold`` is the function :func:`hold` (there is no module of that name).
"""

from __future__ import annotations

from knotmech.verdict.answer import InputWarning, Verdict, format_margin
from knotmech.verdict.command import SIMULATE_COST, SIMULATE_MAX_CPU_S, simulate_command
from knotmech.verdict.criterion import CREEP_CRITERION, CREEP_LIMIT, CREEP_WINDOW
from knotmech.verdict.decide import hold, hold_verdict
from knotmech.verdict.der import BENDING_SCALE_FACTOR, ROD_RATE_FACTOR
from knotmech.verdict.inputs import MU_PLAUSIBLE, STRAIN_LIMIT, WRAP_TURNS_PLAUSIBLE
from knotmech.verdict.plot import PLOT_FORMATS, check_plot_path, plot_verdict
from knotmech.verdict.rule import RULE
from knotmech.verdict.scope import (
    DER_HITCHES,
    KNOT_NAMES,
    can_simulate,
    has_der_answer,
    is_bend,
    knot_key,
)

__all__ = [
    "hold",
    "Verdict",
    "InputWarning",
    "KNOT_NAMES",
    "DER_HITCHES",
    "RULE",
    "knot_key",
    "is_bend",
    "has_der_answer",
    "can_simulate",
    "hold_verdict",
    "plot_verdict",
    "check_plot_path",
    "format_margin",
    "simulate_command",
    "SIMULATE_COST",
    "SIMULATE_MAX_CPU_S",
    "PLOT_FORMATS",
    "STRAIN_LIMIT",
    "MU_PLAUSIBLE",
    "WRAP_TURNS_PLAUSIBLE",
    "BENDING_SCALE_FACTOR",
    "ROD_RATE_FACTOR",
    "CREEP_CRITERION",
    "CREEP_LIMIT",
    "CREEP_WINDOW",
]

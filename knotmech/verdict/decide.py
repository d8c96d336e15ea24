r"""The hold verdict: :func:`hold` collects every model's answer and decides by one rule.

See :mod:`knotmech.verdict` for the models, their validity and the rule. A hitch on a post
(or a capstan) is answered here; a bend by :mod:`knotmech.verdict.bend`.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, replace

from knotmech import knots
from knotmech.errors import InputError, check_nonnegative, check_positive
from knotmech.verdict.answer import Verdict
from knotmech.verdict.axial import AXIAL_HOLD_KNOTS, BOTH_LEGS_KNOTS
from knotmech.verdict.command import SIMULATE_COST, SIMULATE_MAX_CPU_S, simulate_command
from knotmech.verdict.friction import (
    MU_SEARCH_MAX,
    critical_mu,
    friction_preset,
    range_words,
    unknown_friction_verdict,
)
from knotmech.verdict.inputs import STRAIN_LIMIT, _bending_scale, _warnings, _youngs_modulus
from knotmech.verdict.kappa import RANGE_REFUSAL, against_readings, over_range
from knotmech.verdict.rule import decide, with_validity
from knotmech.verdict.scope import BENDS, can_simulate, has_der_answer, knot_key

#: the ``--mu`` of a suggested DER run when no friction coefficient is published
MU_PLACEHOLDER = "MU"
#: what :data:`MU_PLACEHOLDER` stands for
MU_PLACEHOLDER_WORDS = (
    "this rope's friction coefficient on this post, measured; none is published, and a run "
    "at an assumed one decides nothing"
)
#: the loops (their eye round a pin): the registry's
LOOP_NAMES = tuple(k.name for k in knots.records(family="loop"))

__all__ = ["hold", "hold_verdict"]


def hold(
    knot,
    *,
    rod_diameter,
    post_diameter=None,
    mu=None,
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
    post_material=None,
    pin_diameter=None,
    bisect=0,
    max_cpu_s=None,
) -> Verdict:
    r"""Does a rope tied to a post hold a load? The verdict, every model's answer and why.

    Parameters
    ----------
    knot : str
        One of :data:`KNOT_NAMES` (``capstan``, ``clove-hitch``, ``two-half-hitches``,
        ``round-turn``, ``round-turn-two-half-hitches``, ``cow-hitch`` (also girth hitch,
        lark's head), the bends ``reef``, ``granny``, ``thief``, ``grief`` and the tied
        bends, and the loops ``bowline``, ``figure-eight-loop``, ``alpine-butterfly`` (their
        eye round a pin: ``pin_diameter``). Other knots raise a one-line
        :class:`~knotmech.errors.InputError` listing these.
    rod_diameter, post_diameter : float
        Rope diameter d and post diameter D [m], > 0 (no post for a bend: None).
    mu : float, optional
        Rope-post friction coefficient [-], >= 0 (a bend: rope-rope). The critical mu
        ``friction["critical_mu"]`` is the least mu at which the whole verdict holds at this
        load (:func:`knotmech.verdict.friction.critical_mu`; not searched with ``simulate``
        nor for the knots only a DER run answers). Without it, the
        published range of ``material`` on ``post_material``
        (:func:`knotmech.strength.friction_range`): the verdict is given at its low end and
        scanned over the range (:attr:`Verdict.friction`). Where none is published for the
        pair, the friction is unknown and the verdict covers the searched range
        [:data:`~knotmech.verdict.friction.MU_UNKNOWN_LOW`,
        :data:`~knotmech.verdict.friction.MU_SEARCH_MAX`]
        (:func:`knotmech.verdict.friction.unknown_friction_verdict`): HOLDS only if it holds
        at the low end, SLIPS (or BREAKS) only if it does not hold at the top, else
        undecided with the critical mu; ``friction["published"]`` is False,
        ``friction["verdict_at_mu"]`` the mu of its numbers; ``simulate`` then needs ``mu``.
    pin_diameter : float, optional
        A loop's pin diameter [m] (the pin its eye goes round), required for a loop and
        refused for any other knot.
    post_material : str, optional
        The post's material for the friction range when ``mu`` is not given: ``steel``
        (default, :data:`knotmech.verdict.friction.DEFAULT_POST_MATERIAL`), ``aluminium``,
        ``wood``, ``rope`` (:func:`knotmech.strength.counterface_names`). ``mu`` overrides.
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
    bisect : int
        With ``simulate``, a hitch on a post with a free end: this many more DER runs (1 to
        :data:`knotmech.verdict.capacity.MAX_BISECT_RUNS`) bisect its slip load, from the
        band the table and the first run leave (:func:`knotmech.verdict.capacity.bisect_slip`;
        a band open above is probed first at
        :data:`~knotmech.verdict.capacity.BISECT_CEILING` EA, the top of the DER tables).
        Each run costs what the first does; the runs are listed in ``der["bisection"]``.
        0 (default): no bisection.
    max_cpu_s : float, optional
        [s] With ``simulate``, a hitch on a post: the CPU budget of each DER run (default
        :data:`knotmech.verdict.SIMULATE_MAX_CPU_S`, 900 s). A run that spends it stops and
        the DER does not decide (the verdict says so): a soft rope's run is stretched in
        simulated time, and one heavy kappa-0.003 point took 1829 s.
    progress : bool
        Progress bar on stderr for ``simulate``.
    creep_limit : float, optional
        The DER hold criterion's limit [rod diameters per second]: the hitch holds when
        its loose end creeps slower than this over the last second of the hold once the
        load is on (default :data:`knotmech.verdict.criterion.CREEP_LIMIT`, 1e-3 d/s),
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
        does not read; no ``mu`` and no ``material``; ``simulate`` without ``mu`` where no
        friction coefficient is published.

    Examples
    --------
    >>> v = hold("clove-hitch", rod_diameter=4e-3, post_diameter=30e-3, mu=0.3,
    ...          load=1.47, material="vps32")
    >>> v.holds, v.decided_by, v.der["rule"]
    (True, 'DER-table', 'grid')
    >>> round(v.creep["speed_d_per_s"], 7)
    5.09e-05
    """
    key = knot_key(knot)
    _check_sizes(rod_diameter, post_diameter, load)
    bisect = _check_bisect(key, bisect, simulate)
    budget = _check_budget(key, max_cpu_s, simulate)
    kw = dict(
        rod_diameter=rod_diameter, post_diameter=post_diameter, load=load,
        free_end_load=free_end_load, mu_rr=mu_rr, wrap_angle=wrap_angle, material=material,
        youngs_modulus=youngs_modulus, phase_table=phase_table, creep_limit=creep_limit,
        bending_scale=bending_scale, pin_diameter=pin_diameter,
    )  # fmt: skip
    friction = None
    if mu is None:
        preset = friction_preset(key, material, post_material)
        if not preset.published:
            return _unknown_friction(preset, key, simulate=simulate, **kw)
        mu = preset.low
        friction = preset.as_dict()
    v = _verdict_at(key, mu, simulate=simulate, progress=progress, bisect=bisect, top=True,
                    max_cpu_s=budget, **kw)  # fmt: skip
    part = _friction_part(key, mu, v, friction, simulate, lambda m: _verdict_at(key, m, **kw))
    if part.get("holds_at_low") is True and part.get("holds_at_high") is False:
        # holds at the range's low end, slips at its high end: no monotone reading decides
        v = replace(v, holds=None, fails_by=None,
                    next_step=f"{part['words']}; next: ask at a measured mu (--mu)")  # fmt: skip
    return replace(v, friction=part)


def _verdict_at(
    key, mu, *, rod_diameter, post_diameter, load, free_end_load, mu_rr, wrap_angle, material,
    youngs_modulus, phase_table, creep_limit, bending_scale, pin_diameter, simulate=False,
    progress=False, bisect=0, top=False, mu_unknown=False, max_cpu_s=SIMULATE_MAX_CPU_S,
) -> Verdict:  # fmt: skip
    """The verdict at friction ``mu`` (keywords of :func:`hold`), without the critical-mu
    search: what the search asks at each mu. ``top``: the question itself (a hitch's
    ``friction`` then carries its deciding model's own critical mu); ``mu_unknown``: no
    friction coefficient is published, so the DER command asks for a measured one."""
    if knots.get(key).family == "loop":
        from knotmech.verdict.loop import hold_loop

        return hold_loop(
            key, rod_diameter=rod_diameter, post_diameter=post_diameter,
            pin_diameter=pin_diameter, mu=mu, load=load, free_end_load=free_end_load,
            mu_rr=mu_rr, wrap_angle=wrap_angle, material=material,
            youngs_modulus=youngs_modulus, simulate=simulate, phase_table=phase_table,
            progress=progress, bending_scale=bending_scale,
        )  # fmt: skip
    if pin_diameter is not None:
        raise InputError(f"pin_diameter applies to a loop ({', '.join(LOOP_NAMES)}), not {key}")
    if key in BENDS:
        from knotmech.verdict.bend import hold_bend

        v = hold_bend(
            key, rod_diameter=rod_diameter, post_diameter=post_diameter, mu=mu, load=load,
            free_end_load=free_end_load, mu_rr=mu_rr, wrap_angle=wrap_angle, material=material,
            youngs_modulus=youngs_modulus, simulate=simulate, phase_table=phase_table,
            progress=progress, bending_scale=bending_scale,
        )  # fmt: skip
        return _bend_capacity(v, material)
    if key in AXIAL_HOLD_KNOTS:  # the Prusik: pulled along its pole (verdict/axial.py)
        from knotmech.verdict.axial import hold_axial, with_capacity

        v = hold_axial(
            key, rod_diameter=rod_diameter, post_diameter=post_diameter, mu=mu, load=load,
            free_end_load=free_end_load, mu_rr=mu_rr, wrap_angle=wrap_angle, material=material,
            youngs_modulus=youngs_modulus, simulate=simulate, phase_table=phase_table,
            progress=progress, bending_scale=bending_scale,
        )  # fmt: skip
        return with_capacity(v, material)
    c = _case(
        key, rod_diameter=rod_diameter, post_diameter=post_diameter, mu=mu, load=load,
        free_end_load=free_end_load, mu_rr=mu_rr, material=material,
        youngs_modulus=youngs_modulus, simulate=simulate, phase_table=phase_table,
        progress=progress, creep_limit=creep_limit, bending_scale=bending_scale,
    )  # fmt: skip
    c.bisect, c.mu_unknown, c.max_cpu_s = bisect, mu_unknown, max_cpu_s
    v = _verdict(c, wrap_angle)
    if not top:
        return v
    m, text = _critical_mu(c, v)
    extra = {"model_critical_mu": m, "model_critical_mu_text": text}
    if c.simulate and c.simulable:
        extra["search_command"] = c.command().removesuffix(" --simulate")
    return replace(v, friction=extra)


def _unknown_friction(preset, key, *, simulate, **kw) -> Verdict:
    """The verdict without a published friction coefficient: over the searched range
    (:func:`knotmech.verdict.friction.unknown_friction_verdict`), from the verdicts at given
    mu. A DER run (``simulate``) answers at one friction only: refused (InputError)."""
    if simulate:
        raise InputError(
            "simulate runs at one friction coefficient and there is "
            f"{preset.missing()}: give mu (measured)"
            + (f" or post_material ({', '.join(preset.known)})" if preset.known else "")
        )
    v = unknown_friction_verdict(preset, lambda m: _verdict_at(key, m, mu_unknown=True, **kw))
    if math.isnan(v.friction["critical_mu"]):
        v.friction["critical_mu_text"] = _not_found(v, (preset.low, preset.high))
    return v


def _check_bisect(key: str, bisect, simulate) -> int:
    """The number of bisection runs, checked: an integer 0 to ``MAX_BISECT_RUNS``, only with
    ``simulate`` and only for a hitch on a post (InputError, one line)."""
    from knotmech.verdict.capacity import MAX_BISECT_RUNS

    if bisect is None or bisect is False or (isinstance(bisect, int) and bisect == 0):
        return 0
    if isinstance(bisect, bool) or not isinstance(bisect, int):
        raise InputError(f"bisect must be a whole number of runs, got {bisect!r}")
    if not 1 <= bisect <= MAX_BISECT_RUNS:
        raise InputError(f"bisect must be 1 to {MAX_BISECT_RUNS} runs, got {bisect}")
    if not simulate:
        raise InputError("bisect narrows the slip load by DER runs: give simulate as well")
    if not has_der_answer(key):
        raise InputError(
            f"bisect applies to the hitches on a post with a DER scene, not to {key} "
            "(a bend's, a loop's or the Prusik's run gives its slip load directly)"
        )
    return bisect


def _check_budget(key: str, max_cpu_s, simulate) -> float:
    """The CPU budget of each DER run [s], checked: positive, only with ``simulate`` and only
    for a hitch on a post (a bend's or a loop's pull has its rate bound); default
    :data:`SIMULATE_MAX_CPU_S`."""
    if max_cpu_s is None:
        return SIMULATE_MAX_CPU_S
    cpu = check_positive("max_cpu_s", max_cpu_s, scalar=True)
    if not simulate:
        raise InputError("max_cpu_s is the CPU budget of a DER run: give simulate as well")
    if not has_der_answer(key):
        raise InputError(
            f"max_cpu_s applies to the DER run of a hitch on a post, not to {key} (a bend's, "
            "a loop's or the Prusik's pull stops when it crawls)"
        )
    return float(cpu)


def _check_sizes(rod_diameter, post_diameter, load) -> None:
    """The sizes and the load first, so that a wrong size is named before a missing
    friction coefficient (InputError, one line)."""
    check_positive("rod_diameter", rod_diameter, scalar=True)
    if post_diameter is not None:
        check_positive("post_diameter", post_diameter, scalar=True)
    if load is not None:
        check_positive("load", load, scalar=True)


def _friction_part(key, mu, v: Verdict, friction, simulate, at) -> dict:
    """The critical mu mu* (:func:`knotmech.verdict.friction.critical_mu`: bisection of the
    whole verdict ``at(mu)`` in mu; not searched after a DER run) and, when mu came from the
    material (``friction``: the preset), the verdict at the range's high end and over the
    range (the verdict itself is at its low end); a hitch's deciding model's own critical
    mu as ``model_critical_mu``."""
    extra = dict(v.friction or {})
    out = dict(friction or {"range": None})
    asked = {mu: v}
    if friction is not None and not simulate:
        hi = friction["range"][1]
        asked.setdefault(hi, at(hi))
    if simulate:
        m = math.nan
        text = "not searched: a DER run answers at one mu only, mu* needs one run per mu"
        if "search_command" in extra:
            text += f"; {extra.pop('search_command')} searches it in the table and closed forms"
    else:
        mm = extra.get("model_critical_mu", math.nan)
        m, text = critical_mu(at, asked, hints=[(mm, v.decided_by or "deciding")])
        if math.isnan(m):
            text = _not_found(v, (mu, MU_SEARCH_MAX))
    out.update(critical_mu=m, critical_mu_text=text, **extra)
    if friction is None:
        return out
    lo, hi = friction["range"]
    at_high = v.holds if simulate else asked[hi].holds
    out.update(holds_at_low=v.holds, holds_at_high=at_high,
               words=range_words(v.holds, at_high, lo, hi, m))  # fmt: skip
    if simulate:
        out["words"] = f"simulated at mu = {lo:.3g} only (range {lo:.3g}-{hi:.3g})"
    return out


def _not_found(v: Verdict, mus) -> str:
    """Why mu* was not found: the verdict is undecided at each of ``mus`` (the question's mu
    and the top of the search); a knot that only a DER run answers needs one run per mu."""
    at = " and at ".join(f"{m:.3g}" for m in sorted(set(mus)))
    if not v.answers:  # a loop, a bend, the Prusik: no closed form and no table
        return (f"not searched: no closed form and no table answers the {v.knot}, only a DER "
                "run, so mu* needs one DER run per mu (--simulate at each --mu)")  # fmt: skip
    text = f"not found: the verdict is undecided at mu = {at}"
    if "--simulate" in (v.next_step or "") or (v.der or {}).get("refused"):
        text += "; a DER run decides one mu per run (--simulate at each --mu)"
    return text


def _critical_mu(c, v: Verdict) -> tuple:
    """(mu, how): the deciding model's own critical mu at this load (``model_critical_mu``,
    beside the whole verdict's mu*): a closed form's, or a bisection in mu of the DER hold
    table's lookup alone; none when the load breaks the rope."""
    from knotmech.verdict.criterion import CREEP_LIMIT

    if v.fails_by == "break":
        return math.inf, "the load breaks the rope whatever the friction"
    dec = v.deciding or next((a for a in v.answers if a.inside_validity and
                              math.isfinite(a.critical_mu)), None)  # fmt: skip
    if dec is None:
        return math.nan, "no model inside its validity gives one"
    if dec.model == "DER-table":
        tables = _slip_tables(c, v.der, _slip_table(c, v.der))
        if tables:
            x, y = c.d / (c.D + c.d), c.load / (c.E * math.pi * c.d * c.d / 4)
            lim = CREEP_LIMIT if c.creep_limit is None else c.creep_limit
            mr = None if c.mu_rr is None else float(c.mu_rr)

            def ask(m):  # over a kappa range: holds where every table holds
                return _Said.every([t.lookup(x, y, mu=m, mu_rr=mr if mr is not None else m,
                                             creep_limit=lim).holds for t in tables])  # fmt: skip

            what = "the DER table's verdict" + (
                "" if len(tables) == 1 else " at every kappa of the rope's range"
            )
            return critical_mu(ask, {c.mu: ask(c.mu)}, what=what)
    if dec.model.startswith("DER"):
        return math.nan, f"not searched for the {dec.model} answer"
    m = float(dec.critical_mu)
    tag = "" if dec.decides else ", which does not decide here"
    if math.isinf(m):
        return m, f"the {dec.model} model's: no friction coefficient holds it{tag}"
    return m, f"the {dec.model} model's{tag}"


@dataclass(frozen=True)
class _Said:
    """A table's holds (True, False or None) as the critical-mu search reads a verdict."""

    holds: bool | None

    @classmethod
    def every(cls, said: list) -> _Said:
        """Holds where every answer holds, slips where one slips, else undecided."""
        if all(h is True for h in said):
            return cls(True)
        return cls(False if any(h is False for h in said) else None)


@dataclass
class _Case:
    """One hitch (or capstan) question, checked: diameters [m], friction, loads [N], the
    rope's stiffness (E [Pa] or None, its material, kappa and where they came from), what
    the user gave as given (``youngs_modulus``, ``bending_scale``: the command repeats them)
    and how the DER is asked."""

    key: str
    d: float
    D: float
    mu: float
    mu_rr: float | None
    load: float
    free: float
    creep_limit: float | None
    E: float | None
    mat: object
    e_source: str
    kappa: float
    k_source: str
    youngs_modulus: object
    bending_scale: object
    simulate: bool
    phase_table: object
    progress: bool
    #: the thick nip is self-locking and inside its own validity but for the strain (set
    #: by :func:`_closed_form_answers`): it then bounds the slip load from below by 0.1 EA
    nip_locks: bool = False
    #: extra DER runs that bisect the slip load (``simulate``, a free end)
    bisect: int = 0
    #: no friction coefficient is published (mu is one the search assumed): the DER
    #: command asks for a measured one (:data:`MU_PLACEHOLDER`)
    mu_unknown: bool = False
    #: [s] CPU budget of each DER run (``simulate``, ``bisect``)
    max_cpu_s: float = SIMULATE_MAX_CPU_S

    @property
    def simulable(self) -> bool:
        """Whether one DER run decides this case (a scene, a free end; the cow hitch also
        loaded on both legs)."""
        return can_simulate(self.key) and (self.free == 0 or self.key in BOTH_LEGS_KNOTS)

    def command(self) -> str:
        """The one DER run that decides this case ("" when there is none)."""
        if not self.simulable:
            return ""
        cmd = simulate_command(
            self.key, d=self.d, D=self.D, mu=MU_PLACEHOLDER if self.mu_unknown else self.mu,
            mu_rr=None if self.mu_rr is None else float(self.mu_rr), load=self.load,
            material=None if self.mat is None else self.mat.key,
            youngs_modulus=self.youngs_modulus, creep_limit=self.creep_limit,
            bending_scale=self.bending_scale, free_end_load=self.free,
        )  # fmt: skip
        if self.mu_unknown:  # a run at an assumed friction would answer nothing
            cmd += f" ({MU_PLACEHOLDER}: {MU_PLACEHOLDER_WORDS})"
        return cmd


def _case(
    key, *, rod_diameter, post_diameter, mu, load, free_end_load, mu_rr, material,
    youngs_modulus, simulate, phase_table, progress, creep_limit, bending_scale,
) -> _Case:  # fmt: skip
    """The checked inputs of a hitch or capstan question (one-line InputErrors, in order)."""
    if post_diameter is None:
        raise InputError(f"post_diameter is required for {key}")
    d = check_positive("rod_diameter", rod_diameter, scalar=True)
    D = check_positive("post_diameter", post_diameter, scalar=True)
    mu = check_nonnegative("mu", mu, scalar=True)
    load = check_positive("load", load, scalar=True)
    free = check_nonnegative("free_end_load", free_end_load, scalar=True)
    if creep_limit is not None:
        creep_limit = check_positive("creep_limit", creep_limit, scalar=True)
    _check_combination(key, mu_rr=mu_rr, simulate=simulate, free=free, phase_table=phase_table)
    E, mat, e_source = _youngs_modulus(material, youngs_modulus)
    kappa, k_source = _bending_scale(mat, bending_scale)
    _check_stiffness(E, simulate=simulate, phase_table=phase_table)
    return _Case(
        key=key, d=d, D=D, mu=mu, mu_rr=mu_rr, load=load, free=free, creep_limit=creep_limit,
        E=E, mat=mat, e_source=e_source, kappa=kappa, k_source=k_source,
        youngs_modulus=youngs_modulus, bending_scale=bending_scale, simulate=bool(simulate),
        phase_table=phase_table, progress=progress,
    )  # fmt: skip


def _check_combination(key, *, mu_rr, simulate, free, phase_table) -> None:
    """Refuse inputs that do not go together (one line each)."""
    if key == "capstan" and mu_rr is not None:
        raise InputError("mu_rr (rope-on-rope friction) applies to hitches, not to capstan")
    if simulate and not can_simulate(key):
        raise InputError(
            f"simulate is available for the clove hitch, the hitches with a DER scene and the "
            f"bends, not for {key}"
        )
    if simulate and free > 0 and key not in BOTH_LEGS_KNOTS:
        raise InputError(
            "simulate covers the hitches with a free end only (free_end_load 0), and the cow "
            "hitch on one or both legs"
        )
    if simulate and phase_table is not None:
        raise InputError("give either simulate or phase_table, not both")
    if phase_table is not None and not has_der_answer(key):
        from knotmech.verdict.scope import DER_HITCHES

        raise InputError(
            f"phase_table applies to the hitches with a DER answer "
            f"({', '.join(DER_HITCHES)}), not to {key}"
        )


def _check_stiffness(E, *, simulate, phase_table) -> None:
    """A DER run or a user's table needs E."""
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


def _verdict(c: _Case, wrap_angle) -> Verdict:
    """Every model's answer on ``c`` and the verdict of the rule."""
    from knotmech.analytic.hitch import hold_verdict as closed_forms

    base = closed_forms(
        c.key, rod_diameter=c.d, post_diameter=c.D, mu=c.mu, load=c.load,
        free_end_load=c.free, mu_rr=c.mu_rr, wrap_angle=wrap_angle,
    )  # fmt: skip
    inputs = _inputs(c, base)
    answers = _closed_form_answers(c, base)
    assumptions = [c.e_source] if c.e_source else []
    if c.key != "capstan":
        assumptions.append(c.k_source)
    cmd = c.command()
    der, creep, shape = _der_part(c, answers, assumptions, cmd)
    i = decide(answers)
    if i is not None:
        answers[i] = replace(answers[i], decides=True)
    cap = _capacity(c, answers, der)
    holds, fails_by = _settle(c, answers, i, cap)
    if i is not None and holds is None:  # a self-locking closed form that nothing bounds
        answers[i] = replace(answers[i], decides=False)
        i = None
    dec = None if i is None else answers[i]
    return Verdict(
        knot=c.key,
        holds=holds,
        margin=_margin(dec, cap, c.load),
        decided_by=None if dec is None else dec.model,
        inside_validity=dec is not None,
        answers=tuple(answers),
        validity=() if dec is None else tuple(dec.validity),
        assumptions=tuple(assumptions),
        warnings=_warnings(c.mu, c.mu_rr, c.d, c.D, c.load, c.E, inputs.get("wrap_angle")),
        next_step=_next_step(c, dec, der, cmd, cap),
        creep=creep,
        inputs=inputs,
        der=der,
        notes=tuple(base.notes),
        shape=shape,
        capacity=cap,
        fails_by=fails_by,
    )


def _bend_capacity(v: Verdict, material) -> Verdict:
    """A bend's verdict with its capacity: the slip load of its DER pull when one ran (a
    point value; a hold: open above, :func:`knotmech.verdict.bend.der_slip_band`), and the
    bend's breaking load; at or above the breaking load it breaks."""
    from knotmech.verdict import capacity as _cap
    from knotmech.verdict.bend import der_slip_band

    slip = der_slip_band(v, "bend")
    load = v.inputs["load"]
    cap = _cap.capacity_of(knot=v.knot, slip=slip, material=v.inputs.get("material", material),
                           d=v.inputs["rod_diameter"], D=None, load=load)  # fmt: skip
    brk = cap.breaking
    if v.holds is not None and brk is not None and load >= brk.value:
        return replace(v, capacity=cap, holds=False, fails_by="break")
    return replace(v, capacity=cap, fails_by="slip" if v.holds is False else None)


def _slip_table(c: _Case, der):
    """The 3-axis DER hold table that gives this case's slip load, None where none applies
    (no DER answer, a loaded free end, no E, a table refused for its kappa or its rod)."""
    from knotmech.verdict.der import BENDING_SCALE_FACTOR, load_user_table, shipped_hold_table
    from knotmech.verdict.tables import HoldTable

    if not has_der_answer(c.key) or c.free > 0 or c.E is None or (der or {}).get("refused"):
        return None
    if c.phase_table is not None:
        t = load_user_table(c.phase_table)
        return t if isinstance(t, HoldTable) else None
    t = shipped_hold_table(c.key, c.kappa)
    if (
        t is None
        or max(t.bending_scale / c.kappa, c.kappa / t.bending_scale) > BENDING_SCALE_FACTOR
    ):
        return None
    return t


def _slip_tables(c: _Case, der, nominal) -> list:
    """The DER hold tables that give this case's slip load: ``nominal`` (:func:`_slip_table`'s)
    and, over the preset's kappa range, the tables read at its ends and its nominal kappa
    (``der["kappa_range"]``, :func:`knotmech.verdict.kappa.over_range`), ascending; none when
    a range end has no table near enough (the band would hold at one kappa only)."""
    from knotmech.verdict.der import shipped_hold_table

    rng = (der or {}).get("kappa_range")
    if nominal is None or not rng:
        return [] if nominal is None else [nominal]
    if any(r["refused"] for r in rng["readings"]):
        return []
    return [shipped_hold_table(c.key, k)
            for k in sorted({r["table_bending_scale"] for r in rng["readings"]})]  # fmt: skip


def _capacity(c: _Case, answers: list, der):
    """The load the knot takes (:func:`knotmech.verdict.capacity.capacity_of`): the slip load
    from the DER hold table at the user's d/2R and friction, else from the deciding closed
    form, and the knot's breaking load."""
    from knotmech.verdict import capacity as _cap
    from knotmech.verdict.criterion import CREEP_LIMIT

    EA = math.nan if c.E is None else c.E * math.pi * c.d * c.d / 4
    slip = None
    nominal = _slip_table(c, der)  # the table at the preset's kappa gives the value
    tables = _slip_tables(c, der, nominal)
    if tables:
        lim = CREEP_LIMIT if c.creep_limit is None else c.creep_limit
        rows = [_cap.slip_from_table(t, x=c.d / (c.D + c.d), mu=c.mu,
                                     mu_rr=None if c.mu_rr is None else float(c.mu_rr),
                                     creep_limit=lim) for t in tables]  # fmt: skip
        slip = _cap.merge_bands([_cap.band_newtons(r, EA) for r in rows],
                                [t.bending_scale for t in tables],
                                nominal=nominal.bending_scale)  # fmt: skip
    if c.bisect and c.free == 0 and math.isfinite(EA) and (der or {}).get("holds") is not None:
        # the DER's own evidence only (the table and the runs), not a closed form's bound
        slip = _cap.agree_with_verdict(slip, bool(der["holds"]), c.load)
        slip = _bisected(c, slip, EA, der)
        return _cap.capacity_of(knot=c.key, slip=slip, material=c.mat, d=c.d, D=c.D, load=c.load)
    closed = _cap.slip_from_answers(answers, strain_limit_load=STRAIN_LIMIT * EA)
    if closed is None and c.nip_locks and math.isfinite(EA):  # a load beyond its strain
        closed = _cap.LoadBand(math.inf, STRAIN_LIMIT * EA, math.inf,
                               "thick-nip model: self-locking, friction alone cannot unlock it "
                               "up to its validity's strain")  # fmt: skip
    slip = _cap.better_slip(slip, closed)
    dec = next((a for a in answers if a.decides), None)
    if slip is None and c.free > 0 and dec is not None and dec.model == "DER-table":
        slip = _cap.legs_band(dec.holds, c.load)
    slip = _cap.agree_with_verdict(slip, None if dec is None else dec.holds, c.load)
    return _cap.capacity_of(knot=c.key, slip=slip, material=c.mat, d=c.d, D=c.D, load=c.load)


def _bisected(c: _Case, slip, EA: float, der: dict):
    """The slip band narrowed by ``c.bisect`` DER runs of this geometry
    (:func:`knotmech.verdict.capacity.bisect_slip`), starting from ``slip`` (the DER table's
    band narrowed by the first run or, with no table, the first run alone: above its load if
    it held, below if it slipped); the runs are listed in ``der["bisection"]``."""
    from knotmech.verdict import capacity as _cap
    from knotmech.verdict.der import simulate_holds

    held = bool(der["holds"])
    if slip is None:
        slip = (
            _cap.LoadBand(math.inf, c.load, math.inf, "the DER run of this geometry")
            if held
            else _cap.LoadBand(c.load, 0.0, c.load, "the DER run of this geometry")
        )

    def ask(load):
        return simulate_holds(
            knot=c.key, d=c.d, D=c.D, mu=c.mu, mu_rr=c.mu if c.mu_rr is None else float(c.mu_rr),
            load=load, E=c.E, bending_scale=c.kappa, creep_limit=c.creep_limit,
            density=None if c.mat is None else c.mat.density, progress=c.progress,
            max_cpu_s=c.max_cpu_s,
        )  # fmt: skip

    top = _cap.BISECT_CEILING * EA
    band, probes = _cap.bisect_slip(ask, low=slip.low, high=slip.high, runs=c.bisect,
                                    ceiling=top, source=slip.source)  # fmt: skip
    der["bisection"] = [{"load_N": f, "t_over_EA": f / EA, "holds": h} for f, h in probes]
    if not probes:
        der["bisection_note"] = (
            f"no run: nothing slipped up to {slip.low:.4g} N, at or above "
            f"{_cap.BISECT_CEILING:g} EA = {top:.4g} N, the heaviest load the DER answers for"
        )
    return band


def _settle(c: _Case, answers: list, i, cap) -> tuple:
    """(holds, fails_by) from the deciding answer and the capacity: a self-locking closed
    form holds only up to the capacity's lower bound (undecided when nothing bounds it,
    or between the bound and the break); at or above the breaking load the knot breaks."""
    if i is None:
        return None, None
    dec = answers[i]
    holds = bool(dec.holds)
    brk = cap.breaking
    if math.isinf(dec.margin) and dec.margin > 0:
        if not cap.decided or c.load > cap.low:
            holds = None
    if brk is not None and c.load >= brk.value and holds is not False:
        return False, "break"
    return holds, (None if holds is not False else "slip")


def _margin(dec, cap, load: float) -> float:
    """The deciding model's margin ``capacity/load - 1``; where it is self-locking (inf), the
    capacity's (:attr:`Verdict.capacity`, the breaking load) instead; NaN when undecided."""
    if dec is None:
        return math.nan
    if math.isinf(dec.margin) and cap is not None and cap.decided:
        return cap.value / load - 1
    return float(dec.margin) if math.isfinite(dec.margin) else math.nan


def _inputs(c: _Case, base) -> dict:
    """The inputs in SI units, as the verdict reports them."""
    inputs = dict(base.inputs)
    if c.key == "capstan":
        inputs.pop("mu_rr", None)
    if c.mat is not None:
        inputs["material"] = c.mat.key
    if c.E is not None:
        inputs["youngs_modulus"] = c.E
    inputs["bending_scale"] = c.kappa
    return inputs


def _closed_form_answers(c: _Case, base) -> list:
    """The closed forms' answers, none deciding yet; the thick nip inside its validity only
    for a rope no thicker than its post at a strain T_high/EA within :data:`STRAIN_LIMIT`."""
    strain = None if c.E is None else c.load / (c.E * math.pi * c.d * c.d / 4)
    answers = []
    for a in base.answers:
        a = replace(a, decides=False)
        if a.model == "thick-nip":
            c.nip_locks = bool(a.inside_validity and math.isinf(a.capacity) and c.d <= c.D)
            ok = c.d <= c.D and (strain is None or strain <= STRAIN_LIMIT)
            a = with_validity(
                a,
                ok,
                f"rope no thicker than the post; strain T_high/EA <= {STRAIN_LIMIT * 100:g} % "
                "(inextensible rope)"
                + ("" if strain is None else f": here {strain:.3g}")
                + ("" if strain is not None else " (not checked: E not given)"),
            )
        answers.append(a)
    return answers


def _der_part(c: _Case, answers: list, assumptions: list, cmd: str):
    """The DER answer of a hitch with one (appended to ``answers``): (details, creep, shape)."""
    if not has_der_answer(c.key):
        return None, None, None
    if c.free > 0 and c.key not in BOTH_LEGS_KNOTS:
        return {
            "source": "none",
            "holds": None,
            "message": "the DER phase diagram covers the free end only (T_low = 0)",
        }, None, None  # fmt: skip
    if c.E is None:
        assumptions.append(
            "nothing about the rope's stiffness: E was not given, so the DER phase table "
            "(in T_high/EA) was not consulted"
        )
        return {
            "source": "none",
            "holds": None,
            "message": "not consulted: the DER tables are in T_high/EA and E was not given",
        }, None, None  # fmt: skip
    ideal = next((a.holds for a in answers if a.model == "ideal-rope"), None)
    der, answer, creep, shape = _ask_der(c, ideal, cmd, c.kappa)
    rng = _kappa_range(c)
    if rng is not None:
        der, answer = over_range(lambda k: _ask_der(c, ideal, cmd, k)[:2], der, answer,
                                 nominal=c.kappa, low=rng[0], high=rng[1])  # fmt: skip
        answers[:] = against_readings(answers, der)
    if answer is not None:
        answers.append(answer)
    return der, creep, shape


def _ask_der(c: _Case, ideal, cmd: str, kappa: float):
    """The DER answer of ``c`` at bending scale ``kappa``: (details, answer, creep, shape)."""
    from knotmech.verdict.der import der_answer

    return der_answer(
        knot=c.key, d=c.d, D=c.D, mu=c.mu, mu_rr=c.mu if c.mu_rr is None else float(c.mu_rr),
        load=c.load, E=c.E, simulate=c.simulate, phase_table=c.phase_table,
        progress=c.progress, ideal_holds=ideal, creep_limit=c.creep_limit,
        bending_scale=kappa, command=cmd, density=None if c.mat is None else c.mat.density,
        free_end_load=c.free, max_cpu_s=c.max_cpu_s,
    )  # fmt: skip


def _kappa_range(c: _Case):
    """(low, high) of the preset's estimated kappa when the shipped tables answer at the
    preset's kappa (:mod:`knotmech.verdict.kappa`), else None: a kappa the user gives, a
    simulation (it runs at one kappa), a table the user names, or a preset without a range."""
    if c.bending_scale is not None or c.mat is None or c.simulate or c.phase_table is not None:
        return None
    lo, hi = (float(v) for v in c.mat.bending_scale_range)
    return None if lo == hi else (lo, hi)


def _next_step(c: _Case, dec, der, cmd: str, cap=None) -> str:
    """What to do next: the command that decides an undecided case, the input that lets the
    DER answer, the runs that find an unbounded slip load, or the run that checks a case the
    DER did not decide."""
    if dec is None and (der or {}).get("refused") == RANGE_REFUSAL:
        return (
            "next: give --bending-scale (bending_scale=) for a measured rope; "
            + (f"{cmd} runs at the preset's kappa {c.kappa:g}" if c.simulable else "")
        ).removesuffix("; ")
    if dec is None:
        return _undecided_step(c, cmd, cap)
    if has_der_answer(c.key) and c.free == 0 and c.E is None:
        return (
            "next: give --material or --youngs-modulus (material=, youngs_modulus=) to "
            "check against the DER phase table"
        )
    if cap is not None and not cap.decided and c.simulable and not c.simulate:
        return (
            f"next: the slip load is not bounded ({cap.message}); {cmd} with heavier "
            "--load values finds where it slips"
        )
    der_silent = der is not None and der.get("holds") is None and c.free == 0
    if c.simulable and der_silent and not c.simulate and dec.model != "DER-table":
        return f"next: {cmd} checks it with one DER run of this geometry"
    return ""


def _undecided_step(c: _Case, cmd: str, cap) -> str:
    """The next step of an undecided case: the DER run that decides it, or a test."""
    if c.simulable:
        return (
            f"next: {cmd} (one DER run of this geometry, {SIMULATE_COST}) decides it"
            + ("" if c.E is not None else "; MATERIAL: one of the presets, or give "
               "--youngs-modulus")
        )  # fmt: skip
    if cap is not None and not cap.decided and cap.slip is not None:
        return f"next: {cap.message}; test the knot (no model bounds its slip load)"
    return "next: no model here applies inside its validity; test the knot"


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

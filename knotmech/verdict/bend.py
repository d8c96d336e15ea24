"""The hold verdict of a bend (two ropes joined, pulled apart): no closed form and no table;
with ``simulate`` one DER pull of the bend scene (:func:`knotmech.scenes.bends.bend`), its
slip load against the load."""

from __future__ import annotations

import math

from knotmech import knots
from knotmech.errors import InputError, check_nonnegative, check_positive
from knotmech.knots.catalogue import PATIL
from knotmech.verdict._run import refuse_inputs, run_answer, run_shape
from knotmech.verdict.answer import Verdict
from knotmech.verdict.command import simulate_command
from knotmech.verdict.inputs import _bending_scale, _warnings, _youngs_modulus

__all__ = ["hold_bend"]


def hold_bend(
    key, *, rod_diameter, post_diameter, mu, load, free_end_load, mu_rr, wrap_angle, material,
    youngs_modulus, simulate, phase_table, progress, bending_scale=None,
) -> Verdict:  # fmt: skip
    """The verdict on bend ``key`` (keywords of :func:`knotmech.hold`; no post, mu is the
    rope-rope friction): undecided with the command that decides, or one DER pull."""
    d = check_positive("rod_diameter", rod_diameter, scalar=True)
    mu = check_nonnegative("mu", mu, scalar=True)
    load = check_positive("load", load, scalar=True)
    _refuse_post_inputs(key, post_diameter=post_diameter, mu_rr=mu_rr, wrap_angle=wrap_angle,
                        phase_table=phase_table, free_end_load=free_end_load)  # fmt: skip
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
    common = dict(
        knot=key, assumptions=tuple(([e_source] if e_source else []) + [k_source]),
        warnings=_warnings(mu, None, d, math.inf, load, E, None), inputs=inputs,
        notes=(_note(key),),
    )  # fmt: skip
    if not simulate:
        return Verdict(
            holds=None, margin=math.nan, decided_by=None, inside_validity=False, answers=(),
            next_step=f"next: {cmd} (one DER pull of the bend, {_cost(key)}) decides it",
            **common,
        )  # fmt: skip
    if E is None:
        from knotmech.materials import material_names

        raise InputError(
            "simulate needs the rope's stiffness: give material (one of "
            f"{', '.join(material_names())}) or youngs_modulus"
        )
    der, answers, shape = _pull(key, d=d, E=E, mu=mu, load=load, mat=mat, kappa=kappa,
                                progress=progress)  # fmt: skip
    return Verdict(
        holds=der["holds"], margin=answers[0].margin if answers else math.nan,
        decided_by="DER-simulation" if answers else None, inside_validity=bool(answers),
        answers=answers, validity=answers[0].validity if answers else (),
        next_step="" if answers else f"next: test the knot ({der['message']})",
        der=der, shape=shape, **common,
    )  # fmt: skip


#: [wall s per simulated s] the stall bound of a bend pull under ``hold --simulate``: a
#: solid-rod pull runs at 20-70 (2.6 s simulated in 1-3 min, 2.5x that on a busy machine);
#: a fibre rope (kappa = 0.01, E = 0.25 GPa) crawls at ~2700 (a whole pull about an hour,
#: issue 27), and is stopped after the solver's 60 s window as ``failed``, undecided
BEND_WALL_RATE = 300.0


def _cost(key) -> str:
    """What one pull costs (benchmarks/tied.py for the tied bends)."""
    cost = "1-3 minutes" if _patil(knots.get(key)) else "under a minute of CPU"
    return (f"{cost} for a solid rod; a run slower than {BEND_WALL_RATE:g} s of wall per "
            "simulated second stops undecided")  # fmt: skip


def _patil(rec) -> bool:
    """Whether the record is one of the four bends of Patil et al. (tied from bend_curves)."""
    return rec.curve.endswith(":bend_curves")


def _note(key) -> str:
    """What answers for bend ``key``: its source and the scene."""
    rec = knots.get(key)
    where = "Patil et al., Science 2020" if _patil(rec) else rec.summary
    return (f"{key} is a bend ({where}): no closed form and no DER table; one DER pull of "
            "the bend scene (knotmech.scenes.bends.bend) gives its slip load")  # fmt: skip


def _refuse_post_inputs(key, *, post_diameter, mu_rr, wrap_angle, phase_table, free_end_load):
    """A bend has no post, no second friction, no wrap, no table and no free end."""
    refuse_inputs(
        key, "bend", "two ropes pulled apart, no post; mu is the rope-rope friction",
        free_end="no free end", post_diameter=post_diameter, mu_rr=mu_rr,
        wrap_angle=wrap_angle, phase_table=phase_table, free_end_load=free_end_load,
    )  # fmt: skip


def _pull(key, *, d, E, mu, load, mat, kappa, progress):
    """One DER pull of the bend: (details, answers: the DER's, empty when it did not decide,
    the last frame for ``--plot``)."""
    from knotmech.rod import SolverOptions
    from knotmech.scenes.bends import bend

    kw = {"density": mat.density} if mat is not None else {}
    kw["options"] = SolverOptions(max_wall_per_sim_second=BEND_WALL_RATE)
    if kappa != 1.0:
        kw["bending_scale"] = kappa
    r = bend(key, rod_diameter=d, youngs_modulus=E, mu_rod_rod=mu, progress=progress, **kw)
    tied = {
        "tail_drawn": r.tail_drawn, "roll": r.roll, "law": r.law,
        "frames_checked": r.frames_checked,
        "held_to_strain_limit": bool(getattr(r, "held_to_strain_limit", False)),
    } if hasattr(r, "tail_drawn") else {}  # fmt: skip
    der = {
        "source": "simulation", "scene": "knotmech.scenes.bends.bend", "kind": key,
        "verdict": r.verdict, "slip_load": r.slip_load, "max_force": r.max_force,
        "pull_speed": r.pull_speed, "status": r.status, "message": r.message,
        "topology_preserved": bool(r.topology_preserved),
        "wall_s": float(r.stats.get("wall_s", math.nan)), **tied,
    }  # fmt: skip
    holds, capacity, der["message"] = _pull_outcome(key, r, load)
    der["holds"] = holds
    shape = run_shape(r, d=d, ropes=2)
    if holds is None:
        return der, (), shape
    return der, (_pull_answer(key, r, holds, capacity, load, kappa, der["message"]),), shape


def _pull_outcome(key, r, load):
    """(holds or None, capacity [N], message) of a pull against ``load`` [N]. A pull that
    held gives a lower bound of the slip load (its largest force); one stopped at the rod
    model's strain limit (``held_to_strain_limit``) says so, and a load above it is not
    decided (beyond the rod model)."""
    from knotmech.scenes.bends import STRAIN_LIMIT, held_note

    if r.verdict == "slips" and math.isfinite(r.slip_load):
        return load < r.slip_load, float(r.slip_load), (
            f"DER pull of the {key}: slips at {r.slip_load:.4g} N "
            f"(the largest pull force before its tail drew in)")  # fmt: skip
    limit = bool(getattr(r, "held_to_strain_limit", False))
    if r.verdict == "holds" and load <= r.max_force:
        return True, float(r.max_force), (
            f"DER pull of the {key}: " + (held_note(r.max_force) if limit else
            f"did not slip up to {r.max_force:.4g} N, the largest force of the pull"))  # fmt: skip
    if r.verdict == "holds" and limit:
        return None, math.nan, (
            f"DER pull of the {key}: {held_note(r.max_force)}; the load {load:.4g} N is "
            f"above it, where the rod is strained beyond {STRAIN_LIMIT:.0%} (outside the "
            "rod model): not decided")  # fmt: skip
    return None, math.nan, (
        f"DER pull of the {key}: {r.verdict or 'failed'} ({r.message}); the load "
        + (f"{load:.4g} N is above the largest pull force {r.max_force:.4g} N"
           if r.verdict == "holds" else "is not decided")
    )  # fmt: skip


def der_slip_band(v: Verdict, what: str):
    """The slip load of a bend's or loop's DER pull for the capacity
    (:class:`knotmech.verdict.capacity.LoadBand`), or None without one: a slip, a point
    value; a hold (the pull ended, or stopped at the rod model's strain limit), open above
    from the largest force (nothing slipped up to it), also when the load is above it and
    the pull decided nothing."""
    from knotmech.verdict import capacity as _cap

    der, dec = v.der or {}, v.deciding
    if der.get("verdict") == "holds":  # decided or not: nothing slipped up to its force
        cap = float(der.get("max_force", math.nan) if dec is None else dec.capacity)
        if not math.isfinite(cap):
            return None
        why = ("stopped at the rod model's strain limit, 0.1 EA"
               if der.get("held_to_strain_limit") else "ended")  # fmt: skip
        return _cap.LoadBand(math.inf, cap, math.inf, f"the DER pull of the {what} {why}")
    if dec is None or not math.isfinite(dec.capacity):
        return None
    cap = float(dec.capacity)
    return _cap.LoadBand(cap, cap, cap, f"DER pull of the {what}")


def _pull_answer(key, r, holds, capacity, load, kappa, message):
    """The pull's deciding :class:`~knotmech.analytic.hitch.ModelAnswer`."""
    rec = knots.get(key)
    law = getattr(r, "law", "") or "sticking rod-rod friction"
    loading = rec.loading or "set by hand then pulled apart"
    reference = (PATIL + "; knotmech.scenes.bends" if _patil(rec)
                 else "; ".join(rec.sources) + "; knotmech.scenes.bends")  # fmt: skip
    return run_answer(
        holds=holds, capacity=capacity, load=load,
        assumptions=(
            f"two elastic rods (B = kappa E pi d^4/64, kappa = {kappa:g}), {law}, "
            f"{loading} at {r.pull_speed * 1e3:g} mm/s",
            "slip: a tail draws in by more than 2 d while the pull force stays "
            "within 10 % of its largest value",
        ),
        validity=("one DER pull of the bend at this d, E and mu",),
        reference=reference, message=message,
    )  # fmt: skip

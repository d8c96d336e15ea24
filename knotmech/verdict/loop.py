"""The hold verdict of a loop (bowline, figure-eight loop: the eye round a pin, the standing
part loaded): no closed form and no table; with ``simulate`` one DER pull of the loop scene
(:func:`knotmech.scenes.loops.loop`), its slip load against the load, and the loop's
breaking load from :mod:`knotmech.strength` (the capacity form of the bends)."""

from __future__ import annotations

import math
from dataclasses import replace

from knotmech import knots
from knotmech.errors import InputError, check_nonnegative, check_positive
from knotmech.verdict._run import refuse_inputs, run_answer, run_shape
from knotmech.verdict.answer import Verdict
from knotmech.verdict.bend import BEND_WALL_RATE, _pull_outcome, der_slip_band
from knotmech.verdict.command import simulate_command
from knotmech.verdict.inputs import _bending_scale, _warnings, _youngs_modulus

__all__ = ["LOOPS", "hold_loop", "is_loop"]

#: the loops ``hold`` answers (the registry's loops with a scene)
LOOPS = tuple(k.name for k in knots.records(family="loop", answered=True) if k.scene)


def is_loop(knot) -> bool:
    """Whether ``knot`` (a canonical name) is a loop answered by :func:`hold_loop`."""
    return knot in LOOPS


def hold_loop(
    key, *, rod_diameter, post_diameter, pin_diameter, mu, load, free_end_load, mu_rr,
    wrap_angle, material, youngs_modulus, simulate, phase_table, progress, bending_scale=None,
) -> Verdict:  # fmt: skip
    """The verdict on loop ``key`` (keywords of :func:`knotmech.hold`; ``pin_diameter`` [m]
    the pin its eye goes round, required; mu the rope-rope and rope-pin friction):
    undecided with the command that decides, or one DER pull; with its capacity."""
    if pin_diameter is None:
        raise InputError(f"{key} needs pin_diameter: the diameter of the pin its eye goes round")
    D = check_positive("pin_diameter", pin_diameter, scalar=True)
    d = check_positive("rod_diameter", rod_diameter, scalar=True)
    mu = check_nonnegative("mu", mu, scalar=True)
    load = check_positive("load", load, scalar=True)
    _refuse(key, post_diameter=post_diameter, mu_rr=mu_rr, wrap_angle=wrap_angle,
            phase_table=phase_table, free_end_load=free_end_load)  # fmt: skip
    E, mat, e_source = _youngs_modulus(material, youngs_modulus)
    kappa, k_source = _bending_scale(mat, bending_scale)
    inputs = {"rod_diameter": d, "pin_diameter": D, "mu": mu, "load": load,
              "bending_scale": kappa}  # fmt: skip
    if mat is not None:
        inputs["material"] = mat.key
    if E is not None:
        inputs["youngs_modulus"] = E
    cmd = simulate_command(key, d=d, D=None, pin=D, mu=mu, load=load,
                           material=None if mat is None else mat.key,
                           youngs_modulus=youngs_modulus, bending_scale=bending_scale)  # fmt: skip
    common = dict(
        knot=key, assumptions=tuple(([e_source] if e_source else []) + [k_source]),
        warnings=_warnings(mu, None, d, math.inf, load, E, None), inputs=inputs,
        notes=(_note(key),),
    )  # fmt: skip
    if not simulate:
        v = Verdict(
            holds=None, margin=math.nan, decided_by=None, inside_validity=False, answers=(),
            next_step=f"next: {cmd} (one DER pull of the loop, {_cost()}) decides it",
            **common,
        )  # fmt: skip
        return loop_capacity(v, material)
    if E is None:
        from knotmech.materials import material_names

        raise InputError(
            "simulate needs the rope's stiffness: give material (one of "
            f"{', '.join(material_names())}) or youngs_modulus"
        )
    der, answers, shape = _pull(key, d=d, D=D, E=E, mu=mu, load=load, mat=mat, kappa=kappa,
                                progress=progress)  # fmt: skip
    v = Verdict(
        holds=der["holds"], margin=answers[0].margin if answers else math.nan,
        decided_by="DER-simulation" if answers else None, inside_validity=bool(answers),
        answers=answers, validity=answers[0].validity if answers else (),
        next_step="" if answers else f"next: test the knot ({der['message']})",
        der=der, shape=shape, **common,
    )  # fmt: skip
    return loop_capacity(v, material)


def _cost() -> str:
    """What one pull costs (benchmarks/tied.py --loops)."""
    return (f"under about a minute of CPU for a solid rod; a run slower than {BEND_WALL_RATE:g}"
            " s of wall per simulated second stops undecided")  # fmt: skip


#: what a loop's DER pull does not yet show (docs/notes/knots-and-curves/tied-loops-pulled.md)
CAVEATS = {
    "figure-eight-loop": "; caution: its start shape is loose (a doubled figure-eight about "
    "40 x 24 d) and a 20 d pull does not tighten it, so a 'slip' of this run is loose strands "
    "moving, not the tight knot's slip",
    "alpine-butterfly": "; caution: its start shape is loose (229 d of rope, six crossings) "
    "and the pull still tightens it: the force rises to the end of the pull; hold answers "
    "the loop loading only (simulate alpine-butterfly --loading end-to-end for the other)",
}


def _note(key) -> str:
    rec = knots.get(key)
    return (f"{key} is a loop ({rec.summary}): no closed form and no DER table; one DER pull "
            "of the loop scene (knotmech.scenes.loops.loop: the eye round a fixed pin, the "
            "standing part pulled) gives its slip load" + CAVEATS.get(key, ""))  # fmt: skip


def _refuse(key, *, post_diameter, mu_rr, wrap_angle, phase_table, free_end_load):
    """A loop has a pin (not a post), one friction, no wrap, no table, a free tail."""
    refuse_inputs(
        key, "loop", "its eye round a pin, give pin_diameter; mu is the rope-rope and "
        "rope-pin friction", free_end="the tail is free", post_diameter=post_diameter,
        mu_rr=mu_rr, wrap_angle=wrap_angle, phase_table=phase_table,
        free_end_load=free_end_load,
    )  # fmt: skip


def _pull(key, *, d, D, E, mu, load, mat, kappa, progress):
    """One DER pull of the loop: (details, answers: the DER's, empty when it did not decide,
    the last frame for ``--plot``)."""
    from knotmech.rod import SolverOptions
    from knotmech.scenes.loops import loop

    kw = {"density": mat.density} if mat is not None else {}
    kw["options"] = SolverOptions(max_wall_per_sim_second=BEND_WALL_RATE)
    if kappa != 1.0:
        kw["bending_scale"] = kappa
    r = loop(key, pin_diameter=D, rod_diameter=d, youngs_modulus=E, mu_rod_rod=mu,
             progress=progress, **kw)  # fmt: skip
    der = {
        "source": "simulation", "scene": "knotmech.scenes.loops.loop", "kind": key,
        "verdict": r.verdict, "slip_load": r.slip_load, "max_force": r.max_force,
        "pull_speed": r.pull_speed, "status": r.status, "message": r.message,
        "topology_preserved": bool(r.topology_preserved), "slipped_by": r.slipped_by,
        "tail_draw_in": float(r.tail_draw_in[-1]) if r.tail_draw_in.size else math.nan,
        "eye_growth": float(r.eye_growth[-1]) if r.eye_growth.size else math.nan,
        "law": r.law, "frames_checked": r.frames_checked,
        "held_to_strain_limit": bool(getattr(r, "held_to_strain_limit", False)),
        "wall_s": float(r.stats.get("wall_s", math.nan)),
    }  # fmt: skip
    holds, capacity, der["message"] = _pull_outcome(key, r, load)
    der["holds"] = holds
    shape = run_shape(r, d=d, support_diameter=D, support="pin")
    if holds is None:
        return der, (), shape
    return der, (_answer(key, r, holds, capacity, load, kappa, der["message"]),), shape


def _answer(key, r, holds, capacity, load, kappa, message):
    """The pull's deciding :class:`~knotmech.analytic.hitch.ModelAnswer`."""
    rec = knots.get(key)
    return run_answer(
        holds=holds, capacity=capacity, load=load,
        assumptions=(
            f"one elastic rod (B = kappa E pi d^4/64, kappa = {kappa:g}), {r.law}, "
            f"{rec.loading} at {r.pull_speed * 1e3:g} mm/s, pin diameter "
            f"{r.pin_diameter * 1e3:g} mm",
            "slip: the tail draws in, or the eye grows, by more than 2 d while the pull "
            "force stays within 10 % of its largest value",
        ),
        validity=("one DER pull of the loop at this d, D, E and mu",),
        reference="; ".join(rec.sources) + "; knotmech.scenes.loops", message=message,
    )  # fmt: skip


def loop_capacity(v: Verdict, material) -> Verdict:
    """The verdict with its capacity: the slip load of the DER pull when one ran (a point
    value; a hold: open above, :func:`knotmech.verdict.bend.der_slip_band`), and the
    loop's breaking load (:mod:`knotmech.strength`); at or above the breaking load it
    breaks."""
    from knotmech.verdict import capacity as _cap

    slip = der_slip_band(v, "loop")
    load = v.inputs["load"]
    cap = _cap.capacity_of(knot=v.knot, slip=slip, material=v.inputs.get("material", material),
                           d=v.inputs["rod_diameter"], D=v.inputs["pin_diameter"],
                           load=load)  # fmt: skip
    brk = cap.breaking
    if v.holds is not None and brk is not None and load >= brk.value:
        return replace(v, capacity=cap, holds=False, fails_by="break")
    return replace(v, capacity=cap, fails_by="slip" if v.holds is False else None)

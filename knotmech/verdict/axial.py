"""The hold verdict of a hitch loaded along its pole (the Prusik, the rolling hitch): no
closed form and no table; with ``simulate`` one DER drag of the axial scene
(:func:`knotmech.scenes.axial.axial_pull`), its sliding force against the load; the breaking
load from :mod:`knotmech.strength` where it has the knot."""

from __future__ import annotations

import math

from knotmech import knots
from knotmech.errors import InputError, check_nonnegative, check_positive
from knotmech.verdict._run import run_answer, run_shape
from knotmech.verdict.answer import Verdict
from knotmech.verdict.command import simulate_command
from knotmech.verdict.inputs import _bending_scale, _warnings, _youngs_modulus
from knotmech.verdict.scope import BOTH_LEGS_KNOTS

__all__ = ["AXIAL_HOLD_KNOTS", "AXIAL_COST", "BOTH_LEGS_KNOTS", "hold_axial", "with_capacity"]

#: knots whose hold question is a pull along the pole
AXIAL_HOLD_KNOTS = ("prusik", "rolling-hitch")
#: turns a side of the Prusik that ``hold`` simulates (the common three-wrap Prusik)
PRUSIK_WRAPS = 3
#: the turns ``hold`` simulates, by knot (None: the knot's own)
HOLD_WRAPS = {"prusik": PRUSIK_WRAPS, "rolling-hitch": None}
#: what the drag is, in words, by knot
_DRAGGED = {
    "prusik": f"one DER drag along the pole ({PRUSIK_WRAPS} turns a side)",
    "rolling-hitch": "one DER drag of its standing part along the pole (two riding turns)",
}
#: what one drag costs (measured: docs/notes/knots-and-curves/axial-hitches.md)
AXIAL_COST = (
    "one DER drag of a three-turn Prusik, about 2-5 minutes of CPU for a solid rod (a fibre "
    "rope's bending scale costs more)"
)
#: the same, by knot
AXIAL_COSTS = {
    "prusik": AXIAL_COST,
    "rolling-hitch": "one DER drag of a rolling hitch: 30 s of CPU at 90 nodes and 20 mm/s, "
    "not timed at hold's defaults (edges of 3.1 mm, 10 mm/s: a few minutes expected) for a solid "
    "rod (a fibre rope's bending scale costs more)",
}
#: the legs' pre-tension of the simulated set, as a fraction of the load (each leg)
SET_FRACTION = 0.1


def hold_axial(
    key, *, rod_diameter, post_diameter, mu, load, free_end_load, mu_rr, wrap_angle, material,
    youngs_modulus, simulate, phase_table, progress, bending_scale=None,
) -> Verdict:  # fmt: skip
    """The verdict on ``key`` (keywords of :func:`knotmech.hold`): undecided with the
    command that decides, or one DER drag along the pole."""
    if post_diameter is None:
        raise InputError(f"post_diameter is required for {key} (the pole or rope it grips)")
    d = float(check_positive("rod_diameter", rod_diameter, scalar=True))
    D = float(check_positive("post_diameter", post_diameter, scalar=True))
    mu = float(check_nonnegative("mu", mu, scalar=True))
    load = float(check_positive("load", load, scalar=True))
    _refuse(key, wrap_angle=wrap_angle, phase_table=phase_table, free_end_load=free_end_load)
    E, mat, e_source = _youngs_modulus(material, youngs_modulus)
    kappa, k_source = _bending_scale(mat, bending_scale)
    inputs = {"rod_diameter": d, "post_diameter": D, "mu": mu, "load": load,
              "bending_scale": kappa, "wraps": HOLD_WRAPS[key] or 2}  # fmt: skip
    if mat is not None:
        inputs["material"] = mat.key
    if E is not None:
        inputs["youngs_modulus"] = E
    cmd = simulate_command(key, d=d, D=D, mu=mu, mu_rr=mu_rr, load=load,
                           material=None if mat is None else mat.key,
                           youngs_modulus=youngs_modulus, bending_scale=bending_scale)  # fmt: skip
    rec = knots.get(key)
    common = dict(
        knot=key, assumptions=tuple(([e_source] if e_source else []) + [k_source]),
        warnings=_warnings(mu, mu_rr, d, D, load, E, None), inputs=inputs,
        notes=(f"{key}: {rec.loading}; no closed form and no DER table; {_DRAGGED[key]} "
               "gives its sliding force",),
    )  # fmt: skip
    if not simulate:
        return Verdict(holds=None, margin=math.nan, decided_by=None, inside_validity=False,
                       answers=(), next_step=f"next: {cmd} ({AXIAL_COSTS[key]}) decides it",
                       **common)  # fmt: skip
    if E is None:
        from knotmech.materials import material_names

        raise InputError(
            "simulate needs the rope's stiffness: give material (one of "
            f"{', '.join(material_names())}) or youngs_modulus"
        )
    mrr = mu if mu_rr is None else float(check_nonnegative("mu_rr", mu_rr, scalar=True))
    der, answers, shape = _drag(key, d=d, D=D, E=E, mu=mu, mu_rr=mrr, load=load, mat=mat,
                                kappa=kappa, progress=progress)  # fmt: skip
    return Verdict(
        holds=der["holds"], margin=answers[0].margin if answers else math.nan,
        decided_by="DER-simulation" if answers else None, inside_validity=bool(answers),
        answers=answers, validity=answers[0].validity if answers else (),
        next_step="" if answers else f"next: test the knot ({der['message']})",
        der=der, shape=shape, **common,
    )  # fmt: skip


def _refuse(key, *, wrap_angle, phase_table, free_end_load) -> None:
    """No wrap angle (the knot sets its turns), no table, no free end."""
    for name, val in (("wrap_angle", wrap_angle), ("phase_table", phase_table)):
        if val is not None:
            raise InputError(f"{name} does not apply to the {key} (pulled along its pole)")
    if float(free_end_load or 0.0) != 0.0:
        why = (
            "a closed sling, no end" if key == "prusik" else "its working end is set at 0.1 x load"
        )
        raise InputError(f"free_end_load does not apply to the {key} ({why})")


def _drag(key, *, d, D, E, mu, mu_rr, load, mat, kappa, progress):
    """One DER drag: (details, answers: the DER's, empty when it did not decide, the last
    frame for ``--plot``)."""
    from knotmech.scenes.axial import axial_pull

    kw = {"density": mat.density} if mat is not None else {}
    r = axial_pull(key, wraps=HOLD_WRAPS[key], rod_diameter=d, post_diameter=D, youngs_modulus=E,
                   bending_scale=kappa, mu_rod_post=mu, mu_rod_rod=mu_rr,
                   normal_load=SET_FRACTION * load, force_scale=2.0 * load, progress=progress,
                   **kw)  # fmt: skip
    der = {
        "source": "simulation", "scene": "knotmech.scenes.axial.axial_pull", "knot": key,
        "wraps": r.wraps, "sliding_force": r.sliding_force, "peak_force": r.peak_force,
        "slid": r.slid, "status": r.status, "message": r.message,
        "topology_preserved": bool(r.topology_preserved),
        "wall_s": float(r.stats.get("wall_s", math.nan)),
    }  # fmt: skip
    holds, capacity, der["message"] = _outcome(key, r, load)
    der["holds"] = holds
    shape = run_shape(r, d=d, support_diameter=D, support="pole")
    if holds is None:
        return der, (), shape
    return der, (_answer(key, r, holds, capacity, load, kappa, der["message"]),), shape


def _outcome(key, r, load):
    """(holds or None, capacity [N], message) of a drag against ``load`` [N]."""
    if r.status != "success" or not r.topology_preserved:
        why = r.message if r.status != "success" else "its knot type changed"
        return None, math.nan, f"DER drag of the {key}: no verdict ({why})"
    if r.slid and math.isfinite(r.sliding_force):
        return (
            load < r.sliding_force,
            float(r.sliding_force),
            (f"DER drag of the {key}: slides at {r.sliding_force:.4g} N along the pole"),
        )
    if load <= r.peak_force:
        return (
            True,
            float(r.peak_force),
            (f"DER drag of the {key}: did not slide up to {r.peak_force:.4g} N"),
        )
    return None, math.nan, (
        f"DER drag of the {key}: did not slide up to {r.peak_force:.4g} N, below the load "
        f"{load:.4g} N: not decided")  # fmt: skip


def _answer(key, r, holds, capacity, load, kappa, message):
    """The drag's deciding :class:`~knotmech.analytic.hitch.ModelAnswer`."""
    rec = knots.get(key)
    return run_answer(
        holds=holds, capacity=capacity, load=load,
        assumptions=(
            f"an elastic rod (B = kappa E pi d^4/64, kappa = {kappa:g}) on a rigid pole, "
            f"sticking friction; {rec.loading}, set at {SET_FRACTION:g} x the load on each "
            f"leg, then dragged at {r.drag_speed * 1e3:g} mm/s",
            f"slides: the wraps travel {r.slide_distance * 1e3:.3g} mm (one rod diameter)",
        ),
        validity=("one DER drag of this knot at this d, D, E and mu",),
        reference="; ".join(rec.sources) + "; knotmech.scenes.axial", message=message,
    )  # fmt: skip


def with_capacity(v: Verdict, material) -> Verdict:
    """``v`` with its capacity: the sliding force of its DER drag (a point value) when one
    ran, and the knot's breaking load (:mod:`knotmech.strength`); at or above the breaking
    load it breaks."""
    from dataclasses import replace

    from knotmech.verdict import capacity as _cap

    dec = v.deciding
    slip = None
    if dec is not None and math.isfinite(dec.capacity):
        slip = _cap.LoadBand(dec.capacity, dec.capacity, dec.capacity, "DER drag along the pole")
    load = v.inputs["load"]
    cap = _cap.capacity_of(knot=v.knot, slip=slip, material=v.inputs.get("material", material),
                           d=v.inputs["rod_diameter"], D=v.inputs["post_diameter"],
                           load=load)  # fmt: skip
    brk = cap.breaking
    if v.holds is not None and brk is not None and load >= brk.value:
        return replace(v, capacity=cap, holds=False, fails_by="break")
    return replace(v, capacity=cap, fails_by="slip" if v.holds is False else None)

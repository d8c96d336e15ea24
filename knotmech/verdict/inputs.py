"""The inputs of the hold verdict: the rope's stiffness (Young's modulus, bending scale) from
the user or a material preset, and the implausible-input warnings."""

from __future__ import annotations

import math

from knotmech.errors import InputError, check_positive
from knotmech.materials import STRAIN_LIMIT
from knotmech.verdict.answer import InputWarning

__all__ = ["STRAIN_LIMIT", "MU_PLAUSIBLE", "WRAP_TURNS_PLAUSIBLE"]

MU_PLAUSIBLE = 2.0  #: a friction coefficient above this is implausible for rope
WRAP_TURNS_PLAUSIBLE = 20.0  #: a capstan wrap beyond this many turns is implausible


# --------------------------------------------------------------------------- inputs
#: [Pa] the moduli a rope or rod can have (soft gels ~1e2 Pa to diamond ~1e12 Pa); the
#: recording format bounds ``youngs_modulus_Pa`` the same way (docs/recordings.md sec. 6)
YOUNGS_MODULUS_RANGE = (1e2, 1e13)


def _youngs_modulus(material, youngs_modulus):
    """(E [Pa] or None, material or None, what was assumed)."""
    from knotmech.materials import format_modulus as fm
    from knotmech.materials import material as get_material

    mat = None if material is None else get_material(material)
    if youngs_modulus is not None:
        E = check_positive("youngs_modulus", youngs_modulus, scalar=True)
        if not YOUNGS_MODULUS_RANGE[0] <= E <= YOUNGS_MODULUS_RANGE[1]:
            lo, hi = YOUNGS_MODULUS_RANGE
            raise InputError(
                f"youngs_modulus {E:g} Pa is outside {lo:g}-{hi:g} Pa (soft gels to diamond); "
                "no rope or rod is made of it"
            )
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

"""The effect catalogue: the physics a baseline leaves out, as model augmentations.

Each :class:`Effect` names the experiments it applies to, its parameters with
their no-effect values, what it needs from the recording, the effects it can be
confused with, the residual shape it leaves on the baseline, and a reference.
The mean functions that implement the augmentations are in
:mod:`knotmech.diagnose.baselines`; the engine adds effects one at a time.

Names are those of ``shared/spec/recordings.md`` section 3.
"""

from __future__ import annotations

from dataclasses import dataclass

from knotmech.diagnose.recording import Recording

__all__ = ["Effect", "CATALOGUE", "applicable_effects", "missing_requirements"]

CLOVE = (
    "clove-hitch paper: Exploring the inner workings of the clove hitch knot, "
    "Extreme Mech. Lett. (2022), doi:10.1016/j.eml.2022.101788"
)


@dataclass(frozen=True)
class Effect:
    """One catalogue entry.

    Attributes
    ----------
    name : str
        Spec name (``static_friction`` ...).
    experiments : tuple of str
        Experiment kinds it applies to.
    parameters : dict
        Parameter name -> (no-effect value, meaning with units).
    requires : tuple of str
        ``mu_nominal`` (an independent friction coefficient) and/or ``speed``
        (at least two sliding speeds, see :mod:`knotmech.diagnose.recording`).
    confusable_with : tuple of str
        Effects whose signature overlaps.
    signature : str
        The residual shape it leaves on the baseline (used in the summary).
    reference : str
    repeatable : bool
        May be added more than once (one nip per addition).
    """

    name: str
    experiments: tuple
    parameters: dict
    requires: tuple
    confusable_with: tuple
    signature: str
    reference: str
    repeatable: bool = False
    acts_everywhere: bool = False


CATALOGUE: dict[str, Effect] = {
    e.name: e
    for e in (
        Effect(
            "static_friction",
            ("capstan_pull",),
            {
                "mu_static": ("= mu_kinetic", "static coefficient reached at the onset of sliding"),
                "mu_kinetic": ("mu", "kinetic coefficient of the sliding plateau"),
                "decay_length_m": ("any", "displacement over which the peak relaxes [m]"),
            },
            (),
            ("displacement_offset",),
            "a force peak at the onset of sliding, then a drop",
            CLOVE + ", Fig. 1(c): two-loops peak absent from FEM with kinetic friction only",
        ),
        Effect(
            "finite_thickness",
            ("capstan_pull", "tension_profile"),
            {
                "mu": ("mu_nominal", "material friction coefficient (prior mu_nominal)"),
                "mu_eff": ("= mu", "effective coefficient mu_eff(mu, D/d) seen by the capstan"),
            },
            ("mu_nominal",),
            ("rate_dependent_friction",),
            "a slower decay / lower ratio than mu_nominal predicts (a global rate error)",
            CLOVE + ", eq. (3)",
            acts_everywhere=True,
        ),
        Effect(
            "contact_flattening",
            ("pinch",),
            {
                "onset_load_parameter": ("any", "x_c = 4 F_c/(pi E d D) where the bend starts"),
                "slope_ratio": (1.0, "slope of F_t beyond the onset / 2 mu"),
            },
            (),
            ("rate_dependent_friction",),
            "sub-linear F_t beyond a load parameter (a bend at high load)",
            CLOVE + ", sec. 9 and Fig. 5(d): Amontons holds for 4F_n/(pi E d D) < ~0.1",
        ),
        Effect(
            "adhesion",
            ("pinch",),
            {"adhesion_force_N": (0.0, "load-independent tangential force [N]")},
            (),
            (),
            "an intercept at zero normal load",
            "Bowden & Tabor, The Friction and Lubrication of Solids (1950): F = mu N + F_a",
            acts_everywhere=True,
        ),
        Effect(
            "self_contact_nip",
            ("tension_profile",),
            {
                "positions_m": ([], "arc lengths of the tension drops [m]"),
                "drop_fractions": ([], "fraction of the tension lost at each drop"),
            },
            (),
            (),
            "discrete tension drops at certain arc lengths (steps)",
            CLOVE + ", sec. 7 and Fig. 3(b): nip regions",
            repeatable=True,
        ),
        Effect(
            "displacement_offset",
            ("capstan_pull",),
            {"offset_m": (0.0, "pre-stretch: true displacement = recorded + offset_m [m]")},
            (),
            ("static_friction",),
            "the whole curve shifted along x (tension above T_low at zero displacement)",
            "Measurement practice: zero of the displacement axis set under pre-tension",
        ),
        Effect(
            "rate_dependent_friction",
            ("capstan_pull", "pinch"),
            {
                "dmu_dlnv": (0.0, "d mu / d ln(v): change of mu per e-fold of speed"),
                "reference_speed_m_per_s": ("-", "geometric-mean speed at which mu is reported"),
            },
            ("speed",),
            ("finite_thickness", "contact_flattening"),
            "a plateau level (friction) that changes with sliding speed",
            "Rabinowicz, The Friction and Wear of Materials (1995): velocity-dependent friction",
            acts_everywhere=True,
        ),
    )
}


def missing_requirements(effect: Effect, rec: Recording) -> list:
    """What ``rec`` lacks for ``effect`` (empty when it can be tested)."""
    out = []
    if "mu_nominal" in effect.requires and rec.mu_nominal is None:
        out.append("mu_nominal metadata")
    if "speed" in effect.requires:
        if rec.speed is None:
            out.append("sliding speeds (speed_m_per_s column or metadata)")
        elif len(set(rec.speed.tolist())) < 2:
            out.append("at least two different sliding speeds")
    return out


def applicable_effects(rec: Recording) -> tuple[list, dict]:
    """Effects of ``rec``'s experiment that can be tested, and the skipped ones with why."""
    ok, skipped = [], {}
    for e in CATALOGUE.values():
        if rec.experiment not in e.experiments:
            continue
        miss = missing_requirements(e, rec)
        if miss:
            skipped[e.name] = "needs " + " and ".join(miss)
        else:
            ok.append(e.name)
    return ok, skipped

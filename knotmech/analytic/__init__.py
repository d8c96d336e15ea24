"""Closed-form mechanics of capstans and knots: pure, vectorised functions in SI units.

This subpackage imports nothing of knotmech except the leaf module
:mod:`knotmech.errors`, so a classroom can use it alone. Modules:

- :mod:`~knotmech.analytic.capstan`: ideal and finite-thickness capstan, mu_eff(D/d),
  bending-rigidity and nonlinear-friction (Howell) capstans.
- :mod:`~knotmech.analytic.hitch`: ideal-rope hitch criteria (Bayman 1977; Maddocks &
  Keller 1987), a finite-thickness nip model, and the `hold` verdict.
- :mod:`~knotmech.analytic.film`: Landau-Levich-Derjaguin film thickness (plate, fibre,
  White-Tallmadge) with regime selection.
- :mod:`~knotmech.analytic.pinch`: Amontons pinch law, load parameter, Hertz contact.
- :mod:`~knotmech.analytic.knots`: overhand-knot laws of Jawed et al. 2015 and Audoly et al. 2007.
- :mod:`~knotmech.analytic.coating`: the coated-rod paper's mu versus particle fraction.
- :mod:`~knotmech.analytic.registry`: a table of all closed forms for sweeps and tests.
"""

from knotmech.analytic.capstan import (
    bending_parameter,
    capstan_end_factors,
    capstan_high_tension_nonlinear,
    capstan_ratio,
    capstan_ratio_bending,
    capstan_ratio_nonlinear,
    capstan_ratio_thick,
    capstan_ratio_thick_ends,
    capstan_tension_profile,
    liftoff_angle,
    mu_eff,
    mu_from_capstan_test,
    mu_from_mu_eff,
)
from knotmech.analytic.coating import (
    coated_rod_coverage,
    coated_rod_mu,
    coated_rod_volume_fraction,
)
from knotmech.analytic.film import (
    FilmThickness,
    capillary_length,
    capillary_number,
    film_thickness,
    film_thickness_fibre,
    film_thickness_fibre_white_tallmadge,
    film_thickness_plate,
)
from knotmech.analytic.hitch import (
    FREE_END_STATEMENT,
    KNOTS,
    HoldVerdict,
    ModelAnswer,
    hitch_critical_mu,
    hitch_holds,
    hitch_margin,
    hold_verdict,
    ideal_hitch_ratio,
    nip_factor,
    thick_hitch_ratio,
)
from knotmech.analytic.knots import (
    OverhandKnot,
    braid_contact_force_per_length,
    braid_friction_force,
    braid_wavenumber,
    loop_closure,
    loose_knot_force,
    loose_knot_force_from_shortening,
    overhand_knot,
    overhand_pull_force,
)
from knotmech.analytic.pinch import (
    PINCH_AMONTONS_LIMIT,
    HertzContact,
    effective_modulus,
    hertz_circular_contact,
    hertz_crossed_cylinders,
    pinch_amontons_applies,
    pinch_load_parameter,
    pinch_sliding_force,
)

__all__ = [
    # capstan
    "capstan_ratio",
    "capstan_ratio_thick",
    "capstan_end_factors",
    "capstan_ratio_thick_ends",
    "capstan_tension_profile",
    "mu_eff",
    "mu_from_mu_eff",
    "mu_from_capstan_test",
    "capstan_ratio_bending",
    "bending_parameter",
    "liftoff_angle",
    "capstan_ratio_nonlinear",
    "capstan_high_tension_nonlinear",
    # hitches
    "hold_verdict",
    "HoldVerdict",
    "ModelAnswer",
    "hitch_holds",
    "hitch_critical_mu",
    "hitch_margin",
    "ideal_hitch_ratio",
    "thick_hitch_ratio",
    "nip_factor",
    "FREE_END_STATEMENT",
    "KNOTS",
    # film
    "film_thickness_plate",
    "film_thickness_fibre",
    "film_thickness_fibre_white_tallmadge",
    "film_thickness",
    "FilmThickness",
    "capillary_number",
    "capillary_length",
    # pinch
    "pinch_load_parameter",
    "pinch_sliding_force",
    "pinch_amontons_applies",
    "PINCH_AMONTONS_LIMIT",
    "effective_modulus",
    "hertz_circular_contact",
    "hertz_crossed_cylinders",
    "HertzContact",
    # knots
    "overhand_pull_force",
    "overhand_knot",
    "OverhandKnot",
    "braid_wavenumber",
    "braid_friction_force",
    "braid_contact_force_per_length",
    "loop_closure",
    "loose_knot_force",
    "loose_knot_force_from_shortening",
    # coating
    "coated_rod_mu",
    "coated_rod_volume_fraction",
    "coated_rod_coverage",
]

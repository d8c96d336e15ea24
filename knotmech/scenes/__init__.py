"""The papers' experiments rebuilt on the DER solver, and the knot curves they start from.

- :mod:`~knotmech.scenes.capstan`: a rod pulled over (or held on) a fixed post; two loops.
- :mod:`~knotmech.scenes.pinch`: a rod pinched between two crossed cylinders, pulled out.
- :mod:`~knotmech.scenes.clove_hitch`: a clove hitch on a post under symmetric, asymmetric
  or free-end loading; tension profile, contact regions, Darboux vector.
- :mod:`~knotmech.scenes.overhand`: overhand knots with n = 1..4 turns pulled tight.
- :mod:`~knotmech.scenes.curves`: parametric knot centrelines (overhand, clove hitch, coil).
- :mod:`~knotmech.scenes.topology`: knot invariants (Alexander polynomial, determinant),
  winding about a post: the no-pass-through checks.
- :mod:`~knotmech.scenes.phase_table`: the precomputed clove-hitch hold/slip table.
- :mod:`~knotmech.scenes.bends`: two ropes joined by a reef, granny, thief or grief bend
  (:mod:`~knotmech.scenes.bend_curves`), pulled apart until it slips.
- :mod:`~knotmech.scenes.centreline`: a user's own knot from a CSV of points, pulled.
- :mod:`~knotmech.scenes._scene`: the shape scenes share (phases, grips, contacts).
"""

from knotmech.scenes.bend_curves import BendCurves, bend_closure, bend_curves, bend_invariants
from knotmech.scenes.bends import PATIL_ORDER, BendResult, bend
from knotmech.scenes.capstan import CapstanResult, capstan, capstan_two_loops
from knotmech.scenes.centreline import CentrelineResult, centreline, read_centreline
from knotmech.scenes.clove_hitch import CloveHitchResult, clove_hitch, darboux_profile
from knotmech.scenes.curves import (
    OVERHAND_COATED_TABLE1,
    OVERHAND_IMC,
    KnotCurve,
    clove_hitch_curve,
    coil_curve,
    end_to_end,
    loop_metrics,
    min_separation,
    overhand_coated,
    overhand_imc,
    overhand_knot,
    resample_polyline,
)
from knotmech.scenes.overhand import (
    COATED_MU,
    OverhandResult,
    OverhandSetup,
    coated_setup,
    imc_setup,
    inversion_points,
    overhand,
)
from knotmech.scenes.pinch import PinchResult, PinchSweep, pinch, pinch_sweep
from knotmech.scenes.topology import (
    Crossings,
    KnotInvariant,
    alexander_polynomial,
    close_curve,
    identify_knot,
    knot_determinant,
    knot_invariant,
    post_crossing_code,
    projection_crossings,
    torus_knot_polynomial,
    winding_number,
)

__all__ = [
    "bend",
    "BendResult",
    "PATIL_ORDER",
    "BendCurves",
    "bend_curves",
    "bend_closure",
    "bend_invariants",
    "centreline",
    "CentrelineResult",
    "read_centreline",
    "capstan",
    "capstan_two_loops",
    "CapstanResult",
    "pinch",
    "pinch_sweep",
    "PinchResult",
    "PinchSweep",
    "clove_hitch",
    "CloveHitchResult",
    "darboux_profile",
    "overhand",
    "OverhandResult",
    "OverhandSetup",
    "imc_setup",
    "coated_setup",
    "inversion_points",
    "COATED_MU",
    "KnotCurve",
    "OVERHAND_COATED_TABLE1",
    "OVERHAND_IMC",
    "overhand_knot",
    "overhand_coated",
    "overhand_imc",
    "clove_hitch_curve",
    "coil_curve",
    "resample_polyline",
    "min_separation",
    "end_to_end",
    "loop_metrics",
    "KnotInvariant",
    "Crossings",
    "close_curve",
    "projection_crossings",
    "knot_invariant",
    "alexander_polynomial",
    "knot_determinant",
    "torus_knot_polynomial",
    "identify_knot",
    "winding_number",
    "post_crossing_code",
]

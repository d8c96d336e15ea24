"""The papers' experiments rebuilt on the DER solver, and the knot curves they start from.

- :mod:`~knotmech.scenes.capstan`: a rod pulled over (or held on) a fixed post; two loops.
- :mod:`~knotmech.scenes.pinch`: a rod pinched between two crossed cylinders, pulled out.
- :mod:`~knotmech.scenes.clove_hitch`: a clove hitch on a post under symmetric, asymmetric
  or free-end loading; tension profile, contact regions, Darboux vector.
- :mod:`~knotmech.scenes.two_half_hitches`, :mod:`~knotmech.scenes.round_turn_two_half_hitches`,
  :mod:`~knotmech.scenes.cow_hitch`: more post hitches, the clove hitch's keywords
  (:mod:`~knotmech.scenes._hitch`, the scene they share; :mod:`~knotmech.scenes.hitches`,
  all four by name; start curves in :mod:`~knotmech.scenes.hitch_curves`).
- :mod:`~knotmech.scenes.overhand`: overhand knots with n = 1..4 turns pulled tight.
- :mod:`~knotmech.scenes.curves`: parametric knot centrelines (overhand, clove hitch, coil).
- :mod:`~knotmech.scenes.topology`: knot invariants (Alexander polynomial, determinant),
  winding about a post: the no-pass-through checks.
- :mod:`~knotmech.scenes.phase_table`: the precomputed clove-hitch hold/slip table.
- :mod:`~knotmech.scenes.bends`: two ropes joined by a reef, granny, thief or grief bend
  (:mod:`~knotmech.scenes.bend_curves`), pulled apart until it slips.
- :mod:`~knotmech.scenes.centreline`: a user's own knot from a CSV of points, pulled.
- :mod:`~knotmech.scenes._scene`: the shape scenes share (phases, grips, contacts).

The names are loaded on first use: the scenes import the DER solver (numba, seconds), which
``knotmech hold`` answering from :mod:`~knotmech.scenes.phase_table` must not pay. The
package behaves as if it had imported them all: ``knotmech.scenes.capstan`` is the function
:func:`~knotmech.scenes.capstan.capstan` (the submodule is ``sys.modules[...]``), whether or
not the submodule has been imported already.
"""

from __future__ import annotations

import importlib
import sys
import types

#: public name -> submodule defining it
_SUBMODULE = {
    "BendCurves": "bend_curves",
    "bend_closure": "bend_curves",
    "bend_curves": "bend_curves",
    "bend_invariants": "bend_curves",
    "PATIL_ORDER": "bends",
    "BendResult": "bends",
    "bend": "bends",
    "CentrelineResult": "centreline",
    "centreline": "centreline",
    "read_centreline": "centreline",
    "CapstanResult": "capstan",
    "capstan": "capstan",
    "capstan_two_loops": "capstan",
    "CloveHitchResult": "clove_hitch",
    "clove_hitch": "clove_hitch",
    "darboux_profile": "clove_hitch",
    "HitchResult": "_hitch",
    "two_half_hitches": "two_half_hitches",
    "round_turn_two_half_hitches": "round_turn_two_half_hitches",
    "cow_hitch": "cow_hitch",
    "HITCHES": "hitches",
    "hitch": "hitches",
    "hitch_curve": "hitch_curves",
    "hitch_invariants": "hitch_curves",
    "OVERHAND_COATED_TABLE1": "curves",
    "OVERHAND_IMC": "curves",
    "KnotCurve": "curves",
    "clove_hitch_curve": "curves",
    "coil_curve": "curves",
    "end_to_end": "curves",
    "loop_metrics": "curves",
    "min_separation": "curves",
    "overhand_coated": "curves",
    "overhand_imc": "curves",
    "overhand_knot": "curves",
    "resample_polyline": "curves",
    "COATED_MU": "overhand",
    "OverhandResult": "overhand",
    "OverhandSetup": "overhand",
    "coated_setup": "overhand",
    "imc_setup": "overhand",
    "inversion_points": "overhand",
    "overhand": "overhand",
    "PinchResult": "pinch",
    "PinchSweep": "pinch",
    "pinch": "pinch",
    "pinch_sweep": "pinch",
    "Crossings": "topology",
    "KnotInvariant": "topology",
    "alexander_polynomial": "topology",
    "close_curve": "topology",
    "identify_knot": "topology",
    "knot_determinant": "topology",
    "knot_invariant": "topology",
    "post_crossing_code": "topology",
    "projection_crossings": "topology",
    "torus_knot_polynomial": "topology",
    "winding_number": "topology",
}


class _ScenesPackage(types.ModuleType):
    """Importing submodule ``capstan`` binds ``package.capstan`` to the module; the package
    exports the function of the same name there (capstan, pinch, clove_hitch, overhand)."""

    def __setattr__(self, name, value):
        if isinstance(value, types.ModuleType) and _SUBMODULE.get(name) == name:
            value = getattr(value, name, value)
        super().__setattr__(name, value)


def __getattr__(name: str):
    module = _SUBMODULE.get(name)
    if module is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(importlib.import_module(f"{__name__}.{module}"), name)
    globals()[name] = value
    return value


def __dir__():
    return sorted(set(globals()) | set(__all__))


sys.modules[__name__].__class__ = _ScenesPackage

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
    "HitchResult",
    "two_half_hitches",
    "round_turn_two_half_hitches",
    "cow_hitch",
    "HITCHES",
    "hitch",
    "hitch_curve",
    "hitch_invariants",
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

"""The papers' experiments rebuilt on the DER solver, and the knot curves they start from.

- :mod:`~knotmech.scenes.capstan`: a rod pulled over (or held on) a fixed post; two loops.
- :mod:`~knotmech.scenes.pinch`: a rod pinched between two crossed cylinders, pulled out.
- :mod:`~knotmech.scenes.clove_hitch`: a clove hitch on a post under symmetric, asymmetric
  or free-end loading; tension profile, contact regions, Darboux vector.
- ``two_half_hitches``, ``round_turn_two_half_hitches``, ``cow_hitch``: more post hitches,
  the clove hitch's keywords, made from their records in :mod:`knotmech.knots`
  (:mod:`~knotmech.scenes.hitches`: every hitch by name; :mod:`~knotmech.scenes._hitch`, the
  scene they share; start curves in :mod:`~knotmech.scenes.hitch_curves`, one file each).
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
``knotmech hold`` answering from the tables must not pay. A submodule named after its scene
function (:data:`SCENE_MODULES`: ``capstan``, ``pinch``, ``clove_hitch``, ``overhand``,
``centreline``, ``bend_curves``) is the module, as for any package: the function is
``knotmech.scenes.capstan.capstan`` (``from knotmech.scenes.capstan import capstan``). The
other names are the functions (``knotmech.scenes.bend``, ``knotmech.scenes.cow_hitch``: the
hitch scenes made from their records, :mod:`~knotmech.scenes.hitches`).
"""

from __future__ import annotations

import importlib

from knotmech.scenes.hitches import HITCHES

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


#: submodules whose main function has the submodule's name: ``knotmech.scenes.capstan`` is
#: the module (as for any package), the function is ``knotmech.scenes.capstan.capstan``
SCENE_MODULES = tuple(name for name, module in _SUBMODULE.items() if name == module)


def __getattr__(name: str):
    if name in HITCHES and name not in _SUBMODULE:  # a hitch scene made from its record
        from knotmech.scenes.hitches import hitch_function

        return hitch_function(name)
    module = _SUBMODULE.get(name)
    if module is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    if module == name:
        return importlib.import_module(f"{__name__}.{module}")
    value = getattr(importlib.import_module(f"{__name__}.{module}"), name)
    globals()[name] = value
    return value


def __dir__():
    return sorted(set(globals()) | set(__all__))


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
    *(name for name in HITCHES if name != "clove_hitch"),
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

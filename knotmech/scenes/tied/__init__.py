"""Start centrelines of the knots people tie, each with its topology stated and checked.

One module per knot, each exposing one function that returns a
:class:`~knotmech.scenes.tied._common.TiedKnot` (the ropes' nodes [m], which end is the
standing part or the tail, the pin, the expected invariants). :data:`TIED_KNOTS` maps the
knot's name to its function; :func:`~knotmech.scenes.tied._common.measure` computes the
invariants of any frame with the same ropes, for comparison with ``expected``. The design
pipeline and the closures are described in :mod:`knotmech.scenes.tied._common`; the
construction and topology of each knot in its module's docstring and in
``docs/notes/knots-and-curves/tied-knot-curves.md``.
"""

from __future__ import annotations

from knotmech.scenes.tied._common import KNOT_TABLE, TiedKnot, knot_name, measure
from knotmech.scenes.tied.alpine_butterfly import alpine_butterfly
from knotmech.scenes.tied.bowline import bowline
from knotmech.scenes.tied.double_fishermans import double_fishermans
from knotmech.scenes.tied.double_sheet_bend import double_sheet_bend
from knotmech.scenes.tied.figure_eight_bend import figure_eight_bend
from knotmech.scenes.tied.figure_eight_loop import figure_eight_loop
from knotmech.scenes.tied.flat_overhand_bend import flat_overhand_bend
from knotmech.scenes.tied.prusik import prusik
from knotmech.scenes.tied.sheet_bend import sheet_bend

__all__ = [
    "KNOT_TABLE",
    "TIED_KNOTS",
    "TiedKnot",
    "alpine_butterfly",
    "bowline",
    "double_fishermans",
    "double_sheet_bend",
    "figure_eight_bend",
    "figure_eight_loop",
    "flat_overhand_bend",
    "knot_name",
    "measure",
    "prusik",
    "sheet_bend",
]

#: knot name -> the function that ties it
TIED_KNOTS = {
    "bowline": bowline,
    "figure_eight_loop": figure_eight_loop,
    "alpine_butterfly": alpine_butterfly,
    "sheet_bend": sheet_bend,
    "double_sheet_bend": double_sheet_bend,
    "flat_overhand_bend": flat_overhand_bend,
    "figure_eight_bend": figure_eight_bend,
    "double_fishermans": double_fishermans,
    "prusik": prusik,
}

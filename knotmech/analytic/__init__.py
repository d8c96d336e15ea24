"""knotmech.analytic."""

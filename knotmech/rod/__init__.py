"""knotmech.rod."""

"""knotmech.diagnose."""

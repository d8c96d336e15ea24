"""knotmech.scenes."""

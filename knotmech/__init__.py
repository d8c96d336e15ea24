"""knotmech: mechanics of capstans and knots.

The public API is re-exported here explicitly; implementation lives in the
subpackages ``analytic`` (closed forms), ``rod`` (the discrete-elastic-rods
solver), ``scenes`` (experiments), ``diagnose`` (the mismatch engine).
"""

__version__ = "0.1.0"

from knotmech.errors import InputError, KnotmechError, RecordingError, SolverError

__all__ = ["__version__", "KnotmechError", "InputError", "SolverError", "RecordingError"]

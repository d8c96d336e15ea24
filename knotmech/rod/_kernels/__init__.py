"""Private numba kernels of the discrete-elastic-rods solver (one file per energy family).

Every kernel takes plain arrays, writes its results in place and cites the equation it
implements. Nothing here validates input: the Python layer in ``knotmech.rod`` does.
"""

"""Growable COO triplet buffer through which interactions add Jacobian blocks."""

from __future__ import annotations

import numpy as np

from ..errors import InputError

__all__ = ["Triplets"]


class Triplets:
    """Entries (row, col, value) of a sparse matrix, appended in blocks.

    Interactions append the entries of dF/dq (the derivative of the force they add, NOT
    its negative); repeated (row, col) pairs are summed when the matrix is built.
    ``wanted`` False tells them that the solver needs no Jacobian for this evaluation
    (they may skip their entries; adding them anyway is harmless).
    """

    wanted: bool = True

    def __init__(self, capacity: int = 1024):
        self._rows = np.empty(capacity, dtype=np.int64)
        self._cols = np.empty(capacity, dtype=np.int64)
        self._vals = np.empty(capacity)
        self.size = 0

    def clear(self) -> None:
        self.size = 0

    def _grow(self, n: int) -> None:
        if self.size + n > self._rows.size:
            cap = max(2 * self._rows.size, self.size + n)
            for name in ("_rows", "_cols", "_vals"):
                old = getattr(self, name)
                new = np.empty(cap, dtype=old.dtype)
                new[: self.size] = old[: self.size]
                setattr(self, name, new)

    def add(self, rows, cols, vals) -> None:
        """Append entries; the three arguments broadcast to one flat length."""
        r, c, v = np.broadcast_arrays(
            np.asarray(rows, dtype=np.int64),
            np.asarray(cols, dtype=np.int64),
            np.asarray(vals, dtype=float),
        )
        r, c, v = r.ravel(), c.ravel(), v.ravel()
        n = r.size
        self._grow(n)
        self._rows[self.size : self.size + n] = r
        self._cols[self.size : self.size + n] = c
        self._vals[self.size : self.size + n] = v
        self.size += n

    def reserve(self, n: int):
        """Room for up to ``n`` more entries: writable views (rows, cols, vals) of length
        ``n`` past the current end; fill a prefix of them, then :meth:`commit` its length
        (lets a kernel write its entries in place, without temporaries)."""
        n = int(n)
        self._grow(n)
        k = self.size
        return self._rows[k : k + n], self._cols[k : k + n], self._vals[k : k + n]

    def commit(self, n: int) -> None:
        """Keep ``n`` entries written into the views of the last :meth:`reserve`."""
        n = int(n)
        if n < 0 or self.size + n > self._rows.size:
            raise InputError(f"commit of {n} entries exceeds the reserved room")
        self.size += n

    @property
    def rows(self) -> np.ndarray:
        return self._rows[: self.size]

    @property
    def cols(self) -> np.ndarray:
        return self._cols[: self.size]

    @property
    def vals(self) -> np.ndarray:
        return self._vals[: self.size]

    def __len__(self) -> int:
        return self.size

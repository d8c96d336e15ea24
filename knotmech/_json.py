"""One JSON encoder for knotmech's output files: strict JSON, scalars kept scalar.

Every JSON file knotmech writes goes through :func:`dumps` (or :func:`write`):

- the output is strict JSON (RFC 8259): a non-finite float (NaN, +-inf) is written as
  ``null``, never as ``NaN``/``Infinity`` nor as a string mixed with numbers;
- NumPy scalars become Python numbers of the same kind (``np.int64(1091)`` -> ``1091``,
  never ``1091.0``), NumPy booleans become ``true``/``false``, arrays become lists,
  dataclasses become objects, paths become strings.

:func:`split_arrays` separates a result's scalars (for the JSON) from its arrays (for
CSV or NPZ files), so that a "scalars" JSON holds scalars only.
"""

from __future__ import annotations

import dataclasses
import json
import math
import os
from collections.abc import Mapping

import numpy as np

__all__ = ["dumps", "jsonable", "split_arrays", "write"]


def jsonable(obj):
    """Plain-Python, strict-JSON form of ``obj`` (see the module docstring).

    Parameters
    ----------
    obj : object
        Nested dicts, lists, tuples, dataclasses, NumPy arrays and scalars, str, bool,
        int, float, None, paths.

    Returns
    -------
    object
        The same structure made of dict, list, str, int, float (finite), bool and None.

    Raises
    ------
    TypeError
        An object of another type (a programming error, not user input).
    """
    if obj is None or isinstance(obj, (str, bool)):
        return obj
    if isinstance(obj, (np.bool_,)):
        return bool(obj)
    if isinstance(obj, (int, np.integer)):
        return int(obj)
    if isinstance(obj, (float, np.floating)):
        value = float(obj)
        return value if math.isfinite(value) else None
    if isinstance(obj, os.PathLike):
        return os.fspath(obj)
    if dataclasses.is_dataclass(obj) and not isinstance(obj, type):
        return {f.name: jsonable(getattr(obj, f.name)) for f in dataclasses.fields(obj)}
    if isinstance(obj, Mapping):
        return {str(k): jsonable(v) for k, v in obj.items()}
    if isinstance(obj, np.ndarray):
        return jsonable(obj.tolist())
    if isinstance(obj, (list, tuple)):
        return [jsonable(v) for v in obj]
    raise TypeError(f"cannot write {type(obj).__name__} as JSON")


def dumps(obj, *, indent: int | None = 2) -> str:
    """Strict JSON text of ``obj`` (see :func:`jsonable`)."""
    return json.dumps(jsonable(obj), indent=indent, allow_nan=False)


def write(path, obj, *, indent: int | None = 2) -> None:
    """Write ``obj`` as strict JSON (with a final newline) to ``path``."""
    text = dumps(obj, indent=indent)
    with open(path, "w", encoding="utf-8") as fh:
        fh.write(text + "\n")


def _is_scalar(value) -> bool:
    return value is None or isinstance(value, (str, bool, int, float, np.generic))


def split_arrays(obj) -> tuple[dict, dict[str, np.ndarray]]:
    """Split a result into its scalars and its arrays.

    Parameters
    ----------
    obj : dataclass instance or mapping
        For example a scene result. Scalars (numbers, strings, booleans, None), lists of
        strings (warnings) and mappings or dataclasses of scalars (``stats``, a parameter
        set) stay; arrays and sequences of numbers go to the second dict (nested names
        joined with ``.``).

    Returns
    -------
    scalars : dict
        For :func:`dumps`.
    arrays : dict of str to ndarray
        For CSV or :func:`numpy.savez`.
    """
    if dataclasses.is_dataclass(obj) and not isinstance(obj, type):
        items = {f.name: getattr(obj, f.name) for f in dataclasses.fields(obj)}
    else:
        items = dict(obj)
    scalars: dict = {}
    arrays: dict[str, np.ndarray] = {}
    for key, value in items.items():
        if _is_scalar(value):
            scalars[key] = value
        elif isinstance(value, (list, tuple)) and all(isinstance(v, str) for v in value):
            scalars[key] = list(value)  # messages (e.g. a result's warnings) are not arrays
        elif isinstance(value, Mapping) or (
            dataclasses.is_dataclass(value) and not isinstance(value, type)
        ):
            sub_s, sub_a = split_arrays(value)
            scalars[key] = sub_s
            arrays.update({f"{key}.{k}": v for k, v in sub_a.items()})
        else:
            try:
                arr = np.asarray(value)
            except (TypeError, ValueError):
                continue
            if arr.dtype != object:
                arrays[key] = arr
    return scalars, arrays

"""Recordings: read and validate the CSV files of ``knotmech diagnose``.

The file format is fixed by ``shared/spec/recordings.md`` section 1: ``#`` lines
with ``key: value`` metadata, then a CSV header and data rows. The first column is
the control variable, the second the measured quantity; optional columns are
``sigma`` (standard deviation of that row) and ``trial`` (integer trial id).

Extension (allowed by the contract, which may be extended by adding keys/columns):
the sliding speed needed by ``rate_dependent_friction`` is given either as an
optional column ``speed_m_per_s`` (one speed per row) or as metadata
``speed_m_per_s_trial_<k>: <value>`` (one speed per trial id ``k``), or, for a
single-trial file, ``speed_m_per_s: <value>``.

Every validation failure raises :class:`knotmech.errors.RecordingError` with a
one-line message ``<file>, line <n>: <problem>``.
"""

from __future__ import annotations

import csv
import io
import math
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from knotmech.diagnose.experiments import EXPERIMENT_KINDS
from knotmech.errors import RecordingError

__all__ = ["EXPERIMENTS", "Recording", "read_recording", "recording_from_arrays", "MIN_ROWS"]

#: fewest data rows of a recording by default (an experiment kind may set its own,
#: ``Experiment.min_rows``: capstan_hold 5)
MIN_ROWS = 8

#: experiment kind -> (control column, measured column, required metadata keys), read
#: from the registry of experiment kinds (:mod:`knotmech.diagnose.experiments`)
EXPERIMENTS: dict[str, tuple[str, str, tuple[str, ...]]] = {
    k: (e.columns[0], e.columns[1], tuple(e.required_metadata)) for k, e in EXPERIMENT_KINDS.items()
}

#: optional columns accepted after the two required ones
OPTIONAL_COLUMNS = ("sigma", "trial", "speed_m_per_s")

#: metadata keys that must be > 0 when present (sizes, moduli, loads)
_POSITIVE_KEYS = (
    "rod_diameter_m",
    "post_diameter_m",
    "pinch_diameter_m",
    "youngs_modulus_Pa",
    "T_low_N",
    "T_high_N",
    "wrap_angle_rad",
    "mu_nominal_sigma",
    "load_N",
)


@dataclass
class Recording:
    """One validated recording.

    Attributes
    ----------
    experiment : str
        ``capstan_pull``, ``pinch`` or ``tension_profile``.
    x, y : (n,) arrays
        Control variable and measured quantity, in the units of their column names.
    metadata : dict
        Every metadata key; numeric values as float, others as str.
    sigma : (n,) array or None
        Per-row standard deviation of ``y`` when the file gives one.
    trial : (n,) int array
        Trial id per row (all zero when the file has no ``trial`` column).
    speed : (n,) array or None
        Sliding speed per row [m/s], from the ``speed_m_per_s`` column or metadata.
    source : str
        File name (or ``"<arrays>"``) used in messages.
    columns : tuple of str
        The two required column names.
    extra : dict
        Columns of the experiment kind beyond the standard ones (``load_N``,
        ``direction`` of ``capstan_hold``; word columns as numbers), name -> (n,) array.
    """

    experiment: str
    x: np.ndarray
    y: np.ndarray
    metadata: dict
    sigma: np.ndarray | None = None
    trial: np.ndarray = field(default_factory=lambda: np.zeros(0, dtype=int))
    speed: np.ndarray | None = None
    source: str = "<arrays>"
    columns: tuple[str, str] = ("x", "y")
    extra: dict = field(default_factory=dict)

    @property
    def n(self) -> int:
        return int(self.x.size)

    @property
    def mu_nominal(self) -> float | None:
        v = self.metadata.get("mu_nominal")
        return float(v) if isinstance(v, float) else None

    @property
    def mu_nominal_sigma(self) -> float | None:
        """Uncertainty of ``mu_nominal``; 5 % of it when the file gives none."""
        if self.mu_nominal is None:
            return None
        v = self.metadata.get("mu_nominal_sigma")
        return float(v) if isinstance(v, float) else 0.05 * self.mu_nominal

    def meta(self, key: str) -> float:
        return float(self.metadata[key])


def _err(source: str, line: int | None, msg: str) -> RecordingError:
    where = f"{source}, line {line}" if line is not None else source
    return RecordingError(f"{where}: {msg}")


def _parse_value(text: str):
    try:
        v = float(text)
    except ValueError:
        return text
    return v


def read_recording(path) -> Recording:
    """Read and validate a recording file.

    Parameters
    ----------
    path : str or Path
        The ``*.csv`` recording (UTF-8).

    Returns
    -------
    Recording

    Raises
    ------
    RecordingError
        One line naming the file, the line and the problem.
    """
    path = Path(path)
    source = path.name
    try:
        text = path.read_text(encoding="utf-8")
    except FileNotFoundError:
        raise _err(str(path), None, "file not found") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise _err(str(path), None, f"cannot read the file ({exc.__class__.__name__})") from None
    return parse_recording(text, source=source)


def parse_recording(text: str, *, source: str = "<string>") -> Recording:
    """Parse the text of a recording (see :func:`read_recording`)."""
    lines = text.splitlines()
    metadata: dict = {}
    meta_lines: dict = {}
    i = 0
    while i < len(lines) and (lines[i].startswith("#") or not lines[i].strip()):
        raw = lines[i]
        if raw.startswith("#"):
            body = raw[1:].strip()
            if body:
                if ":" not in body:
                    raise _err(
                        source, i + 1, f"metadata line must read '# key: value', got {raw!r}"
                    )
                key, value = body.split(":", 1)
                key, value = key.strip(), value.strip()
                metadata[key] = _parse_value(value)
                meta_lines[key] = i + 1
        i += 1
    version = metadata.get("knotmech-recording")
    if version is not None and version != 1.0:
        raise _err(
            source, meta_lines["knotmech-recording"], f"unsupported format version {version!r}"
        )
    if "experiment" not in metadata:
        raise _err(source, 1, "missing '# experiment: ...' metadata line")
    experiment = str(metadata["experiment"])
    if experiment not in EXPERIMENTS:
        raise _err(
            source,
            meta_lines["experiment"],
            f"unknown experiment {experiment!r} (allowed: {', '.join(EXPERIMENTS)})",
        )
    xcol, ycol, required = EXPERIMENTS[experiment]
    for key in required:
        if key not in metadata:
            raise _err(
                source, i + 1, f"missing metadata '# {key}: ...' for a {experiment} recording"
            )
    for key, value in metadata.items():
        if key in _POSITIVE_KEYS or key == "mu_nominal" or key.startswith("speed_m_per_s"):
            if not isinstance(value, float) or not math.isfinite(value):
                raise _err(
                    source, meta_lines[key], f"metadata {key} must be a number, got {value!r}"
                )
            if key == "mu_nominal" and value < 0:
                raise _err(source, meta_lines[key], f"mu_nominal must be >= 0, got {value:g}")
            if key != "mu_nominal" and value <= 0:
                raise _err(source, meta_lines[key], f"metadata {key} must be > 0, got {value:g}")
    if i >= len(lines):
        raise _err(source, i, "no CSV header after the metadata")
    header_line = i + 1
    reader = csv.reader(io.StringIO("\n".join(lines[i:])))
    try:
        header = [h.strip() for h in next(reader)]
    except StopIteration:
        raise _err(source, header_line, "no CSV header after the metadata") from None
    if header[:2] != [xcol, ycol]:
        raise _err(
            source,
            header_line,
            f"a {experiment} recording needs columns '{xcol},{ycol}' first, "
            f"got {','.join(header)!r}",
        )
    kind = EXPERIMENT_KINDS[experiment]
    allowed = OPTIONAL_COLUMNS + tuple(kind.optional_columns)
    extra = header[2:]
    for name in extra:
        if name not in allowed:
            raise _err(
                source,
                header_line,
                f"unknown column {name!r} (optional columns: {', '.join(allowed)})",
            )
    if len(set(header)) != len(header):
        raise _err(source, header_line, "repeated column name in the header")
    rows = []
    row_lines = []
    for k, row in enumerate(reader):
        lineno = header_line + 1 + k
        if not row or all(not c.strip() for c in row):
            continue
        if len(row) != len(header):
            raise _err(source, lineno, f"expected {len(header)} cells, got {len(row)}")
        vals = []
        for name, cell in zip(header, row, strict=True):
            words = kind.word_columns.get(name)
            if words is not None:  # a column of words (direction: raise / lower)
                if cell.strip().lower() not in words:
                    raise _err(
                        source,
                        lineno,
                        f"column {name} must read {' or '.join(words)}, got {cell.strip()!r}",
                    )
                vals.append(words[cell.strip().lower()])
                continue
            try:
                v = float(cell)
            except ValueError:
                raise _err(
                    source, lineno, f"non-numeric cell {cell.strip()!r} in column {name}"
                ) from None
            if not math.isfinite(v):
                raise _err(source, lineno, f"NaN or infinite value in column {name}")
            vals.append(v)
        rows.append(vals)
        row_lines.append(lineno)
    if len(rows) < kind.min_rows:
        raise _err(
            source,
            header_line,
            f"{len(rows)} data rows; a recording needs at least {kind.min_rows}",
        )
    table = np.array(rows, dtype=float)
    cols = {name: table[:, j] for j, name in enumerate(header)}
    lines_arr = np.array(row_lines)
    sigma = cols.get("sigma")
    if sigma is not None and np.any(sigma <= 0):
        j = int(np.argmax(sigma <= 0))
        raise _err(source, int(lines_arr[j]), f"sigma must be > 0, got {sigma[j]:g}")
    trial = cols.get("trial")
    if trial is not None:
        if np.any(trial != np.round(trial)):
            j = int(np.argmax(trial != np.round(trial)))
            raise _err(source, int(lines_arr[j]), f"trial must be an integer, got {trial[j]:g}")
        trial = trial.astype(int)
    else:
        trial = np.zeros(len(rows), dtype=int)
    speed = cols.get("speed_m_per_s")
    if speed is not None and np.any(speed <= 0):
        j = int(np.argmax(speed <= 0))
        raise _err(source, int(lines_arr[j]), f"speed_m_per_s must be > 0, got {speed[j]:g}")
    if speed is None:
        speed = _speed_from_metadata(metadata, trial, source, meta_lines)
    x = cols[xcol]
    if kind.control_nonnegative and np.any(x < 0):
        j = int(np.argmax(x < 0))
        raise _err(source, int(lines_arr[j]), f"{xcol} must be >= 0, got {x[j]:g}")
    rec = Recording(
        experiment=experiment,
        x=x,
        y=cols[ycol],
        metadata=metadata,
        sigma=sigma,
        trial=trial,
        speed=speed,
        source=source,
        columns=(xcol, ycol),
        extra={k: cols[k] for k in kind.optional_columns if k in cols},
    )
    problem = kind.check(rec)
    if problem:
        raise _err(source, None, problem)
    return rec


def _speed_from_metadata(metadata, trial, source, meta_lines):
    per_trial = {k: v for k, v in metadata.items() if k.startswith("speed_m_per_s_trial_")}
    if per_trial:
        speeds = {}
        for key, v in per_trial.items():
            tail = key[len("speed_m_per_s_trial_") :]
            try:
                speeds[int(tail)] = float(v)
            except ValueError:
                raise _err(
                    source, meta_lines[key], f"bad trial id in metadata key {key!r}"
                ) from None
        missing = sorted(set(np.unique(trial).tolist()) - set(speeds))
        if missing:
            raise _err(
                source, None, f"no speed_m_per_s_trial_{missing[0]} metadata for trial {missing[0]}"
            )
        return np.array([speeds[int(t)] for t in trial], dtype=float)
    if "speed_m_per_s" in metadata:
        return np.full(trial.size, float(metadata["speed_m_per_s"]))
    return None


def recording_from_arrays(
    experiment: str,
    x,
    y,
    *,
    metadata: dict,
    sigma=None,
    trial=None,
    speed=None,
    columns=None,
) -> Recording:
    """Build a validated :class:`Recording` from arrays (notebook use).

    Parameters
    ----------
    experiment : str
        One of :data:`EXPERIMENTS`.
    x, y : array_like
        Control variable and measured quantity (SI units of the experiment's columns).
    metadata : dict
        The metadata keys the experiment requires (e.g. ``rod_diameter_m``), plus
        optional ``mu_nominal`` / ``mu_nominal_sigma``.
    sigma, trial, speed : array_like, optional
        Per-row standard deviation, trial id, sliding speed [m/s].
    columns : dict, optional
        Columns of the experiment kind (``load_N``, ``direction`` of ``capstan_hold``;
        words as strings), name -> array.
    """
    lines = ["# knotmech-recording: 1", f"# experiment: {experiment}"]
    for k, v in metadata.items():
        if k in ("experiment", "knotmech-recording"):
            continue
        if isinstance(v, (int, float, np.number)) and not isinstance(v, bool):
            lines.append(f"# {k}: {float(v)!r}")
        else:
            lines.append(f"# {k}: {v}")
    if experiment not in EXPERIMENTS:
        raise RecordingError(
            f"<arrays>: unknown experiment {experiment!r} (allowed: {', '.join(EXPERIMENTS)})"
        )
    xcol, ycol, _ = EXPERIMENTS[experiment]
    cols = {xcol: x, ycol: y}
    if sigma is not None:
        cols["sigma"] = sigma
    if trial is not None:
        cols["trial"] = trial
    if speed is not None:
        cols["speed_m_per_s"] = speed
    cols.update(columns or {})
    arrays = {}
    for k, v in cols.items():
        arr = np.atleast_1d(np.asarray(v)).ravel()
        arrays[k] = arr if arr.dtype.kind in "USO" else arr.astype(float)
    n = arrays[xcol].size
    for k, arr in arrays.items():
        if arr.size != n:
            raise RecordingError(f"<arrays>: column {k} has {arr.size} values, {xcol} has {n}")
    lines.append(",".join(arrays))
    for i in range(n):
        cells = (
            arr[i] if arr.dtype.kind in "USO" else repr(float(arr[i])) for arr in arrays.values()
        )
        lines.append(",".join(str(c) for c in cells))
    return parse_recording("\n".join(lines) + "\n", source="<arrays>")

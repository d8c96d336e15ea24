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

Reading (beyond the contract, which says UTF-8): a UTF-8 byte-order mark (Excel's
"CSV UTF-8") is accepted; a file that is not UTF-8 is refused naming the line and
byte; numbers are ASCII only (``[+-]digits[.digits][e[+-]digits]``: no fullwidth or
Arabic-Indic digits, no ``1_0``, no Unicode minus), a metadata key may be given once.

Physical bounds checked at read time (the engine's numbers stay finite inside them):
:data:`METADATA_BOUNDS` for metadata keys, :data:`COLUMN_MAX` for the columns (by the
unit their name ends in), and no nonzero value below ``1e-30`` in magnitude.
Degenerate data are refused too: a control variable with fewer than three distinct
values (or a range below ``1e-9`` of its size), a measured column that is constant
(all zero included), a force or tension negative in more than 3/4 of the rows
and on average (mean below -3 standard errors), fewer than
:data:`MIN_ROWS` distinct rows.
"""

from __future__ import annotations

import csv
import io
import math
import re
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

#: physical bounds (SI, inclusive) of metadata keys, checked whenever the key is present;
#: wide enough for any bench (a 0.1 um fibre to a 10 m cable, a gel to diamond, a pN to
#: a GN), narrow enough that exp(mu theta), E d D and the prior stay finite
METADATA_BOUNDS: dict[str, tuple[float, float]] = {
    "rod_diameter_m": (1e-7, 10.0),
    "post_diameter_m": (1e-7, 100.0),
    "pinch_diameter_m": (1e-7, 100.0),
    "rod_radius_m": (5e-8, 5.0),
    "rod_length_m": (1e-6, 1e4),
    "youngs_modulus_Pa": (1e2, 1e13),
    "T_low_N": (1e-12, 1e9),
    "T_high_N": (1e-12, 1e9),
    "load_N": (1e-12, 1e9),
    # 0.06 degree to 16 turns: T_low exp(mu theta) stays finite for every mu the fits allow
    "wrap_angle_rad": (1e-3, 100.0),
    # the fits bound mu to [0, 5]
    "mu_nominal": (0.0, 5.0),
    # a friction coefficient is never known to better than 1e-4
    "mu_nominal_sigma": (1e-4, 5.0),
    "speed_m_per_s": (1e-12, 1e3),
    "pull_speed_m_per_s": (1e-12, 1e3),
    "density_kg_m3": (1e-3, 1e5),
    "poisson_ratio": (-1.0, 0.5),
}

#: largest magnitude of a column's values, by the unit its name ends in (``sigma``
#: takes the bound of the measured column); 10 km, 1 GN, 16 turns, 1 km/s
COLUMN_MAX: dict[str, float] = {"_m_per_s": 1e3, "_m": 1e4, "_N": 1e9, "_rad": 100.0}

#: nonzero values smaller than this in magnitude are not measurements (write 0)
TINY = 1e-30

#: a plain ASCII number: sign, digits, optional fraction, optional exponent
_NUMBER = re.compile(r"[+-]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?")
_NONFINITE = re.compile(r"[+-]?(?:nan|inf|infinity)", re.IGNORECASE)

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


def _number(text: str) -> float | None:
    """``text`` as a float when it is a plain ASCII number (or nan/inf), else None.

    Python's ``float`` also reads fullwidth and Arabic-Indic digits and ``1_0``; a
    recording must not.
    """
    t = text.strip()
    if _NUMBER.fullmatch(t) or _NONFINITE.fullmatch(t):
        return float(t)
    return None


def _not_ascii(text: str) -> str:
    """`` (character U+XXXX is not ASCII ...)`` for the first non-ASCII character, or ''."""
    for c in text:
        if ord(c) > 127:
            return (
                f" (character U+{ord(c):04X} is not ASCII: write numbers with ASCII digits, "
                "'.', 'e' and '-')"
            )
    return ""


def _parse_value(text: str):
    v = _number(text)
    return text if v is None else v


def _decode(data: bytes, source: str) -> str:
    """UTF-8 text of a file (a leading byte-order mark dropped); bad bytes named by line."""
    try:
        return data.decode("utf-8-sig")
    except UnicodeDecodeError as exc:
        bom = 3 if data.startswith(b"\xef\xbb\xbf") else 0
        start = exc.start
        line = data.count(b"\n", 0, start) + 1
        col = start - (data.rfind(b"\n", 0, start) + 1) + 1 - (bom if line == 1 else 0)
        raise _err(
            source,
            line,
            f"byte {col} (0x{data[start]:02x}) is not UTF-8; save the file as UTF-8 "
            "(Excel: 'CSV UTF-8')",
        ) from None


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
        data = path.read_bytes()
    except FileNotFoundError:
        raise _err(str(path), None, "file not found") from None
    except OSError as exc:
        why = exc.strerror or exc.__class__.__name__
        raise _err(str(path), None, f"cannot read the file ({why})") from None
    return parse_recording(_decode(data, source), source=source)


def parse_recording(text: str, *, source: str = "<string>") -> Recording:
    """Parse the text of a recording (see :func:`read_recording`)."""
    # split on line ends only (str.splitlines also splits on form feeds, U+2028...,
    # and the line numbers of the messages would drift)
    lines = text.removeprefix("\ufeff").replace("\r\n", "\n").replace("\r", "\n").split("\n")
    if "\x00" in text:
        j = text.index("\x00")
        raise _err(source, text.count("\n", 0, j) + 1, "NUL byte: this is not a text file")
    metadata, meta_lines, i = _read_metadata(lines, source)
    experiment = _check_metadata(metadata, meta_lines, i, source)
    xcol, ycol, _ = EXPERIMENTS[experiment]
    kind = EXPERIMENT_KINDS[experiment]
    header, reader = _read_header(lines, i, experiment, kind, source)
    header_line = i + 1
    fast = _numeric_rows(lines, i + 1, header, kind, header_line)
    if fast is not None:
        table, lines_arr = fast
    else:
        table, lines_arr = _checked_rows(reader, header, kind, source, header_line)
    if table.shape[0] < kind.min_rows:
        raise _err(
            source,
            header_line,
            f"{table.shape[0]} data rows; a recording needs at least {kind.min_rows}",
        )
    cols = {name: table[:, j] for j, name in enumerate(header)}
    sigma = cols.get("sigma")
    _first_bad(source, lines_arr, sigma, sigma is not None and sigma <= 0, "sigma must be > 0")
    trial = _trial_column(cols.get("trial"), table.shape[0], source, lines_arr)
    speed = cols.get("speed_m_per_s")
    bad_speed = speed is not None and speed <= 0
    _first_bad(source, lines_arr, speed, bad_speed, "speed_m_per_s must be > 0")
    if speed is None:
        speed = _speed_from_metadata(metadata, trial, source, meta_lines)
    x = cols[xcol]
    _first_bad(source, lines_arr, x, kind.control_nonnegative and x < 0, f"{xcol} must be >= 0")
    _check_columns(cols, header, xcol, ycol, trial, source, lines_arr, header_line, kind.min_rows)
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


def _first_bad(source, lines_arr, values, bad, what: str) -> None:
    """Refuse the first row where ``bad`` (a bool array, or False) holds: ``what, got v``."""
    if np.any(bad):
        j = int(np.argmax(bad))
        raise _err(source, int(lines_arr[j]), f"{what}, got {values[j]:g}")


def _trial_column(trial, n: int, source, lines_arr) -> np.ndarray:
    """The ``trial`` column as integers (all zero when the file has none)."""
    if trial is None:
        return np.zeros(n, dtype=int)
    if np.any(np.abs(trial) > 1e9):
        j = int(np.argmax(np.abs(trial) > 1e9))
        raise _err(source, int(lines_arr[j]), f"trial id {trial[j]:g} is beyond |id| <= 1e9")
    _first_bad(source, lines_arr, trial, trial != np.round(trial), "trial must be an integer")
    return trial.astype(int)


def _read_metadata(lines: list, source: str) -> tuple[dict, dict, int]:
    """The ``# key: value`` lines at the top: metadata, the line of each key (1-based),
    and the index of the first other line."""
    metadata: dict = {}
    meta_lines: dict = {}
    i = 0
    while i < len(lines) and (lines[i].startswith("#") or not lines[i].strip()):
        raw = lines[i]
        body = raw[1:].strip() if raw.startswith("#") else ""
        if body:
            if ":" not in body:
                raise _err(source, i + 1, f"metadata line must read '# key: value', got {raw!r}")
            key, value = body.split(":", 1)
            key, value = key.strip(), value.strip()
            if not key:
                raise _err(source, i + 1, f"empty metadata key in {raw!r}")
            if key in metadata:
                raise _err(
                    source,
                    i + 1,
                    f"metadata key {key!r} given twice (lines {meta_lines[key]} and {i + 1})",
                )
            metadata[key] = _parse_value(value)
            meta_lines[key] = i + 1
        i += 1
    return metadata, meta_lines, i


def _check_metadata(metadata: dict, meta_lines: dict, i: int, source: str) -> str:
    """Check the metadata (version, experiment, required keys, numbers); the experiment."""
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
    for key in EXPERIMENTS[experiment][2]:
        if key not in metadata:
            raise _err(
                source, i + 1, f"missing metadata '# {key}: ...' for a {experiment} recording"
            )
    for key, value in metadata.items():
        _check_metadata_number(key, value, source, meta_lines[key])
    if metadata.get("mu_nominal") == 0.0 and "mu_nominal_sigma" not in metadata:
        raise _err(
            source,
            meta_lines["mu_nominal"],
            "mu_nominal: 0 needs a mu_nominal_sigma (the default, 5 % of mu_nominal, is 0)",
        )
    return experiment


def _check_metadata_number(key: str, value, source: str, line: int) -> None:
    """A numeric metadata key must hold a finite number in its range."""
    numeric = (
        key in _POSITIVE_KEYS
        or key in METADATA_BOUNDS
        or key == "mu_nominal"
        or key.startswith("speed_m_per_s")
    )
    if not numeric:
        return
    if not isinstance(value, float) or not math.isfinite(value):
        raise _err(
            source, line, f"metadata {key} must be a number, got {value!r}{_not_ascii(str(value))}"
        )
    if key == "mu_nominal" and value < 0:
        raise _err(source, line, f"mu_nominal must be >= 0, got {value:g}")
    if key in _POSITIVE_KEYS and value <= 0:
        raise _err(source, line, f"metadata {key} must be > 0, got {value:g}")
    _check_bounds(key, value, source, line)


def _read_header(lines: list, i: int, experiment: str, kind, source: str):
    """The CSV header at line ``i`` (0-based), checked; the header and the CSV reader
    positioned after it."""
    xcol, ycol, _ = EXPERIMENTS[experiment]
    if i >= len(lines):
        raise _err(source, i, "no CSV header after the metadata")
    header_line = i + 1
    reader = csv.reader(io.StringIO("\n".join(lines[i:])))
    try:
        header = [h.strip() for h in next(reader)]
    except StopIteration:
        raise _err(source, header_line, "no CSV header after the metadata") from None
    except csv.Error as exc:
        raise _err(source, header_line, _csv_problem(exc)) from None
    if header[:2] != [xcol, ycol]:
        raise _err(
            source,
            header_line,
            f"a {experiment} recording needs columns '{xcol},{ycol}' first, "
            f"got {','.join(header)!r}",
        )
    allowed = OPTIONAL_COLUMNS + tuple(kind.optional_columns)
    for name in header[2:]:
        if name not in allowed:
            raise _err(
                source,
                header_line,
                f"unknown column {name!r} (optional columns: {', '.join(allowed)})",
            )
    if len(set(header)) != len(header):
        raise _err(source, header_line, "repeated column name in the header")
    return header, reader


def _checked_rows(reader, header, kind, source, header_line):
    """The data rows cell by cell (every check, with the line of the first bad cell).

    Returns the (rows, columns) table and the 1-based line number of every row.
    """
    rows = []
    row_lines = []
    while True:
        try:
            row = next(reader)
        except StopIteration:
            break
        except csv.Error as exc:
            raise _err(source, header_line + reader.line_num - 1, _csv_problem(exc)) from None
        lineno = header_line + reader.line_num - 1
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
            v = _number(cell)
            if v is None:
                shown = cell.strip() if len(cell) <= 40 else cell.strip()[:37] + "..."
                raise _err(
                    source,
                    lineno,
                    f"non-numeric cell {shown!r} in column {name}{_not_ascii(cell)}",
                )
            if not math.isfinite(v):
                raise _err(source, lineno, f"NaN or infinite value in column {name}")
            vals.append(v)
        rows.append(vals)
        row_lines.append(lineno)
    return np.array(rows, dtype=float).reshape(len(rows), len(header)), np.array(row_lines, int)


def _numeric_rows(lines, first, header, kind, header_line):
    """The data rows at once when they are plainly numeric, else None.

    A fast path for long recordings (1e6 rows in about a second instead of a minute):
    taken only when the rows hold no word column, no quote, no underscore, no
    non-ASCII character and no very long line, every non-blank line has as many
    cells as the header, and every cell is a finite ASCII number (numpy's conversion,
    which accepts exactly ``_NUMBER`` and ``_NONFINITE`` once those characters are
    excluded). Anything else returns None, and :func:`_checked_rows` reads the rows
    cell by cell, naming the line of the first problem.
    """
    if any(name in kind.word_columns for name in header):
        return None
    block = lines[first:]
    if not block:
        return None
    joined = "\n".join(block)
    if not joined.isascii() or any(c in joined for c in '"_'):
        return None
    if max(map(len, block)) > 1000:
        return None
    keep = np.fromiter((bool(ln.strip()) for ln in block), bool, len(block))
    rows = [ln for ln, k in zip(block, keep, strict=True) if k]
    ncol = len(header)
    counts = np.fromiter((ln.count(",") for ln in rows), int, len(rows))
    if np.any(counts != ncol - 1):
        return None
    try:
        table = np.array(",".join(rows).split(","), dtype=float)
    except ValueError:
        return None
    if not np.all(np.isfinite(table)):
        return None
    lines_arr = header_line + 1 + np.flatnonzero(keep)
    return table.reshape(len(rows), ncol), lines_arr


def _csv_problem(exc: csv.Error) -> str:
    text = str(exc)
    m = re.search(r"field larger than field limit \((\d+)\)", text)
    if m:
        return f"a cell longer than {m.group(1)} characters (the CSV field limit)"
    return f"not readable as CSV ({text})"


def _check_bounds(key, value, source, line):
    """Refuse a metadata value outside :data:`METADATA_BOUNDS` (one line, with the bounds)."""
    bounds = METADATA_BOUNDS.get(key)
    if bounds is None and key.startswith("speed_m_per_s"):
        bounds = METADATA_BOUNDS["speed_m_per_s"]
    if bounds is None:
        return
    lo, hi = bounds
    if not lo <= value <= hi:
        raise _err(
            source,
            line,
            f"metadata {key} = {value:g} is outside its physical range [{lo:g}, {hi:g}]",
        )


def _unit_max(name: str) -> float | None:
    for suffix, vmax in COLUMN_MAX.items():
        if name.endswith(suffix):
            return vmax
    return None


def _check_columns(
    cols, header, xcol, ycol, trial, source, lines_arr, header_line, min_rows=MIN_ROWS
):
    """Magnitude bounds of every column, then degenerate data (see the module docstring)."""
    for name in header:
        v = cols[name]
        vmax = _unit_max(ycol if name == "sigma" else name)
        if name == "trial":
            vmax = 1e9
        if vmax is not None and np.any(np.abs(v) > vmax):
            j = int(np.argmax(np.abs(v) > vmax))
            raise _err(
                source,
                int(lines_arr[j]),
                f"{name} = {v[j]:g} is beyond the physical range (|value| <= {vmax:g})",
            )
        tiny = (v != 0) & (np.abs(v) < TINY)
        if np.any(tiny):
            j = int(np.argmax(tiny))
            raise _err(
                source,
                int(lines_arr[j]),
                f"{name} = {v[j]:g} is not a measurement (nonzero below {TINY:g}); write 0",
            )
    x, y, n = cols[xcol], cols[ycol], cols[xcol].size
    distinct = np.unique(x)
    if distinct.size == 1:
        raise _err(
            source,
            header_line,
            f"all {n} rows have {xcol} = {x[0]:g}: the control variable must vary",
        )
    size = float(np.max(np.abs(x)))
    if float(np.ptp(x)) <= 1e-9 * size:
        raise _err(
            source,
            header_line,
            f"{xcol} varies by only {float(np.ptp(x)):g} over values of {size:g} "
            "(below 1e-9 of its size): the control variable must vary",
        )
    if distinct.size < 3:
        raise _err(
            source,
            header_line,
            f"only {distinct.size} distinct values of {xcol}; a diagnosis needs at least 3",
        )
    if np.all(y == 0):
        raise _err(source, header_line, f"every {ycol} value is 0: nothing was measured")
    if np.all(y == y[0]):
        raise _err(
            source,
            header_line,
            f"all {n} values of {ycol} are {y[0]:g}: a constant reading (a stuck or "
            "saturated sensor?) cannot be diagnosed",
        )
    if ycol.endswith("_N"):
        # mostly negative and clearly so on average: noise about zero (a frictionless
        # control) passes, a reversed sign convention does not
        neg = int(np.sum(y < 0))
        t_mean = float(np.mean(y)) / (float(np.std(y)) / np.sqrt(n))
        if neg > 0.75 * n and t_mean < -3.0:
            raise _err(
                source,
                header_line,
                f"{ycol} is negative in {neg} of {n} rows: a measured tension or friction "
                "force is >= 0 (is the sign convention reversed?)",
            )
    rows = np.unique(np.column_stack([x, y, trial]), axis=0).shape[0]
    if rows < min_rows:
        raise _err(
            source,
            header_line,
            f"only {rows} distinct rows among {n} (rows repeated); a recording needs at "
            f"least {min_rows}",
        )


def _speed_from_metadata(metadata, trial, source, meta_lines):
    per_trial = {k: v for k, v in metadata.items() if k.startswith("speed_m_per_s_trial_")}
    if per_trial:
        speeds = {}
        for key, v in per_trial.items():
            tail = key[len("speed_m_per_s_trial_") :]
            try:
                if not re.fullmatch(r"[0-9]+", tail):
                    raise ValueError(tail)
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
    lines += [_metadata_line(k, v) for k, v in metadata.items()]
    lines = [line for line in lines if line is not None]
    if experiment not in EXPERIMENTS:
        raise RecordingError(
            f"<arrays>: unknown experiment {experiment!r} (allowed: {', '.join(EXPERIMENTS)})"
        )
    xcol, ycol, _ = EXPERIMENTS[experiment]
    optional = {"sigma": sigma, "trial": trial, "speed_m_per_s": speed}
    cols = {xcol: x, ycol: y, **{k: v for k, v in optional.items() if v is not None}}
    cols.update(columns or {})
    arrays = _column_arrays(cols, xcol)
    lines.append(",".join(arrays))
    for i in range(arrays[xcol].size):
        cells = (
            arr[i] if arr.dtype.kind in "USO" else repr(float(arr[i])) for arr in arrays.values()
        )
        lines.append(",".join(str(c) for c in cells))
    return parse_recording("\n".join(lines) + "\n", source="<arrays>")


def _metadata_line(key: str, value) -> str | None:
    """``# key: value`` (numbers written in full), None for the keys the caller writes."""
    if key in ("experiment", "knotmech-recording"):
        return None
    if isinstance(value, (int, float, np.number)) and not isinstance(value, bool):
        return f"# {key}: {float(value)!r}"
    return f"# {key}: {value}"


def _column_arrays(cols: dict, xcol: str) -> dict:
    """Each column as a flat array (numbers as float, words kept), all of one length."""
    arrays = {}
    for k, v in cols.items():
        arr = np.atleast_1d(np.asarray(v)).ravel()
        arrays[k] = arr if arr.dtype.kind in "USO" else arr.astype(float)
    n = arrays[xcol].size
    for k, arr in arrays.items():
        if arr.size != n:
            raise RecordingError(f"<arrays>: column {k} has {arr.size} values, {xcol} has {n}")
    return arrays

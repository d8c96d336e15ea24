r"""Converters from a rig's raw sensor streams to recordings of ``knotmech diagnose``.

:func:`plateau_windows` finds the holds in a force stream (where the force rests on
a high, steady level) and a window inside each; :func:`capstan_yarn_rig` turns the
streams of the capstan yarn rig (cotton yarn lowered over a 41.5 mm cylinder, one
stream per wrap angle, a control stream of the load alone) into a ``capstan_hold``
recording, one row per hold.

Why one row per hold: the readings within a hold are not independent measurements
of it. At 50 Hz they are quantised (steps of 0.0062-0.0066 N, about the noise),
strongly correlated, and drift as the yarn creeps (0.01-0.04 N over a hold), while
holds at one angle differ by 0.03-0.3 N; the hold, not the sample, is the replicate.
The row's value is the median of the window (robust to the few spikes of a stream).

Command line::

    python -m knotmech.diagnose.rigs SRC_DIR OUT.csv
"""

from __future__ import annotations

import csv
import re
import sys
from dataclasses import dataclass
from pathlib import Path

import numpy as np

from knotmech.errors import InputError

__all__ = ["Hold", "sensor_quantum", "plateau_windows", "capstan_yarn_rig", "YARN_RIG"]

#: what the rig's folder does not say in its streams (from its description)
YARN_RIG = {
    "post_diameter_m": 0.0415,
    "direction": "lower",
    "source": (
        "capstan yarn rig: cotton yarn on a 41.5 mm cylinder, 7 wrap angles x 3 trials, "
        "raw 50 Hz force streams; cathaypacific8747 (2021), MIT licence"
    ),
}


@dataclass(frozen=True)
class Hold:
    """One hold of a stream: its steady run and the window used.

    Attributes
    ----------
    start_s, end_s : float
        The steady run [s].
    window : (float, float)
        The window inside it [s].
    force_N : float
        Median force in the window [N].
    sd_N : float
        Standard deviation of the samples in the window [N].
    drift_N : float
        Change of the force over the window (least-squares slope times its length) [N].
    samples : int
    """

    start_s: float
    end_s: float
    window: tuple
    force_N: float
    sd_N: float
    drift_N: float
    samples: int


def sensor_quantum(force) -> float:
    """The reading step of a quantised stream [N]: the median gap between neighbouring
    distinct readings."""
    u = np.unique(np.asarray(force, float))
    if u.size < 3:
        raise InputError("a force stream needs at least three distinct readings")
    return float(np.median(np.diff(u)))


def _rolling(values, half, fn):
    out = np.empty(values.size)
    for i in range(values.size):
        out[i] = fn(values[max(0, i - half) : i + half + 1])
    return out


def _runs(mask, gap):
    """(first, last) index of the runs of ``mask``, gaps of up to ``gap`` samples bridged."""
    idx = np.flatnonzero(mask)
    if idx.size == 0:
        return []
    runs, a, b = [], idx[0], idx[0]
    for i in idx[1:]:
        if i - b <= gap:
            b = i
        else:
            runs.append((a, b))
            a = b = i
    runs.append((a, b))
    return runs


def plateau_windows(
    time_s,
    force_N,
    *,
    window_s: float = 10.0,
    min_hold_s: float = 8.0,
    steady_quanta: float = 2.5,
    level_fraction: float = 0.25,
) -> list:
    """Holds of a force stream (one per loading) and a window of ``window_s`` inside each.

    The stream is *loaded* where its 1 s running median is above ``level_fraction``
    of its 99th percentile; each loaded stretch (between two releases) is one
    loading. A sample is *steady* when the standard deviation of the raw readings in
    the 1 s around it is below ``steady_quanta`` sensor steps (:func:`sensor_quantum`).
    The hold of a loading is its longest steady run (gaps under 0.5 s bridged), if it
    lasts ``min_hold_s`` or more: an operator who re-tensions mid-loading leaves a
    shorter run before the final one. The window is the central ``window_s`` of the
    run (the whole run when shorter), away from the settling and the release.

    Parameters
    ----------
    time_s, force_N : (n,) array_like
        Sample times [s] (uniform) and readings [N].
    window_s, min_hold_s : float
        Window length and shortest hold [s].
    steady_quanta : float
        Largest 1 s standard deviation of a steady stretch [sensor steps].
    level_fraction : float
        Loaded above this fraction of the 99th percentile of the stream.

    Returns
    -------
    list of Hold
        One per loading with a hold, in time order.
    """
    t = np.asarray(time_s, float)
    f = np.asarray(force_N, float)
    if t.size != f.size or t.size < 10:
        raise InputError("time and force streams must have the same length (>= 10 samples)")
    dt = float(np.median(np.diff(t)))
    if not dt > 0:
        raise InputError("sample times must increase")
    half = max(int(round(0.5 / dt)), 1)
    q = sensor_quantum(f)
    sd = _rolling(f, half, np.std)
    level = _rolling(f, half, np.median)
    loaded = level > level_fraction * np.quantile(f, 0.99)
    steady = (sd < steady_quanta * q) & loaded
    holds = []
    for la, lb in _runs(loaded, half):
        runs = [(a, b) for a, b in _runs(steady[la : lb + 1], half)]
        if not runs:
            continue
        a, b = max(runs, key=lambda r: r[1] - r[0])
        a, b = a + la, b + la
        if t[b] - t[a] < min_hold_s:
            continue
        mid = 0.5 * (t[a] + t[b])
        lo, hi = max(t[a], mid - 0.5 * window_s), min(t[b], mid + 0.5 * window_s)
        sel = (t >= lo) & (t <= hi)
        w = f[sel]
        slope = np.polyfit(t[sel] - mid, w, 1)[0] if w.size > 2 else 0.0
        holds.append(
            Hold(
                float(t[a]),
                float(t[b]),
                (round(float(lo), 6), round(float(hi), 6)),
                float(np.median(w)),
                float(np.std(w)),
                float(slope * (hi - lo)),
                int(w.size),
            )
        )
    return holds


def _read_stream(path: Path):
    try:
        data = np.loadtxt(path, delimiter=",", skiprows=1, ndmin=2)
    except (OSError, ValueError) as exc:
        raise InputError(
            f"{path.name}: cannot read the stream ({exc.__class__.__name__})"
        ) from None
    if data.shape[1] < 2:
        raise InputError(f"{path.name}: expected columns time_s,force_N")
    return data[:, 0], data[:, 1]


def _measured_angles(path: Path) -> dict:
    out = {}
    with path.open(newline="", encoding="utf-8") as fh:
        for row in csv.DictReader(fh):
            out[int(float(row["nominal_wrap_deg"]))] = float(row["measured_wrap_rad"])
    return out


def capstan_yarn_rig(folder, *, window_s: float = 10.0) -> tuple[str, list]:
    """The capstan yarn rig's raw streams as a ``capstan_hold`` recording.

    Reads ``raw_logger_<deg>.csv`` (one stream per nominal wrap angle),
    ``raw_logger_control.csv`` (the load hanging straight from the sensor: its hold
    is the load W) and, for the wrap angles, the column ``measured_wrap_rad`` of
    ``capstan_summary.csv`` (the rig's measured contact angles; the nominal angle
    where it is missing). Every hold found by :func:`plateau_windows` becomes a row
    (``trial`` = its index in its stream; rows stacked by trial); the direction is
    ``lower`` (the sensor holds the hanging load back, T < W).

    Returns
    -------
    text : str
        The recording (``# key: value`` metadata, header, rows).
    rows : list of dict
        Per hold: ``nominal_deg``, ``wrap_angle_rad``, ``trial`` and the
        :class:`Hold` fields.
    """
    folder = Path(folder)
    ctrl = folder / "raw_logger_control.csv"
    if not ctrl.exists():
        raise InputError(f"{folder}: no raw_logger_control.csv (the load's stream)")
    load = plateau_windows(*_read_stream(ctrl), window_s=window_s, min_hold_s=5.0)
    if len(load) != 1:
        raise InputError(f"{ctrl.name}: expected one hold of the load, found {len(load)}")
    summary = folder / "capstan_summary.csv"
    angles = _measured_angles(summary) if summary.exists() else {}
    streams = []
    for path in folder.glob("raw_logger_*.csv"):
        m = re.fullmatch(r"raw_logger_(\d+)\.csv", path.name)
        if m:
            streams.append((int(m.group(1)), path))
    if not streams:
        raise InputError(f"{folder}: no raw_logger_<deg>.csv streams")
    rows = []
    quanta = []
    for deg, path in sorted(streams):
        t, f = _read_stream(path)
        quanta.append(sensor_quantum(f))
        holds = plateau_windows(t, f, window_s=window_s)
        if not holds:
            raise InputError(f"{path.name}: no hold found")
        theta = angles.get(deg, np.deg2rad(deg))
        for k, h in enumerate(holds, start=1):
            rows.append({"nominal_deg": deg, "wrap_angle_rad": theta, "trial": k, **h.__dict__})
    lines = [
        "# knotmech-recording: 1",
        "# experiment: capstan_hold",
        f"# load_N: {load[0].force_N:.6g}",
        f"# direction: {YARN_RIG['direction']}",
        f"# post_diameter_m: {YARN_RIG['post_diameter_m']}",
        f"# source: {YARN_RIG['source']}",
        "# licence: MIT, Copyright (c) 2021 cathaypacific8747 (capstan_yarn_rig.LICENSE)",
        "# converted_by: knotmech.diagnose.rigs.capstan_yarn_rig (one row per hold: median of "
        f"the central {window_s:g} s of each steady run of a raw 50 Hz stream)",
        "# wrap_angle_from: measured_wrap_rad of the rig's capstan_summary.csv",
        f"# sensor_quantum_N: {float(np.median(quanta)):.4g}",
        f"# holds: {len(rows)}",
        "wrap_angle_rad,T_N,trial",
    ]
    # stacked by trial (spec section 1), angles in order within a trial
    for r in sorted(rows, key=lambda r: (r["trial"], r["wrap_angle_rad"])):
        lines.append(f"{r['wrap_angle_rad']:.6g},{r['force_N']:.6g},{r['trial']}")
    return "\n".join(lines) + "\n", rows


def main(argv=None) -> int:
    """``python -m knotmech.diagnose.rigs SRC_DIR OUT.csv``: convert the yarn rig."""
    argv = sys.argv[1:] if argv is None else argv
    if len(argv) != 2:
        print("usage: python -m knotmech.diagnose.rigs SRC_DIR OUT.csv", file=sys.stderr)
        return 2
    try:
        text, rows = capstan_yarn_rig(argv[0])
    except InputError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    Path(argv[1]).write_text(text, encoding="utf-8")
    print(f"{len(rows)} holds -> {argv[1]}")
    return 0


if __name__ == "__main__":
    sys.exit(main())

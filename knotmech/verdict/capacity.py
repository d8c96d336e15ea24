r"""The load a knot takes: its slip load (from the DER hold table, or a closed form) and its
breaking load (:func:`knotmech.strength.knot_breaking_load`), whichever is lower.

The slip load is the clove-hitch paper's critical load (Extreme Mech. Lett., DOI
10.1016/j.eml.2022.101788, sec. 8 and Fig. 4) in the user's units: in each column of the
hold table at the grid values of d/2R and mu around the user's (the corners the lookup
uses), the load :math:`T_\mathrm{high}/EA` where the column goes from hold to slip, above
the lightest load that held; bracketed by the last load held and the first that slipped.
The value is interpolated in d/2R and mu (linearly, on the logarithm of each column's
geometric mid-point), the band is the widest bracket of the corners, and both are
converted to newtons with :math:`EA = E\pi d^2/4`. A closed form that says the knot is
self-locking bounds the slip load from below only (friction alone cannot unlock it, up to
the end of the closed form's validity); the capacity is then the breaking load, and
without one the capacity is undecided.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from knotmech.errors import InputError
from knotmech.verdict.answer import format_force
from knotmech.verdict.criterion import CREEP_LIMIT
from knotmech.verdict.tables import MU_TOL, _axis

__all__ = [
    "Capacity",
    "LoadBand",
    "agree_with_verdict",
    "band_newtons",
    "better_slip",
    "bisect_slip",
    "capacity_of",
    "column_bracket",
    "failed_above",
    "legs_band",
    "merge_bands",
    "slip_from_answers",
    "slip_from_table",
]


@dataclass(frozen=True)
class LoadBand:
    """A load [N] with its band ``low <= value <= high`` and where it comes from.

    ``high`` is inf when nothing bounds it from above (nothing slipped up to ``low``)."""

    value: float
    low: float
    high: float
    source: str

    @property
    def bounded(self) -> bool:
        """Whether the band is finite."""
        return math.isfinite(self.high) and math.isfinite(self.value)

    def to_dict(self) -> dict:
        return {
            "value_N": self.value if math.isfinite(self.value) else None,
            "low_N": self.low,
            "high_N": self.high if math.isfinite(self.high) else None,
            "unbounded_above": not math.isfinite(self.high),
            "source": self.source,
        }


@dataclass(frozen=True)
class Capacity:
    """The load a knot takes [N]: ``value`` in ``[low, high]``, the lower of the slip and
    breaking loads (``limited_by`` ``"slip"`` or ``"break"``); NaN and ``limited_by`` None
    when nothing inside its validity bounds it (undecided).

    ``slip``: the slip load (None when no model gives one); ``breaking``: the knot's breaking
    load (None when no published data: ``breaking_note`` says so); ``efficiency`` the knot
    efficiency (nominal, low, high) or None; ``message`` the capacity in words;
    ``rope_strength`` the rope's own breaking strength when no knot efficiency is published
    (an upper bound of the knot's breaking load, not a capacity), else None.
    """

    value: float
    low: float
    high: float
    limited_by: str | None
    slip: LoadBand | None
    breaking: LoadBand | None
    efficiency: tuple | None
    breaking_note: str
    message: str
    rope_strength: LoadBand | None = None

    @property
    def decided(self) -> bool:
        return self.limited_by is not None

    def fraction(self, load: float) -> float:
        """The load as a fraction of the capacity (NaN when undecided)."""
        if not self.decided:
            return math.nan
        return load / self.value if self.value > 0 else math.inf

    def to_dict(self, load: float) -> dict:
        f = self.fraction(load)
        return {
            "value_N": self.value if self.decided else None,
            "low_N": self.low if self.decided else None,
            "high_N": self.high if self.decided else None,
            "limited_by": self.limited_by,
            "load_fraction": f if math.isfinite(f) else None,
            "slip": None if self.slip is None else self.slip.to_dict(),
            "breaking": None if self.breaking is None else self.breaking.to_dict(),
            "knot_efficiency": None if self.efficiency is None else list(self.efficiency),
            "breaking_note": self.breaking_note,
            "rope_breaking_upper_bound": (
                None if self.rope_strength is None else self.rope_strength.to_dict()
            ),
            "message": self.message,
        }


# ----------------------------------------------------------------------- the DER table
def column_bracket(loads, votes) -> tuple:
    """(last load held, first load slipped) above the lightest load held in one column.

    ``loads`` ascending [T/EA], ``votes`` True/False/None. A failed run (None) is no
    evidence of a slip: one that lies between a hold and a slip is passed over (the bracket
    runs from the last load held below the slip to the slip). Where nothing slipped above
    the last hold but a run there failed, the bracket ends at the first failed load above
    it (:func:`failed_above`): the top of what the table knows, not an observed slip (until
    session 20 every failed run counted as a slip). (0, lightest) when nothing held; (last
    load held, inf) when nothing above the first hold slipped or failed.
    """
    b = _bracket(votes)
    if b is None:
        return 0.0, float(loads[0])
    last, top, _ = b
    return float(loads[last]), (float(loads[top]) if top is not None else math.inf)


def failed_above(votes):
    """Index of the first failed run (None) above a column's last hold when nothing above
    that hold slipped, else None: where :func:`column_bracket` ends at a failed run."""
    b = _bracket(votes)
    return b[1] if b is not None and b[2] else None


def _bracket(votes):
    """(index of the last run held below the band's top, index of that top or None: open
    above, whether the top is a failed run) of one column's votes; None when nothing held
    (:func:`column_bracket`)."""
    held = [i for i, v in enumerate(votes) if v]
    if not held:
        return None
    last, failed = held[0], None
    for j in range(held[0] + 1, len(votes)):
        if votes[j] is False:
            return last, j, False
        if votes[j]:
            last, failed = j, None
        elif failed is None:
            failed = j
    return last, failed, failed is not None


def _mid(lo: float, hi: float) -> float:
    """Geometric mid-point of a bracket on a log-spaced grid (hi when lo is 0)."""
    if not math.isfinite(hi):
        return math.inf
    return math.sqrt(lo * hi) if lo > 0 else hi


def _weights(values, idx, q: float) -> list:
    """Linear interpolation weights of ``q`` over the grid values ``values[idx]``."""
    if len(idx) == 1:
        return [1.0]
    a, b = float(values[idx[0]]), float(values[idx[1]])
    w = min(max((q - a) / (b - a), 0.0), 1.0)
    return [1 - w, w]


def slip_from_table(table, *, x, mu, mu_rr=None, creep_limit=CREEP_LIMIT):
    """The slip load of a :class:`~knotmech.verdict.tables.HoldTable` at (d/2R, mu, mu_rr).

    Returns
    -------
    (value, low, high, text) in T_high/EA, or None when d/2R lies outside the table.
    ``high`` is inf where a corner column slipped nowhere above its holds; below the
    smallest mu the band starts at 0 (less friction slips earlier); above the largest, it
    is open above (more friction slips later).
    """
    mr = mu if mu_rr is None else mu_rr
    ax = table.axes
    xi, xw = _axis(ax["d_over_2R"], x, x)
    if xw in ("below", "above"):
        return None
    lo_m, hi_m = min(mu, mr), max(mu, mr)
    mi, mw = _axis(ax["mu"], lo_m, hi_m, rel=MU_TOL / max(hi_m, 1e-9))
    ys = ax["t_over_EA"]
    wx = _weights(ax["d_over_2R"], xi, x)
    wm = _weights(ax["mu"], mi, 0.5 * (lo_m + hi_m))
    logv, lows, highs, tops = 0.0, [], [], []
    for i, a in zip(xi, wx, strict=True):
        for k, b in zip(mi, wm, strict=True):
            votes = [table.point(ax["d_over_2R"][i], y, ax["mu"][k]).holds(creep_limit) for y in ys]
            lo, hi = column_bracket(ys, votes)
            if failed_above(votes) is not None:
                tops.append(f"{hi:g}")
            lows.append(lo)
            highs.append(hi)
            logv += a * b * math.log(_mid(lo, hi)) if math.isfinite(hi) else math.inf
    low, high = min(lows), max(highs)
    value = math.exp(logv) if math.isfinite(logv) else math.inf
    if mw == "below":
        low = 0.0
    if mw == "above":
        high = math.inf
    mus = ", ".join(f"{float(ax['mu'][k]):g}" for k in mi)
    xs = ", ".join(f"{float(ax['d_over_2R'][i]):.4g}" for i in xi)
    text = f"DER {table.knot} hold table, columns d/2R = {xs}, mu = mu_rr = {mus}"
    if tops:
        text += (f"; a column's band ends where its runs failed (T/EA {', '.join(tops)}: "
                 "no verdict there), not at an observed slip")  # fmt: skip
    return value, low, high, text


# ----------------------------------------------------------------------- the capacity
def _breaking(knot: str, material, d: float, D: float | None):
    """(LoadBand or None, efficiency (nominal, low, high) or None, note) of the knot's
    breaking load; a capstan is the rope's own strength (no knot)."""
    from knotmech import strength

    if material is None:
        return None, None, "breaking load: no material given (--material)", None
    name = getattr(material, "key", material)
    if knot != "capstan" and knot not in strength.knot_names():
        return _rope_bound(strength, material, d, f"for {knot}")
    try:
        if knot == "capstan":
            e = strength.breaking_load(material, d)
            rope = LoadBand(float(e.nominal), float(e.low), float(e.high),
                            "rope breaking load (no knot): " + e.source)  # fmt: skip
            return rope, None, "", None
        e = strength.knot_breaking_load(knot, material, d, D)
        eta = strength.knot_efficiency(knot, material, D)
    except strength.NoDataError:
        return _rope_bound(strength, material, d, f"for {knot} in {name}")
    except InputError as exc:  # a diameter outside the published tables
        return None, None, f"breaking load: no published data ({exc}); source needed", None
    band = LoadBand(float(e.nominal), float(e.low), float(e.high), e.source)
    return band, (float(eta.nominal), float(eta.low), float(eta.high)), "", None


def _rope_bound(strength, material, d: float, what: str):
    """(None, None, note, rope) when no knot efficiency is published: ``rope`` the rope's
    own breaking strength (a LoadBand with its source), an upper bound of the knotted
    rope's (efficiency <= 1), or None when it is not tabulated either."""
    missing = f"no published knot efficiency {what}"
    try:
        e = strength.breaking_load(material, d)
    except (strength.NoDataError, InputError):
        return None, None, f"breaking load: {missing}; source needed", None
    rope = LoadBand(float(e.nominal), float(e.low), float(e.high), e.source)
    note = f"breaks below {format_force(rope.high)} (the rope's own strength; {missing})"
    return None, None, note, rope


def capacity_of(*, knot, slip, material, d, D, load) -> Capacity:
    """The capacity from a slip load (``LoadBand`` or None) and the knot's breaking load.

    - a bounded slip load: the lower of it and the breaking load (nominal values);
    - a slip load open above (nothing slipped up to ``slip.low``): the breaking load, its
      band widened down to ``slip.low`` where that is below the break (it may slip in
      between); without a breaking load, undecided;
    - no slip load: the breaking load alone is not a capacity (undecided).
    """
    brk, eta, note, rope = _breaking(knot, material, d, D)
    common = dict(slip=slip, breaking=brk, efficiency=eta, breaking_note=note, rope_strength=rope)
    if slip is not None and slip.bounded:
        if brk is not None and brk.value < slip.value:
            return Capacity(brk.value, brk.low, brk.high, "break", message="breaks before it slips",
                            **common)  # fmt: skip
        return Capacity(slip.value, slip.low, slip.high, "slip", message="slips first", **common)
    if slip is not None and brk is not None:
        low = min(slip.low, brk.low)
        msg = ("breaks before it slips" if slip.low >= brk.value else
               f"no slip up to {slip.low:.4g} N ({slip.source}); it may slip between that and "
               "the break")  # fmt: skip
        return Capacity(brk.value, low, max(brk.high, brk.value), "break", message=msg, **common)
    why = ("no model inside its validity gives a slip load" if slip is None else
           f"nothing slipped up to {slip.low:.4g} N ({slip.source})")  # fmt: skip
    return Capacity(math.nan, math.nan, math.nan, None,
                    message=why + ("" if brk is not None else "; " + (note or "no breaking load")),
                    **common)  # fmt: skip


def slip_from_answers(answers, *, strain_limit_load: float) -> LoadBand | None:
    """The slip load from the deciding closed form (a point value; self-locking: open
    above, from ``strain_limit_load`` [N], the end of its validity, or 0 when unknown)."""
    dec = next((a for a in answers if a.decides), None)
    if dec is None or dec.model.startswith("DER"):
        return None
    cap = float(dec.capacity)
    if math.isinf(cap):
        low = strain_limit_load if math.isfinite(strain_limit_load) else 0.0
        why = f"{dec.model} model: self-locking, friction alone cannot unlock it"
        return LoadBand(math.inf, low, math.inf, why)
    if not math.isfinite(cap):
        return None
    return LoadBand(cap, cap, cap, f"{dec.model} model (a point value, no band)")


def better_slip(table: LoadBand | None, closed: LoadBand | None) -> LoadBand | None:
    """The slip load to report: the DER table's when bounded, else the closed form's when
    bounded, else the one that bounds it from below the furthest."""
    for s in (table, closed):
        if s is not None and s.bounded:
            return s
    if table is None or (closed is not None and closed.low > table.low):
        return closed
    return table


#: the most extra DER runs a bisection of the slip load may take (``hold --bisect``)
MAX_BISECT_RUNS = 8
#: the heaviest load a bisection probes, in T_high/EA: the top of the shipped DER hold
#: tables, where the clove-hitch paper's critical loads end (Fig. 4: at most about 0.3 EA)
BISECT_CEILING = 0.3


def bisect_slip(ask, *, low: float, high: float, runs: int, ceiling: float, source: str):
    """Narrow a slip band ``[low, high]`` [N] by ``runs`` decisions ``ask(load)``.

    Each probe is the band's geometric mid-point (``high / 10`` while ``low`` is 0: the
    decades of the DER tables' load axis); a band
    open above (``high`` inf) is probed first at ``ceiling`` [N] (the end of the model's
    validity): a hold there leaves the band open above ``ceiling`` and ends the search.
    ``ask`` returns True (holds: the slip load is above), False (slips: below) or None (the
    run failed: the search ends there, the band as it was).

    Parameters
    ----------
    ask : callable
        ``ask(load [N]) -> bool or None``: one DER run at that load.
    low, high : float
        The band to start from [N], ``0 <= low <= high`` (``high`` may be inf).
    runs : int
        At most this many calls of ``ask``, 1 to :data:`MAX_BISECT_RUNS`.
    ceiling : float
        Largest load probed [N] (> 0).
    source : str
        Where the band comes from (the runs are appended).

    Returns
    -------
    band : LoadBand
        The narrowed band, its value the geometric mid-point (inf when open above).
    probes : list of (float, bool or None)
        Each load asked [N] and its answer.

    Examples
    --------
    >>> band, probes = bisect_slip(lambda f: f < 3.0, low=1.0, high=16.0, runs=4,
    ...                            ceiling=100.0, source="test")
    >>> [round(f, 3) for f, _ in probes], round(band.low, 3), round(band.high, 3)
    ([4.0, 2.0, 2.828, 3.364], 2.828, 3.364)
    >>> band, probes = bisect_slip(lambda f: f < 0.02, low=0.0, high=1.0, runs=3,
    ...                            ceiling=100.0, source="test")
    >>> [round(f, 4) for f, _ in probes], band.low, round(band.high, 4)
    ([0.1, 0.01, 0.0316], 0.01, 0.0316)
    """
    if not (0 <= low <= high) or not ceiling > 0:
        raise InputError(f"bisect_slip needs 0 <= low <= high and ceiling > 0, got "
                         f"low {low:g}, high {high:g}, ceiling {ceiling:g}")  # fmt: skip
    if not 1 <= int(runs) <= MAX_BISECT_RUNS:
        raise InputError(f"bisect must be 1 to {MAX_BISECT_RUNS} runs, got {runs}")
    probes = []
    for _ in range(int(runs)):
        if math.isinf(high):
            if low >= ceiling:
                break
            f = ceiling
        else:
            f = math.sqrt(low * high) if low > 0 else high / 10
        holds = ask(f)
        probes.append((f, holds))
        if holds is None:
            break
        low, high = (f, high) if holds else (low, f)
    words = ", ".join(f"{format_force(f)} {_word(h)}" for f, h in probes)
    text = f"{source}; bisection: {words}" if probes else source
    return LoadBand(_mid(low, high), low, high, text), probes


def _word(holds) -> str:
    return {True: "held", False: "slipped", None: "failed"}[holds]


def band_newtons(row, EA: float) -> LoadBand | None:
    """A (value, low, high, text) slip band in T/EA as a :class:`LoadBand` in newtons."""
    if row is None:
        return None
    v, lo, hi, text = row
    return _clamped(v * EA, lo * EA, hi * EA, text)


def _clamped(value: float, low: float, high: float, source: str) -> LoadBand:
    """A band with its value inside it (interpolation in logarithms may step an ulp out)."""
    return LoadBand(min(max(value, low), high), low, high, source)


def merge_bands(bands: list, kappas: list, nominal: float | None = None):
    """One slip band over a rope's kappa range from each table's :class:`LoadBand` (None if
    any is None), ``kappas`` the tables' bending scales: from the lowest low to the highest
    high, at the value of the table at ``nominal`` (the preset's kappa; without it, or when
    no table is at it, the lowest value)."""
    if not bands or any(b is None for b in bands):
        return None
    if len(bands) == 1:
        return bands[0]
    at = [b.value for b, k in zip(bands, kappas, strict=True) if k == nominal]
    value = at[0] if at else min(b.value for b in bands)
    low, high = min(b.low for b in bands), max(b.high for b in bands)
    ks = ", ".join(f"{k:g}" for k in kappas)
    src = f"{bands[0].source}; over the rope's kappa range: tables at kappa {ks}"
    value = min(max(value, low), high) if math.isfinite(value) else value
    return LoadBand(value, low, high, src)


def legs_band(holds: bool, load: float):
    """The slip load of the cow hitch on both legs as far as the DER tables decide it: at or
    above ``load`` [N] when it holds, at or below it when it slips (the tables run at fixed
    T_low / T_high, so no band along the load at the user's ratio)."""
    src = "the DER tables of the cow hitch on both legs"
    if holds:
        return LoadBand(math.inf, float(load), math.inf, src)
    return LoadBand(float(load), 0.0, float(load), src)


def agree_with_verdict(slip: LoadBand | None, holds, load: float) -> LoadBand | None:
    """The slip band narrowed by a decided answer at ``load`` [N]: a hold there puts the slip
    load at or above it, a slip at or below it (a value on the wrong side of the load moves
    to the geometric mid-point of the narrowed band; an open band keeps an open value)."""
    if slip is None or holds is None:
        return slip
    if holds and load > slip.low:
        high = max(slip.high, load)
        value = slip.value if slip.value > load else _mid(load, high)
        return _clamped(value, load, high, slip.source)
    if not holds and load < slip.high:
        low = min(slip.low, load)
        value = slip.value if slip.value < load else (math.sqrt(low * load) if low > 0 else load)
        return _clamped(value, low, load, slip.source)
    return slip

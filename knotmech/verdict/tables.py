r"""DER hold/slip tables and their lookups: the smooth-law phase tables of the clove hitch
(:class:`PhaseTable`, one friction; :class:`PhaseTableSet`, several) and the anchor-law hold
tables ``knotmech hold`` reads (:class:`HoldTable`, three axes d/2R, T_high/EA, mu = mu_rr,
one per knot and bending scale; each point keeps the creep speed it measured, so the
criterion of :mod:`knotmech.verdict.criterion` is applied at any limit when read).

Reading: :func:`load_table`, :func:`load_tables` (the shipped smooth-law tables),
:func:`read_hold_table`, :func:`load_hold_tables`, :func:`load_hold_table_sets` (the shipped
hold tables, ``knotmech/data/hold_phase_table_<knot>[_kappa<k>].json``). Building:
:mod:`knotmech.verdict.build`.
"""

from __future__ import annotations

import itertools
import json
import math
from dataclasses import dataclass, field, replace
from importlib import resources
from pathlib import Path

import numpy as np

from knotmech import _json
from knotmech.errors import InputError, check_positive
from knotmech.verdict.criterion import (
    CREEP_CRITERION,
    CREEP_LIMIT,
    CREEP_WINDOW,
    MU,
    creep_verdict,
    solver_gave_verdict,
)

__all__ = [
    "PhasePoint",
    "PhaseTable",
    "PhaseAnswer",
    "PhaseTableSet",
    "load_table",
    "load_tables",
    "table_resource",
    "TABLE_RESOURCE",
    "MU_TOL",
    "HoldPoint",
    "HoldTable",
    "HoldAnswer",
    "HOLD_TABLE_FORMAT",
    "HOLD_COLUMNS",
    "hold_table_resource",
    "load_hold_tables",
    "load_hold_table_sets",
    "load_legs_table_sets",
    "read_shipped_hold_tables",
    "meta_bending_scale",
    "meta_t_low_fraction",
    "read_hold_table",
]

TABLE_RESOURCE = "clove_phase_table.json"  #: the mu = mu_rr = 0.3 table (the first one shipped)
#: every shipped table: ``clove_phase_table.json`` and ``clove_phase_table_mu<mu>.json``
TABLE_GLOB = "clove_phase_table*.json"
MU_TOL = 0.005  #: a friction coefficient within this of a table's is that table's
SNAP = 1e-3  #: relative distance in d/2R within which a query lies on a table column


@dataclass(frozen=True)
class PhasePoint:
    """One simulated point: rescaled diameter, rescaled load, held or not."""

    d_over_2R: float
    t_over_EA: float
    holds: bool


@dataclass(frozen=True)
class PhaseAnswer:
    """Answer of :meth:`PhaseTable.lookup`.

    ``holds`` is None when the query lies outside the table (``inside`` False) or in a
    column where the boundary is not bracketed by the simulated loads; ``critical`` is
    the interpolated critical load :math:`T_\\mathrm{high}/EA` (midpoint of the bracket;
    ``bracket`` its (largest held, smallest slipped) bounds, inf when nothing slipped).
    """

    holds: bool | None
    inside: bool
    critical: float
    bracket: tuple
    message: str
    mu_tables: tuple = ()

    def to_dict(self) -> dict:
        """Strict JSON-ready dict (:mod:`knotmech._json`): a non-finite number is null;
        ``critical_unbounded``: nothing slipped above the largest load held (inf)."""
        return _json.jsonable(
            {
                "holds": self.holds,
                "inside_table": self.inside,
                "critical_t_over_EA": self.critical,
                "critical_unbounded": bool(math.isinf(self.critical)),
                "bracket_t_over_EA": [float(v) for v in self.bracket],
                "message": self.message,
                "mu_tables": list(self.mu_tables),
            }
        )


def _grid_answer(votes: set, where: str, pts: str):
    """(holds, message) from the votes of the grid points around a query."""
    if votes == {True}:
        return True, f"holds in the DER table at {where} (grid points: {pts})"
    if votes == {False}:
        return False, f"slips in the DER table at {where} (grid points: {pts})"
    return None, (
        f"{where} lies near a hold/slip boundary of the DER table (grid points: "
        f"{pts}): undecided, use --simulate"
    )


@dataclass
class PhaseTable:
    """Hold/slip points of the DER clove hitch with a free end, on a (d/2R, T/EA) grid."""

    points: list
    mu: float = MU
    mu_rr: float = MU
    meta: dict = field(default_factory=dict)

    @property
    def d_over_2R(self) -> np.ndarray:
        """Sorted distinct d/2R columns."""
        return np.unique([p.d_over_2R for p in self.points])

    @property
    def t_over_EA(self) -> np.ndarray:
        """Sorted distinct loads T_high/EA."""
        return np.unique([p.t_over_EA for p in self.points])

    def _column(self, x: float) -> list:
        return sorted(
            (p for p in self.points if math.isclose(p.d_over_2R, x, rel_tol=1e-9)),
            key=lambda p: p.t_over_EA,
        )

    def column_bracket(self, x: float) -> tuple:
        """Upper boundary in the column d/2R = x: (largest load held, smallest slipped above it).

        0 when nothing held (then the smallest load that slipped is the upper bound), inf
        when nothing above the largest hold slipped.
        """
        col = self._column(x)
        held = [p.t_over_EA for p in col if p.holds]
        lo = max(held) if held else 0.0
        above = [p.t_over_EA for p in col if not p.holds and p.t_over_EA > lo]
        return lo, (min(above) if above else math.inf)

    def low_slip(self, x: float) -> float:
        """Largest load that slipped *below* the smallest load held in the column (0 if none).

        A light load may not tighten a stiff rod onto a thin post: such a column has a
        lower boundary too.
        """
        col = self._column(x)
        held = [p.t_over_EA for p in col if p.holds]
        if not held:
            return 0.0
        below = [p.t_over_EA for p in col if not p.holds and p.t_over_EA < min(held)]
        return max(below) if below else 0.0

    def boundary(self):
        """(d/2R columns, lower bounds, upper bounds, midpoints) of the upper hold/slip boundary.

        The midpoint is inf where nothing slipped above the holds.
        """
        xs = self.d_over_2R
        lo = np.empty(xs.size)
        hi = np.empty(xs.size)
        for i, x in enumerate(xs):
            lo[i], hi[i] = self.column_bracket(float(x))
        mid = np.where(np.isfinite(hi), 0.5 * (lo + hi), np.inf)
        return xs, lo, hi, mid

    def _corners(self, x: float, y: float) -> list:
        """Grid points around (x, y): the columns at or on each side of x, the loads at or
        on each side of y in each column."""
        xs = self.d_over_2R
        i = int(np.searchsorted(xs, x))
        # a query within 0.1 % of a column is on it (the grid's 0.1176 is the paper's 4/34)
        if i < xs.size and math.isclose(xs[i], x, rel_tol=SNAP):
            cols = [xs[i]]
        elif i > 0 and math.isclose(xs[i - 1], x, rel_tol=SNAP):
            cols = [xs[i - 1]]
        else:
            cols = [xs[max(i - 1, 0)], xs[min(i, xs.size - 1)]]
        out = []
        for c in cols:
            col = self._column(float(c))
            loads = np.array([p.t_over_EA for p in col])
            j = int(np.searchsorted(loads, y))
            if j < loads.size and math.isclose(loads[j], y, rel_tol=1e-9):
                out.append(col[j])
            else:
                out += [col[k] for k in (j - 1, j) if 0 <= k < loads.size]
        return out

    def lookup(self, d_over_2R: float, t_over_EA: float, *, mu=None, mu_rr=None) -> PhaseAnswer:
        """Hold or slip at (d/2R, T_high/EA), from the grid points around the query.

        The simulated points at or around the query (up to two columns in d/2R, two loads
        in each) decide when they agree: all held -> holds, all slipped -> slips; a mix
        means the query lies near a boundary and the table does not decide (None). The
        reported critical load is the upper boundary (midpoint between the largest load
        held and the smallest slipped), interpolated linearly in d/2R. Outside the table's
        d/2R or load range, or at a friction coefficient other than the table's
        (tolerance 0.005), the answer is None with a message saying why.
        """
        x = float(d_over_2R)
        y = float(t_over_EA)
        if not (math.isfinite(x) and math.isfinite(y)) or y < 0:
            raise InputError(f"d_over_2R and t_over_EA must be finite, >= 0; got {x}, {y}")
        xs, lo, hi, _ = self.boundary()
        ys = self.t_over_EA
        nan = (float("nan"), float("nan"))

        def outside(msg):
            return PhaseAnswer(None, False, float("nan"), nan, msg)

        for name, val, ref in (("mu", mu, self.mu), ("mu_rr", mu_rr, self.mu_rr)):
            if val is not None and abs(float(val) - ref) > 0.005:
                return outside(
                    f"the DER table was computed at {name} = {ref:g} only, not {float(val):g}"
                )
        if not (xs[0] * (1 - SNAP) <= x <= xs[-1] * (1 + SNAP)):
            return outside(f"d/2R = {x:.4g} is outside the DER table ({xs[0]:.4g} to {xs[-1]:.4g})")
        if not (ys[0] * (1 - 1e-9) <= y <= ys[-1] * (1 + 1e-9)):
            return outside(
                f"T_high/EA = {y:.4g} is outside the simulated loads ({ys[0]:.4g} to {ys[-1]:.4g})"
            )
        big = 1e30
        lo_i = float(np.interp(x, xs, lo))
        hi_i = float(np.interp(x, xs, np.where(np.isfinite(hi), hi, big)))
        if hi_i >= big / 2:
            hi_i = math.inf
        crit = 0.5 * (lo_i + hi_i) if math.isfinite(hi_i) else math.inf
        corners = self._corners(x, y)
        votes = {p.holds for p in corners}
        pts = ", ".join(
            f"({p.d_over_2R:.3g}, {p.t_over_EA:.3g}) {'held' if p.holds else 'slipped'}"
            for p in corners
        )
        holds, msg = _grid_answer(votes, f"d/2R = {x:.4g}, T_high/EA = {y:.4g}", pts)
        return PhaseAnswer(holds, True, crit, (lo_i, hi_i), msg, (self.mu,))

    def to_dict(self) -> dict:
        return {
            "mu": self.mu,
            "mu_rr": self.mu_rr,
            "meta": self.meta,
            "points": [[p.d_over_2R, p.t_over_EA, bool(p.holds)] for p in self.points],
        }

    @classmethod
    def from_dict(cls, data: dict) -> PhaseTable:
        try:
            pts = [PhasePoint(float(a), float(b), bool(c)) for a, b, c in data["points"]]
            return cls(pts, float(data["mu"]), float(data["mu_rr"]), dict(data.get("meta", {})))
        except (KeyError, TypeError, ValueError) as exc:
            raise InputError(f"not a clove-hitch phase table: {exc}") from None

    def write(self, path) -> None:
        text = json.dumps(self.to_dict(), indent=None, allow_nan=False)
        Path(path).write_text(text.replace("], [", "],\n [") + "\n")


def load_table(path=None) -> PhaseTable:
    """The shipped table (``knotmech/data/clove_phase_table.json``) or one from ``path``."""
    if path is None:
        try:
            text = resources.files("knotmech").joinpath("data", TABLE_RESOURCE).read_text()
        except (FileNotFoundError, OSError) as exc:
            raise InputError(f"the shipped phase table is missing: {exc}") from None
    else:
        try:
            text = Path(path).read_text()
        except OSError as exc:
            raise InputError(f"cannot read phase table {str(path)!r}: {exc.strerror}") from None
    try:
        data = json.loads(text)
    except json.JSONDecodeError as exc:
        raise InputError(f"phase table is not JSON: {exc}") from None
    return PhaseTable.from_dict(data)


def table_resource(mu: float) -> str:
    """File name in ``knotmech/data`` of the shipped table at mu = mu_rr = ``mu``."""
    return TABLE_RESOURCE if abs(float(mu) - MU) <= MU_TOL else f"clove_phase_table_mu{mu:g}.json"


def _fmt_mus(mus) -> str:
    return ", ".join(f"{m:g}" for m in mus)


@dataclass
class PhaseTableSet:
    r"""Phase tables at several friction coefficients mu = mu_rr, answering for any mu.

    :meth:`lookup` brackets the user's friction by the tables: with
    :math:`\mu_- = \min(\mu, \mu_{rr})` and :math:`\mu_+ = \max(\mu, \mu_{rr})`,
    the largest table coefficient :math:`\le \mu_-` and the smallest :math:`\ge \mu_+`
    (one table when the query is on a table's coefficient, within :data:`MU_TOL`). The
    answer is decided when both tables decide the same way; this rests on the hold
    being monotonic in friction (a hold at lower friction stays a hold at higher
    friction), which the shipped tables are tested for. Beyond the tables' friction range
    the same assumption decides one way only: above the largest coefficient a hold in
    that table is a hold; below the smallest a slip in that table is a slip; otherwise
    the answer is None and says so.
    """

    tables: list

    def __post_init__(self):
        if not self.tables:
            raise InputError("a phase-table set needs at least one table")
        for t in self.tables:
            if abs(t.mu - t.mu_rr) > MU_TOL:
                raise InputError(
                    f"a phase-table set holds tables with mu = mu_rr only, got mu = {t.mu:g}, "
                    f"mu_rr = {t.mu_rr:g}"
                )
        self.tables = sorted(self.tables, key=lambda t: t.mu)
        mus = [t.mu for t in self.tables]
        if any(b - a <= MU_TOL for a, b in zip(mus, mus[1:], strict=False)):
            raise InputError(f"two phase tables at the same mu: {_fmt_mus(mus)}")

    @property
    def mus(self) -> list:
        """Friction coefficients (mu = mu_rr) of the tables, ascending."""
        return [t.mu for t in self.tables]

    def table(self, mu: float) -> PhaseTable:
        """The table at ``mu`` (within :data:`MU_TOL`)."""
        for t in self.tables:
            if abs(t.mu - float(mu)) <= MU_TOL:
                return t
        raise InputError(f"no phase table at mu = {float(mu):g} (tables: {_fmt_mus(self.mus)})")

    def lookup(self, d_over_2R: float, t_over_EA: float, *, mu: float, mu_rr=None) -> PhaseAnswer:
        r"""Hold or slip at (d/2R, T_high/EA) and friction (mu, mu_rr) from the bracketing tables.

        ``mu_rr`` defaults to ``mu``. The answer's ``mu_tables`` names the tables used;
        ``bracket`` is (smallest largest-load-held, largest smallest-load-slipped) of
        those tables, ``critical`` the upper boundary interpolated linearly in mu at
        :math:`(\mu + \mu_{rr})/2`.
        """
        m = float(mu)
        mr = m if mu_rr is None else float(mu_rr)
        if not (math.isfinite(m) and math.isfinite(mr)) or m < 0 or mr < 0:
            raise InputError(f"mu and mu_rr must be finite, >= 0; got {m}, {mr}")
        lo_m, hi_m = min(m, mr), max(m, mr)
        which = f"mu = {m:g}" + ("" if mr == m else f", mu_rr = {mr:g}")
        below, above = self._bracketing(lo_m, hi_m)
        if below is None and above is None:
            return PhaseAnswer(
                None,
                False,
                float("nan"),
                _NAN2,
                f"{which} is outside the friction range of the DER tables (computed at "
                f"mu = mu_rr = {_fmt_mus(self.mus)} only)",
            )
        if below is None or above is None:
            return self._one_side(below, above, which, d_over_2R, t_over_EA)
        if below is above:
            return _on_table(below, d_over_2R, t_over_EA)
        return self._bracketed(below, above, which, 0.5 * (lo_m + hi_m), d_over_2R, t_over_EA)

    def _bracketing(self, lo_m: float, hi_m: float):
        """(the largest table at or below ``lo_m``, the smallest at or above ``hi_m``), None
        where there is none (within :data:`MU_TOL`)."""
        below = max((t for t in self.tables if t.mu <= lo_m + MU_TOL), key=lambda t: t.mu,
                    default=None)  # fmt: skip
        above = min((t for t in self.tables if t.mu >= hi_m - MU_TOL), key=lambda t: t.mu,
                    default=None)  # fmt: skip
        return below, above

    def _one_side(self, below, above, which, d_over_2R, t_over_EA) -> PhaseAnswer:
        """Friction beyond the tables on one side: a hold at less friction stays a hold at
        more, a slip at more friction stays a slip at less (the assumption the bracketing
        rests on); anything else is undecided."""
        one = below if above is None else above
        a = one.lookup(d_over_2R, t_over_EA)
        if not a.inside:
            return a
        side = "above" if above is None else "below"
        mus = _fmt_mus(self.mus)
        if a.holds is (above is None):  # holds from below, slips from above
            msg = (
                f"{'holds' if a.holds else 'slips'} in the DER table at mu = mu_rr = "
                f"{one.mu:g}, and {which} lies {side} the tables (computed at mu = mu_rr = "
                f"{mus}): {'more' if a.holds else 'less'} friction keeps that "
                f"(assumed; true of every pair of shipped tables); {a.message}"
            )
            return PhaseAnswer(a.holds, True, a.critical, a.bracket, msg, (one.mu,))
        msg = (
            f"{which} lies {side} the friction range of the DER tables (computed at "
            f"mu = mu_rr = {mus}) and the nearest, mu = {one.mu:g}, {_say(a)}: "
            f"undecided, use --simulate ({a.message})"
        )
        return PhaseAnswer(None, True, float("nan"), _NAN2, msg, (one.mu,))

    @staticmethod
    def _bracketed(below, above, which, mid, d_over_2R, t_over_EA) -> PhaseAnswer:
        """Two tables bracketing the friction: decided where both agree; the boundary
        interpolated linearly in mu at ``mid`` = (mu + mu_rr)/2."""
        a = below.lookup(d_over_2R, t_over_EA)
        b = above.lookup(d_over_2R, t_over_EA)
        for r in (a, b):
            if not r.inside:
                return r
        used = (below.mu, above.mu)
        w = (mid - below.mu) / (above.mu - below.mu)
        if math.isfinite(a.critical) and math.isfinite(b.critical):
            crit = (1 - w) * a.critical + w * b.critical
        else:
            crit = math.inf if math.isinf(a.critical) and math.isinf(b.critical) else float("nan")
        bracket = (min(a.bracket[0], b.bracket[0]), max(a.bracket[1], b.bracket[1]))
        tabs = (f"the DER tables at mu = mu_rr = {below.mu:g} ({_say(a)}) and {above.mu:g} "
                f"({_say(b)})")  # fmt: skip
        if a.holds is not None and a.holds == b.holds:
            msg = (
                f"{_say(a)} in {tabs}, which bracket {which} (assumes friction does not turn a "
                f"hold into a slip); {below.mu:g}: {a.message}; {above.mu:g}: {b.message}"
            )
            return PhaseAnswer(a.holds, True, crit, bracket, msg, used)
        msg = (
            f"{tabs}, which bracket {which}, do not agree: undecided, use --simulate "
            f"({below.mu:g}: {a.message}; {above.mu:g}: {b.message})"
        )
        return PhaseAnswer(None, True, crit, bracket, msg, used)


_NAN2 = (float("nan"), float("nan"))


def _on_table(table, d_over_2R, t_over_EA) -> PhaseAnswer:
    """The friction is a table's: that table's answer, naming it."""
    a = table.lookup(d_over_2R, t_over_EA)
    if not a.inside:
        return a
    return PhaseAnswer(a.holds, True, a.critical, a.bracket,
                       f"{a.message}; table mu = mu_rr = {table.mu:g}", (table.mu,))  # fmt: skip


def _say(answer) -> str:
    """``holds``, ``slips`` or ``undecided``."""
    return {True: "holds", False: "slips", None: "undecided"}[answer.holds]


def load_tables(paths=None) -> PhaseTableSet:
    """Every shipped table (``knotmech/data/clove_phase_table*.json``) or those in ``paths``."""
    if paths is not None:
        return PhaseTableSet([load_table(p) for p in paths])
    try:
        folder = resources.files("knotmech").joinpath("data")
        names = sorted(
            f.name for f in folder.iterdir() if Path(f.name).match(TABLE_GLOB) and f.is_file()
        )
    except (FileNotFoundError, OSError) as exc:
        raise InputError(f"the shipped phase tables are missing: {exc}") from None
    if not names:
        raise InputError("the shipped phase tables are missing")
    return PhaseTableSet([_read_table(folder.joinpath(n).read_text(), n) for n in names])


def _read_table(text: str, name: str) -> PhaseTable:
    try:
        data = json.loads(text)
    except json.JSONDecodeError as exc:
        raise InputError(f"phase table {name} is not JSON: {exc}") from None
    return PhaseTable.from_dict(data)


# --------------------------------------------------------------------------- hold tables
#: file names of the shipped anchor-law hold tables, one per knot:
#: ``hold_phase_table_<knot>.json`` (three axes d/2R, T_high/EA, mu = mu_rr)
HOLD_TABLE_GLOB = "hold_phase_table_*.json"
HOLD_TABLE_FORMAT = "knotmech-hold-table"
#: the columns of a hold table's points
HOLD_COLUMNS = ("d_over_2R", "t_over_EA", "mu", "creep_speed", "ran_to_end", "topology", "solved")
_AXES = ("d_over_2R", "t_over_EA", "mu")
_AXIS_TEXT = {"d_over_2R": "d/2R", "t_over_EA": "T_high/EA", "mu": "mu = mu_rr"}


@dataclass(frozen=True)
class HoldPoint:
    """One DER run of a hold table.

    ``creep_speed`` [d/s] over the last :data:`CREEP_WINDOW` of the hold (NaN when the run
    stopped early), ``ran_to_end`` (False: the loaded end ran off), ``topology`` (the knot
    kept its topology), ``solved`` (the solver did not fail).
    """

    d_over_2R: float
    t_over_EA: float
    mu: float
    creep_speed: float
    ran_to_end: bool
    topology: bool
    solved: bool = True

    def holds(self, limit: float = CREEP_LIMIT):
        """The creep-speed criterion at ``limit`` [d/s] (:func:`creep_verdict`)."""
        return creep_verdict(
            self.creep_speed, ran_to_end=self.ran_to_end, topology_preserved=self.topology,
            solver_ok=self.solved, limit=limit,
        )[0]  # fmt: skip

    def describe(self, limit: float = CREEP_LIMIT) -> str:
        h = self.holds(limit)
        state = {True: "held", False: "slipped", None: "failed"}[h]
        if not self.solved:
            why = "the solver stopped it, topology kept"
        elif not self.ran_to_end:
            why = "ran off"
        elif not self.topology:
            why = "topology changed"
        elif math.isfinite(self.creep_speed):
            why = f"{self.creep_speed:.2g} d/s"
        else:
            why = "no creep"
        return f"({self.d_over_2R:.4g}, {self.t_over_EA:.3g}, mu {self.mu:g}) {state}, {why}"


#: law of the hitch scenes that build the anchor-law hold tables (their meta's "law"): the
#: library's anchor law (cap floor min(1e-2 (r_i + r_j), 1/sharpness), floor rule "min",
#: since session 15; the hitches had cap floor 0 in sessions 13-14) and the path tunnelling
#: guard; a table whose law names no ``cap_floor`` was built with the law as shipped before
#: issue 24 (:attr:`HoldTable.law_note`). Written out rather than imported so that ``hold``
#: from a table does not load the solver (tests/rod/test_default_law.py checks that the two
#: agree).
ANCHOR_LAW = (
    "anchor (rod-rod AnchorFriction, cap_floor 0.01 floor_rule min, tunnel_check path; "
    "rod-post anchor friction)"
)


@dataclass(frozen=True)
class HoldAnswer:
    """Answer of :meth:`HoldTable.lookup`.

    ``holds`` True / False / None (undecided); ``rule``: ``"grid"`` (the neighbouring
    points agree), ``"settled-light-load"`` (below the lightest load: the two lightest agree),
    ``"heavier-slips"`` (above the heaviest load, which slipped), ``"more-friction-holds"``,
    ``"less-friction-slips"``, or ``"undecided"``; ``corners`` the grid points used;
    ``creep_speed`` the largest creep speed measured among those points that held [d/s]
    (NaN if none); ``capacity_t_over_EA`` the largest tabulated load held in every corner
    column, with every lighter tabulated load above the query's also held (a lower bound of
    the capacity; NaN if none), ``first_slip_t_over_EA`` the smallest load above the query
    that slipped in any corner column (inf if none).
    """

    holds: bool | None
    inside: bool
    rule: str
    message: str
    corners: tuple = ()
    creep_speed: float = float("nan")
    capacity_t_over_EA: float = float("nan")
    first_slip_t_over_EA: float = float("inf")
    mu_tables: tuple = ()

    @property
    def critical(self) -> float:
        """Midpoint of (capacity, first slip) [T_high/EA]; inf when nothing slipped above."""
        lo, hi = self.capacity_t_over_EA, self.first_slip_t_over_EA
        if not math.isfinite(lo):
            return float("nan")
        return 0.5 * (lo + hi) if math.isfinite(hi) else math.inf

    @property
    def bracket(self) -> tuple:
        return (self.capacity_t_over_EA, self.first_slip_t_over_EA)


def _axis(values, lo, hi, *, rel=SNAP):
    """Grid indices around [lo, hi] on one sorted axis and where the query lies.

    Returns (indices, where): where is "on" (one grid value), "between", "below" or
    "above" the axis (then the indices are the end value(s)).
    """
    v = np.asarray(values, dtype=float)
    near_lo = np.flatnonzero(np.isclose(v, lo, rtol=rel, atol=0))
    near_hi = np.flatnonzero(np.isclose(v, hi, rtol=rel, atol=0))
    if near_lo.size and near_hi.size and near_lo[0] == near_hi[0]:
        return [int(near_lo[0])], "on"
    if hi < v[0] * (1 - rel):
        return [0], "below"
    if lo > v[-1] * (1 + rel):
        return [v.size - 1], "above"
    i = int(near_lo[0]) if near_lo.size else int(np.searchsorted(v, lo) - 1)
    j = int(near_hi[0]) if near_hi.size else int(np.searchsorted(v, hi))
    if i < 0:
        return [0], "below"
    if j >= v.size:
        return [v.size - 1], "above"
    return sorted({i, j}), "between"


def _hold_query(d_over_2R, t_over_EA, mu, mu_rr, creep_limit):
    """(x, y, mu, mu_rr, limit) of a hold-table query, checked (one-line InputErrors)."""
    x, y, m = float(d_over_2R), float(t_over_EA), float(mu)
    mr = m if mu_rr is None else float(mu_rr)
    lim = check_positive("creep_limit", creep_limit, scalar=True)
    for name, v in (("d_over_2R", x), ("t_over_EA", y), ("mu", m), ("mu_rr", mr)):
        if not math.isfinite(v) or v < 0:
            raise InputError(f"{name} must be finite and >= 0, got {v}")
    return x, y, m, mr, lim


#: how an undecided lookup names runs that contradict each other in mu
#: (:meth:`HoldTable.against_mu`); the verdict's first line looks for it
AGAINST_MU = "contradict more friction never turning a hold into a slip"


def _split_message(where: str, pts: str, votes: list, against: bool = False) -> str:
    """Why neighbours that do not agree (or a run that failed, or runs that contradict each
    other in mu: ``against``) leave a query undecided."""
    if against:
        return f"{where}: neighbouring DER points {AGAINST_MU} ({pts}): undecided"
    if None in votes:
        return f"{where}: a neighbouring DER run failed ({pts}): undecided"
    return f"{where} lies between DER points that disagree ({pts}): undecided"


def _beyond_grid(ax: dict, yw: str, mw: str, v: bool) -> list:
    """The monotonicity rules that apply beyond the grid (where the load is ``yw`` and the
    friction ``mw`` of their axes ``ax``), for neighbours that agree on ``v``: a list of
    (rule name, whether it lets ``v`` stand, text)."""
    rules = []
    if yw == "below":
        rules.append(("settled-light-load", True,
                      f"the load is below the lightest tabulated ({ax['t_over_EA'][0]:.3g} "
                      "EA), where the two lightest loads agree (the verdict has settled)",
                      ))  # fmt: skip
    if yw == "above":
        said = (", which slipped: a heavier load slips" if not v
                else ", which held: that says nothing about a heavier load")  # fmt: skip
        rules.append(("heavier-slips", not v,
                      f"the load is above the heaviest tabulated ({ax['t_over_EA'][-1]:.3g} "
                      "EA)" + said))  # fmt: skip
    if mw == "above":
        said = (", which held: more friction holds" if v
                else ", which slipped: that says nothing about more friction")  # fmt: skip
        rules.append(("more-friction-holds", v,
                      f"the friction is above the largest tabulated (mu = {ax['mu'][-1]:g})"
                      + said))  # fmt: skip
    if mw == "below":
        said = (", which slipped: less friction slips" if not v
                else ", which held: that says nothing about less friction")  # fmt: skip
        rules.append(("less-friction-slips", not v,
                      f"the friction is below the smallest tabulated (mu = {ax['mu'][0]:g})"
                      + said))  # fmt: skip
    return rules


@dataclass
class HoldTable:
    r"""DER hold/slip runs of one knot with a free end on a (d/2R, T_high/EA, mu) grid.

    Every point stores the creep speed it measured, so the criterion's limit can be
    changed at lookup (:meth:`lookup`, ``creep_limit``). mu is the rope-post and the
    rope-rope coefficient alike (mu = mu_rr).

    **Deciding** (:meth:`lookup`). Between grid points the answer is decided only where
    every neighbouring point (up to two values on each axis) agrees. Beyond the grid only
    where monotonicity says so:

    - a load lighter than the lightest tabulated one takes that load's answer when the
      two lightest loads agree at every neighbouring (d/2R, mu) (the verdict has settled as
      the load falls);
    - a load heavier than the heaviest: slips where that load slipped (a hold there says
      nothing about heavier loads);
    - a friction above the largest: holds where that friction held; below the smallest:
      slips where that friction slipped;
    - outside the d/2R range: never decided (no monotonicity in d/2R is assumed).

    Runs that contradict these assumptions in mu (a column that held at one friction and
    slipped at a larger one: :meth:`against_mu`) are read as undecided, both of them, so
    that no rule builds on either.

    A rope-rope friction ``mu_rr`` other than ``mu`` brackets the mu axis by
    ``[min(mu, mu_rr), max(mu, mu_rr)]`` (assumes more friction of either kind does not
    turn a hold into a slip). Everything else is undecided, with the reason.
    """

    knot: str
    points: list
    meta: dict = field(default_factory=dict)
    law: str = "anchor"
    criterion: dict = field(
        default_factory=lambda: {
            "name": CREEP_CRITERION, "limit_d_per_s": CREEP_LIMIT, "window_s": CREEP_WINDOW,
        }
    )  # fmt: skip

    def __post_init__(self):
        if not self.points:
            raise InputError(f"hold table of {self.knot}: no points")
        self._index = {}
        for p in self.points:
            if not (0 < p.d_over_2R < 0.5 and p.t_over_EA > 0 and p.mu >= 0):
                raise InputError(
                    f"hold table of {self.knot}: point ({p.d_over_2R:g}, {p.t_over_EA:g}, "
                    f"{p.mu:g}) is outside 0 < d/2R < 0.5, T_high/EA > 0, mu >= 0"
                )
            key = self._key(p.d_over_2R, p.t_over_EA, p.mu)
            if key in self._index:
                raise InputError(f"hold table of {self.knot}: point {key} appears twice")
            self._index[key] = p
        self.axes = {a: np.unique([getattr(p, a) for p in self.points]) for a in _AXES}
        n = int(np.prod([v.size for v in self.axes.values()]))
        if n != len(self.points):
            raise InputError(
                f"hold table of {self.knot}: {len(self.points)} points do not fill the "
                f"{' x '.join(str(v.size) for v in self.axes.values())} grid"
            )

    @staticmethod
    def _key(x, y, m):
        return (round(float(x), 9), round(float(y), 12), round(float(m), 9))

    def point(self, x, y, m) -> HoldPoint:
        """The grid point at (d/2R, T_high/EA, mu) (exact grid values)."""
        return self._index[self._key(x, y, m)]

    @property
    def mus(self) -> list:
        return [float(m) for m in self.axes["mu"]]

    def holds_at(self, x, y, m, limit: float = CREEP_LIMIT):
        """The verdict of the grid point at (d/2R, T_high/EA, mu) (exact grid values) read
        against its column in mu: None (undecided) where it contradicts more friction never
        turning a hold into a slip (:meth:`against_mu`), else :meth:`HoldPoint.holds`."""
        return self._reading(self.point(x, y, m), limit)[0]

    def _reading(self, p: HoldPoint, limit: float) -> tuple:
        """(verdict, text): the run ``p`` read against its column in mu (:meth:`holds_at`),
        and the contradiction's text (None where there is none)."""
        note = self.against_mu(limit).get(self._key(p.d_over_2R, p.t_over_EA, p.mu))
        return (None if note else p.holds(limit)), note

    def against_mu(self, limit: float = CREEP_LIMIT) -> dict:
        """{point key: text} of the grid points whose verdicts contradict each other in mu:
        in one (d/2R, T_high/EA) column, a point that held at a friction below one that
        slipped, and that one (either run may be the wrong one; a failed run contradicts
        nothing). Every rule of :meth:`lookup` assumes that more friction does not turn a
        hold into a slip, so such points are read as undecided."""
        cache = self.__dict__.setdefault("_against_cache", {})
        if limit not in cache:
            cache[limit] = self._contradictions(limit)
        return cache[limit]

    def _contradictions(self, limit: float) -> dict:
        """:meth:`against_mu`, computed."""
        out = {}
        mus = self.axes["mu"]
        for x in self.axes["d_over_2R"]:
            for y in self.axes["t_over_EA"]:
                pts = [self.point(x, y, m) for m in mus]
                votes = [p.holds(limit) for p in pts]
                for a, b in itertools.combinations(range(len(pts)), 2):
                    if votes[a] is True and votes[b] is False:
                        text = f"held at mu {mus[a]:g}, slipped at mu {mus[b]:g}"
                        for p in (pts[a], pts[b]):
                            out.setdefault(self._key(p.d_over_2R, p.t_over_EA, p.mu), text)
        return out

    def slice(self, mu: float, *, creep_limit: float = CREEP_LIMIT) -> PhaseTable:
        """The (d/2R, T_high/EA) slice at a tabulated ``mu`` as a :class:`PhaseTable`."""
        m = [v for v in self.mus if abs(v - float(mu)) <= MU_TOL]
        if not m:
            raise InputError(f"no mu = {float(mu):g} in the {self.knot} hold table ({self.mus})")
        pts = [PhasePoint(p.d_over_2R, p.t_over_EA, bool(p.holds(creep_limit)))
               for p in self.points if p.mu == m[0]]  # fmt: skip
        return PhaseTable(pts, m[0], m[0], {"law": self.law, "knot": self.knot})

    @property
    def law_note(self) -> str:
        """One line when the table was built with the anchor law as shipped before issue 24
        (its meta's law names no ``cap_floor``), "" otherwise."""
        if "cap_floor" in str(self.meta.get("law", "")):
            return ""
        return (
            "table built with the anchor law as shipped before issue 24 (cap_floor 0, "
            f"tunnel_check displacement), not the hitch scenes' law since: {ANCHOR_LAW}"
        )

    def lookup(
        self,
        d_over_2R: float,
        t_over_EA: float,
        *,
        mu: float,
        mu_rr: float | None = None,
        creep_limit: float = CREEP_LIMIT,
    ) -> HoldAnswer:
        """Hold, slip or undecided at (d/2R, T_high/EA, mu, mu_rr) by the rules above; the
        message ends with :attr:`law_note` when there is one."""
        a = self._lookup(d_over_2R, t_over_EA, mu=mu, mu_rr=mu_rr, creep_limit=creep_limit)
        note = self.law_note
        return replace(a, message=f"{a.message}; {note}") if note else a

    def _lookup(self, d_over_2R, t_over_EA, *, mu, mu_rr, creep_limit) -> HoldAnswer:
        """:meth:`lookup` without the law note."""
        x, y, m, mr, lim = _hold_query(d_over_2R, t_over_EA, mu, mu_rr, creep_limit)
        ax = self.axes
        xi, xw = _axis(ax["d_over_2R"], x, x)
        yi, yw = _axis(ax["t_over_EA"], y, y, rel=1e-9)
        mi, mw = _axis(ax["mu"], min(m, mr), max(m, mr), rel=MU_TOL / max(m, mr, 1e-9))
        if yw == "below":
            yi = [0, 1] if ax["t_over_EA"].size > 1 else [0]
        where = f"d/2R = {x:.4g}, T_high/EA = {y:.3g}, mu = {m:g}" + (
            "" if mr == m else f", mu_rr = {mr:g}")  # fmt: skip
        mus_used = tuple(float(ax["mu"][k]) for k in mi)
        if xw in ("below", "above"):
            return HoldAnswer(
                None, False, "undecided",
                f"{where}: d/2R is {xw} the {self.knot} table ({ax['d_over_2R'][0]:.4g} to "
                f"{ax['d_over_2R'][-1]:.4g}), where nothing is assumed about how d/2R "
                "changes the verdict: undecided", mu_tables=mus_used,
            )  # fmt: skip
        corners = [self.point(ax["d_over_2R"][i], ax["t_over_EA"][j], ax["mu"][k])
                   for i in xi for j in yi for k in mi]  # fmt: skip
        votes, notes = zip(*(self._reading(p, lim) for p in corners), strict=True)
        pts = "; ".join(p.describe(lim) + (f" (against mu: {n})" if n else "")
                        for p, n in zip(corners, notes, strict=True))  # fmt: skip
        common = self._common(corners, votes, xi, mi, y, lim, mus_used)
        inside = yw in ("on", "between") and mw in ("on", "between")
        if None in votes or len(set(votes)) > 1:
            return HoldAnswer(None, inside, "undecided",
                              _split_message(where, pts, votes, any(notes)), **common)  # fmt: skip
        return self._agreed(votes[0], where, pts, inside, _beyond_grid(ax, yw, mw, votes[0]),
                            common)  # fmt: skip

    def _common(self, corners, votes, xi, mi, y, lim, mus_used) -> dict:
        """What every answer from ``corners`` reports: the corners, the largest creep of
        those that held, the capacity bracket and the friction tables used."""
        speeds = [p.creep_speed for p, v in zip(corners, votes, strict=True) if v]
        cap, first_slip = self._capacity(xi, mi, y, lim)
        return dict(corners=tuple(corners),
                    creep_speed=max(speeds, key=abs) if speeds else float("nan"),
                    capacity_t_over_EA=cap, first_slip_t_over_EA=first_slip,
                    mu_tables=mus_used)  # fmt: skip

    def _agreed(self, v: bool, where: str, pts: str, inside: bool, rules: list, common: dict):
        """The answer where every neighbouring point agrees on ``v``: decided unless a rule
        beyond the grid (``rules``: (name, whether it lets ``v`` stand, text)) refuses."""
        bad = [text for _, ok, text in rules if not ok]
        if bad:
            return HoldAnswer(None, False, "undecided",
                              f"{where}: {'; '.join(bad)}: undecided (DER points: {pts})",
                              **common)  # fmt: skip
        rule = rules[0][0] if rules else "grid"
        why = "; ".join(text for _, _, text in rules)
        state = "holds" if v else "slips"
        msg = (f"{state} in the DER {self.knot} table at {where} (" + (why + "; " if why else "")
               + f"DER points: {pts})")  # fmt: skip
        return HoldAnswer(v, inside, rule, msg, **common)

    def _capacity(self, xi, mi, y, lim):
        """(largest tabulated load held in every corner column with every tabulated load
        from the query's up to it held; smallest load >= the query's that slipped in any)."""
        ys = self.axes["t_over_EA"]
        cap = math.inf
        first = math.inf
        for i in xi:
            for k in mi:
                col_cap = float("nan")
                for y_t in ys:
                    if y_t < y * (1 - 1e-9) and y_t != ys[-1]:
                        # loads below the query do not bound it (except the heaviest)
                        continue
                    h = self.point(self.axes["d_over_2R"][i], y_t, self.axes["mu"][k]).holds(lim)
                    if h:
                        col_cap = float(y_t)
                    else:
                        first = min(first, float(y_t))
                        break
                cap = min(cap, col_cap) if math.isfinite(col_cap) else float("nan")
                if math.isnan(cap):
                    break
        return (cap if math.isfinite(cap) else float("nan")), first

    # ----------------------------------------------------------------- file format
    def to_dict(self) -> dict:
        def num(v):
            return None if not math.isfinite(v) else float(f"{v:.4g}")

        return {
            "format": HOLD_TABLE_FORMAT,
            "version": 1,
            "knot": self.knot,
            "law": self.law,
            "criterion": dict(self.criterion),
            "axes": {a: [float(v) for v in self.axes[a]] for a in _AXES},
            "columns": list(HOLD_COLUMNS),
            "points": [
                [
                    p.d_over_2R,
                    p.t_over_EA,
                    p.mu,
                    num(p.creep_speed),
                    int(p.ran_to_end),
                    int(p.topology),
                    int(p.solved),
                ]
                for p in self.points
            ],  # fmt: skip
            "meta": self.meta,
        }

    @classmethod
    def from_dict(cls, data: dict, *, name: str = "hold table") -> HoldTable:
        try:
            if data.get("format") != HOLD_TABLE_FORMAT:
                raise ValueError(f"format is not {HOLD_TABLE_FORMAT!r}")
            if list(data["columns"]) != list(HOLD_COLUMNS):
                raise ValueError(f"columns must be {list(HOLD_COLUMNS)}")
            pts = []
            for row in data["points"]:
                x, y, m, s, ran, topo, ok = row
                pts.append(
                    HoldPoint(
                        float(x),
                        float(y),
                        float(m),
                        float("nan") if s is None else float(s),
                        bool(ran),
                        bool(topo),
                        bool(ok),
                    )
                )
            meta = dict(data.get("meta", {}))
            meta_bending_scale(meta, "its meta")  # an InputError is a ValueError: wrapped below
            meta_t_low_fraction(meta, "its meta")
            return cls(str(data["knot"]), pts, meta, str(data["law"]),
                       dict(data["criterion"]))  # fmt: skip
        except (KeyError, TypeError, ValueError, AttributeError) as exc:
            raise InputError(f"{name}: not a knotmech hold table: {exc}") from None

    @property
    def bending_scale(self) -> float:
        """The rods' bending scale kappa the table was built with (meta, 1 when absent)."""
        return meta_bending_scale(self.meta)

    @property
    def t_low_fraction(self) -> float:
        """T_low / T_high on the other end in every run (meta, 0 when absent: a free end;
        above 0: the cow hitch loaded on both legs)."""
        return meta_t_low_fraction(self.meta)

    def write(self, path) -> None:
        """Compact JSON (one point per line)."""
        d = self.to_dict()
        pts = d.pop("points")
        text = json.dumps(d, separators=(",", ":"), allow_nan=False)
        rows = ",\n".join(json.dumps(r, separators=(",", ":")) for r in pts)
        Path(path).write_text(text[:-1] + ',"points":[\n' + rows + "]}\n")

    @classmethod
    def from_results(cls, knot: str, results, *, meta=None) -> HoldTable:
        """A table from :func:`simulate_point`-like result dicts (anchor law)."""
        pts = []
        for r in results:
            pts.append(HoldPoint(
                float(r["d_over_2R"]), float(r["t_over_EA"]), float(r["mu"]),
                float(r["creep_speed"]), bool(r["ran_to_end"]), bool(r["topology_preserved"]),
                r["holds"] is not None
                and solver_gave_verdict(r.get("status", "success"), r["topology_preserved"]),
            ))  # fmt: skip
        pts.sort(key=lambda p: (p.mu, p.d_over_2R, p.t_over_EA))
        return cls(knot, pts, dict(meta or {}))


def meta_bending_scale(meta, name: str = "the DER table") -> float:
    """A table's bending scale kappa from its meta (``bending_scale``, 1 when absent).

    Raises
    ------
    InputError
        It is not a number in (0, 1] (one line naming ``name``).
    """
    k = (meta or {}).get("bending_scale", 1.0)
    if isinstance(k, bool) or not isinstance(k, (int, float)) or not 0 < k <= 1:
        raise InputError(f"{name}: meta bending_scale must be a number in (0, 1], got {k!r}")
    return float(k)


def meta_t_low_fraction(meta, name: str = "the DER table") -> float:
    """A table's T_low / T_high from its meta (``t_low_fraction``, 0 when absent: a free end).

    Raises
    ------
    InputError
        It is not a number in [0, 1] (one line naming ``name``).
    """
    f = (meta or {}).get("t_low_fraction", 0.0)
    if isinstance(f, bool) or not isinstance(f, (int, float)) or not 0 <= f <= 1:
        raise InputError(f"{name}: meta t_low_fraction must be a number in [0, 1], got {f!r}")
    return float(f)


def _num(v):
    v = float(v)
    return float(f"{v:.4g}") if math.isfinite(v) else None


def read_hold_table(path) -> HoldTable:
    """A hold table from a file (one-line :class:`InputError` when it does not read)."""
    try:
        text = Path(path).read_text()
    except OSError as exc:
        raise InputError(f"cannot read hold table {str(path)!r}: {exc.strerror}") from None
    try:
        data = json.loads(text)
    except json.JSONDecodeError as exc:
        raise InputError(f"hold table {str(path)!r} is not JSON: {exc}") from None
    return HoldTable.from_dict(data, name=f"hold table {str(path)!r}")


def load_hold_tables() -> dict:
    """The shipped solid-rod (kappa = 1) hold tables: {knot: table}
    (:func:`load_hold_table_sets` has those of every bending scale)."""
    out = {}
    for knot, by_kappa in load_hold_table_sets().items():
        out[knot] = by_kappa.get(1.0, by_kappa[max(by_kappa)])
    return out


def load_hold_table_sets(tables=None) -> dict:
    """Every shipped hold table with a free end (``knotmech/data/hold_phase_table_*.json``):
    {knot: {bending scale kappa: table}} (:func:`load_legs_table_sets` has those whose runs
    load the other end too). ``tables``: the list :func:`read_shipped_hold_tables` returned,
    to sort instead of reading the files again."""
    out = {}
    for t in read_shipped_hold_tables() if tables is None else tables:
        if t.t_low_fraction == 0.0:
            out.setdefault(t.knot, {})[t.bending_scale] = t
    return out


def load_legs_table_sets(tables=None) -> dict:
    """The shipped hold tables whose runs load the other end with T_low = f T_high (the cow
    hitch loaded on both legs): {knot: {kappa: {f: table}}}; ``tables`` as for
    :func:`load_hold_table_sets`."""
    out = {}
    for t in read_shipped_hold_tables() if tables is None else tables:
        if t.t_low_fraction > 0.0:
            out.setdefault(t.knot, {}).setdefault(t.bending_scale, {})[t.t_low_fraction] = t
    return out


def read_shipped_hold_tables() -> list:
    """Every ``knotmech/data/hold_phase_table_*.json``, read (a one-line InputError when one
    is missing or not a hold table)."""
    try:
        folder = resources.files("knotmech").joinpath("data")
        names = sorted(
            f.name for f in folder.iterdir() if Path(f.name).match(HOLD_TABLE_GLOB) and f.is_file()
        )
    except (FileNotFoundError, OSError) as exc:
        raise InputError(f"the shipped hold tables are missing: {exc}") from None
    out = []
    for n in names:
        try:
            data = json.loads(folder.joinpath(n).read_text())
        except json.JSONDecodeError as exc:
            raise InputError(f"hold table {n} is not JSON: {exc}") from None
        out.append(HoldTable.from_dict(data, name=f"hold table {n}"))
    return out


def hold_table_resource(knot: str, bending_scale: float = 1.0, t_low_fraction: float = 0.0) -> str:
    """File name in ``knotmech/data`` of the shipped hold table of ``knot`` built with the
    bending scale ``bending_scale`` (``hold_phase_table_<knot>.json`` for the solid rod,
    kappa = 1; ``hold_phase_table_<knot>_kappa<kappa>.json`` otherwise), and with
    ``_tlow<fraction>`` before ``.json`` for a table whose runs load the other end with
    ``t_low_fraction`` x T_high (the cow hitch on both legs)."""
    k, f = float(bending_scale), float(t_low_fraction)
    return (f"hold_phase_table_{knot}" + ("" if k == 1.0 else f"_kappa{k:g}")
            + ("" if f == 0.0 else f"_tlow{f:g}") + ".json")  # fmt: skip

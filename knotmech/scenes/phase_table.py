r"""Clove hitch with a free end: DER hold/slip phase table, one point or a shipped grid.

The clove-hitch paper (Extreme Mech. Lett., DOI 10.1016/j.eml.2022.101788, sec. 8 and
Fig. 4) maps whether a clove hitch with a free end (:math:`T_\mathrm{low} = 0`) holds a
dead load :math:`T_\mathrm{high}` as a function of the rescaled load
:math:`T_\mathrm{high}/EA` (:math:`A = \pi d^2/4`) and the rescaled diameter
:math:`d/2R`, with :math:`R = (D+d)/2` the radius of the rod centreline on the post.
Ideal-rope theory (Maddocks & Keller 1987) predicts a slip at any load; the
experiments find a load-dependent boundary with an upper bound near
:math:`T_\mathrm{high}/EA \approx 0.3`.

This module

- simulates one point of that diagram with the DER scene
  :func:`knotmech.scenes.clove_hitch.clove_hitch` (:func:`simulate_point`, a module-level
  function for :func:`knotmech.sweep.sweep`),
- loads the precomputed table shipped in ``knotmech/data/clove_phase_table.json``
  (:func:`load_table`, mu = mu_rr = 0.3; regenerate with ``python -m
  validation.clove_phase_diagram --write-table``) or every shipped table, one per
  friction coefficient mu = mu_rr (``clove_phase_table_mu<mu>.json``, written by
  ``--write-table --mu <mu>``; :func:`load_tables`),
- answers a query from that table (:meth:`PhaseTable.lookup`): the simulated points
  around the query decide when they agree (all held or all slipped), otherwise the
  query is near a boundary and the table does not decide; per d/2R column the upper
  boundary lies between the largest load that held and the smallest that slipped
  above it, interpolated linearly in d/2R. Outside the grid (or at another friction
  coefficient) the table gives no answer and says so,
- answers for any friction from the set of tables (:meth:`PhaseTableSet.lookup`): the
  tables bracketing the user's (mu, mu_rr) decide when they agree, assuming that more
  friction does not turn a hold into a slip (true of every shipped table pair).

Shipped tables (d = 4 mm VPS32 rod, 4 x 4 grid): mu = 0.2 and 0.25 slip at every
point, 0.3 holds 6 of 16 (interior boundary), 0.35 holds 13 (slips only at 0.3 EA off
the paper's d/2R), 0.4 and 0.5 hold all 16.
"""

from __future__ import annotations

import json
import math
from dataclasses import dataclass, field
from importlib import resources
from pathlib import Path

import numpy as np

from knotmech.errors import InputError, check_positive

__all__ = [
    "PhasePoint",
    "PhaseTable",
    "PhaseAnswer",
    "simulate_point",
    "point_geometry",
    "load_table",
    "load_tables",
    "PhaseTableSet",
    "TABLE_RESOURCE",
    "ROD_DIAMETER",
    "YOUNGS_MODULUS",
    "DENSITY",
    "MU",
]

TABLE_RESOURCE = "clove_phase_table.json"  #: the mu = mu_rr = 0.3 table (the first one shipped)
#: every shipped table: ``clove_phase_table.json`` and ``clove_phase_table_mu<mu>.json``
TABLE_GLOB = "clove_phase_table*.json"
MU_TOL = 0.005  #: a friction coefficient within this of a table's is that table's
ROD_DIAMETER = 4e-3  #: [m] the clove-hitch paper's rod (VPS32)
YOUNGS_MODULUS = 1.26e6  #: [Pa] VPS32
DENSITY = 1150.0  #: [kg/m^3]
MU = 0.3  #: rod-post and rod-rod friction of the table (the paper's sec. 7 value)
TAIL = 0.064  #: [m] straight tail at each end (the paper's L = 374 mm at D = 30 mm)
EDGE = 0.374 / 119  #: [m] rest edge length (120 nodes on 374 mm)
SNAP = 1e-3  #: relative distance in d/2R within which a query lies on a table column
#: run protocol of a point (settle, ramp, hold [s]; time step [s])
PROTOCOL = dict(settle_time=0.2, load_time=0.2, hold_time=0.4, dt=2e-3, n_frames=21)


def point_geometry(d_over_2R: float, *, rod_diameter: float = ROD_DIAMETER) -> dict:
    r"""Post diameter, rod length and node count of a phase point.

    :math:`d/2R = d/(D+d)` gives :math:`D = d(1/(d/2R) - 1)`; the rod is two wraps
    (:math:`4\pi R` plus 15 % slack for the crossing, as the scene requires) plus a
    64 mm tail at each end (the paper's 374 mm rod at D = 30 mm), discretised with a
    fixed edge length of about 3.1 mm.
    """
    x = float(d_over_2R)
    if not 0.0 < x < 0.5:
        raise InputError(f"d_over_2R must be in (0, 0.5), got {x:g}")
    d = float(check_positive("rod_diameter", rod_diameter))
    D = d * (1.0 / x - 1.0)
    R = 0.5 * (D + d)
    L = 4 * np.pi * R * 1.15 + 2 * TAIL
    return {"post_diameter": D, "rod_length": L, "n_nodes": int(round(L / EDGE)) + 1}


def simulate_point(
    *,
    d_over_2R: float,
    t_over_EA: float,
    mu: float = MU,
    mu_rr: float | None = None,
    rod_diameter: float = ROD_DIAMETER,
    youngs_modulus: float = YOUNGS_MODULUS,
    density: float = DENSITY,
    friction: str = "anchor",
    progress: bool = False,
    keep_result: bool = False,
) -> dict:
    r"""One DER run of a clove hitch with a free end: does it hold :math:`T_\mathrm{high}`?

    Ties the hitch on a post of diameter :math:`D = d(1/(d/2R) - 1)`, hangs
    :math:`T_\mathrm{high} = (T_\mathrm{high}/EA)\,E\pi d^2/4` on end 0, leaves the other
    end free, and returns the scene's verdict (hold: end 0 creeps less than one rod
    diameter over the second half of a 0.4 s hold; protocol :data:`PROTOCOL`).

    ``friction`` is the rod-rod law passed to the scene (``"anchor"``, the scene's
    default, or ``"imc"``, the law of the shipped tables); it is passed explicitly so a
    change of the scene's default does not silently change a table.

    Returns
    -------
    dict
        ``d_over_2R, t_over_EA, t_high [N], post_diameter [m], friction, verdict
        ("hold"/"slip"), holds (bool), creep [m], creep_speed [d/s] (creep over the last
        half of the hold divided by that time and by d), status, topology_preserved,
        wall_s``. A run whose solver
        failed has ``holds = None``. With ``keep_result``, also ``result``: the scene's
        :class:`~knotmech.scenes.clove_hitch.CloveHitchResult` (positions, tension).
    """
    d = float(check_positive("rod_diameter", rod_diameter))
    E = float(check_positive("youngs_modulus", youngs_modulus))
    tea = float(check_positive("t_over_EA", t_over_EA))
    from knotmech.scenes.clove_hitch import clove_hitch

    geo = point_geometry(d_over_2R, rod_diameter=d)
    t_high = tea * E * np.pi * d * d / 4
    r = clove_hitch(
        loading="free",
        t_high=t_high,
        rod_diameter=d,
        post_diameter=geo["post_diameter"],
        rod_length=geo["rod_length"],
        n_nodes=geo["n_nodes"],
        youngs_modulus=E,
        density=float(density),
        mu_rod_post=float(mu),
        mu_rod_rod=float(mu if mu_rr is None else mu_rr),
        friction=friction,
        progress=progress,
        **PROTOCOL,
    )
    ok = r.status == "success" or r.verdict == "slip"
    out = {
        "d_over_2R": float(d_over_2R),
        "t_over_EA": tea,
        "t_high": float(t_high),
        "post_diameter": geo["post_diameter"],
        "mu": float(mu),
        "mu_rr": float(mu if mu_rr is None else mu_rr),
        "verdict": r.verdict if ok else "",
        "holds": (r.verdict == "hold") if ok else None,
        "friction": friction,
        "creep": float(r.creep),
        "creep_speed": float(r.creep) / (0.5 * PROTOCOL["hold_time"] * d),
        "status": r.status,
        "message": r.message,
        "topology_preserved": bool(r.topology_preserved),
        "wall_s": float(r.stats.get("wall_s", float("nan"))),
    }
    if keep_result:
        out["result"] = r
    return out


simulate_point.__sweep_version__ = "2"


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
        def num(v):
            return v if math.isfinite(v) else str(v)

        return {
            "holds": self.holds,
            "inside_table": self.inside,
            "critical_t_over_EA": num(self.critical),
            "bracket_t_over_EA": [num(float(v)) for v in self.bracket],
            "message": self.message,
            "mu_tables": list(self.mu_tables),
        }


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
        where = f"d/2R = {x:.4g}, T_high/EA = {y:.4g}"
        if votes == {True}:
            holds, msg = True, f"holds in the DER table at {where} (grid points: {pts})"
        elif votes == {False}:
            holds, msg = False, f"slips in the DER table at {where} (grid points: {pts})"
        else:
            holds = None
            msg = (
                f"{where} lies near a hold/slip boundary of the DER table (grid points: "
                f"{pts}): undecided, use --simulate"
            )
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
        mus = self.mus
        nan = (float("nan"), float("nan"))
        which = f"mu = {m:g}" + ("" if mr == m else f", mu_rr = {mr:g}")
        below = max((t for t in self.tables if t.mu <= lo_m + MU_TOL), key=lambda t: t.mu,
                    default=None)  # fmt: skip
        above = min((t for t in self.tables if t.mu >= hi_m - MU_TOL), key=lambda t: t.mu,
                    default=None)  # fmt: skip
        if below is None and above is None:
            return PhaseAnswer(
                None,
                False,
                float("nan"),
                nan,
                f"{which} is outside the friction range of the DER tables (computed at "
                f"mu = mu_rr = {_fmt_mus(mus)} only)",
            )
        if below is None or above is None:
            # one side only: a hold at less friction stays a hold at more, a slip at more
            # friction stays a slip at less (the assumption the bracketing rests on)
            one = below if above is None else above
            a = one.lookup(d_over_2R, t_over_EA)
            if not a.inside:
                return a
            side = "above" if above is None else "below"
            decides = a.holds is (above is None)  # holds from below, slips from above
            if decides:
                msg = (
                    f"{'holds' if a.holds else 'slips'} in the DER table at mu = mu_rr = "
                    f"{one.mu:g}, and {which} lies {side} the tables (computed at mu = mu_rr = "
                    f"{_fmt_mus(mus)}): {'more' if a.holds else 'less'} friction keeps that "
                    f"(assumed; true of every pair of shipped tables); {a.message}"
                )
                return PhaseAnswer(a.holds, True, a.critical, a.bracket, msg, (one.mu,))
            state = {True: "holds", False: "slips", None: "undecided"}[a.holds]
            msg = (
                f"{which} lies {side} the friction range of the DER tables (computed at "
                f"mu = mu_rr = {_fmt_mus(mus)}) and the nearest, mu = {one.mu:g}, {state}: "
                f"undecided, use --simulate ({a.message})"
            )
            return PhaseAnswer(None, True, float("nan"), nan, msg, (one.mu,))
        if below is above:
            a = below.lookup(d_over_2R, t_over_EA)
            if not a.inside:
                return a
            return PhaseAnswer(
                a.holds,
                True,
                a.critical,
                a.bracket,
                f"{a.message}; table mu = mu_rr = {below.mu:g}",
                (below.mu,),
            )
        a = below.lookup(d_over_2R, t_over_EA)
        b = above.lookup(d_over_2R, t_over_EA)
        for r in (a, b):
            if not r.inside:
                return r
        used = (below.mu, above.mu)

        def say(r):
            return {True: "holds", False: "slips", None: "undecided"}[r.holds]

        w = (0.5 * (lo_m + hi_m) - below.mu) / (above.mu - below.mu)
        if math.isfinite(a.critical) and math.isfinite(b.critical):
            crit = (1 - w) * a.critical + w * b.critical
        else:
            crit = math.inf if math.isinf(a.critical) and math.isinf(b.critical) else float("nan")
        bracket = (min(a.bracket[0], b.bracket[0]), max(a.bracket[1], b.bracket[1]))
        tabs = f"the DER tables at mu = mu_rr = {below.mu:g} ({say(a)}) and {above.mu:g} ({say(b)})"
        if a.holds is not None and a.holds == b.holds:
            msg = (
                f"{say(a)} in {tabs}, which bracket {which} (assumes friction does not turn a "
                f"hold into a slip); {below.mu:g}: {a.message}; {above.mu:g}: {b.message}"
            )
            return PhaseAnswer(a.holds, True, crit, bracket, msg, used)
        msg = (
            f"{tabs}, which bracket {which}, do not agree: undecided, use --simulate "
            f"({below.mu:g}: {a.message}; {above.mu:g}: {b.message})"
        )
        return PhaseAnswer(None, True, crit, bracket, msg, used)


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

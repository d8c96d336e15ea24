r"""Strength and friction of real ropes: breaking load, knot efficiency, friction ranges.

Every number comes from a published table, transcribed literally (in the source's own
units) into ``knotmech/data/strength/*.json`` with its ``source``, ``url`` and
``where`` (table, page, row); this module converts to SI and interpolates. Where no
citable number was found the data say so (``not_found``, ``no_efficiency_found``) and
the functions raise :class:`NoDataError` rather than guess. Sources, the choice
between them and the caveats are in ``docs/notes/strength.md``.

Breaking load
    New-rope breaking strength :math:`F(d)` by nominal diameter :math:`d`, one or more
    tables per material. Between tabulated diameters :math:`F` is interpolated linearly
    in :math:`d^2` (strength scales with the cross-section), so a tabulated diameter
    returns its row exactly. The first table of a material covering :math:`d` gives the
    nominal value; the lowest and highest of all tables covering :math:`d` give the
    range (tables differ by maker and construction). A material without a table may
    have a law instead (``laws`` in ``mbs.json``): :math:`F = s\,d^2` with :math:`s`
    from published single breaks, a stated band and diameter range (HMPE: two breaks,
    an estimate, not a maker's table; its source says so). Outside every table and
    law: InputError.
Knot efficiency
    :math:`\eta = F_\mathrm{knot} / F_\mathrm{rope}` per knot, as a range over the rows
    that apply: the traditional tables (Cordage Institute, Plymouth Cordage 1946), which
    name no fibre, apply to every material except HMPE; rows measured in a material
    apply to it. HMPE knots are much weaker (about 1/3 for bowline, figure-eight loop
    and double fisherman's) and take only HMPE rows. A knot with no row for the material
    falls back on the maker's rule for any knot in it (Marlow: 50 % nylon/polyester,
    40 % HMPE). Where the source gives a post or ring diameter, the rows nearest the
    user's post diameter are used.
Friction
    Coulomb coefficients :math:`\mu` of a rope on a counterface (``rope`` = the same
    rope, or a post material), as ranges over the values sources give.

Units: diameters in m, loads in N; efficiencies and :math:`\mu` dimensionless.
Conversions: 1 in = 0.0254 m, 1 lbf = 4.4482216152605 N, 1 kgf = 9.80665 N,
1 daN = 10 N.
"""

from __future__ import annotations

import json
from fractions import Fraction
from functools import cache
from importlib import resources
from typing import NamedTuple

import numpy as np

from knotmech.errors import InputError, KnotmechError, check_positive
from knotmech.materials import material as _material

__all__ = [
    "Estimate",
    "FrictionRange",
    "NoDataError",
    "StrengthLaw",
    "StrengthTable",
    "breaking_load",
    "breaking_load_laws",
    "breaking_load_tables",
    "counterface_key",
    "counterface_names",
    "friction_counterfaces",
    "friction_range",
    "knot_breaking_load",
    "knot_efficiency",
    "knot_names",
    "published_slip_tests",
]

#: newtons per unit of load, for the units the sources print
LOAD_UNITS = {"N": 1.0, "kN": 1e3, "daN": 10.0, "lbf": 4.4482216152605, "kgf": 9.80665}
#: metres per unit of length
LENGTH_UNITS = {"mm": 1e-3, "in": 0.0254}

#: materials whose knots the traditional (fibre-unnamed) tables do not describe
_TRADITIONAL_EXCLUDED = frozenset({"hmpe"})

_COUNTERFACE_ALIASES = {
    "rope": "rope",
    "self": "rope",
    "same": "rope",
    "same-rope": "rope",
    "another-rope": "rope",
    "rope-on-rope": "rope",
    "steel": "steel",
    "stainless": "steel",
    "stainless-steel": "steel",
    "galvanised-steel": "steel",
    "galvanized-steel": "steel",
    "aluminium": "aluminium",
    "aluminum": "aluminium",
    "alu": "aluminium",
    "anodised-aluminium": "aluminium",
    "anodized-aluminum": "aluminium",
    "wood": "wood",
    "timber": "wood",
}

_KNOT_ALIASES = {
    "square": "reef",
    "square-knot": "reef",
    "reef-knot": "reef",
    "figure-8-loop": "figure-eight-loop",
    "figure-eight-on-a-bight": "figure-eight-loop",
    "figure-8-bend": "figure-eight-bend",
    "figure-8-knot": "figure-eight-knot",
    "double-fisherman": "double-fishermans",
    "double-fishermans-knot": "double-fishermans",
    "grapevine": "double-fishermans",
    "fishermans-knot": "fishermans",
    "fishermans-bend": "anchor-bend",
    "anchor-hitch": "anchor-bend",
    "round-turn-and-two-half-hitches": "round-turn-two-half-hitches",
    "butterfly": "alpine-butterfly",
    "offset-overhand-bend": "flat-overhand-bend",
    "euro-death-knot": "flat-overhand-bend",
    "larks-head": "cow-hitch",
    "girth-hitch": "cow-hitch",
    "prusik-hitch": "prusik",
    "overhand-knot": "overhand",
}


class NoDataError(KnotmechError, LookupError):
    """No citable number was found for this question (the message says which)."""


class Estimate(NamedTuple):
    """A value with its range and where it comes from.

    Attributes
    ----------
    nominal, low, high : float or ndarray
        In the unit of the function that returns it (N for loads, 1 for efficiencies).
    source : str
        The sources used, separated by semicolons.
    """

    nominal: object
    low: object
    high: object
    source: str


class FrictionRange(NamedTuple):
    """Coulomb friction coefficient range [-] and its sources."""

    low: float
    high: float
    source: str


# --------------------------------------------------------------------------- data


@cache
def _data(name: str) -> dict:
    text = resources.files("knotmech").joinpath("data", "strength", name).read_text("utf-8")
    return json.loads(text)


def _length(text: str, unit: str) -> float:
    """A diameter printed as ``'1 1/16'`` or ``'9.5'`` in ``unit``, in metres."""
    value = sum(Fraction(part) for part in str(text).split())
    return float(value) * LENGTH_UNITS[unit]


class StrengthTable(NamedTuple):
    """One breaking-strength table: ``diameters`` [m] increasing, ``loads`` [N]."""

    id: str
    material: str
    diameters: np.ndarray  # [m], increasing
    loads: np.ndarray  # [N]
    source: str


@cache
def _mbs_tables() -> tuple:
    tables = []
    for t in _data("mbs.json")["tables"]:
        d = np.array([_length(row[0], t["diameter_unit"]) for row in t["rows"]])
        f = np.array([float(row[1]) * LOAD_UNITS[t["load_unit"]] for row in t["rows"]])
        source = f"{t['source']} ({t['where']})"
        tables.append(StrengthTable(t["id"], t["material"], d, f, source))
    return tuple(tables)


class StrengthLaw(NamedTuple):
    """A breaking-strength law :math:`F = s\\,d^2` over ``[d_min, d_max]`` [m].

    ``s_nominal``, ``s_low``, ``s_high`` [N/m^2] (F in N for d in m); ``source`` starts
    with the law's kind (an estimate) and names every point with where it stands.
    """

    id: str
    material: str
    s_nominal: float  # [N/m^2]
    s_low: float  # [N/m^2]
    s_high: float  # [N/m^2]
    d_min: float  # [m]
    d_max: float  # [m]
    source: str


@cache
def _mbs_laws() -> tuple:
    laws = []
    for law in _data("mbs.json").get("laws", []):
        s = [
            float(p["load"])
            * LOAD_UNITS[p["load_unit"]]
            / _length(p["diameter"], p["diameter_unit"]) ** 2
            for p in law["points"]
        ]
        d_min, d_max = (_length(x, law["diameter_unit"]) for x in law["diameter_range"])
        points = "; ".join(f"{p['source']} ({p['where']})" for p in law["points"])
        source = f"{law['kind']}, valid {d_min * 1e3:g}-{d_max * 1e3:g} mm: {points}"
        band = law["band"]
        laws.append(
            StrengthLaw(
                law["id"],
                law["material"],
                float(np.mean(s)),
                min(s) * band["low_factor"],
                max(s) * band["high_factor"],
                d_min,
                d_max,
                source,
            )
        )
    return tuple(laws)


def breaking_load_laws(material) -> tuple:
    """The breaking-strength laws (:class:`StrengthLaw`) of a material (a preset name or
    alias), in priority order; used after its tables (:func:`breaking_load_tables`). HMPE
    has one, an estimate through two published single breaks."""
    return _of_material(_mbs_laws(), material)


def breaking_load_tables(material) -> tuple:
    """The breaking-strength tables of a material, in priority order.

    Parameters
    ----------
    material : str or Material
        A preset name or alias (see :func:`knotmech.materials.material`).

    Returns
    -------
    tuple of StrengthTable
        (id, material, diameters [m], loads [N], source), in priority order.
    """
    return _of_material(_mbs_tables(), material)


def _of_material(items, material) -> tuple:
    """The items (tables or laws) whose ``material`` is that of the preset ``material``."""
    key = _material_key(material)
    return tuple(x for x in items if x.material == key)


# ------------------------------------------------------------------ input checks


def _material_key(value) -> str:
    if not isinstance(value, str) and not hasattr(value, "key"):
        raise InputError(f"material must be a preset name, got {value!r}")
    return _material(value).key


def _name(argument: str, value) -> str:
    if not isinstance(value, str):
        raise InputError(f"{argument} must be a name (a string), got {value!r}")
    return value.strip().lower().replace("_", "-").replace(" ", "-").replace("'", "")


def _diameter(argument: str, value) -> np.ndarray:
    """A diameter [m] or an array of them, finite and > 0 (the rule of knotmech.errors)."""
    return check_positive(argument, value)


def _one_diameter(argument: str, value) -> float:
    """One diameter [m], finite and > 0; an array or a list is refused."""
    return check_positive(argument, value, scalar=True)


# ---------------------------------------------------------------- breaking load


def breaking_load(material, rod_diameter) -> Estimate:
    r"""New-rope breaking load of a rope of the given material and diameter.

    .. math:: F(d) = F_i + (F_{i+1} - F_i)\,\frac{d^2 - d_i^2}{d_{i+1}^2 - d_i^2},
              \quad d_i \le d \le d_{i+1}

    between the rows of a table, or :math:`F = s\,d^2` for a law.

    Parameters
    ----------
    material : str or Material
        Rope preset (``nylon``, ``polyester``, ``manila``, ``polypropylene``,
        ``steel-wire`` from makers' tables; ``hmpe`` from an estimate, not a table:
        :math:`F = s\,d^2` through two published single breaks, 1/8 in AmSteel rated
        2500 lbf (hwstock.org) and the 7 mm SK78 core of Marlow D2 Racing broken at
        5360 kgf (Yachting Monthly, Nov. 2017, p. 70), valid 3-8 mm; ``vps32``:
        :class:`NoDataError`).
    rod_diameter : float or array_like
        Nominal rope diameter d [m].

    Returns
    -------
    Estimate
        ``nominal`` from the material's first table (then law) covering d,
        ``low``/``high`` the least and greatest of all its tables and law bands covering
        d [N] (arrays for array input); ``source`` names the tables or laws used (a law's
        starts with its kind, ``estimate: ...``). Makers' values are new-rope minimums
        (or averages where the table says so), straight pull, no knot.

    Raises
    ------
    InputError
        Bad diameter, unknown material, or d outside every table and law of the
        material.
    NoDataError
        The material has neither a breaking-strength table nor a law.
    """
    key = _material_key(material)
    d = _diameter("rod_diameter", rod_diameter)
    tables = breaking_load_tables(key)
    laws = breaking_load_laws(key)
    if not tables and not laws:
        note = _data("mbs.json")["not_found"].get(key, "no table found")
        raise NoDataError(f"no breaking-strength table for {key}: {note}")
    flat = np.atleast_1d(d).ravel()
    bands = [(v, v, v) for v in (_interp_d2(t, flat) for t in tables)]
    bands += [_law_d2(law, flat) for law in laws]
    nominals, lows, highs = (np.stack(b) for b in zip(*bands, strict=True))
    covered = ~np.isnan(nominals)
    if not np.all(covered.any(axis=0)):
        _raise_outside(key, tables, laws, flat[~covered.any(axis=0)][0])
    first = np.argmax(covered, axis=0)
    nominal = nominals[first, np.arange(flat.size)]
    sources = [t.source for t in tables] + [law.source for law in laws]
    used = [src for src, c in zip(sources, covered.any(axis=1), strict=True) if c]
    shape = np.shape(d)
    return Estimate(
        _shaped(nominal, shape),
        _shaped(np.nanmin(lows, axis=0), shape),
        _shaped(np.nanmax(highs, axis=0), shape),
        "; ".join(used),
    )


def _raise_outside(key: str, tables: tuple, laws: tuple, bad: float):
    """The one-line InputError for a diameter ``bad`` [m] outside every table and law."""
    lo = min([t.diameters[0] for t in tables] + [law.d_min for law in laws]) * 1e3
    hi = max([t.diameters[-1] for t in tables] + [law.d_max for law in laws]) * 1e3
    what = "tables" if not laws else ("d^2 law" if not tables else "tables and laws")
    raise InputError(
        f"rod_diameter {bad * 1e3:g} mm is outside the breaking-strength {what} "
        f"for {key} ({lo:.3g}-{hi:.3g} mm)"
    )


def _law_d2(law: StrengthLaw, d: np.ndarray) -> tuple:
    """(nominal, low, high) loads [N] of ``law`` at diameters ``d`` [m]; NaN outside."""
    inside = (d >= law.d_min * (1 - 1e-12)) & (d <= law.d_max * (1 + 1e-12))
    d2 = np.where(inside, d**2, np.nan)
    return law.s_nominal * d2, law.s_low * d2, law.s_high * d2


def _interp_d2(table: StrengthTable, d: np.ndarray) -> np.ndarray:
    """Loads of ``table`` at diameters ``d`` [m], linear in d^2; NaN outside."""
    d2 = d**2
    out = np.interp(d2, table.diameters**2, table.loads)
    inside = (d >= table.diameters[0] * (1 - 1e-12)) & (d <= table.diameters[-1] * (1 + 1e-12))
    return np.where(inside, out, np.nan)


def _shaped(values: np.ndarray, shape: tuple):
    return float(values[0]) if shape == () else values.reshape(shape)


# ---------------------------------------------------------------- knot efficiency


class _Row(NamedTuple):
    knot: str
    low: float
    high: float
    materials: object  # "any" or frozenset of keys
    post_diameter: float | None  # [m]
    source: str


@cache
def _efficiency_rows() -> tuple:
    data = _data("knot_efficiency.json")
    rows = []
    for r in data["rows"]:
        pct = r["percent"]
        low, high = (pct, pct) if np.isscalar(pct) else pct
        src = data["sources"][r["source"]]
        where = src["where"] + (f"; {r['note']}" if "note" in r else "")
        mats = r["materials"] if r["materials"] == "any" else frozenset(r["materials"])
        post = r.get("post_diameter_in")
        rows.append(
            _Row(
                r["knot"],
                low / 100.0,
                high / 100.0,
                mats,
                None if post is None else _length(post, "in"),
                f"{src['source']} ({where})",
            )
        )
    return tuple(rows)


def knot_names() -> tuple[str, ...]:
    """Canonical knot names this module knows (with or without efficiency data)."""
    names = {r.knot for r in _efficiency_rows() if r.knot != "*"}
    names.update(_data("knot_efficiency.json")["no_efficiency_found"])
    return tuple(sorted(names))


def _knot_key(knot) -> str:
    key = _name("knot", knot)
    key = _KNOT_ALIASES.get(key, key)
    if key not in knot_names():
        raise InputError(f"unknown knot {knot!r}; known: {', '.join(knot_names())}")
    return key


def _applies(row: _Row, key: str | None) -> bool:
    if row.materials == "any":
        return key not in _TRADITIONAL_EXCLUDED
    return key is not None and key in row.materials


def _candidate_rows(knot: str, key: str | None) -> list:
    rows = [r for r in _efficiency_rows() if r.knot == knot and _applies(r, key)]
    if not rows and key is not None:
        rows = [r for r in _efficiency_rows() if r.knot == "*" and _applies(r, key)]
    return rows


def _nearest_post(rows: list, post_diameter: float | None) -> list:
    sized = [r for r in rows if r.post_diameter is not None]
    if post_diameter is None or not sized:
        return rows
    gap = [abs(np.log(r.post_diameter / post_diameter)) for r in sized]
    best = min(gap)
    keep = {id(r) for r, g in zip(sized, gap, strict=True) if g == best}
    return [r for r in rows if r.post_diameter is None or id(r) in keep]


def knot_efficiency(knot, material=None, post_diameter=None) -> Estimate:
    r"""Knot efficiency :math:`\eta = F_\mathrm{knot}/F_\mathrm{rope}` with its range.

    Parameters
    ----------
    knot : str
        Canonical knot name (see :func:`knot_names`; aliases such as ``square`` or
        ``figure-8-loop`` accepted).
    material : str or Material, optional
        Rope preset. None: the traditional tables only (fibre not named, new rope,
        slow pull). ``hmpe`` takes only rows measured in HMPE.
    post_diameter : float, optional
        Diameter of the post or ring the hitch is tied on [m]; where rows give one
        (two half hitches, anchor bend), the rows nearest in log(diameter) are used.

    Returns
    -------
    Estimate
        ``low``/``high``: the extreme values of the rows used; ``nominal``: the median
        of the rows' mid-points; all in (0, 1].

    Raises
    ------
    InputError
        Unknown knot or material, or a post diameter that is not a positive number.
    NoDataError
        No citable efficiency for this knot (in this material).
    """
    name = _knot_key(knot)
    key = None if material is None else _material_key(material)
    post = None if post_diameter is None else _one_diameter("post_diameter", post_diameter)
    rows = _nearest_post(_candidate_rows(name, key), post)
    if not rows:
        what = name if key is None else f"{name} in {key}"
        raise NoDataError(f"no published knot efficiency found for {what}")
    mids = [(r.low + r.high) / 2 for r in rows]
    return Estimate(
        float(np.median(mids)),
        min(r.low for r in rows),
        max(r.high for r in rows),
        "; ".join(dict.fromkeys(r.source for r in rows)),
    )


def knot_breaking_load(knot, material, rod_diameter, post_diameter=None) -> Estimate:
    r"""Breaking load of a knotted rope, :math:`\eta\,F(d)` [N].

    Parameters
    ----------
    knot : str
    material : str or Material
    rod_diameter : float or array_like
        Rope diameter [m].
    post_diameter : float, optional
        Post or ring diameter [m] (see :func:`knot_efficiency`).

    Returns
    -------
    Estimate
        nominal = eta_nominal F_nominal, low = eta_low F_low, high = eta_high F_high
        [N]; ``source`` gives both the efficiency's and the strength's sources.
    """
    eta = knot_efficiency(knot, material, post_diameter)
    mbs = breaking_load(material, rod_diameter)
    return Estimate(
        eta.nominal * mbs.nominal,
        eta.low * mbs.low,
        eta.high * mbs.high,
        f"efficiency: {eta.source} | breaking load: {mbs.source}",
    )


# ----------------------------------------------------------------------- friction


def counterface_names() -> tuple[str, ...]:
    """Canonical counterface names: ``rope`` (the same rope) and post materials."""
    return tuple(sorted(set(_COUNTERFACE_ALIASES.values())))


def counterface_key(counterface) -> str:
    """The canonical name of a counterface (``stainless`` -> ``steel``).

    Raises
    ------
    InputError
        An unknown counterface (the message lists the known names).
    """
    face = _COUNTERFACE_ALIASES.get(_name("counterface", counterface))
    if face is None:
        raise InputError(
            f"unknown counterface {counterface!r}; known: {', '.join(counterface_names())}"
        )
    return face


def friction_range(material, counterface) -> FrictionRange:
    """Coulomb friction coefficient of a rope on a counterface, as a range.

    Parameters
    ----------
    material : str or Material
        Rope preset.
    counterface : str
        ``rope`` (rope on the same rope) or a post material: ``steel``,
        ``aluminium``, ``wood`` (aliases: ``aluminum``, ``stainless``, ``timber``...).

    Returns
    -------
    FrictionRange
        (low, high, source): the least and greatest value the sources give [-].

    Raises
    ------
    InputError
        Unknown material or counterface (the message lists the known names).
    NoDataError
        No citable coefficient for this pair (give ``mu`` yourself).
    """
    key = _material_key(material)
    face = counterface_key(counterface)
    data = _data("friction.json")
    rows = [r for r in data["rows"] if r["material"] == key and r["counterface"] == face]
    if not rows:
        note = data["not_found"].get(key, "")
        raise NoDataError(
            f"no published friction coefficient found for {key} on {face}"
            + (f" ({note})" if note else "")
        )
    sources = "; ".join(f"{r['source']} ({r['where']})" for r in rows)
    return FrictionRange(min(r["mu"][0] for r in rows), max(r["mu"][1] for r in rows), sources)


def friction_counterfaces(material) -> tuple[str, ...]:
    """The counterfaces with a published friction coefficient for ``material`` (canonical
    names, sorted; empty when none is published).

    Raises
    ------
    InputError
        Unknown material (the message lists the known names).
    """
    key = _material_key(material)
    rows = _data("friction.json")["rows"]
    return tuple(sorted({r["counterface"] for r in rows if r["material"] == key}))


# ------------------------------------------------------------------- slip tests


def published_slip_tests() -> tuple[dict, ...]:
    """Published knot slip (and hold) tests with their conditions and sources.

    Each record has ``knot``, ``material``, ``rope``, ``rod_diameter`` [m or None],
    ``post``, ``loading``, ``load`` [N or None], ``load_meaning``, ``outcome``,
    ``source``, ``url`` and ``where``. Nothing is claimed about them here: they are
    for comparison with the slip model.
    """
    out = []
    for t in _data("slip_tests.json")["tests"]:
        rec = dict(t)
        d = rec.pop("rod_diameter_mm")
        rec["rod_diameter"] = None if d is None else d * 1e-3
        unit = rec.pop("load_unit")
        rec["load"] = None if rec["load"] is None else rec["load"] * LOAD_UNITS[unit]
        out.append(rec)
    return tuple(out)

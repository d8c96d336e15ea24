"""The knot registry: one record per knot, read by every consumer.

A :class:`Knot` holds a knot's canonical name (the one spelling at the edges:
``clove-hitch``), its aliases, its family (:data:`FAMILIES`), the curve it is tied from, the
scene that loads it, its closed-form geometry (:class:`Wraps`), whether a DER hold table is
shipped, what its DER answer models and the sources of its published numbers. The records
are :data:`knotmech.knots.catalogue.CATALOGUE`; adding a knot is one record there (and, for
a hitch with a new centreline, one curve file).

Readers: :func:`knotmech.hold` (names, aliases, which models answer), ``knotmech simulate``
(its scene commands), :mod:`knotmech.verdict` (which knots have a DER scene), the closed
forms (:data:`knotmech.analytic.hitch.KNOTS`), :mod:`knotmech.scenes` (the made hitch
scenes, the curve dispatch). This package imports nothing heavy (no NumPy).

Examples
--------
>>> from knotmech import knots
>>> knots.key("Lark's head")
'cow-hitch'
>>> knots.get("girth hitch").family
'hitch'
>>> knots.names(family="bend")
('reef', 'granny', 'thief', 'grief')
"""

from __future__ import annotations

from knotmech.errors import InputError
from knotmech.knots._record import FAMILIES, Knot, Wraps, resolve
from knotmech.knots.catalogue import CATALOGUE

__all__ = [
    "FAMILIES",
    "Knot",
    "Wraps",
    "REGISTRY",
    "get",
    "key",
    "names",
    "normalise",
    "resolve",
    "records",
]

#: canonical name -> record, in catalogue order
REGISTRY: dict[str, Knot] = {k.name: k for k in CATALOGUE}
_ALIASES: dict[str, str] = {a: k.name for k in CATALOGUE for a in k.aliases}


def normalise(name) -> str:
    """``name`` lower-cased, ``_`` and spaces as ``-``, apostrophes dropped (``Lark's head``
    -> ``larks-head``)."""
    s = str(name).strip().lower().replace("_", "-").replace(" ", "-")
    return s.replace("'", "").replace("\u2019", "")


def key(name) -> str:
    """The canonical name of ``name`` (an alias or a spelling of one); ``""`` when unknown."""
    s = normalise(name)
    s = _ALIASES.get(s, s)
    return s if s in REGISTRY else ""


def get(name) -> Knot:
    """The record of ``name`` (any alias or spelling); a one-line InputError when unknown."""
    k = key(name)
    if not k:
        raise InputError(f"unknown knot {str(name)!r}; known: {', '.join(REGISTRY)}")
    return REGISTRY[k]


def records(*, family: str | None = None, answered: bool | None = None) -> tuple:
    """The records, in catalogue order, of one ``family`` and/or answered by ``hold`` or not."""
    return tuple(
        k
        for k in CATALOGUE
        if (family is None or k.family == family) and (answered is None or k.answered == answered)
    )


def names(*, family: str | None = None, answered: bool | None = True) -> tuple:
    """Canonical names (see :func:`records`; by default those ``hold`` answers)."""
    return tuple(k.name for k in records(family=family, answered=answered))

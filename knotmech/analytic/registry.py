"""Registry of the closed forms of :mod:`knotmech.analytic` (in the manner of lmfit's models).

Each entry names a pure function, keyword arguments at which it is valid, which of those
arguments must be positive or non-negative (so that a NaN or a negative value must raise
:class:`~knotmech.errors.InputError`), an optional ``output`` that extracts an array from
a result object, known limits to check, and the reference. Tests sweep :data:`REGISTRY`
for finiteness on valid input, broadcasting, InputError on NaN/negative input and the
limits.

The registry imports the modules, never the other way round (no import cycle). To add a
closed form, append a call to :func:`register` in :func:`_register_builtin` (or call it
from anywhere at run time)::

    register(hitch.clove_hitch_holds, sample={"mu": 0.3, ...}, nonnegative=("mu",),
             reference="Bayman (1977)")

``register`` also works as a decorator, ``@register(sample={...})``, for modules that do
not themselves get imported by this one. Modules that are absent or lack a function are
skipped, so the table may name functions other helpers are still writing.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

import numpy as np

__all__ = ["ClosedForm", "Limit", "REGISTRY", "register", "get", "names", "evaluate"]


@dataclass(frozen=True)
class Limit:
    """A known value: ``evaluate(name, **overrides)`` must equal ``expected`` within ``rtol``."""

    description: str
    overrides: Mapping[str, Any]
    expected: float
    rtol: float = 1e-9


@dataclass(frozen=True)
class ClosedForm:
    """One registered closed form.

    Attributes
    ----------
    name : str
    func : callable, called with keyword arguments.
    sample : mapping of valid keyword arguments (SI floats).
    positive : names of arguments that must be > 0 (0, negative, NaN -> InputError).
    nonnegative : names of arguments that must be >= 0 (negative, NaN -> InputError).
    output : callable mapping the function's result to an ndarray (default: identity).
    limits : known values (:class:`Limit`).
    reference : str, citation.
    """

    name: str
    func: Callable
    sample: Mapping[str, Any]
    positive: tuple[str, ...] = ()
    nonnegative: tuple[str, ...] = ()
    output: Callable | None = None
    limits: tuple[Limit, ...] = field(default_factory=tuple)
    reference: str = ""

    def __call__(self, **overrides):
        """Evaluate at ``sample`` updated with ``overrides``; returns an ndarray."""
        result = self.func(**{**self.sample, **overrides})
        if self.output is not None:
            result = self.output(result)
        return np.asarray(result, dtype=float)


#: name -> ClosedForm
REGISTRY: dict[str, ClosedForm] = {}


def register(
    func: Callable | None = None,
    *,
    sample: Mapping[str, Any],
    name: str | None = None,
    positive: tuple[str, ...] = (),
    nonnegative: tuple[str, ...] = (),
    output: Callable | None = None,
    limits: tuple[Limit, ...] = (),
    reference: str = "",
):
    """Register ``func`` (returns it unchanged); without ``func``, a decorator."""

    def add(f: Callable) -> Callable:
        key = name or f.__name__
        REGISTRY[key] = ClosedForm(
            name=key,
            func=f,
            sample=dict(sample),
            positive=tuple(positive),
            nonnegative=tuple(nonnegative),
            output=output,
            limits=tuple(limits),
            reference=reference,
        )
        return f

    return add if func is None else add(func)


def get(name: str) -> ClosedForm:
    """The registered closed form ``name`` (KeyError names the known ones)."""
    try:
        return REGISTRY[name]
    except KeyError:
        raise KeyError(f"no closed form {name!r}; known: {', '.join(sorted(REGISTRY))}") from None


def names() -> list[str]:
    """Sorted names of the registered closed forms."""
    return sorted(REGISTRY)


def evaluate(name: str, **overrides) -> np.ndarray:
    """Evaluate the closed form ``name`` at its sample arguments updated by ``overrides``."""
    return get(name)(**overrides)


def _optional(module: str, attr: str):
    """``knotmech.analytic.<module>.<attr>`` or None when absent (module being written)."""
    try:
        mod = importlib.import_module(f"knotmech.analytic.{module}")
    except ImportError:
        return None
    return getattr(mod, attr, None)


def _register_builtin() -> None:
    from knotmech.analytic import coating, film, knots, pinch
    from knotmech.materials import VPS32_YOUNGS_MODULUS as E_VPS32  # a leaf, like errors

    water = {"viscosity": 1e-3, "speed": 5e-3, "surface_tension": 0.0343}
    # --- film (LLD) -------------------------------------------------------------------
    register(
        film.film_thickness_plate,
        sample={**water, "density": 1060.0},
        positive=("viscosity", "speed", "surface_tension", "density"),
        reference="Landau & Levich 1942; de Gennes, Brochard-Wyart & Quere 2004",
    )
    register(
        film.film_thickness_fibre,
        sample={**water, "radius": 1e-4},
        positive=("radius", "viscosity", "speed", "surface_tension"),
        limits=(
            Limit(
                "h = 1.34 r Ca^(2/3), Ca = 1e-3 (Quere 1999, 3 digits)",
                {"radius": 1.0, "viscosity": 1e-3, "speed": 1.0, "surface_tension": 1.0},
                1.34e-2,
                2e-3,
            ),
        ),
        reference="Goucher & Ward 1922; Quere 1999",
    )
    register(
        film.film_thickness_fibre_white_tallmadge,
        sample={**water, "radius": 1e-4},
        positive=("radius", "viscosity", "speed", "surface_tension"),
        reference="White & Tallmadge 1966; Quere 1999",
    )
    register(
        film.film_thickness,
        sample={**water, "density": 1060.0, "radius": 1e-5},
        positive=("viscosity", "speed", "surface_tension", "density", "radius"),
        output=lambda r: r.thickness,
        reference="regime picker over the LLD laws",
    )
    register(
        film.capillary_length,
        sample={"surface_tension": 0.072, "density": 1000.0},
        positive=("surface_tension", "density"),
        limits=(Limit("water", {}, np.sqrt(0.072 / (1000.0 * 9.80665))),),
    )
    # --- pinch ------------------------------------------------------------------------
    pinch_sample = {
        "normal_force": 1.0,
        "youngs_modulus": E_VPS32,
        "rod_diameter": 4e-3,
        "pinch_diameter": 8e-3,
    }
    register(
        pinch.pinch_load_parameter,
        sample=pinch_sample,
        positive=("youngs_modulus", "rod_diameter", "pinch_diameter"),
        nonnegative=("normal_force",),
        limits=(Limit("zero load", {"normal_force": 0.0}, 0.0),),
        reference="clove-hitch paper, sec. 9",
    )
    register(
        pinch.pinch_sliding_force,
        sample={"mu": 0.32, "normal_force": 1.0},
        nonnegative=("mu", "normal_force"),
        limits=(Limit("2 mu F_n", {}, 0.64),),
        reference="clove-hitch paper, sec. 9 (Amontons on two faces)",
    )
    register(
        pinch.effective_modulus,
        sample={"youngs_modulus": E_VPS32, "poisson_ratio": 0.5},
        positive=("youngs_modulus",),
        nonnegative=("poisson_ratio",),
        limits=(Limit("rigid partner, nu = 0.5", {}, E_VPS32 / 0.75),),
        reference="Johnson 1985, eq. (4.22)",
    )
    register(
        pinch.hertz_circular_contact,
        sample={"normal_force": 1.0, "radius": 2e-3, "contact_modulus": 1.68e6},
        positive=("radius", "contact_modulus"),
        nonnegative=("normal_force",),
        output=lambda r: r.semi_major,
        reference="Johnson 1985, eq. (4.23)",
    )
    register(
        pinch.hertz_crossed_cylinders,
        sample={
            "normal_force": 1.0,
            "radius_1": 2e-3,
            "radius_2": 4e-3,
            "youngs_modulus": E_VPS32,
            "poisson_ratio": 0.5,
        },
        positive=("radius_1", "radius_2", "youngs_modulus"),
        nonnegative=("normal_force", "poisson_ratio"),
        output=lambda r: r.semi_major,
        limits=(
            Limit(
                "equal radii: a = (3 P R/(4 E*))^(1/3)",
                {"radius_2": 2e-3},
                (3.0 * 1.0 * 2e-3 / (4.0 * E_VPS32 / 0.75)) ** (1.0 / 3.0),
            ),
        ),
        reference="Johnson 1985, sec. 4.2",
    )
    # --- knots ------------------------------------------------------------------------
    h = 1.6e-3
    bend = 1.8e6 * np.pi * h**4 / 4.0
    register(
        knots.overhand_pull_force,
        sample={
            "end_to_end_shortening": 0.3,
            "turns": 2,
            "mu": 0.3,
            "rod_radius": h,
            "bending_stiffness": bend,
        },
        positive=("end_to_end_shortening", "turns", "rod_radius", "bending_stiffness"),
        nonnegative=("mu",),
        limits=(Limit("no friction, no force", {"mu": 0.0}, 0.0),),
        reference="Jawed, Dieleman, Audoly & Reis, PRL 115, 118302 (2015)",
    )
    register(
        knots.braid_wavenumber,
        sample={"loop_radius": 0.05, "rod_radius": h},
        positive=("loop_radius", "rod_radius"),
        limits=(Limit("h k^2 R = 1/sqrt(12)", {"loop_radius": 1.0, "rod_radius": 1.0}, 12**-0.25),),
        reference="Jawed et al. 2015, Eq. (3)",
    )
    register(
        knots.braid_friction_force,
        sample={
            "wavenumber": 100.0,
            "turns": 3,
            "mu": 0.3,
            "rod_radius": h,
            "bending_stiffness": bend,
        },
        positive=("wavenumber", "turns", "rod_radius", "bending_stiffness"),
        nonnegative=("mu",),
        reference="Jawed et al. 2015, Eq. (4)",
    )
    register(
        knots.loop_closure,
        sample={"elastica_parameter": 0.5},
        nonnegative=("elastica_parameter",),
        output=lambda r: r[0],
        limits=(Limit("circle: zero braid", {"elastica_parameter": 0.0}, 0.0),),
        reference="Jawed et al. 2015, Eq. (5)",
    )
    register(
        knots.loose_knot_force,
        sample={"loop_radius": 0.05, "bending_stiffness": bend},
        positive=("loop_radius", "bending_stiffness"),
        limits=(Limit("B/(2R^2)", {"loop_radius": 1.0, "bending_stiffness": 2.0}, 1.0),),
        reference="Audoly, Clauvelin & Neukirch, PRL 99, 164301 (2007)",
    )
    register(
        knots.loose_knot_force_from_shortening,
        sample={"end_to_end_shortening": 0.3, "bending_stiffness": bend},
        positive=("end_to_end_shortening", "bending_stiffness"),
        limits=(
            Limit(
                "e = 2 pi R gives B/(2R^2)",
                {"end_to_end_shortening": 2.0 * np.pi, "bending_stiffness": 2.0},
                1.0,
            ),
        ),
        reference="Audoly, Clauvelin & Neukirch, PRL 99, 164301 (2007)",
    )
    # --- coating ----------------------------------------------------------------------
    register(
        coating.coated_rod_mu,
        sample={"volume_fraction": 0.05},
        nonnegative=("volume_fraction",),
        limits=(Limit("4 % -> 0.6", {"volume_fraction": 0.04}, 0.6),),
        reference="coated-rod paper, Fig. 12",
    )
    register(
        coating.coated_rod_volume_fraction,
        sample={"mu": 0.65},
        nonnegative=("mu",),
        limits=(Limit("0.7 -> 7 %", {"mu": 0.7}, 0.07, 1e-12),),
        reference="coated-rod paper, Fig. 12 (inverse)",
    )
    register(
        coating.coated_rod_coverage,
        sample={"volume_fraction": 0.05},
        nonnegative=("volume_fraction",),
        limits=(Limit("13 % -> 29.02 %", {"volume_fraction": 0.13}, 0.2902),),
        reference="coated-rod paper, Fig. 7",
    )
    # --- capstan (knotmech/analytic/capstan.py, another module's owner) ----------------
    capstan_ratio = _optional("capstan", "capstan_ratio")
    if capstan_ratio is not None:
        register(
            capstan_ratio,
            sample={"mu": 0.3, "wrap_angle": 2.0 * np.pi},
            nonnegative=("mu", "wrap_angle"),
            limits=(Limit("mu = 0 gives 1", {"mu": 0.0}, 1.0),),
            reference="Euler-Eytelwein",
        )
    mu_eff = _optional("capstan", "mu_eff")
    if mu_eff is not None:
        register(
            mu_eff,
            sample={"mu": 0.3, "D_over_d": 5.0},
            positive=("D_over_d",),
            nonnegative=("mu",),
            limits=(Limit("issue 2 reference, D/d = 1", {"D_over_d": 1.0}, 0.1467688363035169),),
            reference="clove-hitch paper, finite-thickness capstan",
        )
    ends = _optional("capstan", "capstan_ratio_thick_ends")
    if ends is not None:
        register(
            ends,
            sample={"mu": 0.5, "wrap_angle": np.pi, "D_over_d": 1.0},
            positive=("D_over_d",),
            nonnegative=("mu", "wrap_angle"),
            limits=(Limit("mu = 0 gives 1", {"mu": 0.0}, 1.0),),
            reference="clove-hitch paper eq. (3) with the end layers derived in this package",
        )


_register_builtin()

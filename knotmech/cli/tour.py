"""``knotmech tour``: a short tour of the toolkit printing real results.

The tour is a list of *sections*, :data:`SECTIONS`; each is a function
``section(ctx) -> list[str]`` that computes something with the public API and
returns the lines to print (figures go to ``ctx.out``). To add a section (e.g. a
DER simulation or a diagnosis), write such a function and append it to
:data:`SECTIONS`, or call :func:`register_section`. A section that raises is
reported on one line and the tour goes on; the exit status is then 1.
"""

from __future__ import annotations

import math
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from knotmech.errors import InputError

__all__ = [
    "TourContext",
    "SECTIONS",
    "kernels_cold",
    "register_section",
    "register",
    "run",
]


@dataclass
class TourContext:
    """What a tour section may use: the output folder and a record of files written."""

    out: Path
    files: list[Path] = field(default_factory=list)
    results: dict = field(default_factory=dict)


Section = Callable[[TourContext], list]

#: printed first when the kernels still have to be compiled
COMPILING_NOTICE = "compiling kernels (first run only, about 1 min; later runs take seconds) ..."


def kernels_cold() -> bool:
    """True when a kernel of the tour's DER simulations (a rod on a post: elastic, solver
    and rod-cylinder contact kernels) has no valid numba cache yet: it will compile
    (:func:`knotmech.rod.kernels_cold`)."""
    from knotmech.rod import kernels_cold as rod_kernels_cold

    return rod_kernels_cold(cylinder_contact=True)


#: reference values of mu_eff for mu = 0.3 (clove-hitch paper, as quoted in issue 2)
_PAPER_MU_EFF = {1.0: 0.147, 2.0: 0.196, 5.0: 0.247, 10.0: 0.271}


def section_mu_eff(ctx: TourContext) -> list[str]:
    """Finite-thickness capstan: mu_eff(mu=0.3, D/d) against the paper's values."""
    from knotmech.analytic.capstan import mu_eff, mu_from_mu_eff

    lines = ["Effective friction of a thick rod on a post (clove-hitch paper, eq. 3), mu = 0.3:"]
    lines.append("   D/d   mu_eff (knotmech)   paper   mu back from mu_eff")
    for Dt, ref in _PAPER_MU_EFF.items():
        me = float(mu_eff(0.3, Dt))
        back = float(mu_from_mu_eff(me, Dt))
        lines.append(f"  {Dt:4g}   {me:17.4f}   {ref:5.3f}   {back:.6f}")
        ctx.results[f"mu_eff_Dt{Dt:g}"] = me
    return lines


def section_capstan(ctx: TourContext) -> list[str]:
    """Capstan ratios: ideal, thick rod, bending rigidity, Howell friction."""
    from knotmech.analytic.capstan import (
        capstan_ratio,
        capstan_ratio_bending,
        capstan_ratio_nonlinear,
        capstan_ratio_thick,
        mu_from_capstan_test,
    )

    mu, d, D = 0.3, 4e-3, 30e-3
    R = (D + d) / 2
    E = 1.3e6  # Pa, VPS32-like elastomer (clove-hitch paper, Sec. 2)
    B = E * math.pi * d**4 / 64
    lines = [f"Capstan holding ratio T_high/T_low, mu = {mu}, rod d = 4 mm on a D = 30 mm post:"]
    lines.append(
        "  turns   ideal e^(mu theta)   thick e^(mu_eff theta)   "
        "thin + bending (E 1.3 MPa, T_low 0.1 N)"
    )
    for turns in (0.5, 1.0, 2.0):
        th = 2 * math.pi * turns
        ideal = float(capstan_ratio(mu, th))
        thick = float(capstan_ratio_thick(mu, th, D / d))
        bend = float(
            capstan_ratio_bending(
                mu, th, bending_stiffness=B, low_tension=0.1, high_tension=0.1 * ideal, radius=R
            )
        )
        lines.append(f"  {turns:5g}   {ideal:18.3f}   {thick:22.3f}   {bend:38.3f}")
        ctx.results[f"capstan_ideal_{turns:g}"] = ideal
    ratio = float(capstan_ratio(mu, 2 * math.pi))
    back = float(mu_from_capstan_test(ratio * 1.0, 1.0, 2 * math.pi))
    lines.append(
        f"  capstan test (coated-rod paper's method): ratio {ratio:.3f} over one turn "
        f"-> mu = ln(ratio)/theta = {back:.4f}"
    )
    howell = float(
        capstan_ratio_nonlinear(
            low_tension=1.0,
            wrap_angle=2 * math.pi,
            friction_coefficient=mu,
            friction_exponent=0.999999,
            radius=R,
        )
    )
    lines.append(f"  Howell friction a N^n with n -> 1 recovers the ideal ratio: {howell:.4f}")
    return lines


def section_hold(ctx: TourContext) -> list[str]:
    """Hold verdicts as ``knotmech hold`` gives them (closed forms and the DER table)."""
    from knotmech.analytic.hitch import FREE_END_STATEMENT
    from knotmech.verdict import hold

    lines = ["Does it hold? (knotmech hold ...), rod 4 mm on a 30 mm post, mu = mu_rr = 0.3:"]
    for knot, free in (("clove-hitch", 0.0), ("clove-hitch", 0.05), ("two-half-hitches", 0.05)):
        v = hold(
            knot, rod_diameter=4e-3, post_diameter=30e-3, mu=0.3, load=1.47, free_end_load=free,
            material="vps32",
        )  # fmt: skip
        m = "not computed" if not math.isfinite(v.margin) else f"{v.margin * 100:+.0f} %"
        others = ", ".join(
            f"{a.model} {'holds' if a.holds else 'slips'}"
            for a in v.answers
            if not a.decides and a.holds is not None
        )
        lines.append(
            f"  {knot:17s} load 1.47 N, free end {free:4.2f} N: "
            f"{v.state} (margin {m}, decided by {v.decided_by}; {others})"
        )
    lines.append(f"  {FREE_END_STATEMENT}")
    lines.append(
        "  d/D = 0.13 is outside the ideal rope's validity; the DER phase table decides the "
        "free-end case, as the clove-hitch paper's experiments (Fig. 4) do"
    )
    return lines


def section_coating(ctx: TourContext) -> list[str]:
    """Coated rods: friction coefficient against particle volume fraction (if available)."""
    try:
        from knotmech.analytic.coating import coated_rod_mu, coated_rod_volume_fraction
    except ImportError:
        return ["Coated rods: (knotmech.analytic.coating not available in this install)"]
    phis = np.array([0.0, 0.01, 0.04, 0.07, 0.13])
    mus = coated_rod_mu(phis)
    lines = ["Coated rods (coated-rod paper): particle volume fraction -> friction coefficient"]
    pairs = zip(phis, mus, strict=True)
    lines.append("  " + ",  ".join(f"{p * 100:g} % -> {m:.2f}" for p, m in pairs))
    lines.append(
        f"  for mu = 0.65 use {float(coated_rod_volume_fraction(0.65)) * 100:.2f} % particles"
    )
    return lines


def section_figure(ctx: TourContext) -> list[str]:
    """Figure: capstan tension decay exp(-mu s/R) against exp(-mu_eff s/R) for several D/d."""
    from knotmech.plotting import tension_decay_plot

    s = np.linspace(0.0, 4 * math.pi, 200)
    ax = tension_decay_plot(
        s,
        mu=0.3,
        D_over_d=(1.0, 2.0, 5.0, 10.0),
        title="Capstan tension decay, thin rope vs thick rod (mu = 0.3)",
    )
    ctx.out.mkdir(parents=True, exist_ok=True)
    path = ctx.out / "capstan_tension_decay.png"
    ax.figure.savefig(path, dpi=120)
    ctx.files.append(path)
    return [f"Figure: tension decay along two turns for D/d = 1, 2, 5, 10 -> {path}"]


def section_der_capstan(ctx: TourContext) -> list[str]:
    """DER: a rod pulled over a post; friction on the surface gives mu_eff, not mu."""
    from knotmech.materials import VPS32_DENSITY, VPS32_YOUNGS_MODULUS
    from knotmech.scenes.capstan import capstan

    d, D, E = 4e-3, 16e-3, VPS32_YOUNGS_MODULUS
    EA = E * math.pi * d**2 / 4
    R = 0.5 * (D + d)
    common = dict(
        wrap_angle=math.pi, mu=0.5, rod_diameter=d, post_diameter=D, youngs_modulus=E,
        density=VPS32_DENSITY, t_low=0.01 * EA, bending_stiffness=1e-4 * EA * R**2, n_elements=120,
        pull_speed=0.01, pull_distance=0.0085, ramp_time=0.1, dt=0.05,
    )  # fmt: skip
    t0 = time.perf_counter()
    surface = capstan(**common)
    centre = capstan(**common, surface_friction=False)
    wall = time.perf_counter() - t0
    lines = [
        "DER simulation (knotmech.scenes.capstan): rod d = 4 mm pulled half a turn over a "
        "D = 16 mm post, mu = 0.5:",
        f"  friction on the rod surface : T_high/T_low = {surface.ratio:.3f}   "
        f"theory exp(mu_eff theta) = {surface.exp_mu_eff_theta:.3f}  "
        f"({100 * (surface.ratio / surface.exp_mu_eff_theta - 1):+.1f} %)",
        f"  friction at the centreline  : T_high/T_low = {centre.ratio:.3f}   "
        f"theory exp(mu theta)     = {centre.exp_mu_theta:.3f}  "
        f"({100 * (centre.ratio / centre.exp_mu_theta - 1):+.1f} %)",
        f"  two implicit runs, {surface.stats.get('steps', '?')} steps each, {wall:.1f} s"
        + (" (including compiling the kernels)" if ctx.results.get("compiling") else ""),
    ]
    ctx.results["der_capstan_ratio"] = surface.ratio
    ctx.results["der_capstan_ratio_centreline"] = centre.ratio
    return lines


def section_diagnose(ctx: TourContext) -> list[str]:
    """The mismatch engine on a synthetic pinch recording with hidden adhesion."""
    from knotmech.diagnose import diagnose, make_recording, plot_report

    rec, _truth = make_recording("pinch", "adhesion", size=6.0, noise="ar1", seed=0)
    report = diagnose(rec, seed=0)
    ctx.out.mkdir(parents=True, exist_ok=True)
    path = ctx.out / "diagnose_pinch.png"
    plot_report(report, path)
    ctx.files.append(path)
    ctx.results["diagnose_verdict"] = report.verdict
    return [
        "knotmech diagnose on a synthetic pinch recording (correlated noise, an adhesion "
        "intercept of 6 noise sigma hidden in it):",
        "  " + report.verdict_line,
        f"  figure -> {path}",
    ]


#: the tour, in order
SECTIONS: list[Section] = [
    section_mu_eff,
    section_capstan,
    section_hold,
    section_coating,
    section_figure,
    section_der_capstan,
    section_diagnose,
]


def register_section(section: Section, *, before: Section | None = None) -> None:
    """Add a section to the tour (at the end, or before another one)."""
    if before is None or before not in SECTIONS:
        SECTIONS.append(section)
    else:
        SECTIONS.insert(SECTIONS.index(before), section)


def register(subparsers) -> None:
    p = subparsers.add_parser(
        "tour",
        help="a short tour: closed forms, a hold verdict and a figure",
        description="Print real results of the closed-form models and save a figure.",
    )
    p.add_argument(
        "--out",
        default="knotmech-tour",
        metavar="DIR",
        help="folder for the figures (default ./knotmech-tour)",
    )
    p.set_defaults(func=run)


def run(args) -> int:
    out = Path(args.out)
    if out.exists() and not out.is_dir():
        raise InputError(f"--out {str(out)!r} exists and is not a folder")
    import matplotlib

    matplotlib.use("Agg")
    ctx = TourContext(out=out)
    failed = 0
    t0 = time.perf_counter()
    print("knotmech tour: mechanics of capstans and knots\n")
    try:
        cold = kernels_cold()
    except Exception:  # the notice is a courtesy: never let it stop the tour
        cold = False
    ctx.results["compiling"] = cold
    if cold:
        print(COMPILING_NOTICE + "\n", flush=True)
    for section in SECTIONS:
        try:
            lines = section(ctx)
        except Exception as exc:  # a broken section must not hide the others
            failed += 1
            name = getattr(section, "__name__", "section")
            print(f"[{name} failed: {type(exc).__name__}: {exc}]", file=sys.stderr)
            continue
        print("\n".join(lines))
        print()
    print(f"done in {time.perf_counter() - t0:.1f} s; files written: {len(ctx.files)}")
    return 1 if failed else 0

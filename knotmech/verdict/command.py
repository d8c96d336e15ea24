"""The command that decides an undecided case: ``knotmech hold ... --simulate``, and what one
such run costs."""

from __future__ import annotations

from knotmech.verdict.criterion import RECHECK_HOLD_FACTOR

__all__ = ["SIMULATE_COST", "SIMULATE_MAX_CPU_S", "simulate_command"]

#: [s] the CPU budget of one ``simulate=True`` run of a hitch (each bisection run has its
#: own; a recheck, whose hold is :data:`RECHECK_HOLD_FACTOR` times longer, that many): a
#: soft rope's run is stretched in simulated time with its slower flexural clock (kappa
#: 0.003: 18x the reference rod's span), and the solver's rate guard bounds a crawl per
#: simulated second only, so one heavy kappa-0.003 point of the shipped tables took 1829 s
#: of CPU; a run that spends the budget stops undecided and says so
SIMULATE_MAX_CPU_S = 900.0

#: what one ``simulate=True`` run of a hitch costs, as the answers quote it (measured: the
#: clove hitch at the paper's size 7.3 s wall on an idle machine; the hold-table runs of the
#: hitches 3-30 s of CPU per point, up to ~2 min on large posts, d/D ~ 0.02, where the rod
#: is long)
SIMULATE_COST = (
    "typically 10-30 s of CPU, up to ~2 min on a large post (d/D ~ 0.02); a second run "
    "with a 3 s hold when the creep lies near the limit; the first stops undecided after "
    f"{SIMULATE_MAX_CPU_S:g} s of CPU (--max-cpu), the second after "
    f"{RECHECK_HOLD_FACTOR:g} x that"
)


def _q(value: float, unit: str) -> str:
    """A quantity as a command-line token with its unit (4mm, 1.47N, 1.26MPa)."""
    if unit == "m":
        return f"{value * 1e3:.6g}mm"
    if unit == "Pa":
        return f"{value / 1e6:.6g}MPa"
    return f"{value:.6g}{unit}"


def simulate_command(
    knot, *, d, D, mu, mu_rr=None, load, material=None, youngs_modulus=None, creep_limit=None,
    bending_scale=None, pin=None, free_end_load=None,
) -> str:  # fmt: skip
    """The full ``knotmech hold ... --simulate`` command that decides this case by one DER run
    (``mu`` a number, or a placeholder such as ``MU`` the user replaces)."""
    parts = ["knotmech", "hold", knot, "--rod-diameter", _q(d, "m")]
    if D is not None:
        parts += ["--post-diameter", _q(D, "m")]
    if pin is not None:  # a loop's eye round a pin
        parts += ["--pin-diameter", _q(pin, "m")]
    parts += ["--mu", mu if isinstance(mu, str) else f"{mu:g}"]  # str: a placeholder
    if mu_rr is not None and mu_rr != mu:
        parts += ["--mu-rr", f"{mu_rr:g}"]
    parts += ["--load", _q(load, "N")]
    if free_end_load:  # the cow hitch loaded on both legs
        parts += ["--free-end-load", _q(free_end_load, "N")]
    if youngs_modulus is not None:
        parts += ["--youngs-modulus", _q(youngs_modulus, "Pa")]
    elif material is not None:
        parts += ["--material", str(material)]
    else:  # a DER run needs the stiffness: the user picks it
        parts += ["--material", "MATERIAL"]
    if bending_scale is not None:
        parts += ["--bending-scale", f"{float(bending_scale):g}"]
    if creep_limit is not None:
        parts += ["--creep-limit", f"{creep_limit:g}"]
    return " ".join(parts + ["--simulate"])

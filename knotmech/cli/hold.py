"""``knotmech hold``: does a rod tied to a post hold a load?

Example::

    knotmech hold clove-hitch --rod-diameter 4mm --post-diameter 30mm --mu 0.3 \\
        --load 1.47N --free-end-load 0N
    knotmech hold capstan --wrap-angle 360deg --rod-diameter 4mm --post-diameter 30mm \\
        --mu 0.3 --load 1.47N --free-end-load 0.3N --json verdict.json

The command only parses quantities (``knotmech.units``), calls
:func:`knotmech.analytic.hitch.hold_verdict` and prints its answer. Exit status 0
whether the knot holds or slips (read the verdict or the JSON key ``holds``);
2 on bad input.
"""

from __future__ import annotations

import json
import math
import sys
from pathlib import Path

from knotmech.analytic.hitch import KNOTS, hold_verdict
from knotmech.errors import InputError
from knotmech.units import format_quantity, parse_quantity

__all__ = ["register", "run", "format_verdict"]

KNOT_NAMES = ("capstan",) + tuple(KNOTS)


def register(subparsers) -> None:
    p = subparsers.add_parser(
        "hold",
        help="does a rod tied to a post hold a load? (closed-form verdict)",
        description=(
            "Verdict (holds / slips) for a rod tied to a rigid post, with the margin, the "
            "model that decided, its assumptions and whether the inputs lie inside its "
            "validity. Quantities accept units (4mm, 1.47N, 150gf, 360deg, 2pi, 1.5turn); "
            "bare numbers are SI."
        ),
    )
    p.add_argument("knot", help=f"one of: {', '.join(KNOT_NAMES)}")
    p.add_argument("--rod-diameter", required=True, help="rod diameter d, e.g. 4mm")
    p.add_argument("--post-diameter", required=True, help="post diameter D, e.g. 30mm")
    p.add_argument("--mu", required=True, help="rod-post friction coefficient, e.g. 0.3")
    p.add_argument("--mu-rr", default=None, help="rod-rod friction coefficient (default: --mu)")
    p.add_argument("--load", required=True, help="tension on the loaded end, e.g. 1.47N")
    p.add_argument(
        "--free-end-load", default="0N", help="tension on the other end (default 0N: free end)"
    )
    p.add_argument("--wrap-angle", default=None, help="capstan only: wrap angle, e.g. 360deg")
    p.add_argument(
        "--json",
        metavar="FILE",
        default=None,
        help="also write the verdict as JSON to FILE ('-': print only the JSON)",
    )
    p.set_defaults(func=run)


def _number(text, name: str) -> float:
    value = parse_quantity(text, "dimensionless", name=name)
    return value


def run(args) -> int:
    knot = str(args.knot).strip().lower().replace("_", "-")
    if knot not in KNOT_NAMES:
        raise InputError(f"knot must be one of {', '.join(KNOT_NAMES)}, got {args.knot!r}")
    d = parse_quantity(args.rod_diameter, "length", name="--rod-diameter")
    D = parse_quantity(args.post_diameter, "length", name="--post-diameter")
    mu = _number(args.mu, "--mu")
    mu_rr = None if args.mu_rr is None else _number(args.mu_rr, "--mu-rr")
    load = parse_quantity(args.load, "force", name="--load")
    free = parse_quantity(args.free_end_load, "force", name="--free-end-load")
    theta = None
    if args.wrap_angle is not None:
        if knot != "capstan":
            raise InputError(f"--wrap-angle applies to capstan only, not to {knot}")
        theta = parse_quantity(args.wrap_angle, "angle", name="--wrap-angle")
    elif knot == "capstan":
        raise InputError("--wrap-angle is required for capstan (e.g. --wrap-angle 360deg)")
    # range checks here so that messages name the command-line option
    for name, value in (("--rod-diameter", d), ("--post-diameter", D), ("--load", load)):
        if value <= 0:
            raise InputError(f"{name} must be > 0, got {value:g}")
    for name, value in (("--mu", mu), ("--mu-rr", mu_rr), ("--free-end-load", free)):
        if value is not None and value < 0:
            raise InputError(f"{name} must be >= 0, got {value:g}")
    if theta is not None and theta <= 0:
        raise InputError(f"--wrap-angle must be > 0, got {theta:g}")
    if free > load:
        raise InputError(
            f"--free-end-load must be <= --load (the load is the larger tension), "
            f"got {free:g} N > {load:g} N"
        )
    verdict = hold_verdict(
        knot,
        rod_diameter=d,
        post_diameter=D,
        mu=mu,
        load=load,
        free_end_load=free,
        mu_rr=mu_rr,
        wrap_angle=theta,
    )
    text = json.dumps(verdict.to_dict(), indent=2) if args.json else ""
    if args.json == "-":  # JSON only on stdout, for pipes
        print(text)
        return 0
    print(format_verdict(verdict))
    if args.json:
        try:
            Path(args.json).write_text(text + "\n")
        except OSError as exc:
            raise InputError(f"--json: cannot write {args.json!r}: {exc.strerror}") from None
        print(f"wrote {args.json}", file=sys.stderr)
    return 0


def _pct(margin: float) -> str:
    if math.isinf(margin):
        return "unbounded (self-locking)" if margin > 0 else "-inf"
    return f"{margin * 100:+.1f} %"


def _force(value: float) -> str:
    return "unbounded" if math.isinf(value) else format_quantity(value, "force")


def _mu(value: float) -> str:
    return "none (no friction coefficient suffices)" if math.isinf(value) else f"{value:.4g}"


def format_verdict(verdict) -> str:
    """Human-readable multi-line report of a :class:`~knotmech.analytic.hitch.HoldVerdict`."""
    i = verdict.inputs
    head = (
        f"{verdict.knot}: rod d = {format_quantity(i['rod_diameter'], 'length')}, "
        f"post D = {format_quantity(i['post_diameter'], 'length')}, mu = {i['mu']:g}, "
        f"mu_rr = {i['mu_rr']:g}, load = {_force(i['load'])}, "
        f"free end = {_force(i['free_end_load'])}"
    )
    if "wrap_angle" in i:
        head += f", wrap = {format_quantity(i['wrap_angle'], 'angle')}"
    dec = verdict.deciding
    lines = [
        head,
        f"verdict: {'HOLDS' if verdict.holds else 'SLIPS'}  (margin {_pct(verdict.margin)}, "
        f"decided by the {dec.model} model; inputs "
        f"{'inside' if dec.inside_validity else 'OUTSIDE'} its validity)",
    ]
    for a in verdict.answers:
        tag = "decides" if a.decides else "for comparison"
        lines.append(
            f"  [{a.model}, {tag}] {'holds' if a.holds else 'slips'}; largest load held "
            f"{_force(a.capacity)}; margin {_pct(a.margin)}; critical mu {_mu(a.critical_mu)}; "
            f"inside validity: {'yes' if a.inside_validity else 'no'}"
        )
        for s in a.assumptions:
            lines.append(f"      assumes: {s}")
        for s in a.validity:
            lines.append(f"      validity: {s}")
        for s in a.notes:
            lines.append(f"      note: {s}")
        lines.append(f"      reference: {a.reference}")
    for s in verdict.notes:
        lines.append(f"note: {s}")
    return "\n".join(lines)

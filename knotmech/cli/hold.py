"""``knotmech hold``: does a rod tied to a post hold a load?

Example::

    knotmech hold clove-hitch --rod-diameter 4mm --post-diameter 30mm --mu 0.3 \\
        --load 1.47N --free-end-load 0N
    knotmech hold capstan --wrap-angle 360deg --rod-diameter 4mm --post-diameter 30mm \\
        --mu 0.3 --load 1.47N --free-end-load 0.3N --json verdict.json

    knotmech hold clove-hitch --rod-diameter 4mm --post-diameter 30mm --mu 0.3 \\
        --load 1.47N --simulate

The command parses quantities (``knotmech.units``), calls
:func:`knotmech.analytic.hitch.hold_verdict` and prints its answer. For the clove
hitch with a free end it also answers from the DER phase diagram
(:mod:`knotmech.scenes.phase_table`): interpolated from the tables shipped in the
package (one per friction coefficient mu = mu_rr; a friction between two tables is
decided when both bracketing tables agree, and the answer names the tables used;
outside their friction range the DER gives no answer and says so), or, with
``--simulate``, from one DER run of the user's geometry (progress bar on stderr), and
says where the ideal-rope theory and the simulation disagree.
The DER answer is reported next to the closed forms (JSON key ``der`` and an entry
of ``answers``). The most faithful model whose inputs lie inside its validity decides:
the closed form, unless it is outside its validity range (e.g. the ideal rope for
d/D > 0.1) and the DER gives a definite answer inside its table, in which case the DER
decides and the closed forms are shown for comparison.
Exit status 0 whether the knot holds or slips (read the verdict or the JSON key
``holds``); 2 on bad input.
"""

from __future__ import annotations

import json
import math
import sys
from pathlib import Path

from knotmech.analytic.hitch import KNOTS, ModelAnswer, hold_verdict
from knotmech.errors import InputError
from knotmech.units import format_quantity, parse_quantity

__all__ = ["register", "run", "format_verdict", "der_answer", "format_der"]

KNOT_NAMES = ("capstan",) + tuple(KNOTS)


def register(subparsers) -> None:
    p = subparsers.add_parser(
        "hold",
        help="does a rod tied to a post hold a load? (closed forms; DER for the clove hitch)",
        description=(
            "Verdict (holds / slips) for a rod tied to a rigid post, with the margin, the "
            "model that decided, its assumptions and whether the inputs lie inside its "
            "validity. For the clove hitch with a free end it also answers from the DER "
            "phase diagram (shipped table, or --simulate) and says where it disagrees with "
            "ideal-rope theory. Quantities accept units (4mm, 1.47N, 150gf, 360deg, 2pi, "
            "1.5turn); bare numbers are SI."
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
        "--youngs-modulus",
        default=None,
        help="clove-hitch DER answer: Young's modulus of the rod, e.g. 1.26MPa "
        "(default: VPS32, 1.26 MPa, the table's material); sets T_high/EA",
    )
    p.add_argument(
        "--simulate",
        action="store_true",
        help="clove hitch with a free end: run one DER simulation of this geometry "
        "(about half a minute to a few minutes) instead of interpolating the shipped table",
    )
    p.add_argument(
        "--phase-table",
        metavar="FILE",
        default=None,
        help="clove hitch: read the DER phase table from FILE instead of the shipped one",
    )
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
    E = None
    if args.youngs_modulus is not None:
        if knot != "clove-hitch":
            raise InputError(f"--youngs-modulus applies to clove-hitch only, not to {knot}")
        E = parse_quantity(args.youngs_modulus, "pressure", name="--youngs-modulus")
        if not E > 0:
            raise InputError(f"--youngs-modulus must be > 0, got {E:g}")
    if args.simulate and knot != "clove-hitch":
        raise InputError(f"--simulate is available for clove-hitch only, not for {knot}")
    if args.simulate and free > 0:
        raise InputError(
            "--simulate covers the clove hitch with a free end only (--free-end-load 0)"
        )
    verdict, der = decide(
        knot,
        rod_diameter=d,
        post_diameter=D,
        mu=mu,
        load=load,
        free_end_load=free,
        mu_rr=mu_rr,
        wrap_angle=theta,
        youngs_modulus=E,
        simulate=bool(args.simulate),
        table_path=args.phase_table,
        progress=bool(args.simulate) and args.json != "-",
    )
    data = verdict.to_dict()
    if der is not None:
        data["der"] = der
    data = _no_nan(data)
    text = json.dumps(data, indent=2) if args.json else ""
    if args.json == "-":  # JSON only on stdout, for pipes
        print(text)
        return 0
    print(format_verdict(verdict))
    if der is not None:
        print(format_der(der))
    if args.json:
        try:
            Path(args.json).write_text(text + "\n")
        except OSError as exc:
            raise InputError(f"--json: cannot write {args.json!r}: {exc.strerror}") from None
        print(f"wrote {args.json}", file=sys.stderr)
    return 0


_VPS32 = 1.26e6  # [Pa] the DER table's material (clove-hitch paper, VPS32)


def decide(
    knot,
    *,
    rod_diameter,
    post_diameter,
    mu,
    load,
    free_end_load,
    mu_rr=None,
    wrap_angle=None,
    youngs_modulus=None,
    simulate=False,
    table_path=None,
    progress=False,
):
    """The verdict of ``knotmech hold``: closed forms plus, for the clove hitch, the DER.

    The most faithful model whose inputs lie inside its validity decides: the closed
    form, unless it is outside its validity range and the DER gives a definite answer
    inside its table (or from ``simulate``), in which case the DER decides.

    Returns
    -------
    verdict : HoldVerdict
    der : dict or None
        The DER answer's details (see :func:`der_answer`), None for other knots.
    """
    d, D, free = rod_diameter, post_diameter, free_end_load
    verdict = hold_verdict(
        knot,
        rod_diameter=d,
        post_diameter=D,
        mu=mu,
        load=load,
        free_end_load=free,
        mu_rr=mu_rr,
        wrap_angle=wrap_angle,
    )
    if knot != "clove-hitch":
        return verdict, None
    der = der_answer(
        rod_diameter=d,
        post_diameter=D,
        mu=mu,
        mu_rr=mu if mu_rr is None else mu_rr,
        load=load,
        free_end_load=free,
        youngs_modulus=youngs_modulus,
        simulate=simulate,
        table_path=table_path,
        ideal_holds=next(a.holds for a in verdict.answers if a.model == "ideal-rope"),
        progress=progress,
    )
    answer = der.pop("answer")
    if answer is not None:
        takes_over = (
            answer.holds is not None
            and answer.inside_validity
            and not verdict.deciding.inside_validity
        )
        verdict = verdict.with_answer(answer, decides=takes_over)
    return verdict, der


def der_answer(
    *,
    rod_diameter,
    post_diameter,
    mu,
    mu_rr,
    load,
    free_end_load,
    youngs_modulus=None,
    simulate=False,
    table_path=None,
    ideal_holds=None,
    progress=False,
) -> dict:
    """The DER phase-diagram answer for a clove hitch (table lookup or one simulation).

    Returns a JSON-ready dict: ``source`` ("table", "simulation" or "none"), ``holds``
    (bool, or None when the table cannot decide), ``d_over_2R``, ``t_over_EA``,
    ``inside_table``, ``message``, ``mu_tables`` (friction coefficients of the tables
    that answered), ``agrees_with_ideal_rope`` (None when undecided) and
    ``answer`` (a :class:`~knotmech.analytic.hitch.ModelAnswer`, or None).
    """
    from knotmech.scenes import phase_table as pt

    E = _VPS32 if youngs_modulus is None else float(youngs_modulus)
    d, D = float(rod_diameter), float(post_diameter)
    x = d / (D + d)  # d/2R with R = (D + d)/2
    EA = E * math.pi * d * d / 4
    y = float(load) / EA
    out = {
        "source": "none",
        "holds": None,
        "d_over_2R": x,
        "t_over_EA": y,
        "youngs_modulus": E,
        "youngs_modulus_assumed": youngs_modulus is None,
        "inside_table": False,
        "critical_t_over_EA": None,
        "mu_tables": [],
        "message": "",
        "agrees_with_ideal_rope": None,
        "answer": None,
    }
    if free_end_load > 0:
        out["message"] = "the DER phase diagram covers the free end only (T_low = 0)"
        return out
    capacity = math.nan
    if simulate:
        p = pt.simulate_point(
            d_over_2R=x,
            t_over_EA=y,
            mu=mu,
            mu_rr=mu_rr,
            rod_diameter=d,
            youngs_modulus=E,
            progress=progress,
        )
        if p["holds"] is None:
            out["message"] = f"the DER simulation failed: {p['message']}"
            return out
        out.update(
            source="simulation",
            holds=bool(p["holds"]),
            message=(
                f"DER simulation at d/2R = {x:.4g}, T_high/EA = {y:.4g}: {p['verdict']} "
                f"(end creep {p['creep'] * 1e3:.3g} mm over the last 0.2 s of the hold; "
                f"{p['wall_s']:.0f} s)"
            ),
        )
        validity = "one run of the user's geometry (0.8 s of simulated time)"
    else:
        try:
            tables = (
                pt.load_tables()
                if table_path is None
                else pt.PhaseTableSet([pt.load_table(table_path)])
            )
        except InputError as exc:
            out["message"] = f"no DER table: {exc}"
            return out
        a = tables.lookup(x, y, mu=mu, mu_rr=mu_rr)
        out.update(
            source="table",
            holds=a.holds,
            inside_table=a.inside,
            message=a.message,
            critical_t_over_EA=a.critical if math.isfinite(a.critical) else None,
            mu_tables=list(a.mu_tables),
            mu_tables_available=tables.mus,
        )
        if a.inside and a.bracket[0] > 0:
            capacity = a.bracket[0] * EA  # the largest load that held (interpolated)
        if a.holds is None:
            return out
        used = [tables.table(m) for m in a.mu_tables]
        xs, ys = used[0].d_over_2R, used[0].t_over_EA
        validity = (
            f"table grid d/2R {xs[0]:.3g}-{xs[-1]:.3g}, T_high/EA {ys[0]:.3g}-{ys[-1]:.3g}, "
            f"mu = mu_rr = {' and '.join(f'{t.mu:g}' for t in used)}"
            + (" (bracketing the user's friction)" if len(used) > 1 else "")
            + "; boundary resolved to one grid step"
        )
    holds = bool(out["holds"])
    if ideal_holds is not None:
        out["agrees_with_ideal_rope"] = holds == bool(ideal_holds)
    out["answer"] = ModelAnswer(
        model=f"DER-{out['source']}",
        holds=holds,
        margin=(capacity / load - 1) if math.isfinite(capacity) else math.nan,
        capacity=capacity,
        critical_mu=math.nan,
        decides=False,
        inside_validity=True,
        assumptions=(
            "discrete elastic rod (centreline, circular cross-section, no flattening in "
            "the nips), rigid post, Coulomb-type friction at the rod surface",
            "free end: T_high hung on one end, held if the end creeps less than d over "
            "0.2 s after the load is applied",
        ),
        validity=(validity,),
        reference=(
            "clove-hitch paper (Extreme Mech. Lett., DOI 10.1016/j.eml.2022.101788), "
            "sec. 8 and Fig. 4; knotmech.scenes.phase_table"
        ),
        notes=(out["message"],),
    )
    return out


def _no_nan(obj):
    """NaN (not JSON) as null, recursively."""
    if isinstance(obj, dict):
        return {k: _no_nan(v) for k, v in obj.items()}
    if isinstance(obj, list | tuple):
        return [_no_nan(v) for v in obj]
    if isinstance(obj, float) and math.isnan(obj):
        return None
    return obj


def format_der(der: dict) -> str:
    """Lines on the DER answer and on its (dis)agreement with ideal-rope theory."""
    src = {"table": "DER phase table", "simulation": "DER simulation"}.get(der["source"])
    head = (
        f"DER (d/2R = {der['d_over_2R']:.4g}, T_high/EA = {der['t_over_EA']:.4g}"
        + (", E assumed 1.26 MPa (VPS32)" if der["youngs_modulus_assumed"] else "")
        + "): "
    )
    if der["holds"] is None:
        return head + (der["message"] or "no answer")
    lines = [head + f"{'HOLDS' if der['holds'] else 'SLIPS'} ({src}); {der['message']}"]
    if der["agrees_with_ideal_rope"] is False:
        lines.append(
            "disagreement: ideal-rope theory says "
            + ("it holds" if not der["holds"] else "it slips at any load with a free end")
            + f", the {src} says it {'holds' if der['holds'] else 'slips'}: bending "
            "stiffness and finite thickness (which the ideal rope leaves out) decide here"
        )
    elif der["agrees_with_ideal_rope"]:
        lines.append(f"agreement: ideal-rope theory and the {src} agree")
    return "\n".join(lines)


def _pct(margin: float) -> str:
    if math.isnan(margin):
        return "not computed"
    if math.isinf(margin):
        return "unbounded (self-locking)" if margin > 0 else "-inf"
    return f"{margin * 100:+.1f} %"


def _force(value: float) -> str:
    if math.isnan(value):
        return "not computed"
    return "unbounded" if math.isinf(value) else format_quantity(value, "force")


def _mu(value: float) -> str:
    if math.isnan(value):
        return "not computed"
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

"""``knotmech hold``: does a rope tied to a post hold a load?

Example::

    knotmech hold clove-hitch --rod-diameter 6mm --post-diameter 40mm --mu 0.4 \\
        --load 200N --material nylon
    knotmech hold capstan --wrap-angle 360deg --rod-diameter 4mm --post-diameter 30mm \\
        --mu 0.3 --load 1.47N --free-end-load 0.3N --json verdict.json
    knotmech hold clove-hitch --rod-diameter 4mm --post-diameter 30mm --mu 0.3 \\
        --load 1.47N --material vps32 --simulate
    knotmech hold girth-hitch --rod-diameter 4mm --post-diameter 30mm --mu 0.8 \\
        --load 0.1N --material vps32 --plot cow.png

The command parses quantities (:mod:`knotmech.units`), calls :func:`knotmech.verdict.hold`
(which holds the whole policy: which model decides, what is assumed, what is
implausible) and prints its answer: one line first (verdict, slip load, breaking load, the
load as a fraction of the capacity, deciding model), the friction line (the material's
friction range without ``--mu``, the critical mu), then warnings, assumptions and the next
step; every model's answer under
``--verbose``. Exit status 0 whether the knot holds, slips or is undecided (read the
verdict or the JSON key ``holds``: true, false or null); 2 on bad input.
"""

from __future__ import annotations

import sys
from pathlib import Path

from knotmech.errors import InputError
from knotmech.units import format_quantity, parse_quantity

__all__ = ["register", "run", "format_verdict", "format_creep"]

#: the library's parameter names -> the options that set them (for warnings)
_FLAGS = {
    "rod_diameter": "--rod-diameter",
    "post_diameter": "--post-diameter",
    "pin_diameter": "--pin-diameter",
    "mu": "--mu",
    "mu_rr": "--mu-rr",
    "load": "--load",
    "free_end_load": "--free-end-load",
    "wrap_angle": "--wrap-angle",
    "material": "--material",
    "post_material": "--post-material",
    "youngs_modulus": "--youngs-modulus",
    "bending_scale": "--bending-scale",
}


def register(subparsers) -> None:
    from knotmech.materials import material_names
    from knotmech.verdict import KNOT_NAMES
    from knotmech.verdict.command import SIMULATE_MAX_CPU_S
    from knotmech.verdict.criterion import RECHECK_HOLD_FACTOR

    p = subparsers.add_parser(
        "hold",
        help="does a rope tied to a post hold a load? (closed forms; DER tables and runs for "
        "the hitches, DER pulls for the bends)",
        description=(
            "Verdict (holds / slips / breaks / undecided) for a rope tied to a rigid post: the "
            "load it takes (slip load from the DER tables or a closed form, breaking load "
            "from published rope strengths and knot efficiencies), the critical mu and the "
            "model that decided (the most faithful one inside its validity), then "
            "warnings and the next step; --verbose for every model's answer. For the hitches "
            "with a free end (clove hitch, two half hitches, round turn and two half hitches, "
            "cow hitch loaded on one leg) it also answers from the DER hold tables (shipped, "
            "or --phase-table) or one DER run (--simulate), which need the rope's stiffness "
            "(--material or --youngs-modulus); outside a table's reach the answer is "
            "undecided and prints the --simulate command that decides it. The bends (reef, "
            "granny, thief, grief) are answered by a DER pull (--simulate). Quantities take "
            "units (4mm, 1.47N, 150gf, 360deg, 1.5turn)."
        ),
    )
    p.add_argument("knot", help=f"one of: {', '.join(KNOT_NAMES)}")
    p.add_argument("--rod-diameter", required=True, help="rope diameter d, e.g. 6mm")
    p.add_argument(
        "--post-diameter",
        default=None,
        help="post diameter D, e.g. 40mm (required except for the bends reef, granny, thief, "
        "grief)",
    )
    p.add_argument(
        "--pin-diameter",
        default=None,
        help="loops (bowline, figure-eight-loop, alpine-butterfly): diameter of the pin the "
        "eye goes round, e.g. 20mm (required for a loop)",
    )
    p.add_argument(
        "--mu",
        default=None,
        help="rope-post friction coefficient, e.g. 0.3 (bends: rope-rope). Optional with "
        "--material: the published range of the rope on --post-material is used, the verdict "
        "given at its low end and scanned over it; where none is published (e.g. nylon on "
        "steel, manila, polypropylene, steel-wire) the friction is unknown and the verdict "
        "covers mu 0.05-1.5: HOLDS only if it holds at 0.05, SLIPS only if it does not hold "
        "at 1.5, else UNDECIDED with the critical mu (its numbers at that mu) and what to "
        "give; --simulate then needs --mu. Overrides --post-material",
    )
    p.add_argument(
        "--post-material",
        default=None,
        metavar="NAME",
        help="the post's material for the friction range when --mu is not given: steel "
        "(default), aluminium, wood or rope (aliases: stainless, galvanised-steel, "
        "aluminum, timber, another-rope); the output names the range and its source",
    )
    p.add_argument(
        "--mu-rr", default=None, help="hitches: rope-rope friction coefficient (default: --mu)"
    )
    p.add_argument("--load", required=True, help="tension on the loaded end, e.g. 200N")
    p.add_argument(
        "--free-end-load",
        default="0N",
        help="tension on the other end (cow hitch: on the other leg; default 0N: free end)",
    )
    p.add_argument(
        "--loading",
        default=None,
        choices=("one-leg", "both-legs"),
        help="cow hitch only: one-leg (--load on one leg, --free-end-load on the other, 0 by "
        "default) or both-legs (the girth hitch of a sling: --load on each leg, or "
        "--free-end-load on the other when given)",
    )
    p.add_argument("--wrap-angle", default=None, help="capstan only: wrap angle, e.g. 360deg")
    p.add_argument(
        "--material",
        default=None,
        help=f"rope material preset, gives E: one of {', '.join(material_names())}",
    )
    p.add_argument(
        "--youngs-modulus",
        default=None,
        help="the rope's effective axial modulus E, e.g. 0.25GPa (overrides --material); "
        "sets T_high/EA for the DER answer",
    )
    p.add_argument(
        "--bending-scale",
        default=None,
        metavar="K",
        help="the rope's bending scale kappa in (0, 1]: bending stiffness kappa E pi d^4/64 "
        "(overrides --material's, of order 0.01 for fibre ropes; default the material's, "
        "or 1, a solid rod, without one). The shipped DER tables are at kappa 1 and, for "
        "fibre ropes, 0.003-0.03; a table answers only within a factor 3 of its kappa, and "
        "without this option a material's kappa is read over its range; --simulate runs at "
        "it",
    )
    p.add_argument(
        "--simulate",
        action="store_true",
        help="a hitch with a free end (clove hitch, two half hitches, round turn and two "
        "half hitches, cow hitch): one DER run of this geometry instead of the shipped "
        "tables (typically 10-30 s of CPU, 7.3 s wall for the clove hitch at the paper's "
        "size on an idle machine, up to ~2 min on a large post; a second, 3 s hold when "
        "the creep lies near the limit); a bend: one DER pull (1-3 min); needs E",
    )
    p.add_argument(
        "--bisect",
        type=int,
        default=0,
        metavar="N",
        help="with --simulate, a hitch with a free end: N more DER runs (1-8) bisect the slip "
        "load from the band the table and the first run leave (each costs what the first "
        "does); the runs are listed in the JSON's der.bisection",
    )
    p.add_argument(
        "--max-cpu",
        default=None,
        metavar="TIME",
        help="with --simulate, a hitch on a post: the CPU budget of each DER run, e.g. 30min "
        f"(default {SIMULATE_MAX_CPU_S:g}s; a recheck gets {RECHECK_HOLD_FACTOR:g}x); a run "
        "that spends it stops and the DER does not decide (a soft rope's run is long: its "
        "protocol is stretched to the rope's flexural clock)",
    )
    p.add_argument(
        "--creep-limit",
        default=None,
        metavar="D_PER_S",
        help="DER hold criterion: holds when the loaded end creeps slower than this many "
        "rope diameters per second at the end of the hold (clove hitch: the last second; "
        "the other hitches: the last 0.75 s), in protocol seconds: the DER runs on the "
        "rod's flexural clock and the verdict converts to the rope's seconds (default 1e-3)",
    )
    p.add_argument(
        "--phase-table",
        metavar="FILE",
        default=None,
        help="a hitch with a DER answer: read the DER phase table from FILE instead of the "
        "shipped one (it must exist and parse)",
    )
    p.add_argument(
        "--json",
        metavar="FILE",
        default=None,
        help="also write the verdict as strict JSON to FILE ('-': print only the JSON)",
    )
    p.add_argument(
        "--plot",
        metavar="FILE",
        default=None,
        help="a hitch with a free end: draw where the query sits on the DER hold table's "
        "phase diagram, or with --simulate the knot coloured by tension (png, pdf or svg)",
    )
    p.add_argument("--verbose", "-v", action="store_true", help="every model's answer in full")
    p.set_defaults(func=run)


def _json_path(text) -> Path | None:
    if text is None or text == "-":
        return None
    from knotmech.cli._paths import check_output_path

    return check_output_path(text, option="--json")


def run(args) -> int:
    """Parse the options, ask :func:`knotmech.hold`, print (and write) the verdict.

    The library checks every rule on the inputs; its one-line messages name the options
    (:func:`_flag_names`). Only what concerns the command's own outputs is checked here.
    """
    from knotmech.verdict import hold, knot_key

    knot = knot_key(args.knot)
    inputs = _legs(args.loading, knot, _quantities(args))
    json_path = _json_path(args.json)
    if args.plot is not None:
        _check_plot(args.plot, knot, inputs["free_end_load"], bool(args.simulate))
        from knotmech.cli._paths import check_distinct

        check_distinct([("--json", json_path), ("--plot", args.plot)])
    try:
        verdict = hold(
            knot, **inputs, material=args.material, post_material=args.post_material,
            simulate=bool(args.simulate), bisect=args.bisect,
            phase_table=args.phase_table, progress=bool(args.simulate) and args.json != "-",
        )  # fmt: skip
    except InputError as exc:
        raise InputError(_flag_names(str(exc))) from None
    _emit(args, verdict, json_path)
    return 0


#: option -> (keyword of knotmech.hold, kind of quantity)
_QUANTITIES = {
    "rod_diameter": ("rod_diameter", "length"),
    "post_diameter": ("post_diameter", "length"),
    "pin_diameter": ("pin_diameter", "length"),
    "mu": ("mu", "dimensionless"),
    "mu_rr": ("mu_rr", "dimensionless"),
    "load": ("load", "force"),
    "free_end_load": ("free_end_load", "force"),
    "wrap_angle": ("wrap_angle", "angle"),
    "youngs_modulus": ("youngs_modulus", "pressure"),
    "bending_scale": ("bending_scale", "dimensionless"),
    "creep_limit": ("creep_limit", "dimensionless"),
    "max_cpu": ("max_cpu_s", "time"),
}


def _legs(loading, knot: str, inputs: dict) -> dict:
    """``--loading``: both-legs puts ``--load`` on the cow hitch's other leg too (unless
    ``--free-end-load`` gives it); one-leg is the default's loading."""
    if loading is None:
        return inputs
    if knot != "cow-hitch":
        raise InputError(f"--loading {loading} applies to the cow hitch, not to {knot}")
    free = inputs["free_end_load"] or 0.0
    if loading == "one-leg":
        return inputs
    return {**inputs, "free_end_load": free if free > 0 else inputs["load"]}


def _quantities(args) -> dict:
    """The quantity options in SI units, as keywords of :func:`knotmech.hold` (None: not
    given)."""
    out = {}
    for attr, (kw, kind) in _QUANTITIES.items():
        text = getattr(args, attr)
        flag = "--" + attr.replace("_", "-")
        out[kw] = None if text is None else parse_quantity(text, kind, name=flag)
    return out


def _check_plot(path, knot: str, free: float, simulate: bool) -> None:
    """``--plot`` draws a DER answer into a png, pdf or svg file in an existing folder."""
    from knotmech.verdict import check_plot_path
    from knotmech.verdict.scope import check_plot_request

    try:
        check_plot_path(path)
        check_plot_request(knot, simulate=simulate, free_end_load=free)
    except InputError as exc:
        raise InputError(f"--{exc}") from None


def _emit(args, verdict, json_path) -> None:
    """Print the verdict (or only its JSON with ``--json -``), write --json and --plot
    (also with ``--json -``: the plot is a file, stdout stays JSON only)."""
    from knotmech.verdict import plot_verdict

    text = verdict.to_json() if args.json else ""
    if args.json == "-":  # JSON only on stdout, for pipes (a plot still goes to its file)
        print(text)
    else:
        print(format_verdict(verdict, verbose=bool(args.verbose)))
    if json_path is not None:
        try:
            json_path.write_text(text + "\n")
        except OSError as exc:
            raise InputError(f"--json: cannot write {args.json!r}: {exc.strerror}") from None
        print(f"wrote {args.json}", file=sys.stderr)
    if args.plot is not None:
        try:
            plot_verdict(verdict, args.plot, phase_table=args.phase_table)
        except InputError as exc:
            raise InputError(f"--{exc}") from None
        print(f"wrote {args.plot}", file=sys.stderr)


def _flag_names(message: str) -> str:
    """A library message with its parameter names spelled as the options that set them."""
    import re

    names = ("rod_diameter", "post_diameter", "pin_diameter", "mu_rr", "free_end_load",
             "wrap_angle", "post_material", "material", "youngs_modulus", "simulate", "phase_table",
             "creep_limit", "bending_scale", "bisect")  # fmt: skip
    message = re.sub(r"(?<![\w-])max_cpu_s(?!\w)", "--max-cpu", message)
    pattern = r"(?<![\w-])(" + "|".join(names) + r")(?!\w)"
    message = re.sub(pattern, lambda m: "--" + m.group(1).replace("_", "-"), message)
    # "load" and "mu" are words too: an option only where a message starts with them
    message = re.sub(r"\bgive mu\b", "give --mu", message)
    return re.sub(r"^(load|mu) (must|is|applies)", r"--\1 \2", message)


def _force(value: float) -> str:
    import math

    if math.isnan(value):
        return "not computed"
    if math.isinf(value):
        return "no limit from friction alone (self-locking)"
    return format_quantity(value, "force")


def _mu(value: float) -> str:
    import math

    if math.isnan(value):
        return "not computed"
    return "none (no friction coefficient suffices)" if math.isinf(value) else f"{value:.4g}"


def _wrap(theta: float) -> str:
    import math

    turns = theta / (2 * math.pi)
    return f"{math.degrees(theta):.4g} deg ({turns:.4g} {'turn' if turns == 1 else 'turns'})"


def format_creep(c: dict) -> str:
    """The measured creep in one line: speed in d/s (and mm/s), the criterion, the source."""
    if c.get("speed_d_per_s") is None:
        what = "the loaded end ran off (no creep speed: a slip)" if c.get("ran_off") else (
            "not measured")  # fmt: skip
        return f"creep: {what}; {c['source']}"
    if "limit_d_per_s" not in c:  # a smooth-law table's distance criterion
        return (f"creep: {c['creep_m'] * 1e3:.3g} mm over {c['window_s']:g} s "
                f"({c['speed_d_per_s']:.3g} d/s; {c['source']})")  # fmt: skip
    v = c["speed_d_per_s"]
    rel = "slower than" if abs(v) < c["limit_d_per_s"] else "not slower than"
    return (
        f"creep: {v:.3g} d/s ({c['speed_m_per_s'] * 1e3:.3g} mm/s) over the last "
        f"{c['window_s']:.3g} s of the hold, {rel} the {c['limit_d_per_s']:.3g} d/s of the "
        f"{c['criterion']} criterion; {c['source']}"
    )


def format_verdict(verdict, *, verbose: bool = False) -> str:
    """The verdict for people: one line first, then warnings, assumptions, next step.

    ``verbose`` adds the inputs, every model's answer (assumptions, validity,
    references), the DER details and the measured creep.
    """
    from knotmech.verdict.kappa import RANGE_REFUSAL

    lines = [verdict.summary()]
    if verdict.friction_line():
        lines.append(verdict.friction_line(verbose))
    lines += _breaking_lines(verdict.capacity)
    lines += [f"warning: {_FLAGS.get(w.name, w.name)}: {w.message}" for w in verdict.warnings]
    lines += [f"assumed: {s}" for s in verdict.assumptions]
    if verdict.creep is not None:
        lines.append(format_creep(verdict.creep))
    der = verdict.der or {}
    if not verbose and der.get("refused") in ("bending_scale", "rod", RANGE_REFUSAL):
        lines.append(f"DER: undecided, {der['message']}")
    if verdict.next_step and verdict.holds is not None:
        lines.append(verdict.next_step)
    if not verbose:
        return "\n".join(lines + _others_line(verdict))
    lines.append(_inputs_line(verdict))
    for a in verdict.answers:
        lines += _answer_lines(a)
    lines += _der_lines(verdict.der)
    lines += [f"note: {s}" for s in verdict.notes]
    return "\n".join(lines)


def _breaking_lines(cap) -> list:
    """The breaking load, its band and its source in one line (issue 23); none when no
    material or no published number gives one (the verdict line says so)."""
    from knotmech.verdict.answer import format_force as _f

    def pct(eta):
        same = f"{eta[1]:.0%}" == f"{eta[2]:.0%}"
        return f"{eta[0]:.0%}" + ("" if same else f" ({eta[1]:.0%} to {eta[2]:.0%})")

    if cap is None:
        return []
    if cap.breaking is not None:
        b = cap.breaking
        knot = "" if cap.efficiency is None else f", knot efficiency {pct(cap.efficiency)}"
        return [f"breaking load: {_f(b.value)} ({_f(b.low)} to {_f(b.high)}){knot}; "
                f"source: {b.source}"]  # fmt: skip
    if cap.rope_strength is not None:
        r = cap.rope_strength
        return [f"breaking load: below the rope's own {_f(r.value)} ({_f(r.low)} to "
                f"{_f(r.high)}; no published knot efficiency); source: {r.source}"]  # fmt: skip
    return []


def _others_line(verdict) -> list:
    """The models that did not decide, in one line (none: no line)."""
    others = ", ".join(
        f"{a.model} {'holds' if a.holds else 'slips'}"
        + ("" if a.inside_validity else " (outside its validity)")
        for a in verdict.answers
        if not a.decides
    )
    return [f"other models: {others} (--verbose for details)"] if others else []


def _inputs_line(verdict) -> str:
    """The inputs in one line (``--verbose``)."""
    i = verdict.inputs
    post = i.get("post_diameter")
    head = (
        f"{verdict.knot}: rope d = {format_quantity(i['rod_diameter'], 'length')}, "
        + ("" if post is None else f"post D = {format_quantity(post, 'length')}, ")
        + f"mu = {i['mu']:g}"
    )
    if "mu_rr" in i:
        head += f", mu_rr = {i['mu_rr']:g}"
    head += f", load = {_force(i['load'])}"
    if "free_end_load" in i:
        head += f", free end = {_force(i['free_end_load'])}"
    if "wrap_angle" in i:
        head += f", wrap = {_wrap(i['wrap_angle'])}"
    if "material" in i:
        head += f", material {i['material']}"
    if "youngs_modulus" in i:
        head += f", E = {i['youngs_modulus']:.3g} Pa"
    return head


def _answer_lines(a) -> list:
    """One model's answer in full (``--verbose``)."""
    from knotmech.verdict import format_margin

    tag = "decides" if a.decides else "for comparison"
    return (
        [
            f"  [{a.model}, {tag}] {'holds' if a.holds else 'slips'}; largest load held "
            f"{_force(a.capacity)}; margin {format_margin(a.margin)}; critical mu "
            f"{_mu(a.critical_mu)}; inside validity: {'yes' if a.inside_validity else 'no'}"
        ]
        + [f"      assumes: {s}" for s in a.assumptions]
        + [f"      validity: {s}" for s in a.validity]
        + [f"      note: {s}" for s in a.notes]
        + [f"      reference: {a.reference}"]
    )


def _der_lines(der) -> list:
    """The DER's answer and, where it differs, why from the ideal rope (``--verbose``)."""
    if der is None:
        return []
    lines = [f"DER: {der.get('message') or 'no answer'}"]
    if der.get("agrees_with_ideal_rope") is False:
        lines.append(
            "disagreement: ideal-rope theory says it slips at any load with a free end; "
            f"the DER says it {'holds' if der['holds'] else 'slips'}: bending stiffness "
            "and finite thickness (which the ideal rope leaves out) decide here"
        )
    return lines

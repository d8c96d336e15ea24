"""``knotmech simulate``: run a simulated experiment (scene) and write its curves.

Example::

    knotmech simulate capstan --wrap-angle 180deg --mu 0.5 --rod-diameter 4mm \\
        --post-diameter 16mm --youngs-modulus 1.26MPa --t-low 0.16N --json cap.json --csv cap.csv
    knotmech simulate capstan --mode hold --t-high 0.5N ...
    knotmech simulate two-loops --json two_loops.json
    knotmech simulate pinch --normal-load 0.3N --mu 0.5 --csv pinch.csv
    knotmech simulate overhand --turns 2 --mu 0.3 --n-nodes 151 --pull-time 5s --dt 5ms \\
        --csv knot.csv
    knotmech simulate clove-hitch --loading free --t-high 1.47N --mu 0.3 --json hitch.json
    knotmech simulate clove-hitch --loading pull --speed 20mm/s --t-low 0.069N --mu 0.5 \\
        --mu-kinetic 0.32 --pull-distance 40mm --csv pull.csv

The command parses quantities (``knotmech.units``; bare numbers are SI), calls the scene
function of :mod:`knotmech.scenes` with a progress bar, prints a summary, and writes the
scalars as JSON (``--json``) and the recorded curves as CSV (``--csv``).
"""

from __future__ import annotations

import csv
import json
import math
import sys
from pathlib import Path

from knotmech.errors import InputError
from knotmech.units import parse_quantity

__all__ = ["register", "run"]

SCENES = ("capstan", "two-loops", "pinch", "overhand", "clove-hitch")


def register(subparsers) -> None:
    p = subparsers.add_parser(
        "simulate",
        help="run a simulated experiment (capstan, two-loops, pinch, overhand, clove-hitch)",
        description=(
            "Simulate an experiment with the discrete-elastic-rods solver and frictional "
            "contact. Quantities accept units (4mm, 0.16N, 180deg, 1.26MPa, 10mm/s); bare "
            "numbers are SI."
        ),
    )
    p.add_argument("scene", help=f"one of: {', '.join(SCENES)}")
    g = p.add_argument_group("capstan / two-loops")
    g.add_argument("--wrap-angle", default=None, help="wrap angle theta, e.g. 180deg")
    g.add_argument("--post-diameter", default=None, help="post diameter D, e.g. 16mm")
    g.add_argument("--t-low", default=None, help="dead load on the low end, e.g. 0.16N")
    g.add_argument("--mode", default="pull", choices=("pull", "hold"))
    g.add_argument("--t-high", default=None, help="hold mode: dead load on the high end")
    g.add_argument("--bending-stiffness", default=None, help="EI in N m^2 (default solid rod)")
    g.add_argument("--pull-distance", default=None, help="e.g. 10mm")
    g.add_argument("--hold-time", default=None, help="hold mode: e.g. 2s")
    g.add_argument("--n-elements", type=int, default=None)
    g.add_argument(
        "--centreline-friction",
        action="store_true",
        help="apply the friction at the centreline (gives exp(mu theta)) instead of the surface",
    )
    g2 = p.add_argument_group("pinch")
    g2.add_argument("--normal-load", default=None, help="normal load F_n, e.g. 0.3N")
    g2.add_argument("--cylinder-diameter", default="8mm", help="pinching cylinders' D")
    g2.add_argument("--rod-length", default=None, help="rod length (pinch default 9cm)")
    g3 = p.add_argument_group("overhand")
    g3.add_argument("--turns", type=int, default=1, help="braid turns n = 1..4 (default 1)")
    g3.add_argument(
        "--params",
        default="imc",
        choices=("imc", "coated"),
        help="parameter set: implicit-contact-model paper (imc) or coated-rod paper table 1",
    )
    g3.add_argument("--n-nodes", type=int, default=None, help="nodes (overhand, clove-hitch)")
    g3.add_argument("--pull-time", default=None, help="duration of the pull, e.g. 60s")
    g4 = p.add_argument_group("clove-hitch")
    g4.add_argument(
        "--loading",
        default="free",
        choices=("symmetric", "asymmetric", "free", "pull"),
        help="end loads: both --t-high, --t-high/--t-low, or --t-high with a free end; "
        "pull: dead load --t-low (default 0.069N) on one end, the other pulled at --speed "
        "for --pull-distance (default 20mm/s, 40mm); --mu-kinetic for the post",
    )
    g4.add_argument("--mu-rr", default=None, help="rod-rod friction (default --mu)")
    c = p.add_argument_group("common")
    c.add_argument("--mu", default=None, help="(static) friction coefficient, e.g. 0.5")
    c.add_argument("--mu-kinetic", default=None, help="kinetic coefficient (default --mu)")
    c.add_argument("--rod-diameter", default=None, help="rod diameter d, e.g. 4mm")
    c.add_argument("--youngs-modulus", default=None, help="E, e.g. 1.26MPa")
    c.add_argument("--density", default="1160", help="kg/m^3 (default 1160)")
    c.add_argument("--pull-speed", "--speed", default=None, help="e.g. 10mm/s")
    c.add_argument("--dt", default=None, help="nominal time step, e.g. 20ms")
    c.add_argument("--json", metavar="FILE", default=None, help="write the scalars as JSON")
    c.add_argument("--csv", metavar="FILE", default=None, help="write the curves as CSV")
    c.add_argument("--no-progress", action="store_true", help="no progress bar")
    p.set_defaults(func=run)


def _q(value, kind, name, required=False):
    if value is None:
        if required:
            raise InputError(f"{name} is required for this scene")
        return None
    return parse_quantity(value, kind, name=name)


def _write_csv(path, header, columns):
    try:
        with open(path, "w", newline="") as fh:
            w = csv.writer(fh)
            w.writerow(header)
            for row in zip(*columns, strict=True):
                w.writerow([f"{float(x):.10g}" for x in row])
    except OSError as exc:
        raise InputError(f"--csv: cannot write {str(path)!r}: {exc.strerror}") from None


def _clean(obj):
    if isinstance(obj, dict):
        return {k: _clean(v) for k, v in obj.items()}
    if isinstance(obj, float) and not math.isfinite(obj):
        return None
    if hasattr(obj, "item"):
        return _clean(obj.item())
    return obj


def run(args) -> int:
    scene = str(args.scene).strip().lower().replace("_", "-")
    if scene not in SCENES:
        raise InputError(f"scene must be one of {', '.join(SCENES)}, got {args.scene!r}")
    progress = not args.no_progress
    common = {}
    if args.pull_speed is not None:
        common["pull_speed"] = _q(args.pull_speed, "velocity", "--pull-speed")
    if args.dt is not None:
        common["dt"] = _q(args.dt, "time", "--dt")
    mu_k = _q(args.mu_kinetic, "dimensionless", "--mu-kinetic")
    if scene in ("capstan", "two-loops"):
        from knotmech.scenes.capstan import capstan, capstan_two_loops

        kw = dict(common)
        kw["mode"] = args.mode
        kw["surface_friction"] = not args.centreline_friction
        if mu_k is not None:
            kw["mu_kinetic"] = mu_k
        opt = {
            "t_high": _q(args.t_high, "force", "--t-high"),
            "bending_stiffness": _q(args.bending_stiffness, "dimensionless", "--bending-stiffness"),
            "pull_distance": _q(args.pull_distance, "length", "--pull-distance"),
            "hold_time": _q(args.hold_time, "time", "--hold-time"),
            "n_elements": args.n_elements,
        }
        kw.update({k: v for k, v in opt.items() if v is not None})
        named = {
            "wrap_angle": _q(args.wrap_angle, "angle", "--wrap-angle", scene == "capstan"),
            "mu": _q(args.mu, "dimensionless", "--mu", scene == "capstan"),
            "rod_diameter": _q(args.rod_diameter, "length", "--rod-diameter", scene == "capstan"),
            "post_diameter": _q(
                args.post_diameter, "length", "--post-diameter", scene == "capstan"
            ),
            "youngs_modulus": _q(
                args.youngs_modulus, "pressure", "--youngs-modulus", scene == "capstan"
            ),
            "t_low": _q(args.t_low, "force", "--t-low", scene == "capstan"),
            "density": _q(args.density, "dimensionless", "--density"),
        }
        kw.update({k: v for k, v in named.items() if v is not None})
        res = (capstan if scene == "capstan" else capstan_two_loops)(progress=progress, **kw)
        summary = res.summary()
        print(
            f"{scene}: status {res.status}; T_high/T_low = {res.ratio:.4g} (sliding) | "
            f"exp(mu theta) = {res.exp_mu_theta:.4g}, exp(mu_eff theta) = "
            f"{res.exp_mu_eff_theta:.4g}"
            + (f"; creep {res.creep:.3g} m" if res.mode == "hold" else "")
        )
        if args.csv:
            _write_csv(
                args.csv,
                ["time_s", "displacement_m", "t_high_N"],
                [res.times, res.displacement, res.t_high],
            )
            prof = Path(args.csv).with_name(Path(args.csv).stem + "_profile.csv")
            _write_csv(prof, ["s_m", "tension_N"], [res.s, res.tension])
    elif scene == "overhand":
        summary = _run_overhand(args, progress)
    elif scene == "clove-hitch":
        summary = _run_clove_hitch(args, progress)
    else:
        from knotmech.scenes.pinch import pinch

        kw = dict(common)
        if mu_k is not None:
            kw["mu_kinetic"] = mu_k
        kw["normal_load"] = _q(args.normal_load, "force", "--normal-load", True)
        kw["mu"] = _q(args.mu, "dimensionless", "--mu", True)
        kw["cylinder_diameter"] = _q(args.cylinder_diameter, "length", "--cylinder-diameter")
        kw["rod_length"] = _q(args.rod_length or "9cm", "length", "--rod-length")
        kw["density"] = _q(args.density, "dimensionless", "--density")
        if args.rod_diameter is not None:
            kw["rod_diameter"] = _q(args.rod_diameter, "length", "--rod-diameter")
        if args.youngs_modulus is not None:
            kw["youngs_modulus"] = _q(args.youngs_modulus, "pressure", "--youngs-modulus")
        res = pinch(progress=progress, **kw)
        summary = res.summary()
        print(
            f"pinch: status {res.status}; F_t* = {res.sliding_force:.4g} N, "
            f"F_t*/(2 mu F_n) = {res.ratio:.4g}, x = 4F_n/(pi E d D) = {res.load_parameter:.3g}"
        )
        if args.csv:
            _write_csv(
                args.csv,
                ["time_s", "displacement_m", "pull_force_N"],
                [res.times, res.displacement, res.pull_force],
            )
    if args.json:
        text = json.dumps(_clean(summary), indent=2)
        try:
            Path(args.json).write_text(text + "\n")
        except OSError as exc:
            raise InputError(f"--json: cannot write {args.json!r}: {exc.strerror}") from None
        print(f"wrote {args.json}", file=sys.stderr)
    return 0 if summary.get("status") == "success" else 1


def _run_overhand(args, progress) -> dict:
    from knotmech.scenes.overhand import overhand

    if not 1 <= args.turns <= 4:
        raise InputError(f"--turns must be 1, 2, 3 or 4, got {args.turns}")
    mu = _q(args.mu, "dimensionless", "--mu", True)
    overrides = {
        "n_nodes": args.n_nodes,
        "pull_time": _q(args.pull_time, "time", "--pull-time"),
        "dt": _q(args.dt, "time", "--dt"),
        "pull_speed": _q(args.pull_speed, "velocity", "--pull-speed"),
    }
    overrides = {k: v for k, v in overrides.items() if v is not None}
    res = overhand(args.turns, mu, params=args.params, progress=progress, **overrides)
    print(
        f"overhand n = {args.turns}, mu = {mu:g}: status {res.status}; pull force "
        f"{res.pull_force[-1]:.4g} N at end-to-end {res.end_to_end[-1]:.4g} m; knot "
        f"{res.knot_start} -> {res.knot_end}"
        + ("" if res.knot_preserved else " (KNOT TYPE CHANGED: a strand passed through)")
    )
    if args.csv:
        _write_csv(
            args.csv,
            ["time_s", "end_to_end_m", "pull_force_N", "loop_diameter_m"],
            [res.times, res.end_to_end, res.pull_force, res.loop_diameter],
        )
    return res.to_dict()


def _run_clove_hitch(args, progress) -> dict:
    from knotmech.scenes.clove_hitch import clove_hitch

    pull = args.loading == "pull"
    kw = {
        "loading": args.loading,
        "t_high": _q(args.t_high, "force", "--t-high", not pull),
        "t_low": _q(args.t_low, "force", "--t-low", args.loading == "asymmetric"),
        "rod_diameter": _q(args.rod_diameter, "length", "--rod-diameter"),
        "post_diameter": _q(args.post_diameter, "length", "--post-diameter"),
        "rod_length": _q(args.rod_length, "length", "--rod-length"),
        "youngs_modulus": _q(args.youngs_modulus, "pressure", "--youngs-modulus"),
        "density": _q(args.density, "dimensionless", "--density"),
        "mu_rod_post": _q(args.mu, "dimensionless", "--mu"),
        "mu_rod_rod": _q(
            args.mu_rr if args.mu_rr is not None else args.mu, "dimensionless", "--mu-rr"
        ),  # fmt: skip
        "mu_kinetic": _q(args.mu_kinetic, "dimensionless", "--mu-kinetic"),
        "hold_time": _q(args.hold_time, "time", "--hold-time"),
        "n_nodes": args.n_nodes,
        "dt": _q(args.dt, "time", "--dt"),
        "pull_speed": _q(args.pull_speed, "velocity", "--speed"),
        "pull_distance": _q(args.pull_distance, "length", "--pull-distance"),
    }
    kw = {k: v for k, v in kw.items() if v is not None}
    if kw["loading"] in ("symmetric", "free"):
        kw.pop("t_low", None)
    if pull:
        kw.pop("hold_time", None)
    res = clove_hitch(progress=progress, **kw)
    if pull:
        print(
            f"clove-hitch (pull at {res.pull_speed * 1e3:.3g} mm/s): status {res.status}; "
            f"T_low = {res.t_low:.4g} N; T_high/T_low = {res.ratio_curve[-1]:.4g} after "
            f"{res.pull_displacement[-1] * 1e3:.3g} mm (T_high = {res.t_high:.4g} N)"
            if res.pull_force.size
            else f"clove-hitch (pull): status {res.status}: {res.message}"
        )
    else:
        verdict = f"; verdict: {res.verdict.upper()}" if res.verdict else ""
        print(
            f"clove-hitch ({res.loading}): status {res.status}; T_high = {res.t_high:.4g} N, "
            f"T_low = {res.t_low:.4g} N, creep {res.creep:.3g} m{verdict}"
        )
    if args.csv:
        _write_csv(
            args.csv,
            ["s_m", "tension_N", "rod_contact"],
            [res.s, res.tension, res.rod_contact.astype(int)],
        )
        prof = Path(args.csv).with_name(Path(args.csv).stem + "_darboux.csv")
        _write_csv(
            prof,
            ["s_m", "omega1_per_m", "omega2_per_m", "omega3_per_m"],
            [res.s_nodes, res.darboux[:, 0], res.darboux[:, 1], res.darboux[:, 2]],
        )
        if pull:
            curve = Path(args.csv).with_name(Path(args.csv).stem + "_pull.csv")
            _write_csv(
                curve,
                ["displacement_m", "t_high_N", "t_high_over_t_low"],
                [res.pull_displacement, res.pull_force, res.ratio_curve],
            )
    return res.to_dict()

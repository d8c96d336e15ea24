"""``knotmech simulate SCENE``: run a simulated experiment (scene) and write its curves.

Example::

    knotmech simulate capstan --wrap-angle 180deg --mu 0.5 --rod-diameter 4mm \\
        --post-diameter 16mm --youngs-modulus 1.26MPa --t-low 0.16N --json cap.json --csv cap.csv
    knotmech simulate capstan --mode hold --t-high 0.5N ...
    knotmech simulate two-loops --json two_loops.json
    knotmech simulate pinch --normal-load 0.3N --mu 0.5 --csv pinch.csv --plot pinch.png
    knotmech simulate overhand --turns 2 --mu 0.3 --n-nodes 151 --pull-time 5s --dt 5ms \\
        --csv knot.csv
    knotmech simulate clove-hitch --loading free --t-high 1.47N --mu 0.3 --json hitch.json
    knotmech simulate clove-hitch --loading pull --speed 20mm/s --t-low 0.069N --mu 0.5 \\
        --mu-kinetic 0.32 --pull-distance 40mm --csv pull.csv
    knotmech simulate two-half-hitches --loading free --t-high 0.1N --mu 0.6 --hold-time 0.4s
    knotmech simulate round-turn-two-half-hitches --loading free --t-high 0.3N --plot rt.png
    knotmech simulate cow-hitch --loading symmetric --t-high 0.3N --csv cow.csv
    knotmech simulate bend --kind granny --mu 1 --json granny.json --csv granny.csv
    knotmech simulate centreline reef.csv --unit mm --ends free,pull --ends pull,free \\
        --rod-diameter 4mm --youngs-modulus 1MPa --density 1100kg/m^3 --mu 1 \\
        --pull-distance 16mm

Each scene is its own sub-command with only its own options (``knotmech simulate capstan
--help`` lists them, marks the required ones and shows every default). Quantities need
units (``knotmech.units``: ``4mm``, ``0.16N``, ``180deg``); dimensionless inputs and
counts are bare numbers. Output files are checked before the run starts. The command
calls the scene function of :mod:`knotmech.scenes`, prints a summary and writes:

- ``--json FILE``: the run's scalars (strict JSON, counts as integers, no arrays);
- ``--csv FILE``: the curve the run produced, in FILE; further tables (the tension
  profile, the curvature) in ``FILE-stem_<what>.csv``; every file written is named;
- ``--npz FILE``: every array of the result (NumPy ``.npz``);
- ``--plot FILE``: the curve, against the closed form where one applies.
"""

from __future__ import annotations

import math
import sys
from dataclasses import dataclass
from pathlib import Path

from knotmech import knots
from knotmech.errors import InputError

__all__ = ["register", "run"]

#: the post hitches after the clove hitch (the registry's hitches with a scene made from their
#: curve, :mod:`knotmech.knots`): same options and outputs as clove-hitch
HITCH_SCENES = tuple(k.name for k in knots.records(family="hitch") if k.has_scene and not k.scene)

#: The bends of :func:`knotmech.scenes.bend` (the registry's bends with a scene).
BEND_KINDS = tuple(k.name for k in knots.records(family="bend") if k.has_scene)
#: the bends tied from :mod:`knotmech.scenes.tied`: each its own command, ``simulate NAME``
#: being ``simulate bend --kind NAME``
TIED_BENDS = tuple(
    k.name
    for k in knots.records(family="bend")
    if k.has_scene and k.curve.startswith("knotmech.scenes.tied.")
)

#: the loops of :func:`knotmech.scenes.loops.loop` (the registry's loops with a scene): the
#: eye round a fixed pin, ``--pin-diameter`` required
LOOP_SCENES = tuple(k.name for k in knots.records(family="loop") if k.has_scene)

#: hitches pulled along their pole (knotmech.scenes.axial): their own command; the clove
#: hitch's is ``simulate clove-hitch --loading axial``
AXIAL_SCENES = ("prusik",)
#: hitch commands with ``--loading axial`` (the legs set, then dragged along the pole)
AXIAL_LOADING = ("clove-hitch", "rolling-hitch")

SCENES = ("capstan", "two-loops", "pinch", "overhand", "clove-hitch", *HITCH_SCENES, "bend",
          *TIED_BENDS, *LOOP_SCENES, "centreline", *AXIAL_SCENES)  # fmt: skip

REQUIRED = "required"

_METAVAR = {
    "dimensionless": "X",
    "count": "N",
    "bending_stiffness": "EI",
    "velocity": "SPEED",
    "choice": "KIND",
}


@dataclass(frozen=True)
class Opt:
    """One quantity option of a scene: the flag, the scene argument it sets, its kind
    (a :data:`knotmech.units.KINDS` key, or ``"count"``), help text and default (shown in
    ``--help``; :data:`REQUIRED`, or text, or None when the scene computes it)."""

    flag: str
    kwarg: str
    kind: str
    help: str
    default: str | None = None
    choices: tuple[str, ...] | None = None  # kind "choice": a word, passed on as given


_COMMON_TAIL = (
    Opt("--dt", "dt", "time", "nominal time step, e.g. 5ms"),
    Opt("--max-node-steps", "max_node_steps", "dimensionless",
        "refuse a run above this many steps x nodes, estimated before it starts", "2e8"),
)  # fmt: skip

_CAPSTAN = (
    Opt("--wrap-angle", "wrap_angle", "angle", "wrap angle theta, e.g. 180deg", REQUIRED),
    Opt("--mu", "mu", "dimensionless", "static friction coefficient rod-post, e.g. 0.5",
        REQUIRED),
    Opt("--rod-diameter", "rod_diameter", "length", "rod diameter d, e.g. 4mm", REQUIRED),
    Opt("--post-diameter", "post_diameter", "length", "post diameter D, e.g. 16mm", REQUIRED),
    Opt("--youngs-modulus", "youngs_modulus", "pressure", "Young's modulus E, e.g. 1.26MPa",
        REQUIRED),
    Opt("--t-low", "t_low", "force", "dead load on the low-tension end, e.g. 0.16N", REQUIRED),
    Opt("--t-high", "t_high", "force", "--mode hold: dead load on the high end, e.g. 0.5N",
        "required with --mode hold"),
    Opt("--mu-kinetic", "mu_kinetic", "dimensionless", "kinetic coefficient", "--mu"),
    Opt("--density", "density", "density", "rod density", "1000kg/m^3"),
    Opt("--bending-stiffness", "bending_stiffness", "bending_stiffness",
        "EI, e.g. 1e-5N*m^2 (a rope bends more easily than a solid rod)",
        "solid rod, pi E d^4/64"),
    Opt("--pull-speed", "pull_speed", "velocity", "--mode pull: speed of the pulled end",
        "20mm/s"),
    Opt("--pull-distance", "pull_distance", "length", "--mode pull: how far the end is pulled",
        "3 x the stretch of the wrapped part + 0.3 R"),
    Opt("--hold-time", "hold_time", "time", "--mode hold: time under the loads", "2s"),
    Opt("--n-elements", "n_elements", "count", "rod elements",
        "about 24 per radian of wrap, plus the leads"),
    Opt("--dt", "dt", "time", "nominal time step",
        "pull: element length / (4 x pull speed); hold: 5ms"),
    _COMMON_TAIL[1],
)  # fmt: skip

_TWO_LOOPS_DEFAULTS = {  # capstan_two_loops (clove-hitch paper sect. 3, Fig. 1d)
    "--wrap-angle": "720deg (two loops, 4 pi)",
    "--mu": "0.32",
    "--rod-diameter": "4mm",
    "--post-diameter": "30mm",
    "--youngs-modulus": "1.26MPa",
    "--t-low": "0.069N",
    "--density": "1160kg/m^3",
}
_TWO_LOOPS = tuple(
    Opt(o.flag, o.kwarg, o.kind, o.help, _TWO_LOOPS_DEFAULTS.get(o.flag, o.default))
    for o in _CAPSTAN
)

_PINCH = (
    Opt("--normal-load", "normal_load", "force", "normal load F_n on the upper cylinder, "
        "e.g. 0.3N", REQUIRED),
    Opt("--mu", "mu", "dimensionless", "static friction coefficient rod-cylinder", REQUIRED),
    Opt("--mu-kinetic", "mu_kinetic", "dimensionless", "kinetic coefficient", "--mu"),
    Opt("--rod-diameter", "rod_diameter", "length", "rod diameter d", "4mm"),
    Opt("--cylinder-diameter", "cylinder_diameter", "length", "pinching cylinders' D", "8mm"),
    Opt("--youngs-modulus", "youngs_modulus", "pressure", "Young's modulus E", "1.26MPa"),
    Opt("--density", "density", "density", "rod density", "1160kg/m^3"),
    Opt("--rod-length", "rod_length", "length", "rod length", "9cm"),
    Opt("--pull-speed", "pull_speed", "velocity", "speed of the pulled end", "10mm/s"),
    Opt("--pull-distance", "pull_distance", "length", "how far the end is pulled",
        "1.5 x the stretch of the pulled part at 2 mu F_n, plus 2 d"),
    Opt("--n-elements", "n_elements", "count", "rod elements", "edges of d/8: 180 for 9 cm "
        "and 4 mm"),
    *_COMMON_TAIL,
)  # fmt: skip
_PINCH = tuple(
    Opt(o.flag, o.kwarg, o.kind, o.help, "element length / (4 x pull speed)")
    if o.flag == "--dt"
    else o
    for o in _PINCH
)

_OVERHAND = (
    Opt("--turns", "turns", "count", "braid turns n = 1..4", "1"),
    Opt("--mu", "mu", "dimensionless", "rod-rod friction coefficient", REQUIRED),
    Opt("--n-nodes", "n_nodes", "count", "rod nodes", "from --params (imc: 301)"),
    Opt("--pull-time", "pull_time", "time", "duration of the pull", "from --params (imc: 60s)"),
    Opt("--pull-speed", "pull_speed", "velocity", "speed of each end", "from --params"),
    Opt("--dt", "dt", "time", "nominal time step", "from --params (2.5ms)"),
    _COMMON_TAIL[1],
)  # fmt: skip

_CLOVE = (
    Opt("--t-high", "t_high", "force", "load on end 0 (both ends: symmetric)",
        "required unless --loading pull"),
    Opt("--t-low", "t_low", "force", "load on the other end", "asymmetric: required; free: 0; "
        "pull: 0.069N (the paper's 7 g)"),
    Opt("--mu", "mu_rod_post", "dimensionless", "rod-post (static) friction coefficient",
        "0.3"),
    Opt("--mu-rr", "mu_rod_rod", "dimensionless", "rod-rod friction coefficient", "0.3"),
    Opt("--mu-kinetic", "mu_kinetic", "dimensionless", "kinetic rod-post coefficient", "--mu"),
    Opt("--rod-diameter", "rod_diameter", "length", "rod diameter d", "4mm"),
    Opt("--post-diameter", "post_diameter", "length", "post diameter D", "30mm"),
    Opt("--rod-length", "rod_length", "length", "rod length", "374mm"),
    Opt("--youngs-modulus", "youngs_modulus", "pressure", "Young's modulus E", "1.26MPa"),
    Opt("--density", "density", "density", "rod density", "1150kg/m^3"),
    Opt("--hold-time", "hold_time", "time", "time under the loads (not with pull)", "1s"),
    Opt("--n-nodes", "n_nodes", "count", "rod nodes", "150"),
    Opt("--pull-speed", "pull_speed", "velocity", "--loading pull: speed of end 0", "20mm/s"),
    Opt("--pull-distance", "pull_distance", "length", "--loading pull: how far end 0 moves",
        "40mm"),
    Opt("--dt", "dt", "time", "nominal time step", "2ms"),
    _COMMON_TAIL[1],
)  # fmt: skip

_HITCH_DEFAULTS = {  # the knotmech.scenes.hitches scenes (scenes._hitch.run_hitch)
    "--rod-length": "the knotted part + 64 mm at each end",
    "--n-nodes": "edges of about 3.1 mm",
}
_HITCH = tuple(
    Opt(o.flag, o.kwarg, o.kind, o.help, _HITCH_DEFAULTS.get(o.flag, o.default)) for o in _CLOVE
) + (
    Opt("--creep-limit", "creep_limit", "dimensionless", "--loading free: the hitch slips when "
        "an end creeps faster than this many rod diameters per second over the last second "
        "of the hold", "1e-3"),
    Opt("--settle-time", "settle_time", "time", "settling under the pre-tension", "0.5s"),
    Opt("--load-time", "load_time", "time", "ramp to the final loads", "0.5s"),
)  # fmt: skip

#: the axial drag (knotmech.scenes.axial.axial_pull): clove-hitch --loading axial and prusik
_AXIAL_DRAG = (
    Opt("--drag-speed", "drag_speed", "velocity", "--loading axial: speed of the legs' grips "
        "along the pole", "10mm/s"),
    Opt("--drag-distance", "drag_distance", "length", "--loading axial: travel of the grips",
        "8 x d"),
)  # fmt: skip
_CLOVE_AXIAL = (
    Opt("--normal-load", "normal_load", "force", "--loading axial: dead load T on each leg "
        "before the drag", "required with --loading axial"),
    *_AXIAL_DRAG,
)  # fmt: skip
_PRUSIK = (
    Opt("--post-diameter", "post_diameter", "length", "diameter D of the pole (or rope) the "
        "Prusik grips, 1 to 10 d", REQUIRED),
    Opt("--wraps", "wraps", "count", "turns a side (2 to 6)", "3"),
    Opt("--normal-load", "normal_load", "force", "pre-tension of each leg (along the pole) "
        "before the drag", "0.5N"),
    Opt("--mu", "mu_rod_post", "dimensionless", "rod-pole friction coefficient", "0.3"),
    Opt("--mu-rr", "mu_rod_rod", "dimensionless", "rod-rod friction coefficient", "0.3"),
    Opt("--rod-diameter", "rod_diameter", "length", "cord diameter d", "4mm"),
    Opt("--youngs-modulus", "youngs_modulus", "pressure", "Young's modulus E", "1.26MPa"),
    Opt("--density", "density", "density", "cord density", "1150kg/m^3"),
    Opt("--bending-scale", "bending_scale", "dimensionless", "kappa in (0, 1] (B = kappa E "
        "pi d^4/64; a fibre cord is of order 0.01)", "1"),
    *(Opt(o.flag, o.kwarg, o.kind, o.help.removeprefix("--loading axial: "), o.default)
      for o in _AXIAL_DRAG[:1]),
    Opt("--drag-distance", "drag_distance", "length", "travel of the grips; the drag ends "
        "sooner, once the grips have moved 0.5 x d further after the knot slid (its sliding "
        "force read, the plateau recorded)", "8 x d"),
    Opt("--n-nodes", "n_nodes", "count", "nodes of the sling", "200"),
    Opt("--dt", "dt", "time", "nominal time step", "2ms"),
    _COMMON_TAIL[1],
)  # fmt: skip

_BEND = (  # knotmech.scenes.bends.bend
    Opt("--kind", "kind", "choice", f"which bend: {', '.join(BEND_KINDS)}", REQUIRED,
        choices=BEND_KINDS),
    Opt("--mu", "mu_rod_rod", "dimensionless", "rod-rod (static) friction coefficient", "0.3"),
    Opt("--mu-kinetic", "mu_kinetic", "dimensionless", "kinetic rod-rod coefficient", "--mu"),
    Opt("--rod-diameter", "rod_diameter", "length", "diameter d of both ropes", "4mm"),
    Opt("--youngs-modulus", "youngs_modulus", "pressure", "Young's modulus E (B = E pi d^4/64)",
        "1MPa"),
    Opt("--density", "density", "density", "rope density", "1100kg/m^3"),
    Opt("--pull-speed", "pull_speed", "velocity", "speed of each grip (set and pull)",
        "40mm/s"),
    Opt("--pull-distance", "pull_distance", "length", "travel of each grip", "12 x d"),
    Opt("--settle-time", "settle_time", "time", "all four ends held while contacts settle",
        "0.2s"),
    Opt("--set-tension", "set_tension", "force", "the bend is set (four ends pulled) until "
        "the tension next to the grips reaches this", "0.1 B/d^2"),
    Opt("--set-travel", "set_travel", "length", "largest travel of each end while setting",
        "10 x d"),
    Opt("--slip-draw-in", "slip_draw_in", "length", "tail draw-in near the largest force "
        "that counts as a slip", "2 x d"),
    Opt("--force-scale", "force_scale", "force", "sizes the contact penalty", "2 B/d^2"),
    Opt("--contact-width", "contact_width", "dimensionless",
        "range of the contact penalty in rod diameters", "0.2"),
    Opt("--n-nodes", "n_nodes", "count", "nodes per rope", "80; a tied bend: its record's"),
    Opt("--n-frames", "n_frames", "count", "recorded frames of the pull (>= 10)",
        "120; a tied bend: 20"),
    Opt("--dt", "dt", "time", "nominal time step (halved when Newton fails)", "4ms"),
)  # fmt: skip

_LOOP = (  # knotmech.scenes.loops.loop
    Opt("--pin-diameter", "pin_diameter", "length", "diameter D of the pin the eye goes "
        "round (0.5-40 d), e.g. 20mm", REQUIRED),
    Opt("--mu", "mu_rod_rod", "dimensionless", "rope-rope (static) friction coefficient",
        "0.3"),
    Opt("--mu-kinetic", "mu_kinetic", "dimensionless", "kinetic rope-rope coefficient", "--mu"),
    Opt("--mu-pin", "mu_pin", "dimensionless", "rope-pin friction coefficient", "--mu"),
    Opt("--rod-diameter", "rod_diameter", "length", "rope diameter d", "4mm"),
    Opt("--youngs-modulus", "youngs_modulus", "pressure", "Young's modulus E (B = E pi d^4/64)",
        "1MPa"),
    Opt("--density", "density", "density", "rope density", "1100kg/m^3"),
    Opt("--bending-scale", "bending_scale", "dimensionless",
        "bending stiffness x the solid rod's (a fibre rope ~0.01)", "1"),
    Opt("--pull-speed", "pull_speed", "velocity", "speed of the standing end (set and pull)",
        "40mm/s"),
    Opt("--pull-distance", "pull_distance", "length", "travel of the standing end", "20 x d"),
    Opt("--settle-time", "settle_time", "time", "both ends held while contacts settle (and "
        "the tail's release)", "0.2s"),
    Opt("--set-tension", "set_tension", "force", "the loop is set (standing part and tail "
        "pulled) until the tension next to each grip reaches this", "0.1 B/d^2"),
    Opt("--set-travel", "set_travel", "length", "largest travel of each end while setting",
        "20 x d"),
    Opt("--slip-draw-in", "slip_draw_in", "length", "tail draw-in or eye growth near the "
        "largest force that counts as a slip", "2 x d"),
    Opt("--force-scale", "force_scale", "force", "sizes the contact penalties", "2 B/d^2"),
    Opt("--contact-width", "contact_width", "dimensionless",
        "range of the rope-rope penalty in rod diameters", "0.2"),
    Opt("--n-nodes", "n_nodes", "count", "nodes of the rope", "its record's (175, 300)"),
    Opt("--n-frames", "n_frames", "count", "recorded frames of the pull (>= 10)", "20"),
    Opt("--dt", "dt", "time", "nominal time step (halved when Newton fails)", "4ms"),
)  # fmt: skip


def _loop_options(name: str) -> tuple[Opt, ...]:
    """The options of loop ``name``: with ``--loading`` (and ``--pin-diameter`` needed by the
    loop loading only) when its scene takes more than one loading (the alpine butterfly)."""
    loadings = knots.get(name).scene_defaults.get("loadings", ("loop",))
    if len(loadings) < 2:
        return _LOOP
    pin = Opt("--pin-diameter", "pin_diameter", "length", "diameter D of the pin the eye goes "
              "round (0.5-40 d), e.g. 20mm; end to end: the start eye's size only (no pin)",
              "required with --loading loop; end to end 5 x d")  # fmt: skip
    loading = Opt("--loading", "loading", "choice", f"{' or '.join(loadings)}: the eye round "
                  "the pin, the standing part (node 0) pulled, the other end free; or both "
                  "ends pulled apart, the eye free", loadings[0], choices=loadings)  # fmt: skip
    return (loading, pin, *(o for o in _LOOP if o.kwarg != "pin_diameter"))


_CENTRELINE = (  # knotmech.scenes.centreline.centreline
    Opt("--rod-diameter", "rod_diameter", "length", "rod diameter d, e.g. 4mm", REQUIRED),
    Opt("--youngs-modulus", "youngs_modulus", "pressure", "Young's modulus E, e.g. 1MPa",
        REQUIRED),
    Opt("--density", "density", "density", "rod density, e.g. 1100kg/m^3", REQUIRED),
    Opt("--mu", "mu_rod_rod", "dimensionless", "rod-rod friction coefficient, e.g. 0.3",
        REQUIRED),
    Opt("--post-diameter", "post_diameter", "length", "a rigid post of this diameter on the "
        "z axis through the origin", "no post"),
    Opt("--mu-post", "mu_rod_post", "dimensionless", "rod-post friction coefficient", "--mu"),
    Opt("--pull-speed", "pull_speed", "velocity", "speed of each pulled end, outwards along "
        "its end tangent", "20mm/s"),
    Opt("--pull-distance", "pull_distance", "length", "travel of each pulled end", "12 x d"),
    Opt("--settle-time", "settle_time", "time", "pulled and fixed ends held while the rods "
        "settle", "0.2s"),
    Opt("--slip-draw-in", "slip_draw_in", "length", "free-end draw-in after the force peak "
        "that counts as a slip", "4 x d"),
    Opt("--force-scale", "force_scale", "force", "sizes the contact penalties", "20 B/d^2"),
    Opt("--n-nodes", "n_nodes", "count", "nodes per rod after resampling (>= 10)", "100"),
    Opt("--n-frames", "n_frames", "count", "recorded frames of the pull", "100"),
    Opt("--dt", "dt", "time", "nominal time step", "2ms"),
)  # fmt: skip

SCENE_OPTIONS: dict[str, tuple[Opt, ...]] = {
    "capstan": _CAPSTAN,
    "two-loops": _TWO_LOOPS,
    "pinch": _PINCH,
    "overhand": _OVERHAND,
    "clove-hitch": _CLOVE + _CLOVE_AXIAL,
    **{name: _HITCH + (_CLOVE_AXIAL if name in AXIAL_LOADING else ()) for name in HITCH_SCENES},
    "prusik": _PRUSIK,
    "bend": _BEND,
    **{name: tuple(o for o in _BEND if o.kwarg != "kind") for name in TIED_BENDS},
    **{name: _loop_options(name) for name in LOOP_SCENES},
    "centreline": _CENTRELINE,
}

_DESCRIPTIONS = {
    "capstan": "a rod wrapped round a fixed post: pulled against a dead load (T_high/T_low "
    "against exp(mu_eff theta)) or held by two dead loads (creep)",
    "two-loops": "the capstan with the clove-hitch paper's two loops (sect. 3): theta = 4 pi, "
    "d = 4 mm, D = 30 mm, mu = 0.32, T_low = 0.069 N",
    "pinch": "a rod pinched between two crossed cylinders and pulled out (F_t* against "
    "Amontons' 2 mu F_n)",
    "overhand": "an overhand knot with n braid turns pulled tight (force against end-to-end)",
    **{k.name: k.simulate_help for k in knots.records(family="hitch") if k.simulate_help},
    "bend": "two ropes joined by a reef, granny, thief or grief bend, set and pulled apart "
    "until it slips (Patil et al., Science 2020): verdict and slip load",
    **{
        k.name: f"{k.summary}; set, then pulled apart ({k.loading}) until it slips: slip "
        "load, the tail drawn in, its knot type checked on every frame"
        for k in knots.records(family="bend")
        if k.name in TIED_BENDS
    },
    **{
        k.name: f"{k.summary}; its eye round a fixed pin, set, then pulled by the standing "
        "part (the tail free) until it slips: slip load, tail drawn in and eye growth, its "
        "knot type checked on every frame"
        + (
            "; --loading end-to-end: both ends pulled apart, the eye free, no pin"
            if "end-to-end" in k.scene_defaults.get("loadings", ())
            else ""
        )
        for k in knots.records(family="loop")
        if k.name in LOOP_SCENES
    },
    "centreline": "your own knot from a CSV of centreline points (one or two rods), relaxed "
    "and pulled by the ends you choose: verdict and slip load",
}


def register(subparsers) -> None:
    """Add ``simulate`` and one sub-command per scene (no scene module is imported)."""
    import argparse

    p = subparsers.add_parser(
        "simulate",
        help="run a simulated experiment (capstan, two-loops, pinch, overhand, the hitches, "
        "the bends, centreline)",
        description=(
            "Simulate an experiment with the discrete-elastic-rods solver and frictional "
            "contact. Quantities need units (4mm, 0.16N, 180deg, 1.26MPa, 10mm/s, "
            "1160kg/m^3); friction coefficients and counts are bare numbers. "
            "`knotmech simulate SCENE --help` lists a scene's options and defaults."
        ),
    )
    scenes = p.add_subparsers(dest="scene", metavar="SCENE", parser_class=type(p))
    for name in SCENES:
        sp = scenes.add_parser(
            name,
            aliases=[name.replace("-", "_")] if "-" in name else [],
            help=_DESCRIPTIONS[name],
            description=f"Simulate {_DESCRIPTIONS[name]}.",
            formatter_class=argparse.RawDescriptionHelpFormatter,
        )
        req = sp.add_argument_group("required")
        opt = sp.add_argument_group("options (default in brackets)")
        if name == "centreline":
            req.add_argument(
                "file",
                metavar="FILE",
                help="CSV of centreline points: lines "
                "'x, y, z' (one rod) or 'rod, x, y, z' (rod 0 or 1), a header "
                "line allowed, at least 10 points per rod, lengths in --unit",
            )
            req.add_argument(
                "--ends",
                action="append",
                required=True,
                metavar="FIRST,LAST",
                help="once per rod, in file order: what the rod's first and "
                "last points are, each pull (gripped and pulled outwards), "
                "fixed (clamped) or free; e.g. --ends free,pull --ends pull,free "
                "(at least one end pulled)",
            )
            opt.add_argument(
                "--unit",
                default="m",
                choices=("m", "cm", "mm"),
                help="unit of the coordinates in FILE [m]",
            )
        for o in SCENE_OPTIONS[name]:
            if o.default == REQUIRED:
                req.add_argument(o.flag, dest=o.kwarg, required=True, help=o.help,
                                 choices=o.choices,
                                 metavar=_METAVAR.get(o.kind, o.kind.upper()))  # fmt: skip
            else:
                flags = (o.flag, "--speed") if o.flag == "--pull-speed" else (o.flag,)
                text = f"{o.help} [{o.default}]" if o.default else o.help
                opt.add_argument(*flags, dest=o.kwarg, default=None, help=text,
                                 metavar=_METAVAR.get(o.kind, o.kind.upper()))  # fmt: skip
        if name in ("capstan", "two-loops"):
            opt.add_argument(
                "--mode",
                default="pull",
                choices=("pull", "hold"),
                help="pull the high end, or hold it with --t-high [pull]",
            )
            opt.add_argument("--centreline-friction", action="store_true",
                             help="apply the friction at the centreline (gives exp(mu theta)) "
                             "instead of the surface (exp(mu_eff theta))")  # fmt: skip
        if name == "overhand":
            opt.add_argument("--params", default="imc", choices=("imc", "coated"),
                             help="parameter set: implicit-contact-model paper (imc) or "
                             "coated-rod paper table 1 [imc]")  # fmt: skip
        if name == "clove-hitch" or name in HITCH_SCENES:
            axial = ("axial",) if name in AXIAL_LOADING else ()
            opt.add_argument(
                "--loading", default="free",
                choices=("symmetric", "asymmetric", "free", "pull", *axial),
                help="end loads: both --t-high (symmetric); --t-high and --t-low "
                "(asymmetric); --t-high and a free end (free); pull: dead load --t-low on one "
                "end, the other pulled at --speed for --pull-distance"
                + (_AXIAL_HELP[name] if axial else "") + " [free]",
            )  # fmt: skip
        out = sp.add_argument_group("output (checked before the run starts)")
        out.add_argument("--json", metavar="FILE", help="the run's scalars as strict JSON")
        out.add_argument(
            "--csv",
            metavar="FILE",
            help="the curve as CSV in FILE; further "
            "tables in FILE-stem_<what>.csv (the files written are listed)",
        )
        out.add_argument("--npz", metavar="FILE", help="every array of the result (.npz)")
        out.add_argument(
            "--plot",
            metavar="FILE",
            help="the curve (png, pdf, svg, ...), against the closed form where one applies",
        )
        out.add_argument("--no-progress", action="store_true", help="no progress bar")
        sp.set_defaults(func=run, scene=name)  # fmt: skip
    p.set_defaults(func=_no_scene)


def _no_scene(args) -> int:
    raise InputError(f"choose a scene: {', '.join(SCENES)} (knotmech simulate SCENE --help)")


# ----------------------------------------------------------------------------- parsing


def _parse(args, scene: str) -> dict:
    """Scene keyword arguments in SI from the options given (defaults are the scene's)."""
    from knotmech.units import parse_count, parse_quantity

    kw = {}
    for o in SCENE_OPTIONS[scene]:
        raw = getattr(args, o.kwarg, None)
        if raw is None:
            continue
        if o.kind == "choice":
            kw[o.kwarg] = raw
        elif o.kind == "count":
            kw[o.kwarg] = parse_count(raw, name=o.flag)
        else:
            kw[o.kwarg] = parse_quantity(raw, o.kind, name=o.flag)
    return kw


def _refuse(kw: dict, flags: dict[str, str], reason: str) -> None:
    given = [flag for kwarg, flag in flags.items() if kwarg in kw]
    if given:
        raise InputError(f"{', '.join(given)}: not used {reason}")


#: ``--loading axial`` in the hitches' help
_AXIAL_HELP = {
    "clove-hitch": "; axial: both legs at --normal-load, then dragged along the post (Sabater "
    "et al. 2026)",
    "rolling-hitch": "; axial: the standing part (along the pole) and the working end set at "
    "--normal-load, then the standing part's end dragged along the pole, the working end "
    "keeping its load (settle 0.4 s, ramp 0.3 s unless given)",
}

#: the options of the axial drag only (clove-hitch --loading axial)
_AXIAL_ONLY = {"normal_load": "--normal-load", "drag_speed": "--drag-speed",
               "drag_distance": "--drag-distance"}  # fmt: skip


def _axial_missing(kw: dict) -> list[str]:
    """clove-hitch or rolling-hitch --loading axial: the options it refuses, and the
    missing ones."""
    _refuse(kw, {"t_high": "--t-high", "t_low": "--t-low", "hold_time": "--hold-time",
                 "pull_speed": "--pull-speed", "pull_distance": "--pull-distance",
                 "rod_length": "--rod-length", "mu_kinetic": "--mu-kinetic",
                 "creep_limit": "--creep-limit"},
            "with --loading axial (see --drag-speed, --drag-distance)")  # fmt: skip
    return [] if "normal_load" in kw else ["--normal-load"]


def _check_combination(scene: str, args, kw: dict) -> None:
    """Options that depend on another option: all missing ones at once; unused ones refused."""
    missing = []
    if scene in ("capstan", "two-loops"):
        if args.mode == "hold":
            if "t_high" not in kw:
                missing.append("--t-high")
            _refuse(kw, {"pull_speed": "--pull-speed", "pull_distance": "--pull-distance"},
                    "with --mode hold")  # fmt: skip
        else:
            _refuse(kw, {"t_high": "--t-high", "hold_time": "--hold-time"},
                    "with --mode pull (the pulled end's force is measured)")  # fmt: skip
    elif scene in AXIAL_LOADING and args.loading == "axial":
        missing += _axial_missing(kw)
    elif scene == "clove-hitch" or scene in HITCH_SCENES:
        if scene in AXIAL_LOADING:
            _refuse(kw, _AXIAL_ONLY, "without --loading axial")
        if scene in HITCH_SCENES and args.loading != "free":
            _refuse(kw, {"creep_limit": "--creep-limit"}, "without --loading free")
        if args.loading == "pull":
            _refuse(kw, {"t_high": "--t-high", "hold_time": "--hold-time"},
                    "with --loading pull (the pulled end's force is measured)")  # fmt: skip
        else:
            if "t_high" not in kw:
                missing.append("--t-high")
            if args.loading == "asymmetric" and "t_low" not in kw:
                missing.append("--t-low")
            _refuse(kw, {"pull_speed": "--pull-speed", "pull_distance": "--pull-distance"},
                    f"with --loading {args.loading} (only with pull)")  # fmt: skip
            if args.loading == "symmetric":
                _refuse(kw, {"t_low": "--t-low"}, "with --loading symmetric (both ends carry "
                        "--t-high)")  # fmt: skip
    if missing:
        cond = {"capstan": "--mode hold", "two-loops": "--mode hold"}.get(
            scene, f"--loading {getattr(args, 'loading', '')}"
        )
        raise InputError(
            f"{', '.join(missing)} {'is' if len(missing) == 1 else 'are'} required with {cond}"
        )


# ----------------------------------------------------------------------------- outputs


def _csv_tables(scene: str, args) -> list[tuple[str, str]]:
    """(suffix, description) of every CSV file ``--csv`` writes, the main one first."""
    if scene in ("capstan", "two-loops"):
        return [("", "T_high against time and displacement"),
                ("_tension_profile", "tension along the rod at the end")]  # fmt: skip
    if scene in AXIAL_SCENES or getattr(args, "loading", None) == "axial":
        return [("", "axial force and knot travel against the grips' travel")]
    if scene == "pinch":
        return [("", "pull force against time and displacement")]
    if scene == "overhand":
        return [("", "pull force, end-to-end distance and loop size against time")]
    if scene == "bend":
        return [("", "pull force and the tails' draw-in against the grips' displacement")]
    if scene in LOOP_SCENES:
        return [("", "pull force, tail draw-in and eye growth against the standing end's "
                 "displacement")]  # fmt: skip
    if scene == "centreline":
        return [("", "pull force and the free ends' draw-in against the pulled ends' "
                 "displacement")]  # fmt: skip
    tables = [("_tension_profile", "tension along the rod at the end"),
              ("_curvature", "Darboux vector (curvatures, twist) along the rod")]  # fmt: skip
    if args.loading == "pull":
        return [("", "T_high against the pulled end's displacement"), *tables]
    return [("", tables[0][1]), tables[1]]


def _csv_path(base: Path, suffix: str) -> Path:
    return base if not suffix else base.with_name(base.stem + suffix + (base.suffix or ".csv"))


def _check_outputs(scene: str, args) -> dict:
    from knotmech.cli._paths import check_distinct, check_output_path, plot_formats

    paths = {
        "json": check_output_path(args.json, option="--json"),
        "npz": check_output_path(args.npz, formats=("npz",), option="--npz"),
        "plot": None,
        "csv": [],
    }
    if args.plot is not None:
        paths["plot"] = check_output_path(args.plot, formats=plot_formats(), option="--plot")
    if args.csv is not None:
        base = check_output_path(args.csv, option="--csv")
        for suffix, what in _csv_tables(scene, args):
            paths["csv"].append((check_output_path(_csv_path(base, suffix), option="--csv"), what))
    check_distinct(
        [("--json", paths["json"]), ("--npz", paths["npz"]), ("--plot", paths["plot"])]
        + [("--csv", p) for p, _ in paths["csv"]]
    )
    return paths


def _write_csv(path: Path, header, columns) -> int:
    import csv

    from knotmech.cli._paths import writing

    rows = 0
    with writing(path, option="--csv"), open(path, "w", newline="") as fh:
        w = csv.writer(fh)
        w.writerow(header)
        for row in zip(*columns, strict=True):
            w.writerow([f"{float(x):.10g}" for x in row])
            rows += 1
    return rows


def _csv_columns(scene: str, res, loading: str | None) -> list[tuple[list[str], list]]:
    """Header and columns of each table, in the order of :func:`_csv_tables`."""
    import numpy as np

    if scene in ("capstan", "two-loops"):
        return [
            (["time_s", "displacement_m", "t_high_N", "t_high_over_t_low"],
             [res.times, res.displacement, res.t_high, np.asarray(res.t_high) / res.t_low]),
            (["s_m", "tension_N"], [res.s, res.tension]),
        ]  # fmt: skip
    if scene in AXIAL_SCENES or loading == "axial":
        return [
            (
                ["time_s", "grip_displacement_m", "axial_force_N", "knot_displacement_m"],
                [res.times, res.grip_displacement, res.axial_force, res.knot_displacement],
            )
        ]
    if scene == "pinch":
        return [(["time_s", "displacement_m", "pull_force_N"],
                 [res.times, res.displacement, res.pull_force])]  # fmt: skip
    if scene == "overhand":
        return [(["time_s", "end_to_end_m", "pull_force_N", "loop_diameter_m"],
                 [res.times, res.end_to_end, res.pull_force, res.loop_diameter])]  # fmt: skip
    if scene in LOOP_SCENES:
        return [(["time_s", "pull_displacement_m", "pull_force_N", "tail_draw_in_m",
                  "eye_growth_m"], [res.times, res.pull_displacement, res.pull_force,
                                    res.tail_draw_in, res.eye_growth])]  # fmt: skip
    if scene in ("bend", "centreline"):
        draw = np.asarray(res.draw_in)  # (n_frames, k) for bends and centrelines, 0 frames included
        names = (["draw_in_tail_a_m", "draw_in_tail_b_m"] if scene == "bend"
                 else [f"draw_in_free_end_{j}_m" for j in range(draw.shape[1])])  # fmt: skip
        return [(["time_s", "pull_displacement_m", "pull_force_N", *names],
                 [res.times, res.pull_displacement, res.pull_force,
                  *(draw[:, j] for j in range(draw.shape[1]))])]  # fmt: skip
    tables = [
        (["s_m", "tension_N", "rod_contact"], [res.s, res.tension, res.rod_contact.astype(int)]),
        (["s_m", "omega1_per_m", "omega2_per_m", "omega3_per_m"],
         [res.s_nodes, res.darboux[:, 0], res.darboux[:, 1], res.darboux[:, 2]]),
    ]  # fmt: skip
    if loading == "pull":
        curve = (["displacement_m", "t_high_N", "t_high_over_t_low"],
                 [res.pull_displacement, res.pull_force, res.ratio_curve])  # fmt: skip
        return [curve, *tables]
    return tables


def _scalars_and_arrays(res) -> tuple[dict, dict]:
    """The result's scalars (its fields and its summary's, the solver's integer stats kept)
    and its arrays."""
    from knotmech._json import split_arrays

    scalars, arrays = split_arrays(res)
    if hasattr(res, "to_dict"):
        summary = res.to_dict()
    elif hasattr(res, "summary"):
        summary = res.summary()
    else:
        summary = {}
    if hasattr(type(res), "topology_preserved"):  # a property, not a field
        summary = {**summary, "topology_preserved": bool(res.topology_preserved)}
    extra, _ = split_arrays(summary)
    for key, value in extra.items():
        scalars.setdefault(key, value)
    return scalars, arrays


def _write_outputs(scene: str, args, res, kw: dict, paths: dict) -> None:
    from knotmech import _json
    from knotmech.cli._paths import writing

    written = []
    if paths["csv"]:
        loading = getattr(args, "loading", None)
        for (path, what), (header, cols) in zip(
            paths["csv"], _csv_columns(scene, res, loading), strict=True
        ):
            rows = _write_csv(path, header, cols)
            written.append(f"{path} ({what}; {rows} rows)")
    scalars, arrays = _scalars_and_arrays(res)
    if paths["json"] is not None:
        doc = {"scene": scene, "inputs": kw}
        doc.update((k, v) for k, v in scalars.items() if k not in doc)
        with writing(paths["json"], option="--json"):
            _json.write(paths["json"], doc)
        written.append(f"{paths['json']} (scalars)")
    if paths["npz"] is not None:
        import numpy as np

        with writing(paths["npz"], option="--npz"):
            np.savez(paths["npz"], **arrays)
        written.append(f"{paths['npz']} (arrays: {', '.join(sorted(arrays))})")
    if paths["plot"] is not None:
        what = _plot(paths["plot"], scene, res, kw)
        written.append(f"{paths['plot']} ({what})")
    for line in written:
        print(f"wrote {line}", file=sys.stderr)


def _plot(path: Path, scene: str, res, kw: dict) -> str:
    """Draw the run's curve (and the closed form where one applies); return what it shows."""
    import numpy as np

    from knotmech.cli._paths import writing
    from knotmech.plotting import new_axes

    ax = new_axes(figsize=(6.4, 4.4))
    if scene in ("capstan", "two-loops") and res.mode == "pull":
        ax.plot(res.displacement * 1e3, np.asarray(res.t_high) / res.t_low, "k-", lw=1.2,
                label="DER simulation")  # fmt: skip
        ax.axhline(res.exp_mu_eff_theta, color="C0", ls="--",
                   label=rf"thick-rod capstan $e^{{\mu_{{eff}}\theta}}$ = "
                   f"{res.exp_mu_eff_theta:.4g}")  # fmt: skip
        ax.axhline(res.exp_mu_theta, color="C3", ls=":",
                   label=rf"ideal rope $e^{{\mu\theta}}$ = {res.exp_mu_theta:.4g}")  # fmt: skip
        ax.set_xlabel("pulled-end displacement [mm]")
        ax.set_ylabel(r"$T_{high}/T_{low}$")
        what = "T_high/T_low against displacement, with exp(mu_eff theta) and exp(mu theta)"
    elif scene in ("capstan", "two-loops"):
        ax.plot(res.times, res.displacement * 1e3, "k-", lw=1.2, label="DER simulation")
        ax.set_xlabel("time [s]")
        ax.set_ylabel("high-end displacement [mm]")
        ax.set_title(f"hold: T_high/T_low = {kw['t_high'] / res.t_low:.4g}, limit "
                     f"exp(mu_eff theta) = {res.exp_mu_eff_theta:.4g}")  # fmt: skip
        what = "high-end displacement against time (creep)"
    elif hasattr(res, "grip_displacement"):  # the axial drag
        ax.plot(res.grip_displacement * 1e3, res.axial_force, "k-", lw=1.2,
                label="DER simulation")  # fmt: skip
        if np.isfinite(res.sliding_force):
            ax.axhline(res.sliding_force, color="C3", ls="--",
                       label=f"sliding force {res.sliding_force:.4g} N")  # fmt: skip
        ax.set_xlabel("grips' travel along the pole [mm]")
        ax.set_ylabel("axial force [N]")
        what = "axial force against the grips' travel, with the sliding force"
    elif scene == "pinch":
        ax.plot(res.displacement * 1e3, res.pull_force, "k-", lw=1.2, label="DER simulation")
        amontons = 2 * res.mu * res.normal_load
        ax.axhline(amontons, color="C0", ls="--",
                   label=rf"Amontons $2\mu F_n$ = {amontons:.4g} N")  # fmt: skip
        ax.set_xlabel("pulled-end displacement [mm]")
        ax.set_ylabel("pull force [N]")
        what = "pull force against displacement, with Amontons' 2 mu F_n"
    elif scene == "overhand":
        ax.plot(res.end_to_end, res.pull_force, "k-", lw=1.2, label="DER simulation")
        ax.set_xlabel("end-to-end distance [m]")
        ax.set_ylabel("pull force [N]")
        what = "pull force against end-to-end distance (no closed form drawn)"
    elif scene in ("bend", "centreline", *LOOP_SCENES):
        ax.plot(res.pull_displacement * 1e3, res.pull_force, "k-", lw=1.2,
                label="DER simulation")  # fmt: skip
        if np.isfinite(res.slip_load):
            ax.axhline(res.slip_load, color="C3", ls="--",
                       label=f"slip load {res.slip_load:.4g} N")  # fmt: skip
        ax.set_xlabel("pulled-end displacement [mm]")
        ax.set_ylabel("pull force [N]")
        what = "pull force against displacement, with the slip load (no closed form drawn)"
        name = {"bend": f"bend {getattr(res, 'kind', '')}"}.get(scene, scene)
        ax.set_title(f"simulate {name}: status {res.status}, verdict {res.verdict or 'none'}")
    elif res.loading == "pull":
        ax.plot(res.pull_displacement * 1e3, res.ratio_curve, "k-", lw=1.2,
                label="DER simulation")  # fmt: skip
        ax.set_xlabel("pulled-end displacement [mm]")
        ax.set_ylabel(r"$T_{high}/T_{low}$")
        what = "T_high/T_low against displacement (no closed form drawn)"
    else:
        ax.plot(res.s, res.tension, "k-", lw=1.2, label="DER simulation")
        ax.axhline(res.t_high, color="C3", ls=":", label=f"T_high = {res.t_high:.4g} N")
        ax.axhline(res.t_low, color="C0", ls=":", label=f"T_low = {res.t_low:.4g} N")
        ax.set_xlabel("arc length from end 0 [m]")
        ax.set_ylabel("tension [N]")
        what = "tension along the rod, with the end loads"
    if not ax.get_title():
        ax.set_title(f"simulate {scene}: status {res.status}")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=8)
    with writing(path, option="--plot"):
        ax.figure.savefig(path, dpi=120, bbox_inches="tight")
    return what


# ----------------------------------------------------------------------------- running


def run(args) -> int:
    scene = args.scene
    if scene in TIED_BENDS:  # simulate NAME is simulate bend --kind NAME
        args.kind, scene = scene, "bend"
    paths = _check_outputs(scene, args)  # before any work
    kw = _parse(args, scene)
    _check_combination(scene, args, kw)
    progress = not args.no_progress
    if scene in ("capstan", "two-loops"):
        res = _run_capstan(scene, args, kw, progress)
    elif scene == "pinch":
        from knotmech.scenes.pinch import pinch

        res = pinch(progress=progress, **kw)
        print(
            f"pinch: status {res.status}; F_t* = {res.sliding_force:.4g} N, "
            f"F_t*/(2 mu F_n) = {res.ratio:.4g}, x = 4F_n/(pi E d D) = {res.load_parameter:.3g}"
        )
    elif scene == "overhand":
        res = _run_overhand(kw, args, progress)
    elif scene in ("bend", "centreline"):
        res = _run_pulled_knot(scene, kw, args, progress)
    elif scene in LOOP_SCENES:
        res = _run_loop(scene, kw, progress)
    elif scene in AXIAL_SCENES or (scene in AXIAL_LOADING and args.loading == "axial"):
        res = _run_axial(scene, kw, progress)
    elif scene in HITCH_SCENES:
        res = _run_hitch(scene, kw, args, progress)
    else:
        res = _run_clove_hitch(kw, args, progress)
    for warning in getattr(res, "warnings", None) or ():  # the scene's own checks, one line each
        print(f"warning: {warning}", file=sys.stderr)
    if res.status != "success" and getattr(res, "message", ""):  # why it failed, in one line
        print(f"{scene}: {res.status}: {res.message}", file=sys.stderr)
    _write_outputs(scene, args, res, kw, paths)
    return 0 if res.status == "success" else 1


def _run_capstan(scene, args, kw, progress):
    from knotmech.scenes.capstan import capstan, capstan_two_loops

    kw = {**kw, "mode": args.mode, "surface_friction": not args.centreline_friction}
    res = (capstan if scene == "capstan" else capstan_two_loops)(progress=progress, **kw)
    hold = res.mode == "hold"  # a hold has no sliding ratio (res.ratio is NaN by design)
    ratio = kw["t_high"] / res.t_low if hold else res.ratio
    print(
        f"{scene}: status {res.status}; T_high/T_low = {ratio:.4g} "
        f"({'held' if hold else 'sliding'}) | "
        f"exp(mu theta) = {res.exp_mu_theta:.4g}, exp(mu_eff theta) = "
        f"{res.exp_mu_eff_theta:.4g}" + (f"; creep {res.creep:.3g} m" if res.mode == "hold" else "")
    )
    return res


def _run_overhand(kw, args, progress):
    from knotmech.scenes.overhand import overhand

    kw = dict(kw)
    turns = kw.pop("turns", 1)
    if not 1 <= turns <= 4:
        raise InputError(f"--turns must be 1, 2, 3 or 4, got {turns}")
    mu = kw.pop("mu")
    res = overhand(turns, mu, params=args.params, progress=progress, **kw)
    print(
        f"overhand n = {turns}, mu = {mu:g}: status {res.status}; pull force "
        f"{res.pull_force[-1]:.4g} N at end-to-end {res.end_to_end[-1]:.4g} m; knot "
        f"{res.knot_start} -> {res.knot_end}"
        + ("" if res.knot_preserved else " (KNOT TYPE CHANGED: a strand passed through)")
    )
    return res


def _run_clove_hitch(kw, args, progress):
    from knotmech.scenes.clove_hitch import clove_hitch

    kw = {**kw, "loading": args.loading}  # options not given: the scene's own defaults
    res = clove_hitch(progress=progress, **kw)
    if args.loading == "pull":
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
            f"T_low = {res.t_low:.4g} N, creep {res.creep:.3g} m over the hold's last half"
            + (
                f", {res.creep_speed_d:.3g} d/s ({res.creep_speed:.3g} m/s) over the last "
                f"{res.creep_window:.3g} s"
                if math.isfinite(res.creep_speed_d)
                else ""
            )
            + verdict
        )
    return res


def _run_axial(scene, kw, progress):
    """A hitch dragged along its pole (knotmech.scenes.axial): sliding force, knot type."""
    from knotmech.scenes.axial import axial_pull

    res = axial_pull(scene, progress=progress, **kw)
    kept = "kept" if res.topology_preserved else "CHANGED (a strand passed through another)"
    slid = (f"slides at {res.sliding_force:.4g} N" if res.slid
            else f"did not slide up to {res.peak_force:.4g} N")  # fmt: skip
    print(f"{scene} (axial drag at {res.drag_speed * 1e3:.3g} mm/s, T = {res.normal_load:.4g} N "
          f"a leg, {res.wraps} turns): status {res.status}; {slid} (peak {res.peak_force:.4g} "
          f"N, plateau {res.plateau_force:.4g} N); knot type {kept}; "
          f"{res.stats.get('wall_s', 0.0):.3g} s")  # fmt: skip
    return res


def _run_hitch(scene, kw, args, progress):
    """Two half hitches, round turn and two half hitches, cow hitch (scenes.hitches)."""
    from knotmech.scenes.hitches import hitch_function

    kw = {**kw, "loading": args.loading}  # options not given: the scene's own defaults
    res = hitch_function(scene)(progress=progress, **kw)
    kept = (
        "kept"
        if res.topology_preserved
        else "CHANGED (the knot came apart or a strand passed through another)"
    )
    if args.loading == "pull":
        head = (
            f"T_low = {res.t_low:.4g} N; T_high = {res.t_high:.4g} N after "
            f"{res.pull_displacement[-1] * 1e3:.3g} mm"
            if res.pull_force.size
            else "no pull recorded"
        )
        print(f"{scene} (pull at {res.pull_speed * 1e3:.3g} mm/s): status {res.status}; {head}; "
              f"knot type {kept}")  # fmt: skip
    else:
        verdict = f"verdict: {res.verdict.upper()}; " if res.verdict else ""
        print(
            f"{scene} ({res.loading}): status {res.status}; {verdict}T_high = {res.t_high:.4g} "
            f"N, T_low = {res.t_low:.4g} N; creep {res.creep_speed_d:.3g} d/s "
            f"({res.creep_speed:.3g} m/s) over the last {res.creep_window:.3g} s, free end "
            f"{res.tail_creep_speed_d:.3g} d/s; knot type {kept}; "
            f"{res.stats.get('steps', 0)} steps, {res.stats.get('wall_s', 0.0):.3g} s"
        )
    return res


def _ends(values: list[str]) -> list[tuple[str, str]]:
    """``--ends FIRST,LAST`` (once per rod) as (first, last) pairs; the words are the
    scene's to check."""
    ends = []
    for value in values:
        parts = [p.strip() for p in value.split(",")]
        if len(parts) != 2:
            raise InputError(
                f"--ends {value}: give FIRST,LAST, each pull, fixed or free (e.g. free,pull)"
            )
        ends.append((parts[0], parts[1]))
    return ends


def _run_loop(scene, kw, progress):
    """A loop round its pin, pulled by the standing part until it slips or the pull ends."""
    import math

    from knotmech.scenes.bends import held_words
    from knotmech.scenes.loops import loop

    res = loop(scene, progress=progress, **kw)
    if res.verdict == "slips":
        verdict = f"SLIPS at {res.slip_load:.4g} N ({res.slipped_by or 'tail'})"
    elif res.verdict == "holds":
        verdict = held_words(res)
    else:
        verdict = "no verdict"
    end = "no pull frame"
    if res.tail_draw_in.size and res.loading == "end-to-end":
        end = (f"end to end: eye drawn in {res.eye_growth[-1] * 1e3:.3g} mm, rope drawn out "
               f"to the right end {res.tail_draw_in[-1] * 1e3:.3g} mm")  # fmt: skip
    elif res.tail_draw_in.size:
        end = (f"tail drawn in {res.tail_draw_in[-1] * 1e3:.3g} mm, eye grown "
               f"{res.eye_growth[-1] * 1e3:.3g} mm")  # fmt: skip
    kept = "kept" if res.topology_preserved else "CHANGED"
    peak = f"{res.max_force:.4g} N" if math.isfinite(res.max_force) else "none"
    print(
        f"{scene}: status {res.status}; {verdict}; {end}; max force {peak}; knot type {kept} "
        f"on {res.frames_checked} frames; {res.stats.get('steps', 0)} steps, "
        f"{res.stats.get('wall_s', 0.0):.3g} s"
    )
    return res


def _run_pulled_knot(scene, kw, args, progress):
    """A bend, or a user's centreline: pulled by its ends until it slips or the pull ends."""
    import math

    from knotmech.scenes.bends import held_words

    if scene == "bend":
        from knotmech.scenes.bends import bend

        kw = dict(kw)
        kind = kw.pop("kind")
        res = bend(kind, progress=progress, **kw)
        name = f"bend {kind}"
    else:
        from knotmech.scenes.centreline import centreline

        res = centreline(args.file, ends=_ends(args.ends), unit=args.unit, progress=progress, **kw)
        name = f"centreline {args.file}"
    if res.verdict == "slips":
        verdict = f"SLIPS at {res.slip_load:.4g} N"
    elif res.verdict == "holds":
        verdict = held_words(res)
    else:
        verdict = "no verdict"
    kept = "kept" if res.topology_preserved else "CHANGED (a strand passed through another)"
    if getattr(res, "frames_checked", 0):
        kept += f" on {res.frames_checked} frames"
    if getattr(res, "tail_drawn", ""):
        verdict += (f"; tail drawn in: {res.tail_drawn}; the knot moved {res.roll * 1e3:.3g} mm"
                    " towards both tails")  # fmt: skip
    peak = f"{res.max_force:.4g} N" if math.isfinite(res.max_force) else "none"
    print(
        f"{name}: status {res.status}; {verdict}; max force {peak}; knot type {kept}; "
        f"{res.stats.get('steps', 0)} steps, {res.stats.get('wall_s', 0.0):.3g} s"
    )
    return res

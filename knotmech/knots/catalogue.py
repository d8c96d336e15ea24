"""The knots knotmech knows: one :class:`~knotmech.knots.Knot` record each.

Adding a knot is one record here and, for a hitch tied from a new centreline, one curve file
(``knotmech/scenes/hitch_curves/<knot>.py`` with the curve function and ``knotted_length``).
Every consumer reads these records: ``knotmech hold`` (names, aliases, which models answer),
``knotmech simulate`` (its commands and help), the hold tables (which knots have a scene),
the closed forms (:data:`knotmech.analytic.hitch.KNOTS`) and the scene package.
"""

from __future__ import annotations

import math

from knotmech.knots._record import Knot, Wraps

__all__ = ["CATALOGUE"]

TWO_PI = 2 * math.pi

#: the clove-hitch paper (the DER scene, the hold/slip diagram, the capstan experiments)
CLOVE_PAPER = "clove-hitch paper, Extreme Mech. Lett., DOI 10.1016/j.eml.2022.101788"
#: the bends' paper
PATIL = "Patil, Sandt, Kolle & Dunkel, Science 367, 71 (2020)"
#: the hitches' closed forms
BAYMAN = "Bayman, Am. J. Phys. 45 (1977) 185; Maddocks & Keller, SIAM J. Appl. Math. 47 (1987) 1185"
#: the half hitches, made scenes: the defaults that differ from the clove hitch's
_MADE_HITCH = {"loading": "free", "rod_length": None, "n_nodes": None}

#: the tied bends' start curves and pulls (issue 25)
TIED_NOTE = "this work: docs/notes/knots-and-curves/tied-knots-pulled.md"
_ENDS = "the two standing parts pulled apart along their end tangents, the tails free"
#: (name, aliases, summary, pull, scene defaults, loading) of the bends of
#: knotmech.scenes.tied: pull "ends" along the standing parts' end tangents, "apart" the
#: standing parts (which leave the knot side by side) pulled apart sideways
_TIED_PULL = {"n_frames": 20, "pull_distance_d": 20.0, "set_travel_d": 20.0}
#: the figure-eight bend starts drawn in (about 45-50 d of each rope in the knot, not the
#: loose parametric 120 d that needed a 40 d set): 52 nodes a rope, the bends' 20 d set
#: (docs/notes/knots-and-curves/tied-knots-pulled.md)
_TIED_BENDS = (
    ("sheet-bend", ("sheet", "beckets-bend", "weavers-knot"),
     "a bight in one rope, the other through it, round both legs and under itself",
     "ends", {"n_nodes": 100, **_TIED_PULL}, _ENDS),
    ("double-sheet-bend", ("double-sheet",),
     "the sheet bend with two turns round the bight", "ends",
     {"n_nodes": 120, **_TIED_PULL}, _ENDS),
    ("flat-overhand-bend", ("offset-overhand-bend", "offset-water-knot", "edk",
                            "european-death-knot", "flat-overhand"),
     "two ropes side by side tied in one overhand (the climbers' offset knot for abseil "
     "ropes): loaded, it rolls towards its tails", "apart",
     {"n_nodes": 100, **_TIED_PULL},
     "ring-loaded: the standing parts, which leave the knot side by side, pulled apart "
     "sideways (as on an abseil anchor), the tails free"),
    ("figure-eight-bend", ("figure-8-bend", "flemish-bend"),
     "one rope ties a figure-eight, the other retraces it from the opposite end", "ends",
     {"n_nodes": 52, **_TIED_PULL}, _ENDS),
    ("double-fishermans", ("double-fisherman", "double-fishermans-bend", "grapevine-bend",
                           "grapevine"),
     "each rope ties a double overhand (strangle) round the other", "ends",
     {"n_nodes": 150, **_TIED_PULL}, _ENDS),
)  # fmt: skip

#: the loops (issue 25): their eye round a fixed pin (knotmech.scenes.loops)
LOOP_NOTE = "this work: docs/notes/knots-and-curves/tied-loops-pulled.md"
_LOOP_LOADING = (
    "the eye round a fixed pin, the standing part pulled away from the pin along its end "
    "tangent, the tail free"
)
_BUTTERFLY_LOADING = (
    "on the loop (default): " + _LOOP_LOADING + "; end to end (loading end-to-end): both "
    "ends pulled apart along their end tangents, the eye free, no pin"
)
#: (name, aliases, summary, curve keywords, scene defaults, loading) of the loops of
#: knotmech.scenes.tied: the bowline's tail 15 d (the curve's default 7 d is consumed when
#: the loose knot tightens, before anything slips); scene default "loadings": the loadings
#: its scene takes (default only "loop") (docs/notes/knots-and-curves/tied-loops-pulled.md)
_TIED_LOOPS = (
    ("bowline", ("bowline-knot", "bowline-loop"),
     "a fixed eye: a bight of the tail through a nipping loop in the standing part, round "
     "the standing part and back (a sheet bend with one rope)",
     {"tail": 15.0}, {"n_nodes": 175}, _LOOP_LOADING),
    ("figure-eight-loop", ("figure-8-loop", "figure-eight-on-a-bight", "figure-8-on-a-bight",
                           "flemish-loop", "figure-of-eight-loop"),
     "a fixed eye: a figure-eight knot tied in the doubled rope",
     {}, {"n_nodes": 130}, _LOOP_LOADING),
    ("alpine-butterfly", ("butterfly", "butterfly-loop", "alpine-butterfly-loop",
                          "alpine-butterfly-knot", "butterfly-knot", "linemans-loop",
                          "lineman-loop", "linemans-knot"),
     "a mid-line fixed eye tied in the bight (ABoK #1053): a bight twisted twice, its end "
     "passed through the window between the twists; loadable on the loop and end to end",
     {}, {"n_nodes": 130, "loadings": ("loop", "end-to-end")},
     _BUTTERFLY_LOADING),
)  # fmt: skip

_THH_DOC = r"""Tie {what} on a post and load them.

    Same keywords as :func:`knotmech.scenes.clove_hitch.clove_hitch` (see
    :func:`knotmech.scenes._hitch.run_hitch` for each), with these defaults: ``loading``
    ``"free"`` (T_high on the standing end, the working end free), ``rod_length`` None (the
    knotted part and a 64 mm tail at each end: {length} m at d = 4 mm, D = 30 mm),
    ``n_nodes`` None (edges of about 3.1 mm), ``creep_limit`` 1e-3 d/s: the hitch holds when
    neither end creeps faster than that over the last second of the hold (or its last half
    if shorter) and end 0 moved less than ``slip_distance`` over the last half.

    Returns
    -------
    HitchResult
        ``knot = "{ident}"``; ``verdict``, ``creep_speed`` [m/s] (and
        ``creep_speed_d`` [d/s]), ``tension`` T(s), ``topology_preserved`` (distances,
        winding and the invariants ``{invariants}`` kept), ``post_wraps()``.
    """

CATALOGUE = (
    Knot(
        name="capstan",
        family="capstan",
        summary="a rope wrapped round a post by a wrap angle, no crossing (Euler-Eytelwein)",
        scene="knotmech.scenes.capstan:capstan",
        sources=("Euler-Eytelwein capstan equation", CLOVE_PAPER + ", sec. 3"),
    ),
    Knot(
        name="clove-hitch",
        family="hitch",
        aliases=("clove",),
        summary="two turns on the post, both ends nipped under the diagonal rider",
        wraps=Wraps(
            post_wrap_in=TWO_PI,
            post_wrap_out=TWO_PI,
            post_nips=True,
            description="two turns on the post, both ends nipped under the diagonal rider",
        ),
        curve="knotmech.scenes.curves:clove_hitch_curve",
        pull_angle=4 * math.pi,
        scene="knotmech.scenes.clove_hitch:clove_hitch",
        simulate_help="a clove hitch tied on a post, held by end loads or pulled "
        "(clove-hitch paper)",
        hold_table=True,
        free_end_note="ideal-rope theory (Bayman 1977; Maddocks & Keller 1987): with a free "
        "end (T_low = 0) the clove hitch slips at any load, whatever the rod and post "
        "diameters d, D",
        sources=(CLOVE_PAPER + ", sec. 5-8, Fig. 4", BAYMAN),
    ),
    Knot(
        name="two-half-hitches",
        family="hitch",
        aliases=("2hh",),
        summary="a single turn on the post, then two half hitches round the standing part",
        wraps=Wraps(
            post_wrap_in=math.pi,
            half_hitches=2,
            description="a single turn (pi) on the post, then two half hitches on the "
            "standing part",
        ),
        curve="knotmech.scenes.hitch_curves.two_half_hitches:two_half_hitches_curve",
        curve_params={"wrap_angle": math.pi},
        pull_angle=math.pi,
        scene_defaults=_MADE_HITCH,
        scene_doc=_THH_DOC.format(
            what="two half hitches",
            length="0.411",
            ident="two_half_hitches",
            invariants="(1, -2, 3, -2, 1), -1",
        ),
        simulate_help="two half hitches on a post (a turn, then two half hitches round the "
        "standing part), held by end loads or pulled: verdict, creep speed, knot type kept",
        hold_table=True,
        sources=(BAYMAN, "this work: DER hold table (knotmech.scenes.phase_table)"),
    ),
    Knot(
        name="round-turn",
        family="hitch",
        summary="one complete turn on the post, no crossing",
        wraps=Wraps(
            post_wrap_in=TWO_PI, description="one complete turn (2 pi) on the post, no crossing"
        ),
        sources=("Euler-Eytelwein capstan equation",),
    ),
    Knot(
        name="round-turn-two-half-hitches",
        family="hitch",
        aliases=("round-turn-and-two-half-hitches", "round-turn-&-two-half-hitches", "rt2hh"),
        summary="a round turn on the post, then two half hitches round the standing part",
        wraps=Wraps(
            post_wrap_in=TWO_PI,
            half_hitches=2,
            description="a round turn (2 pi) on the post, then two half hitches on the "
            "standing part",
        ),
        curve="knotmech.scenes.hitch_curves.two_half_hitches:two_half_hitches_curve",
        curve_params={"wrap_angle": 3 * math.pi},
        pull_angle=3 * math.pi,
        scene_defaults=_MADE_HITCH,
        scene_doc=_THH_DOC.format(
            what="a round turn and two half hitches",
            length="0.518",
            ident="round_turn_two_half_hitches",
            invariants="(1, -2, 3, -2, 1), -2",
        ),
        simulate_help="a round turn and two half hitches on a post, held by end loads or "
        "pulled: verdict, creep speed, knot type kept",
        hold_table=True,
        sources=(BAYMAN, "this work: DER hold table (knotmech.scenes.phase_table)"),
    ),
    Knot(
        name="cow-hitch",
        family="hitch",
        aliases=("cow", "girth-hitch", "girth", "larks-head", "larks-head-knot", "larks-foot"),
        summary="two turns on the post in opposite senses (girth hitch, lark's head)",
        wraps=Wraps(
            post_wrap_in=TWO_PI,
            post_wrap_out=TWO_PI,
            post_nips=True,
            thick_nip=False,
            description="two turns on the post in opposite senses (girth hitch, "
            "lark's head), the bight between them lying over both legs; load on one "
            "leg, T_low on the other",
        ),
        curve="knotmech.scenes.hitch_curves.cow_hitch:cow_hitch_curve",
        pull_angle=TWO_PI,
        scene_defaults=_MADE_HITCH,
        scene_doc=r"""Tie a cow hitch on a post and load it.

    Same keywords as :func:`knotmech.scenes.clove_hitch.clove_hitch` (see
    :func:`knotmech.scenes._hitch.run_hitch` for each), with these defaults: ``loading``
    ``"free"`` (T_high on leg 0, leg 1 free), ``rod_length`` None (the knotted part and a
    64 mm leg at each end: 0.436 m at d = 4 mm, D = 30 mm), ``n_nodes`` None (edges of about
    3.1 mm), ``creep_limit`` 1e-3 d/s (see
    :func:`~knotmech.scenes.two_half_hitches.two_half_hitches`).

    Returns
    -------
    HitchResult
        ``knot = "cow_hitch"``; ``verdict``, ``creep_speed`` [m/s] (``creep_speed_d``
        [d/s]), ``tension`` T(s), ``topology_preserved`` (distances, winding and the
        invariants ``(1,), 0`` kept), ``post_wraps()``.
    """,
        simulate_help="a cow (girth) hitch on a post, one leg loaded and the other free, "
        "loaded or both loaded, or pulled: verdict, creep speed, knot type kept",
        hold_table=True,
        loading="cow hitch loaded on one leg (T_high on leg 0), the other leg free (T_low = "
        "0): the one-ended loading, not the girth hitch of a sling whose two legs share the "
        "load",
        free_end_note="ideal-rope theory: with one leg free (T_low = 0) the cow hitch slips "
        "at any load, whatever d and D (a capstan of finite wrap); in practice it is used "
        "with both legs sharing the load (E. C. Fry, Knots and Ropework: useful 'provided "
        "that both standing parts share the load')",
        sources=(
            BAYMAN,
            "E. C. Fry, Knots and Ropework",
            "this work: DER hold table (knotmech.scenes.phase_table)",
        ),
    ),
    *(
        Knot(
            name=kind,
            family="bend",
            aliases=aliases,
            summary=f"the {kind} bend: two ropes joined by interlocked bights",
            curve="knotmech.scenes.bend_curves:bend_curves",
            curve_params={"code": code, "ends": ends},
            scene="knotmech.scenes.bends:bend",
            sources=(PATIL + ", Fig. 3",),
        )
        for kind, aliases, code, ends in (
            ("reef", ("reef-knot", "square-knot", "square"), "UOUUOU", ("end", "start")),
            ("granny", ("granny-knot",), "UOUOUO", ("end", "start")),
            ("thief", ("thief-knot",), "UOUUOU", ("start", "start")),
            ("grief", ("grief-knot",), "UOUOUO", ("start", "start")),
        )
    ),
    Knot(
        name="overhand",
        family="stopper",
        summary="a stopper knot (see `knotmech simulate overhand`), not a hitch on a post",
        curve="knotmech.scenes.curves:overhand_knot",
        scene="knotmech.scenes.overhand:overhand",
        unanswered="a stopper knot (see `knotmech simulate overhand`), not a hitch on a post",
        sources=(
            "Jawed et al. 2015 (the overhand knot law)",
            "Choi, Tong & Jawed 2021 (implicit contact model)",
        ),
    ),
    # -- loops (issue 25): the eye round a fixed pin, the standing part pulled ---------
    *(
        Knot(
            name=name,
            family="loop",
            aliases=aliases,
            summary=summary,
            curve=f"knotmech.scenes.tied.{name.replace('-', '_')}:{name.replace('-', '_')}",
            curve_params=params,
            scene="knotmech.scenes.loops:loop",
            scene_defaults=defaults,
            loading=loading,
            sources=(LOOP_NOTE,),
        )
        for name, aliases, summary, params, defaults, loading in _TIED_LOOPS
    ),
    Knot(
        name="figure-eight",
        family="stopper",
        aliases=("figure-8",),
        unanswered="a stopper / loop knot (no post, no closed form or DER table here)",
    ),
    *(
        Knot(
            name=name,
            family="bend",
            aliases=aliases,
            summary=summary,
            curve=f"knotmech.scenes.tied.{name.replace('-', '_')}:{name.replace('-', '_')}",
            curve_params={"pull": pull},
            scene="knotmech.scenes.bends:bend",
            scene_defaults=defaults,
            loading=loading,
            sources=(TIED_NOTE,),
        )
        for name, aliases, summary, pull, defaults, loading in _TIED_BENDS
    ),
)

# -- hitches pulled along the pole's axis (issue 25, item 3; knotmech.scenes.axial) ---------
#: the axial sliding test of the clove hitch (the scene of knotmech.scenes.axial)
SABATER = (
    "Sabater, Park, Crassous, Neukirch & Reis, J. Mech. Phys. Solids (2026), DOI "
    "10.1016/j.jmps.2026.106628, arXiv 2604.06962"
)
AXIAL_NOTE = "this work: docs/notes/knots-and-curves/axial-hitches.md"

CATALOGUE = (
    *CATALOGUE,
    Knot(
        name="prusik",
        family="hitch",
        aliases=("prusik-knot", "prussik", "prusik-hitch"),
        summary="a closed sling wrapped two to four times round a pole (or a rope) and through "
        "itself, loaded along the pole by its loop (ABoK #1763)",
        simulate_help="a Prusik (a sling with --wraps turns a side) on a pole, its loop "
        "pulled along the pole: sliding force, knot type kept",
        loading="the sling's loop pulled along the pole (both legs, half the load each)",
        sources=(AXIAL_NOTE, SABATER),
    ),
    Knot(
        name="rolling-hitch",
        family="hitch",
        aliases=("rolling", "magnus-hitch", "magnus"),
        summary="two riding turns round the pole over the standing part, then a half hitch on "
        "the other side (Magnus hitch, ABoK #1734-#1735): the hitch for a pull along the pole",
        curve="knotmech.scenes.hitch_curves.rolling_hitch:rolling_hitch_curve",
        pull_angle=7 * math.pi,
        scene_defaults=_MADE_HITCH,
        scene_doc=_THH_DOC.format(
            what="a rolling hitch (its standing part along the pole, -z)",
            length="0.575",
            ident="rolling_hitch",
            invariants="(1,), 4",
        ),
        simulate_help="a rolling (Magnus) hitch on a pole, its standing part along the pole: "
        "held by end loads, or (--loading axial) its standing part dragged along the pole: "
        "sliding force, knot type kept",
        loading="the standing part pulled along the pole towards the riding turns, the "
        "working end under a light set load",
        sources=(AXIAL_NOTE, SABATER, "C. W. Ashley, The Ashley Book of Knots, #1734-#1735"),
    ),
)

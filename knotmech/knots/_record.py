"""The record of one knot: :class:`Knot` (what the registry holds) and :class:`Wraps`.

A leaf module: it imports nothing from knotmech, so that every layer (the closed forms, the
scenes, the verdict, the command line) can read the registry without paying for NumPy,
numba or a scene. Functions (a knot's curve, its scene) are named by ``"module:attribute"``
and imported on first use (:meth:`Knot.curve_function`, :meth:`Knot.scene_function`).
"""

from __future__ import annotations

import importlib
import math
from dataclasses import dataclass, field

__all__ = ["FAMILIES", "Knot", "Wraps", "resolve"]

#: families of knots: a hitch on a post, a capstan wrap, a bend (two ropes joined), a loop,
#: a stopper
FAMILIES = ("capstan", "hitch", "bend", "loop", "stopper")


def resolve(ref: str):
    """The object named by ``"package.module:attribute"`` (the module imported now)."""
    module, _, attr = ref.partition(":")
    return getattr(importlib.import_module(module), attr)


@dataclass(frozen=True)
class Wraps:
    """Wrap angles of a hitch in the closed-form chain model
    (:class:`knotmech.analytic.hitch.HitchGeometry` is built from these).

    Attributes
    ----------
    post_wrap_in, post_wrap_out : float
        Wrap on the post before and after the rider [rad].
    half_hitches : int
        Half hitches round the standing part.
    post_nips : bool
        Both ends nipped under a rider on the post.
    thick_nip : bool
        Whether the thick-nip model is derived for this hitch.
    description : str
        The geometry in words.
    """

    post_wrap_in: float
    post_wrap_out: float = 0.0
    half_hitches: int = 0
    post_nips: bool = False
    thick_nip: bool = True
    description: str = ""


@dataclass(frozen=True)
class Knot:
    """One knot: its names, family, curve, scene, closed form, tables and sources.

    Attributes
    ----------
    name : str
        Canonical name, the one spelling at the edges (``clove-hitch``).
    family : str
        One of :data:`FAMILIES`.
    aliases : tuple of str
        Other names people use (``girth-hitch``); matched after lower-casing, ``_`` and
        spaces to ``-`` and apostrophes dropped.
    summary : str
        One line: what the knot is (the command line's help).
    wraps : Wraps or None
        Its closed-form geometry (:mod:`knotmech.analytic.hitch`), None when there is none.
    curve : str
        ``"module:function"`` of its start centreline, ``""`` when none.
    curve_params : dict
        What picks this knot from its curve family: keywords of ``curve`` (the half hitches'
        wrap angle), or for the bends the crossing ``code`` and the pulled ``ends`` that
        :mod:`knotmech.scenes.bend_curves` reads.
    pull_angle : float
        Wrap of the standing part on the post [rad] (a hitch's scene pulls along it).
    scene : str
        ``"module:function"`` of its DER scene; ``""``: a hitch scene made from ``curve``
        (:func:`knotmech.scenes.hitches.hitch_function`).
    scene_defaults : dict
        Defaults of a made hitch scene that differ from the clove hitch's.
    scene_doc : str
        Docstring of a made hitch scene.
    simulate_help : str
        The scene's line in ``knotmech simulate --help``; ``""``: no ``simulate`` command.
    hold_table : bool
        Whether a DER hold table of this knot is shipped (``hold_phase_table_<name>*.json``).
    loading : str
        The loading its DER answer models, when it is not the obvious one.
    free_end_note : str
        What the ideal-rope theory says of the free-end case, when the verdict should say it.
    unanswered : str
        Why ``knotmech hold`` does not answer for this knot (``""``: it answers).
    sources : tuple of str
        Where its published numbers come from.
    """

    name: str
    family: str
    aliases: tuple = ()
    summary: str = ""
    wraps: Wraps | None = None
    curve: str = ""
    curve_params: dict = field(default_factory=dict)
    pull_angle: float = math.nan
    scene: str = ""
    scene_defaults: dict = field(default_factory=dict)
    scene_doc: str = ""
    simulate_help: str = ""
    hold_table: bool = False
    loading: str = ""
    free_end_note: str = ""
    unanswered: str = ""
    sources: tuple = ()

    def __post_init__(self):
        if self.family not in FAMILIES:
            raise ValueError(f"knot {self.name}: family must be one of {FAMILIES}")

    @property
    def identifier(self) -> str:
        """The name as a Python identifier (``clove_hitch``): scene and curve names."""
        return self.name.replace("-", "_")

    @property
    def answered(self) -> bool:
        """Whether ``knotmech hold`` answers for this knot."""
        return not self.unanswered

    @property
    def has_scene(self) -> bool:
        """Whether a DER scene loads this knot (its own, or one made from its curve)."""
        return bool(self.scene or (self.family == "hitch" and self.curve))

    def curve_function(self):
        """The function tying this knot's start centreline (imported now)."""
        return resolve(self.curve)

    def scene_function(self):
        """The DER scene function of this knot (imported now; the DER solver with it)."""
        if self.scene:
            return resolve(self.scene)
        # named, not imported: the registry sits below the scenes (import-linter layers)
        return resolve("knotmech.scenes.hitches:hitch_function")(self.name)

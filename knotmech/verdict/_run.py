"""What the verdicts answered by one DER run share (bends, loops, hitches dragged along a
pole): the deciding model answer of the run, and the refusal of inputs that do not apply."""

from __future__ import annotations

import math

from knotmech.errors import InputError


def run_answer(*, holds, capacity, load, assumptions, validity, reference, message):
    """The deciding :class:`~knotmech.analytic.hitch.ModelAnswer` of one DER run.

    Parameters
    ----------
    holds : bool
        The run's verdict at ``load``.
    capacity, load : float
        The run's slip (or sliding) load and the user's load [N]; the margin is
        ``capacity / load - 1``.
    assumptions, validity : tuple of str
        What the run assumes and where it applies.
    reference : str
        Sources of the knot and the scene.
    message : str
        The run's outcome in words (the answer's one note).
    """
    from knotmech.analytic.hitch import ModelAnswer

    return ModelAnswer(
        model="DER-simulation", holds=bool(holds), margin=capacity / load - 1,
        capacity=capacity, critical_mu=math.nan, decides=True, inside_validity=True,
        assumptions=tuple(assumptions), validity=tuple(validity), reference=reference,
        notes=(message,),
    )  # fmt: skip


def refuse_inputs(key, what: str, why: str, *, free_end: str | None = None, **given) -> None:
    """One-line InputError for the first keyword of ``given`` that is not None (it does not
    apply to a ``what``, e.g. ``"bend"``; ``why`` says what the knot is), and for a nonzero
    ``free_end_load`` when ``free_end`` (the reason) is given."""
    for name, val in given.items():
        if name == "free_end_load":
            continue
        if val is not None:
            raise InputError(f"{name} does not apply to a {what} ({key}: {why})")
    if free_end is not None and float(given.get("free_end_load") or 0.0) != 0.0:
        raise InputError(f"free_end_load does not apply to a {what} ({key}: {free_end})")


def run_shape(result, *, d, support_diameter=None, support="", ropes=1):
    """The last frame of a DER run for ``hold --plot``, or None when the run has no frames.

    Parameters
    ----------
    result
        A scene result with ``positions`` (n_frames, n_nodes, 3) [m].
    d : float
        Rod diameter [m].
    support_diameter : float or None
        Diameter [m] of what the knot is tied round (its axis the z axis), or None.
    support : str
        Its name ("pin", "pole"), drawn as a cylinder when ``support_diameter`` is given.
    ropes : int
        Ropes stored one after the other in ``positions`` (a bend: 2), drawn in two colours.
    """
    import numpy as np

    try:
        pos = np.asarray(result.positions[-1], dtype=float)
    except (AttributeError, IndexError, TypeError, ValueError):
        return None
    if pos.ndim != 2 or pos.shape[1] != 3 or len(pos) < 2:
        return None
    return {"positions": pos, "rod_diameter": d, "post_diameter": support_diameter,
            "support": support, "ropes": int(ropes)}  # fmt: skip

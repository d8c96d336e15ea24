"""The deciding rule of the hold verdict: the most faithful model inside its validity with a
definite answer decides, in the order :data:`RULE`."""

from __future__ import annotations

from dataclasses import replace

__all__ = ["RULE", "decide", "with_validity"]

#: the order in which models decide (the first inside its validity with an answer)
RULE = (
    "DER-simulation",
    "DER-table",
    "ideal-rope",
    "thick-nip",
    "thick-capstan",
    "ideal-capstan",
)


def with_validity(answer, inside: bool, extra: str):
    """``answer`` inside its validity only if also ``inside``; ``extra`` added to its validity."""
    return replace(
        answer,
        inside_validity=bool(answer.inside_validity and inside),
        validity=tuple(answer.validity) + ((extra,) if extra else ()),
    )


def decide(answers):
    """Index of the deciding answer by :data:`RULE`, None when none qualifies."""
    for model in RULE:
        for i, a in enumerate(answers):
            if a.model == model and a.inside_validity and a.holds is not None:
                return i
    return None

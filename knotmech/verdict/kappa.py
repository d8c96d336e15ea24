"""The DER table answer over a rope's estimated bending scale (issue 23).

A material preset's bending scale kappa (:mod:`knotmech.materials`) is an estimate with a
range (nylon and polyester 0.01, range 0.003-0.03; HMPE 0.005-0.05), and the hold tables'
answers depend on kappa inside such a range: of 20 clove-hitch points at mu 0.3 and 0.5,
d/2R 0.048 and 0.118, T_high/EA 1e-4 to 0.3, the runs at kappa 0.003 agree with the
kappa-0.01 table on 15 and those at 0.03 on 17 (``python -m validation._hold_kappa_check
clove-hitch``; the softer rope slips at 0.1-0.3 EA where 0.01 held).

So when kappa comes from a preset, not from ``--bending-scale``, the table answer stands
only if the tables read at the range's ends and at its nominal value all give it (each
table nearest its kappa, within :data:`~knotmech.verdict.der.BENDING_SCALE_FACTOR`);
otherwise the DER does not decide, the details list each kappa's answer, and a closed form
that one of those tables contradicts does not decide either (:func:`against_readings`:
none of them knows the rope's bending stiffness). The slip load is then the band over
those tables (:func:`knotmech.verdict.capacity.merge_bands`): the nominal kappa's value,
from the lowest low to the highest high.
"""

from __future__ import annotations

from dataclasses import replace

from knotmech.verdict.der import BENDING_SCALE_FACTOR

__all__ = ["RANGE_REFUSAL", "against_readings", "over_range", "range_points"]

#: ``der["refused"]`` when the tables disagree over the rope's kappa range
RANGE_REFUSAL = "bending_scale_range"


def range_points(nominal: float, low: float, high: float) -> tuple:
    """The kappas the table answer is read at: the range's ends and its nominal value,
    ascending, each once."""
    return tuple(sorted({float(low), float(nominal), float(high)}))


def _word(holds) -> str:
    return "holds" if holds is True else ("slips" if holds is False else "undecided")


def _reading(k: float, der: dict, answer) -> dict:
    """One kappa's table answer as the details list it."""
    return {
        "kappa": k,
        "table_bending_scale": der.get("table_bending_scale"),
        "holds": None if answer is None else bool(answer.holds),
        "refused": der.get("refused"),
        "message": der.get("message", ""),
    }


def _say(r: dict) -> str:
    tk = r["table_bending_scale"]
    if r["refused"] == "bending_scale":
        return f"kappa {r['kappa']:g}: no table within a factor {BENDING_SCALE_FACTOR:g}"
    table = "" if tk is None or tk == r["kappa"] else f" (table at {tk:g})"
    return f"kappa {r['kappa']:g}{table}: {_word(r['holds'])}"


def over_range(ask, der: dict, answer, *, nominal: float, low: float, high: float):
    """The table answer ``(der, answer)`` at the ``nominal`` kappa, checked over
    [``low``, ``high``]: ``ask(kappa)`` gives ``(der, answer)`` at another kappa.

    Returns ``(der, answer)`` with ``der["kappa_range"]`` (each kappa's answer, ``agree``,
    ``depends``, ``words``): when every kappa gives the nominal answer, that answer with one
    more validity line; when the nominal answer decides and another kappa does not give
    it, ``answer`` None and ``der`` undecided (``refused`` :data:`RANGE_REFUSAL`,
    ``message`` naming each kappa's answer); when the nominal answer does not decide, it as
    it is (the other kappas' answers still keep a closed form they contradict from deciding,
    :func:`against_readings`). A source other than the tables is returned as it is.
    """
    if der.get("source") != "table":
        return der, answer
    readings = []
    for k in range_points(nominal, low, high):
        d, a = (der, answer) if k == float(nominal) else ask(k)
        readings.append(_reading(k, d, a))
    der = dict(der)
    said = "; ".join(_say(r) for r in readings)
    agree = answer is not None and all(r["holds"] is bool(answer.holds) for r in readings)
    der["kappa_range"] = {
        "range": [float(low), float(high)], "nominal": float(nominal), "readings": readings,
        "agree": agree, "depends": {True, False} <= {r["holds"] for r in readings},
        "words": said,
    }  # fmt: skip
    if agree:
        text = (f"the same at every kappa of the rope's estimated range {low:g}-{high:g} "
                f"({said})")  # fmt: skip
        return der, replace(answer, validity=tuple(answer.validity) + (text,))
    if answer is None:
        return der, None
    why = (
        "the answer depends on the rope's bending stiffness inside its estimated range"
        if der["kappa_range"]["depends"]
        else "no answer at every kappa of the rope's estimated range"
    )
    der.update(
        holds=None,
        refused=RANGE_REFUSAL,
        message=(
            f"not decided by the tables: {why} kappa {low:g}-{high:g} ({said}); give "
            "--bending-scale (bending_scale=) for a measured rope"
        ),
    )
    return der, None


def against_readings(answers: list, der: dict) -> list:
    """The closed forms' ``answers``, each taken outside its validity where a DER table read
    over the rope's kappa range says otherwise (when the tables do not decide over the
    range, whether the nominal kappa's table decided or not). A closed form knows no
    bending stiffness; where a table at a kappa of the range answers the other way, the
    closed form does not decide instead."""
    from knotmech.verdict.rule import with_validity

    rng = (der or {}).get("kappa_range")
    if not rng or rng["agree"]:
        return list(answers)
    said = [r for r in rng["readings"] if r["holds"] is not None]
    out = []
    for a in answers:
        against = [r for r in said if a.holds is not None and r["holds"] is not bool(a.holds)]
        if a.inside_validity and against:
            ks = ", ".join(f"{r['kappa']:g}" for r in against)
            a = with_validity(a, False, f"the DER tables at kappa {ks} of the rope's range say "
                              f"it {_word(against[0]['holds'])}")  # fmt: skip
        out.append(a)
    return out

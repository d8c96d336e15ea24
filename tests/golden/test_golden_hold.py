"""Golden test of the hold verdict: closed forms, shipped tables, table lookups, table bytes.

Recorded on the base commit of the knot-registry / verdict refactor (issue 22) and compared
**bit-identically** (floats through ``repr``, non-finite floats as the strings ``"nan"``,
``"inf"``, ``"-inf"`` in this fixture only): the refactor must not change one number or
one word of a verdict. No DER run here (a marked-slow test runs one short ``simulate``).

Regenerate (only for a deliberate, reviewed change of behaviour)::

    KNOTMECH_REGEN_GOLDEN=1 python -m pytest tests/golden/test_golden_hold.py
"""

from __future__ import annotations

import hashlib
import json
import math
import os
import warnings
from importlib import resources
from pathlib import Path

import pytest

GOLDEN = Path(__file__).with_name("golden_hold.json")

#: materials, loads and friction coefficients of the questions
_HITCHES = ("clove-hitch", "two-half-hitches", "round-turn", "round-turn-two-half-hitches",
            "cow-hitch")  # fmt: skip


def _questions() -> list[dict]:
    """~50 ``knotmech.hold`` questions answered without a DER run."""
    qs = []
    for knot in _HITCHES:
        qs += [
            dict(knot=knot, rod_diameter=6e-3, post_diameter=40e-3, mu=0.4, load=200.0,
                 material="nylon"),
            dict(knot=knot, rod_diameter=4e-3, post_diameter=30e-3, mu=0.3, load=1.0,
                 youngs_modulus=1.26e6),
            dict(knot=knot, rod_diameter=10e-3, post_diameter=0.2, mu=0.15, load=5e3,
                 material="polyester"),
            dict(knot=knot, rod_diameter=6e-3, post_diameter=40e-3, mu=0.4, load=200.0),
            dict(knot=knot, rod_diameter=6e-3, post_diameter=25e-3, mu=0.6, load=50.0,
                 material="hmpe", mu_rr=0.3),
            dict(knot=knot, rod_diameter=8e-3, post_diameter=50e-3, mu=0.3, load=300.0,
                 free_end_load=30.0, material="manila"),
            dict(knot=knot, rod_diameter=8e-3, post_diameter=50e-3, mu=0.3, load=30.0,
                 material="nylon", bending_scale=0.01),
        ]  # fmt: skip
    qs += [
        dict(knot="capstan", rod_diameter=6e-3, post_diameter=40e-3, mu=0.3, load=100.0,
             free_end_load=10.0, wrap_angle=2 * math.pi),
        dict(knot="capstan", rod_diameter=6e-3, post_diameter=40e-3, mu=0.3, load=100.0,
             free_end_load=1.0, wrap_angle=math.pi, material="steel-wire"),
        dict(knot="capstan", rod_diameter=20e-3, post_diameter=25e-3, mu=2.5, load=100.0,
             free_end_load=50.0, wrap_angle=30 * math.pi),
        dict(knot="clove", rod_diameter=5e-3, post_diameter=4e-3, mu=3.0, load=1e4,
             material="polypropylene"),
        dict(knot="girth hitch", rod_diameter=6e-3, post_diameter=40e-3, mu=0.4, load=200.0,
             free_end_load=200.0, material="nylon"),
        dict(knot="lark's head", rod_diameter=4e-3, post_diameter=30e-3, mu=0.3, load=0.5,
             material="vps32"),
        dict(knot="rt2hh", rod_diameter=12e-3, post_diameter=0.1, mu=0.2, load=2e3,
             material="nylon"),
        dict(knot="clove-hitch", rod_diameter=4e-3, post_diameter=30e-3, mu=0.3, load=0.5,
             youngs_modulus=1.26e6, phase_table="knotmech/data/clove_phase_table.json"),
        dict(knot="clove-hitch", rod_diameter=4e-3, post_diameter=60e-3, mu=0.3, load=2.0,
             youngs_modulus=1.26e6, phase_table="knotmech/data/clove_phase_table_mu0.4.json"),
        dict(knot="cow-hitch", rod_diameter=6e-3, post_diameter=40e-3, mu=0.5, load=20.0,
             material="nylon", phase_table="knotmech/data/hold_phase_table_cow-hitch.json"),
        dict(knot="reef", rod_diameter=4e-3, mu=0.3, load=5.0),
        dict(knot="granny", rod_diameter=4e-3, mu=0.3, load=5.0, material="nylon"),
        dict(knot="thief-knot", rod_diameter=6e-3, mu=0.5, load=50.0, bending_scale=0.1),
        dict(knot="grief", rod_diameter=6e-3, mu=0.5, load=50.0, youngs_modulus=1e9),
    ]  # fmt: skip
    return qs


def _canon(obj):
    """Plain structure with floats exact (repr) and non-finite floats as strings."""
    if isinstance(obj, dict):
        return {str(k): _canon(v) for k, v in obj.items()}
    if isinstance(obj, list | tuple):
        return [_canon(v) for v in obj]
    if hasattr(obj, "item") and not isinstance(obj, bool | int | float | str):
        obj = obj.item()
    if isinstance(obj, float):
        return obj if math.isfinite(obj) else repr(obj)
    return obj


def _verdict_record(v) -> dict:
    rec = v.to_dict()
    rec["margin_exact"] = v.margin
    rec["answers_exact"] = [
        [a.model, a.holds, a.margin, a.capacity, a.critical_mu, a.decides, a.inside_validity]
        for a in v.answers
    ]
    rec["warnings_str"] = [str(w) for w in v.warnings]
    rec["summary"] = v.summary()
    return rec


def _hold_records() -> list:
    import knotmech

    out = []
    for q in _questions():
        kw = dict(q)
        knot = kw.pop("knot")
        with warnings.catch_warnings():
            warnings.simplefilter("ignore", DeprecationWarning)
            v = knotmech.hold(knot, **kw)
        out.append({"question": q, "verdict": _verdict_record(v)})
    return out


def _hold_answer(a) -> dict:
    return {
        "holds": a.holds,
        "inside": a.inside,
        "rule": a.rule,
        "message": a.message,
        "creep_speed": a.creep_speed,
        "capacity": a.capacity_t_over_EA,
        "first_slip": a.first_slip_t_over_EA,
        "critical": a.critical,
        "mu_tables": list(a.mu_tables),
        "corners": [[c.d_over_2R, c.t_over_EA, c.mu, c.creep_speed] for c in a.corners],
    }


def _phase_answer(a) -> dict:
    """A smooth-law table's answer (its fields; non-finite numbers as in :func:`_canon`)."""
    return {
        "holds": a.holds,
        "inside_table": a.inside,
        "critical_t_over_EA": a.critical,
        "bracket_t_over_EA": [float(v) for v in a.bracket],
        "message": a.message,
        "mu_tables": list(a.mu_tables),
    }


def _lookup_records() -> dict:
    from knotmech.scenes import phase_table as pt

    xs = (0.01, 0.01961, 0.03, 0.1176, 0.2, 0.2308, 0.3)
    ys = (3e-5, 1e-4, 5e-4, 0.01, 0.05, 0.3, 0.5)
    out = {}
    for knot, by_kappa in sorted(pt.load_hold_table_sets().items()):
        for kappa, table in sorted(by_kappa.items()):
            rows = []
            for x in xs:
                for y in ys:
                    for mu, mu_rr, lim in ((0.05, None, None), (0.3, None, None),
                                           (0.35, 0.2, None), (0.9, None, 1e-2),
                                           (0.5, None, 1e-4)):  # fmt: skip
                        kw = {"mu": mu, "mu_rr": mu_rr}
                        if lim is not None:
                            kw["creep_limit"] = lim
                        rows.append([x, y, mu, mu_rr, lim, _hold_answer(table.lookup(x, y, **kw))])
            out[f"{knot}@{kappa:g}"] = rows
    imc = pt.load_tables()
    rows = []
    for x in (0.03, 0.06, 0.09, 0.2, 0.3, 0.4):
        for y in (0.01, 0.03, 0.15, 0.3, 0.6):
            for mu, mu_rr in ((0.1, None), (0.3, None), (0.33, None), (0.45, 0.2), (0.7, None)):
                a = imc.lookup(x, y, mu=mu, mu_rr=mu_rr)
                rows.append([x, y, mu, mu_rr, _phase_answer(a), list(a.bracket), a.critical])
    out["imc-set"] = rows
    single = pt.load_table()
    out["imc-0.3"] = [
        [x, y, _phase_answer(single.lookup(x, y))]
        for x in (0.05, 0.1176, 0.25)
        for y in (0.02, 0.2)
    ]
    return out


def _table_hashes() -> dict:
    data = resources.files("knotmech") / "data"
    return {
        p.name: hashlib.sha256(p.read_bytes()).hexdigest()
        for p in sorted(data.iterdir(), key=lambda p: p.name)
        if p.name.endswith(".json")
    }


def _golden() -> dict:
    return _canon(
        {"hold": _hold_records(), "lookups": _lookup_records(), "tables": _table_hashes()}
    )


def test_golden_hold(monkeypatch):
    monkeypatch.chdir(Path(__file__).resolve().parents[2])  # table paths relative to the repo
    got = json.loads(json.dumps(_golden()))
    if os.environ.get("KNOTMECH_REGEN_GOLDEN"):
        GOLDEN.write_text(json.dumps(got, sort_keys=True, separators=(",", ":")) + "\n")
    want = json.loads(GOLDEN.read_text())
    assert got["tables"] == want["tables"]
    for g, w in zip(got["hold"], want["hold"], strict=True):
        assert g == w, g["question"]
    assert got["lookups"] == want["lookups"]
    assert len(got["hold"]) >= 40


@pytest.mark.slow
def test_golden_hold_simulate():
    """One short DER run each: a clove hitch ``simulate`` and its verdict's numbers."""
    import knotmech

    path = GOLDEN.with_name("golden_hold_simulate.json")
    v = knotmech.hold("clove-hitch", rod_diameter=4e-3, post_diameter=30e-3, mu=0.3,
                      load=1.0, material="vps32", simulate=True)  # fmt: skip
    got = json.loads(json.dumps(_canon({"verdict": _verdict_record(v)})))
    for drop in ("der",):  # wall-clock seconds are in the DER message
        got["verdict"].pop(drop, None)
    got["verdict"]["answers"] = [
        {k: a[k] for k in a if k != "notes"} for a in got["verdict"]["answers"]
    ]
    if os.environ.get("KNOTMECH_REGEN_GOLDEN"):
        path.write_text(json.dumps(got, indent=1, sort_keys=True) + "\n")
    assert got == json.loads(path.read_text())

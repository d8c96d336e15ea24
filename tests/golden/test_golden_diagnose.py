"""Golden reports of ``knotmech diagnose``: the refactor of ``diagnose/`` changes no number.

Eleven fixed diagnoses (the four shipped templates, the shipped yarn-rig recording,
six synthetic recordings with fixed seeds, one joint diagnosis of two recordings) were
run on the base commit (6966c06) and saved in ``golden_diagnose.json``: verdict, effects,
fitted parameters, held-out errors, the report's JSON and the baseline and final means
row by row. Compared with a relative tolerance of 1e-12 (float order may change when
code moves; a changed model or search changes far more). About 25 s of CPU, so marked
slow. Regenerate only on purpose::

    python tests/golden/test_golden_diagnose.py --write
"""

from __future__ import annotations

import json
import math
import sys
from pathlib import Path

import numpy as np
import pytest

from knotmech.diagnose import diagnose, diagnose_many, make_recording

HERE = Path(__file__).parent
GOLDEN = HERE / "golden_diagnose.json"
DATA = Path(__file__).resolve().parents[2] / "knotmech" / "data"
RTOL = 1e-12

#: name -> (experiment, effect, keyword arguments of make_recording)
SYNTH = {
    "capstan_pull_static_friction": ("capstan_pull", "static_friction", {"seed": 11}),
    "pinch_adhesion": ("pinch", "adhesion", {"seed": 12, "n": 120}),
    "tension_profile_nip": ("tension_profile", "self_contact_nip", {"seed": 13}),
    "knot_pull_null": ("knot_pull", None, {"seed": 14, "n": 80}),
    "capstan_hold_bending": ("capstan_hold", "bending_stiffness", {"seed": 15}),
    "pinch_ar1_null": ("pinch", None, {"seed": 16, "noise": "ar1", "rho": 0.8, "n": 100}),
}


def _clean(obj):
    """The report's JSON without wall-clock times (they differ from run to run)."""
    if isinstance(obj, dict):
        return {k: _clean(v) for k, v in obj.items() if "seconds" not in k}
    if isinstance(obj, list | tuple):
        return [_clean(v) for v in obj]
    if isinstance(obj, float) and not math.isfinite(obj):
        return repr(obj)
    if isinstance(obj, np.generic):
        return _clean(obj.item())
    return obj


def _record(report) -> dict:
    return {
        "verdict": report.verdict,
        "json": _clean(json.loads(json.dumps(report.to_dict(), default=str))),
        "baseline_mean": [float(v) for v in report.baseline_mean],
        "final_mean": [float(v) for v in report.final_mean],
    }


def _cases():
    for name in ("capstan_pull", "capstan_hold", "pinch", "tension_profile"):
        yield f"template_{name}", lambda n=name: diagnose(DATA / "templates" / f"{n}.csv")
    yield (
        "yarn_rig",
        lambda: diagnose(DATA / "recordings" / "capstan_yarn_rig.csv"),
    )
    for name, (kind, effect, kw) in SYNTH.items():

        def synth(k=kind, e=effect, kw=kw):
            return diagnose(make_recording(k, e, **kw)[0])

        yield f"synth_{name}", synth

    def joint():
        recs = [make_recording("pinch", "adhesion", seed=s, n=60)[0] for s in (21, 22)]
        return diagnose_many(recs)

    yield "joint_pinch_adhesion", joint


CASES = dict(_cases())


def _close(a, b, path=""):
    if isinstance(a, dict):
        assert set(a) == set(b), f"{path}: keys {sorted(set(a) ^ set(b))}"
        for k in a:
            _close(a[k], b[k], f"{path}.{k}")
    elif isinstance(a, list):
        assert len(a) == len(b), f"{path}: length {len(a)} != {len(b)}"
        for i, (u, v) in enumerate(zip(a, b, strict=True)):
            _close(u, v, f"{path}[{i}]")
    elif isinstance(a, float) and isinstance(b, float):
        assert math.isclose(a, b, rel_tol=RTOL, abs_tol=1e-300), f"{path}: {a!r} != {b!r}"
    else:
        assert a == b, f"{path}: {a!r} != {b!r}"


@pytest.mark.slow
@pytest.mark.parametrize("name", list(CASES))
def test_golden_diagnose(name):
    expected = json.loads(GOLDEN.read_text())[name]
    _close(_record(CASES[name]()), expected, name)


if __name__ == "__main__":  # pragma: no cover - regenerates the golden file
    if "--write" not in sys.argv:
        raise SystemExit("usage: python tests/golden/test_golden_diagnose.py --write")
    out = {}
    for name, run in CASES.items():
        out[name] = _record(run())
        print(name, out[name]["verdict"], flush=True)
    GOLDEN.write_text(json.dumps(out, indent=1, sort_keys=True) + "\n")

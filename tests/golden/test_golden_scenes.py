"""Golden runs of every DER scene: the refactor of the scenes into phases (issue 22) keeps
them bit for bit.

Each case is a short run of one scene; every field of its result is fingerprinted
(:func:`fingerprint`): floats to full precision (``float.hex``), arrays by the SHA-256 of
their float64 bytes plus their shape, strings and flags as they are. The solver path is
unchanged by the refactor, so the comparison is **bit-identical** (no tolerance). The
stored values are ``golden_scenes.json`` next to this file; regenerate them (only on a
commit whose numbers are the reference) with ``KNOTMECH_REGEN_GOLDEN=1 pytest
tests/golden/test_golden_scenes.py``. Wall-clock times (``stats["wall_s"]``) are left out.
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import os
from pathlib import Path

import numpy as np
import pytest

from knotmech import scenes

GOLDEN = Path(__file__).with_name("golden_scenes.json")

D_ROD, E_VPS = 4e-3, 1.26e6
EA = E_VPS * np.pi * D_ROD**2 / 4


def _capstan_kw(D_over_d=2.0):
    D = D_over_d * D_ROD
    R = 0.5 * (D + D_ROD)
    return dict(
        wrap_angle=np.pi,
        mu=0.5,
        rod_diameter=D_ROD,
        post_diameter=D,
        youngs_modulus=E_VPS,
        bending_stiffness=1e-4 * EA * R**2,
        t_low=0.01 * EA,
        n_elements=40,
    )


def _quarter_circle(n=20, radius=0.05):
    phi = np.linspace(0.0, 0.5 * np.pi, n)
    return np.column_stack([radius * np.cos(phi), radius * np.sin(phi), np.zeros(n)])


_HITCH_QUICK = dict(n_nodes=100, settle_time=0.05, load_time=0.05, hold_time=0.05, n_frames=11)

#: name -> (runner, slow)
CASES = {
    "capstan_pull": (lambda: scenes.capstan.capstan(**_capstan_kw(), pull_distance=2e-3), False),
    "capstan_hold": (
        lambda: scenes.capstan.capstan(
            **_capstan_kw(), mode="hold", t_high=0.015 * EA, hold_time=0.1, ramp_time=0.05
        ),
        False,
    ),
    "capstan_two_loops": (
        lambda: scenes.capstan_two_loops(n_elements=120, pull_distance=1e-3),
        False,
    ),
    "pinch": (
        lambda: scenes.pinch.pinch(normal_load=0.3, mu=0.5, n_elements=60, pull_distance=2e-3),
        False,
    ),
    "clove_hitch_free": (
        lambda: scenes.clove_hitch.clove_hitch(loading="free", t_high=1.47, **_HITCH_QUICK),
        False,
    ),
    "clove_hitch_pull": (
        lambda: scenes.clove_hitch.clove_hitch(
            loading="pull",
            t_low=0.069,
            mu_rod_post=0.32,
            mu_rod_rod=0.32,
            n_nodes=100,
            settle_time=0.05,
            load_time=0.05,
            pull_distance=1e-3,
            n_frames=11,
        ),
        False,
    ),
    "two_half_hitches_free": (
        lambda: scenes.two_half_hitches(loading="free", t_high=0.3, **_HITCH_QUICK),
        False,
    ),
    "overhand_n1": (
        lambda: scenes.overhand.overhand(
            1,
            0.3,
            n_frames=11,
            n_nodes=101,
            pull_speed=0.03,
            dt=5e-3,
            wait_time=0.05,
            pull_time=0.3,
        ),
        False,
    ),
    "bend_reef": (
        lambda: scenes.bend(
            "reef", n_nodes=80, settle_time=0.02, set_travel=1e-3, pull_distance=2e-3, n_frames=10
        ),
        False,
    ),
    "centreline_quarter_circle": (
        lambda: scenes.centreline.centreline(
            _quarter_circle(),
            ends=[("fixed", "pull")],
            rod_diameter=4e-3,
            youngs_modulus=1e6,
            density=1100.0,
            mu_rod_rod=0.3,
            n_nodes=30,
            settle_time=0.02,
            pull_distance=1e-3,
            n_frames=10,
        ),
        False,
    ),
    "two_half_hitches_pull": (
        lambda: scenes.two_half_hitches(
            loading="pull",
            t_low=0.069,
            n_nodes=100,
            settle_time=0.1,
            load_time=0.1,
            pull_distance=2e-3,
            n_frames=11,
        ),
        True,
    ),
    "bend_granny_longer": (
        lambda: scenes.bend(
            "granny", n_nodes=80, settle_time=0.05, pull_distance=6e-3, n_frames=10
        ),
        True,
    ),
}


def _value(v):
    if isinstance(v, np.ndarray) or (
        isinstance(v, (list, tuple)) and v and isinstance(v[0], np.ndarray)
    ):
        a = np.ascontiguousarray(np.asarray(v))
        if a.dtype == object:
            return [_value(x) for x in v]
        a = a.astype(np.float64) if a.dtype.kind in "fiub" else a
        return {"shape": list(a.shape), "sha256": hashlib.sha256(a.tobytes()).hexdigest()}
    if isinstance(v, (bool, np.bool_)) or v is None:
        return None if v is None else bool(v)
    if isinstance(v, (int, np.integer)):
        return int(v)
    if isinstance(v, (float, np.floating)):
        return float(v).hex()
    if isinstance(v, dict):
        return {str(k): _value(x) for k, x in sorted(v.items()) if k != "wall_s"}
    if isinstance(v, (list, tuple)):
        return [_value(x) for x in v]
    if dataclasses.is_dataclass(v):
        return fingerprint(v)
    return str(v)


def fingerprint(result) -> dict:
    """Every field of a result dataclass, fingerprinted (see the module docstring)."""
    return {f.name: _value(getattr(result, f.name)) for f in dataclasses.fields(result)}


def _stored() -> dict:
    return json.loads(GOLDEN.read_text()) if GOLDEN.exists() else {}


@pytest.mark.parametrize(
    "name",
    [pytest.param(k, marks=[pytest.mark.slow] if slow else []) for k, (_, slow) in CASES.items()],
)
def test_scene_is_bit_identical_to_its_golden_run(name):
    got = fingerprint(CASES[name][0]())
    if os.environ.get("KNOTMECH_REGEN_GOLDEN"):
        data = _stored()
        data[name] = got
        GOLDEN.write_text(json.dumps(data, indent=1, sort_keys=True) + "\n")
        return
    want = _stored()[name]
    assert got.keys() == want.keys()
    diff = [k for k in want if got[k] != want[k]]
    assert not diff, f"{name}: fields changed: {diff}"

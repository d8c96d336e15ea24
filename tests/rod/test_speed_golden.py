"""Golden runs guarding the solver's speed work (issue 24): compared bit for bit.

A few short runs through the implicit step with contact: the overhand n = 1 (imc
parameters, 101 nodes) for a few steps with the regularised (``imc``) and the anchor
rod-rod law, a capstan pull over a post, and a clove-hitch slice (rod-post and rod-rod
anchor friction). Each records the final node positions (``float.hex``), the recorded
pull forces and the step, Newton and rejection counts. ``tests/golden/speed_golden.json``
was written on the base commit 9a101fa, before any optimisation, by

    PYTHONPATH=. python tests/rod/test_speed_golden.py write tests/golden/speed_golden.json

and is compared BIT-IDENTICALLY: the optimisations move work, they do not reorder any
arithmetic. ``overhand_anchor`` and ``clove_pull`` were regenerated on branch ``law``
(issue 24: the anchor law's default became cap_floor 1e-2 with the path guard);
``clove_pull`` went back, bit for bit, to its value of before that branch in session 13,
when the hitch scenes returned to cap floor 0 (152 steps, 835 Newton iterations, 28
rejected, against 59 steps with the floor). Session 15: the hitches take the library's
anchor law again, whose floor rule "min" floors their caps at the penalty's width
(sticking-law-cap-width.md sec. 11): ``clove_pull`` regenerated (93 steps, 459 Newton
iterations, 12 rejected; final force 0.6099 -> 0.5937 N).
"""

import json
import sys
from pathlib import Path

import numpy as np
import pytest

GOLDEN = Path(__file__).parents[1] / "golden" / "speed_golden.json"
OVERHAND = dict(n_nodes=101, wait_time=0.05, pull_time=0.1, dt=0.01, n_frames=4)


def _hexes(values):
    return [float(v).hex() for v in np.ravel(values)]


def _record(positions, force, stats):
    return dict(
        positions=_hexes(positions),
        force=_hexes(force),
        steps=int(stats["steps"]),
        newton_iterations=int(stats["newton_iterations"]),
        rejected_steps=int(stats["rejected_steps"]),
    )


def _overhand(law):
    from knotmech.scenes.overhand import overhand

    r = overhand(1, 0.3, friction=law, **OVERHAND)
    return _record(r.snapshots[-1], r.pull_force, r.stats)


def _capstan():
    from knotmech.scenes.capstan import capstan

    d, e = 4e-3, 1.26e6
    ea = e * np.pi * d**2 / 4
    r = capstan(wrap_angle=np.pi, mu=0.5, rod_diameter=d, post_diameter=2 * d,
                youngs_modulus=e, bending_stiffness=1e-4 * ea * (1.5 * d) ** 2,
                t_low=0.01 * ea, n_elements=40, pull_distance=2e-3)  # fmt: skip
    return _record(r.positions[-1], r.tension, r.stats)


def _clove():
    from knotmech.scenes.clove_hitch import clove_hitch

    r = clove_hitch(loading="pull", t_low=0.069, mu_rod_post=0.32, mu_rod_rod=0.32,
                    n_nodes=120, settle_time=0.05, load_time=0.05, pull_speed=0.02,
                    pull_distance=0.001, n_frames=3)  # fmt: skip
    return _record(r.positions[-1], r.pull_force, r.stats)


CASES = {
    "overhand_imc": lambda: _overhand("imc"),
    "overhand_anchor": lambda: _overhand("anchor"),
    "capstan": _capstan,
    "clove_pull": _clove,
}


@pytest.mark.parametrize("name", sorted(CASES))
def test_speed_golden_run_is_bit_identical(name):
    want = json.loads(GOLDEN.read_text())[name]
    got = CASES[name]()
    for key in ("steps", "newton_iterations", "rejected_steps", "force", "positions"):
        assert got[key] == want[key], key


if __name__ == "__main__" and sys.argv[1:2] == ["write"]:
    path = Path(sys.argv[2])
    names = sys.argv[3:] or sorted(CASES)
    data = json.loads(path.read_text()) if path.exists() else {}
    for nm in names:
        data[nm] = CASES[nm]()
        print(nm, data[nm]["steps"], data[nm]["newton_iterations"], data[nm]["rejected_steps"])
    path.write_text(json.dumps(data, indent=0))

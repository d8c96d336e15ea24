"""Golden runs of the DER solver: the refactoring of ``rod/`` keeps them bit for bit.

A fixed set of short runs (a cantilever under gravity; a rod over a post with anchor
friction, sticking and then sliding, with and without the surface couple; a prescribed pull
and twist; a run stopped by the strain guard; a run stopped by a callback; two crossing rods
with anchor friction, which exercises the reordered band solver and its reused LU factors;
a checkpoint written, read back and resumed) records final positions, twist angles,
reactions, the recorded frames, contact forces, and the step, Newton and rejection counts.
The numbers in ``golden_rod.json`` were written on the commit before the refactoring
(``python tests/golden/test_golden_rod.py --write``) and are compared BIT-IDENTICALLY
(``np.array_equal``; JSON keeps a float's 17 significant digits, so the round trip is exact):
the refactoring only moved code, it did not reorder any arithmetic.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

import numpy as np
import pytest

from knotmech import rod
from knotmech.rod import (
    Clamp,
    Cylinder,
    CylinderContact,
    Gravity,
    MovingNodes,
    Rod,
    RodContact,
    RodSystem,
    RotatingEdges,
    SolverOptions,
    State,
    ViscousDamping,
    simulate,
)
from knotmech.rod.friction import AnchorFriction

GOLDEN = Path(__file__).with_name("golden_rod.json")
R = 1e-3


def _summary(res, contact=None) -> dict:
    """The recorded numbers of one run (arrays as nested lists of floats)."""
    out = {
        "status": res.status,
        "message": res.message,
        "steps": res.stats["steps"],
        "newton_iterations": res.stats["newton_iterations"],
        "rejected_steps": res.stats["rejected_steps"],
        "times": res.times,
        "q_final": res.final_state.q,
        "v_final": res.final_state.v,
        "dt_next": res.final_state.dt_next,
        "positions_last": res.positions[-1],
        "reactions": res.reactions,
        "reaction_torques": res.reaction_torques,
        "tension_last": res.tension[-1],
        "bending_moment_last": res.bending_moment[-1],
        "twisting_moment_last": res.twisting_moment[-1],
        "energies": {k: v for k, v in res.energies.items()},
    }
    if contact is not None:
        out["normal_force"] = contact.normal_force
        out["friction_force"] = contact.friction_force
        out["sliding"] = np.asarray(contact.sliding, dtype=float)
    return out


def cantilever():
    r = Rod.straight(length=0.1, n_nodes=21, radius=R, youngs_modulus=1e6, density=1200.0)
    system = RodSystem([r])
    res = simulate(system, t_end=0.1, dt=2e-3, loads=[Gravity(), ViscousDamping(0.01)],
                   constraints=[rod.clamp_end(system)],
                   options=SolverOptions(save_every=0.02))  # fmt: skip
    return _summary(res)


def _post_system():
    n = 21
    x = np.linspace(-0.03, 0.03, n)
    pts = np.stack([x, 0 * x, 0 * x + 5e-3 + R - 2e-5], 1)
    return RodSystem([Rod(positions=pts, radius=R, youngs_modulus=1e6, density=1000.0)]), n


def _post_contact(surface: bool):
    post = Cylinder(point=(0, 0, 0), axis=(0, 1, 0), radius=5e-3)
    fr = AnchorFriction(mu_static=0.5, mu_kinetic=0.3, tangential_stiffness=1e4)
    return CylinderContact((post,), stiffness=1e4, sharpness=2e4, friction=fr,
                           surface_friction=surface)  # fmt: skip


def capstan(surface: bool, velocity):
    """A rod over a post (axis y), one end clamped, the other pulled: sticks, then slides."""
    system, n = _post_system()
    contact = _post_contact(surface)
    cons = [Clamp(nodes=[0]), MovingNodes(nodes=[n - 1], velocity=velocity)]
    res = simulate(system, t_end=0.08, dt=2e-3, loads=[Gravity()], constraints=cons,
                   interactions=[contact], options=SolverOptions(save_every=0.02))  # fmt: skip
    return _summary(res, contact)


def capstan_sparse():
    """The same over the sparse (SuperLU) solver path."""
    system, n = _post_system()
    contact = _post_contact(True)
    cons = [Clamp(nodes=[0]), MovingNodes(nodes=[n - 1], velocity=(0.02, 0.01, -0.05))]
    res = simulate(system, t_end=0.03, dt=2e-3, loads=[Gravity()], constraints=cons,
                   interactions=[contact],
                   options=SolverOptions(linear_solver="sparse"))  # fmt: skip
    return _summary(res, contact)


def pull_and_twist():
    """Prescribed pull of one end along the axis and twist of its edge, the other clamped."""
    r = Rod.straight(length=0.05, n_nodes=11, radius=R, youngs_modulus=1e6, density=1000.0)
    system = RodSystem([r])
    cons = [Clamp(nodes=[0, 1], edges=[0]),
            MovingNodes(nodes=[10], velocity=(0.05, 0.0, 0.002)),
            RotatingEdges(edges=[9], rate=20.0)]  # fmt: skip
    res = simulate(system, t_end=0.05, dt=5e-3, constraints=cons, loads=[Gravity()],
                   options=SolverOptions(predictor="linear"))  # fmt: skip
    return _summary(res)


def strain_guard():
    """A pull so fast that the strain guard stops the run (status failed, not raised)."""
    r = Rod.straight(length=0.02, n_nodes=6, radius=R, youngs_modulus=1e6, density=1000.0)
    system = RodSystem([r])
    cons = [Clamp(nodes=[0]), MovingNodes(nodes=[5], velocity=(2.0, 0.0, 0.0))]
    res = simulate(system, t_end=0.05, dt=5e-3, constraints=cons,
                   options=SolverOptions(max_strain=0.5), throw=False)  # fmt: skip
    return _summary(res)


def tunnelling_failure():
    """A rod pushed through the post: the tunnelling guard rejects steps, dt is halved and
    grown back, and the run fails below dt_min (status failed, not raised)."""
    system, n = _post_system()
    contact = _post_contact(True)
    cons = [Clamp(nodes=[0]), MovingNodes(nodes=[n - 1], velocity=(0.0, 0.0, -0.5))]
    res = simulate(system, t_end=0.06, dt=1e-2, loads=[Gravity()], constraints=cons,
                   interactions=[contact], throw=False)  # fmt: skip
    return _summary(res, contact)


def callback_stop():
    r = Rod.straight(length=0.1, n_nodes=11, radius=R, youngs_modulus=1e6, density=1200.0)
    system = RodSystem([r])
    res = simulate(system, t_end=1.0, dt=3e-3, loads=[Gravity()],
                   constraints=[rod.clamp_end(system)],
                   options=SolverOptions(save_every=0.01),
                   callback=lambda st: st.t > 0.02)  # fmt: skip
    return _summary(res)


def _crossing():
    n = 21
    s = np.linspace(-0.03, 0.03, n)
    a = np.stack([s, 0 * s, 0 * s], 1)
    b = np.stack([0 * s + 1.3e-3, s, 0 * s + 2 * R + 1e-5], 1)
    rods = [Rod(positions=p, radius=R, youngs_modulus=1e6, density=1000.0) for p in (a, b)]
    cons = [Clamp(nodes=[0, n - 1], edges=[0, n - 2]),
            MovingNodes(nodes=[n, 2 * n - 1], velocity=(0.02, 0.0, -0.01))]  # fmt: skip
    return RodSystem(rods), cons


def _crossing_contact():
    return RodContact(stiffness=50.0, sharpness=1 / (0.05 * R),
                      friction=AnchorFriction(mu_static=0.5, mu_kinetic=0.3))  # fmt: skip


def crossing_rods():
    system, cons = _crossing()
    res = simulate(system, t_end=0.06, dt=2e-3, constraints=cons,
                   interactions=[_crossing_contact()],
                   options=SolverOptions(save_every=0.02))  # fmt: skip
    return _summary(res)


def resume(tmp: Path):
    """Half a capstan run, checkpointed to disk, read back and resumed with fresh contacts."""
    system, n = _post_system()
    cons = [Clamp(nodes=[0]), MovingNodes(nodes=[n - 1], velocity=(0.02, 0.01, -0.05))]
    kw = dict(dt=2e-3, loads=[Gravity()], constraints=cons,
              options=SolverOptions(save_every=0.01))  # fmt: skip
    half = simulate(system, t_end=0.04, interactions=[_post_contact(True)], **kw)
    path = tmp / "state.npz"
    half.final_state.save(path)
    contact = _post_contact(True)
    rest = simulate(system, State.load(path), t_end=0.08, interactions=[contact], **kw)
    return {"half": _summary(half), "rest": _summary(rest, contact)}


CASES = {
    "cantilever": cantilever,
    "capstan_surface_slide": lambda: capstan(True, (0.02, 0.01, -0.05)),
    "capstan_centreline_stick": lambda: capstan(False, (0.0, 0.0, -0.01)),
    "capstan_sparse": capstan_sparse,
    "pull_and_twist": pull_and_twist,
    "strain_guard": strain_guard,
    "tunnelling_failure": tunnelling_failure,
    "callback_stop": callback_stop,
    "crossing_rods": crossing_rods,
}


def _plain(x):
    """Nested lists of Python floats/str (JSON); floats keep all 17 digits."""
    if isinstance(x, dict):
        return {k: _plain(v) for k, v in x.items()}
    if isinstance(x, np.ndarray):
        return x.tolist()
    if isinstance(x, (np.floating, np.integer, np.bool_)):
        return x.item()
    return x


def run_case(name: str, tmp: Path) -> dict:
    return _plain(resume(tmp) if name == "resume" else CASES[name]())


def _compare(got, want, where: str) -> None:
    if isinstance(want, dict):
        assert sorted(got) == sorted(want), where
        for k in want:
            _compare(got[k], want[k], f"{where}.{k}")
    elif isinstance(want, str):
        assert got == want, where
    else:
        g = np.asarray(got, dtype=float)
        w = np.asarray(want, dtype=float)
        assert g.shape == w.shape, where
        assert np.array_equal(g, w, equal_nan=True), (
            f"{where}: max |diff| {np.nanmax(np.abs(g - w)) if g.size else 0:.3e}"
        )


@pytest.fixture(scope="module")
def golden() -> dict:
    return json.loads(GOLDEN.read_text())


@pytest.mark.parametrize("name", [*CASES, "resume"])
def test_golden_run_is_bit_identical(name, golden, tmp_path):
    got = json.loads(json.dumps(run_case(name, tmp_path)))
    _compare(got, golden[name], name)


def test_golden_cases_exercise_what_they_claim(golden):
    """The set covers sticking and sliding, the step halving and both stop paths."""
    for name, slides in (("capstan_surface_slide", 1.0), ("capstan_centreline_stick", 0.0)):
        sliding = np.array(golden[name]["sliding"])[:, 0]
        normal = np.array(golden[name]["normal_force"])[:, 0]
        assert normal.max() > 1e-3  # [N] the rod presses on the post
        assert sliding[np.argmax(normal)] == slides  # where it presses most: slides/sticks
    assert golden["strain_guard"]["status"] == "failed"
    assert "max_strain" in golden["strain_guard"]["message"]
    fail = golden["tunnelling_failure"]
    assert fail["status"] == "failed" and "dt_min" in fail["message"]
    assert fail["rejected_steps"] > 10 and fail["steps"] > 10
    assert "callback" in golden["callback_stop"]["message"]


def main() -> None:
    """``--write``: regenerate golden_rod.json (only on the commit before a refactoring)."""
    import tempfile

    if "--write" not in sys.argv:
        raise SystemExit("usage: python tests/golden/test_golden_rod.py --write")
    with tempfile.TemporaryDirectory() as tmp:
        data = {name: run_case(name, Path(tmp)) for name in [*CASES, "resume"]}
    GOLDEN.write_text(json.dumps(data, allow_nan=True) + "\n")
    print(f"wrote {GOLDEN}")


if __name__ == "__main__":
    main()

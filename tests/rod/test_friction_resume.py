"""Checkpoint and resume with friction state: bit-identical in a new process.

The rod-post and rod-rod friction anchors are state committed at every accepted step; a
checkpoint (``State.save``) carries them, so that resuming from ``State.load`` with freshly
built contact objects, as a new process does, repeats the uninterrupted run bit for bit.
Without them (the state of a run before they were saved) the resumed run differs, which
shows that the test can fail.

With rod-rod contact (either friction law) the checkpoint also carries the solver's
linear-algebra state (``State.linear``: the RCM ordering of the contact Jacobian, kept for
up to 100 Jacobians, and the LU factors that the next step may reuse): the resumed run is
bit-identical too. Without it a new solver orders and factors afresh, and the run agrees
only to round-off (seen: 9e-19 m with the anchor law, 2e-18 m with the regularised law).
"""

from dataclasses import replace

import numpy as np
import pytest

from knotmech.errors import InputError
from knotmech.rod import Clamp, Gravity, MovingNodes, Rod, RodSystem, SolverOptions, State, simulate
from knotmech.rod.contact import Cylinder, CylinderContact, RodContact
from knotmech.rod.friction import AnchorFriction, SmoothFriction

R = 1e-3


def post_problem():
    """A rod over a post (axis y), one end pulled down and sideways: it sticks, then slides."""
    n = 21
    x = np.linspace(-0.03, 0.03, n)
    pts = np.stack([x, 0 * x, 0 * x + 5e-3 + R - 2e-5], 1)
    system = RodSystem([Rod(positions=pts, radius=R, youngs_modulus=1e6, density=1000.0)])

    def interactions():
        post = Cylinder(point=(0, 0, 0), axis=(0, 1, 0), radius=5e-3)
        fr = AnchorFriction(mu_static=0.5, mu_kinetic=0.3, tangential_stiffness=1e4)
        return [CylinderContact((post,), stiffness=1e4, sharpness=2e4, friction=fr)]

    cons = [
        Clamp(nodes=[0]),
        MovingNodes(nodes=[n - 1], velocity=(0.02, 0.01, -0.05)),
    ]
    return system, cons, [Gravity()], interactions


def rodrod_problem(law="anchor"):
    """Rod 1 pressed onto the crossing rod 0 and dragged along it (anchor or imc law)."""
    n = 21
    s = np.linspace(-0.03, 0.03, n)
    a = np.stack([s, 0 * s, 0 * s], 1)
    b = np.stack([0 * s + 1.3e-3, s, 0 * s + 2 * R + 1e-5], 1)
    rods = [Rod(positions=p, radius=R, youngs_modulus=1e6, density=1000.0) for p in (a, b)]
    system = RodSystem(rods)

    def interactions():
        if law == "anchor":
            fr = AnchorFriction(mu_static=0.5, mu_kinetic=0.3)
        elif law == "floored":
            fr = AnchorFriction(mu_static=0.5, mu_kinetic=0.3, cap_floor=1e-2)
        elif law in ("penalty", "sliding", "min"):
            fr = AnchorFriction(mu_static=0.5, mu_kinetic=0.3, floor_rule=law)
        else:
            fr = SmoothFriction(0.5)
        return [RodContact(stiffness=50.0, sharpness=1 / (0.05 * R), friction=fr)]

    cons = [
        Clamp(nodes=[0, n - 1], edges=[0, n - 2]),
        MovingNodes(nodes=[n, 2 * n - 1], velocity=(0.02, 0.0, -0.01)),
    ]
    return system, cons, [], interactions


def same(a, b, exact):
    return np.array_equal(a, b) if exact else np.allclose(a, b, rtol=0, atol=1e-15)


def rodrod_imc():
    return rodrod_problem("imc")


@pytest.mark.parametrize(
    "problem, exact", [(post_problem, True), (rodrod_problem, True), (rodrod_imc, True)]
)
def test_resume_from_a_checkpoint_with_fresh_contacts_is_bit_identical(problem, exact, tmp_path):
    system, cons, loads, interactions = problem()
    kw = dict(dt=2e-3, loads=loads, constraints=cons, options=SolverOptions(save_every=0.01))
    full = simulate(system, t_end=0.1, interactions=interactions(), **kw)
    assert full.success
    half = simulate(system, t_end=0.05, interactions=interactions(), **kw)
    path = tmp_path / "state.npz"
    half.final_state.save(path)
    back = State.load(path)
    rest = simulate(system, back, t_end=0.1, interactions=interactions(), **kw)
    assert same(rest.final_state.q, full.final_state.q, exact)
    assert same(rest.positions, full.positions[5:], exact)
    if exact:
        assert np.array_equal(rest.reactions[1:], full.reactions[6:])
    # the friction state matters: without it the resumed run ends elsewhere
    bare = simulate(system, replace(back, interactions=None), t_end=0.1,
                    interactions=interactions(), **kw)  # fmt: skip
    if problem is not rodrod_imc:  # the regularised law is stateless
        assert np.abs(bare.final_state.q - full.final_state.q).max() > 1e-9
    if problem is not post_problem:
        # rod-rod contact: the solver's ordering and LU factors carried by the state are
        # what makes it bit for bit (without them: round-off, 1e-18 m)
        assert back.linear is not None and bool(back.linear["factors_valid"])
        nolin = simulate(system, replace(back, linear=None), t_end=0.1,
                         interactions=interactions(), **kw)  # fmt: skip
        diff = np.abs(nolin.final_state.q - full.final_state.q).max()
        assert 0 < diff < 1e-15
    # and the Result file carries it too
    half.save(tmp_path / "res.npz")
    from knotmech.rod import load_result

    again = simulate(system, load_result(tmp_path / "res.npz").final_state, t_end=0.1,
                     interactions=interactions(), **kw)  # fmt: skip
    assert same(again.final_state.q, full.final_state.q, exact)


def test_state_with_friction_needs_the_interactions_that_wrote_it():
    system, cons, loads, interactions = post_problem()
    kw = dict(dt=2e-3, loads=loads, constraints=cons)
    half = simulate(system, t_end=0.01, interactions=interactions(), **kw)
    with pytest.raises(InputError, match="interaction 0"):
        simulate(system, half.final_state, t_end=0.02, **kw)


def test_solver_state_for_other_constraints_is_not_applied():
    """A checkpoint resumed with other constrained dofs (the next phase of a scene) starts
    with a fresh ordering: the saved one numbers other free dofs (it used to corrupt memory)."""
    system, cons, loads, interactions = rodrod_problem()
    kw = dict(dt=2e-3, loads=loads, options=SolverOptions(save_every=0.01))
    half = simulate(system, t_end=0.02, constraints=cons, interactions=interactions(), **kw)
    assert half.final_state.linear is not None
    more = cons + [Clamp(nodes=[10])]
    rest = simulate(system, half.final_state, t_end=0.04, constraints=more,
                    interactions=interactions(), **kw)  # fmt: skip
    fresh = simulate(system, replace(half.final_state, linear=None), t_end=0.04,
                     constraints=more, interactions=interactions(), **kw)  # fmt: skip
    assert rest.success and np.array_equal(rest.final_state.q, fresh.final_state.q)


@pytest.mark.parametrize("law", ["floored", "penalty", "sliding", "min"])
def test_resume_with_the_floored_anchor_cap_is_bit_identical(tmp_path, law):
    """The anchor law with ``cap_floor`` (no state of its own, whichever ``floor_rule``)
    resumes bit for bit too."""
    test_resume_from_a_checkpoint_with_fresh_contacts_is_bit_identical(
        lambda: rodrod_problem(law), True, tmp_path
    )

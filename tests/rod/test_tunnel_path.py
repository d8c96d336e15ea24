"""The tunnelling guard's path test (``RodContact(tunnel_check="path")``, issue 24).

A step that moves a contact node more than ``max_displacement`` radii is kept when no
candidate pair passes through itself on the straight path between the two states, and
rejected when one does (or when the jump is beyond ``PATH_LIMIT`` times the bound). Two
rods cross at right angles, B resting on A (centrelines 2 r apart); B's middle node is
moved by hand and the guard is asked about the step.
"""

import numpy as np
import pytest
from test_contact_sim import _hard_push

from knotmech.errors import InputError
from knotmech.rod.contact import PATH_LIMIT, RodContact
from knotmech.rod.system import Rod, RodSystem

R = 1e-3


@pytest.fixture(scope="module")
def crossed():
    rod_a = Rod(positions=[[0, 0, 0], [0.01, 0, 0], [0.02, 0, 0]], radius=R,
                youngs_modulus=1e6, density=1000.0)  # fmt: skip
    rod_b = Rod(positions=[[0.01, -0.01, 2 * R], [0.01, 0, 2 * R], [0.01, 0.01, 2 * R]],
                radius=R, youngs_modulus=1e6, density=1000.0)  # fmt: skip
    system = RodSystem((rod_a, rod_b))
    return system, system.initial_state().q


def _verdicts(system, q0, move, check):
    """(displacement guard rejects, path guard rejects) for B's middle node moved by
    ``move`` (3,) [m]."""
    out = []
    for mode in ("displacement", check):
        c = RodContact(stiffness=1.0, sharpness=1.0 / R, max_displacement=0.5, tunnel_check=mode)
        c.begin_step(system, q0, np.zeros_like(q0), 0.01)
        assert c.pairs.shape[0] > 0
        q1 = q0.copy()
        q1[system.node_dofs[4]] += move
        out.append(c.check_step(system, q1, q0, 0.01) is not None)
    return tuple(out)


@pytest.mark.parametrize(
    "move, want",
    [
        ((0.0, 0.0, -0.4 * R), (False, False)),  # within the bound: both keep it
        ((3.0 * R, 0.0, 0.0), (True, False)),  # slides 3 r along A: no crossing
        ((0.0, 3.0 * R, 0.0), (True, False)),  # slides 3 r along itself
        ((0.0, 0.0, -0.8 * R), (True, False)),  # sinks 0.8 r into A: gap 0.6 of 2 r
        ((0.0, 0.0, -1.2 * R), (True, True)),  # 1.2 r: gap 0.4 of 2 r, too close
        ((0.0, 0.0, -3.5 * R), (True, True)),  # through A to the other side
    ],
)
def test_path_guard_rejects_crossings_not_slides(crossed, move, want):
    system, q0 = crossed
    assert _verdicts(system, q0, np.array(move), "path") == want


def test_path_guard_rejects_jumps_beyond_the_limit(crossed):
    system, q0 = crossed
    far = (PATH_LIMIT * 0.5 + 0.1) * R  # along A: no crossing, but beyond the limit
    assert _verdicts(system, q0, np.array([far, 0.0, 0.0]), "path") == (True, True)


def test_path_guard_keeps_the_crossing_order_of_a_hard_push(monkeypatch):
    import knotmech.rod.contact as contact

    orig = contact.RodContact.__post_init__

    def with_path(self):
        self.tunnel_check = "path"
        orig(self)

    monkeypatch.setattr(contact.RodContact, "__post_init__", with_path)
    res, dmin, dz = _hard_push(0.5)
    assert res.status == "success", res.message
    assert res.stats["rejected_steps"] > 0  # the guard cut the step
    assert np.all(dz > 0)  # B stays above A at the crossing
    assert dmin.min() > 0.5 * R  # never through
    assert res.positions[-1, 41, 2] < -30 * R  # the ends really went 40 r down


def test_tunnel_check_is_checked():
    with pytest.raises(InputError, match="tunnel_check"):
        RodContact(stiffness=1.0, sharpness=1.0, tunnel_check="sweep")


def test_path_guard_checks_edges_outside_the_candidate_list():
    """B slides 3 r along A (trips the displacement bound, crosses nothing) while rod C,
    5 r above A and no candidate of the step (margin 0), drops 10 r through A: the path
    test finds the crossing with pairs of its own."""
    mk = dict(radius=R, youngs_modulus=1e6, density=1000.0)
    rod_a = Rod(positions=[[0, 0, 0], [0.01, 0, 0], [0.02, 0, 0]], **mk)
    rod_b = Rod(positions=[[0.015, -0.01, 1.9 * R], [0.015, 0, 1.9 * R],
                           [0.015, 0.01, 1.9 * R]], **mk)  # fmt: skip
    rod_c = Rod(positions=[[0.005, -0.01, 5 * R], [0.005, 0, 5 * R], [0.005, 0.01, 5 * R]], **mk)
    system = RodSystem((rod_a, rod_b, rod_c))
    q0 = system.initial_state().q
    c = RodContact(stiffness=1.0, sharpness=1.0 / R, margin=0.0, tunnel_check="path")
    c.begin_step(system, q0, np.zeros_like(q0), 0.01)
    rods = system.edge_rod[c.pairs]
    assert np.any((rods[:, 0] == 0) & (rods[:, 1] == 1))  # A-B listed
    assert not np.any((rods[:, 0] == 0) & (rods[:, 1] == 2))  # A-C not listed
    q1 = q0.copy()
    q1[system.node_dofs[4, 0]] += 3 * R  # B's middle node slides along A
    assert c.check_step(system, q1, q0, 0.01) is None
    q1[system.node_dofs[7, 2]] -= 10 * R  # C's middle node drops through A
    assert "came within" in c.check_step(system, q1, q0, 0.01)

"""Two rods twisted together (a two-rod braid) hold a load below their pull-out load.

Rod B (a helix of radius r, pitch 30 mm, two turns; naturally helical) is held at both
ends; rod A, the other strand of the double helix (centrelines 2r apart, naturally
helical too, 20 mm tails), carries a dead back-tension T_low at its left end and a load F
at its right end, along the axis. The friction of the helical contact holds F up to the
pull-out load F_po, above T_low and below the ideal-rope capstan bound
T_low exp(mu kappa l) (kappa the helix curvature, l the length in contact). First F is
ramped until A slides (F_po), then F = 0.8 F_po is held: with the anchor law A does not
creep (< 1e-6 m/s over 1 s).
"""

from dataclasses import dataclass

import numpy as np
import pytest

from knotmech.rod import Clamp, NodeForce, Rod, RodSystem, SolverOptions, ViscousDamping, simulate
from knotmech.rod.contact import RodContact
from knotmech.rod.friction import AnchorFriction

R = 1e-3
PITCH = 0.03
TURNS = 2.0
MU = 0.3
T_LOW = 0.05  # [N]
K = 2 * np.pi / PITCH


def helix(length, phase, x0, h=1.5e-3):
    n = int(round(length / h)) + 1
    x = x0 + np.linspace(0.0, length, n)
    phi = K * x + phase
    return np.stack([x, R * np.cos(phi), R * np.sin(phi)], 1)


@dataclass(frozen=True)
class _Ramp:
    """Force along +x on one node: 0 -> f1 over [0, t1], then + rate (t - t2) from t2 on,
    capped at fmax [N]."""

    node: int
    f1: float
    t1: float
    rate: float = 0.0
    t2: float = np.inf
    fmax: float = np.inf

    def value(self, t):
        f = self.f1 * min(t / self.t1, 1.0)
        if t > self.t2:
            f += self.rate * (t - self.t2)
        return min(f, self.fmax)

    def apply(self, system, t, q, q_old, dt, force, jac_diag):
        force[system.node_dofs[self.node, 0]] += self.value(t)

    def energy(self, system, q, t=np.inf):
        return -q[system.node_dofs[self.node, 0]] * self.value(t)


def braid(right_load, t_end, stop_at=None):
    a = helix(TURNS * PITCH + 0.04, 0.0, -0.02)
    b = helix(TURNS * PITCH, np.pi, 0.0)
    na, nb = len(a), len(b)
    rods = [Rod(positions=x, radius=R, youngs_modulus=1e7, density=1000.0, natural="initial")
            for x in (a, b)]  # fmt: skip
    system = RodSystem(rods)
    contact = RodContact(stiffness=500.0, sharpness=1 / (0.05 * R),
                         friction=AnchorFriction(mu_static=MU))  # fmt: skip
    eb = na - 1
    hold_b = Clamp(nodes=[na, na + 1, na + nb - 2, na + nb - 1], edges=[eb, eb + nb - 2])
    loads = [NodeForce(nodes=[0], force=(-T_LOW, 0.0, 0.0), ramp_time=0.2),
             right_load(na - 1), ViscousDamping(0.05)]  # fmt: skip
    x0 = a[0, 0]

    def runaway(state):  # stop once A has slid 1 mm out (no need to follow it)
        return stop_at is not None and system.positions(state.q)[0, 0] - x0 > stop_at

    res = simulate(system, t_end=t_end, dt=1e-3, loads=loads, constraints=[hold_b],
                   interactions=[contact], options=SolverOptions(save_every=5e-3),
                   callback=runaway)  # fmt: skip
    assert res.status == "success", res.message
    return res, loads[1], na


@pytest.mark.slow
def test_braid_holds_eighty_percent_of_its_pull_out_load_without_creep():
    # pull-out: T_low on both ends, then F ramped at 0.1 N/s until A slides
    res, load, na = braid(lambda n: _Ramp(n, T_LOW, 0.2, rate=0.1, t2=0.4), 1.2, stop_at=1e-3)
    left = res.positions[:, 0, 0] - res.positions[0, 0, 0]
    moved = np.flatnonzero(left > 1e-4)
    assert moved.size, "A never slid"
    f_po = load.value(res.times[moved[0] - 1])
    kappa = R * K**2 / (1 + (R * K) ** 2)
    capstan = T_LOW * np.exp(MU * kappa * TURNS * PITCH)
    assert 1.3 * T_LOW < f_po < capstan
    # hold 0.8 F_po (ramped over 0.3 s after the back-tension) for 1 s: no creep
    f_hold = 0.8 * f_po
    res, _, na = braid(lambda n: _Ramp(n, T_LOW, 0.2, rate=(f_hold - T_LOW) / 0.3, t2=0.2,
                                       fmax=f_hold), 1.5)  # fmt: skip
    x = res.positions[:, na - 1, 0]
    held = res.times >= 0.5 - 1e-9
    creep = abs(x[-1] - x[held][0]) / (res.times[-1] - res.times[held][0])
    assert creep < 1e-6

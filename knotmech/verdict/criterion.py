r"""The creep criterion of the DER hold verdict, its limit and the protocol it is measured on.

Defined once here: :data:`CREEP_CRITERION` (``"creep-speed"``), :data:`CREEP_LIMIT` (1e-3
rod diameters per protocol second), :data:`CREEP_WINDOW` (the last second of the hold),
:func:`creep_speed` (what a run measures), :func:`creep_verdict` (the criterion of one run)
and :func:`needs_recheck` (a creep near the limit is run again with a longer hold). The run
protocol (:data:`PROTOCOL`) is in units of the reference rod's flexural time
(:data:`REFERENCE_FLEXURAL_TIME`, :func:`protocol_time_scale`), so a table built on the
reference rod answers for every material of the same bending scale.
"""

from __future__ import annotations

import math

import numpy as np

from knotmech.errors import check_positive

# defined once, with the hitch scenes that measure it (the scenes sit below the verdict)
from knotmech.scenes._common import CREEP_LIMIT

__all__ = [
    "solver_gave_verdict",
    "CREEP_CRITERION",
    "CREEP_LIMIT",
    "CREEP_WINDOW",
    "PROTOCOL",
    "IMC_PROTOCOL",
    "PROTOCOL_CLOCK",
    "REFERENCE_FLEXURAL_TIME",
    "RECHECK_BAND",
    "RECHECK_HOLD_FACTOR",
    "ROD_DIAMETER",
    "YOUNGS_MODULUS",
    "DENSITY",
    "MU",
    "protocol_time_scale",
    "creep_speed",
    "creep_verdict",
    "needs_recheck",
]

ROD_DIAMETER = 4e-3  #: [m] the clove-hitch paper's rod (VPS32)
YOUNGS_MODULUS = 1.26e6  #: [Pa] VPS32
DENSITY = 1150.0  #: [kg/m^3]
MU = 0.3  #: rod-post and rod-rod friction of the table (the paper's sec. 7 value)
#: run protocol of a point with the sticking (anchor) rod-rod law: settle, ramp, hold [s];
#: time step [s]; frames every 0.05 s. The hold is long enough for the creep-speed
#: criterion's window (:data:`CREEP_WINDOW`) after a loaded hitch has re-seated (a finite
#: slide of up to ~0.5 s, then it locks).
PROTOCOL = dict(settle_time=0.2, load_time=0.3, hold_time=1.5, dt=2e-3, n_frames=41)
#: the protocol of the smooth-law (``friction="imc"``) tables shipped first, kept so those
#: tables can be reproduced (hold: end 0 creeps less than d over the last half of the hold)
IMC_PROTOCOL = dict(settle_time=0.2, load_time=0.2, hold_time=0.4, dt=2e-3, n_frames=21)
#: name of the hold criterion of the anchor-law tables and of ``hold --simulate``
CREEP_CRITERION = "creep-speed"
CREEP_WINDOW = 1.0  #: [s] the creep speed is measured over the last this-long of the hold
#: meta ``protocol_clock`` of a table whose points ran on the flexural clock below
PROTOCOL_CLOCK = "flexural"
#: the protocol's clock: its times (and its drag rate, set by the settle time) are in units of
#: this rod's flexural time d / (sqrt(kappa) sqrt(E/rho)), the clove-hitch paper's VPS32 rod
#: (:data:`ROD_DIAMETER`, :data:`YOUNGS_MODULUS`, :data:`DENSITY`, kappa = 1): 0.121 ms
REFERENCE_FLEXURAL_TIME = ROD_DIAMETER / (YOUNGS_MODULUS / DENSITY) ** 0.5


def protocol_time_scale(
    *, rod_diameter=ROD_DIAMETER, youngs_modulus=YOUNGS_MODULUS, density=DENSITY, bending_scale=1.0
) -> float:
    r"""The factor s by which :func:`simulate_point` stretches :data:`PROTOCOL`'s seconds.

    .. math:: s = \frac{d / (\sqrt{\kappa}\,\sqrt{E/\rho})}{t_\mathrm{ref}}

    with :math:`t_\mathrm{ref}` = :data:`REFERENCE_FLEXURAL_TIME` (the tables' VPS32 rod, s = 1).
    A rod's motion under the protocol depends on its material only through the time in units
    of its own elastic time (there is no gravity, and the contact penalties, the friction
    anchors and the solver tolerances scale with the loads and d); the bending waves that
    let a hitch re-seat are slower by 1/sqrt(kappa). Run in units of d/(sqrt(kappa) c),
    with the creep limit in d per protocol second, every rod of the same kappa, d/2R,
    T_high/EA and mu is the same dimensionless run, so one table per kappa serves every
    material. A 6 mm nylon rope (E = 0.25 GPa, 1140 kg/m^3, kappa 0.01) has s = 1.06; a
    solid nylon rod (kappa 1) 0.11; a 6 mm steel wire rope (80 GPa, 5000 kg/m^3, 0.02) 0.09.
    """
    d = check_positive("rod_diameter", rod_diameter, scalar=True)
    E = check_positive("youngs_modulus", youngs_modulus, scalar=True)
    rho = check_positive("density", density, scalar=True)
    from knotmech.errors import check_bending_scale

    kappa = check_bending_scale(bending_scale)
    return float(d / (kappa * E / rho) ** 0.5 / REFERENCE_FLEXURAL_TIME)


def creep_speed(times, end_displacement, *, rod_diameter, window=CREEP_WINDOW) -> float:
    r"""Mean creep speed of the loaded end along its load over the last ``window`` s [d/s].

    :math:`(u(t_\mathrm{end}) - u(t_\mathrm{end} - w)) / (w\,d)`, with :math:`u` the
    displacement of end 0 along its load [m] (the frame nearest to
    :math:`t_\mathrm{end} - w` at or after it) and :math:`d` the rod diameter [m].
    Positive when the rope is drawn out along the load (through the knot: a slip);
    negative when the end moves back (the knot settling). NaN when the run has fewer
    than two frames in the window.
    """
    t = np.asarray(times, dtype=float)
    u = np.asarray(end_displacement, dtype=float)
    d = check_positive("rod_diameter", rod_diameter, scalar=True)
    w = check_positive("window", window, scalar=True)
    if t.size < 2:
        return float("nan")
    sel = np.flatnonzero(t >= t[-1] - w - 1e-9)
    if sel.size < 2:
        return float("nan")
    i = int(sel[0])
    return float((u[-1] - u[i]) / (t[-1] - t[i]) / d)


def solver_gave_verdict(status: str, topology_preserved: bool) -> bool:
    """Whether a hitch run's outcome is a verdict (the anchor tables and ``hold --simulate``).

    A run that ended with status ``"success"`` is judged by :func:`creep_verdict` (a loaded
    end that ran off stops the run early, successfully: a slip). A run whose solver failed
    (the step stalled or fell below ``dt_min``, an edge passed its strain limit, the CPU
    budget ran out) is a verdict only when the knot's topology had already changed (it came
    apart: a slip, whatever the solver did next). Otherwise the creep over the hold's last
    window was never measured, and the failure says nothing about whether the knot would
    have held: no verdict. (Until session 20 such runs counted as slips: a NaN creep read
    as "too fast".)

    Parameters
    ----------
    status : str
        The run's status (``"success"`` or ``"failed"``).
    topology_preserved : bool
        Whether the knot kept its topology up to the last good state.

    Returns
    -------
    bool
        True when the run's outcome is judged (:func:`creep_verdict`), False for no verdict.
    """
    return status == "success" or not bool(topology_preserved)


def creep_verdict(
    speed: float,
    *,
    ran_to_end: bool,
    topology_preserved: bool,
    solver_ok: bool = True,
    limit: float = CREEP_LIMIT,
):
    """The creep-speed criterion (:data:`CREEP_CRITERION`) of one run.

    Holds when the run reached the end of its hold (a slipping end that runs off stops the
    run early: a slip), kept the knot's topology, and its loaded end crept slower than
    ``limit`` [d/s] either way over the last :data:`CREEP_WINDOW` of the hold (at rest: an
    end still moving back fast, a stiff rod springing open, is not a hold). Returns ``(holds,
    reason)``; ``holds`` is None when the solver failed (no verdict).
    """
    lim = check_positive("creep limit", limit, scalar=True)
    if not solver_ok:
        return None, "solver failed"
    if not ran_to_end:
        return False, "the loaded end ran off (run stopped early)"
    if not topology_preserved:
        return False, "the knot's topology changed"
    if not math.isfinite(speed):
        return None, "no creep speed measured"
    if abs(speed) < lim:
        return True, f"creep {speed:.3g} d/s, slower than {lim:g} d/s"
    return False, f"creep {speed:.3g} d/s, not slower than {lim:g} d/s"


#: a point whose creep speed lies between limit/RECHECK_BAND[0] and limit*RECHECK_BAND[1]
#: is run again with a hold :data:`RECHECK_HOLD_FACTOR` times as long, and the longer run
#: decides: light loads and thick rods settle slowly (a settling hitch's creep decays by
#: ~80x per second at 1e-4 EA; at d/2R 0.23, 1e-3 EA, mu 0.3 it read 4.5e-3 d/s after the
#: 1.5 s hold and 8e-7 d/s after 3 s)
RECHECK_BAND = (10.0, 100.0)
RECHECK_HOLD_FACTOR = 2.0


def needs_recheck(speed: float, *, limit: float = CREEP_LIMIT) -> bool:
    """Whether a creep speed [d/s] lies in the recheck band around the limit
    (:data:`RECHECK_BAND`: a decade below it to two decades above it)."""
    lo, hi = limit / RECHECK_BAND[0], limit * RECHECK_BAND[1]
    return bool(math.isfinite(speed) and lo <= abs(speed) < hi)

"""Helpers shared by the simulated experiments (scenes): section parameters, tensions, and
the checks every scene makes of its own set-up (up front) and of its result (after the run).

A scene refuses (InputError) a set-up its rod model cannot represent, warns (the result's
``warnings``) when a number is outside where the model was meant to be used, and reports
``status = "failed"`` with the reason when its own result contradicts what it simulates.

Bounds (one place, used by every scene):

- strain T/EA: the rod's tension law is Hookean, EA (|e|/|e_bar| - 1), with a cross-section
  (contact diameter, EI) that does not thin as it stretches: a warning above
  :data:`STRAIN_WARN` = 10 %, refused above :data:`STRAIN_MAX` = 50 %;
- the pulled end moves at most one edge per step (default steps: a quarter of an edge);
- quasi-static loading: the axial wave crosses the rod (L/c, c = sqrt(EA/(rho A))) in a
  tenth of the shortest loading time (ramp or pull) or less, else a warning; slower than
  that loading time itself, refused (the measured force is the rod's inertia);
- cost, before anything is allocated: nominal steps x nodes at most :data:`MAX_NODE_STEPS`
  (:func:`check_run_size`), and memory at most :data:`MAX_MEMORY` (:func:`check_memory`:
  the solver's arrays, :data:`SOLVER_BYTES_PER_NODE` per node, the all-pairs distance
  checks of the knots and the recorded frames);
- ``success`` only with numbers: a result whose requested quantity is NaN is ``failed``
  (:func:`check_numbers`).
"""

from __future__ import annotations

import math

import numpy as np

from knotmech.errors import InputError, check_positive

#: [d/s] the creep criterion's limit: a hitch holds when its loose end creeps slower than
#: this many rope diameters per (protocol) second at the end of the hold; the hitch scenes
#: measure it and :mod:`knotmech.verdict.criterion` decides with it
CREEP_LIMIT = 1e-3

#: strain T/EA above which a scene warns that its rod model (Hookean stretching, a fixed
#: cross-section) is used outside its range
STRAIN_WARN = 0.10
#: strain T/EA above which a scene refuses the set-up (or fails a run that reached it)
STRAIN_MAX = 0.50
#: the wave-crossing time L/c may be this fraction of the shortest loading time before a
#: scene warns that the loading is not quasi-static
QUASI_STATIC = 0.1


def equivalent_section(*, diameter, youngs_modulus, density, bending_stiffness=None):
    r"""Radius, modulus and density of a DER rod with given EA, EI and mass per length.

    A solid rod of diameter d has :math:`EA = E\pi d^2/4`, :math:`EI = E\pi d^4/64`,
    :math:`\rho A`. A rope or cord bends far more easily than the solid value; with
    ``bending_stiffness`` B given, the rod used by the solver has radius
    :math:`r' = 2\sqrt{B/EA}` and modulus :math:`E' = EA/(\pi r'^2)` (same EA and B), and
    density :math:`\rho' = \rho A/(\pi r'^2)` (same mass per length). The contact diameter
    stays d (pass it to the contact as ``rod_radius``).

    Returns
    -------
    radius [m], youngs_modulus [Pa], density [kg/m^3] for :class:`knotmech.rod.Rod`.
    """
    d = float(check_positive("rod_diameter", diameter, scalar=True))
    e = float(check_positive("youngs_modulus", youngs_modulus, scalar=True))
    rho = float(check_positive("density", density, scalar=True))
    if bending_stiffness is None:
        return 0.5 * d, e, rho
    b = float(check_positive("bending_stiffness", bending_stiffness, scalar=True))
    area = np.pi * d**2 / 4
    ea = e * area
    # a section of area A inside the diameter d has a radius of gyration of at most d/(2
    # sqrt(2)) (a thin-walled tube): EI <= EA d^2/8, twice the solid value
    if b > ea * d * d / 8:
        raise InputError(
            f"bending_stiffness must be <= EA d^2/8 = {ea * d * d / 8:.3g} N m^2 (a thin-walled "
            f"tube of diameter d, twice the solid rod's pi E d^4/64; a rope is below the solid "
            f"value), got {b:g}"
        )
    r2 = 2.0 * np.sqrt(b / ea)
    return r2, ea / (np.pi * r2**2), rho * area / (np.pi * r2**2)


def edge_tension(system, positions) -> np.ndarray:
    """Axial force EA (|e|/|e_bar| - 1) [N] of every edge, (n_frames, n_edges) or (n_edges,)."""
    pos = np.asarray(positions, dtype=float)
    en = system.edge_nodes
    e = pos[..., en[:, 1], :] - pos[..., en[:, 0], :]
    return system.ea * (np.linalg.norm(e, axis=-1) / system.rest_length - 1.0)


def check_strain(tension, ea, *, what="the largest tension") -> list[str]:
    """Up-front strain check of a scene's expected tension [N] on a rod of axial stiffness
    ``ea`` [N]: InputError above :data:`STRAIN_MAX`, a warning (returned in a list) above
    :data:`STRAIN_WARN`, else an empty list."""
    strain = float(tension) / float(ea)
    if strain > STRAIN_MAX:
        raise InputError(
            f"{what} ({float(tension):.3g} N) would stretch the rod by T/EA = {strain:.3g} "
            f"(EA = {float(ea):.3g} N), beyond the {STRAIN_MAX:.0%} its model covers (Hookean "
            "stretching, a cross-section that does not thin); lower the loads or use a "
            "stiffer rod (youngs_modulus, rod_diameter)"
        )
    if strain > STRAIN_WARN:
        return [
            f"strain: {what} stretches the rod by T/EA = {strain:.1%}, above the "
            f"{STRAIN_WARN:.0%} the rod model is meant for (Hookean stretching, fixed "
            "cross-section): the numbers are the model's, not a real rod's"
        ]
    return []


def measured_strain(tension, ea, *, warned: bool) -> tuple[str | None, list[str]]:
    """After a run: the largest |T|/EA of the recorded ``tension`` [N] (any shape).

    Returns (reason to fail or None, warnings): fails above :data:`STRAIN_MAX`, warns above
    :data:`STRAIN_WARN` unless the set-up was already ``warned`` about."""
    t = np.asarray(tension, dtype=float)
    t = t[np.isfinite(t)]
    if t.size == 0:
        return None, []
    strain = float(np.max(np.abs(t))) / float(np.min(np.atleast_1d(ea)))
    if strain > STRAIN_MAX:
        return (
            f"the rod reached a strain T/EA = {strain:.3g}, beyond the {STRAIN_MAX:.0%} its "
            "model covers; no result"
        ), []
    if strain > STRAIN_WARN and not warned:
        return None, [
            f"strain: the rod reached T/EA = {strain:.1%}, above the {STRAIN_WARN:.0%} the "
            "rod model is meant for: the numbers are the model's, not a real rod's"
        ]
    return None, []


def check_pull_step(dt, *, speed, edge_length, name="dt") -> None:
    """InputError unless the pulled end moves at most one edge per step (speed * dt <=
    edge_length): a coarser step does not resolve the pull (the friction anchors, the
    contacts and the recorded force curve all live on the edge scale)."""
    move = float(speed) * float(dt)
    if move > float(edge_length):
        raise InputError(
            f"{name} = {float(dt):.3g} s moves the pulled end {move:.3g} m per step, more "
            f"than an edge ({float(edge_length):.3g} m): the pull is not resolved; use "
            f"{name} <= {float(edge_length) / float(speed):.3g} s (default: a quarter of that)"
        )


def check_quasi_static(*, length, ea, mass_per_length, times, speed=None) -> list[str]:
    """Up-front check that the loading is slow for the rod: an axial wave crosses it in
    L/c, c = sqrt(EA/(rho A)) [m/s]; ``times`` maps a loading time's name to its value [s]
    (a ramp, the pull duration; zeros are skipped). InputError when L/c exceeds the
    shortest of them (or the pull ``speed`` exceeds c): the force the scene measures would
    be the rod's inertia; a warning when L/c exceeds :data:`QUASI_STATIC` of it."""
    c = float(np.sqrt(float(ea) / float(mass_per_length)))
    cross = float(length) / c
    if speed is not None and float(speed) >= c:
        raise InputError(
            f"pull_speed = {float(speed):.3g} m/s is not below the rod's axial wave speed "
            f"c = sqrt(EA/(rho A)) = {c:.3g} m/s: the pull is an impact, not a quasi-static "
            "test"
        )
    named = {k: float(v) for k, v in times.items() if float(v) > 0}
    if not named:
        return []
    key = min(named, key=named.get)
    tau = named[key]
    if cross > tau:
        raise InputError(
            f"an axial wave takes L/c = {cross:.3g} s to cross the rod (c = sqrt(EA/(rho A)) "
            f"= {c:.3g} m/s), longer than the {key} ({tau:.3g} s): the measured force would "
            "be the rod's inertia; slow the loading (ramp_time, pull_speed) or lower the density"
        )
    if cross > QUASI_STATIC * tau:
        return [
            f"inertia: an axial wave takes L/c = {cross:.3g} s to cross the rod, "
            f"{cross / tau:.0%} of the {key} ({tau:.3g} s; quasi-static needs "
            f"<= {QUASI_STATIC:.0%}): the forces include the rod's inertia"
        ]
    return []


def fail(status: str, message: str, reason: str | None) -> tuple[str, str]:
    """(status, message) of a scene: a successful run whose result contradicts what the
    scene simulates becomes "failed" with ``reason``; a run the solver failed keeps its
    message."""
    if reason and status == "success":
        return "failed", reason
    return status, message


#: default bound on the work of one scene run: nominal steps x nodes (see check_run_size)
#: the largest post a DER scene wraps a rod on, in rod diameters (a 6 mm rope on a 6 m
#: post): the start curve is sampled along the post, so its size grows with D/d, and far
#: beyond it the curve's coordinates lose all precision (a 1e297 m post gave a zero edge)
MAX_POST_RATIO = 1000.0


#: the thickest rod a post scene ties, in post diameters: its start curve's length (and
#: node count) grows with d, so a mistyped rod diameter (8 m on a 30 mm post) would build a
#: curve of millions of nodes before the run-size check could refuse it
MAX_ROD_RATIO = 10.0


def check_post_size(post_diameter: float, rod_diameter: float, scene: str) -> None:
    """Refuse a post above :data:`MAX_POST_RATIO` rod diameters, or a rod above
    :data:`MAX_ROD_RATIO` post diameters (InputError, one line)."""
    if rod_diameter > MAX_ROD_RATIO * post_diameter:
        raise InputError(
            f"rod_diameter / post_diameter = {rod_diameter / post_diameter:.3g} is above "
            f"{MAX_ROD_RATIO:g}: a DER {scene} is tied with rods up to {MAX_ROD_RATIO:g} "
            "post diameters (check the units of both)"
        )
    if post_diameter > MAX_POST_RATIO * rod_diameter:
        raise InputError(
            f"post_diameter / rod_diameter = {post_diameter / rod_diameter:.3g} is above "
            f"{MAX_POST_RATIO:g}: a DER {scene} is tied on posts up to {MAX_POST_RATIO:g} "
            "rope diameters (its start curve and run grow with D/d)"
        )


MAX_NODE_STEPS = 2e8

#: rough cost of one node-step of a scene with frictional contact [s] (1 us per node per
#: Newton iteration, ``benchmarks/der_step.py``, times 2-4 iterations and contact)
_SECONDS_PER_NODE_STEP = 3e-6


def check_run_size(*, n_nodes, t_end, dt, max_node_steps=None, hint="") -> float:
    """Refuse, before anything is allocated, a run that could not finish in reasonable time.

    The work of an implicit DER run grows as (nominal steps) x (nodes), steps =
    ``t_end / dt``. A run above ``max_node_steps`` (default :data:`MAX_NODE_STEPS`,
    2e8: about 10 minutes at a few microseconds per node-step) is refused with the
    estimate, so that a mistyped time step (``1e-12 s``), speed or element count gets
    one line instead of hours (or an out-of-memory error).

    Parameters
    ----------
    n_nodes : float
        Number of nodes the rod(s) will have (may be an estimate, computed before the
        rod is built).
    t_end : float [s]
        Simulated time.
    dt : float [s]
        Nominal time step.
    max_node_steps : float, optional
        The bound; ``inf`` lifts it.
    hint : str
        What to change, appended to the message (e.g. "use a larger dt").

    Returns
    -------
    float
        The estimated node-steps.

    Raises
    ------
    InputError
        The estimate exceeds the bound, or is not finite; or the solver's memory
        (:func:`solver_bytes`) exceeds :data:`MAX_MEMORY`.
    """
    limit = MAX_NODE_STEPS if max_node_steps is None else float(max_node_steps)
    if not limit > 0:
        raise InputError(f"max_node_steps must be > 0, got {max_node_steps!r}")
    steps = float(t_end) / float(dt)
    work = steps * float(n_nodes)
    if not math.isfinite(work) or work > limit:
        secs = work * _SECONDS_PER_NODE_STEP
        raise InputError(
            f"this run would take {steps:.3g} steps (t_end {float(t_end):.3g} s / dt "
            f"{float(dt):.3g} s) x {float(n_nodes):.3g} nodes = {work:.3g} node-steps, about "
            f"{_duration(secs)}, above the limit of {limit:.3g} (max_node_steps)"
            + (f"; {hint}" if hint else "")
        )
    check_memory(
        solver_bytes(n_nodes),
        what=f"the solver's arrays on {float(n_nodes):.3g} nodes (about 16 kB per node)",
        hint="use fewer nodes (n_nodes, n_elements)",
    )
    return work


#: peak memory of the implicit solver per node [bytes]: measured on a capstan hold run,
#: 2,000 -> 40,000 nodes added 620 MB of peak RSS (2026-12-03, numpy/numba, float64)
SOLVER_BYTES_PER_NODE = 16e3


def solver_bytes(n_nodes) -> float:
    """Peak memory [bytes] of the solver on ``n_nodes`` nodes
    (:data:`SOLVER_BYTES_PER_NODE` each)."""
    return SOLVER_BYTES_PER_NODE * float(n_nodes)


#: default bound on the memory one scene run may ask for [bytes] (see check_memory)
MAX_MEMORY = 4e9


def pair_check_bytes(n_edges) -> float:
    """Memory [bytes] of one all-pairs edge-distance check on ``n_edges`` edges
    (:func:`knotmech.scenes.curves._edge_distances`: two (n, n, 3) and about eight (n, n)
    float64 temporaries)."""
    return 112.0 * float(n_edges) ** 2


def frames_bytes(n_frames, n_nodes) -> float:
    """Memory [bytes] of ``n_frames`` recorded frames of ``n_nodes`` positions (float64)."""
    return 24.0 * float(n_frames) * float(n_nodes)


def check_memory(n_bytes, *, what: str, hint: str, max_memory=None) -> float:
    """Refuse, before anything is allocated, a run whose arrays would not fit in memory.

    Parameters
    ----------
    n_bytes : float [bytes]
        Estimate of the largest allocation(s) of the run.
    what : str
        What takes the memory (e.g. "the strands' pair-distance check on 2e4 edges").
    hint : str
        The option(s) that bring it down.
    max_memory : float [bytes], optional
        The bound (default :data:`MAX_MEMORY`, 4 GB).

    Returns
    -------
    float
        The estimate [bytes].

    Raises
    ------
    InputError
        The estimate is above the bound, or not finite.
    """
    limit = MAX_MEMORY if max_memory is None else float(max_memory)
    b = float(n_bytes)
    if not math.isfinite(b) or b > limit:
        raise InputError(
            f"this run would need about {_bytes(b)} of memory for {what}, above the limit of "
            f"{_bytes(limit)}; {hint}"
        )
    return b


def _bytes(n: float) -> str:
    if not math.isfinite(n):
        return "unbounded memory"
    for unit, size in (("PB", 1e15), ("TB", 1e12), ("GB", 1e9), ("MB", 1e6)):
        if n >= size:
            return f"{n / size:.3g} {unit}"
    return f"{n:.3g} bytes"


def check_numbers(**quantities) -> str | None:
    """The reason a result may not be ``success``, or None: the name of the first quantity
    the user asked for (a float or an array) that is not a number (NaN or infinite).

    ``success`` means every number is a number (issue 27): a run whose requested result
    is NaN is ``failed`` with this reason.
    """
    for name, value in quantities.items():
        a = np.asarray(value, dtype=float)
        if a.size and not np.all(np.isfinite(a)):
            return f"{name} is not a number (NaN or infinite): the run gave no value for it"
    return None


def _duration(seconds: float) -> str:
    if not math.isfinite(seconds):
        return "forever"
    for unit, size in (("years", 3.15e7), ("days", 86400.0), ("hours", 3600.0),
                       ("minutes", 60.0)):  # fmt: skip
        if seconds >= 2 * size:
            return f"{seconds / size:.3g} {unit}"
    return f"{seconds:.3g} s"

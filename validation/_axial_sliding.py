"""Hitches dragged along the pole's axis: sliding force against the normal load and the wraps.

Sabater, Park, Crassous, Neukirch & Reis (J. Mech. Phys. Solids 2026, DOI
10.1016/j.jmps.2026.106628; arXiv 2604.06962) tie a clove hitch round a cylinder, tension
the filament's legs and translate the cylinder along its axis: the sliding strength (the
axial force at which the knot slides) grows *superlinearly* with the legs' tension, in
elastomer rods, metallic wires and braided ropes, and in their FEM and DER simulations
(abstract; the exponent is not in the text we could read). The surgical-knot study they start
from (Johanns et al., Sci. Adv. 2023) reports a power law of exponent 1.6 between knot
strength and pre-tension (Sabater et al., ESMC 2025 abstract). Their capstan analysis
predicts a return to linearity once the filament is in full contact with the cylinder.

Here: the DER axial pull (:func:`knotmech.scenes.axial.axial_pull`): the clove hitch (d = 4 mm
VPS32 rod, D = 30 mm pole, mu = 0.3) at a few normal loads, the exponent of a log-log fit of
the sliding force against T; the Prusik (d = 4 mm, D = 12 mm) with 2, 3 and 4 turns a side,
its sliding force against the wraps. One process, coarse meshes (a few minutes of CPU).
"""

from __future__ import annotations

import numpy as np

from knotmech.scenes.axial import axial_pull

from ._common import finish, main, save_figure

NAME = "axial_sliding"
SUMMARY = (
    "DER sliding force of a clove hitch dragged along its pole against the legs' normal load "
    "(log-log exponent; Sabater et al. 2026 report a superlinear sliding strength), and of "
    "a Prusik against its turns."
)
LOADS_QUICK = (0.25, 0.5, 1.0, 2.0)  #: [N] normal loads T of the clove hitch
WRAPS = (2, 3, 4)  #: Prusik turns a side
#: the clove hitch: 60 nodes (edges of 4.7 mm), legs of 8 d, the grips moved 12 d at 20 mm/s
CLOVE = {"n_nodes": 60, "n_frames": 41, "drag_speed": 0.02, "drag_distance": 0.048}
#: the clove hitch with its legs' dead loads T kept along the tails while the ends' axial
#: position is driven (the normal load stays T): grips moved 40 d at 40 mm/s; F_s = plateau
DEAD = {"n_nodes": 60, "n_frames": 41, "drag_speed": 0.04, "drag_distance": 0.16,
        "legs": "dead"}  # fmt: skip
#: the Prusik on the same 30 mm pole (on a thinner pole the solid rod's bending unwinds the
#: loosely tied turns, see the note), legs pre-tensioned 0.5 N, the grips moved 8 d
PRUSIK = {"post_diameter": 30e-3, "normal_load": 0.5, "n_frames": 21, "drag_speed": 0.02,
          "drag_distance": 0.032}  # fmt: skip


def _row(r) -> dict:
    """The numbers of one drag (and its curve, for the figure)."""
    return {
        "wraps": r.wraps, "normal_load": r.normal_load, "sliding_force": r.sliding_force,
        "peak_force": r.peak_force, "plateau_force": r.plateau_force, "slid": r.slid,
        "topology_preserved": r.topology_preserved, "status": r.status, "message": r.message,
        "wall_s": float(r.stats.get("wall_s", np.nan)),
        "grip_mm": (r.grip_displacement * 1e3).tolist(), "force_N": r.axial_force.tolist(),
    }  # fmt: skip


def fit_exponent(loads, forces) -> float:
    """Slope of log(forces) against log(loads) (least squares), nan below two finite points."""
    x, y = np.asarray(loads, float), np.asarray(forces, float)
    ok = np.isfinite(y) & (y > 0)
    if np.count_nonzero(ok) < 2:
        return float("nan")
    return float(np.polyfit(np.log(x[ok]), np.log(y[ok]), 1)[0])


def _figure(clove, dead, prusik, loads, wraps, alpha, alpha_dead):
    """Three panels: the clove hitch's axial force against the grips' travel (dead legs,
    clamped legs dashed), its sliding force against T (log-log, slopes 1 and 1.6), the
    Prusik's against its turns."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(13, 4.0), layout="constrained")
    a0, a1, a2 = fig.subplots(1, 3)
    for k, (c, c2) in enumerate(zip(dead, clove, strict=True)):
        a0.plot(c["grip_mm"], c["force_N"], color=f"C{k}", label=f"T = {c['normal_load']:g} N")
        a0.plot(c2["grip_mm"], c2["force_N"], color=f"C{k}", ls="--", lw=0.8)
    a0.set_xlabel("grips' travel along the pole [mm]")
    a0.set_ylabel("axial force F [N]")
    a0.set_title("clove hitch, d = 4 mm, D = 30 mm, mu = 0.3\nsolid: T kept (dead legs); "
                 "dashed: legs clamped", fontsize=8)  # fmt: skip
    a0.legend(fontsize=7)
    t = np.asarray(loads, float)
    fd = np.array([c["plateau_force"] for c in dead], float)
    fc = np.array([c["sliding_force"] for c in clove], float)
    a1.loglog(t, fd, "o-", label=f"T kept: plateau, exponent {alpha_dead:.2f}")
    a1.loglog(t, fc, "s--", label=f"legs clamped: F at 1 d, exponent {alpha:.2f}")
    ref = fd[0] if np.isfinite(fd[0]) else 1.0
    a1.loglog(t, ref * (t / t[0]), "k:", label="slope 1 (linear)")
    a1.loglog(t, ref * (t / t[0]) ** 1.6, "k-.", label="slope 1.6 (surgical knots)")
    a1.set_xlabel("normal load T on each leg [N]")
    a1.set_ylabel("sliding force F_s [N]")
    a1.set_title("superlinear (Sabater et al. 2026): slope > 1", fontsize=8)
    a1.legend(fontsize=7)
    a2.plot(wraps, [p["sliding_force"] for p in prusik], "s-", label="F at 1 d of travel")
    a2.plot(wraps, [p["peak_force"] for p in prusik], "^:", label="peak over the drag")
    a2.set_xlabel("Prusik turns a side")
    a2.set_ylabel("axial force [N]")
    a2.set_title("Prusik, legs set at 0.5 N and clamped, D = 30 mm", fontsize=8)
    a2.legend(fontsize=7)
    return fig


def run(quick: bool = True, out_dir=".", loads=LOADS_QUICK, wraps=WRAPS) -> dict:
    """Run the clove-hitch loads and the Prusik wraps; write the figure and the JSON."""
    clove = [_row(axial_pull("clove-hitch", normal_load=t, **CLOVE)) for t in loads]
    dead = [_row(axial_pull("clove-hitch", normal_load=t, **DEAD)) for t in loads]
    prusik = [_row(axial_pull("prusik", wraps=w, **PRUSIK)) for w in wraps]
    return summarise(clove, dead, prusik, loads, wraps, quick=quick, out_dir=out_dir)


def summarise(clove, dead, prusik, loads, wraps, *, quick=True, out_dir=".") -> dict:
    """The exponents, the figure, the checks and the JSON from the runs' rows."""
    fs = [c["sliding_force"] for c in clove]
    fd = [c["plateau_force"] for c in dead]
    alpha, alpha_dead = fit_exponent(loads, fs), fit_exponent(loads, fd)
    fig = _figure(clove, dead, prusik, loads, wraps, alpha, alpha_dead)
    figures = [save_figure(fig, out_dir, NAME)]
    checks = {
        "clove_topology_kept": all(c["topology_preserved"] for c in clove + dead),
        "clove_dead_legs_slide": all(c["slid"] for c in dead),
        "clove_slides_at_positive_force": all(np.isfinite(f) and f > 0 for f in fs),
        "clove_force_rises_with_load": bool(np.all(np.diff(fs) > 0)),
        "prusik_topology_kept": all(p["topology_preserved"] for p in prusik),
    }
    numbers = {"loads_N": list(loads), "clove_sliding_force_N": fs, "exponent": alpha,
               "clove_dead_plateau_N": fd, "exponent_dead": alpha_dead,
               "prusik_wraps": list(wraps),
               "prusik_sliding_force_N": [p["sliding_force"] for p in prusik],
               "prusik_peak_force_N": [p["peak_force"] for p in prusik]}  # fmt: skip
    notes = [
        "exponent > 1 is superlinear, the trend Sabater et al. report; coarse mesh (60 nodes "
        "on the clove hitch, 200 on the Prusik)",
        "legs clamped: F_s is the axial force when the wraps have travelled one rod diameter; "
        "the legs' tension rises as they tilt and stretch",
        "T kept (dead legs): F_s is the plateau of F while the knot slides with the grips; "
        "F = 2 T tan(tilt), so at the plateau the legs lie nearly along the pole and carry "
        "about F/2, far above T: the grip of the wraps is set by F itself",
    ]
    return finish(NAME, out_dir=out_dir, checks=checks, numbers=numbers, figures=figures,
                  notes=notes, quick=quick,
                  extra={"clove": clove, "clove_dead": dead, "prusik": prusik})  # fmt: skip


if __name__ == "__main__":
    raise SystemExit(main(run))

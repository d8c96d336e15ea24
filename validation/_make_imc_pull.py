"""Make a whole overhand pull to tight, as a ``knot_pull`` recording (a helper).

The implicit-contact-model paper's knot (:func:`knotmech.scenes.overhand.imc_setup`:
1 m rod, h = 1.6 mm, E = 0.18 MPa, 301 nodes, dt = 2.5 ms, both ends pulled apart at
6 mm/s each for 60 s) with the smooth (``imc``) friction law at mu = 0.3, n = 1 turn:
end-to-end from 0.28 m to 0.998 m. The raw frames are written as a recording
(``# experiment: knot_pull``, columns ``end_to_end_m,force_N``), the frames of the
wait and the first 1 % of L of the pull left out (the grips' start-up transient);
rows beyond ``--to`` (default 0.998 L, "pulled to tight") left out too; ``--rows``
decimates to that many rows (evenly in frame order, i.e. in end-to-end distance).
Made by another code path than the DER baseline (its 301-node mesh, the paper's time
step and speed, no boxcar or surface), so that ``knotmech diagnose REC.csv --baseline
der`` is judged on a pull it did not make. About 1-3 minutes on one core.

    python -m validation._make_imc_pull --out imc_pull_mu0.3.csv [--rows 200]
        [--npz frames.npz]  # also keep the raw frames
        [--frames frames.npz]  # no run: rebuild the recording from kept frames
"""

from __future__ import annotations

import argparse
import time
from pathlib import Path

import numpy as np

from knotmech.scenes.overhand import imc_setup, overhand

MU = 0.3
TURNS = 1


def make(n_frames: int = 1500) -> dict:
    """Run the pull; returns its frames (``times`` [s], ``end_to_end`` [m], ``force``
    [N]) and ``cpu`` (CPU seconds of the run)."""
    t0 = time.process_time()
    res = overhand(TURNS, MU, params="imc", friction="imc", n_frames=n_frames, n_snapshots=1)
    cpu = time.process_time() - t0
    if res.status != "success":
        raise SystemExit(f"the pull failed: {res.message}")
    return {"times": res.times, "end_to_end": res.end_to_end, "force": res.pull_force, "cpu": cpu}


def rows(frames: dict, to: float = 0.998, n_rows: int = 0):
    """The recording's rows of the pull's ``frames``: (end_to_end [m], force [N]).

    The wait and the first 1 % of L of the pull are left out, and the frames beyond
    ``to`` L; ``n_rows`` > 0 decimates evenly in frame order.
    """
    s = imc_setup(TURNS)
    t, d, f = (np.asarray(frames[k], float) for k in ("times", "end_to_end", "force"))
    keep = (t > s.wait_time + 0.01 * s.rod_length / (2 * s.pull_speed)) & (d <= to * s.rod_length)
    d, f = d[keep], f[keep]
    if 0 < n_rows < d.size:
        k = np.unique(np.linspace(0, d.size - 1, n_rows).round().astype(int))
        d, f = d[k], f[k]
    return d, f


def write(path, d, f, setup) -> Path:
    """Write (d, f) as a knot_pull recording with the setup's metadata."""
    lines = [
        "# knotmech-recording: 1",
        "# experiment: knot_pull",
        "# knot: overhand",
        f"# turns: {TURNS}",
        f"# rod_radius_m: {setup.rod_radius}",
        f"# youngs_modulus_Pa: {setup.youngs_modulus}",
        f"# rod_length_m: {setup.rod_length}",
        f"# density_kg_m3: {setup.density}",
        f"# poisson_ratio: {setup.poisson_ratio}",
        f"# pull_speed_m_per_s: {2 * setup.pull_speed}",
        f"# source: knotmech overhand imc_setup, 301 nodes, friction imc, mu {MU}",
        "end_to_end_m,force_N",
    ]
    lines += [f"{a:.6f},{b:.6e}" for a, b in zip(d, f, strict=True)]
    path = Path(path)
    path.write_text("\n".join(lines) + "\n", encoding="utf-8")
    return path


def main(argv=None) -> Path:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--out", default="imc_pull_mu0.3.csv")
    p.add_argument("--rows", type=int, default=0, help="decimate to this many rows")
    p.add_argument("--to", type=float, default=0.998, help="last end-to-end / L")
    p.add_argument("--npz", default="", help="also save the raw frames here")
    p.add_argument("--frames", default="", help="rebuild from frames saved with --npz")
    a = p.parse_args(argv)
    if a.frames:
        frames = dict(np.load(a.frames))
    else:
        frames = make()
        print(f"the pull: {frames['cpu']:.0f} s of CPU")
        if a.npz:
            np.savez_compressed(a.npz, **frames)
    d, f = rows(frames, a.to, a.rows)
    out = write(a.out, d, f, imc_setup(TURNS))
    print(f"{out}: {d.size} rows, end_to_end {d[0]:.4f}..{d[-1]:.4f} m")
    return out


if __name__ == "__main__":
    main()

"""Coated-rod n = 3 overhand pulls with both rod-rod friction laws (issue 11 part 2(d)).

Quick mesh of tests/scenes/test_overhand.py (151 nodes, 30 mm/s, dt = 5 ms, 0.5 s wait,
9 s pull, 381 frames), mu = 0.2, 0.6, 0.9, laws "anchor" (mu_s = mu_k = mu) and "imc".

    OPENBLAS_NUM_THREADS=1 nice python docs/figures/coated_n3_laws.py run OUT_DIR [law:mu ...]
    python docs/figures/coated_n3_laws.py plot OUT_DIR   # -> docs/figures/coated_n3_laws.png

``run`` writes OUT_DIR/<law>_<mu>.npz per pull (curves, stats, inversions, knot types) as
each one finishes; ``plot`` draws whatever is there and prints a JSON table.
"""

from __future__ import annotations

import json
import sys
import time
from pathlib import Path

import numpy as np

QUICK = dict(n_nodes=151, pull_speed=0.03, dt=5e-3, wait_time=0.5, pull_time=9.0)
DEFAULT = ["anchor:0.6", "anchor:0.9", "anchor:0.2", "imc:0.2", "imc:0.6", "imc:0.9"]


def run(out: Path, specs) -> None:
    from knotmech.scenes.overhand import inversion_points, overhand

    out.mkdir(parents=True, exist_ok=True)
    for spec in specs:
        law, mu = spec.split(":")
        mu = float(mu)
        t0, c0 = time.perf_counter(), time.process_time()
        r = overhand(3, mu, params="coated", n_frames=381, friction=law, progress=True, **QUICK)
        wall, cpu = time.perf_counter() - t0, time.process_time() - c0
        pulling = r.times > r.setup.wait_time + 0.2
        inv = inversion_points(r.end_to_end[pulling], r.pull_force[pulling], span=0.05)
        np.savez(
            out / f"{law}_{mu:g}.npz",
            times=r.times,
            end_to_end=r.end_to_end,
            pull_force=r.pull_force,
            inversions=inv,
            meta=json.dumps(
                dict(law=law, mu=mu, status=r.status, message=r.message,
                     knot_start=r.knot_start, knot_end=r.knot_end, wall_s=wall, cpu_s=cpu,
                     simulated_s=float(r.times[-1]), solver_wall_s=r.stats.get("wall_s"),
                     **{k: v for k, v in r.stats.items() if k != "wall_s"})
            ),
        )  # fmt: skip
        print(spec, r.status, r.stats, "inversions", inv, f"wall {wall:.0f} s", flush=True)


def plot(out: Path) -> None:
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(1, 2, figsize=(11, 4.2), sharey=True)
    table = []
    for ax, law in zip(axes, ("imc", "anchor"), strict=True):
        for mu, c in ((0.2, "C0"), (0.6, "C1"), (0.9, "C3")):
            p = out / f"{law}_{mu:g}.npz"
            if not p.exists():
                continue
            d = np.load(p)
            meta = json.loads(str(d["meta"]))
            ax.plot(d["end_to_end"], 1e3 * d["pull_force"], c, lw=1, label=f"mu = {mu:g}")
            for e in d["inversions"]:
                ax.axvline(e, color=c, ls=":", lw=1)
            meta["inversions_m"] = [round(float(e), 4) for e in d["inversions"]]
            table.append(meta)
        ax.set_title(f"coated n = 3, law '{law}' (151 nodes, 30 mm/s)")
        ax.set_xlabel("end-to-end length [m]")
        ax.legend(loc="upper left")
    axes[0].set_ylabel("pull force [mN]")
    fig.tight_layout()
    fig.savefig(Path(__file__).with_suffix(".png"), dpi=110)
    print(json.dumps(table, indent=1, default=str))


if __name__ == "__main__":
    cmd, out = sys.argv[1], Path(sys.argv[2])
    if cmd == "run":
        run(out, sys.argv[3:] or DEFAULT)
    else:
        plot(out)

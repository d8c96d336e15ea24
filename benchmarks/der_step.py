"""Cost of one Newton iteration (assembly + banded solve) of the DER solver, free rod.

Prints JSON: {"n_nodes": [...], "us_per_node_iteration": [...], "peak_memory_mb": ...,
"breakdown_us_per_node": {...}}; each number is the median over repeats, after a warm-up
that compiles the numba kernels. Runs on one core (BLAS and numba threads pinned to 1) and
times with the process CPU clock, so that other load on the machine does not inflate it.
Target: <= 1 us per node per iteration at N = 1000.
"""

import os

for _var in ("OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS", "NUMBA_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import json  # noqa: E402
import resource  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402

import numpy as np  # noqa: E402

from knotmech import rod  # noqa: E402
from knotmech.rod.solver import Stepper  # noqa: E402


def _system(n_nodes: int):
    s = np.linspace(0.0, 1.0, n_nodes)
    # a bent, twisted free rod so that no term of the Hessian vanishes
    pos = np.c_[s, 0.05 * np.sin(6 * s), 0.05 * np.cos(5 * s)]
    r = rod.Rod(
        positions=pos, radius=1e-3, youngs_modulus=1e7, density=1000.0, natural="straight",
        thetas=0.3 * np.sin(7 * s[:-1]),
    )  # fmt: skip
    return rod.RodSystem([r])


def measure(n_nodes: int, repeats: int = 7, inner: int = 0) -> dict:
    system = _system(n_nodes)
    stepper = Stepper(system, loads=[rod.Gravity()])
    st = system.initial_state()
    dt = 1e-3
    q = st.q + 1e-7 * np.sin(np.arange(system.n_dof))
    inner = inner or max(3, 20000 // n_nodes)
    stepper.evaluate(q, st, dt, st.t + dt)  # warm-up / compile
    stepper.solve(-stepper.f)
    t_eval, t_solve = [], []
    for _ in range(repeats):
        t0 = time.process_time()
        for _ in range(inner):
            stepper.evaluate(q, st, dt, st.t + dt)
        t1 = time.process_time()
        for _ in range(inner):
            dq = stepper.solve(-stepper.f)
        t2 = time.process_time()
        t_eval.append((t1 - t0) / inner)
        t_solve.append((t2 - t1) / inner)
    assert np.all(np.isfinite(dq))
    te = float(np.median(t_eval)) / n_nodes * 1e6
    ts = float(np.median(t_solve)) / n_nodes * 1e6
    return {"assembly": te, "solve": ts, "total": te + ts}


def main() -> None:
    sizes = [100, 300, 1000, 3000]
    rows = [measure(n) for n in sizes]
    peak = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
    out = {
        "n_nodes": sizes,
        "us_per_node_iteration": [round(r["total"], 3) for r in rows],
        "peak_memory_mb": round(peak, 1),
        "breakdown_us_per_node": {
            "assembly": [round(r["assembly"], 3) for r in rows],
            "solve": [round(r["solve"], 3) for r in rows],
        },
    }
    json.dump(out, sys.stdout)
    sys.stdout.write("\n")


if __name__ == "__main__":
    main()

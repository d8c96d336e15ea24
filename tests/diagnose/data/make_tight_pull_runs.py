"""Make ``tight_pull_runs.npz``: the DER runs behind ``--baseline der`` on the pull to tight.

The recording is ``imc_pull_tight_mu0.3_n1.csv`` (made by
``python -m validation._make_imc_pull --rows 200``: the implicit-contact-model paper's
overhand knot, 301 nodes, smooth friction at mu = 0.3, pulled to 0.998 L), and the runs are
every ``DERKnotLaw.run`` that diagnosing it with ``baseline="der"`` asks for, stored as
``run_<mu>_d`` (end-to-end distance, m) and ``run_<mu>_f`` (pulling force, N) so that
``tests/diagnose/test_diagnose_knot_pull.py`` repeats the diagnosis in seconds. Run it
from the project root (about 1 minute):

    python tests/diagnose/data/make_tight_pull_runs.py
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from knotmech.diagnose import der_knot, diagnose

HERE = Path(__file__).parent


def main() -> Path:
    plain = der_knot.DERKnotLaw.run
    store: dict[str, np.ndarray] = {}

    def run(self, mu):
        d, f = plain(self, mu)
        m = round(float(mu), 6)
        store[f"run_{m}_d"] = np.asarray(d)
        store[f"run_{m}_f"] = np.asarray(f)
        return d, f

    der_knot.DERKnotLaw.run = run
    try:
        rep = diagnose(HERE / "imc_pull_tight_mu0.3_n1.csv", baseline="der", seed=0)
        print(rep.verdict, rep.final["parameters"], rep.details["der"])
    finally:
        der_knot.DERKnotLaw.run = plain
    out = HERE / "tight_pull_runs.npz"
    np.savez_compressed(out, **store)
    print(out, sorted(store))
    return out


if __name__ == "__main__":
    main()

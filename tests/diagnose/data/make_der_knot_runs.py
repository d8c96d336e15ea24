"""Make ``der_knot_runs_null_1022.npz``: the DER runs behind one DER-made null recording.

The recording is :func:`knotmech.diagnose.der_knot.der_made_recording` at turns 1,
mu 0.3, seed 1022 (one of diag12.md's fresh nulls whose two surrogates differ), and
the runs are every ``DERKnotLaw.run`` that making it and diagnosing it with
``baseline="der"`` (surrogate error on and off) asks for. Stored as
``run_<mu>_d`` (end-to-end displacement, m) and ``run_<mu>_f`` (pulling force, N), so
that ``tests/diagnose/test_diagnose_knot_pull.py`` diagnoses the same recording in
seconds, without the solver. Run it from the project root (about 2-5 minutes):

    python tests/diagnose/data/make_der_knot_runs.py
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

from knotmech.diagnose import der_knot, diagnose


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
        rec, _ = der_knot.der_made_recording(1, 0.3, None, size=8.0, seed=1022)
        for on in (True, False):
            der_knot.SURROGATE_ERROR = on
            rep = diagnose(rec, baseline="der", seed=1022)
            print("surrogate error", on, "->", rep.verdict)
    finally:
        der_knot.DERKnotLaw.run = plain
        der_knot.SURROGATE_ERROR = False
    out = Path(__file__).with_name("der_knot_runs_null_1022.npz")
    np.savez_compressed(out, **store)
    print(out, sorted(store))
    return out


if __name__ == "__main__":
    main()

"""Which rod-rod pairs should the anchor law's cap floor apply to? (issue 24, session 15)

Runs one case with the anchor law's floor rule set explicitly in every scene (the hitches
and the overhand knots alike):

- ``free``: the clove-hitch paper's sec. 7 free-end hitch, as
  ``tests/cli/test_simulate_knots.py::test_clove_hitch_free_end_holds_and_tension_vanishes``
  (``knotmech simulate clove-hitch --loading free --t-high 1.47N --mu 0.3 --n-nodes 120``);
- ``n3``, ``n1``: the coated overhand pulls at ``--mu`` of ``validation/_overhand_mu_laws.py``
  (quick mesh, 9 s pull, path guard);
- ``kappa``: the clove-hitch point of ``benchmarks/kappa_point.py`` at ``--kappa``.

``RULE`` is a :data:`~knotmech.rod.friction.FLOOR_RULES` entry (``all``: c (r_i + r_j) on
every pair; ``sliding``: on the pairs that slid at the last step; ``penalty``: ``--cap-floor``
penalty widths 1/sharpness; ``min``: the smaller of c (r_i + r_j) and c/1e-2 penalty widths,
the library's default since session 15) or ``none`` (cap floor 0, the hitches' law of
sessions 13-14). ``--cap-floor`` is c, except for ``penalty``, where it counts penalty widths.
Prints one JSON line (verdict or forces, counts, process CPU [s]) and appends it to
``--out``::

    OPENBLAS_NUM_THREADS=1 nice -n 10 python -m validation._floor_rule free sliding
"""

from __future__ import annotations

import argparse
import contextlib
import functools
import json
import os
import tempfile
import time

from knotmech.rod.friction import CAP_FLOOR, AnchorFriction


@contextlib.contextmanager
def floor_rule(rule, cap_floor=CAP_FLOOR):
    """Inside the block the hitch and overhand scenes build the anchor law with ``rule``."""
    import knotmech.scenes._hitch as hitch
    import knotmech.scenes.overhand as scene

    if rule == "penalty":  # --cap-floor counts penalty widths 1/sharpness here
        cap_floor = cap_floor * CAP_FLOOR
    law = functools.partial(
        AnchorFriction,
        cap_floor=0.0 if rule == "none" else cap_floor,
        floor_rule="all" if rule == "none" else rule,
    )
    orig = hitch.AnchorFriction, scene.AnchorFriction
    hitch.AnchorFriction = scene.AnchorFriction = lambda **k: law(
        **{kk: v for kk, v in k.items() if kk != "cap_floor"}
    )
    try:
        yield
    finally:
        hitch.AnchorFriction, scene.AnchorFriction = orig


def free_end():
    """The free-end clove hitch of the CLI test: verdict and the last tension [N]."""
    import contextlib as cl
    import csv
    import io

    from knotmech.cli.main import main

    with tempfile.TemporaryDirectory() as tmp:
        out_csv = os.path.join(tmp, "h.csv")
        args = ["simulate", "clove-hitch", "--loading", "free", "--t-high", "1.47N", "--mu",
                "0.3", "--n-nodes", "120", "--no-progress", "--csv", out_csv]  # fmt: skip
        buf = io.StringIO()
        with cl.redirect_stdout(buf):
            main(args)
        rows = list(csv.DictReader(open(out_csv)))
    text = buf.getvalue()
    verdict = "HOLD" if "verdict: HOLD" in text else ("SLIP" if "verdict: SLIP" in text else "?")
    lines = [ln.strip() for ln in text.splitlines() if ln.strip()]
    return dict(verdict=verdict, last_tension_N=float(rows[-1]["tension_N"]), summary=lines[-6:])


def overhand_pull(turns, mu):
    """One coated pull of ``_overhand_mu_laws`` (its quick mesh, path guard): its row."""
    from validation import _overhand_mu_laws as om

    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, f"anchor_n{turns}_mu{mu:g}.npz")
        orig = om.law_objects
        om.law_objects = _keep_scene_law(orig)
        try:
            om.run_one(path, "anchor", turns, mu)
        finally:
            om.law_objects = orig
        return om.row(path)


def _keep_scene_law(orig):
    """``law_objects`` that sets the path guard but keeps the scene's (patched) law."""

    @contextlib.contextmanager
    def law_objects(law):
        import knotmech.scenes.overhand as scene

        keep = scene.AnchorFriction
        with orig(law) as guard:
            scene.AnchorFriction = keep
            yield guard

    return law_objects


def kappa_point(kappa):
    """``benchmarks/kappa_point.py``'s point at ``kappa``."""
    import sys

    sys.path.insert(0, "benchmarks")
    from kappa_point import run_point

    return run_point(kappa, 0.1)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("case", choices=("free", "n3", "n1", "kappa"))
    ap.add_argument("rule", choices=("all", "sliding", "penalty", "min", "none"))
    ap.add_argument("--mu", type=float, default=0.9)
    ap.add_argument("--kappa", type=float, default=0.01)
    ap.add_argument("--cap-floor", type=float, default=CAP_FLOOR)
    ap.add_argument("--out", default="floor_rule.jsonl")
    a = ap.parse_args(argv)
    c0 = time.process_time()
    with floor_rule(a.rule, a.cap_floor):
        if a.case == "free":
            res = free_end()
        elif a.case == "kappa":
            res = kappa_point(a.kappa)
        else:
            res = overhand_pull(int(a.case[1]), a.mu)
    row = dict(case=a.case, rule=a.rule, cap_floor=a.cap_floor, **res)
    row["cpu_total_s"] = round(time.process_time() - c0, 1)
    print(json.dumps(row, default=str), flush=True)
    with open(a.out, "a") as f:
        f.write(json.dumps(row, default=str) + "\n")


if __name__ == "__main__":
    main()

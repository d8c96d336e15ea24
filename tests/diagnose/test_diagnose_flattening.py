"""contact_flattening's onset search (issue 14: its thinned bootstrap above 4000 rows).

The bootstrap of a recording longer than fitting.BOOT_ROWS draws every k-th row;
benchmarks/thinned_bootstrap_size.py measures its size (docs/notes/kpull.md). Here: the
power at the benchmark's row count.
"""

import pytest

from knotmech.diagnose import diagnose, make_recording


def test_flattening_found_at_the_benchmark_row_count():
    """A 5-sd flattening in a 20 000-row pinch (the thinned bootstrap's size benchmark
    rows) is found, with its onset."""
    rec, truth = make_recording("pinch", "contact_flattening", size=5.0, seed=11, n=20_000)
    rep = diagnose(rec, seed=0)
    assert rep.verdict == "contact_flattening"
    got = rep.effects[0]["parameters"]["onset_load_parameter"]
    assert got == pytest.approx(truth["onset_load_parameter"], abs=0.03)

"""``knotmech tour``: prints real numbers, writes the figure, sections are extensible."""

import os
import re
import subprocess
import sys
from pathlib import Path

import pytest

from knotmech.cli import tour
from knotmech.cli.main import main


def test_tour_prints_results_and_saves_figure(tmp_path, capsys):
    out = tmp_path / "tour"
    assert main(["tour", "--out", str(out)]) == 0
    text = capsys.readouterr().out
    # mu_eff table against the clove-hitch paper's values (mu = 0.3)
    for Dt, value in ((1, "0.1468"), (2, "0.1962"), (5, "0.2470"), (10, "0.2707")):
        assert re.search(rf"^\s+{Dt}\s+{value}\s", text, re.M), (Dt, value)
    assert "6.586" in text  # e^(0.3 * 2 pi)
    # the free-end clove hitch: the DER table decides (d/D = 0.13 is outside the ideal
    # rope's validity) and the ideal rope's "slips" is shown beside it, as `knotmech hold` does
    assert re.search(r"free end 0\.00 N: HOLDS .*decided by DER-table; ideal-rope slips", text)
    # issue 23: self-locking (thick nip) with no bound on the slip load (no table for a
    # loaded free end, no breaking load for VPS32): undecided, never "unbounded"
    assert "free end 0.05 N: UNDECIDED (margin not computed, decided by None" in text
    # DER capstan: surface friction near exp(mu_eff theta) = 3.354, centreline near 4.810
    ratios = [float(m) for m in re.findall(r"T_high/T_low = (\d+\.\d+)", text)]
    assert ratios[0] == pytest.approx(3.354, rel=0.02) and ratios[1] == pytest.approx(
        4.810, rel=0.02
    )
    png = out / "capstan_tension_decay.png"
    assert png.is_file() and png.stat().st_size > 10_000
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    # the compiling notice, when shown, comes first; after this run every kernel the notice
    # watches is cached (so TOUR_KERNELS names kernels the tour really compiles) and a
    # second tour would be quiet
    if tour.COMPILING_NOTICE in text:
        assert text.splitlines()[2] == tour.COMPILING_NOTICE
        assert "(including compiling the kernels)" in text
    assert tour.kernels_cold() is False


def test_kernels_are_cold_with_an_empty_numba_cache(tmp_path):
    """A fresh cache folder (a first run): the tour's kernels would compile."""
    root = Path(__file__).resolve().parents[2]
    code = "from knotmech.cli import tour; print(tour.kernels_cold())"
    env = {**os.environ, "NUMBA_CACHE_DIR": str(tmp_path / "numba"), "PYTHONPATH": str(root)}
    env.pop("NUMBA_DISABLE_JIT", None)
    out = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=120
    )
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "True"


@pytest.mark.parametrize("cold", [True, False])
def test_compiling_notice_only_when_the_cache_is_cold(cold, tmp_path, capsys, monkeypatch):
    monkeypatch.setattr(tour, "SECTIONS", list(tour.SECTIONS[:1]))
    monkeypatch.setattr(tour, "kernels_cold", lambda: cold)
    assert main(["tour", "--out", str(tmp_path / "t")]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert (lines[2] == tour.COMPILING_NOTICE) is cold
    assert (tour.COMPILING_NOTICE in lines) is cold
    assert "first run only" in tour.COMPILING_NOTICE


def test_sections_can_be_added_and_failures_are_reported(tmp_path, capsys, monkeypatch):
    monkeypatch.setattr(tour, "SECTIONS", list(tour.SECTIONS[:1]))

    def extra(ctx):
        return [f"extra section, out = {ctx.out.name}"]

    def broken(ctx):
        raise RuntimeError("boom")

    tour.register_section(extra)
    tour.register_section(broken, before=extra)
    assert [s.__name__ for s in tour.SECTIONS][-2:] == ["broken", "extra"]
    rc = main(["tour", "--out", str(tmp_path / "t")])
    captured = capsys.readouterr()
    assert rc == 1
    assert "extra section, out = t" in captured.out
    assert "broken failed: RuntimeError: boom" in captured.err


def test_out_must_be_a_folder(tmp_path, capsys):
    f = tmp_path / "file.txt"
    f.write_text("x")
    assert main(["tour", "--out", str(f)]) == 2
    err = capsys.readouterr().err
    assert "--out" in err and len(err.strip().splitlines()) == 1


@pytest.mark.parametrize("section", tour.SECTIONS)
def test_every_section_returns_lines(section, tmp_path):
    lines = section(tour.TourContext(out=tmp_path))
    assert lines and all(isinstance(s, str) for s in lines)

"""Classroom notebooks (jupytext percent scripts) run top to bottom with quick parameters.

Each notebook is executed as a script (runpy, Agg backend, KNOTMECH_QUICK=1) and a
number it computes is checked against a value worked out by hand.
"""

import math
import re
import runpy
import shutil
import subprocess
from pathlib import Path

import matplotlib
import pytest

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
NOTEBOOKS = ROOT / "notebooks"


def _check_capstan(ns):
    # ln(1000/10) / 0.3 / (2 pi) = 4.60517 / 0.3 / 6.28319 = 2.4431 turns
    assert ns["turns_ideal"] == pytest.approx(2.4431, abs=1e-4)
    # mu_eff(0.3, D/d = 1) = 0.146769 (clove-hitch paper eq. 3) -> 4.9939 turns
    assert ns["turns_thick"] == pytest.approx(4.9939, abs=1e-3)
    # 0.2623 measured on D/d = 7.5: 0.2623 * 8.5 / (7.5 - 0.2623**2) = 0.30003
    assert ns["mu_material"] == pytest.approx(0.3000, abs=5e-4)
    # DER capstan, D/d = 1: surface friction decays at mu_eff = 0.1468, centreline friction at mu
    assert ns["rate_surface"] == pytest.approx(0.1468, rel=0.05)
    assert ns["rate_centre"] == pytest.approx(0.3, rel=0.05)


def _check_coating(ns):
    # carrier viscosity 0.5886 mPa s * 1.5982 = 0.9407 mPa s; fibre film 2.828 um
    assert ns["eta"] == pytest.approx(0.9407e-3, rel=1e-3)
    assert ns["h_fibre"] == pytest.approx(2.8277e-6, rel=2e-3)
    # mu = 0.4 lies between the paper's 0 % (0.2) and 1 % (0.5) points
    assert 0.0 < ns["phi_needed"] < 0.01
    # one turn, mu = 0.9 on D/d = 4: mu_eff = 7.2 / (5 + sqrt(37.96)) = 0.64509,
    # exp(0.64509 * 2 pi) = 57.6
    assert ns["ratio_13"] == pytest.approx(math.exp(0.645094 * 2 * math.pi), rel=1e-4)
    assert ns["ratio_13"] == pytest.approx(57.6, abs=0.05)


def _check_hold(ns):
    # ideal-rope clove hitch, two turns: exp(0.3 * 4 pi) = 43.376
    assert ns["K_clove"] == pytest.approx(43.376, abs=1e-3)
    assert ns["verdict"].holds is False  # free end: the ideal rope slips at any load
    # thick-nip lock parameter at d, D = 4, 30 mm, mu = mu_rr = 0.3, by hand:
    # n = 2 sqrt(1 - (34/42)^2) = 1.174174; mu_eff(0.3, 7.5) = 0.262278;
    # (0.3 + 0.3) * 1.174174 * exp(0.262278 * 2 pi) = 0.704504 * 5.19615 = 3.6607
    assert ns["lock"] == pytest.approx(3.6607, abs=2e-3)
    # the boundary found by bisection agrees with hold_verdict's critical mu
    critical = ns["verdict"].answers[1].critical_mu
    assert ns["mu_lock_paper"] == pytest.approx(critical, abs=1e-6)


def _check_der(ns):
    assert ns["result"].status == "success"
    # Euler-Bernoulli cantilever under its weight: q L^4 / (8 EI) with q = 1200 * pi * 1e-6 * 9.81
    # = 0.036982 N/m, EI = 1e8 * pi * 1e-12 / 4 = 7.854e-5 N m^2, L = 0.1 m -> 5.886 mm
    assert ns["w_tip_theory"] == pytest.approx(5.886e-3, rel=1e-3)
    # the DER tip deflection converges to it at first order (fitted slope of log err vs log h)
    assert 0.8 < ns["order"] < 1.2
    assert ns["err"][-1] / ns["w_tip_theory"] < 0.06  # 41 nodes: within 6 %
    assert ns["tip_extrapolated"] == pytest.approx(ns["w_tip_theory"], rel=0.01)


def _check_diagnose(ns):
    # thick post, D/d = 2: mu_eff(0.3, 2) = 1.2 / (3 + sqrt(9.72)) = 0.19615 (clove-hitch eq. 3)
    assert ns["rate"] == pytest.approx(0.19615, abs=1e-5)
    assert ns["report"].verdict == "finite_thickness"
    assert ns["found"]["mu_eff"] == pytest.approx(0.19615, abs=0.005)
    assert ns["found"]["mu"] == pytest.approx(0.30, abs=0.01)
    assert ns["report_none"].verdict == "none"  # D/d = 200: nothing to find
    assert Path("thick_post_profile.csv").is_file()  # written in the test's tmp folder


CHECKS = {
    "capstan_and_thick_rods.py": _check_capstan,
    "coating_and_friction.py": _check_coating,
    "will_this_knot_hold.py": _check_hold,
    "first_der_simulation.py": _check_der,
    "diagnosing_a_recording.py": _check_diagnose,
}

ALL = sorted(p.name for p in NOTEBOOKS.glob("*.py"))


def test_every_notebook_has_a_check():
    assert ALL, "no notebooks found"
    assert set(ALL) == set(CHECKS), f"notebooks without a numeric check: {set(ALL) - set(CHECKS)}"


@pytest.mark.parametrize("name", ALL)
def test_notebook_runs_top_to_bottom(name, monkeypatch, tmp_path):
    monkeypatch.setenv("KNOTMECH_QUICK", "1")
    monkeypatch.setenv("MPLBACKEND", "Agg")
    monkeypatch.chdir(tmp_path)  # anything a notebook writes lands here
    try:
        namespace = runpy.run_path(str(NOTEBOOKS / name), run_name="__main__")
    finally:
        plt.close("all")
    assert namespace["QUICK"] is True
    CHECKS[name](namespace)


@pytest.mark.parametrize("name", ALL)
def test_notebook_is_jupytext_percent_with_markdown(name):
    jupytext = pytest.importorskip("jupytext")
    nb = jupytext.read(NOTEBOOKS / name)
    kinds = [cell.cell_type for cell in nb.cells]
    assert kinds[0] == "markdown" and kinds.count("markdown") >= 3 and "code" in kinds
    text = "".join(cell.source for cell in nb.cells if cell.cell_type == "markdown")
    assert "DOI" in text or "et al." in text  # the physics comes with references


def test_notebooks_extra_installs_what_opening_them_needs():
    """``pip install -e ".[notebooks]"`` brings jupyter, nbconvert, ipykernel and jupytext."""
    text = (ROOT / "pyproject.toml").read_text()
    line = re.search(r"^notebooks = \[(.*)\]$", text, re.M)
    assert line, "no notebooks extra in pyproject.toml"
    names = {re.split(r"[<>=!~\[ ]", s.strip().strip('"'))[0] for s in line.group(1).split(",")}
    assert {"jupyter", "nbconvert", "ipykernel", "jupytext"} <= names


def test_generated_ipynb_are_gitignored_and_the_scripts_are_not():
    if shutil.which("git") is None or not (ROOT / ".git").exists():
        pytest.skip("not a git checkout")

    def ignored(path):
        out = subprocess.run(
            ["git", "check-ignore", "-q", path], cwd=ROOT, capture_output=True, timeout=30
        )
        return out.returncode == 0

    assert ignored("notebooks/first_der_simulation.ipynb")
    assert ignored("notebooks/.ipynb_checkpoints/first_der_simulation-checkpoint.ipynb")
    assert not ignored("notebooks/first_der_simulation.py")


@pytest.mark.slow
def test_a_notebook_opened_as_the_readme_says_runs_in_a_jupyter_kernel(tmp_path, monkeypatch):
    """jupytext -> .ipynb -> executed by a real IPython kernel (what nbconvert --execute and
    Jupyter do), with the number it computes checked (about 25 s: kernel start + imports)."""
    jupytext = pytest.importorskip("jupytext")
    nbclient = pytest.importorskip("nbclient")
    pytest.importorskip("ipykernel")
    nb = jupytext.read(NOTEBOOKS / "will_this_knot_hold.py")
    nb.cells.append(jupytext.reads("print(f'K_clove = {K_clove:.3f}')", fmt="py:percent").cells[0])
    monkeypatch.setenv("KNOTMECH_QUICK", "1")
    monkeypatch.setenv("MPLBACKEND", "Agg")
    monkeypatch.setenv("PYTHONPATH", str(ROOT))
    client = nbclient.NotebookClient(
        nb, timeout=300, kernel_name="python3", resources={"metadata": {"path": str(tmp_path)}}
    )
    client.execute()
    outputs = [o for c in nb.cells if c.cell_type == "code" for o in c.get("outputs", [])]
    assert not [o for o in outputs if o.get("output_type") == "error"]
    text = "".join(o.get("text", "") for o in outputs if o.get("output_type") == "stream")
    assert "K_clove = 43.376" in text  # exp(0.3 * 4 pi), as in _check_hold

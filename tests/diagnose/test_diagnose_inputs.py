"""Every input of ``knotmech diagnose`` gets a clear answer (issue 13, the diagnose items).

Each case below crashed with a traceback (or hung, or gave a nonsense verdict) before:
now it is one line on stderr and exit status 2, or a verdict. The recordings are the
shipped templates (``knotmech/data/templates``) with one thing changed.
"""

from __future__ import annotations

import json
import re
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

from knotmech.cli.diagnose import template_kinds, template_text
from knotmech.cli.main import main
from knotmech.diagnose import diagnose, parse_recording, read_recording
from knotmech.diagnose.stats import ls_solve
from knotmech.errors import DiagnoseError, InputError, RecordingError

ROOT = Path(__file__).resolve().parents[2]
KINDS = ("capstan_pull", "pinch", "tension_profile")


def _table(kind):
    """(metadata lines, header, rows as float array) of a template."""
    lines = template_text(kind).splitlines()
    head = next(i for i, ln in enumerate(lines) if not ln.startswith("#"))
    rows = np.array([[float(c) for c in ln.split(",")] for ln in lines[head + 1 :]])
    return lines[:head], lines[head], rows


def _text(kind, *, meta=None, x=None, y=None, sigma=None, drop=()):
    """Template of ``kind`` with metadata values replaced and columns swapped in."""
    meta_lines, header, rows = _table(kind)
    out = []
    for ln in meta_lines:
        key = ln[1:].split(":", 1)[0].strip()
        if key in drop:
            continue
        if meta and key in meta:
            ln = f"# {key}: {meta[key]}"
        out.append(ln)
    for key, value in (meta or {}).items():
        if not any(ln[1:].split(":", 1)[0].strip() == key for ln in meta_lines):
            out.append(f"# {key}: {value}")
    xs = rows[:, 0] if x is None else np.broadcast_to(x, rows[:, 0].shape)
    ys = rows[:, 1] if y is None else np.broadcast_to(y, rows[:, 1].shape)
    out.append(header + (",sigma" if sigma is not None else ""))
    for i in range(xs.size):
        cells = [repr(float(xs[i])), repr(float(ys[i]))]
        if sigma is not None:
            cells.append(repr(float(np.broadcast_to(sigma, xs.shape)[i])))
        out.append(",".join(cells))
    return "\n".join(out) + "\n"


def _cli(args, capsys):
    try:
        rc = main([str(a) for a in args])
    except SystemExit as exc:  # argparse
        rc = exc.code
    cap = capsys.readouterr()
    return rc, cap.out, cap.err


def _one_line_error(tmp_path, capsys, content, *words, extra=(), name="rec.csv"):
    path = tmp_path / name
    if isinstance(content, bytes):
        path.write_bytes(content)
    else:
        path.write_text(content, encoding="utf-8")
    out_json = tmp_path / "r.json"
    rc, _out, err = _cli(["diagnose", path, "--json", out_json, *extra], capsys)
    assert rc == 2, err
    assert err.count("\n") == 1 and "Traceback" not in err, err
    assert err.startswith("knotmech diagnose: error: ")
    for w in words:
        assert w in err, err
    assert not out_json.exists()
    return err


# --- the tracebacks listed in issue 13 --------------------------------------------------


def _rows(kind):
    return _table(kind)[2]


CASES = {
    # all x equal / all x zero (ValueError: Each lower bound must be strictly less ...)
    "all x equal": ("pinch", {"x": 1.0}, ("all 40 rows have normal_force_N = 1",)),
    "all x zero": ("tension_profile", {"x": 0.0}, ("arclength_m = 0", "must vary")),
    # huge values (Initial guess is outside of provided bounds)
    "values x 1e300": (
        "pinch",
        {"x": _rows("pinch")[:, 0] * 1e300, "y": _rows("pinch")[:, 1] * 1e300},
        ("beyond the physical range (|value| <= 1e+09)",),
    ),
    "values x 1e-300": (
        "capstan_pull",
        {"x": _rows("capstan_pull")[:, 0] * 1e-300, "y": _rows("capstan_pull")[:, 1] * 1e-300},
        ("is not a measurement (nonzero below 1e-30)",),
    ),
    "youngs_modulus 1e300": (
        "pinch",
        {"meta": {"youngs_modulus_Pa": "1e300"}},
        ("youngs_modulus_Pa = 1e+300 is outside its physical range [100, 1e+13]",),
    ),
    "mu_nominal 0, capstan": (
        "capstan_pull",
        {"meta": {"mu_nominal": "0"}, "drop": ("mu_nominal_sigma",)},
        ("mu_nominal: 0 needs a mu_nominal_sigma",),
    ),
    "mu_nominal 0, tension": (
        "tension_profile",
        {"meta": {"mu_nominal": "0"}, "drop": ("mu_nominal_sigma",)},
        ("mu_nominal: 0 needs a mu_nominal_sigma",),
    ),
    "tiny mu_nominal_sigma": (
        "capstan_pull",
        {"meta": {"mu_nominal_sigma": "1e-300"}},
        ("mu_nominal_sigma = 1e-300 is outside its physical range [0.0001, 5]",),
    ),
    "sigma 1e-300": ("pinch", {"sigma": 1e-300}, ("sigma = 1e-300 is not a measurement",)),
    "one row at 1e-310": (
        "pinch",
        {"y": np.r_[_rows("pinch")[:-1, 1], 1e-310]},
        ("line 49: tangential_force_N = 1e-310 is not a measurement",),
    ),
    "x spacing 1e-310": (
        "pinch",
        {"x": np.arange(40) * 1e-310},
        ("normal_force_N = 1e-310 is not a measurement",),
    ),
    "x spacing 1e-310 around 1": (
        "pinch",
        {"x": 1.0 + np.arange(40) * 1e-310},
        ("all 40 rows have normal_force_N = 1",),
    ),
    "x spacing 1e-13 around 1": (
        "pinch",
        {"x": 1.0 + np.arange(40) * 1e-13},
        ("varies by only", "below 1e-9 of its size"),
    ),
    # the hang: locate._located took pinv of a Gram matrix holding an inf
    "wrap_angle 5e-324 with sigma": (
        "capstan_pull",
        {"meta": {"wrap_angle_rad": "5e-324"}, "sigma": 0.01},
        ("wrap_angle_rad = 4.94066e-324 is outside its physical range [0.001, 100]",),
    ),
    "wrap_angle 1e6": (
        "capstan_pull",
        {"meta": {"wrap_angle_rad": "1e6"}},
        ("outside its physical range [0.001, 100]",),
    ),
    # degenerate or nonsense data: refused at read time, never an effect
    "constant y": ("pinch", {"y": 0.5}, ("all 40 values of tangential_force_N are 0.5",)),
    "all-zero tangential force": ("pinch", {"y": 0.0}, ("every tangential_force_N value is 0",)),
    "constant tension": ("tension_profile", {"y": 3.0}, ("constant reading",)),
    "negative forces": (
        "pinch",
        {"y": -_rows("pinch")[:, 1]},
        ("tangential_force_N is negative in 40 of 40 rows",),
    ),
    "negative tension": ("tension_profile", {"y": -_rows("tension_profile")[:, 1]}, ("negative",)),
    "two distinct x": (
        "pinch",
        {"x": np.repeat([1.0, 2.0], 20), "y": np.repeat([0.5, 1.0], 20)},
        ("only 2 distinct values of normal_force_N; a diagnosis needs at least 3",),
    ),
    "duplicated rows": (
        "pinch",
        {"x": np.tile(_rows("pinch")[:5, 0], 8), "y": np.tile(_rows("pinch")[:5, 1], 8)},
        ("only 5 distinct rows among 40 (rows repeated)",),
    ),
}


@pytest.mark.parametrize("case", list(CASES))
def test_issue_cases_are_one_line_exit_2(case, tmp_path, capsys):
    kind, edits, words = CASES[case]
    _one_line_error(tmp_path, capsys, _text(kind, **edits), *words)


def test_mu_nominal_zero_with_its_sigma_is_diagnosed(tmp_path, capsys):
    """mu_nominal = 0 is a usable prior once its sigma is given: a verdict, exit 0."""
    path = tmp_path / "rec.csv"
    path.write_text(_text("pinch", meta={"mu_nominal": "0", "mu_nominal_sigma": "0.05"}))
    rc, out, err = _cli(["diagnose", path, "--json", tmp_path / "r.json"], capsys)
    assert rc == 0, err
    report = json.loads((tmp_path / "r.json").read_text())
    # the template's F_t/(2 F_n) is about 0.27; the prior at 0 +- 0.05 cannot hide that
    assert report["verdict"] != "none" or report["final"]["parameters"]["mu"] > 0.1


def test_cell_beyond_csv_field_limit(tmp_path, capsys):
    text = _text("pinch").replace(
        "normal_force_N,tangential_force_N\n",
        "normal_force_N,tangential_force_N\n" + '"' + "1" * 140000 + '",1\n',
    )
    _one_line_error(
        tmp_path,
        capsys,
        text,
        "line 10: a cell longer than 131072 characters (the CSV field limit)",
    )


def test_seed_minus_one(tmp_path, capsys):
    err = _one_line_error(tmp_path, capsys, _text("pinch"), extra=("--seed", "-1"))
    assert "seed must be an integer >= 0, got -1" in err
    with pytest.raises(InputError, match="seed must be an integer >= 0"):
        diagnose(parse_recording(_text("pinch")), seed=-1)


# --- the reader --------------------------------------------------------------------------


def test_utf8_bom_is_accepted(tmp_path):
    path = tmp_path / "excel.csv"
    path.write_bytes(b"\xef\xbb\xbf" + _text("pinch").encode("utf-8"))
    rec = read_recording(path)
    assert rec.experiment == "pinch" and rec.n == 40
    assert rec.metadata["knotmech-recording"] == 1.0


def test_bad_encoding_names_line_and_byte(tmp_path, capsys):
    text = _text("pinch").replace("# rod_diameter_m", "# operator: Ren\u00e9e\n# rod_diameter_m")
    err = _one_line_error(tmp_path, capsys, text.encode("latin-1"))
    # '# operator: Ren' is 15 bytes, the e-acute (0xe9) is byte 16 of line 4
    assert "rec.csv, line 4: byte 16 (0xe9) is not UTF-8" in err


@pytest.mark.parametrize(
    ("cell", "words"),
    [
        ("\uff10.5", "U+FF10 is not ASCII"),  # fullwidth zero
        ("\u0660.\u0665", "U+0660 is not ASCII"),  # Arabic-Indic digits
        ("1_0", "non-numeric cell '1_0'"),
        ("\u22120.5", "U+2212 is not ASCII"),  # Unicode minus
        ("0x10", "non-numeric cell '0x10'"),
    ],
)
def test_numbers_are_ascii_only(cell, words):
    meta_lines, header, rows = _table("pinch")
    lines = [*meta_lines, header, *(f"{float(a)!r},{float(b)!r}" for a, b in rows)]
    lines[len(meta_lines) + 3] = f"{float(rows[2, 0])!r},{cell}"
    with pytest.raises(RecordingError) as info:
        parse_recording("\n".join(lines) + "\n", source="r.csv")
    msg = str(info.value)
    assert msg.startswith(f"r.csv, line {len(meta_lines) + 4}: ") and words in msg
    assert "\n" not in msg


def test_fullwidth_metadata_value_is_not_a_number():
    text = _text("pinch", meta={"rod_diameter_m": "\uff10.008"})
    with pytest.raises(RecordingError, match="rod_diameter_m must be a number.*U\\+FF10"):
        parse_recording(text, source="r.csv")


def test_duplicated_metadata_key():
    text = _text("pinch").replace("# pinch_diameter_m", "# rod_diameter_m: 0.1\n# pinch_diameter_m")
    with pytest.raises(RecordingError, match=r"'rod_diameter_m' given twice \(lines 4 and 5\)"):
        parse_recording(text, source="r.csv")


def test_line_numbers_survive_form_feeds():
    """str.splitlines splits on \\x0c too; the reader must count real lines only."""
    text = _text("pinch")
    text = text.replace("# note:", "# note: a\x0cb,", 1).replace(
        "\n" + text.splitlines()[12] + "\n", "\n" + text.splitlines()[12].split(",")[0] + ",x\n"
    )
    with pytest.raises(RecordingError, match="line 13: non-numeric cell 'x'"):
        parse_recording(text, source="r.csv")


# --- outputs checked before any work ----------------------------------------------------


@pytest.mark.parametrize(
    ("args", "words"),
    [
        (["--json", "/nonexistent/dir/r.json"], "--json /nonexistent/dir/r.json: folder"),
        (["--json", "/dev/full"], "--json /dev/full: exists and is not a regular file"),
        (["--json", "{tmp}"], "is a directory"),
        (["--json", "{tmp}/r.json", "--plot", "/nonexistent/fit.png"], "--plot /nonexistent"),
        (["--json", "{tmp}/r.json", "--plot", "{tmp}/fit.xyz"], "unsupported format '.xyz'"),
        (["--json", "{tmp}/r.json", "--plot", "{tmp}/fit"], "no file extension"),
    ],
)
def test_output_paths_checked_before_reading(args, words, tmp_path, capsys):
    """The recording does not even exist: the output error comes first, nothing runs."""
    args = [a.replace("{tmp}", str(tmp_path)) for a in args]
    rc, out, err = _cli(["diagnose", tmp_path / "missing.csv", *args], capsys)
    assert rc == 2 and err.count("\n") == 1 and "Traceback" not in err
    assert words in err and "missing.csv" not in err
    assert out == ""


def test_plot_is_written(tmp_path, capsys):
    path = tmp_path / "rec.csv"
    path.write_text(template_text("pinch"))
    rc, out, err = _cli(
        ["diagnose", path, "--json", tmp_path / "r.json", "--plot", tmp_path / "fit.svg"], capsys
    )
    assert rc == 0, err
    assert (tmp_path / "fit.svg").read_text().lstrip().startswith("<?xml")
    assert f"plot: {tmp_path / 'fit.svg'}" in out


def test_missing_arguments(capsys):
    rc, _out, err = _cli(["diagnose"], capsys)
    assert rc == 2 and "missing REC.csv and --json" in err and err.count("\n") == 1


# --- templates and the shipped contract -------------------------------------------------


def test_template_kinds_cover_the_contract():
    assert set(KINDS) <= set(template_kinds())


@pytest.mark.parametrize("kind", KINDS)
def test_template_is_a_valid_baseline_recording(kind, tmp_path, capsys):
    rc, out, err = _cli(["diagnose", "--template", kind], capsys)
    assert rc == 0 and err == ""
    rec = parse_recording(out, source=f"{kind}.csv")
    assert rec.experiment == kind and rec.n == 40
    path = tmp_path / f"{kind}.csv"
    path.write_text(out)
    rc, out2, err = _cli(["diagnose", path, "--json", tmp_path / "r.json"], capsys)
    assert rc == 0, err
    report = json.loads((tmp_path / "r.json").read_text())
    # a baseline recording with white noise: the baseline explains it
    assert report["verdict"] == "none", out2
    assert abs(report["final"]["parameters"]["mu"] - rec.mu_nominal) < 0.1


def test_unknown_template(capsys):
    rc, _out, err = _cli(["diagnose", "--template", "knot"], capsys)
    assert rc == 2 and "no template for 'knot'; kinds: capstan_hold, capstan_pull" in err


def test_templates_are_package_data():
    text = (ROOT / "pyproject.toml").read_text()
    table = re.search(r"\[tool\.setuptools\.package-data\]\s*knotmech = \[([^\]]*)\]", text)
    globs = re.findall(r'"([^"]+)"', table.group(1))
    files = {p.relative_to(ROOT / "knotmech") for g in globs for p in (ROOT / "knotmech").glob(g)}
    for kind in KINDS:
        assert Path("data/templates") / f"{kind}.csv" in files


def test_contract_is_shipped_in_docs():
    doc = (ROOT / "docs" / "recordings.md").read_text(encoding="utf-8")
    for heading in ("## 1. The recording file", "## 4. The report", "## 6. What knotmech's"):
        assert heading in doc
    assert "`youngs_modulus_Pa` | 1e2 .. 1e13" in doc


# --- numerical guards (a regression here would hang or crash, not fail politely) --------


def test_pinv_of_a_gram_with_inf_is_refused_not_hung():
    """locate._located on a design holding inf: DiagnoseError at once (this OpenBLAS's
    pinv of such a matrix never returns), checked in a subprocess with a timeout."""
    code = textwrap.dedent(
        """
        import numpy as np
        from knotmech.diagnose.locate import _located
        from knotmech.errors import DiagnoseError
        x = np.linspace(0.0, 1.0, 10)
        design = np.eye(10)
        xw = np.eye(10)
        xw[0, 0] = np.inf
        try:
            _located(x, design, np.ones(10), xw, 1.0, 0.5)
        except DiagnoseError as exc:
            print("refused:", exc)
        """
    )
    res = subprocess.run(
        [sys.executable, "-c", code],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=60,
        env={"OPENBLAS_NUM_THREADS": "1", "PATH": "/usr/bin:/bin"},
    )
    assert res.returncode == 0, res.stderr
    assert "refused: locating the mismatch" in res.stdout


def test_ls_solve_refuses_non_finite_systems():
    a = np.ones((6, 2))
    a[3, 1] = np.inf
    with pytest.raises(DiagnoseError, match="overflow"):
        ls_solve(a, np.ones(6), step="a test")
    with pytest.raises(DiagnoseError, match="a test"):
        ls_solve(np.ones((6, 2)) * 1e200, np.ones(6), step="a test")
    # the finite system still solves: y = 2 + 3 x exactly
    x = np.linspace(0.0, 1.0, 6)
    coef = ls_solve(np.column_stack([np.ones(6), x]), 2.0 + 3.0 * x)
    assert np.allclose(coef, [2.0, 3.0], atol=1e-10)


def test_least_squares_guard_names_the_step():
    from knotmech.diagnose.baselines import build_model
    from knotmech.diagnose.fitting import _least_squares

    model = build_model(parse_recording(template_text("pinch")), ())
    with pytest.raises(DiagnoseError, match="fitting the pinch model .residuals at the start."):
        _least_squares(
            lambda p: np.array([np.inf, 1.0]), np.array([0.3]), model, "fitting the pinch model"
        )
    model.lower[0] = model.upper[0] = 0.3
    with pytest.raises(DiagnoseError, match="parameter mu has an empty range"):
        _least_squares(lambda p: p, np.array([0.3]), model, "fitting the pinch model")


def test_last_resort_names_the_function(monkeypatch):
    import knotmech.diagnose.baselines as baselines
    import knotmech.diagnose.engine as engine

    def broken(*args, **kwargs):
        raise np.linalg.LinAlgError("SVD did not converge")

    # the closed-form baseline's fit (knotmech.diagnose.baselines.ClosedFormBaseline)
    monkeypatch.setattr(baselines, "fit_baseline", broken)
    with pytest.raises(DiagnoseError, match=r"failed numerically in .*\(LinAlgError: SVD did not"):
        engine.diagnose(parse_recording(template_text("pinch")))


# --- --baseline der: refused before any simulation --------------------------------------


@pytest.mark.parametrize(
    ("edits", "words"),
    [
        # the ZeroDivisionError from a numba kernel (huge wrap)
        ({"meta": {"wrap_angle_rad": "50"}}, "baseline 'der' runs wraps up to 12.57 rad"),
        # ran past 300 s (negative displacements: a 1e-6 m pull at 60 steps per pull)
        ({"x": _rows("capstan_pull")[:, 0] - 0.06}, "needs displacements from about 0 up"),
        ({"x": _rows("capstan_pull")[:, 0] * 1e-3}, "steps per simulation (limit 1000)"),
    ],
)
def test_der_baseline_refuses_before_simulating(edits, words, tmp_path, capsys):
    _one_line_error(
        tmp_path, capsys, _text("capstan_pull", **edits), words, extra=("--baseline", "der")
    )


def test_frictionless_control_is_read_and_diagnosed(tmp_path, capsys):
    """F_t = noise about 0 (a mu = 0 control): about half the rows negative, not refused;
    the fitted mu is ~0 (the true value), the verdict is not an effect of nonsense."""
    rng = np.random.default_rng(5)
    fn = _rows("pinch")[:, 0]
    y = 0.01 * rng.standard_normal(fn.size)
    assert 0.3 < np.mean(y < 0) < 0.7
    path = tmp_path / "control.csv"
    path.write_text(_text("pinch", y=y, drop=("mu_nominal", "mu_nominal_sigma")))
    rc, out, err = _cli(["diagnose", path, "--json", tmp_path / "r.json"], capsys)
    assert rc == 0, err
    report = json.loads((tmp_path / "r.json").read_text())
    # 2 mu F_n with F_n up to ~19 N against 0.01 N noise: mu is pinned near 0
    assert report["baseline"]["parameters"]["mu"] < 1e-3
    assert report["verdict"] in ("none", "undetermined"), out


def test_report_never_overwrites_the_recording(tmp_path, capsys):
    path = tmp_path / "rec.csv"
    path.write_text(template_text("pinch"))
    rc, _out, err = _cli(["diagnose", path, "--json", path], capsys)
    assert rc == 2 and "is the recording itself" in err and err.count("\n") == 1
    assert path.read_text() == template_text("pinch")

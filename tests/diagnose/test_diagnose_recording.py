"""Recording files: the contract of shared/spec/recordings.md section 1 (read, validate)."""

import numpy as np
import pytest

from knotmech.cli.main import main
from knotmech.diagnose import parse_recording, read_recording, recording_from_arrays
from knotmech.errors import RecordingError

GOOD = """# knotmech-recording: 1
# experiment: pinch
# rod_diameter_m: 0.004
# pinch_diameter_m: 0.008
# youngs_modulus_Pa: 1.26e6
# mu_nominal: 0.32
# mu_nominal_sigma: 0.02
# operator: someone
normal_force_N,tangential_force_N
0.010,0.0066
0.020,0.0127
0.030,0.0190
0.040,0.0255
0.050,0.0321
0.060,0.0383
0.070,0.0450
0.080,0.0511
"""


def test_good_file_is_read(tmp_path):
    path = tmp_path / "pinch.csv"
    path.write_text(GOOD)
    rec = read_recording(path)
    assert rec.experiment == "pinch"
    assert rec.n == 8
    assert rec.x[0] == 0.010 and rec.y[-1] == 0.0511
    assert rec.mu_nominal == 0.32 and rec.mu_nominal_sigma == 0.02
    assert rec.metadata["operator"] == "someone"  # unknown keys kept
    assert rec.sigma is None and rec.speed is None
    assert np.all(rec.trial == 0)


def _bad(text):
    with pytest.raises(RecordingError) as exc:
        parse_recording(text, source="rec.csv")
    msg = str(exc.value)
    assert "\n" not in msg
    return msg


@pytest.mark.parametrize(
    ("edit", "line", "words"),
    [
        (lambda t: t.replace("# experiment: pinch\n", ""), 1, "missing '# experiment"),
        (lambda t: t.replace("experiment: pinch", "experiment: knot"), 2, "unknown experiment"),
        (
            lambda t: t.replace("# rod_diameter_m: 0.004\n", ""),
            8,
            "missing metadata '# rod_diameter_m",
        ),
        (lambda t: t.replace("normal_force_N,tangential", "force,tangential"), 9, "needs columns"),
        (
            lambda t: t.replace("tangential_force_N\n", "tangential_force_N,colour\n"),
            9,
            "unknown column",
        ),
        (lambda t: t.replace("0.030,0.0190", "0.030,abc"), 12, "non-numeric cell 'abc'"),
        (lambda t: t.replace("0.030,0.0190", "0.030,nan"), 12, "NaN"),
        (lambda t: t.replace("0.080,0.0511\n", ""), 9, "7 data rows; a recording needs at least 8"),
        (lambda t: t.replace("rod_diameter_m: 0.004", "rod_diameter_m: -0.004"), 3, "must be > 0"),
        (lambda t: t.replace("youngs_modulus_Pa: 1.26e6", "youngs_modulus_Pa: -5"), 5, "> 0"),
        (lambda t: t.replace("0.030,0.0190", "0.030"), 12, "expected 2 cells"),
    ],
)
def test_bad_files_name_file_line_and_problem(edit, line, words):
    msg = _bad(edit(GOOD))
    assert msg.startswith(f"rec.csv, line {line}: ")
    assert words in msg


def test_cli_bad_recording_is_one_line_exit_2(tmp_path, capsys):
    path = tmp_path / "bad.csv"
    path.write_text(GOOD.replace("0.030,0.0190", "0.030,abc"))
    rc = main(["diagnose", str(path), "--json", str(tmp_path / "out.json")])
    err = capsys.readouterr().err
    assert rc == 2
    assert err.count("\n") == 1 and "Traceback" not in err
    assert "bad.csv, line 12: non-numeric cell" in err
    assert not (tmp_path / "out.json").exists()


def test_optional_columns_and_speed_per_trial():
    text = GOOD.replace(
        "# operator: someone\n", "# speed_m_per_s_trial_0: 0.001\n# speed_m_per_s_trial_1: 0.01\n"
    )
    lines = text.splitlines()
    head = lines.index("normal_force_N,tangential_force_N")
    lines[head] += ",sigma,trial"
    for i in range(head + 1, len(lines)):
        lines[i] += f",0.001,{0 if i < head + 5 else 1}"
    rec = parse_recording("\n".join(lines) + "\n", source="t.csv")
    assert np.allclose(rec.sigma, 0.001)
    assert rec.trial.tolist() == [0, 0, 0, 0, 1, 1, 1, 1]
    assert rec.speed.tolist() == [0.001] * 4 + [0.01] * 4


def test_missing_trial_speed_is_an_error():
    text = GOOD.replace("# operator: someone\n", "# speed_m_per_s_trial_1: 0.01\n")
    assert "no speed_m_per_s_trial_0" in _bad(text)


def test_arrays_round_trip():
    x = np.linspace(0.1, 1.0, 10)
    meta = {
        "rod_diameter_m": np.float64(0.004),
        "pinch_diameter_m": 0.008,
        "youngs_modulus_Pa": 1.26e6,
    }
    rec = recording_from_arrays("pinch", x, 0.6 * x, metadata=meta)
    assert rec.experiment == "pinch" and rec.n == 10
    assert np.allclose(rec.y, 0.6 * x)
    with pytest.raises(RecordingError, match="at least 8"):
        recording_from_arrays("pinch", x[:5], x[:5], metadata=meta)

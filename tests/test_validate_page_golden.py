"""Golden test of the validation page's HTML (``knotmech.cli.validate.write_index``).

The page for a fixed set of results (every kind of value ``_cell`` renders: none, scalars,
short and long lists, tables of rows, nested dicts and lists past the depth limit, a
failed case with a traceback) was written by the code before its refactoring (issue 22,
``_cell`` CC 27 and ``write_index`` CC 22) and saved in
``tests/golden/docs_validate_page.json``; the page must stay identical, character for
character.
"""

import json
from pathlib import Path

from knotmech.cli.validate import write_index

GOLDEN = Path(__file__).parent / "golden" / "docs_validate_page.json"

RESULTS = [
    {
        "name": "capstan_decay",
        "verdict": "pass",
        "summary": "DER T(s) against exp(-mu_eff s/R) <for> D/d & mu.",
        "checks": {"rates within 1 %": True, "centreline gives mu": True},
        "seconds": 12.345,
        "figures": ["/tmp/x/capstan_decay.png", "capstan_decay_2.png"],
        "numbers": {
            "none": None,
            "flag": True,
            "count": 1091,
            "rate": 0.262278431,
            "tiny": 3.1e-06,
            "big": 1.5e7,
            "whole": 1091.0,
            "nan": float("nan"),
            "text": "a <b> & c",
            "empty_list": [],
            "empty_dict": {},
            "short": [0.1, 0.2, None, 3],
            "long": [float(k) / 7 for k in range(20)],
            "rows": [[1, 2.5, 3e-9], [4, 5.25, 6e-9]],
            "many_rows": [[k, k / 3] for k in range(15)],
            "wide_rows": [list(range(9)), list(range(9))],
            "ragged": [[1, 2], [3]],
            "nested": {"a": {"b": {"c": {"d": 1}}}, "e": [1, {"f": 2}]},
            "deep_list": [[{"x": [1, [2, [3]]]}]] * 14,
            "tuple": (1.0, 2.0),
            "other": {1, 2},
        },
        "notes": ["a note", "another <note>"],
    },
    {
        "name": "effect_recovery",
        "verdict": "fail",
        "summary": "",
        "checks": {"white nulls": False},
        "seconds": None,
        "figures": [],
        "numbers": {},
        "notes": [],
    },
    {
        "name": "broken",
        "verdict": "error",
        "traceback": "Traceback (most recent call last):\n  boom <here>",
    },
]


def _pages(tmp_path):
    quick = write_index(tmp_path / "quick", RESULTS, quick=True).read_text(encoding="utf-8")
    full = write_index(tmp_path / "full", RESULTS[:1], quick=False).read_text(encoding="utf-8")
    empty = write_index(tmp_path / "empty", [], quick=True).read_text(encoding="utf-8")
    return {"quick": quick, "full": full, "empty": empty}


def test_validation_page_is_unchanged(tmp_path):
    golden = json.loads(GOLDEN.read_text(encoding="utf-8"))
    assert _pages(tmp_path) == golden


if __name__ == "__main__":  # regenerate (only on the commit whose output is the reference)
    import tempfile

    with tempfile.TemporaryDirectory() as tmp:
        GOLDEN.write_text(json.dumps(_pages(Path(tmp)), indent=1) + "\n", encoding="utf-8")

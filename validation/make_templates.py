"""Write the example recordings of ``knotmech diagnose --template KIND``.

Run once (from the repository root) when a kind is added::

    python -m validation.make_templates

Each template is a baseline recording of its kind (no effect, white noise of 0.4 %
of the signal) from :func:`knotmech.diagnose.synth.make_recording`, 40 rows, values
rounded to 5 significant digits, with a ``mu_nominal`` prior in the metadata. It is
written to ``knotmech/data/templates/<kind>.csv``; the tests check that every
template reads and that ``knotmech diagnose`` finds its baseline (verdict ``none``).
"""

from __future__ import annotations

from pathlib import Path

from knotmech.diagnose.recording import EXPERIMENTS
from knotmech.diagnose.synth import make_recording

OUT = Path(__file__).resolve().parents[1] / "knotmech" / "data" / "templates"

#: the metadata keys of the contract, in the order a reader expects them
_ORDER = (
    "wrap_angle_rad",
    "T_low_N",
    "T_high_N",
    "rod_diameter_m",
    "post_diameter_m",
    "pinch_diameter_m",
    "youngs_modulus_Pa",
    "mu_nominal",
    "mu_nominal_sigma",
)


def template_text(kind: str, *, seed: int = 0, n: int = 40) -> str:
    """The text of the template recording of ``kind``."""
    rec, truth = make_recording(kind, None, n=n, seed=seed, mu_nominal=True)
    lines = [
        "# knotmech-recording: 1",
        f"# experiment: {kind}",
        f"# note: example written by 'knotmech diagnose --template {kind}' (synthetic: "
        f"knotmech.diagnose.synth, seed {seed}, no effect); replace the rows by your own",
    ]
    for key in _ORDER:
        if key in rec.metadata:
            lines.append(f"# {key}: {float(rec.metadata[key]):.5g}")
    lines.append(",".join(rec.columns))
    for xv, yv in zip(rec.x, rec.y, strict=True):
        lines.append(f"{float(xv):.5g},{float(yv):.5g}")
    return "\n".join(lines) + "\n"


def main() -> None:
    OUT.mkdir(parents=True, exist_ok=True)
    for kind in EXPERIMENTS:
        path = OUT / f"{kind}.csv"
        path.write_text(template_text(kind), encoding="utf-8")
        print(f"wrote {path}")


if __name__ == "__main__":
    main()

"""Shared fixtures: the optional reference data in ../shared, Agg backend."""

from pathlib import Path

import matplotlib
import pytest

matplotlib.use("Agg")

SHARED = Path(__file__).resolve().parents[2] / "shared"


@pytest.fixture
def shared_reference() -> Path:
    """Path to ../shared/reference; skips the test cleanly when it is absent."""
    ref = SHARED / "reference"
    if not ref.is_dir():
        pytest.skip("../shared/reference is not present")
    return ref

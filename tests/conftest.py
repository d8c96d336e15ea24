"""Shared fixtures: the optional reference data in ../shared, Agg backend; and one
floating-point profile for every machine the tests run on (:func:`_pin_float_profile`)."""

import os
import platform
import sys
from pathlib import Path


def _pin_float_profile() -> None:
    """Make the golden tests' bits the same on every x86-64-v3 machine (AVX2 and FMA).

    numba compiles for the host CPU, and numpy dispatches its loops by the host's SIMD level:
    on an AVX-512 EPYC 11 golden runs moved by one unit in the last place (session 15), and
    a CPU's own cost model moved the fastmath kernels' bits. So the tests compile numba for
    the generic ``x86-64-v3`` and keep numpy below AVX-512 (unless the caller set these);
    both act only if set before numpy and numba are imported, which is why this runs here,
    first. Other CPUs keep their defaults (their goldens may differ: regenerate there)."""
    if platform.machine().lower() not in ("x86_64", "amd64"):
        return
    try:
        flags = set(Path("/proc/cpuinfo").read_text().split("flags", 2)[1].split("\n")[0].split())
    except (OSError, IndexError):
        return
    if not {"avx2", "fma", "bmi2", "movbe"} <= flags:
        return
    if "numpy" in sys.modules or "numba" in sys.modules:
        print("conftest: numpy or numba imported before the float profile was pinned; "
              "golden bits may differ on this machine", file=sys.stderr)  # fmt: skip
    os.environ.setdefault("NUMBA_CPU_NAME", "x86-64-v3")
    os.environ.setdefault(
        "NPY_DISABLE_CPU_FEATURES", "AVX512F AVX512_SKX X86_V4 AVX512_ICL AVX512_SPR"
    )


_pin_float_profile()

import matplotlib  # noqa: E402
import pytest  # noqa: E402

matplotlib.use("Agg")

SHARED = Path(__file__).resolve().parents[2] / "shared"


@pytest.fixture
def shared_reference() -> Path:
    """Path to ../shared/reference; skips the test cleanly when it is absent."""
    ref = SHARED / "reference"
    if not ref.is_dir():
        pytest.skip("../shared/reference is not present")
    return ref

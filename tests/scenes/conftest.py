"""Fixtures shared by the scene tests."""

import importlib

import pytest


@pytest.fixture
def butterfly_tip_over_the_twist(monkeypatch):
    """A function that changes the alpine butterfly's control polygon so that the tongue's
    tip lies over the lower twist (C1) instead of being tucked under it and up through the
    window (a false butterfly, which pulls out: its cut halves are unknots, linked once),
    and returns the module (call its ``alpine_butterfly``); undone after the test."""

    def patch():
        ab = importlib.import_module("knotmech.scenes.tied.alpine_butterfly")
        over = {(-1.5, -1.8): 2.5, (-1.5, -3.1): 3.0, (-1.5, -4.9): 3.0, (-1.5, -6.2): 2.5,
                (1.5, -1.8): 2.5, (1.5, -3.1): 3.0, (1.5, -4.9): 3.0, (1.5, -6.5): 2.5}  # fmt: skip
        for leg in ("LEG_A", "LEG_B"):
            pts = getattr(ab, leg)
            monkeypatch.setattr(ab, leg, tuple((x, y, over.get((x, y), z)) for x, y, z in pts))
        return ab

    return patch

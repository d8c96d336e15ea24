"""Fixtures shared by the scene tests."""

import importlib

import pytest


@pytest.fixture
def butterfly_over_the_window(monkeypatch):
    """A function that changes the alpine butterfly's control polygon so that the tongue
    lies over both arms of the window, not through it (the same crossings, not tied: the
    eye's halves unlinked), and returns the module (call its ``alpine_butterfly``); undone
    after the test."""

    def patch():
        ab = importlib.import_module("knotmech.scenes.tied.alpine_butterfly")
        over = {(-6.0, -6.5): 1, (-9.0, -6.5): 1, (-6.0, -9.5): 1}
        arm = {(-5.5, -9.5), (-6.5, -8.0), (-5.5, -6.5)}
        a = tuple((x, y, over.get((x, y), z)) for x, y, z in ab.LEG_A)
        b = tuple((x, y, -1 if (x, y) in arm else over.get((x, y), z)) for x, y, z in ab.LEG_B)
        monkeypatch.setattr(ab, "LEG_A", a)
        monkeypatch.setattr(ab, "LEG_B", b)
        return ab

    return patch

"""Tests of knotmech.analytic (a package so that basenames may repeat elsewhere in tests/)."""

"""SymPy derivations, one script per result; each exposes functions returning the expressions.

Run any of them as a script (``python derivations/mu_eff.py``) to print its results;
the tests load them by path and compare every derived expression with the numeric
implementation in :mod:`knotmech.analytic` (lambdify at random points).

- ``capstan_ode``: ideal capstan ODE and profile, Howell nonlinear friction, elastica
  lift-off with bending rigidity.
- ``mu_eff``: effective friction of a thick rod from force and moment balance.
- ``hitches``: wrap / nip chain model of the clove hitch, half hitches and round turn.
- the other scripts here (LLD film scaling, the Jawed braid law, the loose-knot law)
  are described in their own docstrings.

This folder is not part of the installed package (it lives in the source checkout).
"""

# ---
# jupyter:
#   jupytext:
#     text_representation:
#       extension: .py
#       format_name: percent
#       format_version: '1.3'
#   kernelspec:
#     display_name: Python 3
#     language: python
#     name: python3
# ---

# %% [markdown]
# # Will this knot hold?
#
# A hitch ties a rope to a post. Why does it hold a load, and when does it not?
# The classic answer treats the knot as a chain of two kinds of elements
# (Bayman, Am. J. Phys. 45, 185, 1977; Maddocks & Keller, SIAM J. Appl. Math.
# 47, 1185, 1987):
#
# * **wraps**: rope on the post (or on itself) over an angle $\theta$; at the
#   onset of slip the tension changes by at most the capstan factor $e^{\mu\theta}$;
# * **nips**: a strand pinched under a crossing *rider*; the rider presses it
#   with a normal force $N$, and friction on both faces can take up to
#   $(\mu_\mathrm{below} + \mu_\mathrm{above}) N$ of tension.
#
# Reading the chain from the free end to the load gives the largest load held,
# $T_\mathrm{high} \le K\,T_\mathrm{low}$.

# %%
import os

import matplotlib.pyplot as plt
import numpy as np

from knotmech.analytic import hitch
from knotmech.plotting import phase_diagram_plot

QUICK = os.environ.get("KNOTMECH_QUICK", "0") == "1"
n_grid = 12 if QUICK else 40

# %% [markdown]
# ## The ideal rope: every hitch is a capstan
#
# For a rope of zero thickness a rider crossing a strand is not deflected, so it
# presses with no force: nips do nothing and $K = e^{\mu\Theta}$ with $\Theta$
# the total wrap. The clove hitch (two turns on the post) gives $e^{4\pi\mu}$.

# %%
mu = 0.3
for knot in hitch.KNOTS:
    K = float(hitch.ideal_hitch_ratio(knot, mu))
    print(f"{knot:30s} K = {K:10.1f}   ({hitch.KNOTS[knot].description})")
K_clove = float(hitch.ideal_hitch_ratio("clove-hitch", mu))

# %% [markdown]
# The consequence is stark. $T_\mathrm{high} \le K\,T_\mathrm{low}$ is linear in
# $T_\mathrm{low}$: **with a free end ($T_\mathrm{low} = 0$) the ideal-rope clove
# hitch slips at any load**, however thick the rope or the post.

# %%
verdict = hitch.hold_verdict(
    "clove-hitch", rod_diameter=4e-3, post_diameter=30e-3, mu=mu, load=1.47, free_end_load=0.0
)
for answer in verdict.answers:
    tag = "decides" if answer.decides else "for comparison"
    print(f"{answer.model:10s} ({tag}): holds = {answer.holds}, margin = {answer.margin:g}")
for note in verdict.notes:
    print("note:", note)

# %% [markdown]
# ## Real rods have a thickness, and experiments disagree
#
# The clove-hitch paper ("Exploring the inner workings of the clove hitch knot",
# Extreme Mech. Lett., DOI 10.1016/j.eml.2022.101788, Sec. 8, Fig. 4) ties elastic
# rods with a free end and finds that the clove hitch **does hold**, up to a
# critical load $T_\mathrm{high}/EA$ that depends on $d/2R$. The ideal rope misses
# two things: a rod of diameter $d$ lifts the rider that crosses it, so the rider
# presses with a real force, and the rod's bending stiffness and thickness change
# the contact (see the capstan notebook: $\mu_\mathrm{eff} < \mu$).
#
# knotmech's *thick-nip* model keeps Bayman's chain but gives the rider a
# deflection set by $d$: $N = n\,T_\mathrm{rider}$ with
# $n = 2\sqrt{1 - ((D+d)/(D+3d))^2}$. When the nip near the free end is pressed
# hard enough by the tension it holds back, the chain *self-locks*: the lock
# parameter $\Lambda = (\mu + \mu_{rr})\,n\,e^{\mu_\mathrm{eff}\theta_o} \ge 1$.
# This model is derived in the package (``derivations/hitches.py``), not taken from
# the papers, and it is load-independent, unlike the experiments: a
# centreline-plus-nip model is an explanation to test, not an answer.

# %%
lock = float(
    hitch.thick_hitch_lock_parameter("clove-hitch", mu, rod_diameter=4e-3, post_diameter=30e-3)
)
print(f"paper geometry (d, D = 4, 30 mm), mu = {mu}: lock parameter = {lock:.3f}")

# %% [markdown]
# Where does the thick-nip model lock? Scan rod-to-post size $d/2R$ (with
# $R = (D+d)/2$, the paper's axis) and friction, and find the boundary
# $\Lambda = 1$ by bisection in $\mu$.

# %%
post = 30e-3
x_axis = np.linspace(0.02, 0.45, n_grid)  # d / 2R = d / (D + d)
mus = np.linspace(0.02, 0.5, n_grid)
X, M = np.meshgrid(x_axis, mus)
d_grid = X * post / (1 - X)  # from d/(D+d) = x
locks = (
    hitch.thick_hitch_lock_parameter("clove-hitch", M, rod_diameter=d_grid, post_diameter=post) >= 1
)


def critical_mu(x, lo=1e-4, hi=2.0, iters=50):
    d = x * post / (1 - x)
    for _ in range(iters):
        mid = 0.5 * (lo + hi)
        if (
            hitch.thick_hitch_lock_parameter("clove-hitch", mid, rod_diameter=d, post_diameter=post)
            >= 1
        ):
            hi = mid
        else:
            lo = mid
    return 0.5 * (lo + hi)


boundary = np.array([critical_mu(x) for x in x_axis])
fig, ax = plt.subplots(figsize=(6.5, 4.5), layout="constrained")
phase_diagram_plot(
    X.ravel(),
    M.ravel(),
    locks.ravel(),
    boundary=(x_axis, boundary),
    theory={"ideal rope: slips at any load (free end)": (x_axis, np.full_like(x_axis, np.inf))},
    ylabel=r"friction coefficient $\mu$",
    xlabel=r"$d/2R$",
    ax=ax,
    title="clove hitch with a free end: thick-nip model",
    note="thickness lifts the rider: the nip grips and the hitch can lock",
    boundary_label=r"lock boundary $\Lambda = 1$",
)
fig
mu_lock_paper = critical_mu(4e-3 / 34e-3)
print(f"thick-nip locking needs mu >= {mu_lock_paper:.3f} at the paper's d/2R = {4 / 34:.3f}")

# %% [markdown]
# ## What the simulation adds
#
# Neither model predicts the load dependence seen in the experiments. The
# discrete-elastic-rods simulation of the clove hitch (bending stiffness, finite
# thickness, frictional contact; validation case 3 of knotmech) produces the
# hold/slip phase diagram over $T_\mathrm{high}/EA$ and $d/2R$, and
# `knotmech hold` will report it next to these closed forms when it lands.
#
# **Things to try.** Which hitch needs the least friction to hold 100 N with 5 N
# on the tail (`hitch.hitch_critical_mu`)? How does the lock parameter change
# when the rope is much thinner than the post?

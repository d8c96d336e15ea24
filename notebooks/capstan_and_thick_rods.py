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
# # The capstan, and why thick rods grip less
#
# A sailor holds a boat with a few turns of rope around a bollard. The rope
# slides only when the pull on the loaded side, $T_\mathrm{high}$, exceeds the
# holding force $T_\mathrm{low}$ by the **capstan (Euler-Eytelwein) factor**
#
# $$\frac{T_\mathrm{high}}{T_\mathrm{low}} = e^{\mu\theta},$$
#
# with $\mu$ the friction coefficient and $\theta$ the wrap angle.
#
# **Where it comes from.** Take a short piece of rope of angle $d\theta$ on the
# post. The two tensions $T$ and $T + dT$ at its ends are almost opposite; their
# sum points toward the post and has magnitude $T\,d\theta$: that is the normal
# force $dN$. At the onset of sliding, Amontons-Coulomb friction carries the
# difference, $dT = \mu\,dN = \mu T\,d\theta$, so $dT/T = \mu\,d\theta$ and the
# tension grows exponentially with the wrap angle. Along the arc length
# $s = R\theta$ on a post of centreline radius $R$, $T(s) = T_\mathrm{high}
# e^{-\mu s/R}$ from the loaded end.
#
# References: L. Euler (1762); J. A. Eytelwein (1808); the clove-hitch paper
# ("Exploring the inner workings of the clove hitch knot", Extreme Mech. Lett.,
# DOI 10.1016/j.eml.2022.101788), eq. (3) and Fig. 3b.

# %%
import os

import matplotlib.pyplot as plt
import numpy as np

from knotmech.analytic.capstan import capstan_ratio, mu_eff, mu_from_mu_eff
from knotmech.plotting import capstan_ratio_plot, tension_decay_plot

QUICK = os.environ.get("KNOTMECH_QUICK", "0") == "1"
n_points = 50 if QUICK else 400

# %% [markdown]
# ## How many turns does it take?
#
# Hold a 1000 N load with your hand pulling 10 N: the ratio is 100. With
# $\mu = 0.3$ (rope on a steel bollard, roughly), $\theta = \ln(100)/\mu$.

# %%
mu = 0.3
ratio_needed = 1000.0 / 10.0
theta_needed = np.log(ratio_needed) / mu
turns_ideal = theta_needed / (2 * np.pi)
print(f"wrap angle {theta_needed:.2f} rad = {turns_ideal:.2f} turns")
print("check: capstan_ratio gives", float(capstan_ratio(mu, theta_needed)))

# %% [markdown]
# ## Real rods have a thickness
#
# The rope of the textbook has no thickness and no bending stiffness. A rod of
# diameter $d$ on a post of diameter $D$ touches the post on its surface, half a
# diameter away from its centreline. The friction force acts there, so it also
# applies a *couple* to the cross-section; balancing it takes a shear force, whose
# variation along the rod adds to the normal force. The net effect is a smaller
# decay rate (Jung, Pan & Kang, Mech. Mach. Theory 43 (2008) 661; clove-hitch
# paper eq. 3):
#
# $$\mu_\mathrm{eff} = \frac{-(1+\tilde D) + \sqrt{(1+\tilde D)^2 + 4\mu^2\tilde D}}{2\mu},
# \qquad \tilde D = D/d,$$
#
# and $T(s) \propto e^{-\mu_\mathrm{eff} s/R}$ with $R = (D+d)/2$. A thin rope
# on a thick post ($\tilde D \to \infty$) recovers $\mu$; a rod as thick as the
# post ($\tilde D = 1$) keeps only half of it.

# %%
for D_over_d in (1.0, 2.0, 7.5, 30.0, 1000.0):
    print(f"D/d = {D_over_d:7.1f}:  mu_eff = {float(mu_eff(mu, D_over_d)):.4f}")

# %%
fig, axes = plt.subplots(1, 2, figsize=(11, 4.2), layout="constrained")
s_over_R = np.linspace(0, 4 * np.pi, n_points)
tension_decay_plot(
    s_over_R,
    mu=mu,
    D_over_d=(1.0, 2.0, 7.5, 30.0),
    ax=axes[0],
    title="tension along the wrap (log scale: straight lines)",
)
capstan_ratio_plot(np.linspace(0, 6 * np.pi, n_points), mu=mu, D_over_d=(1.0, 7.5), ax=axes[1])
fig

# %% [markdown]
# The thick rod needs more turns to hold the same load:

# %%
D_over_d = 1.0
turns_thick = np.log(ratio_needed) / float(mu_eff(mu, D_over_d)) / (2 * np.pi)
print(f"ideal rope: {turns_ideal:.2f} turns; rod with D/d = {D_over_d:g}: {turns_thick:.2f} turns")

# %% [markdown]
# ## Reading a measurement the right way round
#
# Suppose a tension profile measured on a post with $D/d = 7.5$ (the clove-hitch
# paper's 30 mm post and 4 mm rod) decays as $e^{-0.262\,s/R}$. Fitting the
# textbook capstan to it would report $\mu = 0.262$; the material coefficient is
# larger. `mu_from_mu_eff` inverts the relation.

# %%
measured_rate = 0.2623
mu_material = float(mu_from_mu_eff(measured_rate, 7.5))
print(f"decay rate {measured_rate} on D/d = 7.5  ->  material mu = {mu_material:.3f}")

# %% [markdown]
# ## Seeing it in a simulation
#
# Is the couple really what lowers the rate? knotmech's discrete-elastic-rods
# simulation of a capstan (`knotmech.scenes.capstan`) pulls a rod over a post
# with friction acting on the rod's surface, as in reality. We can also switch
# the friction to the centreline (`surface_friction=False`), which removes the
# couple. A rod as thick as the post ($D/d = 1$), half a turn, pulled until it
# slides; the bending stiffness is made rope-like so that the rod hugs the post.

# %%
from knotmech.scenes.capstan import capstan


def simulated_rate(surface_friction):
    d, D, t_low = 4e-3, 4e-3, 0.05
    R = (D + d) / 2
    run = capstan(
        wrap_angle=np.pi,
        mu=mu,
        rod_diameter=d,
        post_diameter=D,
        youngs_modulus=1.26e6,
        density=1160.0,
        t_low=t_low,
        bending_stiffness=0.01 * t_low * R**2,
        surface_friction=surface_friction,
    )
    on_post = run.contact[:-1] & run.contact[1:]  # edges touching the post
    s = (run.s[on_post] - run.s[on_post][0]) / R
    tension = run.tension[on_post] / run.tension[on_post][0]
    inner = slice(len(s) // 10, len(s) - len(s) // 10)  # skip the lift-off regions
    return -np.polyfit(s[inner], np.log(tension[inner]), 1)[0], (s, tension)


rate_surface, profile_surface = simulated_rate(True)
rate_centre, profile_centre = simulated_rate(False)
print(f"theory: mu = {mu}, mu_eff(D/d = 1) = {float(mu_eff(mu, 1.0)):.4f}")
print(f"DER, friction on the surface:    decay rate {rate_surface:.4f}")
print(f"DER, friction at the centreline: decay rate {rate_centre:.4f}")

# %%
fig, ax = plt.subplots(figsize=(6, 4), layout="constrained")
tension_decay_plot(
    np.linspace(0, profile_surface[0].max(), n_points),
    mu=mu,
    D_over_d=(1.0,),
    profiles={1.0: profile_surface},
    ax=ax,
    title="DER capstan, D/d = 1",
)
ax.plot(*profile_centre, color="0.3", lw=1, label="DER, friction at the centreline")
ax.legend(fontsize=7)
fig

# %% [markdown]
# **Things to try.** Change $\mu$ and see that thick rods lose *relatively* more
# grip at high friction. What is $\mu_\mathrm{eff}$ for a rod wound on itself
# ($D = d$)? Why can $\mu_\mathrm{eff}$ never exceed $\sqrt{\tilde D}$, whatever
# the material?

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
# # Coating a rod, and tuning its friction
#
# To study how friction shapes a knot, the coated-rod paper ("Systematic
# Variation of Friction of Rods", J. Appl. Mech., DOI 10.1115/1.4055544) dips a
# 1.59 mm rubber rod into a liquid carrying a polymer binder and iron particles,
# pulls it out at 5 mm/s and dries it. The particles stick in the binder film and
# roughen the surface: more particles, more friction.
#
# Two questions for this notebook:
#
# 1. How thick is the liquid film the rod carries out of the bath?
#    (Landau-Levich-Derjaguin, LLD.)
# 2. Which particle fraction gives the friction coefficient we want?

# %%
import os

import matplotlib.pyplot as plt
import numpy as np

from knotmech.analytic import coating, film
from knotmech.analytic.capstan import mu_eff

QUICK = os.environ.get("KNOTMECH_QUICK", "0") == "1"
n_points = 60 if QUICK else 400

# %% [markdown]
# ## 1. The film: viscous drag against capillary pressure
#
# A solid pulled out of a wetting liquid drags a film up with it. Viscosity
# $\eta$ pulls the liquid along at the speed $U$; surface tension $\gamma$ resists
# bending the free surface where the thin film joins the static meniscus. The
# ratio of the two is the **capillary number** $\mathrm{Ca} = \eta U/\gamma$.
# Matching the curvature of the thin-film region to that of the static meniscus
# gives $h \propto \mathrm{Ca}^{2/3}/\kappa_s$ (Landau & Levich 1942; Derjaguin
# 1943). For a thin fibre of radius $r$, $\kappa_s = 1/r$ and
#
# $$h = 1.34\, r\, \mathrm{Ca}^{2/3}$$
#
# (Goucher & Ward 1922; Quere, Annu. Rev. Fluid Mech. 31, 347, 1999), valid for
# $\mathrm{Ca} \ll 1$ and $r$ much smaller than the capillary length
# $\ell_c = \sqrt{\gamma/\rho g}$. For a plate, $h = 0.946\,\ell_c\,\mathrm{Ca}^{2/3}$.

# %% [markdown]
# **The carrier.** 5 % (by volume) PMMA, $M_w \approx 15\,000$ g/mol, in
# 1,3-dioxolane; $\gamma = 34.3$ mN/m (paper). The paper gives no viscosity. The
# solvent alone has 0.59 mPa s; a dilute polymer raises it by
# $1 + c[\eta] + k_H (c[\eta])^2$ (Huggins), with the intrinsic viscosity
# $[\eta] = K M^a$ (Mark-Houwink; for PMMA in THF $K = 7.56\times10^{-5}$ dL/g,
# $a = 0.731$, Chen et al., Polym. Bull. 30, 575, 1993) and $k_H \approx 0.35$.

# %%
r = 1.59e-3 / 2  # rod radius [m]
U = 5e-3  # withdrawal speed [m/s]
gamma = 34.3e-3  # [N/m]
rho = 0.95 * 1060 + 0.05 * 1190  # carrier density [kg/m^3]
intrinsic = 7.56e-5 * 15000**0.731  # [dL/g]
c = 0.05 * 1.19 * 100  # [g/dL]
eta = 0.5886e-3 * (1 + c * intrinsic + 0.35 * (c * intrinsic) ** 2)  # [Pa s]
Ca = float(film.capillary_number(eta, U, gamma))
l_c = float(film.capillary_length(gamma, rho))
h_fibre = float(film.film_thickness_fibre(r, eta, U, gamma))
print(f"eta = {eta * 1e3:.2f} mPa s, Ca = {Ca:.2e}, l_c = {l_c * 1e3:.2f} mm")
print(f"r/l_c = {r / l_c:.2f}")
print(f"wet film (fibre law): {h_fibre * 1e6:.2f} um")
print(f"dried binder layer: {0.05 * h_fibre * 1e6:.3f} um")

# %% [markdown]
# Two warnings come out of these numbers.
#
# * $r/\ell_c = 0.44$: the 1.59 mm rod is *not* thin compared with the capillary
#   length, so the fibre law is only an upper estimate. `film.film_thickness`
#   refuses to pick a regime here (with `strict=False` it says why).
# * The paper measures a dried polymer layer of $5.85 \pm 0.17\ \mu$m, forty
#   times more than $0.05\,h$. LLD with the carrier's viscosity does not explain
#   it: solvent evaporation in the meniscus (dioxolane is volatile) probably
#   thickens the binder as the rod leaves the bath. A model is only as good as
#   its inputs, and here the key input (the viscosity at the meniscus) is unknown.

# %%
verdict = film.film_thickness(
    viscosity=eta, speed=U, surface_tension=gamma, density=rho, radius=r, strict=False
)
print("regime:", verdict.regime, "-", verdict.message)

etas = np.geomspace(1e-4, 0.3, n_points)
fig, ax = plt.subplots(figsize=(6, 4), layout="constrained")
h_sweep = film.film_thickness_fibre(r, etas, U, gamma)
ax.loglog(etas * 1e3, h_sweep * 1e6, label="wet film, fibre law")
ax.loglog(etas * 1e3, 0.05 * h_sweep * 1e6, label="dried binder layer (5 %)")
ax.axhline(5.85, color="C3", label="measured dried layer")
ax.axvline(eta * 1e3, color="k", ls="--", label="estimated carrier")
ax.set_xlabel("viscosity [mPa s]")
ax.set_ylabel("thickness [um]")
ax.legend(fontsize=8)
fig

# %% [markdown]
# ## 2. Friction from particles
#
# The paper fits the friction coefficient of the coated rods by matching DER
# simulations of tightening overhand knots to the measured pulling force:
# $\mu = 0.2, 0.5, 0.6, 0.7, 0.9$ for $\phi_p = 0, 1, 4, 7, 13\,\%$ particles
# (its Fig. 12). `coating.coated_rod_mu` interpolates these monotonically (PCHIP),
# and `coating.coated_rod_volume_fraction` answers the design question.

# %%
phi = np.linspace(0, 0.13, n_points)
fig, ax = plt.subplots(figsize=(6, 4), layout="constrained")
ax.plot(phi * 100, coating.coated_rod_mu(phi), label="interpolation")
ax.plot(coating.COATING_VOLUME_FRACTION * 100, coating.COATING_MU, "ko", label="paper (DER fits)")
ax.set_xlabel("particle volume fraction [%]")
ax.set_ylabel("friction coefficient")
ax.legend()
fig

# %%
mu_wanted = 0.4
phi_needed = float(coating.coated_rod_volume_fraction(mu_wanted))
print(f"for mu = {mu_wanted}: {phi_needed * 100:.2f} % particles")

# %% [markdown]
# ## Putting it together: a coated rod on a post
#
# How much more can a coated rod hold with one turn on a post four times its
# diameter? Thickness matters ($\mu_\mathrm{eff} < \mu$, see the capstan notebook).

# %%
theta = 2 * np.pi
for phi_p in (0.0, 0.01, 0.13):
    mu_p = float(coating.coated_rod_mu(phi_p))
    ratio = float(np.exp(mu_eff(mu_p, 4.0) * theta))
    print(f"phi_p = {phi_p * 100:4.1f} %: mu = {mu_p:.2f}, one turn on D/d = 4 holds {ratio:.1f}x")
ratio_13 = float(np.exp(mu_eff(float(coating.coated_rod_mu(0.13)), 4.0) * theta))

# %% [markdown]
# **Things to try.** Which withdrawal speed would give a 10 um wet film? How
# sensitive is the answer to the viscosity you assume? Outside 0-13 % the
# interpolation refuses to extrapolate: why is that the right behaviour?

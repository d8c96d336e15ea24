"""Whether the solver's numba kernels still have to be compiled (public; the kernels
themselves live in the private ``knotmech.rod._kernels``).

A command that runs a DER simulation can tell its user that the first run compiles the
kernels (about a minute) before it starts: :func:`kernels_cold`.
"""

from __future__ import annotations

import importlib

__all__ = ["kernels_cold", "simulation_kernels"]

# every DER simulation compiles these (elastic forces and Hessians, frames, the band
# solvers of the contact Jacobian); ``module.function`` in knotmech.rod._kernels
_CORE = (
    "stretch.stretch_grad_hess",
    "bend.bend_grad_hess",
    "twist.twist_grad_hess",
    "elastic_eval.elastic_frames",
    "envelope.env_factor",
    "envelope.env_solve",
)
_CYLINDER = ("contact_cylinder.cylinder_assemble",)
_ROD_ROD = ("contact_rodrod.rodrod_assemble", "contact_broadphase.sweep_pairs")


def simulation_kernels(*, cylinder_contact: bool = False, rod_contact: bool = False):
    """Names (``module.function`` of ``knotmech.rod._kernels``) of the kernels a simulation
    compiles: the elastic and solver kernels, plus those of rod-cylinder
    (:class:`~knotmech.rod.CylinderContact`) and rod-rod (:class:`~knotmech.rod.RodContact`)
    contact when asked."""
    return _CORE + (_CYLINDER if cylinder_contact else ()) + (_ROD_ROD if rod_contact else ())


def _cold(name: str) -> bool:
    module, func = name.rsplit(".", 1)
    kernel = getattr(importlib.import_module(f"knotmech.rod._kernels.{module}"), func)
    cache = getattr(kernel, "_cache", None)
    index = getattr(cache, "_cache_file", None)
    if index is None:  # not a caching numba dispatcher (e.g. NUMBA_DISABLE_JIT=1)
        return False
    try:
        return not index._load_index()
    except Exception:  # an unreadable index: numba recompiles
        return True


def kernels_cold(*, cylinder_contact: bool = False, rod_contact: bool = False) -> bool:
    """True when a kernel of such a simulation has no valid numba cache on disk (the first
    run will compile it).

    Cheap: imports the kernel modules (no compilation) and reads each kernel's cache index,
    the same check numba makes before it compiles (an index written for another numba
    version or an older source file counts as missing). False when numba's compilation is
    off (``NUMBA_DISABLE_JIT``), since nothing is compiled then.

    Parameters
    ----------
    cylinder_contact, rod_contact : bool
        Include the kernels of rod-cylinder and of rod-rod contact.
    """
    names = simulation_kernels(cylinder_contact=cylinder_contact, rod_contact=rod_contact)
    return any(_cold(name) for name in names)

"""knotmech.rod: a discrete-elastic-rods (DER) solver with implicit Euler time stepping.

Public API (everything else in this package is private)
-------------------------------------------------------
The public names, with their signatures and attributes::

    Model
        Rod(positions=, radius=, youngs_modulus=, density=, poisson_ratio=0.5, shear_modulus=None,
            thetas=None, velocities=None, director=None, natural="initial")
        Rod.straight(length=, n_nodes=, radius=, youngs_modulus=, density=, start=, direction=)
        RodSystem(rods, contact_exclusion=2)  global index arrays: node_dofs (n_nodes, 3),
            edge_nodes (n_edges, 2), edge_theta_dof, edge_rod, node_rod, rod_radius_edge, n_dof,
            positions(q), thetas(q), rod_nodes(r), rod_edges(r), initial_state()
        State  t, q, v, tangents, d1, ref_twist, dt_next, n_good; save(path) / State.load(path)
    Loads (generalized forces; ``apply(system, t, q, q_old, dt, force, jac_diag)``)
        Gravity(acceleration=(0, 0, -9.81)), NodeForce(nodes, force), EdgeTorque(edges, torque),
        ViscousDamping(coefficient, rotational=0)
    Constraints (dofs eliminated from Newton; reactions reported)
        Clamp(nodes=(), edges=()), MovingNodes(nodes, velocity=None, path=None),
        RotatingEdges(edges, rate), clamp_end(system, rod=0, end="start", twist=True)
    Interactions (contact, friction, springs: ``Interaction``, ``RodContact``, ``CylinderContact``)
        Interaction (Protocol: begin_step, assemble(system, q, q_old, dt, force, triplets),
        end_step, energy), Triplets (add(rows, cols, vals) of dF/dq), PointSpring
    Solve
        simulate(system, state0=None, *, t_end, dt, loads=(), constraints=(), interactions=(),
                 options=SolverOptions(), progress=False, callback=None, throw=None) -> Result
            Raises knotmech.errors.SolverError (``.state`` last good State, ``.result`` the
            partial Result) when a step fails below dt_min, unless throw=False
        SolverOptions(dt_min, max_newton, rtol, xtol, line_search, max_backtracks, grow_after,
                      save_every, linear_solver, throw)
        Result  status, message, stats, times, positions, thetas, reactions (+ reaction_nodes),
                reaction_torques (+ reaction_edges), tension, bending_moment, twisting_moment,
                energies, final_state; save(path) / load_result(path)
        ElasticWorkspace  elastic energy, gradient and Hessian of a system (for analyses)
        kernels_cold(cylinder_contact=False, rod_contact=False) -> bool  True when the first
            simulation of that kind will compile numba kernels (no valid on-disk cache)

Example
-------
>>> from knotmech import rod
>>> r = rod.Rod.straight(length=0.1, n_nodes=31, radius=1e-3, youngs_modulus=1e6, density=1200)
>>> system = rod.RodSystem([r])
>>> res = rod.simulate(system, t_end=0.5, dt=1e-3, loads=[rod.Gravity()],
...                    constraints=[rod.clamp_end(system)])
"""

from .broadphase import candidate_edge_pairs
from .constraints import Clamp, MovingNodes, RotatingEdges, clamp_end
from .contact import Cylinder, CylinderContact, RodContact
from .elastic import ElasticWorkspace
from .friction import (
    AnchorFriction,
    SmoothFriction,
    default_stick_slip_parameters,
    stick_slip_weight,
)
from .interactions import Interaction, PointSpring
from .jacobian import Triplets
from .kernels import kernels_cold
from .loads import EdgeTorque, Gravity, NodeForce, ViscousDamping
from .results import Result, load_result
from .solver import SolverOptions, simulate
from .system import Rod, RodSystem, State

__all__ = [
    "Rod",
    "RodSystem",
    "State",
    "Gravity",
    "NodeForce",
    "EdgeTorque",
    "ViscousDamping",
    "Clamp",
    "MovingNodes",
    "RotatingEdges",
    "clamp_end",
    "Interaction",
    "Triplets",
    "PointSpring",
    "SolverOptions",
    "simulate",
    "Result",
    "load_result",
    "ElasticWorkspace",
    "RodContact",
    "Cylinder",
    "CylinderContact",
    "SmoothFriction",
    "AnchorFriction",
    "stick_slip_weight",
    "default_stick_slip_parameters",
    "candidate_edge_pairs",
    "kernels_cold",
]

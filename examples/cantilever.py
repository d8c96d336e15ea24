"""A soft cantilever drooping under gravity (the README example).

A 0.2 m rod clamped horizontally at one end is released in gravity with light viscous
damping; it swings down and settles in its large-deflection equilibrium.

``python examples/cantilever.py`` prints the solver's status, the tip position and the clamp
force, and writes the figure (snapshots and the tip height against time) to
``./knotmech-examples/cantilever.png``. ``--out DIR`` writes it elsewhere; the figure shown
in the README is refreshed with ``python examples/cantilever.py --out docs/img``.
"""

import argparse
import sys
from pathlib import Path

#: default output folder, relative to the current directory (a scratch folder, gitignored)
DEFAULT_OUT = Path("knotmech-examples")


def simulate():
    """The README's simulation: returns ``(system, result)``."""
    from knotmech import rod

    r = rod.Rod.straight(length=0.2, n_nodes=41, radius=1e-3, youngs_modulus=5e7, density=1200.0)
    system = rod.RodSystem([r])
    result = rod.simulate(
        system,
        t_end=2.0,
        dt=2e-3,
        loads=[rod.Gravity(), rod.ViscousDamping(0.02)],
        constraints=[rod.clamp_end(system)],
        options=rod.SolverOptions(save_every=0.02),
    )
    return system, result


def summary_lines(system, result) -> list[str]:
    """The lines the script prints (the README quotes them): status, tip, clamp force."""
    tip = result.positions[-1, -1]
    weight = 9.81 * system.mass[system.node_dofs[:, 2]].sum()
    force = result.reactions[-1].sum(axis=0) + 0.0  # + 0.0: no "-0" in the output
    return [
        f"{result.status}: {result.stats['steps']} steps, "
        f"{result.stats['newton_iterations']} Newton iterations",
        f"tip at t = 2 s: [{tip[0]:.3f}, {tip[1]:.3f}, {tip[2]:.3f}] m",
        f"clamp force: [{force[0]:.3e}, {force[1]:.3e}, {force[2]:.3e}] N "
        f"(the rod's weight: {weight:.3e} N)",
    ]


def plot(result, path) -> Path:
    """Draw the snapshots and the tip height against time into ``path`` (PNG)."""
    from knotmech.plotting import new_figure, node_track_plot, rod_snapshots_plot, save_figure

    fig, (ax1, ax2) = new_figure(2, figsize=(9, 3.6), width_ratios=[1.2, 1])
    rod_snapshots_plot(result, n_frames=9, plane="xz", ax=ax1, title="snapshots, every 0.25 s")
    node_track_plot(result, node=-1, axis="z", ax=ax2,
                    title=f"{result.stats['steps']} steps, "
                    f"{result.stats['newton_iterations']} Newton its")  # fmt: skip
    ax2.set_ylabel("tip height [m]")
    return save_figure(fig, path)


def main(argv=None) -> int:
    """``python examples/cantilever.py [--out DIR]``: simulate, print, write the figure."""
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument(
        "--out",
        metavar="DIR",
        default=str(DEFAULT_OUT),
        help=f"folder for cantilever.png (default ./{DEFAULT_OUT}; --out docs/img refreshes "
        "the README's figure)",
    )
    args = parser.parse_args(argv)
    out = Path(args.out)
    if out.exists() and not out.is_dir():  # checked before the simulation, not after it
        print(f"cantilever.py: error: --out {str(out)!r} is not a folder", file=sys.stderr)
        return 2
    system, result = simulate()
    print("\n".join(summary_lines(system, result)))
    print("wrote", plot(result, out / "cantilever.png"))
    return 0


if __name__ == "__main__":
    sys.exit(main())

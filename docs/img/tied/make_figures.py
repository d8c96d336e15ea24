"""Draw the start centreline of every knot in knotmech.scenes.tied (PNG, 3-D and top view).

Run from the repository root: ``python docs/img/tied/make_figures.py``.
"""

from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from knotmech.scenes.tied import TIED_KNOTS  # noqa: E402

D = 0.01
OUT = Path(__file__).parent


def draw(name):
    kw = {"pin_diameter": 3 * D} if name in {"bowline", "figure_eight_loop", "prusik"} else {}
    k = TIED_KNOTS[name](rod_diameter=D, **kw)
    fig = plt.figure(figsize=(11, 4.5))
    ax3 = fig.add_subplot(1, 2, 1, projection="3d")
    ax2 = fig.add_subplot(1, 2, 2)
    for (rope, x), c in zip(k.ropes.items(), ["tab:blue", "tab:red"], strict=False):
        x = x / D
        if k.ends[rope][0] == "closed":
            x = np.vstack([x, x[:1]])
        ax3.plot(*x.T, color=c, lw=2, label=f"{rope}: {k.ends[rope][0]} -> {k.ends[rope][1]}")
        ax2.plot(x[:, 0], x[:, 1], color=c, lw=2)
        ax2.plot(*x[0, :2], "o", color=c)
    if k.pin is not None:
        p = np.array(k.pin["point"]) / D
        r = 0.5 * k.pin["diameter"] / D
        t = np.linspace(0, 2 * np.pi, 60)
        ax2.fill(p[0] + r * np.cos(t), p[1] + r * np.sin(t), color="0.7")
        zz = np.array([x[:, 2].min() for x in k.ropes.values()]).min() / D
        for z in np.linspace(zz, -zz, 5):
            ax3.plot(p[0] + r * np.cos(t), p[1] + r * np.sin(t), z, color="0.6", lw=0.5)
    ax3.set_box_aspect(None, zoom=1.0)
    ax3.set_title(f"{name} (axes in rod diameters d)")
    ax3.legend(fontsize=7, loc="upper left")
    ax2.set_aspect("equal")
    ax2.set_title("seen from +z (dots: node 0, the standing part)")
    fig.tight_layout()
    fig.savefig(OUT / f"{name}.png", dpi=90)
    plt.close(fig)


if __name__ == "__main__":
    for name in TIED_KNOTS:
        draw(name)

"""Cyclic pushover of the portal frame of examples/pushover_portal.py, with and without P-Delta.

The roof (node 2) is driven through the displacement history 0.03, -0.03, 0.06, -0.06, 0.09 m
under displacement control, after gravity (10 t at each top node). The path is followed event to
event: at each reversal the four hinges unload, the frame is elastic until the first hinge
yields back (after a drop of twice its first-yield load), and the sway mechanism carries
+-120 kN; with the string form of P-Delta (`N/L` on the columns' chords) the plateaus slope by
`-W/h` against the roof's mean drift.

Prints the events of each excursion, the plateaus, and the largest equilibrium and LCP errors;
writes ``pushover_cyclic.png`` (the hysteresis loops, the events marked) to the working directory.

Run: ``python examples/pushover_cyclic.py``
"""

import numpy as np
from pushover_portal import H, MP_BEAM, MP_COL, portal

from unilateral.pushover import pushover

HISTORY = [0.03, -0.03, 0.06, -0.06, 0.09]


def figure(curves, path="pushover_cyclic.png"):
    """The hysteresis loops, the events marked (matplotlib imported here, without pyplot)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=(6.4, 4.2))
    FigureCanvasAgg(fig)
    ax = fig.add_subplot()
    for label, r in curves.items():
        line, = ax.plot(1e3 * r.displacement, r.base_shear, lw=1.2, label=label)
        yields = r.events_of("yield")
        ax.plot([1e3 * e.displacement for e in yields], [e.load_factor for e in yields], "o", ms=3.5,
                color=line.get_color())
    for sign in (1, -1):
        ax.axhline(sign * 2 * (MP_COL + MP_BEAM) / H, color="0.6", ls="--", lw=0.8)
    ax.set_xlabel("roof displacement ux of node 2 [mm]")
    ax.set_ylabel("base shear [kN]")
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    return path


def main():
    st = portal()
    load = st.nodal_load(2, ux=1.0)
    r = pushover(st, load, node=2, dof="ux", target=HISTORY, gravity=9.81)
    pd = pushover(st, load, node=2, dof="ux", target=HISTORY, gravity=9.81, p_delta="string")
    print(r.message)
    for e in r.events:
        print(f"event: {e.kind} {e.name} at load factor {e.load_factor:.9f}, ux {1e3 * e.displacement:.6f} mm")
    print(f"plateaus {r.load_factor.max():.12g} kN and {r.load_factor.min():.12g} kN, sway mechanism "
          f"+-{2 * (MP_COL + MP_BEAM) / H:.12g} kN")
    i2, i3 = st.dofs.names.index("2.ux"), st.dofs.names.index("3.ux")
    mean = 0.5 * (pd.u[:, i2] + pd.u[:, i3])
    slope = np.diff(pd.load_factor)[-1] / np.diff(mean)[-1]
    print(f"with P-Delta (string): last plateau's slope {slope:.9g} kN/m against the mean drift, "
          f"-W/h = {-2 * 10 * 9.81 / H:.9g} kN/m")
    worst = max(r.stats["max_residual"], pd.stats["max_residual"]), max(r.stats["max_lcp_error"],
                                                                        pd.stats["max_lcp_error"])
    print(f"max equilibrium error {worst[0]:.2e}, max LCP error {worst[1]:.2e}")
    print(f"figure: {figure({'first order': r, 'P-Delta (string)': pd})}")


if __name__ == "__main__":
    main()

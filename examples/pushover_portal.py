"""Static pushover of a fixed-base portal frame with plastic hinges, by path-following (unilateral.pushover).

A portal (columns 3 m, beam 4 m) with rigid-plastic hinges at the column bases (Mp = 100 kN m) and
at the beam ends (Mp = 80 kN m), under its weight (10 t at each top node) and a lateral force at
the top, pushed under displacement control to 0.1 m. The path is followed event to event: each
hinge forms at an exact load factor, and the plateau is the sway mechanism,
P h = 2 Mp_base + 2 Mp_beam = 120 kN. The same with P-Delta softens after the mechanism.

Prints the capacity curve (one row per event), the events, the plateau against the mechanism,
and the largest equilibrium and LCP errors; writes ``pushover_portal.png`` (matplotlib) to the
working directory.

Run: ``python examples/pushover_portal.py``
"""

from unilateral.pushover import pushover
from unilateral.structure import Frame2D

H, L, MP_COL, MP_BEAM = 3.0, 4.0, 100.0, 80.0


def portal(p_delta=False):
    """The portal frame (kN, m, t)."""
    fr = Frame2D()
    for n, x, y in ((1, 0.0, 0.0), (2, 0.0, H), (3, L, H), (4, L, 0.0)):
        fr.node(n, x, y)
    fr.support(1, ux=True, uy=True, rz=True)
    fr.support(4, ux=True, uy=True, rz=True)
    fr.beam("c1", 1, 2, E=30e6, A=0.09, I=6.75e-4)
    fr.beam("c2", 4, 3, E=30e6, A=0.09, I=6.75e-4)
    fr.beam("g", 2, 3, E=30e6, A=0.09, I=1.35e-3)
    for name, beam, end, mp in (("hb1", "c1", "i", MP_COL), ("hb2", "c2", "i", MP_COL),
                                ("hg1", "g", "i", MP_BEAM), ("hg2", "g", "j", MP_BEAM)):
        fr.hinge(name, beam, end, My=mp)
    fr.mass(2, 10.0)
    fr.mass(3, 10.0)
    if p_delta:
        fr.p_delta(True, g=9.81)
    return fr.build()


def figure(curves, path="pushover_portal.png"):
    """The capacity curves, the events marked (matplotlib imported here, without pyplot)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=(6.0, 4.0))
    FigureCanvasAgg(fig)
    ax = fig.add_subplot()
    for label, r in curves.items():
        line, = ax.plot(1e3 * r.displacement, r.base_shear, label=label)
        shear_per_load_factor = r.base_shear[-1] / r.load_factor[-1]
        ax.plot([1e3 * e.displacement for e in r.events], [shear_per_load_factor * e.load_factor for e in r.events],
                "o", ms=4, color=line.get_color())
    ax.axhline(2 * (MP_COL + MP_BEAM) / H, color="0.6", ls="--", lw=0.8, label="sway mechanism")
    ax.set_xlabel("roof displacement ux of node 2 [mm]")
    ax.set_ylabel("base shear [kN]")
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    return path


def main():
    st = portal()
    r = pushover(st, st.nodal_load(2, ux=1.0), node=2, dof="ux", target=0.1, gravity=9.81)
    print(r.message)
    print("capacity curve (base shear = load factor x 1 kN):")
    print(r.table())
    for e in r.events:
        print(f"event: {e.kind} {e.name} at load factor {e.load_factor:.9f}, ux {1e3 * e.displacement:.6f} mm")
    mechanism = 2 * (MP_COL + MP_BEAM) / H
    print(f"plateau {r.load_factor[-1]:.12g} kN, sway mechanism 2 (Mp_base + Mp_beam) / h = {mechanism:.12g} kN")
    print(f"max equilibrium error {r.stats['max_residual']:.2e}, max LCP error {r.stats['max_lcp_error']:.2e}")
    pd = pushover(portal(p_delta=True), "uniform", node=2, dof="ux", target=0.1, gravity=9.81)
    print(f"with P-Delta: peak base shear {pd.base_shear.max():.6g} kN, at 0.1 m {pd.base_shear[-1]:.6g} kN")
    print(f"figure: {figure({'first order': r, 'P-Delta': pd})}")


if __name__ == "__main__":
    main()

"""A bridge pier that rocks on its foundation: rigid contacts at the footing's edges, against a fixed base.

What it shows
-------------
A "stepping" pier (rocking isolation: Housner's 1963 Chilean tanks, the South Rangitikei rail
bridge): an elastic reinforced-concrete column, 9 m tall (E = 30 GPa, a 2 m round section), carries
a deck mass of 400 t on top and stands on a rigid footing 5 m wide and 2 m thick (150 t) that rests
on the ground on its two edges, each a rigid unilateral contact (``Frame2D.rigid_block``: no
compliance, Newton's impact law with e = 0, ``method="moreau-jean"``). The footing does not slide.
Units: kN, m, s (mass in t). The synthetic 0.35 g record of ``examples/records`` shakes it, and the
same pier is run

* on a **fixed base** (the footing held: the base moment grows with the shaking), and
* on **stiff tensionless springs and dashpots** at the same two edges (compliant rocking:
  ``Frame2D.soil``, a spring of 2e7 kN/m and a dashpot of 2e4 kN s/m acting only in contact at each
  edge; ``method="direct"``, BDF2).

The deck's weight acts through its second-order term ("P-Delta"), written by hand into ``K``: the
column's string term ``-W_d / L`` on the chord and ``-W_d 2h`` on the footing's rotation (the
footing's own ``-W_f h`` is ``rigid_block``'s), so that the pier overturns at the linearised tilt
``b / H_G``. The column has stiffness-proportional damping ``C = a1 K_column`` (no damping of the
rigid rotation). The only approximations are those of ``docs/rocking.md`` (small rotations).

Identities it checks (``tests/test_examples.py`` reads them)
-------------------------------------------------------------
* **the base moment is bounded by the weight**: the contact forces ``R_L, R_R >= 0`` put the base
  moment ``M = b (R_R - R_L)`` within ``b (R_L + R_R) = b (W + sum m_i a_y,i)``: ``W b`` plus the
  vertical inertia of the masses (the deck bounces on the column's axial stiffness after each
  impact), at every step;
* **equilibrium of the base forces**, with the step-mean forces ``v = P / dt`` of the march: the
  vertical force ``R_L + R_R = W + sum m_i a_y,i`` (the momentum balance of the step, exact at
  every step, impacts included), and the moment ``b (R_R - R_L)`` equal to the overturning moment
  of the inertia forces and of the weights about the base centre,
  ``-sum m_i y_i a_x,i(abs) + J theta'' + W_d ux_deck + W_f ux_footing`` (exact at the steps
  without an impact; at a step with an impact the march splits the step at the impact and the
  mean of the step's ends is not its ``K u``);
* **energy**: the balance of the march closes to round-off, and the energy the contacts dissipate
  is the sum of the losses of the located impacts (none between impacts).

What it prints
--------------
The pier (weights, ``W b``, the static uplift acceleration), per model the peak footing rotation,
deck displacement, column drift and base moment (as a multiple of ``W b``), then the identities.
It writes ``rocking_pier.png`` (the footing's rotation, the deck's displacement and the base
moment with and without rocking) and, through :mod:`unilateral.figures.motion`, the deformed shape
at the peak drift and a GIF of the rocking pier (Pillow), into ``--out`` (default
``rocking_pier/`` in the working directory).

Run: ``python examples/rocking_pier.py [--out DIR] [--no-animation]`` (a few seconds).
"""

import argparse
import sys
from pathlib import Path

import numpy as np
import scipy.sparse as sp

import unilateral as ul
from unilateral.analysis.rigid import energy_balance
from unilateral.loads import LoadHistory, read_at2
from unilateral.structure import Frame2D

G = 9.80665
L_COL, M_DECK = 9.0, 400.0                       # column height (m), deck mass (t)
WIDTH, THICK, M_FOOT = 5.0, 2.0, 150.0           # footing 2b x 2h (m), mass (t)
E, A, I = 30e6, np.pi, np.pi / 4                 # kN/m^2; a 2 m round section: m^2, m^4
A1 = 0.002                                       # C = a1 K of the column (s)
K_EDGE, C_EDGE = 2e7, 2e4                        # compliant edges: kN/m, kN s/m each
RECORD = Path(__file__).resolve().parent / "records" / "synthetic_0.35g.AT2"
DT, T_END = 2e-3, 6.0
ANIMATION_WINDOW = (0.8, 3.0)                    # s
B = WIDTH / 2
J_FOOT = M_FOOT * (B ** 2 + (THICK / 2) ** 2) / 3
W = (M_DECK + M_FOOT) * G


def build(base):
    """The pier on a ``"rocking"``, ``"fixed"`` or ``"springs"`` base: ``(structure, model)``."""
    fr = Frame2D()
    fr.node("centre", 0.0, THICK / 2)
    fr.node("deck", 0.0, THICK + L_COL)
    fr.node("cap", 0.0, THICK)
    if base == "rocking":
        fr.rigid_block("footing", "centre", width=WIDTH, height=THICK, mass=M_FOOT, J=J_FOOT)
    else:
        fr.node("footing.base", 0.0, 0.0)
        fr.support("footing.base", ux=True, uy=base == "fixed", rz=base == "fixed")
        fr.rigid_link("footing.base", "centre")
        fr.mass("centre", M_FOOT, J=J_FOOT)
        if base == "springs":
            for side, x in (("left", -B), ("right", B)):
                fr.node(f"footing.{side}", x, 0.0)
                fr.rigid_link("footing.base", f"footing.{side}")
                fr.soil(f"footing.{side}", f"footing.{side}", k=K_EDGE, c=C_EDGE)
    fr.rigid_link("footing.base", "cap")
    fr.beam("pier", "cap", "deck", E=E, A=A, I=I)
    fr.mass("deck", M_DECK)
    st = fr.build()
    model = st.to_model()
    geometric = st.rigid.geometric.toarray() if base == "rocking" else 0.0
    K_column = sp.csr_matrix(model.K).toarray() - geometric
    model.C = sp.csr_matrix(A1 * K_column)
    model.K = sp.csr_matrix(K_column + geometric + second_order(st, base))
    return st, model


def second_order(st, base):
    """``K_G`` (n, n) of the deck's weight (and the footing's, where ``rigid_block`` has not put it):
    the string term ``-W_d / L`` on the column's chord ``ux_deck - ux_cap`` and ``-W 2h`` on the
    footing's rotation."""
    a = _row(st, "deck", "ux") - _row(st, "cap", "ux")
    out = -M_DECK * G / L_COL * np.outer(a, a)
    if base != "fixed":
        theta = _row(st, "footing.base", "rz")
        own = 0.0 if base == "rocking" else M_FOOT * G * THICK / 2
        out -= (M_DECK * G * THICK + own) * np.outer(theta, theta)
    return out


def _row(st, node, dof):
    """The row (n,) of ``T`` that gives the node's ``dof`` from the free DOFs."""
    return np.asarray(st.dofs.T[st.dofs.full_index(node, dof)].todense()).ravel()


def run(base, record):
    """The pier on ``base`` under ``record``: ``(structure, model, load, solution)``."""
    st, model = build(base)
    load = LoadHistory(st.gravity(G), [(-st.gravity(1.0, (1.0, 0.0)), record)])
    method, rule = {"rocking": ("moreau-jean", "trapezoidal"), "fixed": ("direct", "trapezoidal"),
                    "springs": ("direct", "bdf2")}[base]
    sol = ul.solve(model, load, dt=DT, t_end=T_END, method=method, rule=rule, initial="static")
    assert sol.success, sol.message
    return st, model, load, sol


def histories(st, sol, record, base):
    """Step histories: node displacements (N+1,) and the step means (N,) of the base forces."""
    T = st.dofs.T
    d = lambda node, dof: np.asarray(T[st.dofs.full_index(node, dof)] @ sol.u.T).ravel()
    a = lambda node, dof: np.diff(np.asarray(T[st.dofs.full_index(node, dof)] @ sol.udot.T).ravel()) / DT
    mean = lambda x: 0.5 * (x[1:] + x[:-1])
    a_g = record(0.5 * (sol.t[1:] + sol.t[:-1]))            # the march's load at the step's middle
    theta = d("footing.base", "rz") if base != "fixed" else np.zeros(sol.t.size)
    out = {"theta": theta, "deck": d("deck", "ux"),
           "drift": d("deck", "ux") - d("cap", "ux") + L_COL * theta}
    theta_dd = a("footing.base", "rz") if base != "fixed" else 0.0
    out["moment"] = (-M_DECK * (THICK + L_COL) * (a("deck", "ux") + a_g)
                     - M_FOOT * THICK / 2 * (a("centre", "ux") + a_g) + J_FOOT * theta_dd
                     + M_DECK * G * mean(d("deck", "ux")) + M_FOOT * G * mean(d("centre", "ux")))
    out["vertical"] = W + M_DECK * a("deck", "uy") + M_FOOT * a("centre", "uy")
    return out


def impact_steps(sol):
    """Indices (into the N step means) of the steps in which a located impact lies."""
    steps = {int(np.searchsorted(sol.t, ev["time"], side="left")) - 1 for ev in sol.stats["impacts"]}
    return np.array(sorted(k for k in steps if 0 <= k < sol.t.size - 1), dtype=int)


def check_rocking(st, model, sol, h):
    """Print the identities of the rocking pier (see the module)."""
    names = list(sol.constraint_names)
    R = sol.v[1:][:, [names.index("footing.left"), names.index("footing.right")]]    # step means
    M_contacts = B * (R[:, 1] - R[:, 0])
    hit = impact_steps(sol)
    smooth = np.setdiff1d(np.arange(R.shape[0]), hit)
    print(f"contact forces: least {R.min():.3e} kN (>= 0); {len(sol.stats['impacts'])} located impacts "
          f"in {hit.size} steps")
    bound = np.abs(M_contacts) / (B * R.sum(axis=1))
    print(f"bound: max |M| / (b (R_L + R_R)) = {bound.max():.15f} (<= 1); b (R_L + R_R) / (W b) from "
          f"{R[smooth].sum(axis=1).min() / W:.3f} to {R[smooth].sum(axis=1).max() / W:.3f} between impacts")
    print(f"vertical equilibrium: max |R_L + R_R - (W + sum m a_y)| = {np.abs(R.sum(axis=1) - h['vertical']).max():.3e} kN "
          f"(W = {W:.1f} kN)")
    res = np.abs(M_contacts - h["moment"])
    print(f"moment equilibrium: max |b (R_R - R_L) - overturning moment| = {res[smooth].max():.3e} kN m "
          f"without impact, {res[hit].max():.3e} kN m at the impact steps (peak {np.abs(M_contacts).max():.0f} kN m)")
    eb = energy_balance(model, sol)
    located = sum(ev["loss"] for ev in sol.stats["impacts"])
    print(f"energy balance: relative error {eb['relative_error']:.3e}; contacts dissipated "
          f"{eb['impact_loss'][-1]:.9f} kN m, located impacts {located:.9f} kN m (difference "
          f"{abs(eb['impact_loss'][-1] - located):.3e}); column damping {eb['damping_dissipated'][-1]:.3f} kN m")
    return smooth


def report(name, h, steps=None):
    """Print the peaks of one model (the base moment over ``steps`` of the step means)."""
    moment = h["moment"] if steps is None else h["moment"][steps]
    print(f"{name}: peak footing rotation {1e3 * np.abs(h['theta']).max():.3f} mrad, deck displacement "
          f"{1e3 * np.abs(h['deck']).max():.1f} mm, column drift {1e3 * np.abs(h['drift']).max():.1f} mm, "
          f"base moment {np.abs(moment).max():.0f} kN m = {np.abs(moment).max() / (W * B):.3f} W b")


def figure(t, runs, smooth, path):
    """The footing's rotation, the deck's displacement and the base moment of the three models."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, axes = plt.subplots(3, 1, figsize=(8.0, 8.5), sharex=True)
    tm = 0.5 * (t[1:] + t[:-1])
    style = {"rocking": ("tab:red", "rocking on rigid edge contacts"), "fixed": ("0.3", "fixed base"),
             "springs": ("tab:blue", "tensionless springs + dashpots")}
    for base, h in runs.items():
        color, label = style[base]
        if base != "fixed":
            axes[0].plot(t, 1e3 * h["theta"], color=color, lw=1.0, label=label)
        axes[1].plot(t, 1e3 * h["deck"], color=color, lw=1.0, label=label)
        moment = np.where(np.isin(np.arange(tm.size), smooth), h["moment"], np.nan) if base == "rocking" else h["moment"]
        axes[2].plot(tm, moment / 1e3, color=color, lw=1.0, label=label)
    for sign in (1, -1):
        axes[2].axhline(sign * W * B / 1e3, color="k", ls="--", lw=0.8, label="W b" if sign > 0 else None)
    axes[0].set_ylabel("footing rotation [mrad]")
    axes[1].set_ylabel("deck displacement [mm]")
    axes[2].set_ylabel("base moment [MN m]")
    axes[2].set_xlabel("t [s]")
    axes[0].set_title("9 m pier, 400 t deck, 5 m footing; synthetic 0.35 g record", fontsize=10)
    for ax in axes:
        ax.grid(alpha=0.3)
        ax.legend(fontsize=8, loc="upper right")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def motion_pictures(st, model, load, sol, out):
    """The deformed shape at the peak drift and the GIF of the rocking pier (figures/motion.py)."""
    import matplotlib.pyplot as plt

    from unilateral.analysis.outputs import compute_results
    from unilateral.figures.motion import animate, deformed_shape_figure

    units = {"length": "m", "force": "kN", "time": "s"}
    ds = compute_results({"unilateral": sol}, structure=st, model=model, load=load, units=units,
                         title="A pier rocking on its footing", model_figure=True).ds.to_xarray()
    fig = deformed_shape_figure(ds)
    fig.savefig(out / "rocking_pier_shape.png", dpi=90)
    plt.close(fig)
    paths = [out / "rocking_pier_shape.png"]
    try:
        import PIL  # noqa: F401  (the GIF writer of matplotlib)
    except ImportError:
        print("no animation: Pillow is not installed (pip install pillow)")
        return paths
    window = ds.sel(time=slice(*ANIMATION_WINDOW))           # the strongest rocking
    return paths + [animate(window, out / "rocking_pier.gif", frames=45, fps=10)]


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default="rocking_pier", help="folder of the figures (created)")
    parser.add_argument("--no-animation", action="store_true", help="skip the deformed shape and the GIF")
    args = parser.parse_args(argv)
    out = Path(args.out).resolve()
    out.mkdir(parents=True, exist_ok=True)
    record = read_at2(RECORD)
    print(f"pier: W = {W:.1f} kN (deck {M_DECK * G:.1f}, footing {M_FOOT * G:.1f}), b = {B:g} m, "
          f"W b = {W * B:.1f} kN m; static uplift at a_g = {W * B / (M_DECK * G * (THICK + L_COL) + M_FOOT * G * THICK / 2):.3f} g; "
          f"record peak {np.abs(record.acceleration).max() / G:.3f} g")
    runs, solved = {}, {}
    for base in ("rocking", "fixed", "springs"):
        solved[base] = run(base, record)
        runs[base] = histories(solved[base][0], solved[base][3], record, base)
    st, model, load, sol = solved["rocking"]
    smooth = check_rocking(st, model, sol, runs["rocking"])
    report("rocking (between impacts)", runs["rocking"], smooth)
    report("fixed base", runs["fixed"])
    report("springs", runs["springs"])
    ratio = np.abs(runs["rocking"]["moment"][smooth]).max() / np.abs(runs["fixed"]["moment"]).max()
    print(f"rocking / fixed: base moment {ratio:.3f}, column drift "
          f"{np.abs(runs['rocking']['drift']).max() / np.abs(runs['fixed']['drift']).max():.3f}")
    print(f"wrote {figure(sol.t, runs, smooth, out / 'rocking_pier.png')}")
    if not args.no_animation:
        for path in motion_pictures(st, model, load, sol, out):
            print(f"wrote {path}")


if __name__ == "__main__":
    main(sys.argv[1:])

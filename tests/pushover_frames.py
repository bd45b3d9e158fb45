"""Structures of the pushover tests and an independent event-to-event analysis of a portal frame.

The independent analysis is plain direct stiffness in numpy: an elastic frame whose formed hinges
are pins (an extra rotation DOF for the beam end) carrying their plastic moments as constant couples;
the next hinge forms where the moment first reaches its plastic moment. It shares nothing with the
library but the numbers of the frame.
"""

import numpy as np

from unilateral.structure import Frame2D

H, L = 3.0, 4.0
E, A, I_COL, I_BEAM = 30e6, 0.09, 6.75e-4, 1.35e-3
MP_COL, MP_BEAM = 100.0, 80.0
#: hinges (name, beam, end) and their plastic moments
HINGES = (("hb1", "c1", "i", MP_COL), ("hb2", "c2", "i", MP_COL), ("hg1", "g", "i", MP_BEAM),
          ("hg2", "g", "j", MP_BEAM))
NODES = {1: (0.0, 0.0), 2: (0.0, H), 3: (L, H), 4: (L, 0.0)}
BEAMS = {"c1": (1, 2, I_COL), "c2": (4, 3, I_COL), "g": (2, 3, I_BEAM)}


def portal(*, p_delta=False, mass=10.0, k_hinge=None):
    """The fixed-base portal with rigid-plastic hinges at the column bases and the beam ends (with
    ``k_hinge``: elastic-plastic rotational springs of that stiffness)."""
    fr = Frame2D()
    for n, (x, y) in NODES.items():
        fr.node(n, x, y)
    fr.support(1, ux=True, uy=True, rz=True)
    fr.support(4, ux=True, uy=True, rz=True)
    for name, (i, j, inertia) in BEAMS.items():
        fr.beam(name, i, j, E=E, A=A, I=inertia)
    for name, beam, end, mp in HINGES:
        fr.hinge(name, beam, end, My=mp, k=k_hinge)
    fr.mass(2, mass)
    fr.mass(3, mass)
    if p_delta:
        fr.p_delta(True, g=9.81)
    return fr.build()


def _element(i, j, inertia):
    """Global 6 x 6 stiffness of a frame element and its transformation (local = T global)."""
    (xi, yi), (xj, yj) = NODES[i], NODES[j]
    length = np.hypot(xj - xi, yj - yi)
    c, s = (xj - xi) / length, (yj - yi) / length
    a, b = E * A / length, E * inertia / length ** 3
    k = np.array([[a, 0, 0, -a, 0, 0],
                  [0, 12 * b, 6 * b * length, 0, -12 * b, 6 * b * length],
                  [0, 6 * b * length, 4 * b * length ** 2, 0, -6 * b * length, 2 * b * length ** 2],
                  [-a, 0, 0, a, 0, 0],
                  [0, -12 * b, -6 * b * length, 0, 12 * b, -6 * b * length],
                  [0, 6 * b * length, 2 * b * length ** 2, 0, -6 * b * length, 4 * b * length ** 2]])
    R = np.array([[c, s, 0], [-s, c, 0], [0, 0, 1.0]])
    T = np.kron(np.eye(2), R)
    return k, T


def independent_events():
    """Load factors (of a unit lateral force at node 2) at which the hinges form, in order, with the
    displacement ux of node 2 at each; by event-to-event elastic analyses with formed hinges as pins."""
    free = {(n, d): k for k, (n, d) in enumerate((n, d) for n in (2, 3) for d in range(3))}
    hinge_dof = {name: 6 + k for k, (name, *_rest) in enumerate(HINGES)}
    sections = {(beam, end): (name, mp) for name, beam, end, mp in HINGES}
    formed, couples, P, out = {}, {}, 0.0, []
    while len(formed) < len(HINGES):
        def solve(loads):
            n = 6 + len(HINGES)
            K, f = np.zeros((n, n)), np.zeros(n)
            maps = {}
            for name, (i, j, inertia) in BEAMS.items():
                k, T = _element(i, j, inertia)
                idx = []
                for node, end in ((i, "i"), (j, "j")):
                    for d in range(3):
                        h = sections.get((name, end))
                        if d == 2 and h and h[0] in formed:
                            idx.append(hinge_dof[h[0]])
                        else:
                            idx.append(free.get((node, d), -1))
                maps[name] = (k, T, idx)
                kg = T.T @ k @ T
                for a_, ra in enumerate(idx):
                    for b_, rb in enumerate(idx):
                        if ra >= 0 and rb >= 0:
                            K[ra, rb] += kg[a_, b_]
            for dof, value in loads.items():
                f[dof] += value
            used = np.flatnonzero(np.abs(np.diag(K)) > 0)
            u = np.zeros(n)
            u[used] = np.linalg.solve(K[np.ix_(used, used)], f[used])
            moments = {}
            for name, (k, T, idx) in maps.items():
                ue = np.array([u[r] if r >= 0 else 0.0 for r in idx])
                fl = k @ T @ ue
                moments[(name, "i")], moments[(name, "j")] = fl[2], fl[5]
            return u, moments
        loads = {}
        for name, m in couples.items():
            beam, end = next((b, e) for (b, e), (n_, _) in sections.items() if n_ == name)
            node = BEAMS[beam][0 if end == "i" else 1]
            loads[hinge_dof[name]] = loads.get(hinge_dof[name], 0.0) + m
            if (node, 2) in free:
                loads[free[(node, 2)]] = loads.get(free[(node, 2)], 0.0) - m
        u_c, m_c = solve(loads)
        u_1, m_1 = solve({free[(2, 0)]: 1.0})
        best = None
        for sec, (name, mp) in sections.items():
            if name in formed or m_1[sec] == 0.0:
                continue
            for sign in (1.0, -1.0):
                Pk = (sign * mp - m_c[sec]) / m_1[sec]
                if Pk > P * (1 - 1e-14) and (best is None or Pk < best[0]):
                    best = (Pk, name, sign * mp)
        P, name, m = best
        formed[name] = True
        couples[name] = m
        out.append((name, P, u_c[free[(2, 0)]] + P * u_1[free[(2, 0)]]))
    return out


def sdof(*, k=100.0, Fy=5.0, hardening=0.0):
    """One node on a yield link along ux (the other DOFs supported)."""
    fr = Frame2D()
    fr.node(1, 0.0, 0.0)
    fr.support(1, ux=False, uy=True, rz=True)
    fr.yield_link("y", 1, k=k, Fy=Fy, direction="ux", hardening=hardening)
    return fr.build()


def cantilever(*, k=2e4, My=50.0, hardening=0.05, h=3.0):
    """A vertical cantilever with an elastic-plastic rotational spring (``k``) at its base."""
    fr = Frame2D()
    fr.node(1, 0.0, 0.0)
    fr.node(2, 0.0, h)
    fr.support(1, ux=True, uy=True, rz=True)
    fr.beam("col", 1, 2, E=E, A=A, I=I_COL)
    fr.hinge("hb", "col", "i", My=My, k=k, hardening=hardening)
    return fr.build()


def rocking_block(*, b=1.0, height=2.0, k=1e5, mass=50.0):
    """A rigid block (master node at the base centre) on two compression-only springs at +-b, held
    horizontally by a spring, with the load point at ``height`` (a slave node)."""
    fr = Frame2D()
    fr.node("c", 0.0, 0.0)
    fr.node("l", -b, 0.0)
    fr.node("r", b, 0.0)
    fr.node("t", 0.0, height)
    for slave in ("l", "r", "t"):
        fr.rigid_link("c", slave)
    fr.soil("sl", "l", k)
    fr.soil("sr", "r", k)
    fr.spring("hold", "c", 1e6, direction="ux")
    fr.mass("c", mass)
    return fr.build()

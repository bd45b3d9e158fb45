"""The portal frame with every yielding and friction element, shared by several test files.

Two columns and a girder with a rigid-plastic and two elastic-plastic hinges (with hardening), a
frictional soil contact that lifts and slides under one column, a slider under the other, and a
yielding brace with different tension and compression yield forces: as a ``Frame2D`` and as the
``[[unilateral]]`` part of a model file.
"""

from unilateral.structure import Frame2D

PORTAL_TOML = """
units = { length = "m", force = "kN", time = "s" }
nodes = [{ id = 1, x = 0.0, y = 0.0 }, { id = 2, x = 0.0, y = 3.0 }, { id = 3, x = 4.0, y = 3.0 },
         { id = 4, x = 4.0, y = 0.0 }]
supports = [{ node = 4, ux = false, uy = true, rz = true }, { node = 1, ux = false, uy = false, rz = true }]
elements = [
  { type = "beam", name = "c1", node_i = 1, node_j = 2, E = 30e6, A = 0.09, I = 6.75e-4 },
  { type = "beam", name = "c2", node_i = 4, node_j = 3, E = 30e6, A = 0.09, I = 6.75e-4 },
  { type = "beam", name = "g", node_i = 2, node_j = 3, E = 30e6, A = 0.09, I = 6.75e-4 },
]
unilateral = [
  { type = "hinge", name = "h1", beam = "c1", end = "j", My = 40.0 },
  { type = "hinge", name = "h2", beam = "g", end = "i", My = 40.0, k = 2e4, hardening = 0.05 },
  { type = "hinge", name = "h3", beam = "c2", end = "i", My = 60.0, hardening = 0.02 },
  { type = "soil", name = "s1", node = 1, k = 2e5, c = 200.0, mu = 0.4, kt = 5e4, ct = 50.0 },
  { type = "slider", name = "b4", node = 4, mu = 0.3, N = 150.0, k = 5e4 },
  { type="yield", name="br", node=1, node_j=3, k=2e4, Fy_t=30.0, Fy_c=45.0, hardening=0.1, direction=[4.0, 3.0] },
]
masses = [{ node = 2, m = 20.0 }, { node = 3, m = 20.0 }]
damping = { rayleigh = { a0 = 0.5, a1 = 1e-3 } }
"""


def frame(*, rayleigh=(0.5, 1e-3)):
    """A portal on a frictional soil element and a slider, hinges, a yield-link brace."""
    fr = Frame2D()
    for node, x, y in ((1, 0.0, 0.0), (2, 0.0, 3.0), (3, 4.0, 3.0), (4, 4.0, 0.0)):
        fr.node(node, x, y)
    fr.support(4, ux=False, uy=True, rz=True)
    fr.support(1, ux=False, uy=False, rz=True)
    for name, i, j in (("c1", 1, 2), ("c2", 4, 3), ("g", 2, 3)):
        fr.beam(name, i, j, E=30e6, A=0.09, I=6.75e-4)
    fr.hinge("h1", "c1", "j", My=40.0)
    fr.hinge("h2", "g", "i", My=40.0, k=2e4, hardening=0.05)
    fr.hinge("h3", "c2", "i", My=60.0, hardening=0.02)
    fr.soil("s1", 1, 2e5, c=200.0, mu=0.4, kt=5e4, ct=50.0)
    fr.slider("b4", 4, mu=0.3, N=150.0, k=5e4)
    fr.yield_link("br", 1, 3, k=2e4, Fy_t=30.0, Fy_c=45.0, hardening=0.1, direction=(4.0, 3.0))
    fr.mass(2, 20.0)
    fr.mass(3, 20.0)
    fr.rayleigh(*rayleigh)
    return fr.build()

"""The 9-storey, 3-bay moment frame with 58 plastic hinges as a model file (for ``cli_timing.py``).

Storeys 3.5 m, bays 6 m; columns A = 0.36 m^2, I = 1.08e-2 m^4, beams A = 0.24 m^2, I = 7.2e-3 m^4,
E = 30 GPa (kN, m, s, t); an elastic-plastic rotational spring at both ends of every beam
(My = 500 kN m) and at the foot of every column (My = 900 kN m), each 20 times as stiff as
``6 E I / L`` of its member; 120 t per floor spread over its four nodes; mass-proportional
Rayleigh damping; gravity, then a synthetic record (Kanai-Tajimi, PGA 4 m/s^2, seed 3). The frame
of ``benchmarks/opensees_frames.py`` (``FRAMES[2]``): 36 free nodes, 108 DOFs, 58 hinges.

    python benchmarks/frame9.py OUT_DIR [--dt 0.005] [--t-end 15]

writes ``OUT_DIR/frame9.toml`` and its record ``OUT_DIR/frame9_record.txt`` (one column, m/s^2).
"""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path

STOREYS, BAYS, HEIGHT, SPAN, E = 9, 3, 3.5, 6.0, 30e6
COLUMN, BEAM = (0.36, 1.08e-2), (0.24, 7.2e-3)
MY_COLUMN, MY_BEAM, HINGE_FACTOR, FLOOR_MASS, ZETA = 900.0, 500.0, 20.0, 120.0, 0.05


def node_id(floor: int, line: int) -> int:
    return 100 * floor + line


def model_text(record: str, *, dt: float = 0.005, t_end: float = 15.0, output: str = "") -> str:
    """The TOML text of the frame; ``record`` is the record file's name (relative to the model file),
    ``output`` the lines of an ``[output]`` table (none by default)."""
    lines = ['units = { length = "m", force = "kN", time = "s" }', "", "nodes = ["]
    lines += [f"  {{ id = {node_id(f, c)}, x = {c * SPAN}, y = {f * HEIGHT} }},"
              for f in range(STOREYS + 1) for c in range(BAYS + 1)]
    lines += ["]", "", "supports = ["]
    lines += [f"  {{ node = {node_id(0, c)}, ux = true, uy = true, rz = true }}," for c in range(BAYS + 1)]
    lines += ["]", "", "elements = ["]
    hinges, masses = [], []
    k_column = HINGE_FACTOR * 6 * E * COLUMN[1] / HEIGHT
    k_beam = HINGE_FACTOR * 6 * E * BEAM[1] / SPAN
    for f in range(1, STOREYS + 1):
        for c in range(BAYS + 1):
            name = f"C{f}_{c}"
            lines.append(f'  {{ type = "beam", name = "{name}", node_i = {node_id(f - 1, c)}, node_j = {node_id(f, c)}, '
                         f"E = {E}, A = {COLUMN[0]}, I = {COLUMN[1]} }},")
            if f == 1:
                hinges.append(f'  {{ type = "hinge", name = "{name}.base", beam = "{name}", end = "i", '
                              f"My = {MY_COLUMN}, k = {k_column:.6g} }},")
            masses.append(f"  {{ node = {node_id(f, c)}, m = {FLOOR_MASS / (BAYS + 1)} }},")
        for b in range(BAYS):
            name = f"B{f}_{b}"
            lines.append(f'  {{ type = "beam", name = "{name}", node_i = {node_id(f, b)}, node_j = {node_id(f, b + 1)}, '
                         f"E = {E}, A = {BEAM[0]}, I = {BEAM[1]} }},")
            hinges += [f'  {{ type = "hinge", name = "{name}.{end}", beam = "{name}", end = "{end}", '
                       f"My = {MY_BEAM}, k = {k_beam:.6g} }}," for end in "ij"]
    w1 = 2 * math.pi / (0.1 * STOREYS)
    a0 = 2 * ZETA * w1 * 3 * w1 / (4 * w1)
    lines += ["]", "", "unilateral = [", *hinges, "]", "", "masses = [", *masses, "]", "",
              "[damping]", f"rayleigh = {{ a0 = {a0:.6g} }}", "", "[loads.gravity]", "g = 9.81", "",
              "[[loads.ground_motion]]", f'file = "{record}"', 'direction = "ux"', 'units = "m/s2"', f"dt = {dt}", "",
              "[analysis]", 'title = "9-storey frame, 58 hinges"', f"dt = {dt}", f"t_end = {t_end}",
              'method = "direct"', 'rule = "trapezoidal"', "", "[output]",
              f'figure = {{ node = {node_id(STOREYS, 0)}, dof = "ux" }}', output, ""]
    return "\n".join(lines)


def write(folder: Path, *, dt: float = 0.005, t_end: float = 15.0, output: str = "",
          name: str = "frame9") -> Path:
    """Write ``folder/<name>.toml`` and its record; return the model file's path."""
    import numpy as np

    from unilateral.loads import synthetic_accelerogram

    folder.mkdir(parents=True, exist_ok=True)
    record = synthetic_accelerogram(duration=t_end, dt=dt, pga=4.0, seed=3)
    values = np.asarray(record.acceleration, dtype=float)
    (folder / f"{name}_record.txt").write_text("\n".join(f"{x:.9e}" for x in values) + "\n")
    path = folder / f"{name}.toml"
    path.write_text(model_text(f"{name}_record.txt", dt=dt, t_end=t_end, output=output))
    return path


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("out", type=Path)
    p.add_argument("--dt", type=float, default=0.005)
    p.add_argument("--t-end", type=float, default=15.0)
    args = p.parse_args(argv)
    print(write(args.out, dt=args.dt, t_end=args.t_end))
    return 0


if __name__ == "__main__":
    sys.exit(main())

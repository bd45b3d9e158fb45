"""The undamped 3-storey hinge frame of the numerical-dissipation tests (issue: the default rule's accuracy).

examples/yielding_frame.toml without its footings (fixed bases) and without damping: three storeys of
3.5 m, two bays of 6 m, rigid-plastic hinges at both ends of every beam (My = 180 kN m) and
elastic-plastic rotational springs at the column feet (My = 260 kN m, k = 150 MN m/rad), 60 t per
floor, first period 0.735 s, under the synthetic 0.35 g record x 2; optionally P-Delta.
"""

from pathlib import Path

EXAMPLES = Path(__file__).resolve().parent.parent / "examples"


def hinge_frame_toml(*, p_delta=False) -> str:
    """The model file's text (the record by its absolute path)."""
    nodes = [(1, 0.0, 0.0), (2, 6.0, 0.0), (3, 12.0, 0.0)]
    nodes += [(10 * f + c, 6.0 * (c - 1), 3.5 * f) for f in (1, 2, 3) for c in (1, 2, 3)]
    lines = ['units = { length = "m", force = "kN", time = "s" }',
             "supports = [" + ", ".join(f"{{ node = {k}, ux = true, uy = true, rz = true }}" for k in (1, 2, 3)) + "]",
             "nodes = [" + ", ".join(f"{{ id = {k}, x = {x}, y = {y} }}" for k, x, y in nodes) + "]"]
    beams, hinges = [], []
    for f in (1, 2, 3):
        for c in (1, 2, 3):
            lower = c if f == 1 else 10 * (f - 1) + c
            beams.append(f'{{ type = "beam", name = "C{c}_{f}", node_i = {lower}, node_j = {10 * f + c}, '
                         'E = 30e6, A = 0.16, I = 2.1333e-3 }')
        for b in (1, 2):
            beams.append(f'{{ type = "beam", name = "B{f}_{b}", node_i = {10 * f + b}, node_j = {10 * f + b + 1}, '
                         'E = 30e6, A = 0.15, I = 3.125e-3 }')
            hinges += [f'{{ type = "hinge", name = "B{f}_{b}.{end}", beam = "B{f}_{b}", end = "{end}", My = 180.0 }}'
                       for end in "ij"]
    hinges += [f'{{ type = "hinge", name = "C{c}_1.base", beam = "C{c}_1", end = "i", My = 260.0, k = 1.5e5 }}'
               for c in (1, 2, 3)]
    masses = [f"{{ node = {10 * f + c}, m = {30.0 if c == 2 else 15.0} }}" for f in (1, 2, 3) for c in (1, 2, 3)]
    lines += ["elements = [" + ",\n  ".join(beams) + "]", "unilateral = [" + ",\n  ".join(hinges) + "]",
              "masses = [" + ", ".join(masses) + "]", "[loads.gravity]", 'g = "standard"',
              "[[loads.ground_motion]]",
              f'file = "{(EXAMPLES / "records" / "synthetic_0.35g.AT2").as_posix()}"', 'direction = "ux"',
              "scale = 2.0", "[analysis]", "dt = 5e-3", "t_end = 8.0"]
    if p_delta:
        lines.append("p_delta = true")
    return "\n".join(lines) + "\n"


def hinge_frame(tmp_path, *, p_delta=False):
    """The frame's :class:`~unilateral.modelfile.ModelSpec` (written to ``tmp_path``) and its path."""
    from unilateral.modelfile import load_model_file

    path = Path(tmp_path) / ("hinge_frame_pdelta.toml" if p_delta else "hinge_frame.toml")
    path.write_text(hinge_frame_toml(p_delta=p_delta))
    return load_model_file(path), path

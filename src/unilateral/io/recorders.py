"""Recorders: which histories a run writes, of which nodes and elements, how often and how precisely.

A run computes every result in memory (the summary, the peaks and the figures come from all of
them); :class:`Recorders` chooses what of it goes to ``results.nc`` and the CSV tables. Its fields
are those of a model file's ``[output]`` (``docs/model-file.md``, "What is written"):

``histories``   ``"auto"`` (default): ``"full"`` when the histories of the run take at most
                :data:`AUTO_LIMIT` bytes in float64, else ``"key"``; ``"key"``: the key histories
                only (:data:`KEY_VARIABLES`: base forces, drifts, energies, the ground motion, and
                the displacement of the figure's node); ``"full"``: every history of every DOF,
                constraint, element and node.
``variables``   further histories to write beside the key ones (names of :data:`HISTORY_VARIABLES`;
                with ``histories = "auto"`` they make it ``"key"``).
``nodes``       the nodes whose histories are written: ``node_displacement``, ``u``, ``udot`` and the
                accelerations are written for them (also under ``"key"``) and only for them.
``elements``    the elements (beams, bars, hinges, links, contacts) whose histories are written: end
                forces, yield and slip histories, ``v``, ``psi`` of their constraint unknowns.
``every``       write every ``every``-th step (steps 0, k, 2k, ...; the summary's peaks are of every step);
                None (default): 1, unless the histories chosen (not ``"full"``) would still take more than
                :data:`WRITE_LIMIT` bytes (a very long run): then the smallest ``every`` that keeps them
                under it, with a note.
``precision``   ``"float64"`` (default) or ``"float32"``: the histories in ``results.nc`` and the digits
                of the CSV tables (shortest round trip, or 9 significant digits).
``csv``         write the CSV tables (default True); ``results.nc`` and ``summary.json`` always.

This module imports numpy only in its functions: the model file's check reads its names.
"""

from __future__ import annotations

from dataclasses import dataclass, field

HISTORIES = ("auto", "key", "full")
PRECISIONS = ("float32", "float64")
#: ``histories = "auto"`` writes every history up to this many bytes (float64, all cases), else the key ones.
AUTO_LIMIT = 20_000_000
#: With ``every`` not given, the histories written take at most this many bytes (float64): longer runs are decimated.
WRITE_LIMIT = 40_000_000

#: The key histories: always written (those a model has).
KEY_VARIABLES = ("base_shear", "base_vertical", "overturning_moment", "frame_base_shear", "storey_drift",
                 "drift_ratio", "drift_ratio_x", "drift_ratio_y", "ground_acceleration", "base_Fx", "base_Fy",
                 "base_Fz", "base_Mx", "base_My", "base_Mz")
#: Names that start so are key histories too (the energy balance).
KEY_PREFIXES = ("energy_",)
#: Histories along ``node`` or ``dof``: written for ``nodes``.
NODE_VARIABLES = ("node_displacement", "node_acceleration", "node_absolute_acceleration", "u", "udot",
                  "acceleration", "absolute_acceleration")
#: Histories along the elements or the constraint unknowns: written for ``elements``.
ELEMENT_VARIABLES = ("end_force", "axial_force", "v", "psi", "psiL", "constraint_deformation", "plastic_deformation",
                     "yield_force", "yield_total_deformation", "yield_element_deformation", "yield_ratio", "slip", "friction_force",
                     "normal_force", "tangential_deformation", "slip_path")
#: Every history a run may write (``results.nc``; the energies: any ``energy_...``).
HISTORY_VARIABLES = tuple(sorted({*KEY_VARIABLES, *NODE_VARIABLES, *ELEMENT_VARIABLES, "support_reaction",
                                  "ground_reaction", "energy_kinetic", "energy_input_work"}))
#: The dimensions restricted by ``elements`` (the constraint unknowns are named ``<element>.<suffix>``).
ELEMENT_DIMS = ("element", "yield_element", "friction_element", "constraint")


def variable_problem(name) -> str | None:
    """Why ``name`` is not a history a run can write, or None."""
    if isinstance(name, str) and (name in HISTORY_VARIABLES or name.startswith(KEY_PREFIXES)):
        return None
    return f"unknown variable {name!r}; valid: {', '.join(HISTORY_VARIABLES)} (and energy_...)"


@dataclass(frozen=True)
class Recorders:
    """What a run writes (see the module's doc); ``Recorders()`` is the default.

    Raises
    ------
    ValueError
        A field out of range, naming it, the value and what is valid.
    """

    histories: str = "auto"
    variables: tuple = ()
    nodes: tuple | None = None
    elements: tuple | None = None
    every: int | None = None
    precision: str = "float64"
    csv: bool = True
    extra: dict = field(default_factory=dict, compare=False, repr=False)

    def __post_init__(self):
        if self.histories not in HISTORIES:
            raise ValueError(f"histories={self.histories!r}: valid: {', '.join(HISTORIES)}")
        if self.precision not in PRECISIONS:
            raise ValueError(f"precision={self.precision!r}: valid: {', '.join(PRECISIONS)}")
        if self.every is not None and (isinstance(self.every, bool) or not isinstance(self.every, int)
                                       or self.every < 1):
            raise ValueError(f"every={self.every!r}: give an integer >= 1 (1: every step)")
        if not isinstance(self.csv, bool):
            raise ValueError(f"csv={self.csv!r}: give true or false")
        if isinstance(self.variables, str):
            raise ValueError(f"variables={self.variables!r}: give a list of names")
        for name in self.variables:
            problem = variable_problem(name)
            if problem:
                raise ValueError(f"variables: {problem}")
        for key in ("variables", "nodes", "elements"):
            value = getattr(self, key)
            if value is not None:
                object.__setattr__(self, key, tuple(str(x) for x in value))

    @classmethod
    def of(cls, value) -> Recorders:
        """``value``: a :class:`Recorders`, None (the default), a dict of its fields or a model file's
        ``[output]`` table (its recorder keys)."""
        if value is None:
            return cls()
        if isinstance(value, cls):
            return value
        if isinstance(value, dict):
            unknown = set(value) - set(FIELDS)
            if unknown:
                raise ValueError(f"output: unknown key(s) {sorted(unknown)}; valid: {', '.join(FIELDS)}")
            return cls(**value)
        return cls(**{key: getattr(value, key) for key in FIELDS if getattr(value, key, None) is not None})


FIELDS = ("histories", "variables", "nodes", "elements", "every", "precision", "csv")


def select(ds, recorders: Recorders, *, figure_node=None):
    """``(written, info)``: the part of the Dataset ``ds`` (of a run, every result) that ``recorders``
    write, and what was chosen (``info``, for ``summary.json``: ``histories``, ``every``,
    ``precision``, ``written``, ``left_out`` and, with ``"key"``, a ``note``)."""
    import numpy as np

    timed = [name for name, var in ds.data_vars.items() if "time" in var.dims]
    size = sum(ds[name].values.size * 8 for name in timed)
    mode = recorders.histories
    if mode == "auto":
        mode = "full" if size <= AUTO_LIMIT and not recorders.variables else "key"
    if "node" not in ds.coords and "dof" in ds.coords:
        mode = "full"                           # a matrix-level model: its solution is its key history
    wanted = set(timed) if mode == "full" else {n for n in timed if _key(n)} | set(recorders.variables)
    if recorders.nodes is not None:
        wanted |= set(NODE_VARIABLES)
    if recorders.elements is not None:
        wanted |= set(ELEMENT_VARIABLES)
    nodes = recorders.nodes
    if mode == "key" and nodes is None and figure_node is not None and "node_displacement" in ds:
        wanted.add("node_displacement")
        nodes = (str(figure_node),)
    kept = [n for n in timed if n in wanted]
    out = ds.copy()
    out.variables = {n: v for n, v in ds.variables.items() if n not in timed or n in wanted}
    out = _restrict(out, nodes, recorders.elements)
    every = recorders.every
    kept_size = 0
    if every is None and recorders.histories == "full":     # asked for in full: every step
        every = 1
    elif every is None:
        kept_size = sum(out[n].values.size * 8 for n in kept)
        every = max(1, -(-kept_size // WRITE_LIMIT))
    if every > 1:
        out = out.isel(time=slice(0, None, every))
    if recorders.precision == "float32":
        for n in kept:
            var = out.variables[n]
            if var.values.dtype.kind == "f":
                out.variables[n] = type(var)(var.dims, var.values.astype(np.float32), var.attrs)
    info = {"histories": mode, "every": every, "precision": recorders.precision, "csv": recorders.csv,
            "written": kept, "left_out": sorted(set(timed) - set(kept))}
    if nodes is not None:
        info["nodes"] = list(nodes)
    if recorders.elements is not None:
        info["elements"] = list(recorders.elements)
    if mode == "key" and info["left_out"]:
        info["note"] = (f"the histories of every DOF, constraint and element ({size / 1e6:.0f} MB in float64) are "
                        "not written: set [output] histories = \"full\", or name the nodes, elements or variables "
                        "to write (docs/model-file.md, What is written)")
    if recorders.every is None and every > 1:
        info["note_every"] = (f"every {every}-th step is written (the histories would take {kept_size / 1e6:.0f} MB): "
                              "set [output] every = 1 for every step")
    out.attrs = {**out.attrs, "output_histories": mode, "output_every": every,
                 "output_precision": recorders.precision}
    return out, info


def _key(name: str) -> bool:
    return name in KEY_VARIABLES or name.startswith(KEY_PREFIXES)


def _restrict(ds, nodes, elements):
    """``ds`` along ``node`` and ``dof`` to ``nodes``, along the element dims to ``elements`` (None: all)."""
    import numpy as np

    picks = {}
    if nodes is not None:
        wanted = set(nodes)
        if "node" in ds.coords:
            picks["node"] = [str(x) in wanted for x in ds.coords["node"].values]
        if "dof" in ds.coords and any("dof" in v.dims and n != "mode_shape" for n, v in ds.data_vars.items()):
            picks["dof"] = [str(x).rsplit(".", 1)[0] in wanted for x in ds.coords["dof"].values]
    if elements is not None:
        for dim in ELEMENT_DIMS:
            if dim in ds.coords:
                picks[dim] = [_owner(str(x), elements) is not None for x in ds.coords[dim].values]
    for dim, mask in picks.items():
        ds = ds.isel(**{dim: np.flatnonzero(np.asarray(mask, dtype=bool))})
    return ds


def _owner(label: str, elements) -> str | None:
    """The element of ``elements`` that ``label`` (an element, or a constraint ``<element>.<suffix>``) belongs to."""
    found = [e for e in elements if label == e or label.startswith(e + ".")]
    return max(found, key=len) if found else None


def solution_view(ds, sol):
    """The histories of one case of a written Dataset ``ds`` as :func:`unilateral.io.results.save_csv` takes a
    :class:`~unilateral.Solution` (``t``, ``u``, ``dof_names``, ``v``, ``psi``, ``psiL``,
    ``constraint_names``; None where not written), up to the last step ``sol`` computed."""
    from types import SimpleNamespace

    every = int(ds.attrs.get("output_every", 1))
    rows = -(-len(sol.t) // every)

    def history(name):
        return ds[name].values[:rows] if name in ds and "time" in ds[name].dims else None

    names = ds.coords
    return SimpleNamespace(t=ds["time"].values[:rows], u=history("u"), v=history("v"), psi=history("psi"),
                           psiL=history("psiL"),
                           dof_names=[str(x) for x in names["dof"].values] if "dof" in names else [],
                           constraint_names=[str(x) for x in names["constraint"].values] if "constraint" in names else [])

"""Read a model file: TOML -> validated document -> cross checks -> Structure, Model and load.

:func:`load_model_file` is the entry point. Reading, validating and the cross checks are in
:mod:`unilateral.modelfile.checks` (no numpy, scipy or structure code: the command line runs them
before the heavy imports); this module builds the checked document. Every problem is reported as a
:class:`~unilateral.modelfile.errors.ModelFileError` naming the key path; errors of the
:class:`~unilateral.structure.Frame2D` builder and of the load readers are re-raised with the key
path of the entry that caused them.
"""

from __future__ import annotations

from contextlib import contextmanager
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import scipy.sparse as sp

from ..loads import (STANDARD_GRAVITY, Constant, HalfSine, LoadHistory, Ramp, Rectangular, Tabulated,
                     Triangular, length_factor, read_record)
from ..model import Model
from ..structure import Frame2D, Frame3D, Structure
from .analysis_time import resolved_analysis
from .checks import check_document, consistent_mass_factor, is_3d, read_document, validate_document
from .checks import read_toml  # noqa: F401 (the reader of study files too)
from .errors import ModelFileError, Problems, key_path
from .matrices import dof_index, read_matrix_model, read_vector
from .rigid import add_rigid, ground_inertia
from .schema import (TIME_UNITS, Bar, Beam, Cable, ConstantLoad, Dashpot, Gap, HalfSinePulse, Hinge2D, ModelFile,
                     RampLoad, RectangularPulse, Slider, Soil, Spring, TableLoad, TriangularPulse, YieldLink)
from .schema3d import Beam3D, Dashpot3D, Gap3D, Hinge3D, Slider3D, Soil3D, Spring3D, YieldLink3D


@dataclass(frozen=True, eq=False)
class ModelSpec:
    """A model file read and built.

    Attributes
    ----------
    structure : Structure or None
        The frame (None for a matrix-level model).
    model : Model
        The reduced problem (``structure.to_model()`` for a frame).
    load : LoadHistory
        ``q(t) -> (n,)``, the total load in the model's force unit.
    analysis : dict
        ``type`` (``"transient"`` or ``"pushover"``: ``document.pushover``), ``dt, t_end, t_after, method, rule,
        lcp, initial, load_sampling, bilateral_reference, p_delta, title`` (``t_end = "record"`` resolved to a number:
        :mod:`~unilateral.modelfile.analysis_time`).
    units : dict
        ``length, force, time`` as declared and the derived ``mass``.
    figure : dict or None
        ``node, dof, label`` of the history drawn in the main figure.
    source : Path
        The model file.
    document : ModelFile
        The validated file.
    """

    structure: Structure | None
    model: Model
    load: LoadHistory
    analysis: dict
    units: dict
    figure: dict | None
    source: Path
    document: ModelFile


def load_model_file(path) -> ModelSpec:
    """Read, check and build the model file ``path`` (TOML; see ``docs/model-file.md``).

    Raises
    ------
    ModelFileError
        With one line ``<file>: <key path> = <value>: <problem> (<what is valid>)`` per problem.
    """
    source = Path(path)
    try:
        document = read_document(source)
    except Problems as exc:
        raise ModelFileError(path, exc.problems) from None
    return _build_spec(document, source, path)


def build_model_spec(data: dict, source) -> ModelSpec:
    """Check and build a model file that is already parsed: ``data`` as from :func:`tomllib.load`.

    For programs that change a model file's values before building it (parameter studies).
    ``source`` is the file the data stands for: file names in ``data`` are relative to its folder,
    and error messages name it. Raises :class:`ModelFileError` as :func:`load_model_file` does.
    """
    source = Path(source)
    try:
        document = validate_document(data)
    except Problems as exc:
        raise ModelFileError(source, exc.problems) from None
    return _build_spec(document, source, source)


def _build_spec(document: ModelFile, source: Path, path) -> ModelSpec:
    """Cross checks and the build of a validated document (``path``: the file as named in errors)."""
    try:
        check_document(document, source.parent)
        if document.matrices is None:
            structure = _build_structure(document, source.parent)
            with _at("structure"):
                model = structure.to_model()
        else:
            if document.loads.support_motion:
                raise Problems(["loads.support_motion: a support motion needs a frame ([[nodes]], [[supports]]); "
                                "a matrix-level model has no supports to move"])
            structure = None
            model = read_matrix_model(document.matrices, source.parent)
        load = _build_load(document, source.parent, model, structure)
        analysis = resolved_analysis(document, load)
    except Problems as exc:
        raise ModelFileError(path, exc.problems) from None
    units = document.units.model_dump()
    units["mass"] = f"{units['force']} {units['time']}^2/{units['length']}"
    return ModelSpec(structure=structure, model=model, load=load, analysis=analysis,
                     units=units, figure=_figure(document), source=source, document=document)


@contextmanager
def _at(where: str):
    """Re-raise a ``ValueError`` or ``TypeError`` of the library as a problem at ``where``."""
    try:
        yield
    except (ValueError, TypeError) as exc:
        raise Problems([f"{where}: {exc}"]) from None


# ---------------------------------------------------------------------- the site
def _site_profile(document: ModelFile) -> tuple[list[dict], dict | None]:
    """``layers, base`` of ``[site]`` for :func:`~unilateral.loads.site_response.free_field`, rho in the
    consistent mass unit."""
    to_mass = consistent_mass_factor(document.units)

    def table(t):
        values = {key: value for key, value in t.model_dump().items() if value is not None}
        return {**values, "rho": values["rho"] * to_mass}
    site = document.site
    return [table(layer) for layer in site.layers], None if site.base is None else table(site.base)


# ---------------------------------------------------------------------- the frame
def _each(document, section: str, action) -> None:
    """``action(table)`` for each table of ``section`` of ``document``, with its key path as the
    context of the errors it raises (``elements[2]: ...``)."""
    for k, table in enumerate(getattr(document, section)):
        with _at(key_path((section, k))):
            action(table)


def _build_structure(document: ModelFile, folder: Path) -> Structure:
    if is_3d(document):
        return _build_structure_3d(document, folder)
    fr = Frame2D()
    to_mass = consistent_mass_factor(document.units)
    _each(document, "nodes", lambda node: fr.node(node.id, node.x, node.y))
    _each(document, "supports", lambda support: fr.support(support.node, ux=support.ux, uy=support.uy,
                                                           rz=support.rz))
    _each(document, "rigid_links", lambda link: fr.rigid_link(link.master, link.slave))
    _each(document, "equal_dofs", lambda tie: fr.equal_dof(tie.master, tie.slave, *tie.dofs))
    for section in ("elements", "unilateral"):
        _each(document, section, lambda element: _add_element(fr, element, to_mass))
    _each(document, "masses", lambda mass: fr.mass(mass.node, mass.m * to_mass, J=mass.J * to_mass))
    add_rigid(fr, document, to_mass, _each, _gravity_value(document) if document.loads.gravity else None)
    for at, f in document.footings:
        with _at(key_path(at)):
            fr.foundation(f.name, f.node, width=f.width, length=f.length, soil=_footing_soil(f, to_mass),
                          patches=f.patches, nodes=f.nodes, horizontal=f.horizontal, gap=f.gap,
                          mass=f.mass * to_mass, J=f.J * to_mass, mu=f.mu)
    _damping(fr, document)
    _p_delta(fr, document)
    _support_motions(fr, document, folder)
    with _at("structure"):
        return fr.build()


def _footing_soil(f, to_mass: float) -> dict:
    """The soil of a footing as a dict for ``Frame*.foundation``, densities in the consistent mass unit."""
    soil = {key: value for key, value in f.soil.model_dump().items() if value is not None}
    if soil.get("rho") is not None:
        soil["rho"] = soil["rho"] * to_mass
    if soil.get("layers") is not None:
        soil["layers"] = [{key: value * to_mass if key == "rho" else value for key, value in layer.items()
                           if value is not None} for layer in soil["layers"]]
    return soil


def _p_delta(fr, document: ModelFile) -> None:
    """``[analysis] p_delta`` of the frame being built (2-D or 3-D): P-Delta of ``[loads.gravity]``."""
    if document.analysis.p_delta:                   # with [loads.gravity]: checks._analysis_problems
        with _at("analysis.p_delta"):
            fr.p_delta(g=_gravity_value(document), direction=document.loads.gravity.direction)


def _damping(fr, document: ModelFile) -> None:
    """``[damping]`` of the frame being built."""
    rayleigh = document.damping.rayleigh if document.damping is not None else None
    if rayleigh is not None:
        with _at("damping.rayleigh"):
            if rayleigh.zeta is not None:
                fr.rayleigh_from_ratios(rayleigh.zeta, rayleigh.f1, rayleigh.f2)
            else:
                fr.rayleigh(rayleigh.a0 or 0.0, rayleigh.a1 or 0.0)
    modal = document.damping.modal if document.damping is not None else None
    if modal is not None:
        with _at("damping.modal"):
            fr.modal_damping(modal.zeta, modal.modes)


def _build_structure_3d(document: ModelFile, folder: Path) -> Structure:
    """The :class:`~unilateral.structure.Frame3D` of a ``[frame] dimensions = 3`` document."""
    fr = Frame3D()
    to_mass = consistent_mass_factor(document.units)
    _each(document, "nodes", lambda node: fr.node(node.id, node.x, node.y, node.z))
    _each(document, "supports", lambda support: fr.support(support.node, **{dof: getattr(support, dof) for dof in
                                                                            ("ux", "uy", "uz", "rx", "ry", "rz")}))
    _each(document, "rigid_links", lambda link: fr.rigid_link(link.master, link.slave))
    _each(document, "rigid_diaphragms", lambda diaphragm: fr.rigid_diaphragm(diaphragm.master, diaphragm.slaves))
    _each(document, "equal_dofs", lambda tie: fr.equal_dof(tie.master, tie.slave, *tie.dofs))
    add_rigid(fr, document, to_mass, _each, _gravity_value(document) if document.loads.gravity else None)
    for section in ("elements", "unilateral"):
        _each(document, section, lambda element: _add_element_3d(fr, element, to_mass))
    _each(document, "masses", lambda mass: fr.mass(mass.node, mass.m * to_mass, Jx=mass.Jx * to_mass,
                                                   Jy=mass.Jy * to_mass, Jz=mass.Jz * to_mass))
    for at, f in document.footings:
        with _at(key_path(at)):
            fr.foundation(f.name, f.node, width=f.width, length=f.length, soil=_footing_soil(f, to_mass),
                          patches=f.patches if f.patches is None or isinstance(f.patches, int) else tuple(f.patches),
                          nodes=f.nodes, horizontal=f.horizontal, gap=f.gap, mass=f.mass * to_mass,
                          Jx=f.Jx * to_mass, Jy=f.Jy * to_mass, Jz=f.Jz * to_mass, mu=f.mu, facets=f.facets)
    _damping(fr, document)
    _p_delta(fr, document)
    _support_motions(fr, document, folder)
    with _at("structure"):
        return fr.build()


def _support_motions(fr, document: ModelFile, folder: Path) -> None:
    """``[[loads.support_motion]]``: each displacement history (times ``scale``) on its supported DOF."""
    for k, motion in enumerate(document.loads.support_motion):
        parts = ("loads", "support_motion", k)
        displacement = _time_function(motion.displacement, (*parts, "displacement"), folder, motion.scale)
        with _at(key_path(parts)):
            fr.support_motion(motion.node, motion.dof, displacement)


def _add_element_3d(fr: Frame3D, e, to_mass=1.0) -> None:
    facets = {} if getattr(e, "facets", None) is None else {"facets": e.facets}
    match e:
        case Beam3D():
            fr.beam(e.name, e.node_i, e.node_j, E=e.E, A=e.A, Iy=e.Iy, Iz=e.Iz, G=e.G, J=e.J, vecxz=e.vecxz,
                    axial_strain=e.axial_strain, rho=None if e.rho is None else e.rho * to_mass)
        case Bar():
            fr.bar(e.name, e.node_i, e.node_j, e.E, e.A, axial_strain=e.axial_strain, Fy=e.Fy, Fy_t=e.Fy_t,
                   Fy_c=e.Fy_c, hardening=e.hardening)
        case Spring3D():
            fr.spring(e.name, e.node_i, e.k, j=e.node_j, direction=e.direction)
        case Dashpot3D():
            fr.dashpot(e.name, e.node_i, e.c, j=e.node_j, direction=e.direction)
        case Soil3D():
            fr.soil(e.name, e.node, e.k, c=e.c, direction=e.direction, gap=e.gap, capacity=e.capacity, mu=e.mu,
                    kt=e.kt, ct=e.ct, bearing=e.bearing, **facets)
        case Gap3D():
            fr.gap(e.name, e.node_i, e.node_j, e.k, gap=e.gap, c=e.c, direction=e.direction, mu=e.mu, kt=e.kt,
                   ct=e.ct, **facets)
        case Cable():
            fr.cable(e.name, e.node_i, e.node_j, e.E, e.A, slack=e.slack, capacity=e.capacity)
        case YieldLink3D():
            fr.yield_link(e.name, e.node, e.node_j, k=e.k, Fy=e.Fy, Fy_t=e.Fy_t, Fy_c=e.Fy_c, direction=e.direction,
                          hardening=e.hardening, backbone=e.backbone)
        case Hinge3D():
            fr.hinge(e.name, e.beam, e.end, My=e.My, Mz=e.Mz, shape=e.shape, k=e.k, hardening=e.hardening, **facets)
        case Slider3D():
            fr.slider(e.name, e.node, mu=e.mu, N=e.N, k=e.k, direction=e.direction)


def _gravity_value(document: ModelFile) -> float:
    """``g`` of ``[loads.gravity]`` in the model's units."""
    units, g = document.units, document.loads.gravity.g
    return STANDARD_GRAVITY * TIME_UNITS[units.time] ** 2 / length_factor(units.length) if g == "standard" else g


def _add_element(fr: Frame2D, e, to_mass=1.0) -> None:
    match e:
        case Beam():
            fr.beam(e.name, e.node_i, e.node_j, e.E, e.A, e.I, axial_strain=e.axial_strain, curvature=e.curvature,
                    rho=None if e.rho is None else e.rho * to_mass)
        case Bar():
            fr.bar(e.name, e.node_i, e.node_j, e.E, e.A, axial_strain=e.axial_strain, Fy=e.Fy, Fy_t=e.Fy_t,
                   Fy_c=e.Fy_c, hardening=e.hardening)
        case Spring():
            fr.spring(e.name, e.node_i, e.k, j=e.node_j, direction=e.direction)
        case Dashpot():
            fr.dashpot(e.name, e.node_i, e.c, j=e.node_j, direction=e.direction)
        case Soil():
            fr.soil(e.name, e.node, e.k, c=e.c, direction=e.direction, gap=e.gap, capacity=e.capacity, mu=e.mu,
                    kt=e.kt, ct=e.ct, bearing=e.bearing)
        case Gap():
            fr.gap(e.name, e.node_i, e.node_j, e.k, gap=e.gap, c=e.c, direction=e.direction, mu=e.mu, kt=e.kt,
                   ct=e.ct)
        case Cable():
            fr.cable(e.name, e.node_i, e.node_j, e.E, e.A, slack=e.slack, capacity=e.capacity)
        case YieldLink():
            fr.yield_link(e.name, e.node, e.node_j, k=e.k, Fy=e.Fy, Fy_t=e.Fy_t, Fy_c=e.Fy_c, direction=e.direction,
                          hardening=e.hardening, backbone=e.backbone)
        case Hinge2D():
            fr.hinge(e.name, e.beam, e.end, My=e.My, k=e.k, hardening=e.hardening, backbone=e.backbone,
                     interaction=e.interaction, Ny=e.Ny)
        case Slider():
            fr.slider(e.name, e.node, mu=e.mu, N=e.N, k=e.k, direction=e.direction)


# ---------------------------------------------------------------------- loads
def _build_load(document: ModelFile, folder: Path, model: Model, structure: Structure | None) -> LoadHistory:
    """Gravity, nodal loads times their time functions and ground motions ``-M r a_g(t)``."""
    units = document.units
    seconds = TIME_UNITS[units.time]
    to_model = seconds ** 2 / length_factor(units.length)        # m/s^2 -> length/time^2
    constant = np.zeros(model.n)
    gravity = document.loads.gravity
    if gravity is not None:
        constant += structure.gravity(_gravity_value(document), gravity.direction)
    terms = _nodal_terms(document.loads.nodal, folder, model, structure)
    for k, load in enumerate(document.loads.distributed):
        parts = ("loads", "distributed", k)
        with _at(key_path((*parts, "beam"))):
            w = {key: getattr(load, key) for key in ("wx", "wy", "wz") if hasattr(load, key)}
            vector = structure.distributed_load(load.beam, **w)
        terms.append((vector, _time_function(load.time_function, (*parts, "time_function"), folder)))
    for k, motion in enumerate(document.loads.ground_motion):
        parts = ("loads", "ground_motion", k)
        if structure is not None and is_3d(document):
            r = structure.influence(motion.direction)
        elif structure is not None:
            r = np.array([1.0 if dof == motion.direction else 0.0 for _, dof in structure.dofs.free])
        else:
            r = read_vector((*parts, "influence"), motion.influence, folder, model.n)
        options = {key: getattr(motion, key) for key in ("units", "dt", "skip_header")
                   if getattr(motion, key) is not None}
        with _at(key_path((*parts, "file"))):
            record = read_record(folder / motion.file, **options)
        acceleration = record.acceleration
        if motion.at != "surface":              # the free-field surface motion of [site] (scipy.fft: imported here)
            from ..loads.site_response import free_field

            wave = motion.wave or ("P" if motion.direction == ("uz" if is_3d(document) else "uy") else "S")
            layers, base = _site_profile(document)
            with _at(key_path((*parts, "at"))):
                acceleration = free_field(acceleration, record.dt / seconds, layers, base, at=motion.at,
                                          depth=motion.depth, wave=wave)
        a_g = Tabulated(record.time / seconds, acceleration * (motion.scale * to_model))
        with _at(key_path((*parts, "direction"))):
            inertia = ground_inertia(structure, motion.direction)          # rigid blocks: every node's
        terms.append((-np.asarray(model.M @ r).ravel() if inertia is None else inertia, a_g))
    return LoadHistory(constant, tuple(terms), sampling={"average": "hat", "point": "point"}[
        document.analysis.load_sampling])


def _nodal_terms(loads, folder: Path, model: Model, structure: Structure | None) -> list:
    """The ``(vector, f)`` terms of ``[[loads.nodal]]``: one per distinct time function, assembled at once."""
    groups: dict = {}
    for k, load in enumerate(loads):
        groups.setdefault(load.time_function, []).append(k)
    terms = []
    for spec, indices in groups.items():
        if structure is not None:
            vector = _frame_nodal_vector(structure, loads, indices)
        else:
            rows = [dof_index(model, ("loads", "nodal", k, "dof"), loads[k].dof) for k in indices]
            vector = np.bincount(rows, weights=[loads[k].value for k in indices], minlength=model.n)
        terms.append((vector, _time_function(spec, ("loads", "nodal", indices[0], "time_function"), folder)))
    return terms


def _frame_nodal_vector(structure: Structure, loads, indices) -> np.ndarray:
    """The sum (n,) of the frame's nodal loads ``loads[k]``, ``k`` in ``indices``.

    A component on a DOF that cannot move is reported by ``Structure.nodal_load`` with its key path.
    """
    dofs = structure.dofs
    movable = np.diff(sp.csr_matrix(dofs.T).indptr) > 0
    rows, values, owners = [], [], []
    for k in indices:
        for dof in dofs.dof_names:
            value = getattr(loads[k], dof)
            if value:
                rows.append(dofs.full_index(loads[k].node, dof))
                values.append(value)
                owners.append(k)
    stuck = [k for k, row in zip(owners, rows) if not movable[row]]
    if stuck:
        load = loads[stuck[0]]
        with _at(key_path(("loads", "nodal", stuck[0]))):
            structure.nodal_load(load.node, **{dof: getattr(load, dof) or 0.0 for dof in dofs.dof_names})
    return dofs.gather(np.bincount(np.asarray(rows, dtype=int), weights=values, minlength=dofs.T.shape[0]))


def _time_function(spec, parts, folder: Path, peak: float = 1.0):
    """The :mod:`unilateral.loads` time function (peak ``peak``, a table's values times it) of a
    ``time_function`` table."""
    with _at(key_path(parts)):
        match spec:
            case RectangularPulse():
                return Rectangular(peak, t_start=spec.t_start, t_end=spec.t_end)
            case HalfSinePulse():
                return HalfSine(peak, t_start=spec.t_start, duration=spec.duration)
            case TriangularPulse():
                return Triangular(peak, t_start=spec.t_start, t_peak=spec.t_peak, t_end=spec.t_end)
            case ConstantLoad():
                return Constant(peak)
            case RampLoad():
                return Ramp(spec.t_ramp, peak)
            case TableLoad():
                table = Tabulated.from_csv(folder / spec.file, time_column=spec.time_column,
                                           value_column=spec.value_column, outside=spec.outside,
                                           skip_header=spec.skip_header)
                return table if peak == 1.0 else Tabulated(table.t, peak * table.values, table.outside)


def _figure(document: ModelFile) -> dict | None:
    figure = document.output.figure
    if figure is None:
        return None
    unit = "rad" if figure.dof.startswith("r") else document.units.length
    label = figure.label or f"{figure.dof} of node {figure.node} ({unit})"
    return {"node": figure.node, "dof": figure.dof, "label": label}

"""A model file from an OpenSees script: ``unilateral convert model.py|model.tcl -o model.toml``.

The script runs on :mod:`unilateral.opensees` (a Tcl script through :mod:`.tcl`) in a session of
its own, :class:`CaptureSession` (its recorders write their files, as the script's run does). Its static ``LoadControl``
analyses (gravity) run as they are; its main analysis is the first transient one (or the first
``DisplacementControl``): at that ``analyze`` the domain is captured (nodes, elements, masses,
damping, patterns) with the time it starts at, and the following ``analyze`` calls count its steps.
They must go on with the same model, loads, integrator and ``dt``: a model file holds one analysis
of one model. The capture becomes a model file (:mod:`.convert_frame`, :mod:`.convert_loads`),
written by :mod:`.toml_writer`, with the tables and records it needs beside it.

Before anything is written the file is read back by :func:`unilateral.modelfile.load_model_file`
and its model compared with the script's (:func:`_check_same_model`): the same DOFs and
constraints, ``K``, ``M``, ``C`` and the loads at every step to 1e-12. What the model file cannot
express is refused (:class:`~.convert_frame.NotConvertible`), naming the command and what is missing.
"""

from __future__ import annotations

import copy
import runpy
import sys
import tempfile
import types
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import scipy.sparse as sp

from .commands import Session
from .convert_frame import NotConvertible, not_convertible, structure_tables
from .convert_loads import pushover_tables, transient_tables
from .queries import nodal
from .refusals import OpenSeesRefused
from .toml_writer import dumps

__all__ = ["CaptureSession", "Stage", "convert_script", "model_document", "run_captured"]

SUFFIXES = (".py", ".tcl")
#: The largest relative difference between the converted model and the script's.
TOLERANCE = 1e-12


@dataclass
class Stage:
    """The main analysis of a script: its kind, the domain when it began and how far it went."""

    kind: str                       # "transient" or "pushover"
    domain: object                  # a copy of the Domain at the first analyze of the stage
    built: object                   # the Built of that domain
    t0: float
    integrator: tuple
    keys: tuple                     # (version, load_version) of the domain
    dt: float | None = None
    steps: int = 0
    time: float = 0.0
    control: tuple | None = None    # (node, dof) of a DisplacementControl
    end: float | None = None        # the control DOF's displacement at the end
    sign: float = 1.0               # +1, or -1 if the pattern pushes the control DOF the other way
    closed: bool = False            # wipe() was called after it began


class CaptureSession(Session):
    """A :class:`~.commands.Session` that captures the main analysis (:class:`Stage`) of its script."""

    def __init__(self):
        super().__init__()
        self.stage = None

    def wipe(self):
        """``wipe()``; after the main analysis began, a second model follows: refused at its analyze."""
        if self.stage is not None:
            self.stage.closed = True
        super().wipe()

    def analyze(self, numIncr=1, dt=None, *args):
        """``analyze``: runs it; the first transient (or DisplacementControl) one begins the stage."""
        a, d = self.analysis, self.domain
        integrator = a.integrator or (("Newmark", 0.5, 0.25) if a.kind == "Transient" else ("LoadControl", 1.0))
        main = a.kind == "Transient" or (a.kind == "Static" and integrator[0] == "DisplacementControl")
        what = f"analyze({numIncr}{'' if dt is None else f', {dt}'})"
        if not main and self.stage is None:
            return super().analyze(numIncr, dt, *args)
        if a.kind == "Transient" and (dt is None or args or not float(dt) > 0):
            return super().analyze(numIncr, dt, *args)                 # the module refuses it
        if self.stage is None:
            self.stage = self._begin(integrator, dt)
        else:
            self._check_continues(what, integrator, dt)
        code = super().analyze(numIncr, dt, *args)
        if code != 0:
            not_convertible(what, f"the script's analysis failed at t = {d.time:g} (the reason is printed above); "
                            "a model file would run past it", "a script whose analysis runs to its end")
        stage = self.stage
        stage.steps += int(numIncr)
        stage.time = d.time
        if stage.control is not None:
            stage.end = float(nodal(a, "u", *stage.control))
            stage.sign = a.path.scale                   # the sense the pattern pushes the control DOF
        return code

    def _begin(self, integrator, dt) -> Stage:
        a, d = self.analysis, self.domain
        if d.extensions or a.bilateral:                # (extensions.py: no model-file entries are written for them)
            not_convertible(f"{'the extension elements ' + str(list(d.extensions)) if d.extensions else 'bilateral(1)'}",
                            "the extensions of unilateral.opensees are not converted to a model file", "the model "
                            "file's own [[foundations]], [[unilateral]] entries and bilateral_reference, by hand")
        b = a.current()
        keys = (d.version, d.load_version)
        if integrator[0] == "Newmark":
            if tuple(integrator[1:]) != (0.5, 0.25):
                not_convertible(f"integrator('Newmark', {integrator[1]:g}, {integrator[2]:g})", "the rules of a "
                                "model file are bdf1, bdf2, trapezoidal (Newmark 0.5, 0.25) and hht",
                                "integrator('Newmark', 0.5, 0.25)")
            _check_static_start(a)
            return Stage("transient", copy.deepcopy(d), b, d.time, integrator, keys, dt=float(dt), time=d.time)
        _, node, dof, _ = integrator
        return Stage("pushover", copy.deepcopy(d), b, d.time, integrator, keys, time=d.time, control=(node, dof))

    def _check_continues(self, what, integrator, dt):
        s, d = self.stage, self.domain
        why = None
        if s.closed:
            why = "wipe() was called since the analysis began: a second model"
        elif (d.version, d.load_version) != s.keys:
            why = "the model or its loads changed since the analysis began"
        elif integrator[0] != s.integrator[0] or (s.kind == "transient" and integrator != s.integrator) or (
                s.kind == "pushover" and tuple(integrator[1:3]) != s.control):
            why = f"the integrator changed ({s.integrator} to {integrator})"
        elif s.kind == "transient" and float(dt) != s.dt:
            why = f"the time step changed ({s.dt!r} to {float(dt)!r})"
        elif d.time != s.time:
            why = f"the time was set to {d.time:g} (setTime) since the last step"
        if why:
            not_convertible(what, f"{why}, and a model file holds one analysis of one model", "one analysis "
                            "(gravity first, then one transient or DisplacementControl analysis), or convert "
                            "the scripts of each analysis separately")


def _check_static_start(a):
    """Refuse a transient that does not start from rest in the static state of its loads (the model
    file's ``initial = "static"``)."""
    from ..initial import static_state
    from ..lcp import get_lcp_solver

    b, d = a.built, a.domain
    q = a.load([d.time])[0] + b.model.q_imposed(d.time)
    state = static_state(b.model, q, get_lcp_solver("bpp"))
    scale = max(float(np.abs(state.u).max(initial=0.0)), float(np.abs(a.u).max(initial=0.0)),
                float(np.abs(state.v).max(initial=0.0)), 1e-300)       # (openings: the round-off of the gaps)
    moving = bool(np.any(a.ud != 0))
    if state.message or moving or float(np.abs(state.u - a.u).max(initial=0.0)) > 1e-9 * scale:
        not_convertible(f"the transient analysis from t = {d.time:g}", "its start is not at rest in the static "
                        "state of the loads at that time" + (" (the model is moving)" if moving else ""),
                        "a transient analysis from rest or right after the static (gravity) analysis of its loads")


def run_captured(script) -> CaptureSession:
    """Run the OpenSees script ``script`` (``.py`` or ``.tcl``) in a :class:`CaptureSession`.

    A Python script's ``openseespy.opensees`` (or ``opensees``, or ``unilateral.opensees``) is
    :mod:`unilateral.opensees` with the commands of the session, for the time of the run.
    """
    session = CaptureSession()
    path = Path(script)
    if path.suffix.lower() == ".tcl":
        from .tcl import TclSession

        TclSession(session).source(path)
        return session
    from .. import opensees as module

    commands = session.commands()
    saved = {name: module.__dict__.get(name) for name in commands}
    names = ("openseespy", "openseespy.opensees", "opensees")
    modules = {name: sys.modules.get(name) for name in names}
    package = types.ModuleType("openseespy")
    package.opensees = module
    module.__dict__.update(commands)
    sys.modules.update({"openseespy": package, "openseespy.opensees": module, "opensees": module})
    try:
        runpy.run_path(str(path), run_name="__main__")
    except SystemExit as exc:
        if exc.code not in (None, 0):
            raise RuntimeError(f"{path.name} exited with status {exc.code}") from None
    except OpenSeesRefused:
        raise
    except Exception as exc:
        raise RuntimeError(f"{path.name} failed: {type(exc).__name__}: {exc}") from exc
    finally:
        module.__dict__.update(saved)
        for name, old in modules.items():
            if old is None:
                sys.modules.pop(name, None)
            else:
                sys.modules[name] = old
    return session


def model_document(stage: Stage, stem: str) -> tuple[dict, dict]:
    """``(document, files)``: the model file of ``stage`` as a dict for :func:`~.toml_writer.dumps` and
    ``{file name: text}`` of the tables and records beside it (named ``<stem>.<what>.txt``)."""
    d = stage.domain
    tables, fixed = structure_tables(d)
    document = {"units": {"length": "m", "force": "kN", "time": "s"}}
    if d.ndm == 3:
        document["frame"] = {"dimensions": 3}
    damping = tables.pop("damping", None)
    document.update(tables)
    if damping:
        document["damping"] = damping
    files, pushover = {}, None
    if stage.kind == "transient":
        loads, analysis, files = transient_tables(stage, stem)
    else:
        loads, analysis, pushover = pushover_tables(stage, tables.get("masses", []), fixed)
    if loads:
        document["loads"] = loads
    document["analysis"] = analysis
    if pushover:
        document["pushover"] = pushover
    return document, files


_HEADER = """Converted from {script} by `unilateral convert` ({what}).
OpenSees has no units: every number is the script's, and [units] only labels them (masses in
force time^2/length); a record's units say "m/s2" to match the length unit (change both together).
Elements are named after the script's tags: e<tag>, e<tag>.<k> for the k-th material of a zeroLength."""


def convert_script(script, out, *, force=False) -> dict:
    """Run the OpenSees script ``script`` and write its model as the model file ``out``.

    Parameters
    ----------
    script : path of a ``.py`` (OpenSeesPy) or ``.tcl`` script
    out : path of the ``.toml`` file to write; the tables and records it names are written beside it
    force : bool, replace ``out`` and those files if they exist

    Returns
    -------
    dict
        ``path``, ``files`` (the others written), ``kind`` (``"transient"`` or ``"pushover"``), ``steps``.

    Raises
    ------
    NotConvertible
        For a command the model file cannot express (nothing is written).
    OpenSeesRefused
        For a command outside the subset of :mod:`unilateral.opensees`.
    FileExistsError
        If ``out`` (or a file beside it) exists and not ``force``.
    ValueError
        For a wrong suffix or a missing folder.
    RuntimeError
        For an error of the script itself.
    """
    script, out = Path(script), Path(out)
    _check_paths(script, out, force)
    stage = run_captured(script).stage
    if stage is None:
        not_convertible(script.name, "it runs no transient analysis and no DisplacementControl: a model file's "
                        "[analysis] is a time history or a pushover", "a transient analysis (after the gravity's "
                        "static one) or a DisplacementControl pushover")
    document, files = model_document(stage, out.stem)
    what = f"{stage.kind}, {stage.steps} steps" + (f" of dt = {stage.dt!r}" if stage.dt else "")
    text = dumps(document, _HEADER.format(script=script.name, what=what))
    others = [out.parent / name for name in files]
    if not force and any(p.exists() for p in others):
        raise FileExistsError(f"{', '.join(str(p) for p in others if p.exists())} exists: give --force to replace "
                              "the files of the conversion")
    _check_in_folder(text, files, out, stage)
    from ..io.atomic import write_text_atomic

    for path, content in zip(others, files.values()):
        write_text_atomic(path, content)
    write_text_atomic(out, text)
    return {"path": out, "files": others, "kind": stage.kind, "steps": stage.steps}


def _check_paths(script, out, force):
    if not script.is_file():
        raise FileNotFoundError(f"{script}: no such script")
    if script.suffix.lower() not in SUFFIXES:
        raise ValueError(f"{script}: an OpenSees script is a .py (OpenSeesPy) or a .tcl file, not {script.suffix!r}")
    if out.suffix.lower() != ".toml":
        raise ValueError(f"{out}: a model file ends in .toml, not {out.suffix or 'no suffix'!r}")
    if not out.parent.is_dir():
        raise ValueError(f"{out}: the folder {out.parent} does not exist")
    if out.exists() and not force:
        raise FileExistsError(f"{out} exists: give --force to replace it")


def _check_in_folder(text, files, out, stage):
    """Read the model file back (in a temporary folder beside ``out``) and compare its model with the
    script's."""
    from ..modelfile import ModelFileError, load_model_file

    with tempfile.TemporaryDirectory(prefix=f".{out.name}.", dir=out.parent) as folder:
        folder = Path(folder)
        for name, content in files.items():
            (folder / name).write_text(content, encoding="utf-8")
        (folder / out.name).write_text(text, encoding="utf-8")
        try:
            spec = load_model_file(folder / out.name)
        except ModelFileError as exc:
            raise NotConvertible("the script's model", f"the model-file reader refuses the converted file: {exc}",
                                 "a model the model file can express (see docs/opensees.md)") from None
        _check_same_model(spec, stage)


def _sparse(A):
    return sp.csr_matrix(A) if A is not None else None


def _check_same_model(spec, stage):
    """Refuse if the model read back differs from the script's: DOFs, constraints, ``K``, ``M``, ``C``, loads."""
    ours, theirs = spec.model, stage.built.model
    at = {name: k for k, name in enumerate(ours.dof_names)}
    missing = set(at) ^ set(theirs.dof_names)
    if missing or set(ours.constraint_names) != set(theirs.constraint_names):
        extra = sorted(missing) or sorted(set(ours.constraint_names) ^ set(theirs.constraint_names))
        _differs(f"its DOFs or constraints ({', '.join(map(str, extra[:6]))})")
    index = np.array([at[name] for name in theirs.dof_names])
    for label, A, B in (("K", ours.K, theirs.K), ("M", ours.M, theirs.M),
                        ("C", ours.damping(), theirs.damping())):
        A, B = _sparse(A), _sparse(B)
        A = A[index][:, index] if A is not None else sp.csr_matrix(B.shape)
        B = B if B is not None else sp.csr_matrix(A.shape)
        scale = max(abs(A).max(), abs(B).max(), 1e-300)
        if abs(A - B).max() > TOLERANCE * scale:
            _differs(f"{label} (by {abs(A - B).max() / scale:.2e} of its largest entry)")
    if stage.kind == "transient":
        _check_same_loads(spec, stage, index)
    else:
        _check_same_pushover(spec, stage, index)


def _check_same_loads(spec, stage, index):
    from .stepping import Analysis

    N, dt = stage.steps, stage.dt
    times = np.cumsum(np.r_[stage.t0, np.full(N, dt)])
    theirs = Analysis.load(types.SimpleNamespace(built=stage.built, domain=stage.domain), times)
    ours, before = spec.load.grid_samples(dt, N, "point")
    scale = max(float(np.abs(theirs).max(initial=0.0)), 1e-300)
    error = float(np.abs(ours[:, index] - theirs).max(initial=0.0))
    static = float(np.abs(before[index] - theirs[0]).max(initial=0.0))
    if max(error, static) > TOLERANCE * scale:
        _differs(f"the loads (by {max(error, static) / scale:.2e} of the largest)")


def _check_same_pushover(spec, stage, index):
    """The pushover's gravity and pattern (reduced) against the script's held load and Linear patterns."""
    from .control import _loads

    table = spec.document.pushover
    p, q0 = _loads(types.SimpleNamespace(built=stage.built, domain=stage.domain))
    pattern = sum(spec.structure.nodal_load(f.node, **f.components) for f in table.pattern)   # as run_file
    gravity = np.asarray(spec.load.constant, dtype=float) if table.gravity else None
    for label, ours, theirs in (("the pushover's pattern", pattern, stage.sign * p),
                                ("the gravity", np.zeros(p.size) if gravity is None else gravity, q0 + stage.t0 * p)):
        ours = np.asarray(ours, dtype=float)[index]
        scale = max(float(np.abs(theirs).max(initial=0.0)), float(np.abs(ours).max(initial=0.0)), 1e-300)
        if float(np.abs(ours - theirs).max(initial=0.0)) > TOLERANCE * scale:
            _differs(label)


def _differs(what):
    not_convertible("the script's model", f"the model file read back differs from it in {what}: a command the "
                    "conversion does not represent exactly", "report it (docs/opensees.md, Conversion); the "
                    "script runs as it is with `unilateral opensees`")

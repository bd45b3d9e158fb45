"""OpenSeesPy's commands on this library's model: ``import unilateral.opensees as ops``.

An OpenSeesPy script (2-D or 3-D) of the supported subset runs unchanged but for its import: the
commands record the model (:mod:`.domain`), ``analyze`` builds it (:mod:`.build`) and steps it with
a :class:`unilateral.Simulation` or follows its static path (:mod:`.stepping`, :mod:`.control`),
and the queries and recorders answer in OpenSees's layout and signs (:mod:`.queries`,
:mod:`.recorders`). What is outside the subset raises :class:`OpenSeesRefused` at once
(:mod:`.refusals`). Tcl scripts run through Python's Tcl interpreter (:mod:`.tcl`,
``unilateral opensees model.tcl``). :mod:`.convert` writes a script's model as a model file
(``unilateral convert model.py -o model.toml``). See ``docs/opensees.md``."""

from __future__ import annotations

from .commands import Session
from .refusals import OpenSeesRefused, refused_command

_session = Session()
_commands = _session.commands()
globals().update(_commands)

__all__ = ["OpenSeesRefused", *_commands]

#: The submodules not imported with the package (``from unilateral.opensees import convert`` imports them).
_LAZY_MODULES = ("convert", "convert_frame", "convert_loads", "toml_writer", "tcl")


def __getattr__(name):
    """Every other OpenSeesPy command: a function that refuses it when called."""
    if name.startswith("__"):
        raise AttributeError(name)
    if name in _LAZY_MODULES:
        import importlib

        return importlib.import_module(f"{__name__}.{name}")
    return refused_command(name)

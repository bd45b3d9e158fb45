"""Model files: a structure, its loads and the analysis settings in one TOML file.

A model file describes either a 2-D frame (nodes, supports, rigid links, elements, unilateral
elements, masses, damping), a 3-D frame (``[frame] dimensions = 3``: the same sections read by
the rules of :class:`~unilateral.structure.Frame3D`, and rigid diaphragms) or a matrix-level model
read from Matrix Market files, together with
its units, loads (gravity, nodal loads with time functions, ground-motion records) and analysis
settings. The format is documented in ``docs/model-file.md``; its JSON schema, from
:func:`model_file_schema`, in ``docs/model-file.schema.json``.

>>> spec = load_model_file("examples/liolios1990.toml")            # doctest: +SKIP
>>> sol = unilateral.solve(spec.model, spec.load, dt=spec.analysis["dt"], t_end=0.5)   # doctest: +SKIP

Every problem of a file raises :class:`ModelFileError` (a ``ValueError``) whose message names
the file, the key path and the bad value, says what is wrong and what would be valid, e.g.
``model.toml: elements[3].node_j = 17: no node 17 (nodes are 1..12)``.
"""

from importlib import import_module

#: Public name -> the submodule that defines it, imported on first use: :mod:`.build` imports numpy,
#: scipy and the structure code, while :mod:`.schema`, :mod:`.dimensions` and :mod:`.errors`
#: (pydantic only) let the command line check a model file's keys and values before those.
_EXPORTS = {**dict.fromkeys(("LoadHistory", "ModelSpec", "build_model_spec", "load_model_file"), "build"),
            "ModelFileError": "errors", **dict.fromkeys(("model_file_schema", "write_schema"), "dimensions")}

__all__ = sorted(_EXPORTS)


def __getattr__(name):
    module = _EXPORTS.get(name)
    if module is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    value = getattr(import_module(f"{__name__}.{module}"), name)
    globals()[name] = value
    return value


def __dir__():
    return sorted(set(globals()) | set(_EXPORTS))

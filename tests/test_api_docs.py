"""The API reference builds with pdoc, warnings as errors, by the command the README gives.

``python -W error -m pdoc --docformat numpy -o DIR unilateral ...``: every warning of pdoc (a name
in ``__all__`` that does not resolve, an annotation that cannot be evaluated, a module that fails
to import) is an error. ``unilateral`` alone would document only the names of its ``__all__`` and
the one submodule named there (``solve``), so the command lists every public module; the test
checks that the list is complete, runs the command and checks the pages.
"""

import html
import importlib
import os
import pkgutil
import re
import shlex
import subprocess
import sys
from pathlib import Path

import pytest

import unilateral

pytest.importorskip("pdoc")
README = Path(__file__).resolve().parents[1] / "README.md"


def _readme_command() -> list[str]:
    commands = re.findall(r"`(python -W error -m pdoc [^`]+)`", README.read_text(encoding="utf-8"))
    assert len(commands) == 1, "README.md should give the pdoc command once, in its Documentation list"
    return shlex.split(commands[0])


#: Modules of subpackages documented on pages of their own: their packages' ``__all__`` lists the
#: functions the package exports, so pdoc does not walk to them from there (the structure's results,
#: the energy balance, the modes and the outputs of a run are looked up by users).
DEEP_MODULES = {"unilateral.analysis.energy", "unilateral.structure.modes", "unilateral.analysis.outputs",
                "unilateral.analysis.results", "unilateral.structure.forces", "unilateral.structure.forces3d"}


def _public_modules() -> set[str]:
    """``unilateral``, its public direct submodules (the rest is reached through them) and :data:`DEEP_MODULES`."""
    names = {f"unilateral.{info.name}" for info in pkgutil.iter_modules(unilateral.__path__)
             if not info.name.startswith("_")}
    listed = {f"unilateral.{name}" for name in unilateral.__all__}   # pdoc walks these from unilateral
    return {"unilateral"} | (names - listed) | DEEP_MODULES


def test_readme_command_lists_every_public_module():
    command = _readme_command()
    assert command[:8] == ["python", "-W", "error", "-m", "pdoc", "--docformat", "numpy", "-o"]
    assert sorted(command[9:]) == sorted(_public_modules())


def test_api_reference_builds_without_warnings(tmp_path):
    command = _readme_command()
    out = tmp_path / "api"
    command = [sys.executable, *command[1:8], str(out), *command[9:]]
    proc = subprocess.run(command, capture_output=True, text=True, timeout=600, cwd=tmp_path,
                          env={**os.environ, "MPLBACKEND": "Agg"})
    assert proc.returncode == 0, proc.stderr[-4000:]
    assert "Warn" not in proc.stderr and "Warn" not in proc.stdout, proc.stderr[-4000:]
    for module in _public_modules():
        page = out / (module.replace(".", "/") + ".html")
        assert page.is_file(), f"no page for {module}"
        first_line = (importlib.import_module(module).__doc__ or "").strip().splitlines()[0]
        words = re.findall(r"\w+", first_line)[:4]                # the start of the module's docstring
        text = html.unescape(re.sub(r"<[^>]+>", " ", page.read_text(encoding="utf-8")))
        assert re.search(r"\W+".join(words), text), (module, words)
    # the names the package exports are documented on its page, e.g. solve and Model
    top = html.unescape((out / "unilateral.html").read_text(encoding="utf-8"))
    for name in ("solve", "Model", "LoadHistory", "Solution"):
        assert f'id="{name}"' in top, name

"""Every TOML block of README.md and docs/*.md parses (TOML 1.0, as ``tomllib`` reads a model
file); a block that is a whole frame model file (``nodes``, elements and ``[analysis]``; not the syntax sketch of two nodes) also builds."""

from __future__ import annotations

import re
import tomllib
from pathlib import Path

import pytest

from unilateral.modelfile import load_model_file

ROOT = Path(__file__).parents[1]
FENCE = re.compile(r"^```toml[ \t]*\n(.*?)^```", re.S | re.M)


def _blocks():
    found = []
    for path in [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md"))]:
        text = path.read_text()
        for match in FENCE.finditer(text):
            line = text[:match.start()].count("\n") + 2          # the block's first line
            found.append(pytest.param(match.group(1), id=f"{path.name}:{line}"))
    return found


BLOCKS = _blocks()


def test_the_documentation_has_toml_blocks():
    assert len(BLOCKS) >= 9
    assert any("[[foundations]]" in block.values[0] for block in BLOCKS)


@pytest.mark.parametrize("text", BLOCKS)
def test_every_toml_block_parses_and_a_whole_model_file_builds(text, tmp_path):
    try:
        document = tomllib.loads(text)
    except tomllib.TOMLDecodeError as exc:
        pytest.fail(f"not valid TOML: {exc}\n{text}")
    whole = "nodes" in document and "analysis" in document and ("elements" in document or "unilateral" in document)
    if whole:                                                       # a whole frame model file
        path = tmp_path / "model.toml"
        path.write_text(text)
        spec = load_model_file(path)
        assert spec.model.n > 0

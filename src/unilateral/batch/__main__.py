"""``python -m unilateral.batch STUDY.toml --out DIR``: the ``unilateral batch`` command."""

from unilateral.batch.cli import batch

if __name__ == "__main__":
    batch(prog_name="python -m unilateral.batch")

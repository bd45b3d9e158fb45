"""A study is counted before it is read: the refusals of what would not fit come before any model
variant is built or any analysis listed (counted by the calls, never timed), and the keys of the
analyses, computed from fragments, are those of the whole ident."""

from __future__ import annotations

import pytest

from test_batch import record_files, write_study
from unilateral.batch import StudyFileError, load_study
from unilateral.batch import estimate, study as study_module
from unilateral.batch.estimate import ANALYSIS_BYTES, VARIANT_BYTES, size_problems, study_size
from unilateral.batch.study import package_version, sha256_json

GIB = 2**30


@pytest.fixture
def builds(monkeypatch):
    """Counts of the model variants built and of the analyses listed; the machine's memory 16 GiB
    (the refusals do not depend on the machine's memory)."""
    counts = {"variants": 0, "analyses": 0}
    build, analysis = study_module.build_model_spec, study_module._analysis

    def counted_build(*args, **kwargs):
        counts["variants"] += 1
        return build(*args, **kwargs)

    def counted_analysis(*args, **kwargs):
        counts["analyses"] += 1
        return analysis(*args, **kwargs)

    monkeypatch.setattr(study_module, "build_model_spec", counted_build)
    monkeypatch.setattr(study_module, "_analysis", counted_analysis)
    monkeypatch.setattr(estimate, "machine_memory", lambda: 16 * GIB)
    return counts


def _sweep(values: int, parameters=3, group=False) -> str:
    keys = ["unilateral.soil3.k", "unilateral.soil2.k", "unilateral.soil4.k"][:parameters]
    listed = ", ".join(f"{1e5 + i:.1f}" for i in range(values))
    return "".join(f'[[parameters]]\nkey = "{key}"\nvalues = [{listed}]\n' + ('group = "g"\n' if group else "")
                   for key in keys)


def test_a_sweep_of_a_billion_variants_is_refused_before_any_variant_is_built(tmp_path, builds):
    path = write_study(tmp_path, '[[models]]\nfile = "tower.toml"\n' + _sweep(1000))
    with pytest.raises(StudyFileError) as info:
        load_study(path)
    message = str(info.value)
    assert "parameters: 1,000 x 1,000 x 1,000 values crossed = 1,000,000,000 combinations" in message
    assert "1,000,000,000 model variants" in message and "of this machine's 16 GiB" in message
    assert 'group = "..."' in message
    assert builds == {"variants": 0, "analyses": 0}


def test_the_same_values_zipped_in_one_group_are_counted_as_1000_variants():
    from unilateral.batch.schema import StudyFile

    doc = StudyFile.model_validate({"models": [{"file": "tower.toml"}], "quantities": [
        {"name": "u", "type": "uplift"}], "parameters": [
        {"key": k, "values": list(range(1000)), "group": "g"} for k in ("a.b", "c.d", "e.f")]})
    size = study_size(doc, ".")
    assert (size.variants, size.analyses, size.group_sizes) == (1000, 1000, [1000])
    assert size_problems(size, total=16 * GIB) == []


def test_a_study_of_200000_levels_is_refused_before_any_analysis_is_listed(tmp_path, builds):
    files = ", ".join(f'"{p.as_posix()}"' for p in record_files(10))
    levels = ", ".join(f"{0.01 * (i + 1):.4f}" for i in range(200_000))
    path = write_study(tmp_path, f'[[models]]\nfile = "tower.toml"\n[records]\nfiles = [{files}]\ndirection = "ux"\n'
                                 f'[scaling]\nvalues = [{levels}]\n')
    with pytest.raises(StudyFileError) as info:
        load_study(path)
    message = str(info.value)
    assert "scaling.values: 200,000 levels x 10 records x 1 model variants = 2,000,000 analyses" in message
    assert f"{2_000_000 * ANALYSIS_BYTES / GIB:.3g} GiB" in message
    assert builds == {"variants": 0, "analyses": 0}


def test_the_size_is_announced_before_the_variants_are_built_and_counts_the_study(tmp_path, builds):
    files = ", ".join(f'"{p.as_posix()}"' for p in record_files(3))
    path = write_study(tmp_path, f'[[models]]\nfile = "tower.toml"\n[records]\nfiles = [{files}]\ndirection = "ux"\n'
                                 '[scaling]\nvalues = [0.5, 1.0]\n[analysis]\ndt = 0.01\nt_end = 0.5\n'
                                 + _sweep(2, parameters=2))
    seen = []
    study = load_study(path, announce=lambda size: seen.append((size, dict(builds))))
    (size, at_announce), = seen
    assert at_announce == {"variants": 0, "analyses": 0}
    assert (size.variants, size.records, size.levels, size.steps) == (4, 3, 2, 50)
    assert size.analyses == len(study.analyses) == builds["analyses"] == 24
    assert size.variants == len(study.variants) == builds["variants"]
    assert size.memory == 4 * VARIANT_BYTES + 24 * ANALYSIS_BYTES and study.size is size
    assert size.describe().startswith("24 analyses (4 model variants x 3 records x 2 levels) of 50 steps")


def test_the_keys_from_fragments_equal_the_hash_of_the_whole_ident(tmp_path):
    files = ", ".join(f'"{p.as_posix()}"' for p in record_files(2))
    path = write_study(tmp_path, f'[[models]]\nfile = "tower.toml"\n[records]\nfiles = [{files}]\ndirection = "ux"\n'
                                 '[scaling]\nmeasure = "pga"\nvalues = [0.1, 0.2]\n[analysis]\nt_end = "record"\n'
                                 'timeout = 5.0\nlcp_options = { max_iter = 40 }\n' + _sweep(2, parameters=1))
    study = load_study(path)
    assert len({a.key for a in study.analyses}) == len(study.analyses) == 8
    for a in study.analyses:
        ident = {"version": package_version(), "model": a.variant.digest, "overrides": a.variant.overrides,
                 "record": a.record.digest, "ground_motion": a.variant.ground_motion, "scale": a.scale,
                 "settings": {k: v for k, v in a.settings.items() if k != "timeout"},
                 "quantities": [q.model_dump() for q in study.document.quantities]}
        assert a.key == sha256_json(ident)[:24]
        assert a.settings["timeout"] == 5.0 and a.settings["lcp_options"] == {"max_iter": 40}

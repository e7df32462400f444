"""`layoutdsl batch --sample KIND:N`: new buildings drawn by the sampler, compiled, verified,
resumable; a re-run rewrites nothing.

The sampler model here is fitted on the two smallest example plans (8 and 17 rooms), so its
samples are small and each building compiles in a couple of seconds.
"""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from layoutdsl.api import load_spec
from layoutdsl.batch.jobs import BatchInputError
from layoutdsl.batch.sampled import parse_rooms, parse_sample, sample_jobs
from layoutdsl.cli import main
from layoutdsl.layout import Layout
from layoutdsl.layout.verify import drawn_boundary, verify
from layoutdsl.sample import SpecSampler, fit_grammar, load_grammar
from layoutdsl.sample.corpus import read_corpus

EXAMPLES = Path(__file__).resolve().parents[2] / "examples" / "floorplans"


@pytest.fixture(scope="module")
def small_model(tmp_path_factory) -> Path:
    plans = read_corpus([EXAMPLES / "school_Lamuniere1.xml", EXAMPLES / "school_VarzeaPaulistaFDE2.xml"])
    path = tmp_path_factory.mktemp("model") / "grammar.json"
    path.write_text(fit_grammar(plans).to_json())
    return path


def files_state(folder: Path) -> dict[str, tuple[bytes, int, int]]:
    return {str(p.relative_to(folder)): (p.read_bytes(), p.stat().st_mtime_ns, p.stat().st_ino)
            for p in sorted(folder.rglob("*")) if p.is_file()}


def test_parse_sample():
    assert parse_sample("school:12") == ("school", 12)
    for bad in ("school", "school:", ":3", "school:x", "school:0"):
        with pytest.raises(BatchInputError):
            parse_sample(bad)


def test_parse_rooms_and_a_narrower_range():
    assert parse_rooms("10-20") == (10, 20)
    for bad in ("10", "5-20", "20-10", "10-151", "a-b"):
        with pytest.raises(BatchInputError):
            parse_rooms(bad)
    jobs = sample_jobs([("school", 4)], 1, rooms=(10, 20))
    for job in jobs:
        spec, _ = load_spec_text(job.text)
        assert 10 <= len(spec.rooms) <= 20
        assert "--rooms 10-20`" in job.text.splitlines()[0]


def load_spec_text(text: str):
    from layoutdsl.api import lint_source
    from layoutdsl.diagnostics.source import Source

    return lint_source(Source("sample.lay", text))


def test_sample_jobs_carry_the_sampler_specs(small_model):
    jobs = sample_jobs([("school", 3)], 2, base_seed=7, model=small_model)
    assert [job.building for job in jobs] == [
        "school-0001-v1", "school-0001-v2", "school-0002-v1", "school-0002-v2", "school-0003-v1", "school-0003-v2"]
    sampler = SpecSampler(load_grammar(small_model), "school", seed=7)
    assert jobs[2].text == sampler.sample(2).text and jobs[3].text == jobs[2].text
    assert jobs[2].seed != jobs[3].seed  # variants of one sample get their own compile seeds
    again = sample_jobs([("school", 3)], 2, base_seed=7, model=small_model)
    assert [job.fingerprint for job in again] == [job.fingerprint for job in jobs]
    with pytest.raises(BatchInputError, match="knows the kinds school, any"):
        sample_jobs([("office", 1)], 1, model=small_model)


def test_batch_sample_makes_verified_buildings_and_a_rerun_rewrites_nothing(tmp_path, small_model, capsys):
    out = tmp_path / "dataset"
    command = ["batch", "--sample", "school:2", "--sample-model", str(small_model), "-o", str(out),
               "--emit", "xml", "--workers", "2", "--seed", "3"]  # no -q: it would leave out the summary
    assert main(command) == 0
    records = [json.loads(line) for line in (out / "manifest.jsonl").read_text().splitlines()]
    assert [r["building"] for r in records] == ["school-0001-v1", "school-0002-v1"]
    for index, record in enumerate(records, start=1):
        assert record["status"] == "done" and record["kind"] == "sample"
        assert record["source"].startswith(f"sample:school:{index} (seed 3, model ")
        spec_file = out / record["building"] / f"{record['building']}.lay"
        assert f"{record['building']}/{spec_file.name}" in record["files"]
        spec, diagnostics = load_spec(str(spec_file))
        assert spec is not None and not [d for d in diagnostics if d.is_error]
        layout = Layout.from_json((out / record["building"] / f"{record['building']}.layout.json").read_text())
        # the sampled spec leaves its boundary to the tool, which fits it to the building
        assert spec.boundary is not None and spec.boundary.chosen
        assert verify(drawn_boundary(spec, layout), layout) == []
        assert {room.id for room in layout.rooms} == {room.id for room in spec.rooms}
    assert "2 made, 0 failed" in capsys.readouterr().out
    before = files_state(out)
    assert main(command) == 0
    assert "2 already done, 0 made" in capsys.readouterr().out
    assert files_state(out) == before


def test_batch_needs_inputs_or_a_sample(tmp_path, capsys):
    assert main(["batch", "-o", str(tmp_path / "x")]) == 2
    assert "--sample KIND:N" in capsys.readouterr().err
    assert main(["batch", "--sample", "castle:3", "-o", str(tmp_path / "x")]) == 2
    assert "knows the kinds office, school, any" in capsys.readouterr().err

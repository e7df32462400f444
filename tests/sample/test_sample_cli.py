"""`layoutdsl sample`: files written, same bytes on a re-run, JSON result, errors and exit codes."""

from __future__ import annotations

import json

import pytest

from layoutdsl.api import load_spec
from layoutdsl.cli import main
from layoutdsl.sample import load_grammar
from tests.real_plans import EXAMPLES


def snapshot(folder):
    return {p.name: (p.read_bytes(), p.stat().st_mtime_ns, p.stat().st_ino) for p in sorted(folder.iterdir())}


def test_sample_writes_specs_and_records_and_a_rerun_rewrites_nothing(tmp_path, capsys):
    out = tmp_path / "out"
    assert main(["sample", "--like", "school", "-n", "3", "-o", str(out), "--seed", "4"]) == 0
    assert sorted(p.name for p in out.iterdir()) == ["samples.jsonl", "school-0001.lay", "school-0002.lay", "school-0003.lay"]
    records = [json.loads(line) for line in (out / "samples.jsonl").read_text().splitlines()]
    assert [r["name"] for r in records] == ["school-0001", "school-0002", "school-0003"]
    for record in records:
        spec, diagnostics = load_spec(str(out / record["file"]))
        assert spec is not None and not [d for d in diagnostics if d.is_error]
        assert len(spec.rooms) == record["rooms"] and len(spec.adjacencies) == record["doors"]
        assert record["seed"] == 4 and record["model"] == load_grammar().digest
    assert "wrote 3 specs" in capsys.readouterr().out
    before = snapshot(out)
    assert main(["sample", "--like", "school", "-n", "3", "-o", str(out), "--seed", "4"]) == 0
    assert snapshot(out) == before
    assert "wrote 0 specs" in capsys.readouterr().out  # and says so


def test_start_continues_a_run_with_the_same_specs(tmp_path):
    whole, parts = tmp_path / "whole", tmp_path / "parts"
    assert main(["sample", "--like", "office", "-n", "4", "-o", str(whole), "-q"]) == 0
    assert main(["sample", "--like", "office", "-n", "2", "-o", str(parts), "-q"]) == 0
    assert main(["sample", "--like", "office", "-n", "2", "--start", "3", "-o", str(parts), "-q"]) == 0
    assert {p.name: p.read_bytes() for p in whole.iterdir()} == {p.name: p.read_bytes() for p in parts.iterdir()}


def test_json_result_lists_the_samples(tmp_path, capsys):
    assert main(["sample", "--like", "any", "-n", "2", "-o", str(tmp_path), "--format", "json"]) == 0
    result = json.loads(capsys.readouterr().out)
    assert result["command"] == "sample" and result["status"] == "ok"
    assert [s["name"] for s in result["samples"]] == ["any-0001", "any-0002"]
    assert len(result["written"]) == 3  # two specs and samples.jsonl


def test_train_and_save_model_then_sample_from_it(tmp_path, capsys):
    model = tmp_path / "grammar.json"
    assert main(["sample", "--train", str(EXAMPLES), "--save-model", str(model)]) == 0
    grammar = load_grammar(model)
    assert sorted(p.name for p in grammar.plans) == sorted(p.stem for p in EXAMPLES.glob("*.xml"))
    capsys.readouterr()
    assert main(["sample", "--model", str(model), "--like", "office", "-n", "2", "-o", str(tmp_path / "o")]) == 0
    # the one office plan of the examples is office_Milano-1: 17 rooms, so its samples stay near it
    for spec_file in (tmp_path / "o").glob("*.lay"):
        spec, _ = load_spec(str(spec_file))
        assert 10 <= len(spec.rooms) <= 40


def test_usage_errors_exit_2_and_write_nothing(tmp_path, capsys):
    out = tmp_path / "out"
    assert main(["sample", "--like", "house", "-n", "2", "-o", str(out)]) == 2
    assert "the model knows the kinds office, school, any" in capsys.readouterr().err
    assert main(["sample", "-n", "2"]) == 2
    assert "-n needs -o DIR" in capsys.readouterr().err
    assert main(["sample", "--train", str(tmp_path / "none"), "--save-model", str(tmp_path / "m.json")]) == 2
    assert "is not a folder of building XML plans" in capsys.readouterr().err
    bad = tmp_path / "bad.json"
    bad.write_text("[]")
    assert main(["sample", "--model", str(bad), "-n", "1", "-o", str(out)]) == 2
    assert "is not a layoutdsl sampler model" in capsys.readouterr().err
    assert not out.exists()


def test_a_broken_training_plan_is_reported_with_its_diagnostics(tmp_path, capsys):
    plans = tmp_path / "plans"
    plans.mkdir()
    (plans / "school_ok.xml").write_bytes((EXAMPLES / "school_Lamuniere1.xml").read_bytes())
    (plans / "school_broken.xml").write_text("<building><scale>")
    assert main(["sample", "--train", str(plans), "-n", "1", "-o", str(tmp_path / "o")]) == 1
    err = capsys.readouterr().err
    assert "E400" in err and "school_broken.xml" in err
    assert not (tmp_path / "o").exists()


def test_typical_sizes_keep_the_graph_and_change_the_sizes(tmp_path):
    drawn, typical = tmp_path / "drawn", tmp_path / "typical"
    assert main(["sample", "--like", "school", "-n", "1", "-o", str(drawn), "-q"]) == 0
    assert main(["sample", "--like", "school", "-n", "1", "-o", str(typical), "-q", "--typical-sizes"]) == 0
    a, _ = load_spec(str(drawn / "school-0001.lay"))
    b, _ = load_spec(str(typical / "school-0001.lay"))
    assert [(r.id, r.rtype, r.label) for r in a.rooms] == [(r.id, r.rtype, r.label) for r in b.rooms]
    assert a.adjacencies == b.adjacencies
    assert [r.target_w for r in a.rooms] != [r.target_w for r in b.rooms]
    assert "--typical-sizes`, sample 1" in (typical / "school-0001.lay").read_text().splitlines()[0]


def test_rooms_narrows_the_samples(tmp_path, capsys):
    out = tmp_path / "small"
    assert main(["sample", "--like", "any", "-n", "6", "-o", str(out), "--rooms", "10-25", "--format", "json"]) == 0
    result = json.loads(capsys.readouterr().out)
    assert all(10 <= s["rooms"] <= 25 for s in result["samples"])
    with pytest.raises(SystemExit) as exit_info:  # argparse's usage error
        main(["sample", "-n", "1", "-o", str(out), "--rooms", "30-20"])
    assert exit_info.value.code == 2
    assert "a range within 10-150" in capsys.readouterr().err

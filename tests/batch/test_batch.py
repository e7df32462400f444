"""layoutdsl batch: real buildings through the local pool and a real 2-worker Dask cluster.

Every test uses tests/batch/fixtures/tiny.lay (3 rooms, about 2 s per building with the
interpreter start) and checks the written layouts with the independent verifier, the
recorded hashes against the files, and the manifest's one-line-per-building rule.
"""

from __future__ import annotations

import dataclasses
import hashlib
import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

from layoutdsl.api import load_spec
from layoutdsl.batch import SolveLimits, derive_seed, plan_jobs, run_batch
from layoutdsl.batch.jobs import BatchInputError, expand_inputs
from layoutdsl.batch.manifest import append_record, log_path, read_log
from layoutdsl.layout import Layout
from layoutdsl.layout.verify import verify

HERE = Path(__file__).parent
TINY = HERE / "fixtures" / "tiny.lay"
REPO = HERE.parent.parent
LIMITS = SolveLimits(node_limit=5, time_limit=30)


def tiny_jobs(n: int = 3, crash: dict[int, str] | None = None):
    jobs = plan_jobs([str(TINY)], n, base_seed=1, limits=LIMITS, formats=("xml", "png"), timeout=120)
    for index, kind in (crash or {}).items():
        jobs[index] = dataclasses.replace(jobs[index], crash=kind)
    return jobs


def manifest_lines(outdir: Path) -> list[dict]:
    return [json.loads(line) for line in (outdir / "manifest.jsonl").read_text().splitlines()]


def check_done(outdir: Path, record: dict) -> None:
    """A done record: its files exist with the recorded hashes and its layout verifies."""
    assert record["status"] == "done", record
    for name in record["files"]:
        assert hashlib.sha256((outdir / name).read_bytes()).hexdigest() == record["sha256"][name]
    layout_file = next(name for name in record["files"] if name.endswith(".layout.json"))
    layout = Layout.from_json((outdir / layout_file).read_text())
    spec, _ = load_spec(str(TINY))
    assert verify(spec, layout) == []
    assert {room.id for room in layout.rooms} == {"C0", "R0", "R1"}


def without_timing(outdir: Path, record: dict) -> dict[str, bytes]:
    """A building's files, the layout JSON without its timing fields."""
    files = {}
    for name in record["files"]:
        data = (outdir / name).read_bytes()
        if name.endswith(".layout.json"):
            layout = json.loads(data)
            layout["solve"].pop("seconds")
            layout["solve"].pop("first_feasible_seconds")
            data = json.dumps(layout, sort_keys=True).encode()
        files[name] = data
    return files


# --- planning -------------------------------------------------------------------------------

def test_seed_depends_only_on_plan_variant_and_base_seed():
    assert derive_seed("tiny", 1, 0) == derive_seed("tiny", 1, 0)
    # a fixed value: the hash must not change between processes or versions of Python
    assert derive_seed("tiny", 1, 0) == int.from_bytes(
        hashlib.sha256(b"tiny\x001\x000").digest()[:8], "big") % 2**31
    seeds = {derive_seed(plan, v, b) for plan in ("a", "b") for v in (1, 2) for b in (0, 1)}
    assert len(seeds) == 8


def test_inputs_from_folder_and_list_file(tmp_path):
    (tmp_path / "a.lay").write_text(TINY.read_text())
    (tmp_path / "b.xml").write_text("<building/>")
    (tmp_path / "notes.md").write_text("ignored in a folder")
    listing = tmp_path / "list.txt"
    listing.write_text("# two plans\na.lay\nb.xml  # the XML\n")
    assert [p.name for p in expand_inputs([str(tmp_path)])] == ["a.lay", "b.xml"]
    assert [p.name for p in expand_inputs([str(listing), str(tmp_path / "a.lay")])] == ["a.lay", "b.xml"]
    with pytest.raises(BatchInputError, match="notes.md"):
        expand_inputs([str(tmp_path / "notes.md")])


def test_two_plans_with_one_name_are_refused(tmp_path):
    (tmp_path / "x").mkdir()
    (tmp_path / "x" / "tiny.lay").write_text(TINY.read_text())
    with pytest.raises(BatchInputError, match="same name"):
        plan_jobs([str(TINY), str(tmp_path / "x" / "tiny.lay")], 1)


def test_log_survives_a_torn_last_line(tmp_path):
    append_record(tmp_path, {"building": "a-v1", "status": "done"})
    with open(log_path(tmp_path), "ab") as handle:
        handle.write(b'{"building": "b-v1", "sta')  # a driver killed mid-write
    append_record(tmp_path, {"building": "c-v1", "status": "failed"})
    assert sorted(read_log(tmp_path)) == ["a-v1", "c-v1"]


# --- the local pool -------------------------------------------------------------------------

def test_pool_batch_records_an_aborted_building_and_redoes_only_it(tmp_path):
    jobs = tiny_jobs(3, crash={1: "abort"})
    summary = run_batch(jobs, tmp_path, workers=2)
    assert (summary.done, summary.failed) == (2, 1)
    records = {r["building"]: r for r in manifest_lines(tmp_path)}
    assert list(records) == ["tiny-v1", "tiny-v2", "tiny-v3"]
    assert records["tiny-v2"]["status"] == "failed"
    assert "SIGABRT" in records["tiny-v2"]["reason"]
    assert not (tmp_path / "tiny-v2").exists()
    for building in ("tiny-v1", "tiny-v3"):
        check_done(tmp_path, records[building])

    again = run_batch(tiny_jobs(3), tmp_path, workers=2)
    assert (again.skipped, again.done, again.failed) == (2, 1, 0)
    log = [json.loads(line)["building"] for line in log_path(tmp_path).read_text().splitlines()]
    assert sorted(log) == ["tiny-v1", "tiny-v2", "tiny-v2", "tiny-v3"]
    final = manifest_lines(tmp_path)
    assert [r["building"] for r in final] == ["tiny-v1", "tiny-v2", "tiny-v3"]
    for record in final:
        check_done(tmp_path, record)


def test_a_changed_file_is_made_again(tmp_path):
    jobs = tiny_jobs(1)
    run_batch(jobs, tmp_path, workers=1)
    png = tmp_path / "tiny-v1" / "tiny-v1.png"
    original = png.read_bytes()
    png.write_bytes(original[:100])  # damaged after the run
    again = run_batch(jobs, tmp_path, workers=1)
    assert (again.skipped, again.done) == (0, 1)
    assert png.read_bytes() == original  # same seed, same bytes


def test_timeout_costs_that_building_only(tmp_path):
    jobs = [dataclasses.replace(job, timeout=0.05) if job.variant == 1 else job for job in tiny_jobs(2)]
    summary = run_batch(jobs, tmp_path, workers=2)
    records = {r["building"]: r for r in manifest_lines(tmp_path)}
    assert records["tiny-v1"]["status"] == "failed"
    assert records["tiny-v1"]["reason"].startswith("timeout")
    check_done(tmp_path, records["tiny-v2"])
    assert (summary.done, summary.failed) == (1, 1)


def _kill_driver_after_first_record(outdir: Path, extra: list[str]) -> None:
    """Start the batch command, SIGKILL it once one building is logged, before the rest."""
    env = dict(os.environ, PYTHONPATH=os.pathsep.join([str(REPO), os.environ.get("PYTHONPATH", "")]))
    command = [sys.executable, "-m", "layoutdsl", "batch", str(TINY), "-o", str(outdir), "--variants", "4",
               "--seed", "1", "--node-limit", "5", "--time-limit", "30", "--emit", "xml,png", "-q", *extra]
    driver = subprocess.Popen(command, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    log = log_path(outdir)
    deadline = time.monotonic() + 120
    while time.monotonic() < deadline and driver.poll() is None:
        if log.exists() and log.read_text().count("\n") >= 1:
            break
        time.sleep(0.05)
    driver.send_signal(signal.SIGKILL)
    driver.wait()
    return command, env


@pytest.mark.parametrize("engine", ["pool", "dask"])
def test_killed_driver_resumes_without_redoing_finished_buildings(tmp_path, engine):
    if engine == "dask":
        pytest.importorskip("distributed")
    extra = ["--workers", "1"] if engine == "pool" else ["--engine", "dask", "--workers", "2"]
    command, env = _kill_driver_after_first_record(tmp_path, extra)
    before = read_log(tmp_path)
    assert 1 <= len(before) < 4, "the driver was killed before it finished"
    again = [word for word in command if word != "-q"]  # the summary (which -q leaves out)
    result = subprocess.run(again, env=env, capture_output=True, text=True, timeout=300)
    assert result.returncode == 0, result.stderr
    assert f"{len(before)} already done" in result.stdout
    log = [json.loads(line)["building"] for line in log_path(tmp_path).read_text().splitlines() if line.strip()]
    assert sorted(log) == ["tiny-v1", "tiny-v2", "tiny-v3", "tiny-v4"], "something was made twice"
    final = manifest_lines(tmp_path)
    assert sorted(r["building"] for r in final) == ["tiny-v1", "tiny-v2", "tiny-v3", "tiny-v4"]
    for record in final:
        check_done(tmp_path, record)


# --- a real Dask cluster --------------------------------------------------------------------

def test_dask_cluster_survives_a_dead_worker_and_matches_the_pool(tmp_path):
    pytest.importorskip("distributed")
    on_dask = run_batch(tiny_jobs(3, crash={1: "worker"}), tmp_path / "dask", engine="dask", workers=2)
    assert (on_dask.done, on_dask.failed) == (2, 1)
    records = {r["building"]: r for r in manifest_lines(tmp_path / "dask")}
    assert "worker died" in records["tiny-v2"]["reason"]

    run_batch(tiny_jobs(3), tmp_path / "pool", workers=2)
    pool = {r["building"]: r for r in manifest_lines(tmp_path / "pool")}
    for building in ("tiny-v1", "tiny-v3"):
        check_done(tmp_path / "dask", records[building])
        assert without_timing(tmp_path / "dask", records[building]) == without_timing(tmp_path / "pool", pool[building])
        assert records[building]["seed"] == pool[building]["seed"]


def test_dask_engine_without_the_extra_is_a_usage_error(monkeypatch, capsys):
    from layoutdsl.cli import main

    monkeypatch.setitem(sys.modules, "distributed", None)  # as if not installed
    assert main(["batch", str(TINY), "-o", "unused", "--engine", "dask"]) == 2
    assert "layoutdsl[cluster]" in capsys.readouterr().err


def test_cli_records_a_plan_that_does_not_import_and_exits_3(tmp_path, capsys):
    from layoutdsl.cli import main

    broken = tmp_path / "broken.xml"
    broken.write_text("<building><floor><spaces><space id='a'>")  # cut short
    outdir = tmp_path / "out"
    code = main(["batch", str(broken), str(TINY), "-o", str(outdir), "--node-limit", "5",
                 "--time-limit", "30", "--emit", "xml"])  # no -q: it would leave out the summary
    assert code == 3
    out = capsys.readouterr().out
    assert "2 buildings: 0 already done, 1 made, 1 failed" in out
    records = {r["building"]: r for r in manifest_lines(outdir)}
    assert records["broken-v1"]["status"] == "failed"
    assert records["broken-v1"]["reason"].startswith("import: E4")
    assert records["broken-v1"]["kind"] == "plan"
    check_done(outdir, records["tiny-v1"])


def test_dask_cluster_by_address(tmp_path):
    distributed = pytest.importorskip("distributed")
    # default worker settings, as on a cluster someone else started
    # its HTTP server on a free port: another test run's scheduler may hold 8787
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                                  scheduler_kwargs={"dashboard_address": ":0"}, host="127.0.0.1") as cluster:
        summary = run_batch(tiny_jobs(2), tmp_path, engine="dask", address=cluster.scheduler_address)
    assert (summary.done, summary.failed) == (2, 0)
    for record in manifest_lines(tmp_path):
        check_done(tmp_path, record)


def test_cli_names_buildings_that_repeat_an_earlier_variant(tmp_path, capsys):
    from layoutdsl.cli import main

    # five rooms in a door chain, one room deep: every seed gives the row or its mirror
    row = tmp_path / "row.lay"
    row.write_text((REPO / "tests" / "diagnostics" / "solve" / "W906-variants-in-a-long-boundary.lay").read_text())
    outdir = tmp_path / "out"
    code = main(["batch", str(row), "-o", str(outdir), "--variants", "3", "--node-limit", "5",
                 "--time-limit", "30", "--emit", "xml"])  # no -q: it would leave out the summary
    assert code == 0
    out = capsys.readouterr().out
    assert "close       row: 2 buildings within 0.3 of an earlier variant (row-v2, row-v3); W906 says why" in out
    records = manifest_lines(outdir)
    assert [r["status"] for r in records] == ["done"] * 3

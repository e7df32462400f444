"""Make one building in a process of its own, with a hard time-out.

`run_isolated(job)` starts `python -m layoutdsl.batch.building RESULT_FILE`, hands it the job
on standard input and waits at most `job.timeout` seconds. Whatever happens to that process
(a SCIP abort such as "double free", a segfault, the kernel's OOM killer, the time-out) costs
this building only: the caller, a pool thread or an engine's worker, lives on and gets a
failed outcome with the reason. A fresh interpreter per building also means no state leaks
from one building into the next, so its bytes depend on the job alone.

The child imports or lints the input, compiles it with the job's seed and limits, parses the
layout back from its own JSON and verifies that with the independent verifier, renders the
chosen formats in memory and returns the files as bytes. It writes nothing into the batch's
output: the driver does, after all of a building's files exist (layoutdsl.batch.driver).
"""

from __future__ import annotations

import os
import pickle
import signal
import subprocess
import sys
import tempfile
import threading
import time
from dataclasses import asdict, dataclass, field

from layoutdsl.batch.jobs import Job

_LIVE: set[subprocess.Popen] = set()
"""Building processes now running from this process (to stop them on an interrupt)."""
_LIVE_LOCK = threading.Lock()

STDERR_TAIL = 400
"""Characters of a dead process's stderr kept in the reason (SCIP's abort message is there)."""


@dataclass(slots=True)
class Outcome:
    """What making one building gave: files (name -> bytes) and facts, or a reason."""

    building: str
    ok: bool
    reason: str | None = None
    seconds: float = 0.0
    facts: dict = field(default_factory=dict)
    """solve_status, objective, rooms, area_m2, difference (see manifest.RECORD_FIELDS)."""
    files: dict[str, bytes] = field(default_factory=dict)


def run_isolated(job: Job) -> Outcome:
    """Make `job`'s building in a child process; never raises for what happens in the child."""
    began = time.monotonic()
    if job.crash == "worker":
        os._exit(70)  # test-only: the engine's worker process dies with the task
    with tempfile.TemporaryDirectory(prefix="layoutdsl-batch-") as folder:
        result_path = os.path.join(folder, "outcome.pickle")
        env = dict(os.environ)
        # the child must import the same layoutdsl as this process, installed or not
        package_root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
        env["PYTHONPATH"] = os.pathsep.join(p for p in (package_root, env.get("PYTHONPATH")) if p)
        process = subprocess.Popen(
            [sys.executable, "-m", "layoutdsl.batch.building", result_path, str(os.getpid())],
            stdin=subprocess.PIPE, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
            env=env, start_new_session=True,
        )
        with _LIVE_LOCK:
            _LIVE.add(process)
        try:
            _, stderr = process.communicate(pickle.dumps(job), timeout=job.timeout)
        except subprocess.TimeoutExpired:
            _kill_group(process)
            process.communicate()
            return Outcome(job.building, False, f"timeout: killed after {job.timeout:g} s",
                           time.monotonic() - began)
        except BaseException:
            _kill_group(process)
            raise
        finally:
            with _LIVE_LOCK:
                _LIVE.discard(process)
        seconds = time.monotonic() - began
        if process.returncode != 0 or not os.path.exists(result_path):
            return Outcome(job.building, False, _death_reason(process.returncode, stderr), seconds)
        try:
            with open(result_path, "rb") as handle:
                outcome: Outcome = pickle.load(handle)  # written by our own child, just now
        except Exception as error:  # noqa: BLE001 - a bad result costs this building only
            return Outcome(job.building, False, f"unreadable result: {type(error).__name__}: {error}", seconds)
    outcome.seconds = seconds
    return outcome


def _die_with_parent(parent: int) -> None:
    """In the child: be killed when the process that started it dies (Linux), so a killed
    driver or worker leaves no building processes running on.

    Set here rather than in a Popen preexec_fn, which is unsafe with the pool's threads; the
    parent check after it closes the window in which the parent died first.
    """
    try:
        import ctypes

        PR_SET_PDEATHSIG = 1
        ctypes.CDLL(None, use_errno=True).prctl(PR_SET_PDEATHSIG, signal.SIGKILL)
    except (OSError, AttributeError):
        return
    if os.getppid() != parent:
        os._exit(1)


def stop_all() -> None:
    """Kill every building process this process started that still runs (on an interrupt)."""
    with _LIVE_LOCK:
        running = list(_LIVE)
    for process in running:
        _kill_group(process)


def _kill_group(process: subprocess.Popen) -> None:
    try:
        os.killpg(process.pid, signal.SIGKILL)
    except (ProcessLookupError, PermissionError):
        pass


def _death_reason(returncode: int, stderr: bytes) -> str:
    if returncode < 0:
        try:
            name = signal.Signals(-returncode).name
        except ValueError:
            name = f"signal {-returncode}"
        what = f"process killed by {name}"
        if -returncode == signal.SIGABRT:
            what += " (an abort inside the solver, e.g. SCIP's 'double free')"
    else:
        what = f"process exited with code {returncode}"
    tail = stderr.decode("utf-8", "replace").strip()[-STDERR_TAIL:]
    return f"{what}: {tail.splitlines()[-1]}" if tail else what


def difference_from_original(spec, layout) -> float | None:
    """How different the layout is from the plan it came from (0..1), when the spec knows it.

    Imported plans carry each room's original place as a hint; a spec without hints has no
    original to compare with.
    """
    from layoutdsl.layout.difference import difference, hint_centres, layout_centres

    original = hint_centres(spec)
    if not original:
        return None
    return round(difference(original, layout_centres(layout)), 6)


def make_building(job: Job) -> Outcome:
    """Import or lint, compile, verify and render one building (runs in the child)."""
    from layoutdsl.api import lint_source
    from layoutdsl.compile import compile_spec
    from layoutdsl.diagnostics import has_errors
    from layoutdsl.emit import render_outputs
    from layoutdsl.layout import Layout
    from layoutdsl.solve import SolveOptions
    from layoutdsl.diagnostics.source import Source
    from layoutdsl.layout.verify import drawn_boundary, verify

    if job.crash == "abort":
        os.abort()  # test-only: dies the way SCIP does on a double free
    if job.kind == "plan":
        from layoutdsl.importer import import_building

        spec, diagnostics = import_building(job.source, text=job.text, name=job.plan)
        stage = "import"
    else:
        spec, diagnostics = lint_source(Source(job.source, job.text))
        stage = "lint"
    if spec is None or has_errors(diagnostics):
        return Outcome(job.building, False, _first_error(stage, diagnostics))
    limits = asdict(job.limits)
    options = SolveOptions.from_settings(spec.settings, seed=job.seed, quiet=True, **limits)
    result = compile_spec(spec, options, explain_infeasible=False)
    if result.layout is None:
        return Outcome(job.building, False, _first_error(f"compile ({result.status})", result.diagnostics))
    layout_json = result.layout.to_json()
    # verify what is written, read back from its own bytes, not the object it came from
    layout = Layout.from_json(layout_json)
    violations = verify(drawn_boundary(spec, layout), layout)
    if violations:
        return Outcome(job.building, False, f"verify: {violations[0].rule}: {violations[0].message}")
    files = {f"{job.building}.layout.json": layout_json.encode("utf-8")}
    if job.kind == "sample":  # a sampled spec exists nowhere else (layoutdsl.batch.sampled)
        files[f"{job.building}.lay"] = job.text.encode("utf-8")
    files.update(render_outputs(layout, job.building, job.formats))
    info = layout.solve
    facts = {
        "solve_status": None if info is None else info.status,
        "objective": None if info is None else info.objective,
        "rooms": len(layout.rooms),
        "area_m2": round(sum(room.area for room in layout.rooms), 3),
        "difference": difference_from_original(spec, layout),
    }
    return Outcome(job.building, True, None, 0.0, facts, files)


def _first_error(stage: str, diagnostics) -> str:
    errors = [d for d in diagnostics if d.is_error] or list(diagnostics)
    if not errors:
        return f"{stage}: failed without a diagnostic"
    first = errors[0]
    more = f" (+{len(errors) - 1} more)" if len(errors) > 1 else ""
    return f"{stage}: {first.code} {first.message}{more}"


def main(argv: list[str]) -> int:
    """The child: job (pickle) on stdin -> Outcome (pickle) in the file named by argv[0];
    argv[1] is the parent's process id."""
    if len(argv) > 1:
        _die_with_parent(int(argv[1]))
    job: Job = pickle.loads(sys.stdin.buffer.read())
    try:
        outcome = make_building(job)
    except Exception as error:  # a bug or a solver error: this building's reason, not a crash
        outcome = Outcome(job.building, False, f"internal error: {type(error).__name__}: {error}")
    temp = argv[0] + ".tmp"
    with open(temp, "wb") as handle:
        pickle.dump(outcome, handle)
    os.replace(temp, argv[0])  # the parent reads a whole outcome or none
    return 0


if __name__ == "__main__":
    # run the imported module's main, so the pickled Outcome is layoutdsl.batch.building.Outcome
    # (not __main__.Outcome, which the parent could not load)
    from layoutdsl.batch.building import main as module_main

    sys.exit(module_main(sys.argv[1:]))

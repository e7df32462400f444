"""What a batch has to do: one `Job` per building, i.e. per (plan, variant index).

Inputs are specs (`.lay`), building XML plans (`.xml`), folders holding them (not recursive)
or list files (`.txt` / `.list`: one path per line, relative to the list's folder, `#`
comments). The driver reads every input once and ships its text inside the job, so workers on
other machines need no access to the input files.

A job's seed is a stable hash of (plan name, variant index, base seed): the same building gets
the same seed whichever worker runs it and in whatever order. Its `fingerprint` hashes
everything its output depends on; a finished record counts for a later run only while the
fingerprint is the same.
"""

from __future__ import annotations

import hashlib
import json
from dataclasses import asdict, dataclass, field
from pathlib import Path

from layoutdsl import __version__

SPEC_SUFFIX = ".lay"
PLAN_SUFFIX = ".xml"
LIST_SUFFIXES = (".txt", ".list")

SEED_RANGE = 2**31
"""Seeds stay below 2**31: SCIP's randomization/randomseedshift is a C int."""


class BatchInputError(ValueError):
    """An input that cannot be read or does not name specs or plans (a usage error)."""


@dataclass(frozen=True, slots=True)
class SolveLimits:
    """The compile settings a batch applies to every building (None: the spec's own)."""

    time_limit: float | None = None
    node_limit: int | None = None
    solution_limit: int | None = None
    gap: float | None = None
    emphasis: str | None = None
    strategy: str = "auto"
    search: bool = False
    """Keep improving after the first verified layout (neighbourhoods, branch-and-bound). Off by
    default: a building is then its first verified layout polished with its relations fixed, a
    stopping rule that does not depend on the clock, so any worker gives the same bytes, in a
    few seconds."""


@dataclass(frozen=True, slots=True)
class Job:
    """One building: a plan's variant, with everything a worker needs to make it."""

    building: str
    """`PLANNAME-vK`: the building's folder and file stem, unique in the batch."""
    plan: str
    source: str
    """The input file as the user named it (for the manifest)."""
    kind: str
    """'spec', 'plan' (building XML) or 'sample' (a spec the sampler drew: layoutdsl.batch.sampled)."""
    text: str
    source_sha256: str
    variant: int
    seed: int
    limits: SolveLimits
    formats: tuple[str, ...]
    timeout: float
    """Seconds after which the building's process is killed."""
    crash: str | None = field(default=None, compare=False)
    """Test-only fault injection ('abort' kills the building's process, 'worker' the engine's
    worker); set only through `run_batch`'s private test argument, never from user input."""

    @property
    def fingerprint(self) -> str:
        """Hash of everything the building's output depends on."""
        data = {
            "source_sha256": self.source_sha256, "kind": self.kind, "variant": self.variant,
            "seed": self.seed, "limits": asdict(self.limits), "formats": list(self.formats),
            "version": __version__,
        }
        return hashlib.sha256(json.dumps(data, sort_keys=True).encode()).hexdigest()[:16]


def derive_seed(plan: str, variant: int, base_seed: int) -> int:
    """A seed from (plan name, variant index, base seed) that no process or order changes.

    Python's hash() is salted per process; sha256 is the same everywhere.
    """
    digest = hashlib.sha256(f"{plan}\0{variant}\0{base_seed}".encode()).digest()
    return int.from_bytes(digest[:8], "big") % SEED_RANGE


def expand_inputs(inputs: list[str]) -> list[Path]:
    """The spec and plan files the inputs name, in the given order, each once."""
    found: list[Path] = []
    for text in inputs:
        found.extend(_expand(Path(text), via=None))
    unique: list[Path] = []
    seen: set[Path] = set()
    for path in found:
        key = path.resolve()
        if key not in seen:
            seen.add(key)
            unique.append(path)
    if not unique:
        raise BatchInputError("the inputs name no spec (.lay) or building plan (.xml)")
    return unique


def _expand(path: Path, via: Path | None) -> list[Path]:
    where = f" (listed in `{via}`)" if via is not None else ""
    if path.is_dir():
        return sorted(p for p in path.iterdir() if p.suffix.lower() in (SPEC_SUFFIX, PLAN_SUFFIX) and p.is_file())
    if not path.is_file():
        raise BatchInputError(f"`{path}`{where} does not exist or is not a file or folder")
    suffix = path.suffix.lower()
    if suffix in (SPEC_SUFFIX, PLAN_SUFFIX):
        return [path]
    if suffix in LIST_SUFFIXES and via is None:
        try:
            lines = path.read_text(encoding="utf-8").splitlines()
        except (OSError, UnicodeDecodeError) as error:
            raise BatchInputError(f"cannot read the list `{path}`: {error}") from None
        listed: list[Path] = []
        for line in lines:
            entry = line.split("#", 1)[0].strip()
            if entry:
                listed.extend(_expand(path.parent / entry, via=path))
        return listed
    raise BatchInputError(
        f"`{path}`{where}: expected a spec (.lay), a building plan (.xml), a folder or a list file "
        f"({', '.join(LIST_SUFFIXES)})"
    )


def plan_jobs(
    inputs: list[str],
    variants: int,
    *,
    base_seed: int = 0,
    limits: SolveLimits = SolveLimits(),
    formats: tuple[str, ...] = ("xml", "png", "world", "map"),
    timeout: float = 600.0,
) -> list[Job]:
    """One job per (input, variant 1..N), in input order; reads each input once."""
    files = expand_inputs(inputs)
    by_plan: dict[str, Path] = {}
    for path in files:
        if path.stem in by_plan:
            raise BatchInputError(
                f"`{by_plan[path.stem]}` and `{path}` have the same name `{path.stem}`: buildings are "
                "named after their plan, so rename one"
            )
        by_plan[path.stem] = path
    jobs: list[Job] = []
    for plan, path in by_plan.items():
        try:
            data = path.read_bytes()
            text = data.decode("utf-8")
        except (OSError, UnicodeDecodeError) as error:
            raise BatchInputError(f"cannot read `{path}`: {getattr(error, 'strerror', None) or error}") from None
        kind = "plan" if path.suffix.lower() == PLAN_SUFFIX else "spec"
        digest = hashlib.sha256(data).hexdigest()
        for variant in range(1, variants + 1):
            jobs.append(Job(
                building=f"{plan}-v{variant}", plan=plan, source=str(path), kind=kind, text=text,
                source_sha256=digest, variant=variant, seed=derive_seed(plan, variant, base_seed),
                limits=limits, formats=tuple(formats), timeout=timeout,
            ))
    return jobs

"""Batch inputs drawn by the sampler: `--sample school:1000` is 1,000 new buildings' specs.

The driver draws every sample's spec text up front (milliseconds each) and ships it inside
its job like a spec read from a file. Sample K of a run depends only on (model, kind,
--seed, K), so a re-run draws the same texts, the jobs get the same fingerprints, and done
buildings are skipped. The building's folder also gets the spec it was made from
(`NAME.lay`): it exists nowhere else.
"""

from __future__ import annotations

import hashlib
from pathlib import Path

from layoutdsl.batch.jobs import BatchInputError, Job, SolveLimits, derive_seed

SAMPLE_KIND = "sample"
"""Job.kind of a sampled spec."""

MAX_SAMPLES = 100_000
"""More than this in one --sample is almost surely a typo (and would take a while to draw)."""


def parse_sample(text: str) -> tuple[str, int]:
    """`school:1000` -> ("school", 1000); a bad value is a usage error."""
    kind, sep, count = text.partition(":")
    kind = kind.strip()
    if not sep or not kind or not count.strip().isdigit():
        raise BatchInputError(f"--sample {text}: expected KIND:N, e.g. school:100")
    number = int(count)
    if not 1 <= number <= MAX_SAMPLES:
        raise BatchInputError(f"--sample {text}: N must be 1-{MAX_SAMPLES}")
    return kind, number


def parse_rooms(text: str) -> tuple[int, int]:
    """`10-40` -> (10, 40), within the sampler's 10-150; a bad value is a usage error."""
    from layoutdsl.sample import MAX_ROOMS, MIN_ROOMS

    low, sep, high = text.partition("-")
    if not sep or not low.strip().isdigit() or not high.strip().isdigit():
        raise BatchInputError(f"--sample-rooms {text}: expected MIN-MAX, e.g. 10-40")
    rooms = (int(low), int(high))
    if not MIN_ROOMS <= rooms[0] <= rooms[1] <= MAX_ROOMS:
        raise BatchInputError(f"--sample-rooms {text}: a range within {MIN_ROOMS}-{MAX_ROOMS}")
    return rooms


def sample_jobs(
    samples: list[tuple[str, int]],
    variants: int,
    *,
    base_seed: int = 0,
    model: str | Path | None = None,
    limits: SolveLimits = SolveLimits(),
    formats: tuple[str, ...] = ("xml", "png", "world", "map"),
    timeout: float = 600.0,
    rooms: tuple[int, int] | None = None,
) -> list[Job]:
    """One job per (sample, variant 1..N), samples in order; `model` is a grammar saved by
    `layoutdsl sample --save-model` (None: the shipped one); `rooms` narrows the samples' room
    count (None: the sampler's 10-150)."""
    from layoutdsl.sample import ModelError, SampleError, SpecSampler, load_grammar
    from layoutdsl.sizes import ModelError as SizesError

    try:
        grammar = load_grammar(model)
    except ModelError as error:
        raise BatchInputError(str(error)) from None
    jobs: list[Job] = []
    for kind, count in samples:
        if kind not in (*grammar.kinds, "any"):
            raise BatchInputError(f"--sample {kind}:{count}: the sampler model knows the kinds "
                                  f"{', '.join((*grammar.kinds, 'any'))}")
        try:
            sampler = SpecSampler(grammar, kind, seed=base_seed, rooms=rooms)
        except (SampleError, SizesError) as error:
            raise BatchInputError(f"--sample {kind}:{count}: {error}") from None
        for index in range(1, count + 1):
            try:
                sample = sampler.sample(index)
            except SampleError as error:
                raise BatchInputError(f"--sample {kind}: sample {index}: {error}") from None
            digest = hashlib.sha256(sample.text.encode("utf-8")).hexdigest()
            for variant in range(1, variants + 1):
                jobs.append(Job(
                    building=f"{sample.name}-v{variant}", plan=sample.name,
                    source=f"sample:{kind}:{index} (seed {base_seed}, model {grammar.digest})",
                    kind=SAMPLE_KIND, text=sample.text, source_sha256=digest, variant=variant,
                    seed=derive_seed(sample.name, variant, base_seed), limits=limits,
                    formats=tuple(formats), timeout=timeout,
                ))  # fmt: skip
    return jobs

"""`layoutdsl batch INPUT... -o OUTDIR --variants N`: many verified buildings, resumably.

Each building (a plan's variant) gets OUTDIR/NAME-vK/ with its usual files; OUTDIR/manifest.jsonl
lists every building once. Re-running the same command skips what is done and intact and
redoes missing or failed buildings. The progress bar goes to stderr (only on a terminal, not
with -q); the summary goes to stdout (not with -q; with --format json a result object instead).
"""

from __future__ import annotations

import argparse
import sys

from layoutdsl.cli.argtypes import non_negative_float, non_negative_int, positive_float, positive_int
from layoutdsl.cli.compile import EMPHASES, STRATEGIES
from layoutdsl.cli.output import Output, add_command, add_output_arguments
from layoutdsl.diagnostics import exitcodes

BATCH_NODE_LIMIT = 20
"""Default branch-and-bound node limit: a deterministic stopping rule where SCIP runs at all
(with --search, or for a spec the construction finds no start for). By default a building is
its first verified layout, polished: no search, nothing that stops on the clock."""

BATCH_TIME_LIMIT = 60.0
"""Default time limit per building, as for compile: a building without a verified layout by
then is recorded as failed (E902). With --search, a building that reaches it is still
written, but its solve_status says `time_limit` (timing-dependent)."""

MAX_FAILURES_SHOWN = 10


def add_parser(subparsers) -> None:
    """Register the `batch` subcommand."""
    parser = add_command(
        subparsers, "batch",
        help="make many verified buildings from specs and plans, resumably",
        description=(
            "Make N variants of every input (specs .lay, building XML plans .xml, folders of "
            "them, or list files .txt/.list with one path per line). Each building is compiled "
            "in its own process, verified, and written to OUTDIR/NAME-vK/ (the names compile "
            "--variants gives its files); OUTDIR/manifest.jsonl has one JSON record per building "
            "(load it with pandas.read_json(path, lines=True)).\n\n"
            "Run the same command again to finish an interrupted or partly failed batch: done "
            "buildings whose files are intact are skipped. Seeds come from (plan name, variant, "
            "--seed), so a building's bytes do not depend on where or when it ran.\n\n"
            "--sample school:1000 adds 1,000 new buildings whose room graphs and sizes the sampler "
            "draws (layoutdsl sample); --seed also seeds the sampler, so a re-run draws the same specs."
        ),
        examples=[
            ("three variants of every spec and plan under a folder", "layoutdsl batch examples/floorplans -o dataset --variants 3"),
            ("100 new school buildings drawn by the sampler", "layoutdsl batch --sample school:100 -o dataset"),
            ("finish an interrupted batch: the same command again", "layoutdsl batch examples/floorplans -o dataset --variants 3"),
            ("the counts and the manifest's path as JSON", "layoutdsl batch specs -o dataset --format json -q"),
        ],
    )  # fmt: skip
    parser.add_argument("inputs", nargs="*", metavar="INPUT", help="spec, plan, folder or list file")
    parser.add_argument("--sample", action="append", default=[], metavar="KIND:N",
                        help="also make N new buildings of a kind drawn by the sampler (e.g. school:1000; "
                        "see `layoutdsl sample`); each building's folder gets its spec; repeatable")
    parser.add_argument("--sample-rooms", metavar="MIN-MAX",
                        help="only sampled buildings with this many rooms (within the default 10-150), e.g. 10-40")
    parser.add_argument("--sample-model", metavar="FILE",
                        help="the sampler's grammar, saved by `layoutdsl sample --save-model` (default: the shipped one)")
    parser.add_argument("-o", "--output", required=True, metavar="OUTDIR", help="the dataset's folder")
    parser.add_argument("--variants", type=positive_int, default=1, metavar="N",
                        help="buildings per input (default 1)")
    parser.add_argument("--seed", type=non_negative_int, default=0, metavar="N",
                        help="base seed; each building's seed is derived from it (default 0)")
    parser.add_argument("--engine", choices=("pool", "dask"), default="pool",
                        help="pool: processes on this machine (default); dask: a Dask cluster, "
                        "the one at --address or a local one (needs layoutdsl[cluster])")
    parser.add_argument("--address", metavar="HOST:PORT",
                        help="the Dask scheduler to use (with --engine dask)")
    parser.add_argument("--workers", type=positive_int, metavar="N",
                        help="buildings at once on this machine (default: every core); with "
                        "--engine dask and no --address, the local cluster's worker count")
    parser.add_argument("--node-limit", type=positive_int, default=BATCH_NODE_LIMIT, metavar="N",
                        help=f"branch-and-bound nodes per building (default {BATCH_NODE_LIMIT}, deterministic)")
    parser.add_argument("--solution-limit", type=positive_int, metavar="N",
                        help="stop after N improving solutions (deterministic)")
    parser.add_argument("--time-limit", type=positive_float, default=BATCH_TIME_LIMIT, metavar="S",
                        help=f"seconds per building's solve (default {BATCH_TIME_LIMIT:g}; a safety net: "
                        "a solve stopped by it may differ from run to run)")
    parser.add_argument("--gap", type=non_negative_float, metavar="G", help="stop at this relative gap")
    parser.add_argument("--emphasis", choices=EMPHASES, help="SCIP emphasis")
    parser.add_argument("--strategy", choices=STRATEGIES, default="auto", help="as for compile")
    parser.add_argument("--search", action="store_true",
                        help="keep improving each building after its first verified layout (slower; the "
                             "neighbourhood search stops on the clock, so outputs may then differ by worker)")
    parser.add_argument("--timeout", type=positive_float, metavar="S",
                        help="kill a building's process after S seconds (default: 2 x time limit + 60)")
    parser.add_argument("--emit", default="xml,png,world,map", metavar="FORMATS",
                        help="comma-separated output formats, as for compile (default xml,png,world,map)")
    add_output_arguments(parser)
    parser.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    """Run a batch; 0 when every building is done, 3 when some failed, 2 on usage/I/O errors."""
    out = Output("batch", args)
    fields: dict = {}  # what the JSON result says about the batch, once it ran
    code = _run(args, out, fields)
    return out.finish(code, **fields)


def _run(args: argparse.Namespace, out: Output, fields: dict) -> int:
    from pathlib import Path

    from layoutdsl.batch import (
        BatchBusy, BatchInputError, EngineUnavailable, SolveLimits, default_workers, plan_jobs, run_batch,
    )
    from layoutdsl.emit import EmitError, parse_formats

    if args.address and args.engine != "dask":
        return out.error("--address needs --engine dask")
    if args.engine == "dask":
        from layoutdsl.batch.executors import CLUSTER_EXTRA_HINT

        try:
            import distributed  # noqa: F401
        except ImportError:
            return out.error(f"--engine dask needs the `distributed` package: {CLUSTER_EXTRA_HINT}")
    try:
        formats = parse_formats(args.emit)
    except EmitError as error:
        return out.error(str(error))
    outdir = Path(args.output)
    if outdir.exists() and not outdir.is_dir():
        return out.error(f"`{outdir}` exists and is not a directory")
    limits = SolveLimits(time_limit=args.time_limit, node_limit=args.node_limit, solution_limit=args.solution_limit,
                         gap=args.gap, emphasis=args.emphasis, strategy=args.strategy, search=args.search)
    timeout = args.timeout or 2 * args.time_limit + 60
    if not args.inputs and not args.sample:
        return out.error("give specs, plans, folders or list files, or --sample KIND:N")
    for path in args.inputs:  # the one I/O error style of every command
        if not Path(path).exists():
            return out.cannot_read(path, FileNotFoundError(2, "No such file or directory"))
    try:
        jobs = plan_jobs(args.inputs, args.variants, base_seed=args.seed, limits=limits,
                         formats=formats, timeout=timeout) if args.inputs else []
        if args.sample:
            from layoutdsl.batch.sampled import parse_rooms, parse_sample, sample_jobs

            rooms = parse_rooms(args.sample_rooms) if args.sample_rooms else None
            jobs += sample_jobs([parse_sample(text) for text in args.sample], args.variants,
                                base_seed=args.seed, model=args.sample_model, limits=limits,
                                formats=formats, timeout=timeout, rooms=rooms)
        names = [job.building for job in jobs]
        if len(set(names)) != len(names):
            clash = next(name for name in names if names.count(name) > 1)
            raise BatchInputError(f"two buildings would be named `{clash}`: rename the input or drop the repeated --sample")
    except BatchInputError as error:
        return out.error(str(error))
    workers = args.workers or default_workers()
    show = not out.quiet and sys.stderr.isatty()
    out.detail(f"{len(jobs)} buildings, {workers} at once")
    display = _Progress(len(jobs)) if show else None
    try:
        summary = run_batch(jobs, outdir, engine=args.engine, workers=workers, address=args.address,
                            progress=display, running=display.running if display else None)
    except (BatchBusy, EngineUnavailable) as error:
        return out.error(str(error))
    except OSError as error:
        return out.cannot_write(getattr(error, "filename", None) or outdir, error)
    finally:
        if display:
            display.close()
    where = f"dask at {args.address}" if args.address else (
        f"local dask cluster, {workers} workers" if args.engine == "dask" else f"{workers} processes")
    rate = summary.done / (summary.seconds / 60) if summary.seconds > 0 else 0.0
    lines = [
        f"batch `{outdir}`: {summary.total} buildings: {summary.skipped} already done, "
        f"{summary.done} made, {summary.failed} failed ({where})",
        f"  time        {summary.seconds:.1f} s, {rate:.1f} buildings/min",
        f"  manifest    {summary.manifest}",
    ]
    from layoutdsl.compile.variants import MIN_PAIRWISE  # near_copies' threshold (loaded by it already)

    for plan, near in summary.close.items():
        shown = ", ".join(building for building, _ in near[:MAX_FAILURES_SHOWN])
        more = f" and {len(near) - MAX_FAILURES_SHOWN} more" if len(near) > MAX_FAILURES_SHOWN else ""
        lines.append(f"  close       {plan}: {len(near)} buildings within {MIN_PAIRWISE:g} of an earlier "
                     f"variant ({shown}{more}); W906 says why")
    for building, reason in summary.failures[:MAX_FAILURES_SHOWN]:
        lines.append(f"  failed      {building}: {reason}")
    if len(summary.failures) > MAX_FAILURES_SHOWN:
        lines.append(f"  ...         {len(summary.failures) - MAX_FAILURES_SHOWN} more failures in the manifest")
    if summary.failed:
        lines.append("  run the same command again to retry the failed buildings")
    out.summary("\n".join(lines))
    out.wrote(summary.manifest)
    fields.update({
        "output": str(outdir), "manifest": str(summary.manifest), "total": summary.total,
        "skipped": summary.skipped, "made": summary.done, "failed": summary.failed,
        "failures": [{"building": building, "reason": reason} for building, reason in summary.failures],
        "seconds": round(summary.seconds, 3),
    })
    return exitcodes.NO_LAYOUT if summary.failed else exitcodes.OK


class _Progress:
    """A tqdm bar: done / failed / running, rate and ETA, over the buildings left to make."""

    def __init__(self, total: int) -> None:
        from layoutdsl.batch.executors import Running

        self.total = total
        self.running = Running()
        self.bar = None
        self.failed = 0

    def __call__(self, event: str, payload) -> None:
        from tqdm import tqdm

        if event == "start":
            # the bar counts this run's buildings, so rate and ETA are this run's
            self.bar = tqdm(total=payload, unit="bldg", file=sys.stderr, dynamic_ncols=True,
                            desc="batch", smoothing=0.1)
        elif event == "finished" and self.bar is not None:
            outcome = payload
            if not outcome.ok:
                self.failed += 1
            self.bar.update(1)
            self.bar.set_postfix(failed=self.failed, running=self.running.count, refresh=True)

    def close(self) -> None:
        if self.bar is not None:
            self.bar.close()

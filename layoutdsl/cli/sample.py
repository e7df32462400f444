"""`layoutdsl sample --like school -n 100 -o DIR`: specs of new buildings learned from real plans.

Each sample is a new room graph (connected, planar, a corridor backbone with rooms and
entrances, isomorphic to no training plan) drawn from a graph grammar fitted on real plans,
with room sizes and a boundary from the size model (layoutdsl.sample, docs/sampling.md).
DIR gets `LIKE-0001.lay`, ... and `samples.jsonl` (one record per sample). A spec whose
file already holds the same bytes is not rewritten.
"""

from __future__ import annotations

import argparse
import json
from pathlib import Path

from layoutdsl.cli.argtypes import non_negative_int, positive_int
from layoutdsl.cli.output import Output, add_command, add_output_arguments
from layoutdsl.diagnostics import exitcodes

RECORDS_NAME = "samples.jsonl"

PROGRESS_EVERY = 100
"""A progress line (stderr) after this many samples: a thousand take half a minute."""


def add_parser(subparsers) -> argparse.ArgumentParser:
    """Register the `sample` subcommand."""
    parser = add_command(
        subparsers, "sample",
        help="write specs of new buildings learned from real plans",
        description=(
            "Write N specs of new buildings: room graphs drawn from a graph grammar fitted on "
            "real plans (corridor backbones with their rooms, entrances and cycles), each "
            "connected, planar and different from every training plan, with room sizes and a "
            "boundary from the size model. Every spec is ready for `layoutdsl compile`. The "
            "model fitted on the 24 real plans of the development corpus ships with layoutdsl; "
            "--train fits one on another folder of building XML plans (and --save-model keeps "
            "it). The same --seed gives the same specs on any machine, and sample K does not "
            "depend on N. `layoutdsl batch --sample KIND:N` samples and compiles in one go."
        ),
        examples=[
            ("ten school specs into out/", "layoutdsl sample --like school -n 10 -o out/ --seed 1"),
            ("office specs from a model fitted on your own plans",
             "layoutdsl sample --like office -n 5 -o out/ --train my_plans/"),
            ("refit the shipped model (what layoutdsl ships was made so)",
             "layoutdsl sample --train ../shared/floorplans --save-model layoutdsl/sample/data/grammar.json"),
        ],
    )  # fmt: skip
    parser.add_argument("--like", default="school", metavar="KIND",
                        help="building kind to sample: school, office (the kinds the model has) or any "
                        "(every training plan a template; default school)")
    parser.add_argument("-n", "--count", type=non_negative_int, metavar="N", help="how many specs to write")
    parser.add_argument("-o", "--output", metavar="DIR", help="folder for the specs (created if needed)")
    parser.add_argument("--seed", type=non_negative_int, default=0, metavar="S", help="random seed (default 0)")
    parser.add_argument("--start", type=positive_int, default=1, metavar="K",
                        help="number of the first sample (default 1): --start 11 -n 10 writes samples 11-20")
    source = parser.add_mutually_exclusive_group()
    source.add_argument("--train", metavar="DIR",
                        help="fit the grammar and the size model on the building XML plans in DIR "
                        "instead of using the shipped ones")
    source.add_argument("--model", metavar="FILE", help="a grammar saved with --save-model")
    parser.add_argument("--sizes", metavar="FILE",
                        help="a size model file (default: the shipped one, or one fitted on --train)")
    parser.add_argument("--save-model", metavar="FILE", help="write the grammar fitted with --train to FILE")
    parser.add_argument("--rooms", type=room_range, metavar="MIN-MAX",
                        help="only samples with this many rooms (within 10-150, the default); e.g. 10-40")
    parser.add_argument("--typical-sizes", action="store_true",
                        help="give each room its label's typical sizes instead of sizes drawn from the model's "
                        "laws (less varied buildings, no outliers such as a corridor three times its usual length)")
    add_output_arguments(parser, diagnostics=True)
    parser.set_defaults(run=run)
    return parser


def room_range(text: str) -> tuple[int, int]:
    """`10-40` -> (10, 40), within the sampler's 10-150 (a usage error otherwise)."""
    from layoutdsl.sample import MAX_ROOMS, MIN_ROOMS

    low, sep, high = text.partition("-")
    if not sep or not low.strip().isdigit() or not high.strip().isdigit():
        raise argparse.ArgumentTypeError(f"expected MIN-MAX rooms, e.g. 10-40, got {text!r}")
    rooms = (int(low), int(high))
    if not MIN_ROOMS <= rooms[0] <= rooms[1] <= MAX_ROOMS:
        raise argparse.ArgumentTypeError(f"rooms {text}: a range within {MIN_ROOMS}-{MAX_ROOMS}")
    return rooms


def run(args: argparse.Namespace) -> int:
    out = Output("sample", args)
    if args.count is None and not args.save_model:
        return out.finish(out.error("give -n N and -o DIR to write specs, or --train DIR --save-model FILE"))
    if args.count and not args.output:
        return out.finish(out.error("-n needs -o DIR: the folder the specs go to"))
    if args.save_model and not args.train:
        return out.finish(out.error("--save-model needs --train DIR: the plans to fit on"))
    with out.timed("fit"):
        loaded = _grammar_and_sizes(args, out)
    if isinstance(loaded, int):
        return out.finish(loaded)
    grammar, sizes = loaded
    if args.save_model:
        from layoutdsl.emit.atomic import write_text_atomic

        try:
            write_text_atomic(args.save_model, grammar.to_json())
        except OSError as error:
            return out.finish(out.cannot_write(args.save_model, error))
        out.wrote(args.save_model)
    count = args.count or 0
    if not count:
        out.summary(f"fitted the sampler on {len(grammar.plans)} plans; wrote {args.save_model}")
        return out.finish(exitcodes.OK, model=grammar.digest, plans=[p.name for p in grammar.plans], samples=[])
    return _write_samples(args, out, grammar, sizes, count)


def _grammar_and_sizes(args, out: Output):
    """(grammar, size model) from --train / --model / the shipped files, or an exit code."""
    from layoutdsl.sample import CorpusError, ModelError, fit_grammar, load_grammar
    from layoutdsl.sample.corpus import plan_files, read_plan_graph
    from layoutdsl.sizes import ModelError as SizesError
    from layoutdsl.sizes import load_model

    sizes = None
    if args.sizes:
        out.reading(args.sizes)
        try:
            sizes = load_model(args.sizes)
        except (SizesError, OSError, ValueError) as error:
            return out.error(f"cannot use the size model `{args.sizes}`: {error}", kind="io", path=args.sizes)
    if args.train:
        try:
            files = plan_files(args.train)
        except CorpusError as error:
            return out.error(str(error), kind="io", path=args.train)
        plans = []
        failed = False
        for path in files:
            out.reading(str(path))
            plan, diagnostics = read_plan_graph(path)
            out.diagnostics([d for d in diagnostics if d.is_error])
            if plan is None:
                failed = True
            else:
                plans.append(plan)
        if failed:
            out.error(f"a plan in `{args.train}` has errors: fix or remove it, then fit again", kind="input")
            return exitcodes.SPEC_ERRORS
        grammar = fit_grammar(plans, source=f"{Path(args.train).name}: {len(plans)} real plans")
        if sizes is None:
            from layoutdsl.sizes.fit import fit_model

            sizes = fit_model(files, corpus=Path(args.train).name)
    else:
        if args.model:
            out.reading(args.model)
        try:
            grammar = load_grammar(args.model)
        except ModelError as error:
            return out.error(str(error), kind="io", path=args.model)
    if sizes is None:
        sizes = load_model()
    kinds = (*grammar.kinds, "any")
    if args.like not in kinds:
        return out.error(f"--like {args.like}: the model knows the kinds {', '.join(kinds)}")
    return grammar, sizes


def _write_samples(args, out: Output, grammar, sizes, count: int) -> int:
    from layoutdsl.emit.atomic import write_text_atomic
    from layoutdsl.sample import SampleError, SpecSampler
    from layoutdsl.sizes import ModelError as SizesError

    outdir = Path(args.output)
    if outdir.exists() and not outdir.is_dir():
        return out.finish(out.error(f"`{outdir}` exists and is not a folder", kind="io", path=str(outdir)))
    try:
        sampler = SpecSampler(grammar, args.like, sizes, seed=args.seed, drawn_sizes=not args.typical_sizes,
                              rooms=args.rooms)
    except (SampleError, SizesError) as error:
        return out.finish(out.error(str(error)))
    records = []
    unchanged = 0
    with out.timed("sample"):
        for index in range(args.start, args.start + count):
            try:
                sample = sampler.sample(index)
            except SampleError as error:
                return out.finish(out.error(f"sample {index}: {error}", code=exitcodes.USAGE))
            path = outdir / f"{sample.name}.lay"
            try:
                if _same_text(path, sample.text):
                    unchanged += 1
                else:
                    outdir.mkdir(parents=True, exist_ok=True)
                    write_text_atomic(path, sample.text)
                    out.wrote(path)
            except OSError as error:
                return out.finish(out.cannot_write(path, error))
            records.append({**sample.record(), "file": path.name, "seed": args.seed, "model": grammar.digest})
            if len(records) % PROGRESS_EVERY == 0 and len(records) < count:
                out.progress(f"  {len(records)} of {count} specs")
            if out.verbose:
                out.detail(f"  {sample.name}: {records[-1]['rooms']} rooms, {records[-1]['corridors']} corridor-like, "
                           f"{records[-1]['entrances']} entrances, cycle rank {records[-1]['cycle_rank']}")
    records_path = outdir / RECORDS_NAME
    try:
        previous = _read_records(records_path)
        previous.update({record["name"]: record for record in records})
        text = "".join(json.dumps(r) + "\n" for r in sorted(previous.values(), key=lambda r: (r["name"])))
        if not _same_text(records_path, text):
            write_text_atomic(records_path, text)
            out.wrote(records_path)
    except OSError as error:
        return out.finish(out.cannot_write(records_path, error))
    rooms = sorted(r["rooms"] for r in records)
    out.summary(
        f"wrote {count - unchanged} specs to `{outdir}` ({unchanged} already there), like {args.like}, "
        f"seed {args.seed}: {rooms[0]}-{rooms[-1]} rooms, median {rooms[len(rooms) // 2]}\n"
        f"  compile one:  layoutdsl compile {outdir / records[0]['file']} -o OUT/"
    )
    return out.finish(exitcodes.OK, model=grammar.digest, samples=records)


def _same_text(path: Path, text: str) -> bool:
    try:
        return path.read_text(encoding="utf-8") == text
    except (OSError, UnicodeDecodeError):
        return False


def _read_records(path: Path) -> dict[str, dict]:
    """Earlier runs' records by sample name (a re-run with --start adds to them)."""
    found: dict[str, dict] = {}
    try:
        lines = path.read_text(encoding="utf-8").splitlines()
    except (OSError, UnicodeDecodeError):
        return found
    for line in lines:
        try:
            record = json.loads(line)
        except json.JSONDecodeError:
            continue
        if isinstance(record, dict) and isinstance(record.get("name"), str):
            found[record["name"]] = record
    return found

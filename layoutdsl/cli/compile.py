"""`layoutdsl compile SPEC.lay -o OUTDIR`: lint, solve, verify, write the layout's files.

Flags override the spec's settings. Diagnostics go to stderr, progress too (unless -q); the
one-screen summary goes to stdout. Outputs (`NAME.layout.json` plus the emitters' files) are
written all-or-nothing, and only for a verified layout.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from layoutdsl.cli.argtypes import non_negative_float, non_negative_int, positive_float, positive_int
from layoutdsl.cli.output import Output, add_command, add_output_arguments
from layoutdsl.diagnostics import exitcodes
from layoutdsl.syntax.ast import EMPHASES

from layoutdsl.compile.strategies import STRATEGIES  # the table; light, so `--help` need not import Pyomo


def add_parser(subparsers) -> None:
    """Register the `compile` subcommand."""
    parser = add_command(
        subparsers, "compile",
        help="solve a spec into a verified layout and write its files",
        description=(
            "Compile a layout spec: lint it, solve the thesis' MIQP (§5.5.1) with SCIP, "
            "verify the result independently and write OUTDIR/NAME.layout.json plus the "
            "chosen output formats (OUTDIR is created if needed). Flags override the spec's "
            "settings.\n\nThe same spec and seed give the same layout whenever the solve stops "
            "at its gap, node limit or solution limit; a run that stops at the wall-clock time "
            "limit may differ from run to run (the summary says which rule stopped it)."
        ),
        examples=[
            ("compile a spec into out/", "layoutdsl compile specs/office_small.lay -o out"),
            ("a deterministic run: stop after 50 branch-and-bound nodes", "layoutdsl compile specs/office_small.lay -o out --seed 3 --node-limit 50"),
            ("three different layouts, out/NAME-v1.* ... out/NAME-v3.*", "layoutdsl compile specs/office_small.lay -o out --variants 3"),
            ("the result (files written, status, timings) as JSON", "layoutdsl compile specs/office_small.lay -o out --format json -q"),
        ],
    )  # fmt: skip
    parser.add_argument("spec", help="spec file (.lay), or - for standard input")
    parser.add_argument("-o", "--output", required=True, metavar="OUTDIR", help="directory for the outputs")
    parser.add_argument("--time-limit", type=positive_float, metavar="S",
                        help="wall-clock seconds for the whole solve (setting time_limit)")
    parser.add_argument("--gap", type=non_negative_float, metavar="G",
                        help="stop at this relative optimality gap, e.g. 0.01 (setting gap)")
    parser.add_argument("--seed", type=non_negative_int, metavar="N", help="random seed (setting seed)")
    parser.add_argument("--emphasis", choices=EMPHASES,
                        help="SCIP emphasis (setting emphasis; default: default)")
    parser.add_argument("--node-limit", type=positive_int, metavar="N",
                        help="stop after N branch-and-bound nodes: a deterministic stopping rule")
    parser.add_argument("--solution-limit", type=positive_int, metavar="N",
                        help="stop after N improving solutions: a deterministic stopping rule")
    parser.add_argument("--emit", default="xml,png,world,map", metavar="FORMATS",
                        help="comma-separated output formats: xml, png, world, map (the default "
                        "set), svg (the drawing as vectors), and the 3D worlds mjcf (MuJoCo), sdf (Gazebo), gltf (mesh; needs "
                        "pip install 'layoutdsl[sim]')")
    parser.add_argument("--robot-room", metavar="ID", help="room the simulated robot starts in")
    parser.add_argument("--wall-height", type=positive_float, default=2.5, metavar="M",
                        help="wall height of the 3D worlds in metres (default 2.5)")
    parser.add_argument("--no-robot", dest="robot", action="store_false",
                        help="leave the wheeled robot and its rangefinders out of the MuJoCo scene")
    parser.add_argument("--variants", type=positive_int, metavar="N",
                        help="write N different verified layouts, NAME-v1.* ... NAME-vN.*: new "
                        "arrangements generated from the room graph, seeds seed, seed+1, ... "
                        "tried in turn, each stopping at its first verified layout, polished; "
                        "one within 0.3 of a variant kept is skipped")
    parser.add_argument("--variants-from", choices=("graph", "hints"), default="graph",
                        help="graph (default): variants ignore the spec's hints; hints: "
                        "variants perturb the hints (they stay close to the original plan)")
    parser.add_argument("--workers", type=positive_int, metavar="N",
                        help="variants compiled in parallel (default: one per core)")
    parser.add_argument("--strategy", choices=STRATEGIES, default="auto",
                        help="auto: the generator's first layout, then SCIP; thesis: the thesis' "
                        "formulation solved by SCIP from scratch")
    parser.add_argument("--grow-boundary", dest="grow_boundary", action="store_true", default=None,
                        help="let the generator grow a boundary too tight for the arrangement it "
                        "finds; the growth is reported")
    parser.add_argument("--no-explain", dest="explain", action="store_false",
                        help="when the spec is infeasible, say so without searching for the "
                        "conflicting lines (faster on large specs)")
    parser.add_argument("--stdin-filename", metavar="NAME", help="the name messages use for standard input")
    add_output_arguments(parser, diagnostics=True)
    parser.set_defaults(run=run)


def run(args: argparse.Namespace) -> int:
    """Compile one spec; exit 0 with a layout, 1 spec errors, 2 usage/I/O, 3 no layout."""
    from layoutdsl.api import lint_source, read_source
    from layoutdsl.diagnostics import has_errors
    from layoutdsl.diagnostics.filekind import wrong_kind_for_spec
    from layoutdsl.diagnostics.source import Source

    out = Output("compile", args)
    out.reading(args.spec)
    try:
        if args.spec == "-":
            stream = getattr(sys.stdin, "buffer", sys.stdin)  # bytes, so bad UTF-8 is an I/O error
            data = stream.read()
            text = data.decode("utf-8") if isinstance(data, bytes) else data
            source = Source(args.stdin_filename or "<stdin>", text)
        else:
            source = read_source(args.spec)
    except (OSError, UnicodeDecodeError) as error:
        return out.finish(out.cannot_read(args.spec, error))
    sources = {source.path: source}
    wrong = wrong_kind_for_spec(source.path, source.text)
    if wrong is not None:  # `compile plan.xml`: say to import it, not a page of syntax errors
        out.diagnostics([wrong], sources)
        return out.finish(exitcodes.SPEC_ERRORS)
    with out.timed("lint"):
        spec, diagnostics = lint_source(source)
    out.diagnostics(diagnostics, sources)
    if spec is None or has_errors(diagnostics):
        return out.finish(exitcodes.SPEC_ERRORS)

    formats = _formats(args.emit)
    if isinstance(formats, str):
        return out.finish(out.error(formats))
    from layoutdsl.emit import MAX_WALL_HEIGHT

    if args.wall_height > MAX_WALL_HEIGHT:
        return out.finish(out.error(f"--wall-height {args.wall_height:g} is taller than {MAX_WALL_HEIGHT:g} m"))
    if args.robot_room is not None and spec.room(args.robot_room) is None:
        from layoutdsl.diagnostics.suggest import suggest

        guess = suggest(args.robot_room, spec.room_ids)
        hint = f"did you mean `{guess}`?" if guess else "rooms: " + ", ".join(spec.room_ids[:10])
        return out.finish(out.error(f"--robot-room `{args.robot_room}` is not a room of the spec ({hint})"))
    outdir = Path(args.output)
    if outdir.exists() and not outdir.is_dir():
        return out.finish(out.error(f"`{outdir}` exists and is not a directory", kind="io", path=str(outdir)))

    from layoutdsl.solve import SolveOptions

    options = SolveOptions.from_settings(
        spec.settings,
        time_limit=args.time_limit,
        gap=args.gap,
        seed=args.seed,
        emphasis=args.emphasis,
        node_limit=args.node_limit,
        solution_limit=args.solution_limit,
        quiet=out.quiet,  # the solver's progress lines on stderr are progress: not with -q
        strategy=args.strategy,
        grow_boundary=getattr(args, "grow_boundary", None),
    )
    if args.variants:
        return _run_variants(spec, args, options, outdir, formats, sources, out)

    from layoutdsl.compile import compile_spec

    out.progress(f"compiling `{spec.name}`: {len(spec.rooms)} rooms, time limit {options.time_limit:g} s")
    with out.timed("solve"):
        result = compile_spec(spec, options, explain_infeasible=args.explain)
    out.diagnostics(result.diagnostics, sources)
    if result.layout is None:
        return out.finish(exitcodes.NO_LAYOUT, spec=spec.name)
    try:
        with out.timed("write"):
            written = write_layout_files(result.layout, outdir, spec.name, formats, robot_room=args.robot_room,
                                         wall_height=args.wall_height, robot=args.robot)
    except OSError as error:
        return out.finish(out.cannot_write(getattr(error, "filename", None) or outdir, error))
    except ValueError as error:  # the emitters refuse an option (EmitError)
        return out.finish(out.error(str(error)))
    out.wrote(*written)
    out.summary(summary(spec, result.layout, written))
    return out.finish(exitcodes.OK, spec=spec.name, layout=layout_fields(spec, result.layout))


def layout_fields(spec, layout) -> dict:
    """What the JSON result says about a layout: the summary's numbers, for scripts."""
    info = layout.solve
    deviations = size_deviations(spec, layout)
    fields = {
        "rooms": len(layout.rooms),
        "portals": len(layout.portals),
        "room_area_m2": round(sum(r.area for r in layout.rooms), 3),
        "boundary_area_m2": round(layout.width * layout.height, 3),
        "max_size_error": round(max(deviations.values()), 4) if deviations else None,
    }
    if info is not None:
        fields.update({
            "solve_status": info.status,
            "objective": info.objective,
            "gap": info.gap,
            "solve_seconds": round(info.seconds, 3),
            "method": info.method,
            "seed": info.seed,
        })
    return fields


def _formats(text: str) -> tuple[str, ...] | str:
    """The chosen formats, or an error message."""
    from layoutdsl.emit import parse_formats

    try:
        return parse_formats(text)
    except ValueError as error:
        return str(error)


def write_layout_files(layout, outdir: Path, stem: str, formats, *, robot_room: str | None = None,
                       **world_options) -> list[Path]:
    """NAME.layout.json plus the emitters' files for `formats`, all or nothing."""
    files: dict[str, bytes] = {f"{stem}.layout.json": layout.to_json().encode("utf-8")}
    from layoutdsl.emit import render_outputs, write_rendered

    if formats:
        files.update(render_outputs(layout, stem, formats, robot_room=robot_room, **world_options))
    return write_rendered(files, outdir)


def size_deviations(spec, layout) -> dict[str, float]:
    """Per room: the larger relative deviation of its two sides from their targets."""
    from layoutdsl.model import best_orientation, orientation_targets

    deviations = {}
    for room in spec.rooms:
        placed = layout.room(room.id)
        o = best_orientation(room, placed.w, placed.h)
        tw, th = orientation_targets(room, o)
        deviations[room.id] = max(abs(placed.w - tw) / tw, abs(placed.h - th) / th)
    return deviations


_STATUS_TEXT = {
    "optimal": "optimal",
    "gap_limit": "solved to the gap",
    "time_limit": "time limit reached; the best layout found is written",
    "node_limit": "node limit reached; the best layout found is written",
    "solution_limit": "solution limit reached",
    "iteration_limit": "LP iteration limit reached; the best layout found is written",
    "construction": "constructed layout (SCIP found no better one in time)",
    "interrupted": "interrupted; the best layout found is written",
    "unknown": "solver stopped; the best layout found is written",
    "solver_crashed": "the solver's search aborted or hung (a crash inside SCIP); the best layout found before it is written",
}


def _status_text(spec, info) -> str:
    text = _STATUS_TEXT.get(info.status, info.status)
    if getattr(info, "wall_clock_limited", False) and info.status != "time_limit":
        # the time limit stopped a stage before its deterministic work limits
        text += " (a stage stopped at the time limit: another machine may give another layout)"
    elif info.status == "time_limit":
        text += " (so another machine may give another layout)"
    return text


def summary(spec, layout, written: list[Path]) -> str:
    """The one-screen summary printed on stdout."""
    info = layout.solve
    room_area = sum(r.area for r in layout.rooms)
    boundary_area = layout.width * layout.height
    deviations = size_deviations(spec, layout)
    worst = max(deviations, key=lambda r: deviations[r]) if deviations else None
    mean = sum(deviations.values()) / len(deviations) if deviations else 0.0
    lines = [f"compiled `{layout.name}`: {len(layout.rooms)} rooms placed, {len(layout.portals)} portals"]
    lines.append(f"  room area   {room_area:.1f} m² of {boundary_area:.1f} m² boundary "
                 f"({100 * room_area / boundary_area:.1f} %)")
    if worst is not None:
        lines.append(f"  size error  mean {100 * mean:.1f} %, max {100 * deviations[worst]:.1f} % "
                     f"(`{worst}`) from the target sizes")
    if info is not None:
        gap = "-" if info.gap is None else f"{100 * info.gap:.2f} %"
        objective = "-" if info.objective is None else f"{info.objective:.4g}"
        lines.append(f"  status      {_status_text(spec, info)}")
        first = "" if info.first_feasible_seconds is None else f", first layout after {info.first_feasible_seconds:.1f} s"
        lines.append(f"  objective   {objective}, gap {gap}, {info.seconds:.1f} s{first} "
                     f"({info.method}, seed {info.seed})")
    lines.append("  wrote       " + ", ".join(str(p) for p in written))
    return "\n".join(lines)


def variant_differences(spec, layouts):
    """((i, j) -> arrangement difference of variants i < j, both found; per variant its
    difference from the spec's hints, None without hints or layout). 1-based indices."""
    from itertools import combinations

    from layoutdsl.layout.difference import difference, hint_centres, layout_centres

    numbered = [(i, layout) for i, layout in enumerate(layouts, start=1) if layout is not None]
    pairwise = {(i, j): difference(layout_centres(a), layout_centres(b))
                for (i, a), (j, b) in combinations(numbered, 2)}
    original = hint_centres(spec) if spec.hints else None
    from_hints = [None if layout is None or original is None
                  else difference(layout_centres(layout), original) for layout in layouts]
    return pairwise, from_hints


def _write_variants_report(spec, seeds: list[int], source: str, layouts, pairwise, from_hints,
                           outdir: Path, distinct: list[bool] | None = None,
                           kicks: list[int | None] | None = None) -> Path:
    """NAME-variants.json: each variant's seed and differences, for comparing them later;
    `distinct` (new arrangements only): whether it lies 0.3 or more from every one before it;
    `derived_kick` (new arrangements only): the kick of its seed's layout it was derived
    from, null for the seed's own layout (which `--variants 1 --seed S` makes again)."""
    import json

    from layoutdsl.emit.atomic import write_text_atomic

    report = {
        "spec": spec.name,
        "source": source,
        "variants": [
            {"index": index, "seed": seed, "found": layout is not None,
             "distinct": None if distinct is None else distinct[index - 1],
             "derived_kick": None if kicks is None else kicks[index - 1],
             "difference_from_hints": None if original is None else round(original, 4)}
            for index, (layout, original, seed) in enumerate(zip(layouts, from_hints, seeds), start=1)
        ],
        "pairwise_differences": [
            {"a": i, "b": j, "difference": round(value, 4)} for (i, j), value in sorted(pairwise.items())
        ],
    }
    return write_text_atomic(outdir / f"{spec.name}-variants.json", json.dumps(report, indent=2) + "\n")


def variant_stem(name: str, index: int) -> str:
    """A variant's file stem, `NAME-vK`: the one naming scheme of compile --variants and batch
    (layoutdsl.batch names its buildings the same way); the `v` keeps `office-2`'s first
    variant, `office-2-v1`, apart from a plan named `office-2-1`."""
    return f"{name}-v{index}"


def variant_failure(args, options, seed: int | None) -> str:
    """Why a variant has no layout, in words: which stopping rule it met, and what to try.

    compile_variants returns None for such a variant without a reason; what is known is the
    rule every variant stops at (layoutdsl.compile.variants: the generator's rounds, then the
    time limit), so that is what is said."""
    limit = f"{options.time_limit:g} s"
    if args.variants_from == "hints":
        return (f"seed {seed}: neither the generator starting from the hints nor the solve found a "
                f"verified layout within the time limit ({limit}); try a larger --time-limit")
    # a seed's try ends at the generator's rounds (work, the same on every machine) or at
    # the time limit, whichever comes first: the result does not say which, so both are named
    return (f"no seed tried gave a new arrangement: for each, the generator found no layout within "
            f"its work limits or the time limit ({limit}), or none that verified; try another "
            "--seed, --variants-from hints, or a larger --time-limit")


def _run_variants(spec, args, options, outdir: Path, formats, sources, out: Output) -> int:
    """--variants N: compile_variants writes NAME-v1.* ... NAME-vN.*."""
    from layoutdsl.compile.variants import compile_variants

    try:
        with out.timed("solve"):
            result = compile_variants(spec, args.variants, seed=options.seed, options=options,
                                      outdir=outdir, formats=formats, robot_room=args.robot_room,
                                      workers=args.workers, source=args.variants_from,
                                      world_options={"wall_height": args.wall_height, "robot": args.robot},
                                      progress=out.progress)
    except OSError as error:
        return out.finish(out.cannot_write(getattr(error, "filename", None) or outdir, error))
    layouts = list(result.layouts)
    count = sum(1 for layout in layouts if layout is not None)
    pairwise, from_hints = variant_differences(spec, layouts)
    paths = list(result.paths)
    if outdir is not None and count:
        try:
            paths.append(_write_variants_report(spec, result.seeds, args.variants_from, layouts,
                                                pairwise, from_hints, outdir, result.distinct, result.kicks))
        except OSError as error:
            return out.finish(out.cannot_write(getattr(error, "filename", None) or outdir, error))
    out.wrote(*paths)
    line = f"compiled `{spec.name}`: {count} of {args.variants} variants"
    if pairwise:
        mean = sum(pairwise.values()) / len(pairwise)
        line += (f", mean pairwise difference {mean:.2f} (share of room pairs whose relative "
                 "position differs, best of 8 rotations/mirrors)")
    lines = [line]
    records = []
    for index, layout in enumerate(layouts, start=1):
        stem = variant_stem(spec.name, index)
        seed = result.seeds[index - 1] if index - 1 < len(result.seeds) else None
        if layout is None:
            reason = variant_failure(args, options, seed)
            lines.append(f"  {stem}: no layout: {reason}")
            records.append({"name": stem, "found": False, "seed": seed, "reason": reason})
            continue
        info = layout.solve
        objective = "-" if info is None or info.objective is None else f"{info.objective:.4g}"
        status = "-" if info is None else _status_text(spec, info)
        original = from_hints[index - 1]
        versus = "" if original is None else f", difference from the hints {original:.2f}"
        close = ", close to an earlier variant" if result.distinct is not None and not result.distinct[index - 1] else ""
        lines.append(f"  {stem}: objective {objective}, {status}{versus}{close}")
        records.append({"name": stem, "found": True, "seed": seed,
                        "layout": layout_fields(spec, layout)})
    if pairwise:
        lines.append("  pairwise    " + ", ".join(
            f"{i}-{j} {value:.2f}" for (i, j), value in sorted(pairwise.items())))
    if paths:
        lines.append("  wrote       " + ", ".join(str(p) for p in paths))
    if count == 0:  # maybe no variant can exist: a single compile says why (E90x)
        lines.append(f"  none found: `layoutdsl compile {args.spec} -o {args.output}` without --variants "
                     "says whether the spec itself has no layout, and which lines conflict")
    out.summary("\n".join(lines))
    out.diagnostics(list(result.diagnostics), sources)
    code = exitcodes.OK if count == args.variants else exitcodes.NO_LAYOUT
    return out.finish(code, spec=spec.name, variants=records)

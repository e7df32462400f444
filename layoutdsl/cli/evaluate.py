"""`layoutdsl evaluate ORIGINAL.xml GENERATED.xml... -o REPORT_DIR`: the realism report.

Reads every plan with the project's XML reader; a plan with errors is a located diagnostic
on stderr (exit 1), a file that cannot be read at all the common I/O error (exit 2), never a
traceback. The report files are written all or nothing.
"""

from __future__ import annotations

import argparse
import time

from pathlib import Path

from layoutdsl.cli.argtypes import non_negative_float, positive_float
from layoutdsl.cli.output import Output, add_command, add_output_arguments
from layoutdsl.diagnostics import exitcodes
from layoutdsl.diagnostics import has_errors
from layoutdsl.evaluate.explore import ExploreSettings
from layoutdsl.evaluate.plan import EvaluateOptions


def add_parser(subparsers) -> argparse.ArgumentParser:
    """Register the `evaluate` subcommand."""
    defaults = EvaluateOptions()
    parser = add_command(
        subparsers, "evaluate",
        help="compare generated plans with their original (topology, areas, paths, exploration)",
        description=(
            "Measure how much generated building plans behave like the real one they come "
            "from (the thesis, §6.4-6.5): room graph, areas and room sizes, path lengths between "
            "entrances, and the effort of a simulated frontier exploration. Writes "
            "report.json, report.md and PNG plots into REPORT_DIR (created if needed)."
        ),
        examples=[
            ("compare two variants with the plan they come from",
             "layoutdsl evaluate plan.xml out/plan-v1.xml out/plan-v2.xml -o report"),
            ("the same exploration start in every plan, the result as JSON",
             "layoutdsl evaluate plan.xml out/plan-v1.xml -o report --start-room E0 --format json"),
        ],
    )  # fmt: skip
    parser.add_argument("original", metavar="ORIGINAL.xml", help="the real plan (building XML)")
    parser.add_argument("generated", nargs="+", metavar="GENERATED.xml", help="generated plans (building XML)")
    parser.add_argument("-o", "--output", required=True, metavar="REPORT_DIR", help="directory for the report")
    parser.add_argument(
        "--robot-radius", type=non_negative_float, default=defaults.robot_radius_m, metavar="M",
        help=f"robot radius the walls are inflated by (default {defaults.robot_radius_m} m)",
    )  # fmt: skip
    parser.add_argument(
        "--resolution", type=positive_float, default=defaults.resolution_m, metavar="M",
        help=f"occupancy grid cell size for the paths (default {defaults.resolution_m} m)",
    )  # fmt: skip
    parser.add_argument(
        "--explore-resolution", type=positive_float, default=defaults.explore_resolution_m, metavar="M",
        help=(
            "cell size of the exploration grid, a whole multiple of --resolution "
            f"(default {defaults.explore_resolution_m} m)"
        ),
    )  # fmt: skip
    parser.add_argument("--seed", type=int, default=defaults.seed, help="seed of the exploration (initial heading)")
    parser.add_argument(
        "--start-room", default=None, metavar="ID",
        help="room the exploration starts in, the same in every plan (default: the first entrance, E0)",
    )  # fmt: skip
    add_output_arguments(parser, diagnostics=True)
    parser.set_defaults(run=run)
    return parser


def _read_plans(paths: list[str], out: Output):
    """The plans, their diagnostics, and whether a file could not be read at all (exit 2)."""
    from layoutdsl.diagnostics.filekind import wrong_kind_for_plan
    from layoutdsl.diagnostics.source import Source
    from layoutdsl.importer import read_building

    buildings, diagnostics, sources = [], [], {}
    for path in paths:
        out.reading(path)
        try:  # one I/O error style for every command: exit 2, no diagnostic with a made-up place
            text = Path(path).read_bytes().decode("utf-8", errors="replace")
        except OSError as error:
            out.cannot_read(path, error)
            return None, diagnostics, True
        wrong = wrong_kind_for_plan(path, text)
        if wrong is not None:  # a spec or a layout.json: say so, not "malformed XML"
            building, found = None, [wrong]
        else:
            building, found = read_building(path)
        diagnostics.extend(found)
        if found:
            sources[path] = Source(path, text)
        buildings.append(building)
    out.diagnostics(diagnostics, sources)
    return buildings, diagnostics, False


def run(args: argparse.Namespace) -> int:
    """Evaluate the plans and write the report; exit 1 when a plan has errors, 2 when unreadable."""
    from layoutdsl.evaluate.report import evaluate, map_check_warnings, write_report

    out = Output("evaluate", args)
    files = [args.original, *args.generated]
    buildings, diagnostics, unreadable = _read_plans(files, out)
    if unreadable:
        return out.finish(exitcodes.USAGE)
    if has_errors(diagnostics) or any(b is None for b in buildings):
        return out.finish(exitcodes.SPEC_ERRORS)
    if args.explore_resolution < args.resolution:
        args.explore_resolution = args.resolution
    options = EvaluateOptions(
        robot_radius_m=args.robot_radius,
        resolution_m=args.resolution,
        explore_resolution_m=args.explore_resolution,
        seed=args.seed,
        start_room=args.start_room,
        explore=ExploreSettings(),
    )
    if args.start_room is not None:
        from layoutdsl.diagnostics.suggest import did_you_mean
        from layoutdsl.evaluate.topology import room_ids

        known = sorted(set(room_ids(buildings[0]).values()))
        if args.start_room not in known:
            guess = did_you_mean(args.start_room, known)
            return out.finish(out.error(f"start room `{args.start_room}` is not a room of {args.original}"
                                        + (f" ({guess})" if guess else "")))
    out.progress(f"evaluating {len(buildings) - 1} plans against {args.original}")
    started = time.monotonic()
    try:
        with out.timed("evaluate"):
            report = evaluate(buildings[0], buildings[1:], files, options)
    except (ValueError, MemoryError) as error:
        return out.finish(out.error(f"cannot evaluate: {error}"))
    for line in map_check_warnings(report):
        out.warning(line)
    try:
        written = write_report(report, args.output)
    except OSError as error:
        return out.finish(out.cannot_write(args.output, error))
    out.wrote(*written)
    for line in realism_lines(report):
        out.progress(line)
    elapsed = time.monotonic() - started
    out.summary(f"wrote {len(written)} files to {args.output} in {elapsed:.1f} s")
    return out.finish(exitcodes.OK, report=str(Path(args.output) / "report.json"),
                      realism={g["name"]: g.get("realism") for g in [report["original"], *report["generated"]]})


def realism_lines(report: dict) -> list[str]:
    """One line a plan: entrances open to the outside, enclosed voids, rooms out of reach."""
    lines = []
    for plan in [report["original"], *report["generated"]]:
        realism = plan.get("realism")
        if realism is None:
            continue
        unreachable = plan.get("unreachable", {})
        lines.append(
            f"{plan['name']}: entrances open {realism['entrances_open']}/{realism['entrances']}, "
            f"enclosed voids {100 * realism['void_share']:.1f} % of room area, "
            f"{realism['rooms_with_outside_wall']}/{realism['rooms']} rooms with an outside wall"
            + (f", {len(unreachable)} rooms out of the robot's reach ({', '.join(unreachable)})" if unreachable else ""))
    return lines

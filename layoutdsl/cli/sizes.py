"""`layoutdsl sizes`: the room-size model (docs/sizes.md).

    layoutdsl sizes fit DIR -o model.json     # fit on a folder of real plans (KIND_NAME.xml)
    layoutdsl sizes show --like school        # the typical size of every label of a kind

`fit` is `python -m layoutdsl.sizes.fit`; the shipped model is `layoutdsl sizes fit
../shared/floorplans`. A fitted model is used with `layoutdsl import --size-model FILE`.
"""

from __future__ import annotations

import argparse
from pathlib import Path

from layoutdsl.cli.output import Output, add_command, add_output_arguments
from layoutdsl.diagnostics import exitcodes

def add_parser(subparsers) -> argparse.ArgumentParser:
    """Register `sizes` and its two actions."""
    parser = add_command(
        subparsers, "sizes",
        help="fit or show the room-size model learned from real plans",
        description=(
            "The room-size model gives rooms without sizes (a sizeless room line `R1 R CLASSROOM`, "
            "an imported room graph, a sampled building) the sizes of real rooms of the same "
            "building kind, type and label: a log-normal area and the quantiles of the aspect "
            "ratio per label, corridors sized by their door count (docs/sizes.md)."
        ),
        examples=[
            ("refit the shipped model on the 24 real plans", "layoutdsl sizes fit ../shared/floorplans -o model.json"),
            ("the typical sizes of every office label", "layoutdsl sizes show --like office"),
        ],
    )  # fmt: skip
    parser.add_argument("action", choices=("fit", "show"),
                        help="fit: fit a model on a folder of plans; show: the typical sizes of each label")
    parser.add_argument("folder", metavar="DIR", nargs="?",
                        help="fit: the folder of building XML plans, named KIND_NAME.xml")
    parser.add_argument("-o", "--output", default="-",
                        help="fit: model JSON to write, or - for standard output (default)")
    parser.add_argument("--like", default="school", metavar="KIND", help="show: building kind (default school)")
    parser.add_argument("--size-model", default=None, metavar="FILE",
                        help="show: a fitted model (default: the shipped one)")
    add_output_arguments(parser)
    parser.set_defaults(run=run)
    return parser


def run(args: argparse.Namespace) -> int:
    out = Output("sizes", args)
    if args.action == "fit":
        return _fit(args, out)
    return _show(args, out)


def _fit(args: argparse.Namespace, out: Output) -> int:
    from layoutdsl.emit.atomic import write_text_atomic
    from layoutdsl.sizes.fit import fit_folder

    if args.folder is None:
        return out.finish(out.error("`sizes fit` needs the folder of plans: layoutdsl sizes fit DIR -o model.json"))
    folder = Path(args.folder)
    if not folder.is_dir():
        return out.finish(out.error(f"cannot read `{folder}`: not a folder", kind="io", path=str(folder)))
    out.reading(str(folder))
    skipped: list[tuple[str, str]] = []
    try:
        with out.timed("fit"):
            model = fit_folder(folder, skipped)
    except ValueError as error:
        return out.finish(out.error(str(error)))
    for name, problem in skipped:
        out.warning(f"skipped {name}: {problem}")
    text = model.dumps()
    if args.output == "-":
        out.product(text)
    else:
        try:
            write_text_atomic(args.output, text)
        except OSError as error:
            return out.finish(out.cannot_write(args.output, error))
        out.wrote(args.output)
    kinds = {kind: {"plans": len(m.plans), "rooms": m.overall.rooms} for kind, m in model.kinds.items()}
    out.progress("fitted " + ", ".join(f"{k}: {v['plans']} plans, {v['rooms']} rooms" for k, v in kinds.items()))
    return out.finish(exitcodes.OK, kinds=kinds, skipped=[name for name, _ in skipped])


def _show(args: argparse.Namespace, out: Output) -> int:
    from layoutdsl.sizes import ModelError, load_model
    from layoutdsl.syntax.format import format_number

    try:
        model = load_model(args.size_model)
        kind = model.kind(args.like)
    except OSError as error:
        return out.finish(out.cannot_read(args.size_model, error))
    except ModelError as error:
        return out.finish(out.error(str(error)))
    rows = []
    for label, law in sorted(kind.by_label.items()):
        rtype = kind.label_types.get(label, "R")
        size = model.room_sizes(args.like, rtype, label)
        rows.append({"label": label, "rtype": rtype, "rooms": law.rooms, "target_w": size.target_w,
                     "target_h": size.target_h, "source": size.source,
                     "area_median": round(law.typical_area, 3),
                     "long_side_quartiles": [round(law.long_quantiles[i], 3) for i in (2, 3, 4)],
                     "short_side_quartiles": [round(law.short_quantiles[i], 3) for i in (2, 3, 4)]})  # fmt: skip
    if not out.json:
        width = max(len(row["label"]) for row in rows)
        lines = [f"{'label':<{width}}  type  rooms  typical size (m)  from"]
        for row in rows:
            size = f"{format_number(row['target_w'])} x {format_number(row['target_h'])}"
            lines.append(f"{row['label']:<{width}}  {row['rtype']:<4}  {row['rooms']:>5}  {size:<16}  {row['source']}")
        out.product("\n".join(lines) + "\n")
    return out.finish(exitcodes.OK, kind=args.like, labels=rows)

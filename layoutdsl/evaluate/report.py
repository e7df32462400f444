"""The realism report: generated plans against their original, as JSON, Markdown and plots.

`evaluate(original, generated, options)` measures every plan and compares; the result is a
plain dict (the content of report.json), from which report.md and the PNG plots are drawn.
Nothing in it depends on the clock, so the same inputs and seed give the same files.
"""

from __future__ import annotations

import io
import json
import math
from pathlib import Path

import numpy as np

from layoutdsl.emit.atomic import write_files_atomic
from layoutdsl.layout.difference import difference
from layoutdsl.importer.building import Building
from layoutdsl.evaluate.metrics import shape_deviation, size_deviation
from layoutdsl.evaluate.plan import EvaluateOptions, PlanMeasures, measure_plan
from layoutdsl.evaluate.topology import compare_topology

PATH_METRIC = (
    "16-connected grid Dijkstra (moves (1,0), (1,1), (2,1) at their Euclidean cost; at most "
    "+2.75 % over the straight line) on the map inflated by the robot radius, then the path "
    "string-pulled with line-of-sight checks; the reported any-angle length lies between the "
    "true shortest length on the grid and the 16-connected length"
)


def _rel(value: float | None, reference: float | None) -> float | None:
    if value is None or reference is None or reference == 0:
        return None
    return (value - reference) / reference


def _mean_std(values: list[float]) -> tuple[float | None, float | None]:
    """Mean and sample standard deviation (n - 1; 0 for a single value)."""
    if not values:
        return None, None
    mean = float(np.mean(values))
    std = float(np.std(values, ddof=1)) if len(values) > 1 else 0.0
    return mean, std


def _pair(a: str, b: str) -> str:
    return f"{a}-{b}"


def _exploration_dict(m: PlanMeasures) -> dict:
    e = m.exploration
    area = m.areas.room_area_m2
    if e is None:
        return {"ran": False, "note": m.explore_note}
    per_area = (lambda v: None if v is None or area <= 0 else v / area)  # noqa: E731
    return {
        "ran": True,
        "start_room": m.explore_start.room if m.explore_start else None,
        "start_offset_m": m.explore_start.offset_m if m.explore_start else None,
        "reached_target": e.reached_target,
        "distance_to_target_m": e.distance_to_target_m,
        "time_to_target_s": e.time_to_target_s,
        "distance_per_m2": per_area(e.distance_to_target_m),
        "time_per_m2": per_area(e.time_to_target_s),
        "total_distance_m": e.total_distance_m,
        "total_time_s": e.total_time_s,
        "final_coverage": e.final_coverage,
        "reachable_free_m2": e.reachable_free_m2,
        "goals": e.goals,
        "blacklisted_goals": e.blacklisted,
        "hit_goal_limit": e.hit_goal_limit,
        "note": m.explore_note,
    }


def _plan_dict(m: PlanMeasures, path: str) -> dict:
    return {
        "file": path,
        "name": m.name,
        "rooms": m.rooms,
        "adjacencies": m.graph.number_of_edges(),
        "room_area_m2": m.areas.room_area_m2,
        "bbox_area_m2": m.areas.bbox_area_m2,
        "bbox_m": [m.areas.bbox_width_m, m.areas.bbox_height_m],
        "entrances": list(m.entrances),
        "entrance_anchor_offset_m": {room: a.offset_m for room, a in m.anchors.items()},
        "paths_m": {_pair(a, b): v for (a, b), v in m.path_lengths.items()},
        "grid_paths_m": {_pair(a, b): v for (a, b), v in m.grid_path_lengths.items()},
        "exploration": _exploration_dict(m),
        "map_check": _map_check_dict(m),
        "unreachable": dict(m.unreachable),
        "path_notes": {_pair(a, b): note for (a, b), note in m.path_notes.items()},
        "realism": None if m.realism is None else m.realism.summary(),
    }


def _map_check_dict(m: PlanMeasures) -> dict | None:
    check = m.map_check
    if check is None:
        return None
    return {
        "realises_portal_graph": check.realised,
        "realised_as_rasterized": check.realised_before,
        "opened_portals": [list(p) for p in check.opened],
        "sealed_joins": [list(p) for p in check.closed],
        "closed_portals": [list(p) for p in check.still_missing],
        "joins_without_portal": [list(p) for p in check.extra],
    }


def compare_plans(original: PlanMeasures, generated: list[PlanMeasures], files: list[str], options: EvaluateOptions) -> dict:
    """The report content (report.json) for already measured plans."""
    plans = []
    for m, path in zip(generated, files[1:]):
        entry = _plan_dict(m, path)
        topo = compare_topology(original.graph, m.graph)
        sizes = size_deviation(original.sizes, m.sizes)
        entry["topology"] = {
            "isomorphic": topo.isomorphic,
            "identical": topo.identical,
            "summary": topo.summary(),
            "missing_rooms": list(topo.missing_rooms),
            "extra_rooms": list(topo.extra_rooms),
            "relabelled_rooms": [list(x) for x in topo.relabelled_rooms],
            "missing_adjacencies": [list(x) for x in topo.missing_edges],
            "extra_adjacencies": [list(x) for x in topo.extra_edges],
            "changed_portals": [list(x) for x in topo.changed_portals],
        }
        entry["deviation"] = {
            "arrangement_difference": difference(original.centres, m.centres),
            "room_area": _rel(m.areas.room_area_m2, original.areas.room_area_m2),
            "bbox_area": _rel(m.areas.bbox_area_m2, original.areas.bbox_area_m2),
            "room_size_mean": sizes.mean,
            "room_size_max": sizes.max,
            "room_size_worst_room": sizes.worst_room,
            "rooms_not_compared": list(sizes.unmatched),
            "room_shapes": shape_deviation(original.shapes, m.shapes),
            "paths": {
                _pair(a, b): _rel(m.path_lengths.get((a, b)), v) for (a, b), v in original.path_lengths.items()
            },
        }
        plans.append(entry)
    pairs = []
    for (a, b), orig in original.path_lengths.items():
        values = [m.path_lengths[(a, b)] for m in generated if m.path_lengths.get((a, b)) is not None]
        mean, std = _mean_std(values)
        pairs.append({
            "pair": _pair(a, b),
            "original_m": orig,
            "generated_mean_m": mean,
            "generated_std_m": std,
            "generated_n": len(values),
            "generated_unreachable": sum(1 for m in generated if m.path_lengths.get((a, b)) is None),
            "relative_deviation_of_mean": _rel(mean, orig),
        })
    s = options.explore
    return {
        "format": "layoutdsl-evaluate/1",
        "settings": {
            "robot_radius_m": options.robot_radius_m,
            "resolution_m": options.resolution_m,
            "explore_resolution_m": options.resolution_m * options.coarsening,
            "seed": options.seed,
            "start_room": options.start_room,
            "path_metric": PATH_METRIC,
            "path_endpoints": "room area centroid, or the nearest cell of the room the robot fits in",
            "laser": {"fov_deg": s.laser_fov_deg, "range_m": s.laser_range_m, "beams": s.laser_beams},
            "speed_model": {
                "linear_m_s": s.linear_speed_m_s,
                "turn_deg_s": s.turn_speed_deg_s,
                "stop_per_goal_s": s.stop_per_goal_s,
                "scan_every_m": s.scan_every_m,
                "time": "distance / linear + turning / turn speed + stops",
            },
            "coverage_target": s.coverage_target,
            "std": "sample standard deviation (n - 1)",
            "area_normalisation": "by total room area",
        },
        "original": _plan_dict(original, files[0]),
        "generated": plans,
        "path_pairs": pairs,
    }


def distinct_names(files: list[str]) -> list[str]:
    """A name per file: its stem, with as many parent folders as it takes to tell apart
    different files of the same stem (the same file given twice keeps one name).

    Variants of several runs are often called alike (`run1/plan-0.xml`, `run2/plan-0.xml`);
    the report's columns and plots must not merge them.
    """
    parts = [Path(f).resolve().with_suffix("").parts for f in files]
    names = [p[-1] for p in parts]
    for depth in range(2, max(len(p) for p in parts) + 1):
        clashing = {n for n in names if len({q for q, m in zip(parts, names) if m == n}) > 1}
        if not clashing:
            break
        names = ["/".join(p[-depth:]) if n in clashing else n for p, n in zip(parts, names)]
    return names


def evaluate(original: Building, generated: list[Building], files: list[str], options: EvaluateOptions = EvaluateOptions()) -> dict:
    """Measure the original and every generated plan and compare them (report.json content)."""
    names = distinct_names(files)
    measured = [measure_plan(b, options, name) for b, name in zip([original, *generated], names)]
    report = compare_plans(measured[0], measured[1:], files, options)
    return report


# ----------------------------------------------------------------------------- output


def _fmt(value, digits: int = 2, suffix: str = "") -> str:
    if value is None:
        return "–"
    if isinstance(value, float) and not math.isfinite(value):
        return "–"
    return f"{value:.{digits}f}{suffix}"


def _pct(value) -> str:
    return "–" if value is None else f"{value * 100:+.1f} %"


def _abs_pct(value) -> str:
    return "–" if value is None else f"{value * 100:.1f} %"


def _map_check_lines(plans: list[dict], original: dict) -> list[str]:
    """The 'Map check' section: which maps join exactly the rooms their portals join."""
    out = ["", "## Map check", "",
           "Every measure runs on the occupancy map. Before measuring, each map is checked against its "
           "portal graph (flood fill: rooms joined by a portal must be connected, and no others); portals "
           "the rasterization left closed are opened with a door-wide cut, and rooms joined without a portal "
           "are parted by a one-cell wall where that parts nothing else. Repairs, and what could not be fixed:", ""]
    for g in plans:
        check = g.get("map_check")
        if check is None:
            continue
        label = g["name"] + (" (original)" if g is original else "")
        for a, b in check["opened_portals"]:
            out.append(f"- {label}: opened the portal between `{a}` and `{b}` (closed in the rasterized map)")
        for a, b in check["sealed_joins"]:
            out.append(f"- {label}: walled `{a}` off from `{b}` (joined in the rasterized map without a portal)")
        for a, b in check["closed_portals"]:
            out.append(f"- {label}: **`{a}` and `{b}` share a portal but are not joined in the map**")
        for a, b in check["joins_without_portal"]:
            out.append(f"- {label}: `{a}` and `{b}` are joined in the map without a portal")
    if out[-1] == "":
        out.append("Every map realises its portal graph.")
    return out


def _realism_lines(plans: list[dict], original: dict) -> list[str]:
    """The realism section: entrances open to the outside, enclosed voids, outside walls,
    slivers, and every room the robot cannot reach, with the reason."""
    out = ["", "## Realism: entrances, voids, reach", "",
           "| plan | entrances open | enclosed entrances | enclosed voids (share of room area) | rooms with an outside wall | slivers | rooms out of reach |",
           "|---|---|---|---|---|---|---|"]
    for g in plans:
        r = g.get("realism")
        label = g["name"] + (" (original)" if g is original else "")
        if r is None:
            out.append(f"| {label} | – | – | – | – | – | – |")
            continue
        enclosed = ", ".join(f"`{e}`" for e in r["enclosed_entrances"]) or "none"
        slivers = "–" if r["slivers"] is None else str(r["slivers"])
        out.append(f"| {label} | {r['entrances_open']}/{r['entrances']} | {enclosed} | {_pct_plain(r['void_share'])} | "
                   f"{r['rooms_with_outside_wall']}/{r['rooms']} | {slivers} | {len(g.get('unreachable', {}))} |")
    out += ["", "An entrance is open when at least 0.9 m of its outline borders the outside; gaps under 0.6 m "
            "between rooms count as wall. Enclosed voids: empty space at least 0.6 m wide that the outside does "
            "not reach. Slivers: gaps between facing walls wider than a wall and narrower than 0.6 m "
            "(rectangular rooms only)."]
    unreachable = [(g["name"] + (" (original)" if g is original else ""), room, why)
                   for g in plans for room, why in g.get("unreachable", {}).items()]
    if unreachable:
        start = plans[0].get("exploration", {}).get("start_room")
        out += ["", f"Rooms the robot cannot reach from the start room{f' `{start}`' if start else ''}:", ""]
        out += [f"- {name}: `{room}`: {why}" for name, room, why in unreachable]
    return out


def _pct_plain(value: float | None) -> str:
    return "–" if value is None else f"{100 * value:.1f} %"


def map_check_warnings(report: dict) -> list[str]:
    """One line per map problem left after the repair, naming the plan and the rooms."""
    lines = []
    for g in [report["original"], *report["generated"]]:
        check = g.get("map_check") or {}
        for a, b in check.get("closed_portals", []):
            lines.append(f"{g['name']}: rooms `{a}` and `{b}` share a portal but are not joined in the map")
        for a, b in check.get("joins_without_portal", []):
            lines.append(f"{g['name']}: rooms `{a}` and `{b}` are joined in the map without a portal")
        for a, b in check.get("opened_portals", []):
            lines.append(f"{g['name']}: opened the portal between `{a}` and `{b}`, closed in the rasterized map")
        for a, b in check.get("sealed_joins", []):
            lines.append(f"{g['name']}: walled `{a}` off from `{b}`, joined in the rasterized map without a portal")
    return lines


def render_markdown(report: dict) -> str:
    """report.md: the tables a person reads."""
    o = report["original"]
    gens = report["generated"]
    st = report["settings"]
    out = [f"# Realism report: {o['name']}", ""]
    out.append(
        f"Original `{o['file']}` against {len(gens)} generated plan(s). Robot radius "
        f"{st['robot_radius_m']} m, map resolution {st['resolution_m']} m, exploration grid "
        f"{st['explore_resolution_m']} m, seed {st['seed']}."
    )
    out += ["", "## Topology and arrangement", "",
            "| plan | rooms | adjacencies | isomorphic | topology difference | arrangement difference |",
            "|---|---|---|---|---|---|"]
    out.append(f"| {o['name']} (original) | {o['rooms']} | {o['adjacencies']} | – | – | – |")
    for g in gens:
        t = g["topology"]
        out.append(f"| {g['name']} | {g['rooms']} | {g['adjacencies']} | {'yes' if t['isomorphic'] else '**no**'} | "
                   f"{t['summary']} | {_fmt(g['deviation']['arrangement_difference'])} |")
    out += ["", "Arrangement difference: the share of room pairs whose relative position (left, right, above, "
            "below of each other's centres) differs from the original, under the best of the 8 rotations and "
            "mirrors; 0 is the original arrangement redrawn."]
    out += _map_check_lines([o, *gens], o)
    out += ["", "## Areas and room sizes", ""]
    out += [
        "| plan | room area m² | Δ | bounding box m² | Δ | room size dev. mean | max (room) |",
        "|---|---|---|---|---|---|---|",
        f"| {o['name']} (original) | {_fmt(o['room_area_m2'], 1)} | – | {_fmt(o['bbox_area_m2'], 1)} | – | – | – |",
    ]
    for g in gens:
        d = g["deviation"]
        out.append(
            f"| {g['name']} | {_fmt(g['room_area_m2'], 1)} | {_pct(d['room_area'])} | {_fmt(g['bbox_area_m2'], 1)} | "
            f"{_pct(d['bbox_area'])} | {_abs_pct(d['room_size_mean'])} | {_abs_pct(d['room_size_max'])}"
            f"{f' ({worst})' if (worst := d['room_size_worst_room']) and d['room_size_max'] else ''} |"
        )
    out += ["", "Room size deviation: |generated side − original target| / target, per side, each room in its best orientation; targets are the rectangularized sizes (§5.3.1)."]
    out += ["", "| plan | non-rectangular rooms | room area change, mean |", "|---|---|---|"]
    for g in gens:
        shapes = g["deviation"]["room_shapes"]
        out.append(f"| {g['name']} | {shapes['non_rectangular_generated']} (original "
                   f"{shapes['non_rectangular_original']}) | {_abs_pct(shapes['room_area_change_mean'])} |")
    out += ["", "Real shapes (issue 14): a room is non-rectangular when its polygon covers less than 0.8 of "
            "its bounding box (an L-room does); the area change is |generated polygon area / original − 1| "
            "per room."]
    out += _realism_lines([o, *gens], o)
    out += ["", "## Path lengths between entrances (m)", ""]
    if report["path_pairs"]:
        head = "| pair | original | generated mean ± std | Δ mean | " + " | ".join(g["name"] for g in gens) + " |"
        out += [head, "|" + "---|" * (4 + len(gens))]
        for p in report["path_pairs"]:
            cells = [_fmt(g["paths_m"].get(p["pair"])) for g in gens]
            mean = _fmt(p["generated_mean_m"])
            std = _fmt(p["generated_std_m"])
            out.append(f"| {p['pair']} | {_fmt(p['original_m'])} | {mean} ± {std} | {_pct(p['relative_deviation_of_mean'])} | " + " | ".join(cells) + " |")
        out += ["", f"Metric: {st['path_metric']}. Endpoints: {st['path_endpoints']}. – = unreachable or missing; why:", ""]
        notes = [(g["name"] + (" (original)" if g is o else ""), pair, note)
                 for g in [o, *gens] for pair, note in g.get("path_notes", {}).items()]
        out += [f"- {name}, {pair}: {note}" for name, pair, note in notes] or ["- every pair has a path"]
        out += ["", "![paths](paths.png)"]
    else:
        out.append("The original has fewer than two entrances (E rooms): no pairs to compare.")
    out += ["", "## Exploration", ""]
    sm = st["speed_model"]
    out.append(
        f"Laser {st['laser']['fov_deg']:g}° / {st['laser']['range_m']:g} m ({st['laser']['beams']} beams); nearest frontier by path "
        f"distance; time = distance / {sm['linear_m_s']} m/s + turning / {sm['turn_deg_s']:g}°/s + {sm['stop_per_goal_s']:g} s per goal. "
        f"Figures are at {st['coverage_target'] * 100:g} % of the reachable free space; per m² divides by the room area."
    )
    out += [
        "",
        "| plan | start | distance m | time s | distance m/m² | time s/m² | total distance m | coverage at end | goals |",
        "|---|---|---|---|---|---|---|---|---|",
    ]
    for g in [o, *gens]:
        e = g["exploration"]
        label = g["name"] + (" (original)" if g is o else "")
        if not e["ran"]:
            out.append(f"| {label} | – | {e['note']} | | | | | | |")
            continue
        out.append(
            f"| {label} | {e['start_room']} | {_fmt(e['distance_to_target_m'], 1)} | {_fmt(e['time_to_target_s'], 0)} | "
            f"{_fmt(e['distance_per_m2'], 3)} | {_fmt(e['time_per_m2'], 3)} | {_fmt(e['total_distance_m'], 1)} | "
            f"{_fmt(e['final_coverage'] * 100, 1, ' %')} | {e['goals']} |"
        )
    out += ["", "![exploration](exploration.png)", "", "![areas](areas.png)", ""]
    return "\n".join(out)


def _png(fig) -> bytes:
    buffer = io.BytesIO()
    # no timestamp or software metadata, so identical reports give identical bytes
    fig.savefig(buffer, format="png", dpi=100, metadata={"Software": None})
    return buffer.getvalue()


def render_plots(report: dict) -> dict[str, bytes]:
    """PNG plots: paths (Figure 6.14), exploration (Figure 6.25) and areas."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    o, gens = report["original"], report["generated"]
    files: dict[str, bytes] = {}
    names = [o["name"] + "\n(original)"] + [g["name"] for g in gens]

    pairs = report["path_pairs"]
    if pairs:
        fig, ax = plt.subplots(figsize=(max(6, 0.7 * len(pairs) + 2), 4))
        x = np.arange(len(pairs))
        orig = [p["original_m"] if p["original_m"] is not None else np.nan for p in pairs]
        mean = [p["generated_mean_m"] if p["generated_mean_m"] is not None else np.nan for p in pairs]
        std = [p["generated_std_m"] if p["generated_std_m"] is not None else 0.0 for p in pairs]
        ax.bar(x - 0.2, orig, 0.4, label="original", color="tab:blue")
        ax.bar(x + 0.2, mean, 0.4, yerr=std, capsize=3, label=f"generated (mean ± std, n={len(gens)})", color="tab:orange")
        ax.set_xticks(x, [p["pair"].replace("E", "") for p in pairs])
        ax.set_xlabel("entrance pair")
        ax.set_ylabel("path length (m)")
        ax.set_title(f"Paths between entrances: {o['name']}")
        ax.legend()
        fig.tight_layout()
        files["paths.png"] = _png(fig)
        plt.close(fig)

    plans = [o, *gens]
    fig, axes = plt.subplots(2, 2, figsize=(max(7, 1.2 * len(plans) + 3), 6.5))
    keys = (
        ("time_to_target_s", "time (s)"),
        ("distance_to_target_m", "distance (m)"),
        ("time_per_m2", "time / area (s/m²)"),
        ("distance_per_m2", "distance / area (m/m²)"),
    )
    colors = ["tab:blue"] + ["tab:orange"] * len(gens)
    for ax, (key, label) in zip(axes.flat, keys):
        values = [p["exploration"].get(key) if p["exploration"]["ran"] else None for p in plans]
        ax.bar(range(len(plans)), [np.nan if v is None else v for v in values], color=colors)
        ax.set_xticks(range(len(plans)), names, rotation=30, ha="right", fontsize=8)
        ax.set_ylabel(label)
    fig.suptitle(f"Exploration to {report['settings']['coverage_target'] * 100:g} % coverage: {o['name']}")
    fig.tight_layout()
    files["exploration.png"] = _png(fig)
    plt.close(fig)

    fig, ax = plt.subplots(figsize=(max(6, 1.2 * len(plans) + 2), 4))
    x = np.arange(len(plans))
    ax.bar(x - 0.2, [p["room_area_m2"] for p in plans], 0.4, label="room area", color="tab:green")
    ax.bar(x + 0.2, [p["bbox_area_m2"] for p in plans], 0.4, label="bounding box", color="tab:gray")
    ax.set_xticks(x, names, rotation=30, ha="right", fontsize=8)
    ax.set_ylabel("area (m²)")
    ax.set_title(f"Areas: {o['name']}")
    ax.legend()
    fig.tight_layout()
    files["areas.png"] = _png(fig)
    plt.close(fig)
    return files


def write_report(report: dict, out_dir: Path | str) -> list[Path]:
    """Write report.json, report.md and the plots into `out_dir`, all or nothing."""
    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    files: dict[Path, bytes | str] = {
        out / "report.json": json.dumps(report, indent=2, ensure_ascii=False) + "\n",
        out / "report.md": render_markdown(report),
    }
    for name, data in render_plots(report).items():
        files[out / name] = data
    return write_files_atomic(files)

"""Generation from the room graph alone (issue 11): verified, seeded, different per seed."""

from __future__ import annotations

import json
import random
import time
from dataclasses import replace
from pathlib import Path

import pytest

from layoutdsl.compile.construct import construct_start, rects_to_layout
from layoutdsl.compile.generate import RoomSizes, generate_geometry
from layoutdsl.compile.variants import compile_variants
from layoutdsl.layout.difference import difference, layout_centres
from layoutdsl.importer import import_building
from layoutdsl.layout.verify import verify
from layoutdsl.solve import SolveOptions
from layoutdsl.syntax.ast import Boundary, Obstacle, Position

from _specs import cycle_spec, tree_spec

LAMUNIERE = Path(__file__).resolve().parents[2] / "examples" / "floorplans" / "school_Lamuniere1.xml"


def generated_layout(spec, seed: int):
    rects = construct_start(spec, seed=seed, use_hints=False, deadline=time.monotonic() + 20)
    assert rects is not None, "no layout generated"
    layout = rects_to_layout(spec, rects)
    assert verify(spec, layout) == []
    return layout


@pytest.mark.parametrize("make_spec", [tree_spec, cycle_spec], ids=["tree", "cycle"])
def test_generated_geometry_has_every_room_within_its_size_bounds(make_spec):
    spec = make_spec()
    geometry = generate_geometry(spec, random.Random(0))
    assert set(geometry) == set(spec.room_ids)
    for room in spec.rooms:
        x, y, w, h = geometry[room.id]
        sizes = RoomSizes.of(room)
        assert sizes.lo_long - 1e-9 <= max(w, h) <= sizes.hi_long + 1e-9
        assert sizes.lo_short - 1e-9 <= min(w, h) <= sizes.hi_short + 1e-9


@pytest.mark.parametrize("make_spec", [tree_spec, cycle_spec], ids=["tree", "cycle"])
def test_generated_layouts_verify_and_differ_by_seed(make_spec):
    spec = make_spec()
    first, second = generated_layout(spec, 0), generated_layout(spec, 1)
    assert difference(layout_centres(first), layout_centres(second)) > 0


def test_same_seed_gives_the_same_geometry():
    spec = cycle_spec()
    assert generate_geometry(spec, random.Random(5)) == generate_geometry(spec, random.Random(5))


def test_position_obstacle_and_on_boundary_are_honoured():
    base = tree_spec()
    rooms = tuple(replace(r, on_boundary=True) if r.id == "R5" else r for r in base.rooms)
    spec = replace(base, rooms=rooms,
                   boundary=Boundary(24.0, 18.0, (Obstacle("O0", 10.0, 0.0, 3.0, 4.0),)),
                   positions=(Position("C0", 3.0, 9.0),))
    geometry = generate_geometry(spec, random.Random(2))
    x, y, w, h = geometry["C0"]
    assert x <= 3.0 <= x + w and y <= 9.0 <= y + h, "a pinned room is placed over its point"
    layout = generated_layout(spec, 2)  # verify() covers the obstacle, onB and position
    c0 = layout.room("C0")
    assert c0.x <= 3.0 <= c0.x + c0.w


def test_hints_are_ignored_when_asked():
    # hints far from anything the generator would draw: with use_hints=False they play no part
    spec = tree_spec()
    with_hints = replace(spec, hints=())
    assert (construct_start(spec, seed=4, use_hints=False, deadline=time.monotonic() + 20)
            == construct_start(with_hints, seed=4, use_hints=False, deadline=time.monotonic() + 20))


def test_import_writes_no_hints_by_default_and_the_spec_compiles():
    spec, diagnostics = import_building(LAMUNIERE)
    assert spec is not None and spec.hints == ()
    layout = generated_layout(spec, 0)
    assert len(layout.rooms) == 8


def test_graph_variants_differ_and_are_reproducible(tmp_path):
    spec = tree_spec()
    options = SolveOptions(time_limit=20, quiet=True)
    result = compile_variants(spec, 3, seed=1, options=options, outdir=tmp_path,
                              formats=("xml",), workers=1)
    assert all(layout is not None for layout in result.layouts)
    for layout in result.layouts:
        assert verify(spec, layout) == []
    centres = [layout_centres(layout) for layout in result.layouts]
    pairwise = [difference(centres[i], centres[j]) for i, j in ((0, 1), (0, 2), (1, 2))]
    assert all(value >= 0.3 for value in pairwise), pairwise
    again = compile_variants(spec, 1, seed=result.seeds[1], options=options, workers=1)
    # a variant compiled alone from variant 2's seed is variant 2: same seed, same geometry
    # (the layout's solve info holds wall-clock seconds, so compare rooms and portals)
    assert again.layouts[0].rooms == result.layouts[1].rooms
    assert again.layouts[0].portals == result.layouts[1].portals


def test_compile_variants_command_reports_pairwise_differences(tmp_path, capsys):
    from layoutdsl.cli import main
    from layoutdsl.syntax.format import format_spec

    spec_path = tmp_path / "tree.lay"
    spec_path.write_text(format_spec(tree_spec()))
    code = main(["compile", str(spec_path), "-o", str(tmp_path / "out"), "--emit", "xml",
                 "--variants", "2", "--workers", "1", "--time-limit", "20"])
    out = capsys.readouterr().out  # the summary (which -q leaves out)
    assert code == 0, out
    assert "2 of 2 variants" in out and "pairwise    1-2 " in out
    report = json.loads((tmp_path / "out" / "tree-variants.json").read_text())
    seeds = [v["seed"] for v in report["variants"]]
    assert report["source"] == "graph" and seeds[0] == 0 and len(set(seeds)) == 2
    assert report["pairwise_differences"][0]["difference"] > 0


def test_compile_variants_command_shows_each_variant_kept(tmp_path, capsys):
    from layoutdsl.cli import main
    from layoutdsl.syntax.format import format_spec

    spec_path = tmp_path / "tree.lay"
    spec_path.write_text(format_spec(tree_spec()))
    code = main(["compile", str(spec_path), "-o", str(tmp_path / "out"), "--emit", "xml",
                 "--variants", "2", "--workers", "1", "--time-limit", "20", "--seed", "3"])
    captured = capsys.readouterr()
    assert code == 0, captured.err
    report = json.loads((tmp_path / "out" / "tree-variants.json").read_text())
    seeds = [v["seed"] for v in report["variants"]]
    assert captured.err.splitlines()[-2:] == [f"variant 1 of 2: seed {seeds[0]} (quick try)",
                                              f"variant 2 of 2: seed {seeds[1]} (quick try)"]


def test_cycle_blocks_are_the_biconnected_parts_of_three_rooms_or_more():
    from layoutdsl.compile.generate import cycle_blocks

    assert cycle_blocks(cycle_spec()) == [frozenset("ABCDE")]
    assert cycle_blocks(tree_spec()) == []


def test_a_solved_cycle_block_is_placed_as_a_rigid_whole():
    from layoutdsl.compile.construct import block_spec, block_templates

    spec = cycle_spec()
    (template,) = block_templates(spec, seed=3, deadline=time.monotonic() + 20)
    assert set(template) == set("ABCDE")
    # the template is a verified layout of the ring alone
    ring = block_spec(spec, frozenset("ABCDE"))
    assert verify(ring, rects_to_layout(ring, template)) == []
    geometry = generate_geometry(spec, random.Random(0), templates=[template])
    # every ring room moved by the same offset, or mirrored as a whole: the contacts that
    # close the cycle stay, so the adjacencies of the ring hold in the seed geometry
    placed = rects_to_layout(ring, {r: geometry[r] for r in "ABCDE"})
    assert verify(ring, placed) == []
    # and the construction from it is a verified layout of the whole spec
    assert generated_layout(spec, 3) is not None


def test_a_tree_hanging_off_a_missing_door_moves_as_a_whole():
    from layoutdsl.compile.generate import _contact_shortfall, _move_subtrees, _neighbours, _placement_of, _Placement

    spec = tree_spec()
    walldim = spec.settings.walldim
    # C0 at the bottom with its six rooms; C1 (and R6, R7 hanging off it) drawn far away
    # in the top corner: the door C0-C1, a bridge of the graph, is missing
    geometry = {"C0": (1.0, 1.0, 14.0, 2.0)}
    for i in range(6):
        geometry[f"R{i}"] = (1.0 + i * (2.0 + walldim), 3.0 + walldim, 2.0, 3.5)
    geometry["C1"] = (20.0, 8.0, 2.0, 8.0)
    geometry["R6"] = (22.0 + walldim, 8.0, 1.5, 3.5)
    geometry["R7"] = (22.0 + walldim, 12.0, 1.5, 3.5)
    walls = {frozenset((a.a, a.b)): a.door / spec.settings.door_utilization for a in spec.adjacencies}
    placement = _placement_of(geometry, _Placement(spec.boundary.w, spec.boundary.h, walldim))
    before = {r: geometry[r] for r in ("C1", "R6", "R7")}

    def shortfall(a, b):
        import numpy as np
        return _contact_shortfall(np.array([geometry[a]]), np.array(geometry[b]), walldim,
                                  walls[frozenset((a, b))])[0]

    assert shortfall("C0", "C1") > 1.0
    _move_subtrees(geometry, placement, _neighbours(spec), walls, pinned=set())
    assert shortfall("C0", "C1") < 1e-6
    # the tree kept its own doors and its shape (moved, perhaps mirrored; never resized)
    assert shortfall("C1", "R6") < 1e-6 and shortfall("C1", "R7") < 1e-6
    assert {r: geometry[r][2:] for r in before} == {r: rect[2:] for r, rect in before.items()}
    assert geometry["C1"] != before["C1"]
    # the rest of the building stayed where it was
    assert geometry["C0"] == (1.0, 1.0, 14.0, 2.0)


def test_each_generated_try_gets_its_own_solved_blocks():
    from layoutdsl.compile.construct import _TemplateSets

    sets = _TemplateSets(cycle_spec(), seed=0, deadline=time.monotonic() + 30)
    first, second = sets.get(0), sets.get(1)
    assert first and second
    assert set(first[0]) == set(second[0]) == set("ABCDE")
    # solved from other seeds: the same rooms, another solution of the block
    assert first[0] != second[0]
    assert sets.get(1) is second  # solved once, kept


def test_corridors_sharing_a_door_meet_end_on_not_side_by_side():
    import numpy as np

    from layoutdsl.compile.generate import _side_by_side

    walldim = 0.2
    corridor = np.array([0.0, 0.0, 20.0, 2.0])  # 20 m along x
    cands = np.array([
        [0.0, 2.2, 20.0, 2.0],   # parallel, sharing its whole 20 m side: 18 m beyond its end
        [9.0, 2.2, 2.0, 12.0],   # a T: its 2 m end against the corridor's side
        [20.2, 0.0, 15.0, 2.0],  # end to end
        [10.0, 2.2, 15.0, 2.0],  # parallel, sharing 10 m: 8 m beyond its end
    ])
    assert _side_by_side(cands, corridor, walldim).tolist() == pytest.approx([36.0, 0.0, 0.0, 16.0])


def test_a_ladder_of_corridors_is_drawn_with_every_rung_spanning_the_rails():
    from _specs import ladder_spec

    from layoutdsl.compile.construct import block_spec, hard_violations
    from layoutdsl.compile.generate import cycle_blocks
    from layoutdsl.compile.ladders import find_ladder, ladder_template

    spec = ladder_spec()
    (block,) = cycle_blocks(spec)
    ring = block_spec(spec, block)
    assert find_ladder(ring) == ("A", "B", ["K0", "K1", "K2"])
    turned = set()
    for seed in range(6):
        rects = ladder_template(ring, random.Random(seed))
        assert rects is not None and set(rects) == set("AB") | {"K0", "K1", "K2"}
        # every door among the ladder's rooms, sizes within bounds, no overlaps
        assert hard_violations(ring.restricted_to(frozenset(rects), "ladder"), rects) == []
        # the rungs share one length: the gap between the rails
        spans = {round(max(rects[k][2:]), 9) for k in ("K0", "K1", "K2")}
        assert len(spans) == 1
        turned.add(rects["A"][2] < rects["A"][3])
    assert turned == {False, True}  # rails along x for some seeds, along y for others
    # and the whole spec, offices included, compiles from it
    assert generated_layout(spec, 0) is not None


def test_blocks_sharing_a_room_give_it_one_shape_and_are_laid_over_it():
    from _specs import adjacent, room

    from layoutdsl.compile.construct import block_templates, hard_violations
    from layoutdsl.compile.generate import _neighbours, _place_template, _Placement
    from layoutdsl.syntax.ast import Spec

    # two triangles of rooms sharing the hall S (the bow tie): two blocks, one room in both
    rooms = (room("S", 8.0, 5.0), room("A", 4.0, 3.0), room("B", 4.0, 3.0),
             room("C", 4.0, 3.0), room("D", 4.0, 3.0))
    adjacencies = tuple(adjacent(a, b) for a, b in
                        [("S", "A"), ("A", "B"), ("B", "S"), ("S", "C"), ("C", "D"), ("D", "S")])
    spec = Spec("bowtie", rooms, Boundary(30.0, 30.0), adjacencies)
    first, second = block_templates(spec, seed=1, deadline=time.monotonic() + 30)
    assert sorted(first["S"][2:]) == pytest.approx(sorted(second["S"][2:]))
    # laid over S as placed: S keeps its place, the other block's doors to it hold
    walls = {frozenset((a.a, a.b)): a.door / spec.settings.door_utilization for a in adjacencies}
    placement = _Placement(30.0, 30.0, spec.settings.walldim)
    geometry = {}
    for room_id, (x, y, w, h) in first.items():  # in the middle of the boundary
        geometry[room_id] = (x + 10.0, y + 10.0, w, h)
        placement.add(room_id, geometry[room_id])
    placed = _place_template(second, "S", placement, geometry, _neighbours(spec), walls, random.Random(0))
    assert placed is not None and "S" not in placed
    ring = spec.restricted_to(frozenset(second), "ring")
    assert hard_violations(ring, {**placed, "S": geometry["S"]}) == []
    # a shared room of another shape cannot be laid over: the block is not used
    x, y, w, h = geometry["S"]
    geometry["S"] = (x, y, w + 1.0, h)
    assert _place_template(second, "S", placement, geometry, _neighbours(spec), walls, random.Random(0)) is None


def test_new_arrangements_are_taken_in_seed_order_and_close_ones_skipped(monkeypatch):
    from layoutdsl.compile import variants
    from layoutdsl.layout import Layout

    def grid(order) -> Layout:
        # six rooms on a 3 x 2 grid, in this order
        rects = {f"R{room}": ((i % 3) * 5.0, (i // 3) * 5.0, 4.0, 4.0) for i, room in enumerate(order)}
        return rects_to_layout(spec, rects)

    spec = replace(tree_spec(), rooms=tuple(r for r in tree_spec().rooms if r.id in {f"R{i}" for i in range(6)}),
                   adjacencies=())
    first, far, farther = grid(range(6)), grid((0, 1, 2, 4, 5, 3)), grid((0, 1, 2, 5, 3, 4))
    centres = [layout_centres(layout) for layout in (first, far, farther)]
    assert min(difference(a, b) for a, b in ((centres[0], centres[1]), (centres[0], centres[2]),
                                             (centres[1], centres[2]))) >= 0.3
    tries = []

    def run(outcomes: dict, n: int):
        """compile_variants' new arrangements, each seed's (quick, full) outcome given."""
        tries.clear()

        def fake(spec_, seed, options, point, source, quick=False, **_):
            tries.append((seed, quick))
            return outcomes.get(seed, (None, None))[0 if quick else 1], None

        monkeypatch.setattr(variants, "_compile_variant", fake)
        results, seeds, distinct = variants._new_arrangements(spec, n, 10, None, workers=1)
        return [layout for layout, _ in results], seeds, distinct

    # 11 is a copy of 10 and 12 finds nothing quickly: skipped, and 13 is kept; the seeds
    # after the N-th kept one are never tried
    layouts, seeds, distinct = run({10: (first, first), 11: (grid(range(6)), None), 13: (far, far),
                                    14: (farther, farther)}, 2)
    assert seeds == [10, 13] and layouts == [first, far] and distinct == [True, True]
    assert tries == [(10, True), (11, True), (12, True), (13, True)]
    # quick tries used up (1 + 3 * (N - 1) seeds): the seeds that found nothing get their
    # full construction in seed order, then copies fill what is still missing
    layouts, seeds, distinct = run({10: (first, first), 11: (grid(range(6)), None), 12: (None, far)}, 3)
    assert tries[:7] == [(s, True) for s in range(10, 17)]
    assert tries[7:] == [(s, False) for s in range(12, 17)]
    assert seeds == [10, 12, 11] and layouts == [first, far, grid(range(6))]
    assert distinct == [True, True, False]  # the copy only fills the third place
    # quick tries that mostly fail stop at 2 failures per variant asked for (10 of 13 here)
    layouts, seeds, distinct = run({10: (first, first)}, 5)
    assert tries == [(s, True) for s in range(10, 21)] + [(s, False) for s in range(11, 21)]
    assert seeds == [10, None, None, None, None] and layouts == [first, None, None, None, None]
    assert distinct == [True, False, False, False, False]
    # nothing at all: no layout, no seed
    layouts, seeds, distinct = run({}, 1)
    assert tries == [(10, True), (10, False)] and layouts == [None] and seeds == [None]
    assert distinct == [False]


LONG_ROW = Path(__file__).resolve().parents[1] / "diagnostics" / "solve" / "W906-variants-in-a-long-boundary.lay"


def test_variants_that_repeat_one_another_are_flagged_and_the_suggested_boundary_frees_them():
    from layoutdsl.api import lint_source, read_source

    # a row of five rooms, each with a door to the next, one room deep: every arrangement is
    # the row or its mirror (its snapshot shows the whole message)
    spec, _ = lint_source(read_source(str(LONG_ROW)))
    options = SolveOptions(time_limit=10, quiet=True)
    result = compile_variants(spec, 3, seed=0, options=options, workers=1)
    assert all(layout is not None for layout in result.layouts)
    assert result.distinct == [True, False, False]
    assert max(difference(layout_centres(a), layout_centres(b))
               for a in result.layouts for b in result.layouts) < 0.3
    [warning] = result.diagnostics
    assert warning.code == "W906" and "variants 2 and 3 of 3" in warning.message
    # the help's boundary: the same area at 2:1, and in it the row folds three ways
    w, h = (float(v) for v in warning.help.split("`")[1].split())
    assert w == pytest.approx(2 * h) and w * h == pytest.approx(24 * 4.8, rel=0.02)
    folded = compile_variants(replace(spec, boundary=Boundary(w, h)), 3, seed=0, options=options, workers=1)
    assert folded.distinct == [True, True, True] and folded.diagnostics == ()
    centres = [layout_centres(layout) for layout in folded.layouts]
    assert min(difference(a, b) for i, a in enumerate(centres) for b in centres[i + 1:]) >= 0.3


def test_new_arrangements_on_two_workers_are_those_of_one(tmp_path):
    # outcomes are taken in seed order whichever worker finishes first
    spec = tree_spec()
    options = SolveOptions(time_limit=20, quiet=True)
    one = compile_variants(spec, 3, seed=4, options=options, workers=1)
    two = compile_variants(spec, 3, seed=4, options=options, workers=2)
    assert one.seeds == two.seeds
    assert [layout.rooms for layout in one.layouts] == [layout.rooms for layout in two.layouts]


def test_blocks_sharing_a_room_are_joined_and_solved_together():
    from _specs import adjacent, room

    from layoutdsl.compile.construct import JOINED_MAX_ROOMS, _joined_blocks, block_templates
    from layoutdsl.syntax.ast import Spec

    a, b, c = frozenset("SAB"), frozenset("SCD"), frozenset("XYZ")
    assert _joined_blocks([a, b, c]) == [frozenset("SABCD"), c]
    # a join beyond the cap leaves the block on its own
    big = frozenset(f"Q{i}" for i in range(JOINED_MAX_ROOMS)) | {"S"}
    assert _joined_blocks([big, a]) == [big, a]

    # the bow tie of two triangles sharing the hall S, with a room hanging off A: the two
    # triangles come back as one template in which both rings close around S
    rooms = (room("S", 8.0, 5.0), room("A", 4.0, 3.0), room("B", 4.0, 3.0),
             room("C", 4.0, 3.0), room("D", 4.0, 3.0), room("T", 3.0, 3.0))
    adjacencies = tuple(adjacent(x, y) for x, y in
                        [("S", "A"), ("A", "B"), ("B", "S"), ("S", "C"), ("C", "D"), ("D", "S"),
                         ("A", "T")])
    spec = Spec("bowtie-tail", rooms, Boundary(30.0, 30.0), adjacencies)
    (template,) = block_templates(spec, seed=1, deadline=time.monotonic() + 30)
    assert set(template) == set("SABCD")
    joined = spec.restricted_to(frozenset("SABCD"), "joined")
    assert verify(joined, rects_to_layout(joined, template)) == []


def test_a_corridor_is_drawn_long_enough_for_the_rooms_on_it():
    from _specs import adjacent, room

    from layoutdsl.compile.construct import _with_long_sides
    from layoutdsl.compile.generate import FRONTAGE_USE, RoomSizes, drawn_sides
    from layoutdsl.syntax.ast import Spec

    # a 10 m corridor with twelve 4 m offices: their short sides need ~46 m of its perimeter
    rooms = (room("C", 10.0, 2.0, rtype="C", var=0.8),) + tuple(room(f"R{i}", 5.0, 4.0) for i in range(12))
    spec = Spec("hub", rooms, Boundary(60.0, 60.0), tuple(adjacent("C", f"R{i}") for i in range(12)))
    sides = drawn_sides(spec)
    corridor = RoomSizes.of(rooms[0])
    need = sum(sides[f"R{i}"][1] for i in range(12)) / FRONTAGE_USE
    long_side, short_side = sides["C"]
    # as long as its rooms need, or as long as its bounds allow
    assert long_side == pytest.approx(min(corridor.hi_long, need / 2 - short_side))
    assert long_side > 10.0
    # a block containing the corridor is solved with that length as its least long side
    lengthened = _with_long_sides(spec, {"C": long_side})
    c = lengthened.rooms[0]
    assert c.min_w == pytest.approx(long_side) and c.min_w <= c.max_w
    assert c.min_h == rooms[0].min_h
    # rooms that are not corridors keep their bounds
    assert lengthened.rooms[1:] == rooms[1:]
    # in a boundary the rooms' targets nearly fill, the corridor keeps its drawn length
    dense = replace(spec, boundary=Boundary(17.0, 17.0))
    assert drawn_sides(dense)["C"][0] < 10.0


def test_rooms_hanging_off_a_rung_get_the_space_beside_it():
    from _specs import ladder_spec

    from layoutdsl.compile.construct import _hanging_areas, block_spec, hard_violations
    from layoutdsl.compile.generate import cycle_blocks, drawn_sides
    from layoutdsl.compile.ladders import ladder_template

    spec = ladder_spec()
    (block,) = cycle_blocks(spec)
    ring = block_spec(spec, block)
    sides = drawn_sides(spec)
    hanging = _hanging_areas(spec, block, {}, sides)
    # the office on each rung is all that hangs off the ladder: its drawn area, on its rung
    assert hanging == pytest.approx({**{r: 0.0 for r in block},
                                     **{f"K{i}": sides[f"R{i}"][0] * sides[f"R{i}"][1] for i in range(3)}})
    for seed in range(4):
        rects = ladder_template(ring, random.Random(seed), {"K1": 40.0, "K2": 30.0})
        assert rects is not None
        assert hard_violations(ring.restricted_to(frozenset(rects), "ladder"), rects) == []
        along = 0 if rects["A"][2] > rects["A"][3] else 1  # the rails' axis
        gap = min(max(rects[k][2:]) for k in ("K0", "K1", "K2"))
        rungs = sorted(("K0", "K1", "K2"), key=lambda k: rects[k][along])
        # the rung with the most hanging off it is at an end, the rails flush with it: its
        # rooms take the ladder's open end
        assert "K1" in (rungs[0], rungs[-1])
        start = min(rects[r][along] for r in ("A", "B"))
        end = max(rects[r][along] + rects[r][2 + along] for r in ("A", "B"))
        outer = rects["K1"][along] if rungs[0] == "K1" else rects["K1"][along] + rects["K1"][2 + along]
        assert outer == pytest.approx(start if rungs[0] == "K1" else end)
        # the strips beside K2 (to the next rung either way) hold its 30 m² over the gap
        free = 0.0
        for left, right in zip(rungs, rungs[1:]):
            if "K2" in (left, right):
                free += rects[right][along] - rects[left][along] - rects[left][2 + along]
        assert free * gap >= 30.0 - 1e-6, (seed, free, gap)

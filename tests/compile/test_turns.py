"""Corridors that turn a corner: compile.shapes.with_turns / turned_geometry and the
generator rounds that use them."""

from __future__ import annotations

from layoutdsl.compile.generator import generate
from layoutdsl.compile.shapes import ARM_SHARE, BOX_SHARE, turned_geometry, with_turns
from layoutdsl.layout import lshape
from layoutdsl.layout.geometry import layout_from_rects
from layoutdsl.layout.verify import verify
from layoutdsl.syntax.ast import Boundary, Spec, arm_id

from tests.compile._specs import adjacent, room


def _corridors_k4() -> Spec:
    corridors = [room(f"C{i}", 8.0, 2.0, rtype="C", var=0.4) for i in range(4)]
    pairs = [adjacent(f"C{i}", f"C{j}", kind="i") for i in range(4) for j in range(i + 1, 4)]
    return Spec("k4", tuple(corridors), Boundary(30.0, 30.0), tuple(pairs))


def test_the_corridor_of_an_unmet_door_turns_and_other_rooms_do_not():
    spec = Spec("t", (room("C0", 8.0, 2.0, rtype="C"), room("C1", 8.0, 2.0, rtype="C"), room("R0", 4.0, 4.0),
                      room("R1", 4.0, 4.0)),
                Boundary(30.0, 30.0),
                (adjacent("C0", "C1"), adjacent("C0", "R0"), adjacent("C1", "R0"), adjacent("R0", "R1")))
    turned, made = with_turns(spec, [("C0", "C1"), ("R0", "R1"), ("C1", "R0")])
    # of two corridors the one with more doors (C0 and C1 have two each: the first in spec
    # order); a door with a room that is no corridor turns nothing (the room can move)
    assert made == ["C0"]
    assert {arm.room for arm in turned.arms} == {"C0"}
    again, more = with_turns(turned, [("C0", "C1")])
    assert more == [] and again == turned  # an L is not turned twice


def test_a_turned_corridor_is_split_into_an_l_towards_the_room_it_must_reach():
    # C0 lies along x; R0, the room its unmet door leads to, lies above its right end
    geometry = {"C0": (0.0, 0.0, 10.0, 2.0), "R0": (12.0, 6.0, 4.0, 4.0)}
    turned = turned_geometry(geometry, ["C0"], [("C0", "R0", 4.0)])
    box, arm = turned["C0"], turned[arm_id("C0")]
    assert box == (0.0, 0.0, 10.0 * BOX_SHARE, 2.0)
    # the arm stands on the box's right end and runs up, as wide as the corridor
    assert arm[2] == 2.0 and abs(arm[3] - 10.0 * ARM_SHARE) < 1e-9
    assert abs(arm[0] + arm[2] - (box[0] + box[2])) < 1e-9 and arm[1] == box[1] + box[3]
    assert lshape.join_option(box, arm) == "below:hi"
    assert turned["R0"] == geometry["R0"]


def test_the_generator_turns_a_corridor_where_rectangles_cannot_meet_every_door():
    # four corridors joined pairwise: no four rectangles do it, so the first rounds leave a
    # door unmet and the generator turns a corridor of it (compile would give one an L before
    # generating, structure.with_l_rooms; the generator alone finds it by itself)
    spec = _corridors_k4()
    generated = generate(spec, seed=0)
    assert generated.rects is not None
    assert len(generated.turned) >= 1
    assert {arm.room for arm in generated.spec.arms} == set(generated.turned)
    assert verify(generated.spec, layout_from_rects(generated.spec, generated.rects)) == []
    assert generate(spec, seed=0).rects == generated.rects


def test_a_generator_resumed_after_its_corridors_turned_goes_on_as_one_run():
    # the corridors turn after the second round; a run stopped there and resumed (a variant's
    # quick try, then its full construction) searches the same turned spec from the same state
    spec = _corridors_k4()
    stopped = generate(spec, seed=0, max_rounds=2)
    assert stopped.rects is None and stopped.resume is not None
    assert stopped.resume.turns and stopped.turned
    resumed = generate(spec, seed=0, resume=stopped.resume)
    straight = generate(spec, seed=0)
    assert resumed.rects == straight.rects and resumed.rects is not None
    assert (resumed.rounds, resumed.moves, resumed.turned) == (straight.rounds, straight.moves, straight.turned)

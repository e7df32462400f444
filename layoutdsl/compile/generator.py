"""The generator: one way from a checked spec to a first layout that passes verification.

    structure    -> can the room graph be drawn at all?          (structure.py, shapes.py)
    hints        -> the original plan's boxes, when the spec keeps its arrangement
    initial      -> a sequence pair read off the room graph      (initial.py)
    schedule     -> annealing: moves, one cost, work limits      (schedule.py, moves.py, cost.py)
    growth       -> a found state's rooms grown to their targets (schedule.grown); a layout
                    sized from an unmet state, read back and grown (_regrown)
    sizing       -> relations fixed, SCIP's LP/MIP finds sizes   (layoutdsl.solve.relations)
    verify       -> the independent verifier                     (layoutdsl.layout.verify)

A spec that keeps its arrangement (`hints`, from `import --keep-arrangement`) is sized from
the original boxes first. Otherwise, and when that fails, each round of the schedule anneals
CHAINS sequence-pair states from new spring embeddings of the room graph, with more moves
than the round before; its best state, when within `repair_max_violation_m` of a layout, is
packed (first grown towards the rooms' targets when it is one: the rounds draw rooms small
in a given outline) and handed to the sizing stage (once: a state it failed on is not sized again), whose
relation model meets every door exactly, keeps every other pair a wall apart and brings the
sizes near their targets. After the rounds of
WORK["turn_after_rounds"], a corridor-like room of each door between two of them that the
best state still leaves unmet turns a corner (shapes.with_turns): it becomes an L, split
where it lies, and the rounds go on from there. The first rectangles that pass
`check_start` are the answer. Every limit is work (budgets.WORK); the deadline
only cuts a compile off, and the result then says so (`cut_off`). A generator stopped by
fewer rounds than that (a variant's quick try) returns where it stopped (`Resume`), and
a later call goes on from there.

A spec without a boundary of its own (`boundary.chosen`), or a compile allowed to grow a
given one (`grow_boundary`), treats the outline as a guide only (cost.CHOSEN_OVERFLOW_WEIGHT);
the boundary is then drawn round the annealed packing, never smaller than the one given,
and `Generated.boundary` reports it.
"""

from __future__ import annotations

import random
import time
from dataclasses import dataclass, replace

from layoutdsl.compile import initial, schedule, shapes
from layoutdsl.compile.moves import traded
from layoutdsl.compile.budgets import WORK
from layoutdsl.compile.representation import Rooms
from layoutdsl.layout import lshape
from layoutdsl.layout.difference import difference, rect_centres
from layoutdsl.layout.geometry import Rect, rooms_between
from layoutdsl.solve.relations import (
    RepairLimits,
    boxed_problem,
    hint_geometry,
    perturbed_hint_geometry,
    problem_of,
    repair,
)
from layoutdsl.syntax.ast import Spec

HINT_SHRINKS: tuple[bool | float, ...] = (False, True)
"""Hint geometries in the order tried: the original boxes, then boxes shrunk to target."""

BOUNDARY_MARGIN = 1.0
"""Share of slack (1.0 = none) of a boundary drawn round an annealed packing; the sizing
stage may use only what the packing used."""


@dataclass(frozen=True)
class Generated:
    """What the generator found: rectangles (None: nothing within its work limits), the spec
    they are for (its boundary may have been chosen or grown), and how much work it took."""

    rects: dict[str, Rect] | None
    spec: Spec
    source: str
    """'hints' or 'annealed' (or '' without rectangles)."""
    rounds: int = 0
    moves: int = 0
    cut_off: bool = False
    """The wall clock cut the generator off before its work limits."""
    grown: tuple[float, float] | None = None
    """(width, height) of a boundary grown beyond the spec's (None: not grown)."""
    unmet: tuple[tuple[str, str, float], ...] = ()
    """Without rectangles: the doors the closest annealed arrangement left unmet, (room,
    room, metres) worst first; they say where the room graph is hard to draw."""
    between: tuple[tuple[str, ...], ...] = ()
    """Without rectangles, one per door of `unmet`: the rooms (an L's arm by its arm id)
    that lay between its two rooms in the closest arrangement, the one that covers most of
    the gap first: what the door would have to reach round."""
    away: tuple[tuple[str, float], ...] = ()
    """Without rectangles: the rooms that must open to the outside (onB) the closest
    arrangement left inside, (room, metres from the outside) furthest first."""
    overflow: tuple[float, float] = (0.0, 0.0)
    """Without rectangles: metres the closest arrangement stuck out of a given boundary,
    along x and y."""
    turned: tuple[str, ...] = ()
    """Corridor-like rooms the generator made L-shaped (shapes.with_turns): `spec` has
    their arms."""
    resume: Resume | None = None
    """Without rectangles, when the rounds ran out (not the clock): where the schedule
    stopped, so `generate(..., resume=...)` goes on with the next round instead of doing
    the same rounds again."""
    origin: Origin | None = None
    """With annealed (or derived) rectangles: the state they were sized from, from which
    `derive` makes new arrangements near this one."""


@dataclass(frozen=True)
class Origin:
    """The state an annealed layout was sized from, and the doors each turn of corridors
    was made for (replayed, as in Resume, since a Spec does not cross processes)."""

    turns: tuple[tuple[tuple[str, str], ...], ...]
    state: tuple


@dataclass(frozen=True)
class Resume:
    """Where a generator stopped by its round limit: everything the rounds after it read.
    Resumed, the rounds give what one longer run would have given (same seeds, same
    states), so a variant's quick try and its full construction do no round twice."""

    turns: tuple[tuple[tuple[str, str], ...], ...]
    """The doors each turn of corridors was made for (shapes.with_turns), in order: the
    spec the rounds searched is the given one with these turns made again (a Resume
    crosses process boundaries, and a Spec does not pickle)."""
    rounds: int
    moves: int
    best: schedule.Found | None
    carried: tuple | None
    """The state the turned corridors were laid in, for the next round's first chain."""
    sized: frozenset
    """States the sizing stage already failed on."""
    rng_state: tuple


def generate(spec: Spec, *, seed: int = 0, deadline: float | None = None, use_hints: bool = True,
             perturb_hints: bool = False, grow_boundary: bool = False,
             max_rounds: int | None = None, resume: Resume | None = None) -> Generated:
    """A first layout of the spec (see the module docstring). `perturb_hints`: the hints'
    boxes moved a little first (variants that stay near the original plan); `max_rounds`:
    fewer rounds than budgets.WORK's (variants try another seed sooner); `resume`: the
    `Generated.resume` of an earlier call with the same spec and seed and fewer rounds,
    whose rounds are not made again."""
    if spec.boundary is None or not spec.rooms:
        return Generated(None, spec, "")
    limits = _limits(deadline)
    rng = random.Random(seed)
    drawn = lshape.seeds_spec(spec)
    rounds = max_rounds if max_rounds is not None else WORK["max_rounds"]
    if resume is not None:
        rng.setstate(resume.rng_state)
        return _annealed(spec, drawn, rng, seed, limits, grow_boundary, rounds, resume)
    if use_hints and hint_geometry(drawn) is not None:
        found = _from_hints(spec, drawn, rng, seed, replace(limits, round_nodes=WORK["hint_round_nodes"]),
                            perturb_hints)
        if found is not None:
            return Generated(found, spec, "hints")
    return _annealed(spec, drawn, rng, seed, limits, grow_boundary, rounds)


def _from_hints(spec: Spec, drawn: Spec, rng: random.Random, seed: int, limits: RepairLimits,
                perturb: bool) -> dict[str, Rect] | None:
    geometries = [perturbed_hint_geometry(drawn, rng)] if perturb else []
    geometries += [hint_geometry(drawn, shrink=shrink) for shrink in HINT_SHRINKS]
    crossing = lshape.crossings(spec) if spec.arms else None
    for geometry in geometries:
        if time.monotonic() >= limits.deadline:
            return None
        geometry = _with_pinned_points(spec, geometry)
        problem, rebox = problem_of(spec), None
        if spec.arms:
            geometry = lshape.seed_arms(spec, geometry, rng, hints=True)
            problem = boxed_problem(spec, geometry, crossing)
            rebox = lambda rects: boxed_problem(spec, rects, crossing)  # noqa: E731
        rects = repair(problem, geometry, limits, seed, local=True, rebox=rebox)
        if rects is not None:
            return rects
    return None


def _annealed(spec: Spec, drawn: Spec, rng: random.Random, seed: int, limits: RepairLimits,
              grow_boundary: bool, max_rounds: int, resume: Resume | None = None) -> Generated:
    boundary = spec.boundary
    assert boundary is not None
    outline = (boundary.w, boundary.h)
    soft = grow_boundary or boundary.chosen
    # what the rounds search: the spec, its drawn spec (an L's arm a room) and their rooms;
    # a corridor that turns a corner (shapes.with_turns) changes all three
    current, turned = _replayed(spec, resume.turns if resume is not None else (), outline, soft, drawn)
    best: list = []
    carried: list = []
    done_rounds = moves = 0
    # states the sizing stage already failed on: a round whose chains all end where they
    # started (chain 0 starts from the best state) hands the same state back, and its
    # sizing would fail the same way again (measured: 17 s of cml_synth_121's 48)
    sized: set[tuple] = set()
    turns: list[tuple[tuple[str, str], ...]] = []
    if resume is not None:
        best = [resume.best] if resume.best is not None else []
        carried = [resume.carried] if resume.carried is not None else []
        done_rounds, moves, turns, sized = resume.rounds, resume.moves, list(resume.turns), set(resume.sized)

    def starts(round_index: int, chain: int):
        # the first chain of a later round goes on from the best state so far (longer, so
        # it can leave its local minimum), or from the state its corridors turned in; the
        # others start from new embeddings
        if chain == 0 and best:
            return best[0].state
        if chain == 0 and carried:
            return carried[0]
        # new starts alternate between the plain embedding and the one with entrances
        # pulled outside: on the hardest graphs the start decides, and each kind draws
        # graphs the other does not (docs/generator.md, "Two kinds of start")
        pulled = (round_index + chain) % 2 == 1
        return initial.initial_state(current.drawn, current.rooms, _embedding_seed(seed, round_index, chain), pulled)

    def ended(cut_off: bool = False) -> Generated:
        resume = None if cut_off else Resume(tuple(turns), done_rounds, moves, best[0] if best else None,
                                             carried[0] if carried else None, frozenset(sized),
                                             rng.getstate())
        if not best:
            return Generated(None, current.spec, "", done_rounds, moves, cut_off=cut_off, turned=tuple(turned),
                             resume=resume)
        away, overflow = current.rooms.outside_shortfall(best[0].state)
        unmet = current.rooms.unmet_doors(best[0].state)
        geometry = current.rooms.geometry(best[0].state)
        return Generated(None, current.spec, "", done_rounds, moves, cut_off=cut_off,
                         unmet=tuple(unmet), between=tuple(tuple(rooms_between(geometry, a, b)) for a, b, _m in unmet),
                         away=tuple(away), overflow=overflow, turned=tuple(turned), resume=resume)

    for found in schedule.rounds(lambda _round: current.rooms, starts, seed, limits.deadline, max_rounds,
                                 first_round=done_rounds):
        if found is None:
            return ended(cut_off=True)
        done_rounds += 1
        moves += found.moves
        if not best or found.rank < best[0].rank:
            best[:] = [found]
        key = (tuple(turned), b"".join(part.tobytes() for part in found.state))
        if found.violation <= WORK["repair_max_violation_m"] and key not in sized:
            sized.add(key)
            layout = _sized_found(current, found, soft, f"{seed}:{found.round}", rng, seed, limits)
            if layout is not None:
                rects, target = layout
                return Generated(rects, target, "annealed", done_rounds, moves, grown=_grown(target, boundary),
                                 turned=tuple(turned), origin=Origin(tuple(turns), found.state))
            if time.monotonic() >= limits.deadline:
                return ended(cut_off=True)
        if found.round in WORK["turn_after_rounds"]:
            # the doors still unmet are those a corridor's straight run cannot reach: such a
            # corridor turns a corner for the rounds that follow, from where it lay
            doors = current.rooms.unmet_doors(best[0].state)
            turn = tuple(door[:2] for door in doors)
            turned_spec, made = shapes.with_turns(current.spec, list(turn))
            if made:
                geometry = shapes.turned_geometry(current.rooms.geometry(best[0].state), made, doors)
                current = _Searched.of(turned_spec, lshape.seeds_spec(turned_spec), outline, soft)
                turned += made
                turns.append(turn)
                best.clear()
                carried[:] = [current.rooms.state_of(geometry)]
    return ended()


def derive(spec: Spec, origin: Origin, *, seed: int, deadline: float | None = None,
           grow_boundary: bool = False) -> Generated:
    """A new arrangement near a found one: its state (`origin`, from `Generated.origin`)
    kicked by WORK["derive_trades"] random trades of two rooms (moves.traded), then one
    chain of annealing from a twentieth of the rounds' start temperature, cool enough to
    keep most of the layout and warm enough to mend what the trades broke. A chain that
    meets every door again (WORK["derive_walk_m"]) but stays within derive_min_difference
    (layout.difference) of the origin is kicked again from where it ended, up to
    WORK["derive_steps"] chains: a walk away from the origin, one met state at a time. The
    first state within repair_max_violation_m of a layout and at least derive_min_difference
    from the origin is sized like a round's; otherwise there are no rectangles, and another
    seed is another walk. A run is work-limited like `generate`: the same spec, origin and
    seed give the same rectangles.

    Variants use it once a seed has found a layout: a derived arrangement costs a few chains
    and a short sizing, where a new seed on a plan with cycles needs 3-8 rounds."""
    if spec.boundary is None or not spec.rooms:
        return Generated(None, spec, "")
    limits = _limits(deadline)
    deadline = limits.deadline
    boundary = spec.boundary
    outline = (boundary.w, boundary.h)
    soft = grow_boundary or boundary.chosen
    current, turned = _replayed(spec, origin.turns, outline, soft)
    rng = random.Random(f"derive:{seed}")
    origin_geometry = current.rooms.geometry(origin.state)
    chain_moves = WORK["derive_moves_per_room"] * len(current.rooms.ids)
    state, moves = origin.state, 0
    for _step in range(WORK["derive_steps"]):
        found = schedule.one_chain(current.rooms, traded(state, WORK["derive_trades"], rng),
                                   rng.randrange(2**31), chain_moves, deadline, WORK["derive_temperature"])
        if found is None:
            return Generated(None, current.spec, "", 1, moves, cut_off=True, turned=tuple(turned))
        moves += found.moves
        if found.violation <= WORK["repair_max_violation_m"] and _difference(
                origin_geometry, current.rooms.geometry(found.state)) >= WORK["derive_min_difference"]:
            # not regrown: of office_floorplanMAIN's 25 derived variants none gained room area
            # from it, and it cost 9 % of the variants a minute (7.3 against 8.0)
            layout = _sized_found(current, found, soft, f"derive:{seed}", rng, seed, limits,
                                  rounds=WORK["derive_repair_rounds"], regrow=False)
            if layout is not None:
                rects, target = layout
                return Generated(rects, target, "derived", 1, moves, grown=_grown(target, boundary),
                                 turned=tuple(turned), origin=Origin(origin.turns, found.state))
            break
        if found.score <= WORK["derive_walk_m"]:
            state = found.state
    return Generated(None, current.spec, "", 1, moves, cut_off=time.monotonic() >= deadline,
                     turned=tuple(turned))


def _sized_found(current: _Searched, found: schedule.Found, soft: bool, key: str, rng: random.Random,
                 seed: int, limits: RepairLimits, rounds: int = WORK["repair_rounds"],
                 regrow: bool = True) -> tuple[dict[str, Rect], Spec] | None:
    """(rectangles, the spec they are sized for) of a round's or a derived arrangement's
    best state: grown first (`_grown_first`), the state as found should that not size,
    and (`regrow`) a layout sized from a state too far to grow grown after all
    (`_regrown`); None when neither sizes or the deadline passed. `key` seeds the growth."""
    for state in _grown_first(current, found, soft, key, limits.deadline):
        geometry = current.rooms.geometry(state)
        target = _drawn_round(current.spec, geometry) if soft else current.spec
        rects = _sized(target, geometry, rng, seed, limits, rounds=rounds)
        if rects is not None:
            if regrow and state is found.state and not soft:
                rects = _regrown(current, rects, key, rng, seed, limits, rounds) or rects
            return rects, target
        if time.monotonic() >= limits.deadline:
            break
    return None


def _regrown(current: _Searched, rects: dict[str, Rect], key: str, rng: random.Random, seed: int,
             limits: RepairLimits, rounds: int) -> dict[str, Rect] | None:
    """A layout sized from a state too far from one to grow (so its rooms stayed at the
    rounds' small sides), grown after all: read back as a state (Rooms.state_of_layout),
    its doors met again by one cool chain with the rooms held at their sized sides, grown
    towards the targets (schedule.grown) and sized again. None when a step fails before any
    growth or the second sizing gives less room area."""
    rooms = current.rooms
    if any(room_id not in rects for room_id in rooms.ids):
        return None
    start = rooms.state_of_layout(rects)
    _p, _q, _turned, long_side, short_side = start
    held = rooms.grown_towards({room_id: (long_side[i], short_side[i]) for i, room_id in enumerate(rooms.ids)},
                               1.0, WORK["grow_floor"])
    draw = random.Random(f"regrow:{key}")
    mended = schedule.one_chain(held, held.fitted(start), draw.randrange(2**31),
                                WORK["grow_moves_per_room"] * len(rooms.ids), limits.deadline,
                                WORK["grow_temperature"], zero_stop=0.0, met=WORK["grow_tolerance_m"])
    if mended is None or mended.violation > WORK["grow_tolerance_m"]:
        return None
    grown = schedule.grown(rooms, current.targets, mended.state, draw.randrange(2**31), limits.deadline)
    if grown is mended.state:
        return None
    again = _sized(current.spec, rooms.geometry(grown), rng, seed, limits, rounds=rounds)
    if again is None or _area(again) <= _area(rects):
        return None
    return again


def _area(rects: dict[str, Rect]) -> float:
    return sum(w * h for _x, _y, w, h in rects.values())


def _grown_first(current: _Searched, found: schedule.Found, soft: bool, key: str,
                 deadline: float) -> list:
    """The states to size, in order: `found` grown towards the rooms' targets
    (schedule.grown), then `found` itself should the grown one not size. The rounds draw
    rooms smaller than their targets in an outline the spec gives; with a boundary drawn
    round the packing they are drawn at their targets, and only a state at a layout grows."""
    if soft or found.violation > WORK["grow_tolerance_m"]:
        return [found.state]
    grown = schedule.grown(current.rooms, current.targets, found.state,
                           random.Random(f"grow:{key}").randrange(2**31), deadline)
    return [found.state] if grown is found.state else [grown, found.state]


def _limits(deadline: float | None) -> RepairLimits:
    return RepairLimits(deadline=time.monotonic() + 3600.0 if deadline is None else deadline,
                        round_nodes=WORK["repair_round_nodes"], final_nodes=WORK["final_nodes"])


def _grown(target: Spec, boundary) -> tuple[float, float] | None:
    """(width, height) of the boundary drawn round a packing when beyond the spec's own."""
    drawn = target.boundary
    if drawn is not None and (drawn.w > boundary.w + 1e-9 or drawn.h > boundary.h + 1e-9):
        return (drawn.w, drawn.h)
    return None


def _difference(a: dict[str, Rect], b: dict[str, Rect]) -> float:
    return difference(rect_centres(a), rect_centres(b))


def _replayed(spec: Spec, turns, outline: tuple[float, float], soft: bool,
              drawn: Spec | None = None) -> tuple[_Searched, list[str]]:
    """What the rounds search after the given turns of corridors (shapes.with_turns) made
    again on `spec` (`drawn`: its drawn spec, when already known), and the rooms they
    turned."""
    turned: list[str] = []
    for doors in turns:
        spec, made = shapes.with_turns(spec, list(doors))
        turned += made
    if turns or drawn is None:
        drawn = lshape.seeds_spec(spec)
    return _Searched.of(spec, drawn, outline, soft), turned


@dataclass(frozen=True)
class _Searched:
    """The spec the rounds search, its drawn spec (lshape.seeds_spec) and their Rooms."""

    spec: Spec
    drawn: Spec
    rooms: Rooms
    targets: dict[str, tuple[float, float]]
    """Each drawn room's (long, short) sides at full size, which a found state grows towards."""

    @staticmethod
    def of(spec: Spec, drawn: Spec, outline: tuple[float, float], soft: bool) -> _Searched:
        targets = initial.drawn_sides(drawn, outline, shrink=1.0)
        sides = targets if soft else initial.drawn_sides(drawn, outline)
        return _Searched(spec, drawn, Rooms.of(drawn, sides, outline, outline_given=not soft,
                                               crossings=lshape.crossings(spec)), targets)


def _sized(spec: Spec, geometry: dict[str, Rect], rng: random.Random, seed: int,
           limits: RepairLimits, rounds: int = WORK["repair_rounds"]) -> dict[str, Rect] | None:
    """The sizing stage on a packed geometry (of the drawn spec: an L's arm a room): a few
    rounds only, since another round of annealing is cheaper than a long repair."""
    limits = replace(limits, max_rounds=rounds, max_stalls=WORK["repair_stalls"])
    geometry = _with_pinned_points(spec, geometry)
    problem = problem_of(spec)
    if spec.arms:
        geometry = lshape.seed_arms(spec, geometry, rng)
        problem = boxed_problem(spec, geometry)
    return repair(problem, geometry, limits, seed, free_defects=True)


def _drawn_round(spec: Spec, geometry: dict[str, Rect]) -> Spec:
    """The spec with its boundary drawn round the packing, never smaller than its own."""
    boundary = spec.boundary
    assert boundary is not None
    right = max(x + w for x, _y, w, _h in geometry.values())
    top = max(y + h for _x, y, _w, h in geometry.values())
    width = max(boundary.w if not boundary.chosen else 0.0, round(right * BOUNDARY_MARGIN, 3))
    height = max(boundary.h if not boundary.chosen else 0.0, round(top * BOUNDARY_MARGIN, 3))
    return replace(spec, boundary=replace(boundary, w=width, h=height))


def _with_pinned_points(spec: Spec, geometry: dict[str, Rect]) -> dict[str, Rect]:
    """Each room with a position (or connection) moved so its rectangle covers the point:
    the relations then already put it where the hard constraint wants it."""
    moved = dict(geometry)
    for room_id, (px, py) in initial.pinned_points(spec).items():
        if room_id in moved:
            _x, _y, w, h = moved[room_id]
            moved[room_id] = (px - w / 2, py - h / 2, w, h)
    return moved


def _embedding_seed(seed: int, round_index: int, chain: int) -> int:
    return random.Random(f"embedding:{seed}:{round_index}:{chain}").randrange(2**31)


__all__ = ["Generated", "Origin", "Resume", "derive", "generate"]

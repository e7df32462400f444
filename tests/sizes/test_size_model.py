"""The room-size model: the shipped file is what refitting gives, its laws are what the
samples say (checked with numpy, independently of the fitting code), typical sizes are
deterministic and drawn sizes reproducible, and every RoomSize is a consistent room line."""

from __future__ import annotations

import json
import math
import random
import statistics
from pathlib import Path

import numpy as np
import pytest

from layoutdsl.sizes import ModelError, RoomSize, load_model
from layoutdsl.sizes.fit import RoomSample, fit_corridor, fit_folder, fit_law, fit_model, plan_kind
from layoutdsl.sizes.model import MIN_SAMPLES, QUANTILES, SHIPPED_MODEL, SizeModel, room_size_from_target

ROOT = Path(__file__).resolve().parents[2]
EXAMPLES = ROOT / "examples" / "floorplans"
CORPUS = ROOT.parent / "shared" / "floorplans"
needs_corpus = pytest.mark.skipif(
    len(list(CORPUS.glob("*.xml"))) != 24,
    reason=f"the 24-plan corpus the shipped model was fitted on is not at {CORPUS} (CI provides it)",
)
MODEL = load_model()


@needs_corpus
def test_refitting_the_corpus_gives_the_shipped_model_byte_for_byte() -> None:
    assert fit_folder(CORPUS).dumps() == SHIPPED_MODEL.read_text(encoding="utf-8")


def test_the_shipped_model_says_what_it_was_fitted_on() -> None:
    assert MODEL.corpus == "floorplans"
    assert set(MODEL.kinds) == {"school", "office"}
    assert len(MODEL.kind("school").plans) == 17 and len(MODEL.kind("office").plans) == 7
    assert all(p.startswith("school_") for p in MODEL.kind("school").plans)


def test_fitting_the_bundled_examples_is_deterministic_and_per_kind() -> None:
    first, second = fit_folder(EXAMPLES), fit_folder(EXAMPLES)
    assert first.dumps() == second.dumps()
    assert set(first.kinds) == {plan_kind(p) for p in EXAMPLES.glob("*.xml")} == {"school", "office"}
    # the same JSON reads back into the same model
    assert SizeModel.from_json(json.loads(first.dumps())).dumps() == first.dumps()


def test_a_law_is_the_log_normal_and_quantiles_of_its_samples() -> None:
    rng = np.random.default_rng(3)
    sides = rng.uniform(2, 12, size=(40, 2))
    rooms = [RoomSample("school", "R", "X", max(a, b), min(a, b), 1) for a, b in sides]
    law = fit_law(rooms)
    areas = sides[:, 0] * sides[:, 1]
    assert law.rooms == 40
    assert law.log_area_mean == pytest.approx(np.log(areas).mean())
    assert law.log_area_sd == pytest.approx(np.log(areas).std(ddof=1))
    ratios = np.maximum(sides[:, 0], sides[:, 1]) / np.minimum(sides[:, 0], sides[:, 1])
    assert law.aspect_quantiles == pytest.approx(tuple(np.quantile(ratios, QUANTILES)))
    assert law.typical_area == pytest.approx(math.exp(np.log(areas).mean()))


def test_the_corridor_law_is_a_least_squares_line_over_doors() -> None:
    doors = [1, 2, 4, 6, 8, 10]
    lengths = [5.0, 9.0, 14.0, 20.5, 24.0, 33.0]
    corridors = [RoomSample("school", "C", "CORRIDOR", length, 3.0, d) for d, length in zip(doors, lengths)]
    law = fit_corridor(corridors)
    slope, intercept = np.polyfit(doors, lengths, 1)
    assert (law.length_per_door, law.length_intercept) == pytest.approx((slope, intercept))
    assert math.exp(law.log_width_mean) == pytest.approx(3.0)
    longer = [law.typical(d)[0] for d in (2, 6, 12)]
    assert longer == sorted(longer) and longer[0] < longer[-1]


def check_room_line(size: RoomSize, rtype: str) -> None:
    """An independent check that the eight numbers make a room the linter accepts."""
    assert 1.0 <= size.min_w <= size.target_w <= size.max_w
    assert 1.0 <= size.min_h <= size.target_h <= size.max_h
    ar = max(size.target_w, size.target_h) / min(size.target_w, size.target_h)
    assert 1.0 <= size.min_ar <= ar <= size.max_ar
    assert max(size.max_w, size.max_h) >= 0.9 + 2 * 0.2  # a door between two walls


@pytest.mark.parametrize("kind", ["school", "office"])
def test_every_label_gets_a_consistent_typical_size(kind: str) -> None:
    model = MODEL.kind(kind)
    for label, law in model.by_label.items():
        rtype = model.label_types[label]
        size = MODEL.room_sizes(kind, rtype, label)
        check_room_line(size, rtype)
        assert MODEL.room_sizes(kind, rtype, label) == size  # deterministic
        if law.rooms >= MIN_SAMPLES:
            assert size.target_w * size.target_h == pytest.approx(law.typical_area, rel=0.01, abs=0.05)
            assert f"label {label} (" in size.source


def test_fallbacks_go_label_then_type_then_kind() -> None:
    school = MODEL.kind("school")
    few = next(label for label, law in school.by_label.items() if law.rooms < MIN_SAMPLES)
    assert "type R" in MODEL.room_sizes("school", "R", few).source
    assert "type R" in MODEL.room_sizes("school", "R", "ROOM 7").source  # an unnamed CSV code
    assert MODEL.room_sizes("school", "R", "ROOM 7").as_tuple() == MODEL.room_sizes("school", "R", "NEVER SEEN").as_tuple()
    assert "label CLASSROOM" in MODEL.room_sizes("school", "R", "classroom").source  # labels ignore case
    with pytest.raises(ModelError, match="unknown building kind `hospital`"):
        MODEL.room_sizes("hospital", "R", "WARD")


def test_drawn_sizes_are_reproducible_and_follow_the_law() -> None:
    draws = [MODEL.sample_room_sizes("school", "R", "CLASSROOM", random.Random(seed)) for seed in range(400)]
    again = [MODEL.sample_room_sizes("school", "R", "CLASSROOM", random.Random(seed)) for seed in range(400)]
    assert draws == again
    assert len({d.as_tuple() for d in draws}) > 350
    for size in draws:
        check_room_line(size, "R")
    law = MODEL.kind("school").by_label["CLASSROOM"]
    areas = [d.target_w * d.target_h for d in draws]
    # the median of a log-normal is exp(mu); 400 draws land within 10 % of it
    assert statistics.median(areas) == pytest.approx(law.typical_area, rel=0.1)
    assert law.area_min * 0.98 <= min(areas) and max(areas) <= law.area_max * 1.02


def test_a_corridor_with_more_doors_is_longer() -> None:
    lengths = [MODEL.room_sizes("school", "C", "CORRIDOR", doors=d).target_w for d in (1, 5, 15)]
    assert lengths == sorted(lengths) and lengths[-1] > lengths[0] + 20
    drawn = MODEL.sample_room_sizes("school", "C", "CORRIDOR", random.Random(1), doors=15)
    assert drawn == MODEL.sample_room_sizes("school", "C", "CORRIDOR", random.Random(1), doors=15)
    assert "corridor with 15 doors" in drawn.source


def test_a_tiny_target_still_holds_a_door() -> None:
    size = room_size_from_target(0.5, 0.5, "R")
    check_room_line(size, "R")


def test_door_width_and_openings_come_from_the_corpus() -> None:
    assert MODEL.door("school") == pytest.approx(0.9)
    assert MODEL.adjacency_kind("school", "R", "C") == "e"
    share = MODEL.kind("school").implicit_share
    assert 0 < share["CC"] < 1  # corridors are joined by doors and by openings


def test_fit_model_takes_any_list_of_plans(capsys) -> None:
    plans = sorted(EXAMPLES.glob("school_*.xml"))[:2]
    model = fit_model(plans, corpus="two")
    assert set(model.kinds) == {"school"} and len(model.kind("school").plans) == 2
    with pytest.raises(ValueError, match="no plan imported"):
        fit_model([])


def test_a_broken_model_file_is_a_model_error(tmp_path: Path) -> None:
    bad = tmp_path / "m.json"
    bad.write_text("{")
    with pytest.raises(ModelError, match="not JSON"):
        load_model(bad)
    bad.write_text('{"format": "something else"}')
    with pytest.raises(ModelError, match="not a size model"):
        load_model(bad)


@pytest.mark.parametrize("kind", ["school", "office"])
def test_typical_sides_lie_within_the_corpus_sides(kind: str) -> None:
    """The typical room (median area at median aspect) has a long and a short side inside the
    10-90 % range of the long and short sides measured on the corpus, for every label with
    20 rooms or more: area and aspect ratio treated as independent still give real rooms."""
    model = MODEL.kind(kind)
    checked = 0
    for label, law in model.by_label.items():
        if law.rooms < 20:
            continue
        size = MODEL.room_sizes(kind, model.label_types[label], label)
        long_side, short_side = max(size.target_w, size.target_h), min(size.target_w, size.target_h)
        assert law.long_quantiles[1] <= long_side <= law.long_quantiles[5], label
        assert law.short_quantiles[1] <= short_side <= law.short_quantiles[5], label
        checked += 1
    assert checked >= 4


def _ks(a: list[float], b: list[float]) -> float:
    """Two-sample Kolmogorov-Smirnov distance, computed here rather than by the model's code."""
    return float(np.max(np.abs(
        np.searchsorted(np.sort(a), np.sort(np.concatenate([a, b])), side="right") / len(a)
        - np.searchsorted(np.sort(b), np.sort(np.concatenate([a, b])), side="right") / len(b)
    )))  # fmt: skip


@needs_corpus
@pytest.mark.parametrize("kind", ["school", "office"])
def test_drawing_every_corpus_room_again_gives_the_corpus_areas(kind: str) -> None:
    """Each real room's sizes drawn again from its group (kind, type, label, door count): the
    areas follow the real ones (KS distance 0.046 for both kinds at seed 0) and add up to
    the real total within 5 %."""
    from layoutdsl.sizes.fit import measure_plan

    rng = random.Random(0)
    real, drawn = [], []
    for path in sorted(CORPUS.glob(f"{kind}_*.xml")):
        sample, _ = measure_plan(path)
        for room in sample.rooms:
            real.append(room.long * room.short)
            size = MODEL.sample_room_sizes(kind, room.rtype, room.label, rng, doors=room.doors)
            drawn.append(size.target_w * size.target_h)
    assert _ks(real, drawn) < 0.1
    assert sum(drawn) == pytest.approx(sum(real), rel=0.05)

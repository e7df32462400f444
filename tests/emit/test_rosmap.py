"""The ROS map: a P5 PGM of the shared grid and map_server's YAML."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from _emit_support import CASES, load_case

from layoutdsl.emit import write_outputs
from layoutdsl.emit.raster import rasterize_layout

MAP_SERVER_KEYS = {"image", "resolution", "origin", "negate", "occupied_thresh", "free_thresh", "mode"}


def _read_pgm(path: Path) -> np.ndarray:
    data = path.read_bytes()
    fields: list[bytes] = []
    pos = 0
    while len(fields) < 4:
        while data[pos : pos + 1].isspace():
            pos += 1
        if data[pos : pos + 1] == b"#":
            pos = data.index(b"\n", pos) + 1
            continue
        end = pos
        while not data[end : end + 1].isspace():
            end += 1
        fields.append(data[pos:end])
        pos = end
    pos += 1  # the single whitespace after maxval
    magic, width, height, maxval = fields
    assert magic == b"P5" and int(maxval) == 255
    pixels = np.frombuffer(data[pos:], dtype=np.uint8)
    assert pixels.size == int(width) * int(height)
    return pixels.reshape(int(height), int(width))


def _read_yaml(path: Path) -> dict[str, object]:
    # map_server YAML is flat `key: value`; parse it by hand (no YAML dependency)
    import json

    result: dict[str, object] = {}
    for line in path.read_text().splitlines():
        key, _, value = line.partition(":")
        result[key.strip()] = json.loads(value.strip())
    return result


@pytest.mark.parametrize("case", CASES, ids=[c.name for c in CASES])
def test_map_is_the_shared_grid_with_map_server_metadata(case: Path, tmp_path: Path) -> None:
    layout = load_case(case)
    paths = write_outputs(layout, tmp_path, "plan", ["map"], resolution=0.05)
    assert [p.name for p in paths] == ["plan.pgm", "plan.yaml"]
    pixels = _read_pgm(tmp_path / "plan.pgm")
    grid = rasterize_layout(layout, 0.05)
    assert np.array_equal(pixels == 0, grid.occupied)
    assert set(np.unique(pixels)) <= {0, 254}
    meta = _read_yaml(tmp_path / "plan.yaml")
    assert set(meta) <= MAP_SERVER_KEYS
    assert meta["image"] == "plan.pgm" and (tmp_path / meta["image"]).exists()
    assert meta["resolution"] == 0.05 and meta["negate"] == 0
    assert meta["occupied_thresh"] == 0.65 and meta["free_thresh"] == 0.196
    # origin = the lower-left pixel's pose, so a room centre lands on a free pixel
    ox, oy, yaw = meta["origin"]
    assert (ox, oy) == pytest.approx(grid.origin) and yaw == 0
    for room in layout.rooms:
        x, y = room.centre
        row = pixels.shape[0] - 1 - int((y - oy) / 0.05)
        col = int((x - ox) / 0.05)
        # map_server: p = (255 - v) / 255 below free_thresh is free
        assert (255 - pixels[row, col]) / 255 < meta["free_thresh"]


def test_map_resolution_option_changes_the_grid(tmp_path: Path) -> None:
    layout = load_case(CASES[0])
    write_outputs(layout, tmp_path / "fine", "plan", ["map"], resolution=0.025)
    write_outputs(layout, tmp_path / "coarse", "plan", ["map"], resolution=0.1)
    fine = _read_pgm(tmp_path / "fine" / "plan.pgm")
    coarse = _read_pgm(tmp_path / "coarse" / "plan.pgm")
    assert fine.shape[1] == pytest.approx(coarse.shape[1] * 4, abs=4)
    assert _read_yaml(tmp_path / "fine" / "plan.yaml")["resolution"] == 0.025

"""Outputs are written whole or not at all."""

from __future__ import annotations

import os
from pathlib import Path

import pytest
from _emit_support import load_case

import layoutdsl.emit as emit
from layoutdsl.emit.atomic import write_files_atomic, write_text_atomic
from layoutdsl.emit import EMITTERS, EmitError, write_outputs


SMALL = Path(__file__).parent / "small_office"


def _listing(folder: Path) -> list[str]:
    return sorted(p.name for p in folder.iterdir()) if folder.exists() else []


def test_all_formats_write_the_documented_files(tmp_path: Path) -> None:
    paths = write_outputs(load_case(SMALL), tmp_path, "plan")
    assert [p.name for p in paths] == ["plan.xml", "plan.png", "plan.world", "plan.world.png", "plan.pgm", "plan.yaml"]
    assert _listing(tmp_path) == sorted(p.name for p in paths)  # no temporary files left
    assert all(p.stat().st_size > 0 for p in paths)


def test_each_emitter_writes_only_its_own_files(tmp_path: Path) -> None:
    layout = load_case(SMALL)
    written = {name: [p.name for p in emitter(layout, tmp_path / name, "plan")] for name, emitter in EMITTERS.items()}
    assert written == {
        "xml": ["plan.xml"],
        "png": ["plan.png"],
        "svg": ["plan.svg"],
        "world": ["plan.world", "plan.world.png"],
        "map": ["plan.pgm", "plan.yaml"],
        "mjcf": ["plan.mjcf.xml"],
        "sdf": ["plan.sdf"],
        "gltf": ["plan.glb"],
    }


def test_unknown_format_names_the_valid_ones_and_writes_nothing(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match="unknown output format `stage`.*xml, png, world, map"):
        write_outputs(load_case(SMALL), tmp_path, "plan", ["xml", "stage"])
    assert _listing(tmp_path) == []


def test_formats_may_be_a_comma_separated_string(tmp_path: Path) -> None:
    paths = write_outputs(load_case(SMALL), tmp_path, "plan", "xml,map")
    assert [p.name for p in paths] == ["plan.xml", "plan.pgm", "plan.yaml"]
    with pytest.raises(EmitError, match="no output format"):
        write_outputs(load_case(SMALL), tmp_path, "plan", "")


def test_an_emitter_failing_midway_leaves_no_file(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    def broken(*_args, **_kwargs):
        raise RuntimeError("renderer crashed")

    from layoutdsl.emit import rosmap

    monkeypatch.setattr(rosmap, "render", broken)  # the last format of the default order
    with pytest.raises(RuntimeError, match="renderer crashed"):
        write_outputs(load_case(SMALL), tmp_path / "out", "plan")
    assert _listing(tmp_path / "out") == []


def test_a_write_failing_midway_rolls_back_and_restores_old_files(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    out = tmp_path / "out"
    out.mkdir()
    (out / "plan.xml").write_text("previous run\n")
    real_replace = os.replace
    calls = {"n": 0}

    def flaky_replace(src, dst):
        calls["n"] += 1
        if calls["n"] == 4:  # after three files are already in place
            raise OSError(28, "No space left on device")
        return real_replace(src, dst)

    monkeypatch.setattr(os, "replace", flaky_replace)
    with pytest.raises(OSError, match="No space left"):
        write_outputs(load_case(SMALL), out, "plan")
    monkeypatch.setattr(os, "replace", real_replace)
    assert _listing(out) == ["plan.xml"]
    assert (out / "plan.xml").read_text() == "previous run\n"


def test_single_file_write_replaces_whole(tmp_path: Path) -> None:
    target = tmp_path / "a.txt"
    write_text_atomic(target, "one\n")
    write_text_atomic(target, "two\n")
    assert target.read_text() == "two\n" and _listing(tmp_path) == ["a.txt"]


def test_write_set_rejects_a_path_given_twice(tmp_path: Path) -> None:
    with pytest.raises(ValueError, match="twice"):
        write_files_atomic({tmp_path / "a": b"1", tmp_path / "sub" / ".." / "a": b"2"})
    assert _listing(tmp_path) == []


def test_emit_module_exports_the_interface() -> None:
    assert set(EMITTERS) == {"xml", "png", "svg", "world", "map", "mjcf", "sdf", "gltf"}
    assert emit.DEFAULT_FORMATS == ("xml", "png", "world", "map")
    assert callable(emit.write_outputs) and issubclass(EmitError, ValueError)


def test_a_portal_to_an_unknown_room_is_refused_before_writing(tmp_path: Path) -> None:
    from dataclasses import replace

    layout = load_case(SMALL)
    broken = replace(layout, portals=(replace(layout.portals[0], b="R99"),))
    with pytest.raises(EmitError, match="unknown room `R99`"):
        write_outputs(broken, tmp_path, "plan")
    assert _listing(tmp_path) == []


def test_a_bitmap_too_large_for_memory_is_refused(tmp_path: Path) -> None:
    with pytest.raises(EmitError, match="coarser resolution"):
        write_outputs(load_case(SMALL), tmp_path, "plan", ["map"], resolution=0.0002)
    assert _listing(tmp_path) == []

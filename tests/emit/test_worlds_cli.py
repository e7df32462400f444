"""The 3D formats through `write_outputs` and `layoutdsl compile`: opt-in, all or nothing, clear errors."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import pytest

from _emit_support import ROOT, load_case
from layoutdsl.diagnostics import exitcodes
from layoutdsl.emit import EmitError, WORLD_3D_FORMATS, write_outputs
from spec_cases import SMALL_LAY

SMALL = Path(__file__).parent / "small_office"

# Runs the CLI with trimesh made unimportable, as in an install without the sim extra.
WITHOUT_TRIMESH = "import sys; sys.modules['trimesh'] = None; from layoutdsl.cli import main; sys.exit(main(sys.argv[1:]))"


def _listing(folder: Path) -> list[str]:
    return sorted(p.name for p in folder.iterdir()) if folder.exists() else []


def test_3d_formats_write_their_files_beside_the_2d_ones(tmp_path: Path) -> None:
    paths = write_outputs(load_case(SMALL), tmp_path, "plan", ["world", *WORLD_3D_FORMATS])
    assert [p.name for p in paths] == ["plan.world", "plan.world.png", "plan.mjcf.xml", "plan.sdf", "plan.glb"]


def test_a_3d_emitter_failing_leaves_no_file_of_the_set(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    from layoutdsl.emit import gltf

    def broken(*_args, **_kwargs):
        raise RuntimeError("mesh export crashed")

    monkeypatch.setattr(gltf, "render", broken)
    with pytest.raises(RuntimeError, match="mesh export crashed"):
        write_outputs(load_case(SMALL), tmp_path / "out", "plan", "xml,mjcf,sdf,gltf")
    assert _listing(tmp_path / "out") == []


def test_gltf_without_the_mesh_library_is_refused_before_writing(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setitem(sys.modules, "trimesh", None)
    with pytest.raises(EmitError, match=r"needs the optional mesh library trimesh: pip install 'layoutdsl\[sim\]'"):
        write_outputs(load_case(SMALL), tmp_path, "plan", "mjcf,gltf")
    assert _listing(tmp_path) == []
    # the other 3D formats need no extra
    assert [p.name for p in write_outputs(load_case(SMALL), tmp_path, "plan", "mjcf,sdf")] == ["plan.mjcf.xml", "plan.sdf"]


def test_bad_wall_height_is_refused(tmp_path: Path) -> None:
    with pytest.raises(EmitError, match="wall height"):
        write_outputs(load_case(SMALL), tmp_path, "plan", "sdf", wall_height=0.0)
    assert _listing(tmp_path) == []


def _compile(*args: str, script: str | None = None) -> subprocess.CompletedProcess:
    command = [sys.executable, "-c", script, "compile"] if script else [sys.executable, "-m", "layoutdsl", "compile"]
    return subprocess.run([*command, *args], cwd=ROOT, capture_output=True, text=True, timeout=120)


def test_compile_emits_3d_worlds_with_options(tmp_path: Path) -> None:
    spec = tmp_path / "office.lay"
    spec.write_text(SMALL_LAY)
    done = _compile(str(spec), "-o", str(tmp_path / "out"), "-q", "--emit", "mjcf,sdf,gltf",
                    "--wall-height", "3", "--no-robot")
    assert done.returncode == exitcodes.OK, done.stderr
    assert _listing(tmp_path / "out") == ["office.glb", "office.layout.json", "office.mjcf.xml", "office.sdf"]
    scene = (tmp_path / "out" / "office.mjcf.xml").read_text()
    assert "rangefinder" not in scene and 'size="' in scene and ' 1.5"' in scene  # half of 3 m


def test_compile_gltf_without_the_extra_is_a_one_line_usage_error(tmp_path: Path) -> None:
    done = _compile("specs/office_small.lay", "-o", str(tmp_path / "out"), "--emit", "gltf", script=WITHOUT_TRIMESH)
    assert done.returncode == exitcodes.USAGE
    assert done.stderr.strip().count("\n") == 0, done.stderr
    assert "pip install 'layoutdsl[sim]'" in done.stderr and "Traceback" not in done.stderr
    assert not (tmp_path / "out").exists()


def test_compile_refuses_an_absurd_wall_height_before_solving(tmp_path: Path) -> None:
    done = _compile("specs/office_small.lay", "-o", str(tmp_path / "out"), "--emit", "sdf", "--wall-height", "500")
    assert done.returncode == exitcodes.USAGE and "--wall-height" in done.stderr
    assert not (tmp_path / "out").exists()

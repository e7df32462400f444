"""The glTF walls mesh back in the layout's frame, for the tests that read a written `.glb`."""

from __future__ import annotations

import numpy as np


def walls_in_layout_frame(scene):
    """The walls mesh with its node transform applied, turned back to z-up (x, y, z) = (X, -Z, Y)."""
    import trimesh  # the sim extra: callers skip without it

    transform, name = scene.graph["walls"]
    mesh = scene.geometry[name].copy()
    mesh.apply_transform(transform)
    x, y, z = mesh.vertices.T
    return trimesh.Trimesh(np.column_stack([x, -z, y]), mesh.faces, process=False)

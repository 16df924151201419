"""monge.blender and examples/blender/monge_mesh.py with the bpy module
(Blender as a Python module, from the package index)."""

import pathlib
import subprocess
import sys

import numpy as np
import pytest

bpy = pytest.importorskip("bpy")  # scripts/pytest.sh installs it where the package index has it

import monge
import monge.blender
import measure_np as mnp
from conftest import example

DUPIN = example("fig12-dupin-theta30.json")
SCRIPT = pathlib.Path(__file__).resolve().parents[3] / "examples" / "blender" / "monge_mesh.py"
FLOAT32 = 1e-7  # Blender stores single-precision coordinates


def vectors(collection, key, n):
    out = np.zeros(n * 3, dtype=np.float32)
    collection.foreach_get(key, out)
    return out.reshape(n, 3).astype(float)


def test_the_mesh_in_blender():
    mesh = monge.generate(monge.Design.from_file(DUPIN))
    obj = monge.blender.add_mesh(mesh, name="dupin")
    data = obj.data
    n = mesh.rows * mesh.cols
    assert obj.name in bpy.context.scene.collection.objects
    assert len(data.vertices) == n and len(data.polygons) == (mesh.rows - 1) * (mesh.cols - 1)
    v = vectors(data.vertices, "co", n)
    assert np.abs(v - mesh.vertices.reshape(-1, 3)).max() <= FLOAT32 * mnp.scale(mesh.vertices)
    faces = np.array([list(p.vertices) for p in data.polygons])
    assert np.array_equal(faces, mesh.faces)
    axes = vectors(data.attributes["node_axis"].data, "vector", n)
    assert np.abs(axes - mesh.normals.reshape(-1, 3)).max() <= FLOAT32
    # the custom normals at every corner are the node axes of its vertex
    corners = np.array([loop.vertex_index for loop in data.loops])
    normals = vectors(data.corner_normals, "vector", len(data.loops))
    # (Blender keeps custom normals compressed: measured 3.5e-5)
    assert np.abs(normals - mesh.normals.reshape(-1, 3)[corners]).max() <= 1e-4
    gauss = monge.blender.add_mesh(mesh, name="gauss", gauss=True)
    g = vectors(gauss.data.vertices, "co", n)
    assert np.abs(np.linalg.norm(g, axis=1) - 1).max() <= FLOAT32


def test_conical_meshes_carry_face_normals():
    mesh = monge.generate(monge.Design.from_file(example("fig13-conical.json")))
    data = monge.blender.add_mesh(mesh, name="conical").data
    fn = vectors(data.attributes["face_normal"].data, "vector", len(data.polygons))
    assert np.abs(fn - mesh.face_normals.reshape(-1, 3)).max() <= FLOAT32
    assert "node_axis" not in data.attributes
    with pytest.raises(monge.MeshError, match="no node axes"):
        monge.blender.add_mesh(mesh, gauss=True)
    with pytest.raises(monge.MeshError, match="needs a monge.Mesh"):
        monge.blender.add_mesh(mesh.vertices)


def test_the_example_script_saves_a_blend_file(tmp_path):
    out = tmp_path / "dupin.blend"
    p = subprocess.run([sys.executable, str(SCRIPT), DUPIN, str(out)], capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    assert "monge: 41 × 33 circular mesh" in p.stdout
    bpy.ops.wm.open_mainfile(filepath=str(out))
    objects = {o.name: o for o in bpy.data.objects}
    assert {"monge", "monge Gauss map"} <= set(objects)
    mesh = monge.generate(monge.Design.from_file(DUPIN))
    v = vectors(objects["monge"].data.vertices, "co", mesh.rows * mesh.cols)
    assert np.abs(v - mesh.vertices.reshape(-1, 3)).max() <= FLOAT32 * mnp.scale(mesh.vertices)


def test_a_trimmed_result_in_blender(trimmed_result):
    """add_mesh(mesh, trimmed=…): the panels of a mesh trimmed to a target's outline, as
    Blender polygons with the face attribute `cut`; no Gauss map of its own."""
    mesh, t = trimmed_result["mesh"], trimmed_result["trimmed"]
    obj = monge.blender.add_mesh(mesh, name="trimmed", trimmed=t)
    data = obj.data
    n = len(t["vertices"])
    assert len(data.vertices) == n and len(data.polygons) == len(t["faces"])
    assert [list(p.vertices) for p in data.polygons] == [list(f) for f in t["faces"]]
    v = np.asarray(t["vertices"])
    assert np.abs(vectors(data.vertices, "co", n) - v).max() <= FLOAT32 * mnp.scale(v)
    cut = [bool(x.value) for x in data.attributes["cut"].data]
    assert cut == [bool(c) for c in t["cut"]] and 0 < sum(cut) < len(cut)
    with pytest.raises(monge.MeshError, match="no Gauss map of its own"):
        monge.blender.add_mesh(mesh, gauss=True, trimmed=t)

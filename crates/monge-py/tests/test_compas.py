"""monge.compas: to a COMPAS mesh and back, measured with COMPAS's own
geometry and numpy."""

import numpy as np
import pytest

pytest.importorskip("compas")  # an optional dependency (the wheel's extra `compas`)

import compas.geometry
from compas.datastructures import Mesh as CompasMesh

import monge
import monge.compas
import measure_np as mnp
from conftest import example

DUPIN = example("fig12-dupin-theta30.json")


def test_round_trip_of_a_circular_mesh(cli_mesh):
    mesh = monge.generate(monge.Design.from_file(DUPIN))
    c = monge.compas.to_mesh(mesh)
    assert c.number_of_vertices() == mesh.rows * mesh.cols
    assert c.number_of_faces() == (mesh.rows - 1) * (mesh.cols - 1)
    assert all(len(c.face_vertices(f)) == 4 for f in c.faces())
    assert c.attributes["kind"] == "circular" and c.attributes["theta_deg"] == 30
    ref = cli_mesh(DUPIN)
    v, n = monge.compas.from_mesh(c)
    assert np.abs(v - ref["vertices"]).max() <= 1e-12 * mnp.scale(v)
    assert np.abs(n - ref["normals"]).max() <= 1e-12
    assert monge.check(v, normals=n)["max_error"] <= 1e-9
    # As README.md writes it: the arrays straight into check, normals second.
    assert monge.check(*monge.compas.from_mesh(c)) == monge.check(v, normals=n)
    # COMPAS's own face geometry: every face is flat (compas.geometry.is_coplanar)
    for f in list(c.faces())[::37]:
        assert compas.geometry.is_coplanar(c.face_coordinates(f), tol=1e-9)
    # node axes are unit vectors at each vertex
    for key in list(c.vertices())[::53]:
        assert abs(compas.geometry.length_vector(c.vertex_attribute(key, "node_axis")) - 1) <= 1e-12


def test_serialised_meshes_come_back(tmp_path):
    mesh = monge.generate(monge.Design.from_file(example("fig13-freeform.json")))
    path = str(tmp_path / "mesh.json")
    monge.compas.to_mesh(mesh).to_json(path)
    v, n = monge.compas.from_mesh(CompasMesh.from_json(path))
    assert np.array_equal(v, mesh.vertices) and np.array_equal(n, mesh.normals)


def test_conical_meshes_carry_face_normals():
    mesh = monge.generate(monge.Design.from_file(example("fig13-conical.json")))
    c = monge.compas.to_mesh(mesh)
    v, n = monge.compas.from_mesh(c)
    assert n is None and np.array_equal(v, mesh.vertices)
    assert monge.check(*monge.compas.from_mesh(c), kind="conical")["conical"]["value"] <= 1e-9
    for f, expected in zip(c.faces(), mesh.face_normals.reshape(-1, 3)):
        assert np.abs(np.cross(c.face_normal(f), expected)).max() <= 1e-9  # COMPAS's normal, parallel
        assert np.array_equal(c.face_attribute(f, "normal"), expected)


def test_errors():
    with pytest.raises(monge.MeshError, match="needs a monge.Mesh"):
        monge.compas.to_mesh(np.zeros((2, 2, 3)))
    plain = CompasMesh.from_vertices_and_faces([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], [[0, 1, 2, 3]])
    with pytest.raises(monge.MeshError, match="no `rows` attribute"):
        monge.compas.from_mesh(plain)
    plain.attributes.update(rows=2, cols=3)
    with pytest.raises(monge.MeshError, match="4 vertices, not rows × cols = 2 × 3 = 6"):
        monge.compas.from_mesh(plain)
    plain.attributes.update(rows=2, cols=2)
    with pytest.raises(monge.MeshError, match="vertex 0 of the COMPAS mesh has no grid position"):
        monge.compas.from_mesh(plain)
    for key in plain.vertices():
        plain.vertex_attributes(key, ["i", "j"], [0, 0])
    with pytest.raises(monge.MeshError, match="do not cover the grid"):
        monge.compas.from_mesh(plain)


def test_a_trimmed_result_is_its_planar_panels(trimmed_result):
    """to_mesh(mesh, trimmed=…): the panels of a mesh trimmed to a target's outline, each
    a COMPAS face as the polygon it is, flat by COMPAS's own measure, with its cut."""
    t = trimmed_result["trimmed"]
    c = monge.compas.to_mesh(trimmed_result["mesh"], trimmed=t)
    assert c.number_of_vertices() == len(t["vertices"]) and c.number_of_faces() == len(t["faces"])
    assert c.attributes["trimmed"] is True
    v = np.asarray(t["vertices"])
    for key, face, cut, (i, j) in zip(c.faces(), t["faces"], t["cut"], t["from"]):
        assert c.face_vertices(key) == list(face)
        assert c.face_attributes(key, ["cut", "i", "j"]) == [cut, i, j]
        assert compas.geometry.is_coplanar(c.face_coordinates(key), tol=1e-9)
        assert np.array_equal(np.array(c.face_coordinates(key)), v[face])
    assert 0 < sum(c.face_attribute(key, "cut") for key in c.faces()) < c.number_of_faces()
    assert max(len(c.face_vertices(key)) for key in c.faces()) > 4

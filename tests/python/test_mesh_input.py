"""Bad input to Mesh, load_mesh, intersect and occluded: one clear Python exception each, never a
crash; and the inputs that are accepted though not in the preferred layout."""
import numpy as np
import pytest

import raylane
from conftest import model_or_skip

VERTICES = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], dtype=np.float32)
TRIANGLES = np.array([[0, 1, 2]], dtype=np.int32)


@pytest.mark.parametrize("vertices, triangles, message", [
    (VERTICES[:, :2], TRIANGLES, r"vertices: shape \(3, 2\), expected \(N, 3\)"),
    (VERTICES.ravel(), TRIANGLES, r"vertices: shape \(9,\), expected \(N, 3\)"),
    (VERTICES, TRIANGLES[:, :2], r"triangles: shape \(1, 2\), expected \(N, 3\)"),
    (VERTICES.astype(np.float64), TRIANGLES, r"vertices: dtype float64, expected float32"),
    (VERTICES, TRIANGLES.astype(np.float32), r"triangles: dtype float32, expected an integer"),
    (VERTICES, np.array([[0, 1, 3]]), r"triangles: row 0 holds index 3, outside 0 \.\. 2"),
    (VERTICES, np.array([[0, -1, 2]]), r"triangles: row 0 holds index -1, outside 0 \.\. 2"),
    (VERTICES, np.array([[0, 1, 2]], dtype=np.uint64) + np.uint64(2**63),
     r"triangles: row 0 holds index 9223372036854775807, outside 0 \.\. 2"),
    (np.array([[0, 0, 0], [1, np.nan, 0], [0, 1, 0]], dtype=np.float32), TRIANGLES,
     r"vertices: row 1 is not finite"),
    (np.array([[0, 0, 0], [1, 0, 0], [0, np.inf, 0]], dtype=np.float32), TRIANGLES,
     r"vertices: row 2 is not finite"),
    ([[0, 0, 0], [1, 0, 0], [0, 1, 0]], TRIANGLES, r"vertices: expected a NumPy array, got list"),
])
def test_bad_mesh_arrays_raise_one_clear_value_error(vertices, triangles, message):
    with pytest.raises(ValueError, match=message):
        raylane.Mesh(vertices, triangles)


def test_non_contiguous_and_read_only_mesh_arrays_are_accepted():
    vertices = np.asfortranarray(np.vstack([VERTICES, VERTICES + 5]))
    vertices.setflags(write=False)
    triangles = np.array([[0, 9], [1, 9], [2, 9]], dtype=np.uint16).T[:1]  # a strided view
    assert not triangles.flags.c_contiguous
    mesh = raylane.Mesh(vertices, triangles)
    assert mesh.triangle_count == 1
    assert np.array_equal(mesh.vertices, vertices)
    hit = mesh.intersect(np.array([[0.2, 0.2, 1, 0, 0, -1]], dtype=np.float32))
    assert hit["prim"][0] == 0 and hit["t"][0] == 1.0


@pytest.mark.parametrize("call, message", [
    (lambda m: m.intersect(np.zeros((4, 3), np.float32)), r"rays: shape \(4, 3\), expected \(N, 6\)"),
    (lambda m: m.intersect(np.zeros((4, 3), np.float32), np.zeros((5, 3), np.float32)),
     r"origins and directions: 4 and 5 rows, expected the same"),
    (lambda m: m.intersect(np.zeros((4, 3), np.float32), np.zeros((4, 4), np.float32)),
     r"directions: shape \(4, 4\), expected \(N, 3\)"),
    (lambda m: m.occluded(np.zeros((4, 6), np.float32), tmax=np.ones(3, np.float32)),
     r"tmax: 3 values for 4 rays"),
    (lambda m: m.intersect(np.zeros((4, 6), np.complex64)), r"rays: dtype complex64, expected float32"),
    (lambda m: m.intersect(np.zeros((4, 6), np.float32), path="gpu"), r"path: unknown path \"gpu\""),
    (lambda m: m.intersect(np.zeros((4, 6), np.float32), threads=-1), r"threads: -1 is outside"),
])
def test_bad_rays_raise_one_clear_value_error(call, message):
    mesh = raylane.Mesh(VERTICES, TRIANGLES)
    with pytest.raises(ValueError, match=message):
        call(mesh)


def test_a_missing_model_raises_file_not_found(tmp_path):
    with pytest.raises(FileNotFoundError, match="no-such-model.ply"):
        raylane.load_mesh(str(tmp_path / "no-such-model.ply"))
    with pytest.raises(FileNotFoundError, match="not-on-the-path.ply"):
        raylane.load_mesh("not-on-the-path.ply")


def test_a_bad_model_raises_raylane_error_with_file_line_and_reason(tmp_path):
    path = tmp_path / "bad.obj"
    path.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n")
    with pytest.raises(raylane.Error, match=r"bad\.obj:4: ") as e:
        raylane.load_mesh(str(path))
    assert isinstance(e.value, ValueError)
    path = tmp_path / "model.stl"
    path.write_text("solid\n")
    with pytest.raises(raylane.Error, match="unsupported mesh format"):
        raylane.load_mesh(str(path))


def test_a_model_on_the_model_path_loads_by_name():
    model_or_skip("bunny.ply")
    assert raylane.load_mesh("bunny.ply").triangle_count > 60_000

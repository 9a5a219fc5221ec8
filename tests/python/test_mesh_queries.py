"""Mesh.intersect and Mesh.occluded: the packet path against the scalar path (the reference),
ray by ray and bit for bit, on the bunny and the dragon; hand-made cases with known answers."""
import threading

import numpy as np
import pytest

import raylane
from conftest import camera_rays, model_or_skip, random_rays


def quad():
    """The unit square in z = 0 as two triangles, facing +z."""
    vertices = np.array([[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0]], dtype=np.float32)
    triangles = np.array([[0, 1, 2], [0, 2, 3]], dtype=np.int32)
    return raylane.Mesh(vertices, triangles)


def assert_same_hits(a, b):
    assert np.array_equal(a["prim"], b["prim"])
    # bit for bit: t, u and v of the same hit are the same floats
    for key in ("t", "u", "v", "normal"):
        assert np.array_equal(a[key].view(np.uint32), b[key].view(np.uint32)), key


def test_ray_at_a_quad_gives_its_hit():
    mesh = quad()
    origins = np.array([[0.75, 0.25, 2], [0.25, 0.75, 2], [2, 2, 2]], dtype=np.float32)
    directions = np.array([[0, 0, -1], [0, 0, -2], [0, 0, -1]], dtype=np.float32)
    h = mesh.intersect(origins, directions)
    assert h["prim"].dtype == np.int32 and h["t"].dtype == np.float32
    assert list(h["prim"]) == [0, 1, -1]
    assert h["t"][0] == 2.0 and h["t"][1] == 1.0 and np.isinf(h["t"][2])
    assert np.allclose(h["normal"][:2], [[0, 0, 1], [0, 0, 1]])
    assert np.array_equal(h["normal"][2], [0, 0, 0])
    # barycentrics of (0.75, 0.25) in triangle (0, 1, 2): weights of corners 1 and 2
    assert np.allclose([h["u"][0], h["v"][0]], [0.5, 0.25])
    assert list(mesh.occluded(origins, directions)) == [True, True, False]
    assert list(mesh.occluded(origins, directions, tmax=1.5)) == [False, True, False]


def test_tmax_per_ray_and_six_column_rays_give_the_same_answers():
    mesh = quad()
    origins = np.array([[0.5, 0.4, 1], [0.5, 0.4, 1]], dtype=np.float32)
    directions = np.array([[0, 0, -1], [0, 0, -1]], dtype=np.float32)
    h = mesh.intersect(origins, directions, np.array([0.5, 2.0], dtype=np.float32))
    assert list(h["prim"]) == [-1, 0]
    rays = np.hstack([origins, directions])
    assert_same_hits(mesh.intersect(rays), mesh.intersect(origins, directions))
    assert list(mesh.occluded(rays, tmax=0.5)) == [False, False]


@pytest.mark.parametrize("model", ["bunny.ply", "dragon.ply"])
def test_packet_path_equals_scalar_path_on_100k_random_rays(model):
    mesh = raylane.load_mesh(model_or_skip(model))
    origins, directions = random_rays(mesh, 100_000, seed=7)
    scalar = mesh.intersect(origins, directions, path="scalar")
    hits = np.count_nonzero(scalar["prim"] >= 0)
    assert 20_000 < hits < 100_000, "the rays must both hit and miss"
    for coherent in (None, False, True):
        assert_same_hits(mesh.intersect(origins, directions, coherent=coherent), scalar)
    blocked = mesh.occluded(origins, directions, path="scalar")
    assert np.array_equal(blocked, scalar["prim"] >= 0)
    for coherent in (None, False, True):
        assert np.array_equal(mesh.occluded(origins, directions, coherent=coherent), blocked)
    # shadow-like: from just short of each hit back to its origin, t_max below the segment
    t = np.where(scalar["prim"] >= 0, scalar["t"], 1.0)
    short = mesh.occluded(origins, directions, tmax=t * 0.999, path="scalar")
    assert np.array_equal(mesh.occluded(origins, directions, tmax=t * 0.999), short)


@pytest.mark.parametrize("model", ["bunny.ply", "dragon.ply"])
def test_packet_path_equals_scalar_path_on_camera_rays(model):
    mesh = raylane.load_mesh(model_or_skip(model))
    origins, directions = camera_rays(mesh, 320, 240)
    scalar = mesh.intersect(origins, directions, path="scalar")
    assert np.count_nonzero(scalar["prim"] >= 0) > 1000
    for coherent in (None, True, False):
        assert_same_hits(mesh.intersect(origins, directions, coherent=coherent), scalar)
        assert np.array_equal(mesh.occluded(origins, directions, coherent=coherent),
                              scalar["prim"] >= 0)


def test_geometric_normal_faces_the_winding_side():
    mesh = raylane.load_mesh(model_or_skip("bunny.ply"))
    origins, directions = random_rays(mesh, 2000, seed=3)
    h = mesh.intersect(origins, directions)
    hit = h["prim"] >= 0
    tri = mesh.vertices[mesh.triangles[h["prim"][hit]]]
    n = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
    n /= np.linalg.norm(n, axis=1, keepdims=True)
    assert np.allclose(h["normal"][hit], n, atol=1e-5)
    assert np.allclose(np.linalg.norm(h["normal"][hit], axis=1), 1, atol=1e-6)


def test_nan_and_degenerate_rays_are_misses():
    mesh = quad()
    origins = np.array([[np.nan, 0.5, 1], [0.5, 0.5, 1], [0.5, 0.5, 1], [0.5, 0.5, np.inf],
                        [0.5, 0.5, 1]], dtype=np.float32)
    directions = np.array([[0, 0, -1], [0, np.nan, -1], [0, 0, 0], [0, 0, -1], [0, 0, -1]],
                          dtype=np.float32)
    for path in ("packet", "scalar"):
        h = mesh.intersect(origins, directions, path=path)
        assert list(h["prim"]) == [-1, -1, -1, -1, 0]
        assert np.isinf(h["t"][:4]).all()
        assert list(mesh.occluded(origins, directions, path=path)) == [False] * 4 + [True]
    h = mesh.intersect(origins[4:], directions[4:], tmax=np.float32(np.nan))
    assert h["prim"][0] == -1


def test_empty_rays_and_empty_mesh():
    mesh = quad()
    none = np.zeros((0, 3), dtype=np.float32)
    h = mesh.intersect(none, none)
    assert h["t"].shape == (0,) and h["normal"].shape == (0, 3)
    assert mesh.occluded(np.zeros((0, 6), dtype=np.float32)).shape == (0,)
    empty = raylane.Mesh(np.zeros((0, 3), dtype=np.float32), np.zeros((0, 3), dtype=np.int32))
    assert empty.triangle_count == 0
    rays = np.array([[0, 0, 1, 0, 0, -1]], dtype=np.float32)
    assert empty.intersect(rays)["prim"][0] == -1
    assert not empty.occluded(rays)[0]


def test_strided_read_only_and_float64_rays_give_the_same_answers():
    mesh = raylane.load_mesh(model_or_skip("bunny.ply"))
    origins, directions = random_rays(mesh, 5000, seed=11)
    expected = mesh.intersect(origins, directions)
    rays = np.hstack([origins, directions])
    assert_same_hits(mesh.intersect(rays[:, :3], rays[:, 3:]), expected)  # strided views
    wide = np.zeros((5000, 8), dtype=np.float32)
    wide[:, 1:4], wide[:, 4:7] = origins, directions
    assert_same_hits(mesh.intersect(wide[:, 1:4], wide[:, 4:7]), expected)
    fortran = np.asfortranarray(origins)
    read_only = directions.copy()
    read_only.setflags(write=False)
    assert_same_hits(mesh.intersect(fortran, read_only), expected)
    assert_same_hits(mesh.intersect(origins.astype(np.float64), directions.astype(np.float64)),
                     expected)
    reversed_rays = rays[::-1]
    assert_same_hits(mesh.intersect(reversed_rays), {k: v[::-1] for k, v in expected.items()})


def test_two_python_threads_on_one_mesh_get_the_same_answers():
    mesh = raylane.load_mesh(model_or_skip("dragon.ply"))
    origins, directions = random_rays(mesh, 50_000, seed=5)
    expected = mesh.intersect(origins, directions, path="scalar")
    expected_blocked = expected["prim"] >= 0
    results, errors = {}, []

    def work(name):
        try:
            for _ in range(3):
                results[name] = (mesh.intersect(origins, directions),
                                 mesh.occluded(origins, directions))
        except Exception as e:  # reported below, not lost in the thread
            errors.append(e)

    threads = [threading.Thread(target=work, args=(k,)) for k in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors
    for hits, blocked in results.values():
        assert_same_hits(hits, expected)
        assert np.array_equal(blocked, expected_blocked)


def test_mesh_from_arrays_equals_the_loaded_mesh():
    loaded = raylane.load_mesh(model_or_skip("bunny.ply"))
    rebuilt = raylane.Mesh(loaded.vertices, loaded.triangles.astype(np.int64))
    origins, directions = random_rays(loaded, 20_000, seed=2)
    assert_same_hits(rebuilt.intersect(origins, directions), loaded.intersect(origins, directions))


def test_save_rays_writes_an_n_by_6_float32_file(tmp_path):
    origins = np.arange(12, dtype=np.float64).reshape(4, 3)
    directions = -origins
    path = str(tmp_path / "rays.npy")
    raylane.save_rays(path, origins, directions)
    rays = np.load(path)
    assert rays.dtype == np.float32 and rays.shape == (4, 6)
    assert np.array_equal(rays[:, :3], origins) and np.array_equal(rays[:, 3:], directions)


def test_out_arrays_are_written_returned_and_give_the_same_answers():
    mesh = raylane.load_mesh(model_or_skip("bunny.ply"))
    origins, directions = random_rays(mesh, 20_000, seed=3)
    n = len(origins)
    expected = mesh.intersect(origins, directions)
    out = {"t": np.full(n, -7, np.float32), "prim": np.full(n, -7, np.int32),
           "u": np.empty(n, np.float32), "v": np.empty(n, np.float32),
           "normal": np.empty((n, 3), np.float32)}
    arrays = dict(out)
    for _ in range(2):  # a second call into the same arrays gives the same answers
        got = mesh.intersect(origins, directions, out=out)
        assert got is out
        assert all(got[k] is arrays[k] for k in arrays), "the caller's arrays, not new ones"
        assert_same_hits(got, expected)
    # only the arrays asked for are written
    t_only = {"t": np.empty(n, np.float32)}
    assert mesh.intersect(origins, directions, out=t_only) is t_only and list(t_only) == ["t"]
    assert np.array_equal(t_only["t"].view(np.uint32), expected["t"].view(np.uint32))
    occluded = np.zeros(n, bool)
    assert mesh.occluded(origins, directions, out=occluded) is occluded
    assert np.array_equal(occluded, mesh.occluded(origins, directions))
    assert np.array_equal(occluded, expected["prim"] >= 0)


@pytest.mark.parametrize("out, message", [
    ({"t": np.empty(3, np.float64)}, r"out\['t'\]: float64 \(3,\), expected float32 \(3,\)"),
    ({"t": np.empty(4, np.float32)}, r"out\['t'\]: float32 \(4,\), expected float32 \(3,\)"),
    ({"normal": np.empty((3, 3), np.float32).T}, r"out\['normal'\]: not C-contiguous"),
    ({"prim": np.empty(3, np.int64)}, r"out\['prim'\]: int64 \(3,\), expected int32 \(3,\)"),
    ({"depth": np.empty(3, np.float32)}, r"out: unknown key 'depth'"),
    ([np.empty(3, np.float32)], r"out: expected a dict"),
])
def test_bad_out_arrays_raise_one_clear_value_error(out, message):
    origins = np.zeros((3, 3), np.float32)
    directions = np.ones((3, 3), np.float32)
    with pytest.raises(ValueError, match=message):
        quad().intersect(origins, directions, out=out)


def test_a_read_only_or_wrong_occluded_out_array_is_refused():
    origins = np.zeros((3, 3), np.float32)
    directions = np.ones((3, 3), np.float32)
    read_only = np.zeros(3, bool)
    read_only.flags.writeable = False
    with pytest.raises(ValueError, match=r"out: read-only"):
        quad().occluded(origins, directions, out=read_only)
    with pytest.raises(ValueError, match=r"out: uint8 \(3,\), expected bool \(3,\)"):
        quad().occluded(origins, directions, out=np.zeros(3, np.uint8))

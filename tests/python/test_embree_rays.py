"""bench_intersect's ray files. Raylane's hits against Embree's on the same rays:
`bench_intersect --rays FILE.npy --embree-hits OUT.npy` writes Embree's closest hits (t,
primitive, u, v) for rays saved by raylane.save_rays. Two watertight tests may part on rays
that graze an edge, so the rays compared are those whose hit lies away from every edge in both
answers. And the benchmark run on a ray file, with its table."""
import os
import re
import subprocess

import numpy as np
import pytest

import raylane
from conftest import model_or_skip, random_rays

BENCH = os.environ.get("RAYLANE_BENCH_INTERSECT", "")


def away_from_edges(u, v, margin=1e-4):
    return (u > margin) & (v > margin) & (1 - u - v > margin)


@pytest.mark.parametrize("model", ["bunny.ply", "dragon.ply"])
def test_hits_agree_with_embree_on_a_ray_file(tmp_path, model):
    if not BENCH:
        pytest.skip("bench_intersect was not built (Google Benchmark missing)")
    mesh = raylane.load_mesh(model_or_skip(model))
    origins, directions = random_rays(mesh, 100_000, seed=13)
    rays_file, hits_file = str(tmp_path / "rays.npy"), str(tmp_path / "embree.npy")
    raylane.save_rays(rays_file, origins, directions)
    p = subprocess.run([BENCH, "--rays", rays_file, "--mesh", model, "--embree-hits", hits_file],
                       capture_output=True, text=True)
    if p.returncode == 2 and "built without Embree" in p.stderr:
        pytest.skip("bench_intersect was built without Embree")
    assert p.returncode == 0, p.stderr
    embree = np.load(hits_file)
    assert embree.shape == (100_000, 4)
    ours = mesh.intersect(origins, directions)
    e_t, e_prim, e_u, e_v = embree.T
    ours_hit, e_hit = ours["prim"] >= 0, e_prim >= 0
    clean_ours = ours_hit & away_from_edges(ours["u"], ours["v"])
    clean_embree = e_hit & away_from_edges(e_u, e_v)
    # a hit away from the edges in one answer is a hit in the other
    assert np.array_equal(e_hit[clean_ours], np.ones(np.count_nonzero(clean_ours), bool))
    assert np.array_equal(ours_hit[clean_embree], np.ones(np.count_nonzero(clean_embree), bool))
    both = clean_ours & clean_embree
    assert np.count_nonzero(both) > 20_000
    assert np.array_equal(ours["prim"][both], e_prim[both].astype(np.int32))
    rel = np.abs(ours["t"][both] - e_t[both]) / e_t[both]
    assert rel.max() <= 1e-5


def test_bench_intersect_races_a_ray_file_and_prints_its_table(tmp_path):
    if not BENCH:
        pytest.skip("bench_intersect was not built (Google Benchmark missing)")
    mesh = raylane.load_mesh(model_or_skip("bunny.ply"))
    origins, directions = random_rays(mesh, 2000, seed=17)
    rays_file = str(tmp_path / "rays.npy")
    np.save(rays_file, np.hstack([origins, directions]))  # plain numpy.save works too
    p = subprocess.run([BENCH, "--rays", rays_file, "--mesh", "bunny.ply", "--summary",
                        "--benchmark_min_time=0.01", "--benchmark_filter=threads:1/|Build"],
                       capture_output=True, text=True)
    assert p.returncode == 0, p.stderr
    assert f"2000 rays of {rays_file}" in p.stdout
    for query in ("Closest", "Occluded"):
        row = re.search(rf"^\| {query}, 1 thread \|(.*)$", p.stdout, re.M)
        assert row, p.stdout
        figures = [f.strip() for f in row.group(1).split("|") if f.strip()]
        # Scalar, Packet, Block, Stream always; Embree's four when it is built in
        assert all(re.fullmatch(r"[0-9.e+]+", f) for f in figures[:4]), figures
    assert re.search(r"BVH build \(BM_RayFile_Build\): [0-9.]+ ms", p.stdout)

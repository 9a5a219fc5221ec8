#!/usr/bin/python3
"""The Python module's ray queries against the C++ packet path and Embree, on the same rays.

Three ray sets of 1M rays at a mesh (the 100k dragon by default): primary-like rays from a
pinhole camera in 16x16 tiles of 4x4 squares (coherent), random rays from a sphere around the
mesh towards points inside its bounds (incoherent), and shadow-like occlusion queries from the
primary hits towards a directional light. Each set is saved as a ray file and raced by
`bench_intersect --rays FILE` (Raylane's packet path through the same batch function, and
Embree 3's APIs); the Python calls (Mesh.intersect, Mesh.occluded) are timed here, returning
new arrays and writing into out= arrays, a median of 5 after a warm-up, on all threads, in rounds
that alternate with bench_intersect's (3 by default). Then the mesh's BVH build from NumPy arrays (raylane.Mesh) against the C++ build from
the loaded mesh (BM_RayFile_Build).

    PYTHONPATH=build/release/python /usr/bin/python3 bench/python/ray_queries.py \\
        [--bench build/release/bench/bench_intersect] [--mesh dragon.ply] [--rays 1000000] \\
        [--rounds 3]

Prints a Markdown table of Mrays/s (and ms for the build).
"""
import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
import time

import numpy as np

import raylane

HERE = os.path.dirname(os.path.abspath(__file__))
SOURCE_DIR = os.path.normpath(os.path.join(HERE, "..", ".."))


def camera_rays(mesh, count):
    """count primary-like rays (a square image) in 16x16 tiles of 4x4 squares (as the C++
    benchmark orders its primary rays): each 16 consecutive rays are a 4x4 square of pixels."""
    side = int(round(count ** 0.5))
    v = mesh.vertices
    lo, hi = v.min(axis=0), v.max(axis=0)
    centre, size = (lo + hi) / 2, np.linalg.norm(hi - lo)
    eye = centre + np.array([0.3, 0.2, 1.0]) * size
    forward = centre - eye
    forward /= np.linalg.norm(forward)
    right = np.cross(forward, [0.0, 1.0, 0.0])
    right /= np.linalg.norm(right)
    up = np.cross(right, forward)
    ys, xs = np.mgrid[0:side, 0:side]
    tiles = (ys // 16) * ((side + 15) // 16) + xs // 16
    squares = (ys % 16) // 4 * 4 + (xs % 16) // 4
    order = np.lexsort((xs.ravel(), ys.ravel(), squares.ravel(), tiles.ravel()))
    half = np.tan(np.radians(20.0))
    px = ((xs.ravel()[order] + 0.5) / side * 2 - 1) * half
    py = (1 - (ys.ravel()[order] + 0.5) / side * 2) * half
    d = forward + px[:, None] * right + py[:, None] * up
    o = np.broadcast_to(eye, d.shape)
    return np.ascontiguousarray(o, dtype=np.float32), np.ascontiguousarray(d, dtype=np.float32)


def random_rays(mesh, count, seed=1):
    """Rays from a sphere around the mesh's bounds towards random points inside them: most hit,
    some miss, from every direction."""
    rng = np.random.default_rng(seed)
    v = mesh.vertices
    lo, hi = v.min(axis=0), v.max(axis=0)
    centre, radius = (lo + hi) / 2, np.linalg.norm(hi - lo)
    d = rng.normal(size=(count, 3))
    o = centre + radius * d / np.linalg.norm(d, axis=1, keepdims=True)
    t = lo + rng.random((count, 3)) * (hi - lo)
    return o.astype(np.float32), (t - o).astype(np.float32)


def shadow_rays(mesh, count):
    """From the primary hits (in their tile order, repeated up to count) towards a directional
    light, offset along the normal on the lit side."""
    o, d = camera_rays(mesh, count)
    h = mesh.intersect(o, d)
    hit = h["prim"] >= 0
    n = h["normal"][hit]
    n = np.where((np.einsum("ij,ij->i", n, d[hit]) > 0)[:, None], -n, n)
    size = np.linalg.norm(mesh.vertices.max(axis=0) - mesh.vertices.min(axis=0))
    p = o[hit] + h["t"][hit][:, None] * d[hit] + 1e-4 * size * n
    reps = -(-count // len(p))
    p = np.tile(p, (reps, 1))[:count]
    light = np.array([1.0, 1.0, -1.0], dtype=np.float32) / np.sqrt(3.0)
    return p.astype(np.float32), np.ascontiguousarray(np.broadcast_to(light, p.shape))


def median_seconds(call, repeats=5):
    call()  # warm-up
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        call()
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def bench_intersect(bench, rays_file, mesh, threads, query, isa, min_time):
    """Median Mrays/s of each contender of bench_intersect --rays (5 repetitions of at least
    `min_time` seconds) on the instruction set `isa` (Raylane's and Embree's: RAYLANE_ISA)."""
    out = subprocess.run(
        [bench, "--rays", rays_file, "--mesh", mesh, "--benchmark_repetitions=5",
         f"--benchmark_min_time={min_time}",
         "--benchmark_report_aggregates_only=true", "--benchmark_format=json",
         f"--benchmark_filter=BM_RayFile_({query}_(Packet|Block|Stream|Embree[A-Za-z0-9]*)_"
         f"[^/]+/threads:{threads}/|Build)"],
        env=dict(os.environ, RAYLANE_ISA=isa), check=True, capture_output=True,
        text=True).stdout
    rates, build_ms = {}, None
    for b in json.loads(out)["benchmarks"]:
        if b.get("aggregate_name") != "median":
            continue
        name = b["run_name"]
        if name.startswith("BM_RayFile_Build"):
            build_ms = b["real_time"]
        else:
            rates[name.split("_")[3].split("/")[0]] = b["rays/s"] * 1e-6
    return rates, build_ms


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--bench", default=os.path.join(SOURCE_DIR, "build", "release", "bench",
                                                    "bench_intersect"))
    ap.add_argument("--mesh", default="dragon.ply")
    ap.add_argument("--rays", type=int, default=1_000_000)
    ap.add_argument("--rounds", type=int, default=3,
                    help="rounds of Python and C++ measurements, in turn (default 3)")
    ap.add_argument("--min-time", type=float, default=0.5,
                    help="seconds each bench_intersect repetition runs at least (default 0.5)")
    args = ap.parse_args()
    os.environ.setdefault("RAYLANE_MODEL_PATH", os.path.join(SOURCE_DIR, "..", "shared", "models"))
    threads = os.cpu_count()

    mesh = raylane.load_mesh(args.mesh)
    vertices, triangles = mesh.vertices, mesh.triangles
    build_py = median_seconds(lambda: raylane.Mesh(vertices, triangles)) * 1e3

    sets = [("primary (coherent)", "Closest", camera_rays(mesh, args.rays)),
            ("random (incoherent)", "Closest", random_rays(mesh, args.rays)),
            ("shadow (occluded)", "Occluded", shadow_rays(mesh, args.rays))]
    isa = raylane.instruction_sets()
    print(f"{args.mesh}: {mesh.triangle_count} triangles; {threads} threads; Mrays/s, medians "
          f"over {args.rounds} rounds of medians of 5; Raylane {raylane.__version__}, packet "
          f"{isa['in_use']}, width {isa['packet_width']}; load average "
          f"{os.getloadavg()[0]:.1f} at the start\n")
    print("| rays | count | Python | Python, out= | C++ packet (best of Packet, Block, Stream) "
          "| Embree's best | Python / C++ | Python out= / C++ | Python out= / Embree |")
    print("|---|---:|---:|---:|---:|---:|---:|---:|---:|")
    build_cpp = []
    details = []
    with tempfile.TemporaryDirectory() as folder:
        for label, query, (o, d) in sets:
            n = len(o)
            rays_file = os.path.join(folder, "rays.npy")
            raylane.save_rays(rays_file, o, d)
            # rounds of the Python call and bench_intersect in turn, so that a busy spell of a
            # shared machine falls on both; the medians over the rounds are reported
            python_rates, out_rates, cpp_rates, embree_rates, all_rates = [], [], [], [], []
            # out=: the result arrays made once and written by every call (no allocation)
            if query == "Closest":
                out = {"t": np.empty(n, np.float32), "prim": np.empty(n, np.int32),
                       "u": np.empty(n, np.float32), "v": np.empty(n, np.float32),
                       "normal": np.empty((n, 3), np.float32)}
            else:
                out = np.empty(n, bool)
            for _ in range(args.rounds):
                if query == "Closest":
                    seconds = median_seconds(lambda: mesh.intersect(o, d))
                    seconds_out = median_seconds(lambda: mesh.intersect(o, d, out=out))
                else:
                    seconds = median_seconds(lambda: mesh.occluded(o, d))
                    seconds_out = median_seconds(lambda: mesh.occluded(o, d, out=out))
                python_rates.append(n / seconds * 1e-6)
                out_rates.append(n / seconds_out * 1e-6)
                rates, build_ms = bench_intersect(args.bench, rays_file, args.mesh, threads, query,
                                                  isa["in_use"], args.min_time)
                if build_ms is not None:
                    build_cpp.append(build_ms)
                cpp_rates.append(max(rates.get(k, 0.0) for k in ("Packet", "Block", "Stream")))
                embree_rates.append(max((v for k, v in rates.items() if k.startswith("Embree")),
                                        default=0.0))
                all_rates.append(rates)
            python_rate = statistics.median(python_rates)
            out_rate = statistics.median(out_rates)
            cpp = statistics.median(cpp_rates)
            embree = statistics.median(embree_rates)
            print(f"| {label} | {n} | {python_rate:.2f} | {out_rate:.2f} | {cpp:.2f} | "
                  f"{embree:.2f} | {python_rate / cpp:.2f}x | {out_rate / cpp:.2f}x | "
                  + (f"{out_rate / embree:.2f}x |" if embree else "— |"), flush=True)
            details.append((label, {k: statistics.median(r[k] for r in all_rates)
                                    for k in all_rates[0]}))
    build_cpp = statistics.median(build_cpp)
    print(f"\nBVH build: raylane.Mesh from NumPy {build_py:.1f} ms, C++ (BM_RayFile_Build) "
          f"{build_cpp:.1f} ms: {build_py / build_cpp:.2f}x")
    print("\nEvery contender (Mrays/s):\n")
    for label, rates in details:
        print(f"- {label}: " + ", ".join(f"{k} {v:.2f}" for k, v in sorted(rates.items())))
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""Shared set-up of the Python module's tests: where the checkout, the raylane binary and the
models are (ctest sets RAYLANE_SOURCE_DIR, RAYLANE_EXE and RAYLANE_MODEL_PATH), a PFM reader,
and rays at a mesh (the random ones are the benchmark's, bench/python/ray_queries.py)."""
import os
import subprocess
import sys

import numpy as np
import pytest

SOURCE_DIR = os.environ.get(
    "RAYLANE_SOURCE_DIR", os.path.normpath(os.path.join(os.path.dirname(__file__), "..", "..")))
RAYLANE_EXE = os.environ.get("RAYLANE_EXE", "")

sys.path.insert(0, os.path.join(SOURCE_DIR, "bench", "python"))
from ray_queries import random_rays  # noqa: E402,F401 (the tests import it from here)


def pytest_configure(config):
    config.addinivalue_line(
        "markers", "slow: may build the module from nothing (minutes); -m 'not slow' skips it")


def scene_path(name):
    return os.path.join(SOURCE_DIR, "scenes", name)


def model_or_skip(name):
    """The path of a model on RAYLANE_MODEL_PATH; the test is skipped when it is not there, or
    fails when RAYLANE_REQUIRE_MODELS=1 (CI sets it: there a missing model is a fault)."""
    for folder in os.environ.get("RAYLANE_MODEL_PATH", "").split(":"):
        if folder and os.path.isfile(os.path.join(folder, name)):
            return os.path.join(folder, name)
    why = (name + " is not on RAYLANE_MODEL_PATH (put ../shared/models beside the checkout or its "
           "folder in RAYLANE_MODEL_PATH)")
    if os.environ.get("RAYLANE_REQUIRE_MODELS") == "1":
        pytest.fail(why + " and RAYLANE_REQUIRE_MODELS=1")
    pytest.skip(why)


def run_cli(*args):
    """Runs the raylane binary; returns (exit code, stdout, stderr)."""
    if not RAYLANE_EXE:
        pytest.skip("RAYLANE_EXE is not set")
    p = subprocess.run([RAYLANE_EXE, *args], capture_output=True, text=True)
    return p.returncode, p.stdout, p.stderr


def read_pfm(path):
    """A colour PFM as (H, W, 3) float32, row 0 at the top (the file stores the bottom row
    first)."""
    with open(path, "rb") as f:
        assert f.readline().strip() == b"PF"
        width, height = (int(x) for x in f.readline().split())
        scale = float(f.readline())
        assert scale < 0, "little-endian PFM expected"
        data = np.frombuffer(f.read(), dtype="<f4")
    assert data.size == width * height * 3
    return data.reshape(height, width, 3)[::-1]


def camera_rays(mesh, width, height):
    """Primary-like rays: a pinhole camera in front of the mesh, in 16x16 tiles (coherent)."""
    v = mesh.vertices
    lo, hi = v.min(axis=0), v.max(axis=0)
    centre, size = (lo + hi) / 2, np.linalg.norm(hi - lo)
    eye = centre + np.array([0.0, 0.0, 1.5 * size])
    ys, xs = np.mgrid[0:height, 0:width]
    tiles = (ys // 16) * ((width + 15) // 16) + xs // 16
    order = np.lexsort((xs.ravel(), ys.ravel(), tiles.ravel()))
    px = (xs.ravel()[order] + 0.5) / width - 0.5
    py = 0.5 - (ys.ravel()[order] + 0.5) / height
    d = np.stack([px * 0.8 * width / height, py * 0.8, -np.ones_like(px)], axis=1)
    origins = np.broadcast_to(eye, d.shape)
    return np.ascontiguousarray(origins, dtype=np.float32), d.astype(np.float32)

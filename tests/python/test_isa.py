"""raylane.instruction_sets and raylane.use_isa: the sets compiled in, those this CPU runs and the
one in use; forcing each runnable set renders the same pixels and casts the same rays; a name
that is unknown, or that this CPU cannot run, is a ValueError naming the runnable sets."""
import os
import subprocess
import sys

import numpy as np
import pytest

import raylane
from conftest import scene_path


def test_instruction_sets_names_the_compiled_runnable_and_used_sets():
    sets = raylane.instruction_sets()
    assert sets["compiled"] == ["sse4.2", "avx2", "avx512"]
    assert "sse4.2" in sets["cpu"]
    assert sets["in_use"] in sets["cpu"]
    assert sets["packet_width"] == {"sse4.2": 4, "avx2": 8, "avx512": 16}[sets["in_use"]]


def test_every_runnable_set_renders_and_casts_the_same():
    runnable = [s for s in raylane.instruction_sets()["cpu"]]
    scene = raylane.load_scene(scene_path("fig05_refractive_sphere.json"))
    rng = np.random.default_rng(5)
    org = rng.uniform(-1.0, 1.0, (4000, 3)).astype(np.float32)
    direction = rng.normal(size=(4000, 3)).astype(np.float32)
    mesh = raylane.Mesh(np.array([[-1, -1, 0], [1, -1, 0], [0, 1, 0]], np.float32),
                        np.array([[0, 1, 2]], np.int32))
    images, hits = {}, {}
    try:
        for name in runnable:
            raylane.use_isa(name)
            assert raylane.instruction_sets()["in_use"] == name
            images[name] = scene.render(width=48, spp=2)
            hits[name] = mesh.intersect(org, direction)
    finally:
        raylane.use_isa(runnable[-1])
    first = runnable[0]
    for name in runnable[1:]:
        assert np.array_equal(images[name], images[first]), name
        for key in hits[first]:
            assert np.array_equal(hits[name][key], hits[first][key]), (name, key)


@pytest.mark.parametrize("name", ["avx9", "", "AVX2"])
def test_an_unknown_set_is_a_value_error_naming_the_runnable_sets(name):
    with pytest.raises(ValueError, match="unknown instruction set"):
        raylane.use_isa(name)


def test_raylane_isa_in_the_environment_chooses_the_set_or_is_refused():
    code = "import raylane; print(raylane.instruction_sets()['in_use'])"
    env = dict(os.environ, RAYLANE_ISA="sse4.2")
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True)
    assert out.returncode == 0 and out.stdout.strip() == "sse4.2", out.stderr
    env["RAYLANE_ISA"] = "mmx"
    out = subprocess.run([sys.executable, "-c", code], env=env, capture_output=True, text=True)
    assert out.returncode != 0
    assert "RAYLANE_ISA: unknown instruction set 'mmx'" in out.stderr

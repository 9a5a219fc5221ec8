"""load_scene, Scene.render, Scene.compare and Scene.info against the command line: the same
pixels as `raylane render -o FILE.pfm`, the same figures as `raylane compare` and `raylane info`,
the same one-line errors."""
import json
import re

import numpy as np
import pytest

import raylane
from conftest import model_or_skip, read_pfm, run_cli, scene_path

# a mesh scene, the report's glass sphere (report tone mapping), a textured and normal-mapped model
SCENES = ["bunny.json", "fig05_refractive_sphere.json", "fig07b_apple_normal_map.json"]


def cli_render(tmp_path, scene, *options):
    out = str(tmp_path / "cli.pfm")
    code, _, err = run_cli("render", scene_path(scene), "-o", out, "-q", *options)
    assert code == 0, err
    return read_pfm(out)


@pytest.fixture(scope="module")
def bunny():
    model_or_skip("bunny.ply")
    return raylane.load_scene(scene_path("bunny.json"))


@pytest.mark.parametrize("path", ["packet", "scalar"])
@pytest.mark.parametrize("scene", SCENES)
def test_render_equals_the_command_lines_pfm(tmp_path, scene, path):
    if scene.startswith("bunny"):
        model_or_skip("bunny.ply")
    if "apple" in scene:
        model_or_skip("apple/food_apple_01_4k.obj")
    s = raylane.load_scene(scene_path(scene))
    image = s.render(width=96, spp=2, path=path, threads=2)
    assert image.dtype == np.float32 and image.ndim == 3 and image.shape[1:] == (96, 3)
    expected = cli_render(tmp_path, scene, "--width", "96", "--spp", "2", "--path", path,
                          "--threads", "2")
    assert image.shape == expected.shape
    assert np.array_equal(image, expected)
    assert image.max() > 0, "the image must not be black"


@pytest.mark.parametrize("aov", ["normal", "depth", "bvh-cost"])
def test_aovs_equal_the_command_lines_raw_pfm(tmp_path, bunny, aov):
    image = bunny.render(width=80, height=45, aov=aov, path="packet")
    expected = cli_render(tmp_path, "bunny.json", "--width", "80", "--height", "45", "--aov", aov)
    if aov == "normal":
        assert image.shape == (45, 80, 3)
        assert np.array_equal(image, expected)
    else:
        assert image.shape == (45, 80)
        assert np.array_equal(image, expected[:, :, 0])
        assert np.array_equal(expected[:, :, 0], expected[:, :, 1])
    assert np.count_nonzero(image) > 0


def test_render_keeps_the_scenes_camera_between_calls(bunny):
    small = bunny.render(width=64, aov="depth")
    assert small.shape == (36, 64)
    assert bunny.render(height=30, aov="depth").shape == (30, 53)  # 53.3 rounded
    assert bunny.render(width=40, height=40, aov="depth").shape == (40, 40)
    assert np.array_equal(bunny.render(width=64, aov="depth"), small)
    assert (bunny.width, bunny.height, bunny.spp) == (1920, 1080, 1)


def cli_figures(text):
    figures = {}
    for line in text.splitlines():
        key, _, value = line.partition(" ")
        figures.setdefault(key, value.strip())
    return figures


def test_compare_gives_the_command_lines_metrics(bunny):
    d = bunny.compare(width=64, spp=2, repeats=1, threads=2)
    code, out, err = run_cli("compare", scene_path("bunny.json"), "--width", "64", "--spp", "2",
                             "--repeats", "1", "--threads", "2", "-q")
    assert code == 0, err
    lines = dict(re.findall(r"^(\S.*?)\s{2,}(.*)$", out, re.M))
    assert lines["max |diff|"] == f"{d['max_abs_diff']:.3g}"
    assert lines["mean |diff|"] == f"{d['mean_abs_diff']:.3g}"
    assert lines["RMSE"] == f"{d['rmse']:.3g}"
    assert lines["PSNR"] == f"{d['psnr_db']:.1f} dB"
    assert lines["> 1/255"] == f"{d['pixels_over_1_255']} of {d['pixels']} pixels"
    assert lines["hit ids"] == f"{d['hit_id_mismatches']} of {d['pixels']} primary hits differ"
    assert lines["result"].startswith("agree" if d["agree"] else "DIFFER")
    assert d["pixels"] == 64 * 36 and d["packet_width"] == raylane.instruction_sets()["packet_width"]
    assert d["scalar_ms"] > 0 and d["packet_ms"] > 0


def test_info_gives_the_command_lines_figures(bunny):
    d = bunny.info()
    code, out, err = run_cli("info", scene_path("bunny.json"))
    assert code == 0, err
    assert f"objects    {d['objects']} ({d['spheres']} spheres, {d['boxes']} boxes, " \
           f"{d['cylinders']} cylinders, {d['planes']} planes, {d['single_triangles']} " \
           f"triangles, {len(d['meshes'])} meshes)" in out
    assert f"triangles  {d['triangles']}\n" in out
    assert f"features   {d['features']}\n" in out
    c = d["camera"]
    assert f"camera     {c['width']}x{c['height']}, {c['spp']} spp, {c['fov_axis']} fov " \
           f"{c['fov_deg']:.1f} deg" in out
    m = d["meshes"][0]
    b = m["binary"]
    assert f"{b['nodes']} nodes, {b['leaves']} leaves, leaf depth max {b['max_leaf_depth']} " \
           f"mean {b['mean_leaf_depth']:.1f}, SAH cost {b['sah_cost']:.1f}" in out
    w = m["wide"]
    assert f"wide tree (packet path): {w['nodes']} nodes, {w['mean_children']:.2f} children " \
           f"per node, {w['leaves']} leaves" in out
    assert f"memory     {d['memory_mib']:.2f} MiB" in out
    assert d["triangles"] == m["triangles"] > 60_000
    assert set(d["build_phases_ms"]) == {"centroids", "sorts", "splits", "vertices", "boxes",
                                         "collapse"}
    assert sum(d["build_phases_ms"].values()) <= d["build_ms"]


def test_a_bad_scene_raises_the_command_lines_one_line_error(tmp_path):
    path = tmp_path / "bad.json"
    path.write_text('{"version": 1, "camera": {"fov_deg": "wide"}}')
    code, _, err = run_cli("render", str(path), "-o", str(tmp_path / "x.png"))
    assert code == 2
    with pytest.raises(raylane.Error) as e:
        raylane.load_scene(str(path))
    assert isinstance(e.value, ValueError)
    assert err.strip() == "raylane: " + str(e.value)
    assert str(e.value).startswith(str(path))


def test_a_folder_given_as_the_scene_says_so_in_the_command_lines_words(tmp_path):
    code, _, err = run_cli("render", str(tmp_path))
    assert code == 2
    with pytest.raises(raylane.Error) as e:
        raylane.load_scene(str(tmp_path))
    assert str(e.value) == str(tmp_path) + ": is a folder, not a scene (.json) or a model (.obj, .ply)"
    assert err.strip().endswith(str(e.value) + " (see raylane --help)"), err


def test_a_missing_scene_or_model_raises_file_not_found(tmp_path):
    with pytest.raises(FileNotFoundError, match="missing.json"):
        raylane.load_scene(str(tmp_path / "missing.json"))
    with open(scene_path("builtin.json")) as f:
        scene = json.load(f)
    scene["objects"].append({"shape": "mesh", "file": "none-such.ply",
                             "material": scene["objects"][0]["material"]})
    path = tmp_path / "scene.json"
    path.write_text(json.dumps(scene))
    with pytest.raises(raylane.Error, match="none-such.ply"):
        raylane.load_scene(str(path))


@pytest.mark.parametrize("kwargs, message", [
    ({"aov": "albedo"}, r"aov: unknown output \"albedo\""),
    ({"path": "gpu"}, r"path: unknown renderer \"gpu\""),
    ({"spp": -1}, r"spp: -1 is outside 0 \.\. 1048576"),
    ({"width": 40000}, r"width: 40000 is outside 0 \.\. 32768"),
    ({"width": 30000, "height": 30000}, r"too large"),
])
def test_bad_render_options_raise_value_error(bunny, kwargs, message):
    with pytest.raises(ValueError, match=message):
        bunny.render(**kwargs)


def test_render_leaves_the_callers_float_modes_alone(bunny):
    bunny.render(width=32, aov="depth")
    tiny = np.float32(1e-38) * np.float32(1e-3)  # a subnormal, not flushed to zero
    assert tiny > 0

"""`pip install .` and `pip wheel .` as docs/building.md gives them, offline: from a scratch copy
of the checkout (the files git lists, tracked or not ignored: no build output), into a virtual
environment made with --system-site-packages (Debian's NumPy, setuptools and wheel), with
--no-build-isolation. The installed module imports from the environment (PYTHONPATH unset),
renders the built-in scene, and has its stubs beside it (raylane.pyi, and the stub-only package
raylane-stubs that mypy reads); the wheel installs into a second environment and imports there.

The CMake build folder is RAYLANE_BUILD_DIR, handed to setup.py: ctest sets it to its own build
folder (python/CMakeLists.txt), so the module is not compiled a second time. Unset, the test
builds the module from nothing in the scratch copy's build/pip, as a first `pip install .` does:
about 7 minutes on 2 cores, hence the slow mark and ctest's longer timeout for this file."""
import os
import re
import shutil
import subprocess
import sys

import pytest

from conftest import SOURCE_DIR

pytestmark = pytest.mark.slow

BUILD_DIR = os.environ.get("RAYLANE_BUILD_DIR", "")
PIP_TIMEOUT = 1800  # seconds for one pip command: a build from nothing on 2 cores fits


def project_version():
    with open(os.path.join(SOURCE_DIR, "CMakeLists.txt"), encoding="utf-8") as f:
        return re.search(r"^project\(raylane VERSION ([0-9.]+)", f.read(), re.M).group(1)


def scratch_copy(dest):
    """The files of the checkout that git lists (tracked, or untracked and not ignored) under
    `dest`; without git, the checkout less its build folder."""
    listed = subprocess.run(
        ["git", "-C", SOURCE_DIR, "ls-files", "-z", "--cached", "--others", "--exclude-standard"],
        capture_output=True)
    if listed.returncode != 0:
        shutil.copytree(SOURCE_DIR, dest, symlinks=True,
                        ignore=shutil.ignore_patterns("build", "__pycache__", "*.egg-info"))
        return
    for name in sorted(set(listed.stdout.decode().split("\0")) - {""}):
        source = os.path.join(SOURCE_DIR, name)
        if not os.path.lexists(source):  # deleted in the work tree, not yet in git
            continue
        os.makedirs(os.path.join(dest, os.path.dirname(name)), exist_ok=True)
        shutil.copy2(source, os.path.join(dest, name), follow_symlinks=False)


def clean_environment(tmp):
    """The tests' environment without what would let Python find a module elsewhere (the build
    folder on PYTHONPATH, a user site) and with pip kept off any index."""
    env = {k: v for k, v in os.environ.items()
           if k not in ("PYTHONPATH", "PYTHONHOME", "VIRTUAL_ENV", "RAYLANE_BUILD_DIR")}
    env["PYTHONNOUSERSITE"] = "1"
    env["PIP_NO_INDEX"] = "1"  # offline: everything comes from Debian's packages
    env["RAYLANE_BUILD_DIR"] = BUILD_DIR or os.path.join(tmp, "raylane", "build", "pip")
    return env


def run(command, env, cwd, timeout=PIP_TIMEOUT):
    p = subprocess.run(command, env=env, cwd=cwd, capture_output=True, text=True,
                       timeout=timeout)
    assert p.returncode == 0, (f"{' '.join(command)} failed ({p.returncode}):\n"
                               f"{p.stdout[-4000:]}\n{p.stderr[-4000:]}")
    return p.stdout


def make_venv(path, env):
    run([sys.executable, "-m", "venv", "--system-site-packages", str(path)], env, cwd=path.parent,
        timeout=300)
    return str(path / "bin" / "python")


CHECK = r"""
import importlib.metadata, os, sys
import numpy as np
import raylane
print("module", raylane.__file__)
folder = os.path.dirname(raylane.__file__)
print("stubs", os.path.isfile(os.path.join(folder, "raylane.pyi")),
      os.path.isfile(os.path.join(folder, "raylane-stubs", "__init__.pyi")))
print("version", raylane.__version__, importlib.metadata.version("raylane"))
print("requires", importlib.metadata.requires("raylane"))
print("sets", raylane.instruction_sets())
image = raylane.load_scene(sys.argv[1]).render(width=64, spp=1)
print("image", image.shape, image.dtype, float(image.max()), bool(np.isfinite(image).all()))
"""


def check_installed(python, env, cwd, venv):
    """Imports raylane with the environment's python and checks what it prints."""
    out = run([python, "-c", CHECK, os.path.join(SOURCE_DIR, "scenes", "builtin.json")], env,
              cwd=cwd, timeout=300)
    lines = dict(line.split(" ", 1) for line in out.splitlines())
    module = lines["module"]
    assert module.startswith(str(venv) + os.sep), f"raylane imported from {module}, not {venv}"
    assert re.search(r"/site-packages/raylane\.[^/]*\.so$", module), module
    assert lines["stubs"] == "True True", \
        "raylane.pyi and raylane-stubs/__init__.pyi are not both installed beside the module"
    assert lines["version"].split() == [project_version()] * 2
    assert lines["requires"] == "['numpy']"
    assert "'in_use'" in lines["sets"]
    shape, dtype, peak, finite = lines["image"].rsplit(" ", 3)
    assert shape.startswith("(48, 64, 3)") and dtype == "float32", lines["image"]
    assert finite == "True" and float(peak) > 0.05, f"the image is black: {lines['image']}"


@pytest.fixture(scope="module")
def work(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("pip")
    scratch_copy(tmp / "raylane")
    env = clean_environment(str(tmp))
    return tmp, env


def test_pip_install_builds_imports_renders_and_installs_the_stubs(work):
    tmp, env = work
    python = make_venv(tmp / "env", env)
    run([python, "-m", "pip", "install", "--no-build-isolation", "."], env, cwd=tmp / "raylane")
    check_installed(python, env, cwd=tmp, venv=tmp / "env")
    # the module's own tests pass against the installed module (no PYTHONPATH into a build)
    tests = [os.path.join(SOURCE_DIR, "tests", "python", name) for name in
             ("test_scene.py", "test_mesh_queries.py", "test_mesh_input.py", "test_isa.py",
              "test_stubs.py")]
    out = run([python, "-m", "pytest", "-q", "-p", "no:cacheprovider", *tests], env, cwd=tmp,
              timeout=900)
    assert " passed" in out and " failed" not in out, out[-2000:]


def test_pip_wheel_installs_into_another_environment(work):
    tmp, env = work
    builder = make_venv(tmp / "wheel-env", env)
    run([builder, "-m", "pip", "wheel", "--no-build-isolation", "--no-deps", "-w",
         str(tmp / "wheels"), "."], env, cwd=tmp / "raylane")
    wheels = sorted(os.listdir(tmp / "wheels"))
    assert len(wheels) == 1 and re.match(
        r"raylane-" + re.escape(project_version()) + r"-cp3\d+-cp3\d+-linux_x86_64\.whl$",
        wheels[0]), wheels
    python = make_venv(tmp / "other-env", env)
    run([python, "-m", "pip", "install", str(tmp / "wheels" / wheels[0])], env, cwd=tmp)
    check_installed(python, env, cwd=tmp, venv=tmp / "other-env")

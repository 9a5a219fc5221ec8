"""`pip install .`: builds the Python module `raylane` with CMake (the target raylane_python of
python/CMakeLists.txt) and installs it with its type stubs, python/raylane.pyi, beside it (and as
raylane-stubs/__init__.pyi, for mypy).

Offline, with Debian's setuptools and wheel (docs/building.md, "pip install"):

    python3 -m venv --system-site-packages ENV
    ENV/bin/pip install --no-build-isolation .

The CMake build folder is RAYLANE_BUILD_DIR when that is set, else build/pip in the checkout; it
is kept between runs, so a second install only rebuilds what changed. A folder that is not
configured yet is configured here (Ninja, Release, -O3, no benchmarks, this interpreter); one
that is, such as the release preset's build/release, is built as it stands, its options kept.
"""
import os
import re
import shutil
import subprocess
import sys
import sysconfig

from setuptools import Extension, setup
from setuptools.command.build_ext import build_ext

SOURCE_DIR = os.path.dirname(os.path.abspath(__file__))


def project_version():
    """x.y.z of `project(raylane VERSION x.y.z ...)` in CMakeLists.txt, the one place it is set."""
    with open(os.path.join(SOURCE_DIR, "CMakeLists.txt"), encoding="utf-8") as f:
        m = re.search(r"^\s*project\(\s*raylane\s+VERSION\s+([0-9][0-9.]*)", f.read(), re.M)
    if not m:
        sys.exit("setup.py: no `project(raylane VERSION x.y.z)` in CMakeLists.txt")
    return m.group(1)


def cache_entries(build_dir):
    """NAME -> value of a configured build folder's CMakeCache.txt ({} when there is none)."""
    entries = {}
    try:
        with open(os.path.join(build_dir, "CMakeCache.txt"), encoding="utf-8") as f:
            for line in f:
                m = re.match(r"^([A-Za-z_][A-Za-z0-9_.-]*):[A-Z]+=(.*)$", line.rstrip("\n"))
                if m:
                    entries[m.group(1)] = m.group(2)
    except FileNotFoundError:
        pass
    return entries


def jobs():
    try:
        return len(os.sched_getaffinity(0))
    except AttributeError:
        return os.cpu_count() or 1


def run(command):
    print("setup.py: " + " ".join(command), flush=True)
    subprocess.run(command, check=True)


class CMakeBuild(build_ext):
    """Runs CMake instead of compiling the extension's sources itself."""

    def build_extension(self, ext):
        build_dir = os.path.abspath(
            os.environ.get("RAYLANE_BUILD_DIR") or os.path.join(SOURCE_DIR, "build", "pip"))
        cache = cache_entries(build_dir)
        if not cache:
            os.makedirs(build_dir, exist_ok=True)
            run(["cmake", "-S", SOURCE_DIR, "-B", build_dir, "-G", "Ninja",
                 "-DCMAKE_BUILD_TYPE=Release", "-DCMAKE_CXX_FLAGS_RELEASE=-O3 -DNDEBUG",
                 "-DRAYLANE_BENCH=OFF", "-DPython_EXECUTABLE=" + sys.executable])
        else:
            configured_from = cache.get("CMAKE_HOME_DIRECTORY", "")
            if not os.path.isdir(configured_from):
                sys.exit(f"setup.py: {build_dir} is configured from {configured_from}, which is "
                         "gone: remove the folder or set RAYLANE_BUILD_DIR to another")
            if os.path.realpath(configured_from) != os.path.realpath(SOURCE_DIR):
                print(f"setup.py: {build_dir} is configured from {configured_from}: the module "
                      "is built from that source tree", flush=True)
            python = cache.get("Python_EXECUTABLE", "")
            if python and not os.path.exists(python):
                # an interpreter gone since (a deleted virtual environment): this one instead
                run(["cmake", build_dir, "-DPython_EXECUTABLE=" + sys.executable])
        try:
            run(["cmake", "--build", build_dir, "--target", "raylane_python", "-j", str(jobs())])
        except subprocess.CalledProcessError:
            sys.exit(f"setup.py: building raylane_python in {build_dir} failed (above); the module "
                     "needs pybind11-dev and python3-dev (bash scripts/setup.sh installs them)")

        # the module of this interpreter's ABI: raylane.cpython-311-x86_64-linux-gnu.so, ...
        suffix = sysconfig.get_config_var("EXT_SUFFIX")
        built = os.path.join(build_dir, "python", "raylane" + suffix)
        if not os.path.isfile(built):
            found = sorted(f for f in os.listdir(os.path.join(build_dir, "python"))
                           if f.startswith("raylane.") and f.endswith(".so"))
            sys.exit(f"setup.py: {built} was not built (the folder holds {found or 'no module'}): "
                     f"{build_dir} is configured for another Python than {sys.executable}; "
                     "set RAYLANE_BUILD_DIR to another folder")
        target = self.get_ext_fullpath(ext.name)
        os.makedirs(os.path.dirname(target), exist_ok=True)
        shutil.copyfile(built, target)
        if not self.inplace:
            # the stubs beside the module, where editors read them, and as the stub-only package
            # raylane-stubs, where mypy does (it reads no stubs of an installed single module)
            stubs, lib = os.path.join(SOURCE_DIR, "python", "raylane.pyi"), os.path.dirname(target)
            shutil.copyfile(stubs, os.path.join(lib, "raylane.pyi"))
            os.makedirs(os.path.join(lib, "raylane-stubs"), exist_ok=True)
            shutil.copyfile(stubs, os.path.join(lib, "raylane-stubs", "__init__.pyi"))


setup(
    version=project_version(),
    packages=[],  # one extension module and its stubs; no Python packages to discover
    py_modules=[],
    ext_modules=[Extension("raylane", sources=[])],
    cmdclass={"build_ext": CMakeBuild},
    zip_safe=False,
)

#!/usr/bin/env bash
# Installs what Raylane needs from Debian 12's packages (apt-get, as root), if missing.
set -euo pipefail
packages=(cmake ninja-build g++ clang libclang-rt-14-dev libxsimd-dev libtbb-dev libglm-dev
          libstb-dev libgtest-dev libbenchmark-dev nlohmann-json3-dev libcli11-dev zlib1g-dev
          libopenexr-dev)
# one frame over many processes (`mpirun ... raylane render`) and its tests
packages+=(libopenmpi-dev openmpi-bin procps)
# the packet tests on emulated CPUs without AVX-512 or AVX (qemu-user), and the instruction check
packages+=(qemu-user binutils)
# the Python module (python/), its tests and the examples of docs/python.md
packages+=(pybind11-dev python3-dev python3-numpy python3-pytest python3-matplotlib)
# `pip install .` offline in a virtual environment (docs/building.md, "pip install")
packages+=(python3-venv python3-setuptools python3-wheel python3-pip)
# the man page check of tests/python/test_packaging.py (groff); the Debian package (cpack -G DEB
# computes its dependencies with dpkg-shlibdeps) and its test (pkg-config for the examples)
packages+=(groff-base dpkg-dev pkg-config)
# Embree is only for the baseline benchmark; the renderer never links it.
[ "${RAYLANE_NO_EMBREE:-0}" = 1 ] || packages+=(libembree-dev)
missing=()
for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
    echo "setup: installing ${missing[*]}" >&2
    sudo_cmd=""
    [ "$(id -u)" = 0 ] || sudo_cmd="sudo"
    $sudo_cmd apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo_cmd apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

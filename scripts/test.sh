#!/usr/bin/env bash
# Quick start 2: set up, build and run every test, in the given presets (default: release asan),
# with warnings as errors.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
presets=("$@")
[ ${#presets[@]} -gt 0 ] || presets=(release asan)
jobs=$(nproc)
for preset in "${presets[@]}"; do
    echo "== $preset" >&2
    cmake --preset "$preset" -DRAYLANE_WERROR=ON >/dev/null
    cmake --build --preset "$preset" -j "$jobs"
    ctest --preset "$preset" -j "$jobs"
done

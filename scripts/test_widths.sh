#!/usr/bin/env bash
# The other packet widths: builds the avx2 (W = 8) and sse4 (W = 4) presets with warnings as
# errors and runs the test programs that exercise packet code at each width: the simd
# vocabulary, packet shapes and packet / block / stream traversal against the scalar path, the
# packet BRDFs and textures, the stiff and extreme cases, the BVH build, and the packet renderer
# against the scalar one. The release build tests W = 4 and 8 too, but compiled for the host's
# widest instruction set (AVX-512 on the CI machine), so the AVX2 and SSE code paths of simd/
# (compaction, gathers, masked loads and stores, unsigned compares) and the scalar loops of src/
# (the BVH build's, which run where compaction is not native) only run here. CI runs it after
# scripts/test.sh.
#
#   scripts/test_widths.sh [PRESET...]   default: avx2 sse4
#
# Each preset builds into build/<preset>-tests (no benchmarks, no raylane binary), beside any
# full build of it, at -O1, with the typed tests at the SIMD widths only (RAYLANE_TEST_WIDTHS=simd:
# W = 1, the scalar width, does not depend on the instruction set and the release build tests
# it). These builds check answers, not speed: -O1 takes the same code paths as -O3 (no
# fast-math, no contraction either way), and builds in about half the time.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
presets=("$@")
[ ${#presets[@]} -gt 0 ] || presets=(avx2 sse4)
programs=(tests_simd tests_traverse tests_shade tests_numerics tests_accel tests_render)
for preset in "${presets[@]}"; do
    dir="build/$preset-tests"
    echo "== $preset (${programs[*]})" >&2
    cmake --preset "$preset" -B "$dir" -DRAYLANE_WERROR=ON -DRAYLANE_BENCH=OFF \
        -DCMAKE_CXX_FLAGS_RELEASE="-O1 -DNDEBUG" -DRAYLANE_TEST_WIDTHS=simd >/dev/null
    cmake --build "$dir" -j "$(nproc)" --target "${programs[@]}"
    for program in "${programs[@]}"; do
        "$dir/tests/$program" --gtest_brief=1
    done
done

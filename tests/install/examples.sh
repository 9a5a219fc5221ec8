#!/bin/sh
# examples/ against an install of the build, as a user builds them: each example configured with
# CMake in a scratch folder (-DCMAKE_PREFIX_PATH=PREFIX, Ninja when it is there), built and run
# with no LD_LIBRARY_PATH (CMake's run path to PREFIX/lib must be enough); render_scene also
# with -DRAYLANE_STATIC=ON (Raylane::raylane_static: the program must not need libraylane.so),
# and cast_rays also with pkg-config and no CMake, run with LD_LIBRARY_PATH=PREFIX/lib. Each run
# exits 0 and prints what it should; render_scene's PPM has its size and is not black, its PFM
# holds the same image as floats, and a scene that is not there ends it with Raylane's message
# and exit status 1.
# Usage: examples.sh PREFIX SOURCE_DIR WORK_DIR MODELS_DIR [CXX]
set -eu
prefix="$1" source="$2" work="$3" models="$4" cxx="${5:-c++}"
fail() { echo "examples: $*" >&2; exit 1; }
if [ ! -f "$models/bunny.ply" ]; then
    [ "${RAYLANE_REQUIRE_MODELS:-0}" = 1 ] &&
        fail "$models/bunny.ply is missing and RAYLANE_REQUIRE_MODELS=1"
    echo "skipped: $models/bunny.ply is missing (put ../shared/models beside the checkout)"
    exit 77
fi
[ -f "$prefix/lib/cmake/Raylane/RaylaneConfig.cmake" ] || fail "no install under $prefix"
rm -rf "$work"
mkdir -p "$work"
generator=""
command -v ninja >/dev/null 2>&1 && generator="-G Ninja"
unset LD_LIBRARY_PATH PKG_CONFIG_PATH CMAKE_PREFIX_PATH || true
export RAYLANE_MODEL_PATH="$models"

# build NAME EXAMPLE [CMAKE OPTIONS...]: configure and build examples/EXAMPLE in $work/NAME
build() {
    name="$1" example="$2"
    shift 2
    # shellcheck disable=SC2086 # $generator is two words or none
    { cmake -S "$source/examples/$example" -B "$work/$name" $generator \
          -DCMAKE_CXX_COMPILER="$cxx" -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$prefix" \
          "$@" && cmake --build "$work/$name"; } >"$work/$name.log" 2>&1 ||
        { cat "$work/$name.log" >&2; fail "$example ($name) did not configure and build"; }
}

# run NAME COMMAND...: runs in $work, output in $work/NAME.out; fails unless it exits 0
run() {
    name="$1"
    shift
    status=0
    (cd "$work" && "$@") >"$work/$name.out" 2>&1 || status=$?
    [ "$status" -eq 0 ] || { cat "$work/$name.out" >&2; fail "$name exited with $status"; }
}

expect() {  # expect NAME PATTERN: the output of run NAME has a line matching PATTERN
    grep -q -E "$2" "$work/$1.out" || { cat "$work/$1.out" >&2; fail "$1 did not print /$2/"; }
}

# check_ppm FILE WIDTH HEIGHT: a binary PPM of that size whose bytes are not all dark
check_ppm() {
    header=$(head -n 3 "$1" | tr '\n' ' ')
    case "$header" in
        "P6 $2 $3 255 "*) ;;
        *) fail "$1: header '$header', expected 'P6 $2 $3 255'" ;;
    esac
    size=$(wc -c <"$1")
    [ "$size" -eq $((${#header} + $2 * $3 * 3)) ] || fail "$1: $size bytes"
    mean=$(tail -c $(($2 * $3 * 3)) "$1" | od -An -v -tu1 |
        awk '{ for (i = 1; i <= NF; ++i) s += $i; n += NF } END { printf "%d", s / n }')
    [ "$mean" -ge 20 ] || fail "$1: mean byte $mean, a black image"
}

# CMake, libraylane.so
build cast_rays cast_rays
run cast_rays "$work/cast_rays/cast_rays"
expect cast_rays "bunny\.ply: [0-9]+ vertices, [0-9]+ triangles"
expect cast_rays "^hits: [1-9][0-9]* of 64 rays$"
expect cast_rays "^occluded: [1-9][0-9]* of 64 rays; the same rays as hit$"
if readelf -d "$work/cast_rays/cast_rays" | grep -q -E "R(UN)?PATH.*$prefix/lib"; then :; else
    fail "cast_rays has no run path to $prefix/lib"
fi
run cast_rays_dragon "$work/cast_rays/cast_rays" dragon.ply
expect cast_rays_dragon "^hits: [1-9][0-9]* of 64 rays$"

build render_scene render_scene
run render_scene "$work/render_scene/render_scene"
expect render_scene "bunny\.ply: 640 x 360 pixels at [0-9]+ samples per pixel, rendered in"
expect render_scene "^instruction set: (sse4\.2|avx2|avx512) \((4|8|16) rays per packet\); wrote render_scene\.ppm$"
check_ppm "$work/render_scene.ppm" 640 360
run render_scene_pfm "$work/render_scene/render_scene" "$source/scenes/dragon.json" dragon.pfm 160
expect render_scene_pfm "dragon\.json: 160 x 90 pixels"
[ "$(head -n 3 "$work/dragon.pfm" | tr '\n' ' ')" = "PF 160 90 -1.0 " ] || fail "dragon.pfm: bad header"
[ "$(wc -c <"$work/dragon.pfm")" -eq $((15 + 160 * 90 * 12)) ] || fail "dragon.pfm: bad size"
if (cd "$work" && "$work/render_scene/render_scene" no/such.json) >"$work/missing.out" 2>&1; then
    fail "render_scene exited with 0 for a scene that is not there"
fi
expect missing "^render_scene: no/such.json: no such file$"

# CMake, COMPONENTS static: Raylane::raylane_static
build render_scene_static render_scene -DRAYLANE_STATIC=ON
if readelf -d "$work/render_scene_static/render_scene" | grep -q "libraylane"; then
    fail "render_scene built with -DRAYLANE_STATIC=ON needs libraylane.so"
fi
run render_scene_static "$work/render_scene_static/render_scene" "" builtin.ppm 64
expect render_scene_static "^<built-in>: 64 x [0-9]+ pixels"

# pkg-config, no CMake; found at run time through LD_LIBRARY_PATH
flags=$(PKG_CONFIG_PATH="$prefix/lib/pkgconfig" pkg-config --cflags --libs raylane) ||
    fail "pkg-config does not find raylane.pc under $prefix/lib/pkgconfig"
# shellcheck disable=SC2086 # the flags are words
"$cxx" -std=c++17 -O2 "$source/examples/cast_rays/main.cpp" -o "$work/cast_rays_pc" $flags \
    >"$work/cast_rays_pc.log" 2>&1 || { cat "$work/cast_rays_pc.log" >&2; fail "pkg-config build"; }
run cast_rays_pc env LD_LIBRARY_PATH="$prefix/lib" "$work/cast_rays_pc"
expect cast_rays_pc "^occluded: [1-9][0-9]* of 64 rays; the same rays as hit$"

echo "examples: cast_rays and render_scene build against $prefix with CMake (shared and static)" \
     "and pkg-config, and run"

#!/bin/sh
# The Debian package as a user gets it: `cpack -G DEB` in the build folder, the package's
# dependencies computed (oneTBB among them), the package unpacked with dpkg-deb -x into a scratch
# folder, and from there: the command line renders the bunny, the Python module imports, and the
# ray-casting example builds against the package's CMake files and runs.
# Usage: deb_test.sh BUILD_DIR SOURCE_DIR BUNNY_PLY
set -eu
build="$1" source="$2" bunny="$3"
work="$build/deb-test"
fail() { echo "deb_test: $*" >&2; exit 1; }
if [ ! -f "$bunny" ]; then
    [ "${RAYLANE_REQUIRE_MODELS:-0}" = 1 ] && fail "$bunny is missing and RAYLANE_REQUIRE_MODELS=1"
    echo "skipped: $bunny is missing (put ../shared/models beside the checkout)"
    exit 77
fi
rm -rf "$work"
mkdir -p "$work"
cpack --config "$build/CPackConfig.cmake" -B "$work" >"$work/cpack.log" 2>&1 ||
    { cat "$work/cpack.log" >&2; fail "cpack failed"; }
deb=$(ls "$work"/raylane_*_amd64.deb)
dpkg-deb -f "$deb" Depends | grep -q "libtbb" || fail "$deb: no dependency on oneTBB computed"
dpkg-deb -x "$deb" "$work/root"
usr="$work/root/usr"
for f in bin/raylane lib/libraylane.so lib/libraylane.a include/raylane/raylane.h \
         lib/cmake/Raylane/RaylaneConfig.cmake lib/pkgconfig/raylane.pc \
         share/man/man1/raylane.1 share/bash-completion/completions/raylane; do
    [ -e "$usr/$f" ] || fail "the package lacks /usr/$f"
done

"$usr/bin/raylane" render "$bunny" --width 96 --spp 1 -o "$work/bunny.png" 2>"$work/render.log" ||
    { cat "$work/render.log" >&2; fail "the packaged raylane did not render the bunny"; }
grep -q "black" "$work/render.log" && { cat "$work/render.log" >&2; fail "a black bunny"; }
[ -s "$work/bunny.png" ] || fail "no image written"

module=$(ls "$usr"/lib/python3/dist-packages/raylane*.so)
env -u PYTHONPATH PYTHONPATH="$usr/lib/python3/dist-packages" /usr/bin/python3 -c \
    "import raylane, sys; assert raylane.__file__ == sys.argv[1], raylane.__file__" "$module" ||
    fail "the packaged Python module does not import"

cmake -S "$source/examples/cast_rays" -B "$work/example" -G Ninja -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_PREFIX_PATH="$usr" >"$work/example.log" 2>&1 &&
    cmake --build "$work/example" >>"$work/example.log" 2>&1 ||
    { cat "$work/example.log" >&2; fail "the example did not build against the package"; }
LD_LIBRARY_PATH="$usr/lib" RAYLANE_MODEL_PATH="$(dirname "$bunny")" "$work/example/cast_rays" \
    >"$work/example.out" || { cat "$work/example.out" >&2; fail "the example failed"; }
echo "$(basename "$deb"): renders the bunny, imports in Python, builds and runs examples/cast_rays"

#!/usr/bin/env bash
# Layers: a stage includes only its own headers and those of stages below it
# (docs/architecture.md, "Layers"). Prints every #include that points up or sideways and exits
# with 1 when there is one. Test-only headers live under tests/support/, so that an include of
# "accel/..." always means the library.
set -euo pipefail
cd "$(dirname "$0")/.."

declare -A rank=([simd]=0 [core]=1 [scene]=2 [image]=3 [io]=3 [accel]=3 [traverse]=4 [shade]=5 [query]=5
                 [render]=6 [report]=7 [distribute]=8 [api]=8 [app]=9 [python]=9)
bad=0
while IFS= read -r file; do
    case "$file" in
        simd/*) stage=simd ;;
        src/*) stage="${file#src/}"; stage="${stage%%/*}" ;;
    esac
    [[ -n "${rank[$stage]:-}" ]] || { echo "$file: stage '$stage' has no place in the layers" >&2; bad=1; continue; }
    while IFS=: read -r line target; do
        dep="${target%%/*}"
        [[ -n "${rank[$dep]:-}" && "$dep" != "$stage" ]] || continue
        if (( rank[$dep] >= rank[$stage] )); then
            echo "$file:$line: $stage includes \"$target\", a stage at or above it ($dep)" >&2
            bad=1
        fi
    done < <(grep -n '^[[:space:]]*#[[:space:]]*include[[:space:]]*"' "$file" |
             sed 's/^\([0-9]*\):[^"]*"\([^"]*\)".*/\1:\2/' || true)
done < <(git ls-files 'simd/*.h' 'src/*.h' 'src/*.cpp')

while IFS= read -r header; do
    echo "$header: a test-only header outside tests/support/" >&2
    bad=1
done < <(git ls-files 'tests/*.h' | grep -v -e '^tests/support/' -e '^tests/fuzz/' || true)

[[ $bad == 0 ]] && echo "layers: every include points down" >&2
exit $bad

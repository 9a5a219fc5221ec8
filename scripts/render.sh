#!/usr/bin/env bash
# Quick start 1: set up, build (release) and render. A scene or model file given as the first
# argument (bash scripts/render.sh bunny.ply); else the dragon when its model is found, the
# built-in scene otherwise. Further arguments go to `raylane render`.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
# The Stanford models and the textures: the shared folder beside the checkout, when it is there.
shared="$(cd .. && pwd)/shared"
[ -d "$shared/models" ] && export RAYLANE_MODEL_PATH="$shared/models:$shared/textures${RAYLANE_MODEL_PATH:+:$RAYLANE_MODEL_PATH}"
cmake --preset release >/dev/null
cmake --build --preset release --target raylane
mkdir -p out
if [ $# -gt 0 ] && [ "${1#-}" = "$1" ]; then
    input="$1"
    shift
    name="$(basename "$input")"
    ./build/release/raylane render "$input" -o "out/${name%%.*}.png" "$@"
    echo "image: $(pwd)/out/${name%%.*}.png"
elif ./build/release/raylane info scenes/dragon.json >/dev/null 2>&1; then
    ./build/release/raylane render scenes/dragon.json -o out/dragon.png "$@"
    echo "image: $(pwd)/out/dragon.png"
else
    echo "render: dragon model not found (see the message above); rendering the built-in scene" >&2
    ./build/release/raylane info scenes/dragon.json 2>&1 | head -1 >&2 || true
    ./build/release/raylane render -o out/builtin.png "$@"
    echo "image: $(pwd)/out/builtin.png"
fi

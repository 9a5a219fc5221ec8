#!/usr/bin/env bash
# Gallery: renders every report figure (scenes/fig*.json) into docs/gallery/*.png, as listed in
# docs/gallery.md. Usage: scripts/gallery.sh [path/to/raylane]   (default build/release/raylane)
# Images are 400 pixels wide (aspect kept) at the scene's spp, except where `options` below says
# otherwise; renders are deterministic (fixed sample hash seed), so a rerun gives the same files.
set -euo pipefail

raylane="${1:-build/release/raylane}"
# A relative path given by the caller is relative to the caller's directory.
if [[ "$raylane" != /* && -e "$raylane" ]]; then raylane="$PWD/$raylane"; fi
cd "$(dirname "$0")/.."
if [[ ! -x "$raylane" ]]; then
    echo "gallery: raylane binary not found: $raylane (build it or pass its path)" >&2
    exit 1
fi

out=docs/gallery
mkdir -p "$out"

# Per-figure options (default --width 400); keep in step with the commands in docs/gallery.md.
declare -A options=(
    [fig01b_glossy_sphere]="--width 400 --spp 20"  # 50 spp would take ~100 s on 2 shared cores
    [fig11_fractal]="--width 640"                  # the fractal's detail is lost at 400 pixels
)

render() {
    local name="$1"
    shift
    local start=$SECONDS
    "$raylane" render "scenes/$name.json" -q "$@" -o "$out/${OUT_NAME:-$name}.png" >/dev/null
    printf '%-40s %4d s\n' "${OUT_NAME:-$name}.png" $((SECONDS - start))
}

for scene in scenes/fig*.json; do
    name="$(basename "$scene" .json)"
    # shellcheck disable=SC2086  # the extra options are meant to split into words
    render "$name" ${options[$name]:---width 400}
done

# Figure 9's false colour: nodes tested per ray. The packet path (default) counts per packet of
# 16 rays; the scalar path counts per ray, as the report did.
OUT_NAME=fig09_bunny_bvh_cost render fig09_bunny_bvh --width 400 --aov bvh-cost
OUT_NAME=fig09_bunny_bvh_cost_scalar render fig09_bunny_bvh --width 400 --aov bvh-cost --path scalar

echo "total: $(du -sh "$out" | cut -f1) in $out"

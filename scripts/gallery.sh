#!/usr/bin/env bash
# Gallery: renders every report figure (scenes/fig*.json) into docs/gallery/*.png, as listed in
# docs/gallery.md. With --times it also times each in both paths (the best of 3 runs) and
# rewrites the table under "Render times" there; without, it changes no tracked file unless an
# image changed.
# Usage: scripts/gallery.sh [--times] [path/to/raylane]   (default build/release/raylane)
# Images are 400 pixels wide (aspect kept) at the scene's spp, except where `options` below says
# otherwise (every PNG under 200 KB); renders are deterministic (fixed sample hash seed), so a rerun gives the same files.
set -euo pipefail
export LC_ALL=C  # printf and awk read "1817.3" with a decimal point

with_times=false
if [[ "${1:-}" == "--times" ]]; then
    with_times=true
    shift
fi
raylane="${1:-build/release/raylane}"
# A relative path given by the caller is relative to the caller's directory.
if [[ "$raylane" != /* && -e "$raylane" ]]; then raylane="$PWD/$raylane"; fi
cd "$(dirname "$0")/.."
if [[ ! -x "$raylane" ]]; then
    echo "gallery: raylane binary not found: $raylane (build it or pass its path)" >&2
    exit 1
fi

# The Stanford models and the textures: the shared folder beside the checkout, when it is there.
shared="$(cd .. && pwd)/shared"
[ -d "$shared/models" ] && export RAYLANE_MODEL_PATH="$shared/models:$shared/textures${RAYLANE_MODEL_PATH:+:$RAYLANE_MODEL_PATH}"

out=docs/gallery
mkdir -p "$out"

# Per-figure options (default --width 400); keep in step with the commands in docs/gallery.md.
declare -A options=(
    [fig01b_glossy_sphere]="--width 400 --spp 20"  # the scene's 50 would be the slowest by far
    [fig11_fractal]="--width 440"                  # more detail than 400; 640 takes 366 KB
    # the PNGs stay under 200 KB (blur and noise compress poorly)
    [fig06c_reflection_magenta]="--width 390"
    [fig08a_dof_close]="--width 340"
    [fig08b_dof_middle]="--width 340"
    [fig08c_dof_far]="--width 340"
)

# The render time a `raylane render` printed ("time ... render X ms"), in milliseconds; fails
# when there is none.
render_ms() {
    local ms
    ms=$(sed -n 's/^time .*render \([0-9.]*\) ms$/\1/p')
    [[ "$ms" =~ ^[0-9]+(\.[0-9]+)?$ ]] || { echo "gallery: no render time in the output" >&2; return 1; }
    echo "$ms"
}

grep -q '<!-- render-times begin' docs/gallery.md && grep -q '<!-- render-times end' docs/gallery.md || {
    echo "gallery: docs/gallery.md lacks the render-times markers" >&2
    exit 1
}

render() {
    local name="$1"
    shift
    local start=$SECONDS
    "$raylane" render "scenes/$name.json" -q "$@" -o "$out/${OUT_NAME:-$name}.png" >/dev/null
    printf '%-40s %4d s\n' "${OUT_NAME:-$name}.png" $((SECONDS - start))
}

# The fastest of `runs` renders (the same image each time): one render's time varies by 10-15 %
# on a shared machine. Usage: best_ms OUTPUT RAYLANE-RENDER-ARGS...
runs=3
best_ms() {
    local output="$1" best="" ms
    shift
    for ((r = 0; r < runs; ++r)); do
        ms=$("$raylane" render "$@" -q -o "$output" | render_ms)
        best=$(awk -v a="$best" -v b="$ms" 'BEGIN { print (a == "" || b < a) ? b : a }')
    done
    echo "$best"
}

# Each figure rendered by the packet path into docs/gallery, then by the scalar path (same
# options and samples) into a scratch file, for the table of render times in docs/gallery.md.
scratch="$(mktemp -d)"
trap 'rm -rf "$scratch"' EXIT
times="$scratch/times.md"
for scene in scenes/fig*.json; do
    name="$(basename "$scene" .json)"
    opts="${options[$name]:---width 400}"
    if ! $with_times; then
        # shellcheck disable=SC2086  # the extra options are meant to split into words
        OUT_NAME="$name" render "$name" $opts
        continue
    fi
    # shellcheck disable=SC2086
    packet=$(best_ms "$out/$name.png" "$scene" $opts)
    # shellcheck disable=SC2086
    scalar=$(best_ms "$scratch/$name.png" "$scene" $opts --path scalar)
    printf '%-40s packet %8.1f ms, scalar %8.1f ms\n' "$name.png" "$packet" "$scalar"
    awk -v n="$name" -v o="$opts" -v p="$packet" -v s="$scalar" 'BEGIN {
        printf "| %s | <img src=\"gallery/%s.png\" width=\"96\"> | `%s` | %.0f ms | %.0f ms | %.2fx |\n",
            n, n, o, p, s, (p > 0 ? s / p : 0) }' >>"$times"
done

# the table between the markers of docs/gallery.md
$with_times && awk -v times="$times" '
    /<!-- render-times begin/ { print; skip = 1
        print "| figure | image | options | packet | scalar | speed-up (scalar / packet time) |"
        print "|---|---|---|---:|---:|---:|"
        while ((getline line < times) > 0) print line
        next }
    /<!-- render-times end/ { skip = 0 }
    !skip { print }' docs/gallery.md >"$scratch/gallery.md" && cp "$scratch/gallery.md" docs/gallery.md

# Figure 9's false colour: boxes tested per ray, as the report counted them. Both paths count
# per ray (for this AOV the packet path traverses each ray of its packets on its own), each
# through its own tree: the scalar path's binary tree, the packet path's wide tree.
OUT_NAME=fig09_bunny_bvh_cost render fig09_bunny_bvh --width 400 --aov bvh-cost
OUT_NAME=fig09_bunny_bvh_cost_scalar render fig09_bunny_bvh --width 400 --aov bvh-cost --path scalar

echo "total: $(du -sh "$out" | cut -f1) in $out"

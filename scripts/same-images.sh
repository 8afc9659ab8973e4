#!/usr/bin/env bash
# Shows that the working tree renders every bundled scene, from every view, bit-identical to an
# earlier commit: for restructurings that must not change a pixel.
#
#   scripts/same-images.sh BASE        e.g. scripts/same-images.sh afdfdfc
#
# Builds BASE in a temporary worktree (target/same-images), renders each scene of this tree's
# scenes/ at 40×30, 4 samples a pixel, seed 7, with both builds into target/same-images/{before,after}
# as EXR, and compares their pixels bit for bit (tests/same_images.rs). Exits non-zero on any
# difference or failed render. Takes a few minutes, mostly building BASE.
set -euo pipefail
cd "$(dirname "$0")/.."
base=${1:?usage: scripts/same-images.sh BASE}
work=target/same-images
worktree=$work/base-tree
rm -rf "$work/before" "$work/after"
mkdir -p "$work/before" "$work/after"

cargo build --release --quiet
if [[ -d $worktree ]]; then git worktree remove --force "$worktree"; fi
git worktree add --quiet --detach "$worktree" "$base"
trap 'git worktree remove --force "$worktree"' EXIT
CARGO_TARGET_DIR="$PWD/$work/target" cargo build --release --quiet --manifest-path "$worktree/Cargo.toml"

render_all() { # BINARY OUT_DIR
    local bin=$1 out=$2 scene name view
    for scene in scenes/*.toml; do
        name=$(basename "$scene" .toml)
        "$bin" render "$scene" --width 40 --height 30 --spp 4 --seed 7 --quiet -o "$out/$name.exr"
        for view in $(sed -n 's/^\[views\.\([A-Za-z0-9_-]*\)\]$/\1/p' "$scene"); do
            "$bin" render "$scene" --view "$view" --width 40 --height 30 --spp 4 --seed 7 --quiet \
                -o "$out/$name.view-$view.exr"
        done
    done
}
render_all "$work/target/release/nullpath" "$work/before"
render_all target/release/nullpath "$work/after"
NULLPATH_SAME_IMAGES="$work/before:$work/after" \
    cargo test --release --quiet --test same_images -- --ignored --nocapture

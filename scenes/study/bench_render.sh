#!/usr/bin/env bash
# The full-render table of bench/README.md ("Full-render mode"): nori-bench --render on the
# path-traced pa5 scenes and the dragon scenes, octree vs the Embree-backed accel, same
# samples, interleaved repeats.
#
#   scenes/study/bench_render.sh [BUILD [SHARED [OUT]]]   (defaults: build ../shared /tmp/nori-bench-render)
#
# Environment: THREADS (default 2), REPEATS (3), PT_SPP (8: cbox_mis, table_mis, veach_mis),
# DRAGON_SPP (4: the five dragon scenes). The table (one row per scene) goes to OUT/table.md,
# each scene's JSON to OUT/NAME.json.
set -euo pipefail
BUILD=${1:-build}
SHARED=${2:-../shared}
OUT=${3:-/tmp/nori-bench-render}
THREADS=${THREADS:-2}
REPEATS=${REPEATS:-3}
PT_SPP=${PT_SPP:-8}
DRAGON_SPP=${DRAGON_SPP:-4}
HERE=$(cd "$(dirname "$0")/.." && pwd)
mkdir -p "$OUT"

# bench NAME SCENE SPP [-a DIR ...]: one scene; its Markdown and JSON into OUT.
bench() {
    local name=$1 scene=$2 spp=$3
    shift 3
    echo "nori-bench --render: $name ($spp spp)" >&2
    "$BUILD/bench/nori-bench" --scene "$scene" --render --spp "$spp" --threads "$THREADS" --repeats "$REPEATS" \
        --render-images "$OUT/$name" --json "$OUT/$name.json" --markdown "$OUT/$name.md" "$@"
}

for s in cbox/cbox_mis table/table_mis veach_mi/veach_mis; do
    bench "$(basename $s)" "$SHARED/nori-scenes/pa5/$s.xml" "$PT_SPP"
done
for s in normals ao simple smooth rough; do
    bench "dragon-$s" "$HERE/dragon-$s.xml" "$DRAGON_SPP" -a "$SHARED/meshes" -a "$SHARED/nori-scenes/pa5/ajax"
done

# One table: the header once, then each scene's row.
{
    head -n 4 "$OUT/cbox_mis.md" | tail -n 2
    for f in cbox_mis table_mis veach_mis dragon-normals dragon-ao dragon-simple dragon-smooth dragon-rough; do
        grep '^| [a-z_-]*\.xml' "$OUT/$f.md"
    done
} | tee "$OUT/table.md"

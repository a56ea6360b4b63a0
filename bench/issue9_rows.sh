#!/usr/bin/env bash
# The 28 rows of issue 9's table (bench/README.md, "Every kind of scene"): the 17 generated
# shapes (seed 1, default sizes), Nori's pa5 scenes and the shared meshes, measured with one or
# more builds of nori-bench. For each row, run k = 1..RUNS, the builds take turns (row by row,
# so that the machine's drift hits every build alike).
#
# usage: bench/issue9_rows.sh SHARED_DIR OUT_DIR RUNS BUILD_DIR [BUILD_DIR ...]
#   OUT_DIR/b<i>/run<k>/<row>.json for build i (1-based); then, per build:
#   python3 bench/summary.py OUT_DIR/b1/run*/*.json --floors --median
# ROWS="city grass ..." limits the rows; an absolute path to a scene XML is a row too.
set -euo pipefail
if [ $# -lt 4 ]; then
  sed -n '2,10p' "$0" | sed 's/^# \{0,1\}//' >&2
  exit 2
fi
S=$1; OUT=$2; RUNS=$3; shift 3
BUILDS=("$@")
for b in "${BUILDS[@]}"; do
  [ -x "$b/bench/nori-bench" ] || { echo "issue9_rows.sh: $b/bench/nori-bench not found" >&2; exit 1; }
done
[ -d "$S/meshes" ] || { echo "issue9_rows.sh: $S/meshes not found (SHARED_DIR is ../shared)" >&2; exit 1; }
SHAPES=$OUT/shapes
[ -d "$SHAPES" ] || "${BUILDS[0]}/scenes/generators/nori-genscene" all "$SHAPES" > /dev/null
ROWS=${ROWS:-"city grass heightfield sphere room wide tabletop stadium coplanar forest office towers clutter hair sparse park speck cbox table veach dragon res2 res3 res4 bunny igea nefertiti beast"}
mesh() { if [ -f "$S/meshes/$1" ]; then echo "$S/meshes/$1"; else echo "$S/meshes/$1.gz"; fi; }
for r in $ROWS; do
  case $r in
    cbox) a=(--scene "$S/nori-scenes/pa5/cbox/cbox_mis.xml");;
    table) a=(--scene "$S/nori-scenes/pa5/table/table_mis.xml");;
    veach) a=(--scene "$S/nori-scenes/pa5/veach_mi/veach_mis.xml");;
    dragon) a=(--mesh "$(mesh dragon_vrip.obj)");;
    res2|res3|res4) a=(--mesh "$(mesh dragon_vrip_$r.obj)");;
    bunny) a=(--mesh "$S/meshes/stanford-bunny.obj");;
    igea) a=(--mesh "$(mesh igea.obj)");;
    nefertiti|beast) a=(--mesh "$S/meshes/$r.obj");;
    /*) a=(--scene "$r"); r=$(basename "$r" .xml);;
    *) a=(--scene "$SHAPES/$r.xml");;
  esac
  for k in $(seq "$RUNS"); do
    for i in "${!BUILDS[@]}"; do
      dir=$OUT/b$((i + 1))/run$k
      mkdir -p "$dir"
      echo "[issue9_rows] $r run $k build $((i + 1))" >&2
      "${BUILDS[$i]}/bench/nori-bench" "${a[@]}" --default-only --threads 1 --no-brute --cpu-time \
        --json "$dir/$r.json" > "$dir/$r.log" 2>&1 || { echo "issue9_rows.sh: $r failed (see $dir/$r.log)" >&2; exit 1; }
    done
  done
done

#!/usr/bin/env bash
# render_and_check.sh NORI PYTHON SCENE.xml MESHDIR OUTDIR: renders SCENE at 1 spp with its
# meshes from MESHDIR, then runs check_default.py on its statistics and PNG; exit status of
# the first step that fails.
set -euo pipefail
nori=$1 python=$2 scene=$3 meshes=$4 out=$5
name=$(basename "$scene" .xml)
mkdir -p "$out"
"$nori" "$scene" -a "$meshes" --spp 1 -q -o "$out/$name" --stats-json "$out/$name.json"
"$python" "$(dirname "$0")/check_default.py" "$out/$name.json" "$out/$name.png"

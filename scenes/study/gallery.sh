#!/usr/bin/env bash
# The gallery of scenes/README.md: every pa4/pa5 scene of Nori rendered unmodified (sample
# count lowered with --spp), the dragon counterparts of the PA5 Ajax scenes, the default
# scene, and the consistency study's references; written as small PNG thumbnails into
# scenes/gallery/.
#
#   scenes/study/gallery.sh [BUILD [SHARED [OUT [STUDY]]]]
#       (defaults: build ../shared /tmp/nori-gallery /tmp/nori-consistency)
#
# Environment: SPP (default 16), THREADS (2). The renders stay in OUT (EXR, PNG,
# --stats-json); a render already there is not repeated. A thumbnail is the render's PNG
# averaged over 2x2 pixel blocks (in sRGB values: a thumbnail, not a measurement), which also
# takes its noise down as 64 spp would; the default scene is rendered at its own 32 spp, as
# the README's first command renders it. Of the pa5 scenes only the path_mis renders are kept
# (the study's strips show path_mats and path_ems). STUDY: consistency.sh's output
# folder, for the reference and equal-spp strips (left out when it is missing).
set -euo pipefail
BUILD=${1:-build}
SHARED=${2:-../shared}
OUT=${3:-/tmp/nori-gallery}
STUDY=${4:-/tmp/nori-consistency}
SPP=${SPP:-16}
THREADS=${THREADS:-2}
HERE=$(cd "$(dirname "$0")/.." && pwd)
GALLERY="$HERE/gallery"
mkdir -p "$OUT" "$GALLERY"

# render SCENE NAME [nori options]: skipped if OUT/NAME.png is there.
render() {
    local scene=$1 name=$2
    shift 2
    if [ ! -f "$OUT/$name.png" ]; then
        echo "rendering $name" >&2
        "$BUILD/nori" "$scene" -t "$THREADS" -q -o "$OUT/$name" --stats-json "$OUT/$name.json" "$@"
    fi
}

N="$SHARED/nori-scenes"
for s in pa4/cbox/cbox-whitted pa4/cbox/cbox-distributed pa4/motto/motto-diffuse pa4/motto/motto-dielectric \
         pa5/cbox/cbox_mats pa5/cbox/cbox_ems pa5/cbox/cbox_mis pa5/table/table_mats pa5/table/table_ems \
         pa5/table/table_mis pa5/veach_mi/veach_mats pa5/veach_mi/veach_ems pa5/veach_mi/veach_mis; do
    render "$N/$s.xml" "$(basename "$s")" --spp "$SPP"
done
for s in smooth rough; do
    render "$HERE/dragon-$s.xml" "dragon-$s" --spp "$SPP" -a "$SHARED/meshes" -a "$N/pa5/ajax"
done
render "$HERE/default.xml" default -a "$BUILD/scenes"

/usr/bin/python3 - "$OUT" "$GALLERY" "$STUDY" <<'PY'
import os, sys
import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

out, gallery, study = sys.argv[1:4]

def load(path):
    return plt.imread(path)[:, :, :3]

def half(img):
    h, w = img.shape[0] // 2 * 2, img.shape[1] // 2 * 2
    img = img[:h, :w]
    return 0.25 * (img[0::2, 0::2] + img[1::2, 0::2] + img[0::2, 1::2] + img[1::2, 1::2])

def save(name, img):
    plt.imsave(os.path.join(gallery, name + ".png"), np.clip(img, 0, 1))

# Only the path_mis render of each pa5 scene: the study's strips show the other two.
for name in ["cbox-whitted", "cbox-distributed", "motto-diffuse", "motto-dielectric",
             "cbox_mis", "table_mis", "veach_mis", "dragon-smooth", "dragon-rough", "default"]:
    save(name, half(load(os.path.join(out, name + ".png"))))

# The study: references, and one strip per scene with the three integrators at 16 spp (cbox,
# table) or at equal CPU time (veach_mi), next to the reference.
if os.path.isdir(study):
    for scene in ["cbox", "table"]:
        row = [load(os.path.join(study, f"{scene}-{it}-16.png")) for it in ["mats", "ems", "mis"]]
        row.append(load(os.path.join(study, f"{scene}-ref.png")))
        save(f"study-{scene}", np.concatenate(row, axis=1))
    row = [load(os.path.join(study, f"veach-{it}-equal128.png")) for it in ["mats", "ems", "mis"]]
    row.append(load(os.path.join(study, "veach-ref.png")))
    save("study-veach", np.concatenate(row, axis=1))
PY
du -sh "$GALLERY"

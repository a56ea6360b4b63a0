#!/usr/bin/env bash
# Consistency study of scenes/README.md: the three path tracers (path_mats, path_ems,
# path_mis) are unbiased estimators of one image.
#
#   scenes/study/consistency.sh [BUILD [SHARED [OUT]]]   (defaults: build ../shared /tmp/nori-consistency)
#
# Nori's pa5 scene files are rendered unmodified except for the image size: a copy with
# width and height divided by DIV is written to OUT and its meshes are found with -a (the
# scene's folder), so the study runs in minutes on 2 shared cores.
#
# cbox and table: a path_mis reference at REF_SPP samples per pixel, then every integrator at
# each of SPP_LIST, compared with the reference by nori-imgdiff (means with a standard error,
# RMSE, fitted slope of log RMSE over log spp). The reference's own noise adds
# RMSE_ref^2 = RMSE_1^2 / REF_SPP to every squared RMSE; with REF_SPP 16 times the largest
# count it bends the slope by less than 0.01.
# veach_mi: the three integrators at equal CPU time (TIME_SPP samples of path_mis set a
# budget; the cost per sample of each integrator comes from a probe render of PROBE_SPP
# samples). CPU time (user + system, bash's `times`) instead of wall-clock time, because the
# machine is shared and wall-clock time depends on the other users' load. The comparison is
# made over the whole image and over VEACH_REGION (default 0,0.4,1,1: below the light
# sources, i.e. the plates, the wall and the floor): the anti-aliased edges of the directly
# visible lights (radiance up to 901) have the same large variance per sample under every
# integrator, so over the whole image they dominate the RMSE and reward whichever integrator
# takes the most samples in the budget, not the best estimator.
# Renders are left in OUT (EXR, PNG, --stats-json); tables go to OUT/*.md and OUT/*.json.
# Environment: DIV (default 4), REF_SPP (2048), SPP_LIST ("4 8 16 32 64 128"), THREADS (2),
# VEACH_REF_SPP (2048), TIME_SPP ("32 128": one equal-time comparison per budget), PROBE_SPP (32), VEACH_REGION (0,0.4,1,1).
set -euo pipefail
BUILD=${1:-build}
SHARED=${2:-../shared}
OUT=${3:-/tmp/nori-consistency}
DIV=${DIV:-4}
REF_SPP=${REF_SPP:-2048}
SPP_LIST=${SPP_LIST:-"4 8 16 32 64 128"}
THREADS=${THREADS:-2}
VEACH_REF_SPP=${VEACH_REF_SPP:-2048}
TIME_SPP=${TIME_SPP:-"32 128"}
PROBE_SPP=${PROBE_SPP:-32}
VEACH_REGION=${VEACH_REGION:-0,0.4,1,1}
NORI="$BUILD/nori"
IMGDIFF="$BUILD/bench/nori-imgdiff"
mkdir -p "$OUT"

# scaled DIR FILE: writes OUT/FILE with the camera's width and height divided by DIV.
scaled() {
    /usr/bin/python3 - "$1/$2" "$OUT/$2" "$DIV" <<'PY'
import re, sys
src, dst, div = sys.argv[1], sys.argv[2], int(sys.argv[3])
text = open(src).read()
text = re.sub(r'(name="(?:width|height)"\s+value=")(\d+)', lambda m: m.group(1) + str(int(m.group(2)) // div), text)
open(dst, "w").write(text)
PY
}

# render DIR FILE SPP NAME: one render of the scaled scene, its stats and CPU seconds
# (OUT/NAME.cpu) next to it; skipped if already there.
render() {
    if [ ! -f "$OUT/$4.exr" ]; then
        echo "rendering $4 ($3 spp)" >&2
        scaled "$1" "$2"
        cpu_seconds > "$OUT/.before"
        "$NORI" "$OUT/$2" -a "$1" --spp "$3" -t "$THREADS" -q -o "$OUT/$4" --stats-json "$OUT/$4.json"
        cpu_seconds > "$OUT/.after"
        /usr/bin/python3 -c "print(round($(cat "$OUT/.after") - $(cat "$OUT/.before"), 3))" > "$OUT/$4.cpu"
    fi
}

# cpu_seconds: user + system CPU seconds of this shell's finished children so far. `times`
# runs in this shell (in a $(...) subshell it would report the subshell's children).
cpu_seconds() {
    times > "$OUT/.times"
    /usr/bin/python3 -c "
import re, sys
s = 0.0
for m, sec in re.findall(r'(\d+)m([\d.]+)s', open(sys.argv[1]).read().splitlines()[-1]): s += 60 * int(m) + float(sec)
print(s)" "$OUT/.times"
}

for scene in cbox table; do
    dir="$SHARED/nori-scenes/pa5/$scene"
    render "$dir" "${scene}_mis.xml" "$REF_SPP" "$scene-ref"
    for it in mats ems mis; do
        files=() counts=()
        for spp in $SPP_LIST; do
            render "$dir" "${scene}_$it.xml" "$spp" "$scene-$it-$spp"
            files+=("$OUT/$scene-$it-$spp.exr")
            counts+=("$spp")
        done
        (IFS=,; "$IMGDIFF" "$OUT/$scene-ref.exr" "${files[@]}" --spp "${counts[*]}" \
            --json "$OUT/$scene-$it.json") | tee "$OUT/$scene-$it.md"
    done
done

# veach_mi at equal CPU time: path_mis at each TIME_SPP sets a budget; the others get the spp
# that their measured CPU cost per sample buys in that time.
dir="$SHARED/nori-scenes/pa5/veach_mi"
render "$dir" veach_mis.xml "$VEACH_REF_SPP" veach-ref
for it in mats ems mis; do render "$dir" "veach_$it.xml" "$PROBE_SPP" "veach-$it-probe"; done
for tspp in $TIME_SPP; do
    budget=$(/usr/bin/python3 -c "print(max(0.001, $(cat "$OUT/veach-mis-probe.cpu")) / $PROBE_SPP * $tspp)")
    files=() counts=()
    for it in mats ems mis; do
        spp=$(/usr/bin/python3 -c "print(max(1, round($budget / (max(0.001, $(cat "$OUT/veach-$it-probe.cpu")) / $PROBE_SPP))))")
        render "$dir" "veach_$it.xml" "$spp" "veach-$it-equal$tspp"
        files+=("$OUT/veach-$it-equal$tspp.exr")
        counts+=("$spp")
    done
    "$IMGDIFF" "$OUT/veach-ref.exr" "${files[@]}" --json "$OUT/veach-equal$tspp.json" | tee "$OUT/veach-equal$tspp.md"
    "$IMGDIFF" "$OUT/veach-ref.exr" "${files[@]}" --region "$VEACH_REGION" --json "$OUT/veach-equal$tspp-region.json" |
        tee -a "$OUT/veach-equal$tspp.md"
    i=0
    for it in mats ems mis; do
        echo "veach-$it-equal$tspp: ${counts[$i]} spp, $(cat "$OUT/veach-$it-equal$tspp.cpu") CPU s (probe: $(cat "$OUT/veach-$it-probe.cpu") CPU s for $PROBE_SPP spp)"
        i=$((i + 1))
    done | tee -a "$OUT/veach-equal$tspp.md"
done

# Summary tables (the ones in scenes/README.md) from the JSON files above.
/usr/bin/python3 - "$OUT" "$TIME_SPP" <<'PY' | tee "$OUT/summary.md"
import json, sys
out, budgets = sys.argv[1], sys.argv[2].split()
print("| scene | integrator | spp | mean (ref) | z of mean − ref at each spp | max abs z | RMSE at 4 / 16 / 128 spp | fitted slope |")
print("|---|---|---|---:|---|---:|---|---:|")
for scene in ["cbox", "table"]:
    for it in ["mats", "ems", "mis"]:
        j = json.load(open(f"{out}/{scene}-{it}.json"))
        im = j["images"]
        rm = {i["spp"]: i["rmse"] for i in im}
        zs = " ".join(f"{i['z']:+.1f}" for i in im)
        spp = ",".join(str(i["spp"]) for i in im)
        print(f"| {scene} | path_{it} | {spp} | {im[-1]['mean']:.4f} ({im[0]['mean_ref']:.4f}) | {zs} | "
              f"{max(abs(i['z']) for i in im):.2f} | {rm.get(4, float('nan')):.3g} / {rm.get(16, float('nan')):.3g} / "
              f"{rm.get(128, float('nan')):.3g} | {j['slope']:.3f} |")
print()
print("| budget (path_mis spp) | integrator | spp | CPU s | whole image: RMSE (z of mean) | below the lights: RMSE (z of mean) |")
print("|---:|---|---:|---:|---|---|")
for b in budgets:
    whole = json.load(open(f"{out}/veach-equal{b}.json"))["images"]
    region = json.load(open(f"{out}/veach-equal{b}-region.json"))["images"]
    for k, it in enumerate(["mats", "ems", "mis"]):
        cpu = open(f"{out}/veach-{it}-equal{b}.cpu").read().strip()
        js = json.load(open(f"{out}/veach-{it}-equal{b}.json"))
        print(f"| {b} | path_{it} | {js['spp']} | {cpu} | {whole[k]['rmse']:.4g} ({whole[k]['z']:+.2f}) | "
              f"{region[k]['rmse']:.4g} ({region[k]['z']:+.2f}) |")
PY

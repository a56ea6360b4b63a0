#!/usr/bin/env bash
# Path-tracing throughput of scenes/README.md: Mrays/s of nori on Nori's cbox_mis, table_mis
# and veach_mis (unmodified; --spp lowers the sample count) at 1 and 2 threads, from
# --stats-json (rays by kind: camera, closest-hit, shadow; rays = closest-hit + shadow).
#
#   scenes/study/mrays.sh [BUILD [SHARED [OUT]]]   (defaults: build ../shared /tmp/nori-mrays)
#
# Environment: SPP (default 8), REPEATS (3: the median render time is used). Besides the
# wall-clock rate (rays / render_ms) it prints rays per CPU second of the whole process
# (load and build included, from bash's `times`), which a shared machine disturbs less.
set -euo pipefail
BUILD=${1:-build}
SHARED=${2:-../shared}
OUT=${3:-/tmp/nori-mrays}
SPP=${SPP:-8}
REPEATS=${REPEATS:-3}
mkdir -p "$OUT"

# cpu_seconds FILE: user + system CPU seconds of this shell's finished children, into FILE.
cpu_seconds() {
    times > "$OUT/.times"
    /usr/bin/python3 -c "
import re, sys
print(sum(60 * int(m) + float(s) for m, s in re.findall(r'(\d+)m([\d.]+)s', open(sys.argv[1]).read().splitlines()[-1])))" \
        "$OUT/.times" > "$1"
}

echo "| scene | W×H×spp | threads | camera | closest-hit | shadow | rays | render ms (median of $REPEATS) | Mrays/s | Mrays per CPU s |"
echo "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|"
for s in cbox/cbox_mis table/table_mis veach_mi/veach_mis; do
    name=$(basename "$s")
    for t in 1 2; do
        for r in $(seq 1 "$REPEATS"); do
            cpu_seconds "$OUT/.before"
            "$BUILD/nori" "$SHARED/nori-scenes/pa5/$s.xml" --spp "$SPP" -t "$t" -q -o "$OUT/$name-t$t" \
                --stats-json "$OUT/$name-t$t-$r.json"
            cpu_seconds "$OUT/.after"
            /usr/bin/python3 -c "print($(cat "$OUT/.after") - $(cat "$OUT/.before"))" > "$OUT/$name-t$t-$r.cpu"
        done
        /usr/bin/python3 - "$OUT" "$name" "$t" "$REPEATS" <<'PY'
import json, statistics, sys
out, name, t, repeats = sys.argv[1], sys.argv[2], sys.argv[3], int(sys.argv[4])
runs = [json.load(open(f"{out}/{name}-t{t}-{r}.json")) for r in range(1, repeats + 1)]
cpus = [float(open(f"{out}/{name}-t{t}-{r}.cpu").read()) for r in range(1, repeats + 1)]
j = runs[0]
ms = statistics.median(x["render_ms"] for x in runs)
cpu = statistics.median(cpus)
print(f"| {name} | {j['width']}×{j['height']}×{j['spp']} | {t} | {j['rays_camera']:,} | {j['rays_closest_hit']:,} | "
      f"{j['rays_shadow']:,} | {j['rays']:,} | {ms:.0f} | {j['rays'] / ms / 1000:.2f} | {j['rays'] / cpu / 1e6:.2f} |")
PY
    done
done

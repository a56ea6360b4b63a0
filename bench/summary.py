#!/usr/bin/env python3
"""One row per input of nori-bench JSON results, in the layout of issue 9's table: the octree's
default run against Embree's default mode (same rays, same run): ray rates as octree/Embree
(higher is better), build time and bytes as octree/Embree (lower is better), and mismatches
against Embree robust with Embree default's own in brackets, and the exact referee's count of wrong
answers on the disputed rays (octree's, Embree default's in brackets).

usage: bench/summary.py RESULT.json [RESULT.json ...] [--names NAME,NAME,...]
"""
import json
import sys


def load(paths):
    rows = []
    for path in paths:
        with open(path) as f:
            data = json.load(f)
        rows.extend(data if isinstance(data, list) else [data])
    return rows


def default_run(result):
    runs = [r for r in result["runs"] if r.get("accel") == "octree"]
    marked = [r for r in runs if r.get("default")]
    return (marked or runs or [None])[0]


def row(result, name):
    run = default_run(result)
    if run is None:
        return None
    e = result["embree"]
    sets = ["primary", "diffuse", "shadow"]
    ratios = ["%.2f×" % run[s]["ratio_vs_embree"] for s in sets]
    build = "%.2f×" % (run["build_ms"] / e["build_ms"]) if e["build_ms"] > 0 else "–"
    size = "%.2f×" % (run["bytes"] / e["bytes"]) if e.get("bytes") and run.get("bytes") else "–"
    mism = "/".join(str(run[s]["mismatches"]) for s in sets)
    own = "/".join(str(e[s]["mismatches"]) for s in sets)
    # Exact referee on the disputed rays (octree or Embree default differs from robust).
    if all("exact_wrong" in run[s] for s in sets):
        exact = "%s (%s)" % ("/".join(str(run[s]["exact_wrong"]) for s in sets),
                             "/".join(str(run[s]["embree_exact_wrong"]) for s in sets))
    else:
        exact = "–"
    tris = result["triangles"]
    tris = "%dk" % round(tris / 1000) if tris >= 1000 else str(tris)
    return "| %s | %s | %s | %s | %s | %s (%s) | %s |" % (name, tris, " | ".join(ratios), build, size, mism, own, exact)


def main(argv):
    names = None
    if "--names" in argv:
        i = argv.index("--names")
        names = argv[i + 1].split(",")
        argv = argv[:i] + argv[i + 2:]
    if not argv:
        print(__doc__, file=sys.stderr)
        return 2
    results = load(argv)
    print("| scene | tris | primary | diffuse | shadow | build | bytes | mismatches p/d/s (Embree default's own) "
          "| exact errors p/d/s (Embree default's) |")
    print("|---|---:|---:|---:|---:|---:|---:|---|---|")
    for k, result in enumerate(results):
        name = names[k] if names and k < len(names) else result["mesh"]
        line = row(result, name)
        if line:
            print(line)
    print("\nprimary/diffuse/shadow: octree rays/s over Embree default's, interleaved (> 1: faster than Embree); "
          "build, bytes: octree over Embree (< 1: less); mismatches: against Embree robust; exact errors: "
          "answers that are not the exact closest hit (decided in double on the triangles the answers name) "
          "on the rays where the octree or Embree default differs from Embree robust.")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

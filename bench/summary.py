#!/usr/bin/env python3
"""One row per input of nori-bench JSON results, in the layout of issue 9's table: the octree's
default run against Embree's default mode (same rays, same run): ray rates as octree/Embree
(higher is better), build time and bytes as octree/Embree (lower is better), and mismatches
against Embree robust with Embree default's own in brackets, and the exact referee's count of wrong
answers on the disputed rays (octree's, Embree default's in brackets).

With --floors, a figure below issue 9's floor is marked ✗ (primary >= 0.7, diffuse >= 0.6,
shadow >= 0.7, build <= 1, bytes <= 1, mismatches against robust <= Embree default's own) and a
last line counts the rows that meet each floor.

With --median, results for the same input (runs of nori-bench in separate processes, e.g. one
directory of JSON files per run) become one row: the median of each ratio over the runs. On a
shared machine one process's ratios move by up to +-20 %; the median of three is steadier.
Mismatches are the same in every run (same rays, deterministic answers); the first run's are shown.

usage: bench/summary.py RESULT.json [RESULT.json ...] [--names NAME,NAME,...] [--floors] [--median]
"""
import copy
import json
import statistics
import sys


def load(paths):
    rows = []
    for path in paths:
        with open(path) as f:
            try:
                data = json.load(f)
            except ValueError as e:
                raise ValueError("%s: not nori-bench JSON (%s)" % (path, e)) from None
        rows.extend(data if isinstance(data, list) else [data])
    return rows


def default_run(result):
    runs = [r for r in result["runs"] if r.get("accel") == "octree"]
    marked = [r for r in runs if r.get("default")]
    return (marked or runs or [None])[0]


FLOORS = {"primary": 0.7, "diffuse": 0.6, "shadow": 0.7}
FLOOR_NAMES = ["primary", "diffuse", "shadow", "build", "bytes", "mismatches"]


def row(result, name, floors=False, met=None):
    run = default_run(result)
    if run is None:
        return None
    e = result["embree"]
    sets = ["primary", "diffuse", "shadow"]
    ok = {}
    ratios = []
    for s in sets:
        ok[s] = run[s]["ratio_vs_embree"] >= FLOORS[s]
        ratios.append("%.2f×" % run[s]["ratio_vs_embree"] + ("" if ok[s] or not floors else " ✗"))
    b = run["build_ms"] / e["build_ms"] if e["build_ms"] > 0 else None
    ok["build"] = b is None or b <= 1.0
    build = ("%.2f×" % b if b is not None else "–") + ("" if ok["build"] or not floors else " ✗")
    z = run["bytes"] / e["bytes"] if e.get("bytes") and run.get("bytes") else None
    ok["bytes"] = z is None or z <= 1.0
    size = ("%.2f×" % z if z is not None else "–") + ("" if ok["bytes"] or not floors else " ✗")
    ok["mismatches"] = all(run[s]["mismatches"] <= e[s]["mismatches"] for s in sets)
    mism = "/".join(str(run[s]["mismatches"]) for s in sets)
    own = "/".join(str(e[s]["mismatches"]) for s in sets)
    mark = "" if ok["mismatches"] or not floors else " ✗"
    if met is not None:
        for k in FLOOR_NAMES:
            met[k] = met.get(k, 0) + (1 if ok[k] else 0)
    # Exact referee on the disputed rays (octree or Embree default differs from robust).
    if all("exact_wrong" in run[s] for s in sets):
        exact = "%s (%s)" % ("/".join(str(run[s]["exact_wrong"]) for s in sets),
                             "/".join(str(run[s]["embree_exact_wrong"]) for s in sets))
    else:
        exact = "–"
    tris = result["triangles"]
    tris = "%dk" % round(tris / 1000) if tris >= 1000 else str(tris)
    return "| %s | %s | %s | %s | %s | %s (%s)%s | %s |" % (name, tris, " | ".join(ratios), build, size, mism, own, mark, exact)


def median_of(results):
    """One result whose octree default run and build/bytes ratios are the medians of \p results
    (runs of one input); everything else is the first run's."""
    first = copy.deepcopy(results[0])
    if len(results) == 1:
        return first
    runs = [default_run(r) for r in results]
    if any(r is None for r in runs):
        return first
    out = default_run(first)
    for s in ["primary", "diffuse", "shadow"]:
        out[s]["ratio_vs_embree"] = statistics.median(r[s]["ratio_vs_embree"] for r in runs)
    e = first["embree"]
    if e["build_ms"] > 0:
        out["build_ms"] = e["build_ms"] * statistics.median(
            run["build_ms"] / r["embree"]["build_ms"] for run, r in zip(runs, results))
    if e.get("bytes") and out.get("bytes"):
        out["bytes"] = e["bytes"] * statistics.median(run["bytes"] / r["embree"]["bytes"] for run, r in zip(runs, results))
    first["median_of"] = len(results)
    return first


def machine_line(result):
    """Where a result was measured (absent from files written before nori-bench recorded it)."""
    m = result.get("machine")
    if not m:
        return "machine not recorded"
    return "%s: %s, octree kernels %d lanes" % (m["cpu"], "AVX-512 (Embree's kernels too)" if m["cpu_avx512"]
                                                 else "no AVX-512 (Embree runs AVX2 or narrower)", m["octree_lanes"])


def main(argv):
    names = None
    if "--names" in argv:
        i = argv.index("--names")
        names = argv[i + 1].split(",")
        argv = argv[:i] + argv[i + 2:]
    if not argv or "-h" in argv or "--help" in argv:
        print(__doc__, file=sys.stderr if not argv else sys.stdout)
        return 2 if not argv else 0
    unknown = [a for a in argv if a.startswith("-") and a not in ("--floors", "--median")]
    if unknown:
        print("summary.py: unknown option %s (see --help)" % unknown[0], file=sys.stderr)
        return 2
    floors = "--floors" in argv
    median = "--median" in argv
    argv = [a for a in argv if a not in ("--floors", "--median")]
    try:
        results = load(argv)
    except (OSError, ValueError) as e:
        print("summary.py: %s" % e, file=sys.stderr)
        return 1
    if median:
        groups = {}
        for r in results:
            groups.setdefault(r["mesh"], []).append(r)
        results = [median_of(g) for g in groups.values()]
    met = {}
    print("| scene | tris | primary | diffuse | shadow | build | bytes | mismatches p/d/s (Embree default's own) "
          "| exact errors p/d/s (Embree default's) |")
    print("|---|---:|---:|---:|---:|---:|---:|---|---|")
    for k, result in enumerate(results):
        name = names[k] if names and k < len(names) else result["mesh"]
        line = row(result, name, floors, met)
        if line:
            print(line)
    machines = sorted({machine_line(r) for r in results})
    print("\n" + "; ".join(machines) + ".")
    if median:
        counts = sorted({r.get("median_of", 1) for r in results})
        print("\nEach ratio: the median of %s runs." % "/".join(str(c) for c in counts))
    if floors:
        print("\nFloors met, of %d rows: " % len(results) + ", ".join("%s %d" % (k, met.get(k, 0)) for k in FLOOR_NAMES))
    print("\nprimary/diffuse/shadow: octree rays/s over Embree default's, interleaved (> 1: faster than Embree); "
          "build, bytes: octree over Embree (< 1: less); mismatches: against Embree robust; exact errors: "
          "answers that are not the exact closest hit (decided in double on the triangles the answers name) "
          "on the rays where the octree or Embree default differs from Embree robust.")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

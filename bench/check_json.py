#!/usr/bin/env python3
"""Check that a nori-bench JSON file has the shape of issue 4 (used by ctest).

usage: check_json.py FILE [--min-runs N] [--properties NAME=VALUE,...]

--properties: every octree run must carry exactly these --octree-set properties.

Checks structure, types and internal arithmetic (Mrays/s = rays / ms / 1000, mismatches
<= rays); never a timing. Exits 1 with one line per problem.
"""
import json
import sys

SETS = ("primary", "diffuse", "shadow")
from json_checks import fail, number, problems


def string(obj, key, where, choices=None):
    v = obj.get(key)
    if not isinstance(v, str) or not v:
        fail(where, f"'{key}' is {v!r}, expected a non-empty string")
    elif choices and v not in choices:
        fail(where, f"'{key}' = {v!r}, expected one of {choices}")
    return v


def check_set(obj, name, where, contender):
    if not isinstance(obj.get(name), dict):
        fail(where, f"missing ray set '{name}'")
        return
    s = obj[name]
    w = f"{where}.{name}"
    rays = number(s, "rays", w, 0, integral=True)
    ms = number(s, "ms", w, 0)
    mrays = number(s, "mrays_s", w, 0)
    if rays and ms and mrays is not None and ms > 0:
        expected = rays / (ms * 1e3)
        if abs(mrays - expected) > 1e-6 * max(1.0, expected):
            fail(w, f"mrays_s {mrays} != rays / ms / 1000 = {expected}")
    if contender:
        ratio = number(s, "ratio_vs_embree", w, 0)
        mism = number(s, "mismatches", w, 0, integral=True)
        if mism is not None and rays is not None and mism > rays:
            fail(w, f"mismatches {mism} > rays {rays}")
        if ratio is not None and ratio <= 0:
            fail(w, "ratio_vs_embree must be positive")
        if "disputed" in s:
            disputed = number(s, "disputed", w, 0, integral=True)
            for key in ("exact_wrong", "embree_exact_wrong", "reference_exact_wrong"):
                wrong = number(s, key, w, 0, integral=True)
                if wrong is not None and disputed is not None and wrong > disputed:
                    fail(w, f"{key} {wrong} > disputed {disputed}")
            if mism is not None and disputed is not None and disputed < mism:
                fail(w, f"disputed {disputed} < mismatches {mism}: every mismatch is refereed")


def check_mesh(m, where, properties=None):
    if not isinstance(m, dict):
        fail(where, "expected an object")
        return 0
    string(m, "mesh", where)
    number(m, "triangles", where, 1, integral=True)
    number(m, "threads", where, 1, integral=True)
    number(m, "load_ms", where, 0)
    if m.get("clock", "wall") not in ("wall", "cpu"):
        fail(where, f"clock {m.get('clock')!r} is neither 'wall' nor 'cpu'")
    machine = m.get("machine")
    if not isinstance(machine, dict):
        fail(where, "missing 'machine' (cpu, cpu_avx512, octree_lanes)")
    else:
        string(machine, "cpu", f"{where}.machine")
        if not isinstance(machine.get("cpu_avx512"), bool):
            fail(f"{where}.machine", f"cpu_avx512 is {machine.get('cpu_avx512')!r}, expected true or false")
        if machine.get("octree_lanes") not in (1, 8, 16):
            fail(f"{where}.machine", f"octree_lanes is {machine.get('octree_lanes')!r}, expected 1, 8 or 16")
    e = m.get("embree")
    if not isinstance(e, dict):
        fail(where, "missing 'embree'")
    else:
        number(e, "build_ms", f"{where}.embree", 0)
        number(e, "bytes", f"{where}.embree", 0, integral=True)
        for name in SETS:
            check_set(e, name, f"{where}.embree", False)
        if e.get("primary", {}).get("rays", 0) <= 0:
            fail(f"{where}.embree.primary", "no rays")
    r = m.get("embree_robust")
    if isinstance(r, dict):
        for name in SETS:
            check_set(r, name, f"{where}.embree_robust", True)
            # The reference against itself: any mismatch means the harness is not deterministic.
            if r.get(name, {}).get("mismatches", 0) != 0:
                fail(f"{where}.embree_robust.{name}", "the reference disagrees with itself")
    runs = m.get("runs")
    if not isinstance(runs, list):
        fail(where, "'runs' is not a list")
        return 0
    for i, run in enumerate(runs):
        w = f"{where}.runs[{i}]"
        if not isinstance(run, dict):
            fail(w, "expected an object")
            continue
        accel = string(run, "accel", w)
        if not isinstance(run.get("default"), bool):
            fail(w, "'default' is not a boolean")
        number(run, "build_ms", w, 0)
        if accel == "octree":
            if "buildRule" in run:
                string(run, "buildRule", w, ("sah", "count", "seed"))
            number(run, "maxDepth", w, 0, integral=True)
            number(run, "leafSize", w, 1, integral=True)
            string(run, "overlap", w, ("exact", "bbox"))
            string(run, "traversal", w)
            string(run, "intersector", w, ("mt", "watertight"))
            number(run, "internal_nodes", w, 0, integral=True)
            number(run, "leaf_nodes", w, 1, integral=True)
            number(run, "avg_tris_per_leaf", w, 0)
            number(run, "bytes", w, 1, integral=True)
            given = run.get("properties", {})
            if properties is not None and given != properties:
                fail(w, f"'properties' is {given!r}, expected {properties!r}")
        for name in SETS:
            check_set(run, name, w, True)
    return len(runs)


def main(argv):
    if len(argv) < 2:
        print(__doc__.strip(), file=sys.stderr)
        return 2
    min_runs = 0
    if "--min-runs" in argv:
        min_runs = int(argv[argv.index("--min-runs") + 1])
    properties = None
    if "--properties" in argv:
        properties = dict(item.split("=", 1) for item in argv[argv.index("--properties") + 1].split(","))
    try:
        with open(argv[1]) as f:
            data = json.load(f)
    except (OSError, ValueError) as e:
        print(f"{argv[1]}: {e}", file=sys.stderr)
        return 1
    meshes = data if isinstance(data, list) else [data]
    if not meshes:
        fail(argv[1], "empty array")
    for i, m in enumerate(meshes):
        runs = check_mesh(m, f"[{i}]" if isinstance(data, list) else "$", properties)
        if runs < min_runs:
            fail(f"[{i}]", f"{runs} runs, expected at least {min_runs}")
    for p in problems:
        print(f"{argv[1]}: {p}", file=sys.stderr)
    if not problems:
        print(f"{argv[1]}: OK ({len(meshes)} mesh(es))")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))

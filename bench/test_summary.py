#!/usr/bin/env python3
"""Checks bench/summary.py --median on synthetic results: three runs of one input whose primary
ratios are 0.5, 0.9 and 0.7 make one row at the median 0.70x (which meets the 0.7 floor, where the
first run alone would not), and without --median three rows; and that bad input (malformed
JSON, a missing file, an unknown option) gets one line and a non-zero status, not a traceback."""
import json
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))


def result(primary, build_ms):
    sets = {s: {"ratio_vs_embree": r, "mismatches": 0} for s, r in
            (("primary", primary), ("diffuse", 0.8), ("shadow", 0.8))}
    embree = {"build_ms": 10.0, "bytes": 1000, **{s: {"mismatches": 0} for s in sets}}
    run = {"accel": "octree", "default": True, "build_ms": build_ms, "bytes": 500, **sets}
    return {"mesh": "synthetic", "triangles": 1200, "embree": embree, "runs": [run]}


def main():
    with tempfile.TemporaryDirectory() as tmp:
        paths = []
        for k, (p, b) in enumerate([(0.5, 4.0), (0.9, 12.0), (0.7, 6.0)]):
            paths.append(os.path.join(tmp, "run%d.json" % k))
            with open(paths[-1], "w") as f:
                json.dump(result(p, b), f)
        summary = os.path.join(HERE, "summary.py")
        med = subprocess.run([sys.executable, summary, *paths, "--floors", "--median"], capture_output=True,
                             text=True, check=True).stdout
        rows = [l for l in med.splitlines() if l.startswith("| synthetic")]
        errors = []
        if len(rows) != 1:
            errors.append("--median: %d rows, expected 1" % len(rows))
        elif "| 0.70× | 0.80× | 0.80× | 0.60× |" not in rows[0]:
            errors.append("--median: unexpected row " + rows[0])
        if "primary 1," not in med or "median of 3 runs" not in med:
            errors.append("--median: floors line or run count missing:\n" + med)
        plain = subprocess.run([sys.executable, summary, *paths, "--floors"], capture_output=True, text=True,
                               check=True).stdout
        if len([l for l in plain.splitlines() if l.startswith("| synthetic")]) != 3:
            errors.append("without --median: expected one row per run")
        if "primary 2," not in plain:
            errors.append("without --median: expected 2 of 3 rows at or above the primary floor")
        # Bad input: one line naming the problem and a non-zero status, no traceback.
        bad = os.path.join(tmp, "bad.json")
        with open(bad, "w") as f:
            f.write("{")
        for args, status, needle in (([bad], 1, bad + ": not nori-bench JSON"),
                                     ([os.path.join(tmp, "missing.json")], 1, "missing.json"),
                                     ([paths[0], "--flors"], 2, "unknown option --flors")):
            p = subprocess.run([sys.executable, summary, *args], capture_output=True, text=True)
            if p.returncode != status or needle not in p.stderr or "Traceback" in p.stderr:
                errors.append("%s: status %d, stderr %r" % (args, p.returncode, p.stderr))
        if subprocess.run([sys.executable, summary, "--help"], capture_output=True, text=True).stdout.find("usage:") < 0:
            errors.append("--help: no usage on stdout")
    for e in errors:
        print("FAIL:", e)
    return 1 if errors else 0


if __name__ == "__main__":
    sys.exit(main())

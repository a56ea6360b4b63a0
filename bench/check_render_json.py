#!/usr/bin/env python3
"""Check a nori-bench --render JSON file (used by ctest bench_render_smoke_json).

usage: check_render_json.py FILE

Checks structure, types and internal arithmetic: both accelerators traced rays, the image
statistics fit the image size, each repeat reproduced its first image, and Embree's image
stays close to the octree's (RMSE below 5% of the mean). Never a timing. Exits 1 with one
line per problem.
"""
import json
import math
import sys

from json_checks import fail, number, problems


def check_run(doc, name, repeats):
    run = doc.get(name)
    if not isinstance(run, dict):
        fail(name, "missing")
        return None
    if not isinstance(run.get("accel"), str) or not run["accel"]:
        fail(name, "'accel' is not a non-empty string")
    number(run, "build_ms", name, minimum=0)
    ms = number(run, "render_ms", name, minimum=0)
    rays = number(run, "rays", name, minimum=1, integral=True)
    mrays = number(run, "mrays_s", name, minimum=0)
    samples = run.get("samples_ms")
    if not isinstance(samples, list) or len(samples) != repeats:
        fail(name, f"'samples_ms' should list {repeats} renders: {samples!r}")
    if ms and rays and mrays is not None and not math.isclose(mrays, rays / ms / 1000.0, rel_tol=1e-6):
        fail(name, f"mrays_s {mrays} != rays / render_ms / 1000")
    return rays


def main():
    if len(sys.argv) != 2:
        print(__doc__.strip().splitlines()[2], file=sys.stderr)
        return 2
    path = sys.argv[1]
    with open(path) as f:
        doc = json.load(f)
    w = number(doc, "width", "root", minimum=1, integral=True)
    h = number(doc, "height", "root", minimum=1, integral=True)
    number(doc, "spp", "root", minimum=1, integral=True)
    number(doc, "threads", "root", minimum=1, integral=True)
    repeats = number(doc, "repeats", "root", minimum=1, integral=True) or 0
    number(doc, "ratio_vs_embree", "root", minimum=0)
    check_run(doc, "octree", repeats)
    check_run(doc, "embree", repeats)
    if doc.get("repeats_identical") is not True:
        fail("root", "a repeated render did not reproduce its first image")
    d = doc.get("image_diff")
    if not isinstance(d, dict):
        fail("image_diff", "missing")
    else:
        pixels = number(d, "pixels", "image_diff", minimum=1, integral=True)
        if w and h and pixels != w * h:
            fail("image_diff", f"pixels {pixels} != width x height {w * h}")
        mean = number(d, "mean_octree", "image_diff", minimum=0)
        if mean == 0:
            fail("image_diff", "the octree render is black")
        number(d, "mean_embree", "image_diff", minimum=0)
        number(d, "rmse_rel", "image_diff", minimum=0, maximum=0.05)
        number(d, "max_abs_rel", "image_diff", minimum=0)
        differing = number(d, "differing_pixels", "image_diff", minimum=0, integral=True)
        visible = number(d, "visible_pixels", "image_diff", minimum=0, integral=True)
        if pixels and differing is not None and differing > pixels:
            fail("image_diff", "more differing pixels than pixels")
        if differing is not None and visible is not None and visible > differing:
            fail("image_diff", "more pixels differ by 1% than differ at all")
        frac = number(d, "differing_fraction", "image_diff", minimum=0, maximum=1)
        if pixels and differing is not None and frac is not None and \
                not math.isclose(frac, differing / pixels, rel_tol=1e-9, abs_tol=1e-12):
            fail("image_diff", "differing_fraction != differing_pixels / pixels")
    for p in problems:
        print(f"{path}: {p}")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())

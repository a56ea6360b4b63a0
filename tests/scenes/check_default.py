#!/usr/bin/env python3
"""Checks a render of scenes/default.xml: STATS.json (nori --stats-json) and IMAGE.png.

   check_default.py STATS.json IMAGE.png

Exit 0 when the scene has at least 200,000 triangles, the render completed with secondary
rays (a path tracer, not a camera-only integrator), the image is lit (mean sRGB value between
0.15 and 0.85), and the knot in the middle of the frame is red (red at least twice green
and blue there) in front of a neutral background (the top rows' red within 20% of their
blue). Prints what failed otherwise.
"""
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

stats = json.load(open(sys.argv[1]))
img = plt.imread(sys.argv[2])[:, :, :3]
h, w = img.shape[:2]
failures = []
if stats["triangles"] < 200000:
    failures.append(f"{stats['triangles']} triangles (at least 200000 wanted)")
if not stats.get("complete", False):
    failures.append("the render did not complete")
if stats["rays"] <= stats["rays_camera"]:
    failures.append("no secondary rays: not a path-traced scene")
mean = float(img.mean())
if not 0.15 <= mean <= 0.85:
    failures.append(f"mean sRGB value {mean:.3f} outside [0.15, 0.85]")
centre = img[int(0.3 * h):int(0.5 * h), int(0.35 * w):int(0.65 * w)].reshape(-1, 3).mean(axis=0)
if not (centre[0] >= 2 * centre[1] and centre[0] >= 2 * centre[2]):
    failures.append(f"centre of the frame is not red: mean RGB {centre.round(3).tolist()}")
top = img[: int(0.1 * h)].reshape(-1, 3).mean(axis=0)
if abs(top[0] - top[2]) > 0.2 * max(top[2], 1e-6):
    failures.append(f"background is not neutral: mean RGB {top.round(3).tolist()}")
for f in failures:
    print("check_default:", f)
print("check_default:", "passed" if not failures else "FAILED")
sys.exit(1 if failures else 0)

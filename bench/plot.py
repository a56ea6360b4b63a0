#!/usr/bin/python3
"""Charts for nori-bench results (matplotlib; run with /usr/bin/python3).

usage: plot.py RESULTS.json [RESULTS.json ...] [--out DIR]

Writes into DIR (default: plots/):
  speed_vs_accuracy.png  Mrays/s against mismatch rate, one point per traversal x depth x overlap
                         (primary and diffuse rays), Embree marked
  depth.png              build time, memory and primary-ray render time against octree depth
  scaling.png            build ms and Mrays/s against triangle count, octree vs Embree, log-log
                         (only when the results cover several meshes, e.g. the dragon series)
Charts 1 and 2 show the largest mesh. Several JSON files are merged (one mesh each, or arrays).
"""
import json
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import matplotlib.ticker  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402

plt.rcParams.update({"font.size": 11, "axes.titlesize": 12, "axes.grid": True, "grid.alpha": 0.3,
                     "legend.fontsize": 9, "figure.dpi": 100})

TRAVERSAL_MARKERS = ["o", "s", "^", "D", "v", "P", "X"]
DEPTH_COLORS = plt.get_cmap("viridis")
EMBREE_COLOR = "#d62728"
TRAVERSAL_COLORS = ["#ff7f0e", "#9467bd", "#2ca02c", "#8c564b", "#17becf"]


def readable_log_y(ax):
    """Log y axis labelled at 1, 2, 5 x 10^k in plain numbers."""
    ax.yaxis.set_major_locator(matplotlib.ticker.LogLocator(base=10, subs=(1.0, 2.0, 5.0)))
    ax.yaxis.set_major_formatter(matplotlib.ticker.FuncFormatter(lambda v, _: f"{v:g}"))
    ax.yaxis.set_minor_formatter(matplotlib.ticker.NullFormatter())


def steady_mrays(mesh, run, name):
    """Throughput with the machine's drift removed: Embree's median over the whole session times
    the contender's ratio to the Embree runs interleaved with it. On a busy machine this is far
    steadier than the raw median (which depends on when the contender happened to run)."""
    ratio = run[name].get("ratio_vs_embree")
    if not ratio:
        return run[name]["mrays_s"]
    return mesh["embree"][name]["mrays_s"] * ratio


def steady_ms(mesh, run, name):
    m = steady_mrays(mesh, run, name)
    return run[name]["rays"] / (m * 1e3) if m > 0 else float("nan")


def load(paths):
    meshes = []
    for p in paths:
        with open(p) as f:
            data = json.load(f)
        meshes.extend(data if isinstance(data, list) else [data])
    return meshes


def short(mesh):
    name = os.path.basename(mesh["mesh"])
    for ext in (".gz", ".obj", ".xml"):
        if name.endswith(ext):
            name = name[: -len(ext)]
    return name


def octree_runs(mesh):
    return [r for r in mesh.get("runs", []) if r.get("accel") == "octree"]


def ordered(values):
    seen = []
    for v in values:
        if v not in seen:
            seen.append(v)
    return seen


def representative(mesh):
    """The octree run standing for 'the octree' in the scaling chart: the default settings,
    else the fastest exact (non-seed) run, else the fastest run."""
    runs = octree_runs(mesh)
    if not runs:
        return None
    defaults = [r for r in runs if r.get("default")]
    if defaults:
        return defaults[0]
    exact = [r for r in runs if r.get("traversal") != "seed"] or runs
    return max(exact, key=lambda r: r["primary"].get("ratio_vs_embree", r["primary"]["mrays_s"]))


def subtitle(mesh):
    rays = mesh.get("rays", {})
    return (f"{short(mesh)}: {mesh['triangles']:,} triangles, {mesh['threads']} thread(s), "
            f"{rays.get('width', '?')}x{rays.get('height', '?')}x{rays.get('spp', '?')} camera rays")


def speed_vs_accuracy(mesh, out):
    runs = octree_runs(mesh)
    fig, axes = plt.subplots(1, 2, figsize=(13, 5.2))
    traversals = ordered(r["traversal"] for r in runs)
    depths = sorted(set(r["maxDepth"] for r in runs))
    overlaps = ordered(r["overlap"] for r in runs)
    intersectors = ordered(r["intersector"] for r in runs)
    depth_color = {d: DEPTH_COLORS(0.1 + 0.75 * i / max(1, len(depths) - 1)) for i, d in enumerate(depths)}
    marker = {t: TRAVERSAL_MARKERS[i % len(TRAVERSAL_MARKERS)] for i, t in enumerate(traversals)}

    def rate(s):
        return 100.0 * s.get("mismatches", 0) / max(1, s["rays"])  # percent

    for ax, name in zip(axes, ("primary", "diffuse")):
        # Log x axis; exact contenders (rate 0) sit in a column one decade left of the smallest error.
        rates = [rate(r[name]) for r in runs] + [rate(mesh["embree"][name])]
        nonzero = [x for x in rates if x > 0]
        zero_at = 10.0 ** (math.floor(math.log10(min(nonzero))) - 1) if nonzero else 1e-4
        top = max(nonzero) if nonzero else zero_at * 100

        def x_of(s):
            return rate(s) if rate(s) > 0 else zero_at

        for r in runs:
            s = r[name]
            filled = r["overlap"] == overlaps[0]
            ax.scatter(x_of(s), steady_mrays(mesh, r, name), s=80 if r["intersector"] == intersectors[0] else 40,
                       marker=marker[r["traversal"]], color=depth_color[r["maxDepth"]],
                       facecolors=depth_color[r["maxDepth"]] if filled else "none",
                       linewidths=1.6, zorder=3, alpha=0.85)
        e = mesh["embree"][name]
        ax.scatter(x_of(e), e["mrays_s"], marker="*", s=360, color=EMBREE_COLOR, edgecolors="black", zorder=4)
        ax.annotate("Embree", (x_of(e), e["mrays_s"]), textcoords="offset points", xytext=(12, -4),
                    color=EMBREE_COLOR, fontweight="bold")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlim(zero_at / 3, top * 3)
        ax.axvspan(zero_at / 3, zero_at * 3, color="#2ca02c", alpha=0.07, zorder=0)
        ticks = [zero_at] + [10.0 ** k for k in range(int(math.log10(zero_at)) + 1, int(math.ceil(math.log10(top * 3))))]
        ax.set_xticks(ticks)
        ax.set_xticklabels(["exact"] + [f"{t:g}%" for t in ticks[1:]])
        ax.xaxis.set_minor_locator(matplotlib.ticker.NullLocator())
        ax.set_title(f"{name} rays ({e['rays']:,})")
        ax.set_xlabel("mismatch rate vs Embree robust")
        ax.set_ylabel("Mrays/s (Embree median × ratio, log)")
        readable_log_y(ax)
    handles = [Line2D([], [], marker=marker[t], linestyle="", color="gray", markersize=8, label=f"traversal {t}")
               for t in traversals]
    handles += [Line2D([], [], marker="o", linestyle="", color=depth_color[d], markersize=8, label=f"maxDepth {d}")
                for d in depths]
    handles += [Line2D([], [], marker="o", linestyle="", markerfacecolor="gray" if i == 0 else "none",
                       markeredgecolor="gray", markersize=8, label=f"overlap {o}") for i, o in enumerate(overlaps)]
    if len(intersectors) > 1:
        handles += [Line2D([], [], marker="o", linestyle="", color="gray", markersize=9 if i == 0 else 6,
                           label=f"intersector {x}") for i, x in enumerate(intersectors)]
    handles.append(Line2D([], [], marker="*", linestyle="", color=EMBREE_COLOR, markersize=14, label="Embree"))
    fig.legend(handles=handles, loc="center right", frameon=True)
    fig.suptitle(f"Speed vs accuracy — {subtitle(mesh)}")
    fig.tight_layout(rect=(0, 0, 0.84, 0.95))
    fig.savefig(out)
    plt.close(fig)


def depth_chart(mesh, out):
    runs = octree_runs(mesh)
    depths = sorted(set(r["maxDepth"] for r in runs))
    # One line per build rule and overlap (and leaf size, when several were run).
    kinds = ordered((r.get("buildRule", ""), r["overlap"]) for r in runs)
    leaves = ordered(r["leafSize"] for r in runs)
    traversals = ordered(r["traversal"] for r in runs)
    intersectors = ordered(r["intersector"] for r in runs)
    styles = ["-", "--", ":", "-."]
    colors = plt.get_cmap("tab10")
    fig, axes = plt.subplots(1, 3, figsize=(16, 6.2))
    e = mesh["embree"]

    def pick(kind, leaf, depth, traversal=None, intersector=None):
        c = [r for r in runs if (r.get("buildRule", ""), r["overlap"]) == kind and r["leafSize"] == leaf
             and r["maxDepth"] == depth
             and (traversal is None or r["traversal"] == traversal)
             and (intersector is None or r["intersector"] == intersector)]
        return c[0] if c else None

    for oi, kind in enumerate(kinds):
        for li, leaf in enumerate(leaves):
            label = (f"{kind[0]}, " if kind[0] else "") + f"overlap {kind[1]}" + (f", leaf {leaf}" if len(leaves) > 1 else "")
            pts = [(d, pick(kind, leaf, d)) for d in depths]
            pts = [(d, r) for d, r in pts if r]
            if not pts:
                continue
            style = dict(linestyle=styles[(oi + 2 * li) % len(styles)], marker="o", color=colors(oi + 2 * li))
            axes[0].plot([d for d, _ in pts], [r["build_ms"] for _, r in pts], label=label, **style)
            axes[1].plot([d for d, _ in pts], [r["bytes"] / 2**20 for _, r in pts], label=label, **style)
            for ti, t in enumerate(traversals):
                x = intersectors[0]
                tp = [(d, pick(kind, leaf, d, t, x)) for d in depths]
                tp = [(d, r) for d, r in tp if r]
                if not tp:
                    continue
                axes[2].plot([d for d, _ in tp], [steady_ms(mesh, r, "primary") for _, r in tp],
                             linestyle=styles[(oi + 2 * li) % len(styles)], marker=TRAVERSAL_MARKERS[ti],
                             color=TRAVERSAL_COLORS[ti % len(TRAVERSAL_COLORS)], label=f"{t}, {label}")
    axes[0].axhline(e["build_ms"], color=EMBREE_COLOR, linestyle="--", label="Embree")
    axes[1].axhline(e["bytes"] / 2**20, color=EMBREE_COLOR, linestyle="--", label="Embree")
    axes[2].axhline(e["primary"]["ms"], color=EMBREE_COLOR, linestyle="--", label="Embree")
    axes[0].set_title("build time")
    axes[0].set_ylabel("ms")
    axes[1].set_title("memory")
    axes[1].set_ylabel("MiB")
    axes[2].set_title(f"render time, {e['primary']['rays']:,} primary rays ({intersectors[0] if intersectors else ''})")
    axes[2].set_ylabel("ms (Embree median / ratio, log)")
    axes[2].set_yscale("log")
    for ax in axes:
        ax.set_xlabel("maxDepth")
        ax.set_xticks(depths)
        ax.set_xlim(min(depths) - 1, max(depths) + 1)
        ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=2 if ax is axes[2] else 3, frameon=False)
    axes[0].set_ylim(bottom=0)
    axes[1].set_ylim(bottom=0)
    readable_log_y(axes[2])
    fig.suptitle(f"Octree depth — {subtitle(mesh)}")
    fig.tight_layout(rect=(0, 0, 1, 0.95))
    fig.savefig(out)
    plt.close(fig)


def scaling_chart(meshes, out):
    meshes = sorted(meshes, key=lambda m: m["triangles"])
    tris = [m["triangles"] for m in meshes]
    reps = [representative(m) for m in meshes]
    fig, axes = plt.subplots(1, 2, figsize=(13, 6))
    axes[0].plot(tris, [m["embree"]["build_ms"] for m in meshes], "-*", color=EMBREE_COLOR, markersize=12,
                 label="Embree")
    have = [(t, r) for t, r in zip(tris, reps) if r]
    if have:
        label = "octree (default)" if all(r.get("default") for _, r in have) else "octree (fastest exact)"
        axes[0].plot([t for t, _ in have], [r["build_ms"] for _, r in have], "-o", color="#1f77b4", label=label)
    for name, style in (("primary", "-"), ("diffuse", "--"), ("shadow", ":")):
        axes[1].plot(tris, [m["embree"][name]["mrays_s"] for m in meshes], style, marker="*", markersize=11,
                     color=EMBREE_COLOR, label=f"Embree {name}")
        if have:
            axes[1].plot([t for t, _ in have], [steady_mrays(m, r, name) for (t, r), m in
                                                zip(have, [m for m, r in zip(meshes, reps) if r])], style, marker="o",
                         color="#1f77b4", label=f"octree {name}")
    axes[0].set_title("build time")
    axes[0].set_ylabel("ms (log)")
    axes[1].set_title("throughput")
    axes[1].set_ylabel("Mrays/s (octree: Embree × ratio, log)")
    for ax in axes:
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("triangles (log)")
        ax.set_xticks(tris)
        ax.set_xticklabels([f"{short(m)}\n{t / 1000:.0f}k" for t, m in zip(tris, meshes)], fontsize=9)
        ax.xaxis.set_minor_locator(matplotlib.ticker.NullLocator())
        readable_log_y(ax)
        ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.2), ncol=3, frameon=False)
    threads = ordered(m["threads"] for m in meshes)
    fig.suptitle(f"Scaling over {len(meshes)} meshes, {'/'.join(map(str, threads))} thread(s)")
    fig.tight_layout(rect=(0, 0, 1, 0.95))
    fig.savefig(out)
    plt.close(fig)


def main(argv):
    args = argv[1:]
    out = "plots"
    if "--out" in args:
        i = args.index("--out")
        out = args[i + 1]
        del args[i:i + 2]
    if not args or any(a.startswith("-") for a in args):
        print(__doc__.strip(), file=sys.stderr)
        return 2
    meshes = load(args)
    if not meshes:
        print("plot.py: no results", file=sys.stderr)
        return 1
    os.makedirs(out, exist_ok=True)
    largest = max(meshes, key=lambda m: m["triangles"])
    written = []
    if octree_runs(largest):
        speed_vs_accuracy(largest, os.path.join(out, "speed_vs_accuracy.png"))
        depth_chart(largest, os.path.join(out, "depth.png"))
        written += ["speed_vs_accuracy.png", "depth.png"]
    else:
        print(f"plot.py: no octree runs for {short(largest)}: speed/accuracy and depth charts skipped",
              file=sys.stderr)
    if len(meshes) > 1:
        scaling_chart(meshes, os.path.join(out, "scaling.png"))
        written.append("scaling.png")
    print(f"plot.py: wrote {', '.join(written) if written else 'nothing'} in {out}", file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))

#!/usr/bin/env python3
"""Chart and summary table from igi-lightcuts-bench's CSV.

    plot_lightcuts.py results/lightcuts/lightcuts.csv results/lightcuts [--meta "conditions"]

Writes into the output folder:
  lightcuts.png  one row per scene: shadow rays per pixel, seconds per frame and
                 relMSE against pt, each against the VPL count (log-log), for ir,
                 lightcuts, reconstruction cuts and multidimensional lightcuts
  summary.md     per scene and VPL count: rays per pixel, time, speed-up over ir
                 (same run), relMSE and mean relative difference against ir, FLIP,
                 and the issue's targets at the largest count
"""
import argparse
import csv
import os
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

STYLE = {
    "ir": ("tab:blue", "o", "ir (every VPL)"),
    "lightcuts": ("tab:red", "s", "lightcuts (4 x 4 block cuts)"),
    "lightcuts-pixel": ("tab:olive", "v", "lightcuts, a cut per pixel"),
    "lightcuts-rc": ("tab:orange", "^", "reconstruction cuts"),
    "lightcuts-md": ("tab:purple", "D", "multidimensional (K gather points)"),
}
NUMERIC = ("vpls", "paths_per_set", "seconds", "cpu_seconds", "frame_setup_seconds", "shadow_rays_per_pixel",
           "cut_nodes_per_pixel", "reconstructed", "rel_mse_ir", "rel_mse_pt", "mean_rel_diff_ir", "within_2pct_ir",
           "flip_ir", "flip_pt", "flip_plain")


def read_rows(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    for r in rows:
        for k in NUMERIC:
            r[k] = float(r[k])
    return rows


def plot(rows, scenes, path, meta):
    panels = (("shadow_rays_per_pixel", "shadow rays per pixel"), ("seconds", "seconds per frame"),
              ("rel_mse_pt", "relMSE against pt"))
    fig, axes = plt.subplots(len(scenes), len(panels), figsize=(13, 3.6 * len(scenes)), squeeze=False)
    for i, scene in enumerate(scenes):
        by_method = defaultdict(list)
        for r in rows:
            if r["scene"] == scene:
                by_method[r["method"]].append(r)
        for j, (key, label) in enumerate(panels):
            ax = axes[i][j]
            for method, pts in by_method.items():
                pts = sorted(pts, key=lambda r: r["vpls"])
                colour, marker, name = STYLE.get(method, ("gray", "x", method))
                ax.plot([r["vpls"] for r in pts], [max(r[key], 1e-9) for r in pts], color=colour, marker=marker,
                        label=name)
            ax.set_xscale("log")
            ax.set_yscale("log")
            ax.set_xlabel("VPLs")
            ax.set_title(f"{scene}: {label}", fontsize=10)
            ax.grid(True, which="both", alpha=0.25)
    handles, labels = axes[0][0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=4, frameon=False)
    fig.suptitle(f"Lightcuts against ir over the same VPLs ({meta})", fontsize=10)
    fig.tight_layout(rect=(0, 0.04, 1, 0.97))
    fig.savefig(path, dpi=100)
    plt.close(fig)


def fmt(v, spec):
    return "-" if v < 0 else format(v, spec)


def summary(rows, scenes, meta):
    lines = [
        f"Lightcuts against ir over exactly the same VPLs, and against pt ({meta}). ",
        "Speed-up: ir's seconds per frame over the method's, same run. relMSE and mean relative "
        "difference (of luminance, pixels above 1 % of the mean) against ir; relMSE and FLIP against a "
        "converged pt; FLIP of reconstruction cuts against plain cuts. Multidimensional rows antialias, so "
        "they are compared with pt only.",
        "",
        "| scene | VPLs | method | rays/pixel | s/frame | cpu s | speed-up over ir (wall / cpu) | relMSE vs ir "
        "| mean rel. diff. vs ir | relMSE vs pt | FLIP vs pt | FLIP vs plain |",
        "|---|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for scene in scenes:
        srows = [r for r in rows if r["scene"] == scene]
        for vpls in sorted({r["vpls"] for r in srows}):
            group = [r for r in srows if r["vpls"] == vpls]
            ir = next((r for r in group if r["method"] == "ir"), None)
            for r in group:
                other = ir and r["method"] != "ir"
                speedup = f"{ir['seconds'] / r['seconds']:.1f} / {ir['cpu_seconds'] / r['cpu_seconds']:.1f}" if other else "-"
                lines.append(
                    f"| {scene} | {int(vpls)} | {r['method']} | {r['shadow_rays_per_pixel']:.1f} | {r['seconds']:.3g} "
                    f"| {r['cpu_seconds']:.3g} | {speedup} | {fmt(r['rel_mse_ir'], '.2e')} "
                    f"| {fmt(r['mean_rel_diff_ir'], '.4f')} | {r['rel_mse_pt']:.4f} | {r['flip_pt']:.4f} "
                    f"| {fmt(r['flip_plain'], '.4f')} |")
    lines += ["", "Targets at the largest VPL count of each scene:", ""]
    for scene in scenes:
        srows = [r for r in rows if r["scene"] == scene]
        top = max(r["vpls"] for r in srows)
        group = {r["method"]: r for r in srows if r["vpls"] == top}
        lc, ir, rc = group.get("lightcuts"), group.get("ir"), group.get("lightcuts-rc")
        if not lc:
            continue
        parts = [f"{lc['shadow_rays_per_pixel']:.0f} rays/pixel (<= 500)"]
        if ir:
            parts.append(f"{ir['seconds'] / lc['seconds']:.1f}x faster than ir in wall time, "
                         f"{ir['cpu_seconds'] / lc['cpu_seconds']:.1f}x in CPU time (>= 50x)")
            parts.append(f"mean relative difference {100 * lc['mean_rel_diff_ir']:.2f} % (< 2 %)")
        if rc:
            parts.append(f"reconstruction cuts {lc['shadow_rays_per_pixel'] / rc['shadow_rays_per_pixel']:.1f}x "
                         f"fewer rays (>= 3x) at FLIP {rc['flip_pt']:.4f} vs plain {lc['flip_pt']:.4f} "
                         f"against pt, {rc['flip_plain']:.4f} against plain cuts (within 0.01)")
        lines.append(f"- {scene}, {int(top)} VPLs: " + "; ".join(parts))
    return "\n".join(lines) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("csv")
    ap.add_argument("out_dir")
    ap.add_argument("--meta", default="see the CSV", help="run conditions for the title and table")
    args = ap.parse_args()
    rows = read_rows(args.csv)
    os.makedirs(args.out_dir, exist_ok=True)
    scenes = list(dict.fromkeys(r["scene"] for r in rows))
    chart = os.path.join(args.out_dir, "lightcuts.png")
    plot(rows, scenes, chart, args.meta)
    print(chart)
    path = os.path.join(args.out_dir, "summary.md")
    with open(path, "w") as f:
        f.write(summary(rows, scenes, args.meta))
    print(path)


if __name__ == "__main__":
    main()

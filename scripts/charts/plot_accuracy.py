#!/usr/bin/env python3
"""Charts and the headline table from igi-accuracy's CSV.

    plot_accuracy.py results/accuracy/accuracy.csv results/accuracy [--targets 0.05,0.01] [--flip-targets 0.1,0.06,0.05]

Writes into the output folder:
  <scene>.png   relMSE and mean FLIP against render time, log-log, one series
                per method variant (pt; ir per clamp; igi per filter and clamp;
                igi+caustics per photon count),
                with the Pareto front of each method (pt, ir, igi) drawn over them
  pareto.csv    the points on each method's front
  headline.md   time to reach each target error, per method and scene, and how
                many times faster than pt each method gets there; for light
                the view's options (igi-power: lights by power, without igi's
                default light importance; igi-bidir: bidirectional IR on top
                of it) how many times faster than igi, in wall and CPU time,
                and the share of VPLs in rooms the camera sees
"""
import argparse
import csv
import math
import os
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

METHOD_COLOURS = {"pt": "black", "ir": "tab:blue", "igi": "tab:red", "lightcuts": "tab:green",
                  "igi+caustics": "tab:pink", "igi-power": "tab:orange", "igi-bidir": "tab:purple",
                  "igi-draws": "tab:olive"}
METHODS = ("pt", "ir", "igi", "lightcuts", "igi+caustics", "igi-power", "igi-bidir", "igi-draws")
VIEW_METHODS = ("igi-power", "igi-bidir")


def read_rows(path):
    rows = []
    with open(path, newline="") as f:
        for r in csv.DictReader(f):
            r["seconds"] = float(r["seconds"])
            for k in ("relmse", "rmse", "flip"):
                r[k] = float(r[k])
            # Columns added later: absent in older CSVs.
            r["cpu_seconds"] = float(r.get("cpu_seconds") or "nan")
            r["vpls_seen"] = float(r.get("vpls_seen") or "-1")
            r["params_dict"] = dict(kv.split("=", 1) for kv in r["params"].split(";") if "=" in kv)
            rows.append(r)
    return rows


def variant(row):
    """The series a point belongs to: everything but the budget (spp, M, passes)."""
    p = row["params_dict"]
    if row["method"] == "pt":
        return "pt"
    label = f"{row['method']} clamp {p.get('clamp', '0')}"
    if row["method"].startswith("igi"):
        label += f" filter {p.get('filter', 'on')}"
    if p.get("aa", "1") != "1":
        label += f" aa {p['aa']}"
    if "photons" in p:
        label += f" {p['photons']} photon paths"
    if p.get("bc", "off") != "off":
        label += " bc"
    return label


def pareto(points, key):
    """Points not beaten in both time and error, by increasing time."""
    front, best = [], math.inf
    for r in sorted(points, key=lambda r: (r["seconds"], r[key])):
        if r[key] < best:
            front.append(r)
            best = r[key]
    return front


def plot_scene(scene, rows, out_dir):
    series = defaultdict(list)
    for r in rows:
        series[variant(r)].append(r)
    # The legend below the charts: a row of 5 entries per 0.16 inch, so the
    # charts keep their height however many series there are.
    legend_rows = math.ceil((len(series) + len(METHODS)) / 5)
    legend_height = 0.3 + 0.16 * legend_rows
    fig, axes = plt.subplots(1, 2, figsize=(13, 5.5 + legend_height))
    markers = ["o", "s", "^", "v", "D", "P", "X"]
    for ax, key, label in ((axes[0], "relmse", "relMSE (epsilon 0.01)"), (axes[1], "flip", "mean FLIP (LDR, 67 ppd)")):
        style_index = defaultdict(int)
        for name, pts in sorted(series.items()):
            pts = sorted(pts, key=lambda r: r["seconds"])
            method = pts[0]["method"]
            marker = markers[style_index[method] % len(markers)]
            style_index[method] += 1
            # Bias-compensated series ("... bc"): hollow markers beside their clamp's filled ones.
            ax.plot([r["seconds"] for r in pts], [r[key] for r in pts], linestyle="none", marker=marker, ms=4,
                    color=METHOD_COLOURS.get(method, "gray"), alpha=0.6, label=name,
                    fillstyle="none" if name.endswith(" bc") else "full")
        for method in METHODS:
            front = pareto([r for r in rows if r["method"] == method], key)
            if front:
                ax.step([r["seconds"] for r in front], [r[key] for r in front], where="post", lw=2.5,
                        color=METHOD_COLOURS[method], label=f"{method} Pareto front")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("render time (s, same machine, same run)")
        ax.set_ylabel(label)
        ax.grid(True, which="both", alpha=0.25)
    axes[0].set_title(f"{scene}: relMSE against time")
    axes[1].set_title(f"{scene}: FLIP against time")
    handles, labels = axes[0].get_legend_handles_labels()
    fig.legend(handles, labels, loc="lower center", ncol=5, fontsize=7, frameon=False)
    fig.tight_layout(rect=(0, legend_height / (5.5 + legend_height), 1, 1))
    path = os.path.join(out_dir, f"{scene}.png")
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path


def fastest(rows, method, key, target, clock="seconds"):
    hits = [r for r in rows if r["method"] == method and r[key] <= target]
    return min(hits, key=lambda r: r[clock]) if hits else None


def time_to_reach(rows, method, key, target):
    r = fastest(rows, method, key, target)
    if r is None:
        best = min((r[key] for r in rows if r["method"] == method), default=math.nan)
        return f"not reached (best {best:.3g})"
    params = r["params"]
    for default in (";bc=off", ";aa=1", ";imp=0", ";bidir=0"):
        params = params.replace(default, "")
    params = params.replace(";", ", ")
    return f"{r['seconds']:.3g} s ({params})"


def speedup(rows, method, key, target):
    """How many times faster than pt the method reaches the target."""
    ours, pt = fastest(rows, method, key, target), fastest(rows, "pt", key, target)
    if ours is None:
        return "not reached"
    if not any(r["method"] == "pt" for r in rows):
        return "pt not run"
    if pt is None:
        return f"pt not reached (> {max(r['seconds'] for r in rows if r['method'] == 'pt') / ours['seconds']:.0f}x)"
    return f"{pt['seconds'] / ours['seconds']:.1f}x"


def over_igi(rows, method, key, target):
    """How many times faster than plain igi the method reaches the target: wall / CPU time."""
    ours, igi = fastest(rows, method, key, target), fastest(rows, "igi", key, target)
    if ours is None:
        best = min((r[key] for r in rows if r["method"] == method), default=math.nan)
        return f"not reached (best {best:.3g})"
    if igi is None:
        return f"igi not reached; {ours['seconds']:.3g} s"
    ours_cpu, igi_cpu = fastest(rows, method, key, target, "cpu_seconds"), fastest(rows, "igi", key, target, "cpu_seconds")
    return (f"{igi['seconds'] / ours['seconds']:.2f}x / {igi_cpu['cpu_seconds'] / ours_cpu['cpu_seconds']:.2f}x "
            f"({ours['seconds']:.3g} s vs {igi['seconds']:.3g} s)")


def seen_share(rows, method):
    """Median share of VPLs in rooms the camera sees over the method's points."""
    values = sorted(r["vpls_seen"] for r in rows if r["method"] == method and r["vpls_seen"] >= 0)
    return f"{100 * values[len(values) // 2]:.0f} %" if values else "-"


def view_table(rows, scenes, goals):
    """Lights by power and bidirectional IR against igi (with its default light importance), per scene."""
    if not any(r["method"] in VIEW_METHODS for r in rows):
        return ""
    lines = [
        "| scene | method | VPLs in rooms seen | " + " | ".join(g[2] for g in goals) + " |",
        "|---|---|---|" + "---|" * len(goals),
    ]
    for scene in scenes:
        srows = [r for r in rows if r["scene"] == scene]
        lines.append(f"| {scene} | igi | {seen_share(srows, 'igi')} | " + " | ".join("1" for _ in goals) + " |")
        for method in VIEW_METHODS:
            if any(r["method"] == method for r in srows):
                lines.append(f"| {scene} | {method} | {seen_share(srows, method)} | " +
                             " | ".join(over_igi(srows, method, k, t) for k, t, _ in goals) + " |")
    return ("\nHow many times faster than igi at its defaults (its fastest point over the method's, wall time / CPU "
            "time of all threads), and the median share of VPLs that land in rooms where the camera sees a "
            "point:\n\n" + "\n".join(lines) + "\n")


def headline(rows, scenes, targets, flip_targets, meta):
    goals = [("relmse", t, f"relMSE <= {t:g}") for t in targets] + [("flip", t, f"FLIP <= {t:g}") for t in flip_targets]
    lines = [
        "| scene | method | " + " | ".join(g[2] for g in goals) + " |",
        "|---|---|" + "---|" * len(goals),
    ]
    ratios = [
        "| scene | method | " + " | ".join(g[2] for g in goals) + " |",
        "|---|---|" + "---|" * len(goals),
    ]
    for scene in scenes:
        srows = [r for r in rows if r["scene"] == scene]
        for method in METHODS:
            if not any(r["method"] == method for r in srows):
                continue
            lines.append(f"| {scene} | {method} | " + " | ".join(time_to_reach(srows, method, k, t) for k, t, _ in goals) + " |")
            if method != "pt":
                ratios.append(f"| {scene} | {method} | " + " | ".join(speedup(srows, method, k, t) for k, t, _ in goals) + " |")
    intro = (
        "Time to reach a given error against the converged path-traced reference "
        f"({meta}); the fastest measured point of each method, with its settings. "
        "relMSE = mean (x - r)^2 / (r^2 + 0.01); FLIP = mean LDR-FLIP at 67 pixels per degree "
        "of the images clamped to [0, 1] and sRGB-encoded. VPL points are medians over three seeds. "
        "All points from one run on one machine (scripts/bench-accuracy.sh).\n"
    )
    return (intro + "\n" + "\n".join(lines) + "\n\nHow many times faster than pt each method reaches the target "
            "(pt's fastest point over the method's):\n\n" + "\n".join(ratios) + "\n" + view_table(rows, scenes, goals))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("csv")
    ap.add_argument("out_dir")
    ap.add_argument("--targets", default="0.05,0.02,0.01", help="relMSE targets for the headline table")
    ap.add_argument("--flip-targets", default="0.1,0.08,0.06,0.05", help="FLIP targets for the headline table")
    ap.add_argument("--meta", default="", help="run conditions for the table's introduction")
    args = ap.parse_args()
    rows = read_rows(args.csv)
    os.makedirs(args.out_dir, exist_ok=True)
    scenes = list(dict.fromkeys(r["scene"] for r in rows))
    for scene in scenes:
        print(plot_scene(scene, [r for r in rows if r["scene"] == scene], args.out_dir))
    with open(os.path.join(args.out_dir, "pareto.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["scene", "method", "metric", "params", "seconds", "value"])
        for scene in scenes:
            for method in METHODS:
                for key in ("relmse", "flip"):
                    for r in pareto([r for r in rows if r["scene"] == scene and r["method"] == method], key):
                        w.writerow([scene, method, key, r["params"], r["seconds"], r[key]])
    targets = [float(t) for t in args.targets.split(",") if t]
    path = os.path.join(args.out_dir, "headline.md")
    with open(path, "w") as f:
        flip_targets = [float(t) for t in args.flip_targets.split(",") if t]
        f.write(headline(rows, scenes, targets, flip_targets, args.meta or "see the CSV"))
    print(path)


if __name__ == "__main__":
    main()

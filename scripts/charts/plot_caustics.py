#!/usr/bin/env python3
"""Charts from igi-caustics-bench's CSVs.

    plot_caustics.py results/caustics [--meta TEXT]

Writes into the folder:
  caustics.png  left: the photon pass's time per frame against photon paths
                (wall and CPU, log-log); middle: igi's frames per second at
                640x480 against photon paths (0 = no caustics); right: relMSE
                against render time for pt and igi with caustics (reach.csv)
"""
import argparse
import csv
import os
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def rows(path):
    if not os.path.exists(path):
        return []
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("folder")
    ap.add_argument("--meta", default="")
    args = ap.parse_args()
    fig, axes = plt.subplots(1, 3, figsize=(17, 5.5))

    passes = rows(os.path.join(args.folder, "pass.csv"))
    if passes:
        n = [int(r["photon_paths"]) for r in passes]
        axes[0].plot(n, [float(r["ms"]) for r in passes], "o-", label="wall")
        axes[0].plot(n, [float(r["cpu_ms"]) for r in passes], "s--", label="CPU")
        axes[0].set_xscale("log")
        axes[0].set_yscale("log")
        axes[0].set_xlabel("photon paths per frame")
        axes[0].set_ylabel("photon pass per frame (ms)")
        axes[0].set_title(f"photon pass, {passes[0]['threads']} threads")
        axes[0].legend()
        axes[0].grid(True, which="both", alpha=0.25)

    all_fps = rows(os.path.join(args.folder, "fps.csv"))
    fps = [r for r in all_fps if r["scene"] != "cornell"]
    baseline = [r for r in all_fps if r["scene"] == "cornell"]
    if fps:
        n = [max(1, int(r["photon_paths"])) for r in fps]
        axes[1].plot(n, [float(r["fps"]) for r in fps], "o-")
        axes[1].axhline(20, color="gray", ls=":", label="20 fps")
        for r in baseline:
            axes[1].axhline(float(r["fps"]), color="tab:green", ls="--", label="Cornell box, no caustics")
        axes[1].set_xscale("log")
        axes[1].set_xlabel("photon paths per frame (1 = caustics off)")
        axes[1].set_ylabel("frames per second")
        axes[1].set_title(f"igi at {fps[0]['width']}x{fps[0]['height']}, {fps[0]['threads']} threads")
        axes[1].legend()
        axes[1].grid(True, which="both", alpha=0.25)

    reach = rows(os.path.join(args.folder, "reach.csv"))
    if reach:
        series = defaultdict(list)
        for r in reach:
            series[f"{r['method']} {r['settings']}" if r["method"] != "pt" else "pt"].append(r)
        for name, pts in sorted(series.items()):
            axes[2].plot([float(r["seconds"]) for r in pts], [float(r["relmse"]) for r in pts], "o-", ms=4,
                         label=name, color="black" if name == "pt" else None)
        axes[2].axhline(0.03, color="gray", ls=":", label="relMSE 0.03")
        axes[2].set_xscale("log")
        axes[2].set_yscale("log")
        axes[2].set_xlabel("render time (s)")
        axes[2].set_ylabel("relMSE against the pt reference")
        axes[2].set_title("time to relMSE 0.03 (glass scene)")
        axes[2].legend(fontsize=7)
        axes[2].grid(True, which="both", alpha=0.25)

    fig.suptitle(args.meta, fontsize=9)
    fig.tight_layout()
    path = os.path.join(args.folder, "caustics.png")
    fig.savefig(path, dpi=110)
    print(path)


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""The master under simulated load: igi-loadgen runs over a matrix of worker
counts, frame sizes, tile sizes, pixel formats and I/O threads, each run
appending a row to results/master/master.csv; then a chart (master.png) and a
summary with the issue's targets (summary.md).

Master CPU per tile comes from /proc (every thread of the master process) over
the frames after the warm-up: it does not depend on what else the machine runs,
so "cores at 30 fps" = CPU per tile x tiles a second at 30 fps is the figure to
compare with the target, next to the frames a second this machine reached.
"""
import argparse
import csv
import os
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
LOADGEN = os.path.join(ROOT, "build", "tests", "loadgen", "igi-loadgen")
OUT = os.path.join(ROOT, "results", "master")


def tiles_per_frame(size, tile):
    w, h = map(int, size.split("x"))
    return -(-w // tile) * -(-h // tile)


def run(a, label, workers, size, tile, pixels="half", io=1, tile_ms=None, frames=None):
    args = [LOADGEN, "--workers", str(workers), "--size", size, "--tile", str(tile), "--pixels", pixels,
            "--io-threads", str(io), "--frames", str(frames or a.frames), "--warmup", str(a.warmup),
            "--dir", os.path.join(OUT, "run"), "--csv", os.path.join(OUT, "master.csv"), "--label", label]
    if tile_ms is not None:
        args += ["--tile-ms", str(tile_ms)]
    print(" ".join(args[1:]), file=sys.stderr)
    r = subprocess.run(args, capture_output=True, text=True, timeout=600)
    print(r.stdout, file=sys.stderr, end="")
    if r.returncode != 0:
        print(f"  (exit {r.returncode})", file=sys.stderr)


def matrix(a):
    sizes = ["640x480", "1920x1080"]
    for size in sizes:
        for tile in (32, 64):
            for workers in (8, 64, 256):
                run(a, "paced", workers, size, tile)
    if a.quick:
        return
    for tile in (32, 64):
        run(a, "flat out", 64, "1920x1080", tile, tile_ms=0)
        run(a, "float pixels", 64, "1920x1080", tile, pixels="float")
    for io in (2, 4):
        run(a, "io threads", 64, "1920x1080", 32, io=io)


def read_rows():
    with open(os.path.join(OUT, "master.csv")) as f:
        return list(csv.DictReader(f))


def summary(rows):
    lines = ["| run | workers | size | tile | pixels | I/O threads | fps reached | tiles/s | master CPU a tile (us) "
             "| of which session thread (us) | master cores | cores at 30 fps | latency median / p95 (ms) "
             "| RSS first / second half (MiB) | tiles copied |", "|" + "---|" * 15]
    for r in rows:
        size = f"{r['width']}x{r['height']}"
        t = tiles_per_frame(size, int(r["tile"]))
        at30 = float(r["cpu_us_per_tile"]) * 1e-6 * 30 * t
        lines.append(f"| {r['label']} | {r['workers']} | {size} | {r['tile']} | {r['pixels']} | {r['io_threads']} | "
                     f"{float(r['fps']):.1f} | {float(r['tiles_per_s']):.0f} | {float(r['cpu_us_per_tile']):.1f} | "
                     f"{float(r['session_us_per_tile']):.1f} | {float(r['cores']):.2f} | {at30:.2f} | "
                     f"{float(r['latency_median_ms']):.0f} / {float(r['latency_p95_ms']):.0f} | "
                     f"{float(r['rss_first_mib']):.1f} / {float(r['rss_second_mib']):.1f} | {r['duplicated']} |")
    return "\n".join(lines) + "\n"


def plot(rows):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (left, right) = plt.subplots(1, 2, figsize=(12, 4.5))
    paced = [r for r in rows if r["label"] == "paced"]
    for size in ("640x480", "1920x1080"):
        for tile in ("32", "64"):
            pts = sorted((int(r["workers"]), r) for r in paced
                         if f"{r['width']}x{r['height']}" == size and r["tile"] == tile)
            if not pts:
                continue
            xs = [p[0] for p in pts]
            left.plot(xs, [float(p[1]["cpu_us_per_tile"]) for p in pts], "o-", label=f"{size}, {tile}-px tiles")
            at30 = [float(p[1]["cpu_us_per_tile"]) * 1e-6 * 30 * tiles_per_frame(size, int(tile)) for p in pts]
            right.plot(xs, at30, "o-", label=f"{size}, {tile}-px tiles")
    for ax in (left, right):
        ax.set_xscale("log", base=2)
        ax.set_xlabel("simulated workers")
        ax.legend(fontsize=8)
    left.set_ylabel("master CPU per tile (us, all threads)")
    left.set_title("master cost per tile")
    right.axhline(1.0, color="gray", ls="--", label="one core")
    right.set_ylabel("master cores needed at 30 fps")
    right.set_title("cores for 30 frames a second (CPU per tile x tiles/s)")
    fig.tight_layout()
    fig.savefig(os.path.join(OUT, "master.png"), dpi=110)


def main():
    p = argparse.ArgumentParser(description=__doc__)
    p.add_argument("--frames", type=int, default=150)
    p.add_argument("--warmup", type=int, default=15)
    p.add_argument("--quick", action="store_true", help="only the paced matrix")
    p.add_argument("--plot-only", action="store_true", help="chart and summary from an existing master.csv")
    a = p.parse_args()
    os.makedirs(OUT, exist_ok=True)
    if not a.plot_only:
        if os.path.exists(os.path.join(OUT, "master.csv")):
            os.remove(os.path.join(OUT, "master.csv"))
        matrix(a)
    rows = read_rows()
    text = summary(rows)
    open(os.path.join(OUT, "summary.md"), "w").write(text)
    print(text)
    plot(rows)


if __name__ == "__main__":
    main()

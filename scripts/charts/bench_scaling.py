#!/usr/bin/env python3
"""Frame time and Mrays/s against the number of workers and the tile size,
with the single-process render as the baseline, all in one run.

Writes results/scaling/scaling.csv, scaling.png and summary.md, and prints the
summary: the master's own CPU cost per tile and bytes per frame. How many
workers one master feeds is measured by scripts/bench-master.sh.

Then a model (see model_frame_seconds) fitted to nothing: it predicts each
measured run from the single process's CPU time, the master's measured costs
and the cores, prints measured over predicted, and predicts the frame time
on a machine of --model-cores cores and over 1 and 10 Gbit/s links.
"""
import argparse
import csv
import json
import os
import re
import statistics
import subprocess
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BUILD = os.path.join(ROOT, "build")
OUT = os.path.join(ROOT, "results", "scaling")


def render_args(a):
    return ["--scene", a.scene, "--method", "igi", "--vpl-paths", str(a.paths), "--clamp", "0.05",
            "--size", a.size, "--quiet"]


def baseline(a):
    """Single process, all threads: seconds per frame (one pass = one frame)."""
    cmd = [os.path.join(BUILD, "master", "igi-render")] + render_args(a) + [
        "--spp", str(a.frames), "-o", os.path.join(OUT, "baseline.exr")]
    text = subprocess.run(cmd, check=True, capture_output=True, text=True).stdout
    seconds = float(re.search(r", ([0-9.]+) s, ", text).group(1))
    mrays = float(re.search(r"([0-9.]+) Mrays \(", text).group(1))
    return seconds / a.frames, mrays / seconds


def read_stats(path):
    """The master's --stats (JSON Lines): the last totals line, with "frames", every frame's line in order."""
    frames, totals = [], {}
    with open(path) as f:
        for text in f:
            try:
                line = json.loads(text)
            except json.JSONDecodeError:  # a killed master's last line
                continue
            if "frame" in line:
                frames.append(line)
            else:
                totals = line
    return {**totals, "frames": frames}


def cluster(a, workers, threads, tile):
    stats = os.path.join(OUT, "stats.json")
    cmd = [os.path.join(BUILD, "master", "igi-master"), "--workers", str(workers), "--worker-threads", str(threads),
           "--frames", str(a.frames), "--no-write", "--stats", stats, "--tile", str(tile),
           "-o", os.path.join(OUT, "unused.exr")] + render_args(a)
    subprocess.run(cmd, check=True, capture_output=True, text=True, timeout=600)
    s = read_stats(stats)
    frames = s["frames"][2:] or s["frames"]  # skip the warm-up frames
    rays = sum(f["rays"] for f in frames) / len(frames)
    # Throughput, frames overlapping (pipelining): the steady rate after the
    # warm-up frames, not the run's wall time over its frames (which counts
    # the workers' start and scene loads: 20-35 % of a 10-frame run).
    done = [f["completed_at"] for f in s["frames"]]
    per_frame = (done[-1] - done[1]) / (len(done) - 2) if len(done) > 3 else s["wall_seconds"] / len(done)
    bytes_per_frame = statistics.median(
        sum(w["bytes_in"] + w["bytes_out"] for w in f["workers"].values()) for f in frames)
    n = len(s["frames"])
    return {"frame_s": per_frame, "mrays_s": rays * 1e-6 / per_frame, "latency_s": statistics.median(f["seconds"] for f in frames),
            "master_us_per_tile": s["master_cpu_us_per_tile"], "tiles_per_frame": s["tiles"] / n,
            "bytes_per_frame": bytes_per_frame,
            # The master's CPU a frame (every thread: session, I/O, the VPL-set hash) and its session thread's alone.
            "master_cpu_s": s["master_cpu_seconds"] / n, "session_cpu_s": s["session_cpu_seconds"] / n,
            "hash_s": s.get("master_hash_seconds", 0.0) / max(1, s.get("master_hash_frames", n))}


def main():
    p = argparse.ArgumentParser(description=__doc__)
    p.add_argument("--scene", default="cornell-blob")
    p.add_argument("--size", default="640x480")
    p.add_argument("--paths", type=int, default=6, help="light paths per VPL set (about 16 VPLs per set)")
    p.add_argument("--frames", type=int, default=12)
    p.add_argument("--workers", default="1,2,4,8")
    p.add_argument("--tiles", default="16,32,64,128")
    p.add_argument("--model-cores", type=int, default=16, help="the machine the model predicts for")
    a = p.parse_args()
    os.makedirs(OUT, exist_ok=True)
    cores = os.cpu_count()
    base_s, base_mrays = baseline(a)
    rows = [{"kind": "single process", "workers": 0, "threads": cores, "tile": 32, "frame_s": base_s,
             "mrays_s": base_mrays, "latency_s": base_s, "master_us_per_tile": 0, "tiles_per_frame": 0, "bytes_per_frame": 0,
             "master_cpu_s": 0, "session_cpu_s": 0, "hash_s": 0}]
    for n in map(int, a.workers.split(",")):
        r = cluster(a, n, max(1, cores // n), 32)
        rows.append({"kind": "workers", "workers": n, "threads": max(1, cores // n), "tile": 32, **r})
        print(f"{n} workers: {1e3 * r['frame_s']:.1f} ms/frame, {r['mrays_s']:.1f} Mrays/s", file=sys.stderr)
    for t in map(int, a.tiles.split(",")):
        r = cluster(a, 2, max(1, cores // 2), t)
        rows.append({"kind": "tile size", "workers": 2, "threads": max(1, cores // 2), "tile": t, **r})
        print(f"tile {t}: {1e3 * r['frame_s']:.1f} ms/frame", file=sys.stderr)
    with open(os.path.join(OUT, "scaling.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    write_summary(a, rows, cores)
    write_model(a, rows, cores)
    plot(a, rows)


BORDER = 3  # igi's filter border at the defaults (6 x 6 sets)


def border_factor(tile):
    """Pixels a tile renders over the pixels it returns (its border included)."""
    return ((tile + 2 * BORDER) / tile) ** 2


def model_frame_seconds(render_cpu_s, tile, workers, threads, cores, tiles, session_s, master_s, bytes_per_frame,
                        link_bytes_s=None, shared=True):
    """Seconds a frame, in steady state (frames overlap), as the largest of:
    the workers' rendering (render_cpu_s core-seconds at 32-pixel tiles,
    scaled by the tile's border, over min(workers x threads, cores) cores);
    the master's session thread (session_s a frame, serial); every process's
    CPU together over the cores, when master and workers share the machine
    (shared; master_s: the session thread and the VPL-set hash, a frame's
    share of the run's, which counts the start too); and the link into the
    master (bytes_per_frame over link_bytes_s).
    Assumes a core renders as fast at any thread count and tiles are spread
    evenly: both hold to within the 2-thread speed-up (2.0x) and the last
    tile's wait, which the model leaves out."""
    work = render_cpu_s * border_factor(tile) / border_factor(32)
    parts = {"workers": work / min(workers * threads, cores), "master thread": session_s}
    if shared:
        parts["all CPU"] = (work + master_s) / cores
    if link_bytes_s:
        parts["link"] = bytes_per_frame / link_bytes_s
    bound = max(parts, key=parts.get)
    return parts[bound], bound


def write_model(a, rows, cores):
    base = rows[0]
    render_cpu_s = base["frame_s"] * cores  # core-seconds a frame, one process at 32-pixel tiles
    w, h = map(int, a.size.split("x"))
    lines = ["Model (bench_scaling.py, model_frame_seconds): each run predicted from the single process's "
             f"CPU time ({render_cpu_s * 1e3:.0f} core-ms a frame) and that run's own master costs.", "",
             "| run | workers x threads | tile | measured ms | predicted ms | bound | measured / predicted |",
             "|---|---|---|---|---|---|---|"]
    cluster_rows = rows[1:]
    for r in cluster_rows:
        t, bound = model_frame_seconds(render_cpu_s, r["tile"], r["workers"], r["threads"], cores, r["tiles_per_frame"],
                                       r["session_cpu_s"], r["session_cpu_s"] + r["hash_s"], r["bytes_per_frame"])
        lines.append(f"| {r['kind']} | {r['workers']} x {r['threads']} | {r['tile']} | {1e3 * r['frame_s']:.1f} | "
                     f"{1e3 * t:.1f} | {bound} | {r['frame_s'] / t:.2f} |")
    # The master's costs per tile and per frame, medians over the runs at 32-pixel tiles.
    at32 = [r for r in cluster_rows if r["tile"] == 32]
    session_per_tile = statistics.median(r["session_cpu_s"] / r["tiles_per_frame"] for r in at32)
    other_per_frame = statistics.median(r["hash_s"] for r in at32)
    bytes_per_pixel = statistics.median(r["bytes_per_frame"] for r in at32) / (w * h)
    tiles = statistics.median(r["tiles_per_frame"] for r in at32)
    k = a.model_cores
    one = render_cpu_s / k  # one process on all k cores, as the baseline measures it here
    lines += ["", f"Predicted on one machine of {k} cores as fast as these (master and workers on it; "
              f"session thread {1e6 * session_per_tile:.0f} us a tile, the master's other threads "
              f"{1e3 * other_per_frame:.1f} ms a frame for the VPL-set hash; the I/O thread left out):", "",
              "| workers x threads | predicted ms | bound | against one process |", "|---|---|---|---|"]
    for n, c in [(1, 1), (2, 1), (4, 1), (8, 1), (16, 1), (1, k)]:
        if n * c > k:
            continue
        t, bound = model_frame_seconds(render_cpu_s, 32, n, c, k, tiles, session_per_tile * tiles,
                                       session_per_tile * tiles + other_per_frame, 0)
        lines.append(f"| {n} x {c} | {1e3 * t:.1f} | {bound} | {100 * one / t:.0f} % |")
    lines += ["", f"The link into the master at {bytes_per_pixel:.1f} bytes a pixel (this run's pixels and "
              "messages; float pixels are 12 bytes, half floats 6, and the window's surfaces 8 more): "
              "frames a second it carries at most,", "", "| size | 1 Gbit/s | 10 Gbit/s |", "|---|---|---|"]
    for label, pixels in [(a.size, w * h), ("1920x1080", 1920 * 1080)]:
        per_frame = bytes_per_pixel * pixels
        lines.append(f"| {label} | {125e6 / per_frame:.1f} | {1250e6 / per_frame:.1f} |")
    text = "\n".join(lines) + "\n"
    with open(os.path.join(OUT, "summary.md"), "a") as f:
        f.write("\n" + text)
    print(text)


def write_summary(a, rows, cores):
    base = rows[0]
    two = next(r for r in rows if r["kind"] == "workers" and r["workers"] == 2)
    cost = statistics.median(r["master_us_per_tile"] for r in rows[1:]) * 1e-6
    w, h = map(int, a.size.split("x"))
    lines = [f"Scene {a.scene}, {a.size}, igi, {a.paths} paths per set, {cores}-core machine, "
             f"master and workers on the same machine.", "",
             "| run | workers x threads | tile | ms/frame | Mrays/s | vs single process |", "|---|---|---|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['kind']} | {r['workers']} x {r['threads']} | {r['tile']} | {1e3 * r['frame_s']:.1f} | "
                     f"{r['mrays_s']:.1f} | {100 * base['frame_s'] / r['frame_s']:.0f} % |")
    lines += ["", f"Master CPU per tile (median over runs, ZeroMQ I/O included): {1e6 * cost:.0f} us; "
              f"bytes per frame at {a.size}: {two['bytes_per_frame'] / 1e6:.2f} MB.", ""]
    # How many workers one master feeds is measured, not computed, by
    # scripts/bench-master.sh (simulated workers, up to 256).
    text = "\n".join(lines) + "\n"
    open(os.path.join(OUT, "summary.md"), "w").write(text)
    print(text)


def plot(a, rows):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (left, right) = plt.subplots(1, 2, figsize=(11, 4))
    base = rows[0]
    wr = [r for r in rows if r["kind"] == "workers"]
    left.plot([r["workers"] for r in wr], [1e3 * r["frame_s"] for r in wr], "o-", label="master + N workers")
    left.axhline(1e3 * base["frame_s"], color="gray", ls="--", label=f"single process ({base['threads']} threads)")
    left.set_xlabel("workers (processes)")
    left.set_ylabel("ms per frame")
    left.set_title(f"{a.scene} {a.size}: frame time against workers")
    left.legend()
    tr = [r for r in rows if r["kind"] == "tile size"]
    right.plot([r["tile"] for r in tr], [1e3 * r["frame_s"] for r in tr], "o-", label="2 workers")
    right.axhline(1e3 * base["frame_s"], color="gray", ls="--", label="single process")
    right.set_xscale("log", base=2)
    right.set_xlabel("tile size (pixels)")
    right.set_ylabel("ms per frame")
    right.set_title("frame time against tile size")
    right.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(OUT, "scaling.png"), dpi=110)


if __name__ == "__main__":
    main()

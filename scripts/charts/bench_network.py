#!/usr/bin/env python3
"""The cluster over a shaped network link, inside this machine.

Two network namespaces joined by a veth pair, each end's egress shaped by a
token bucket (tc tbf) to --rates (1 Gbit/s and 10 Gbit/s by default; a 0.1 ms
netem delay each way where the kernel has sch_netem, none where it does not),
traffic never leaving the machine. igi-master runs in one namespace, listening
on the link's address, so CURVE is on (the master refuses a network endpoint
without it); simulated workers (igi-loadgen, answering with the tiles of a
frame igi-render rendered: real pixels) and real igi-worker processes run in
the other. For each frame size and pixel format and codec: frames a second
(the workers paced for --fps, 40: more than the 30 asked of the master), bytes
a pixel into the master, the master's CPU a tile and a frame. A loopback pair
with and without CURVE gives CURVE's own cost.

Needs root (ip netns, tc). Results in results/network/: network.csv, summary.md.
"""
import argparse
import csv
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BUILD = os.path.join(ROOT, "build")
LOADGEN = os.path.join(BUILD, "tests", "loadgen", "igi-loadgen")
MASTER = os.path.join(BUILD, "master", "igi-master")
RENDER = os.path.join(BUILD, "master", "igi-render")
WORKER = os.path.join(BUILD, "worker", "igi-worker")
KEYS = os.path.join(BUILD, "master", "igi-keys")
OUT = os.path.join(ROOT, "results", "network")

NS_MASTER, NS_WORKERS = "igi-bench-m", "igi-bench-w"
DEV_MASTER, DEV_WORKERS = "igi-bm0", "igi-bw0"
ADDR_MASTER, ADDR_WORKERS = "10.231.0.1", "10.231.0.2"
PORT = 5555


def sh(*args, check=True):
    return subprocess.run(list(args), check=check, capture_output=True, text=True)


def in_ns(ns, *args):
    return ["ip", "netns", "exec", ns, *args]


class Link:
    """The two namespaces and the veth pair between them; removed on exit."""

    def __enter__(self):
        self.close()
        sh("ip", "netns", "add", NS_MASTER)
        sh("ip", "netns", "add", NS_WORKERS)
        sh("ip", "link", "add", DEV_MASTER, "type", "veth", "peer", "name", DEV_WORKERS)
        for dev, ns, addr in ((DEV_MASTER, NS_MASTER, ADDR_MASTER), (DEV_WORKERS, NS_WORKERS, ADDR_WORKERS)):
            sh("ip", "link", "set", dev, "netns", ns)
            sh(*in_ns(ns, "ip", "addr", "add", addr + "/30", "dev", dev))
            sh(*in_ns(ns, "ip", "link", "set", dev, "up"))
            sh(*in_ns(ns, "ip", "link", "set", "lo", "up"))
        self.delay = None
        return self

    def shape(self, rate, delay_ms):
        """tbf at `rate` on both ends (netem's delay first, where there is netem)."""
        burst = {"1gbit": "256kb", "10gbit": "2mb"}.get(rate, "1mb")
        self.delay = None
        for dev, ns in ((DEV_MASTER, NS_MASTER), (DEV_WORKERS, NS_WORKERS)):
            sh(*in_ns(ns, "tc", "qdisc", "del", "dev", dev, "root"), check=False)
            netem = sh(*in_ns(ns, "tc", "qdisc", "add", "dev", dev, "root", "handle", "1:", "netem", "delay",
                              f"{delay_ms}ms"), check=False)
            parent = ["parent", "1:1", "handle", "10:"] if netem.returncode == 0 else ["root"]
            if netem.returncode == 0:
                self.delay = delay_ms
            sh(*in_ns(ns, "tc", "qdisc", "add", "dev", dev, *parent, "tbf", "rate", rate, "burst", burst,
                      "latency", "20ms"))

    def close(self):
        for ns in (NS_MASTER, NS_WORKERS):
            sh("ip", "netns", "del", ns, check=False)

    def __exit__(self, *exc):
        self.close()


def link_throughput(seconds=2.0):
    """What the shaped link carries, workers to master: a TCP stream through it (Python sockets)."""
    server = ("import socket,time\ns=socket.socket();s.setsockopt(socket.SOL_SOCKET,socket.SO_REUSEADDR,1)\n"
              f"s.bind(('{ADDR_MASTER}',{PORT + 1}));s.listen(1);c,_=s.accept();n=0;t=time.time()\n"
              "while True:\n b=c.recv(1<<20)\n if not b: break\n n+=len(b)\n"
              "print(n*8/(time.time()-t)/1e9)\n")
    client = ("import socket,time\nc=socket.create_connection(('%s',%d));b=bytes(1<<20);t=time.time()\n"
              "while time.time()-t<%f: c.sendall(b)\nc.close()\n") % (ADDR_MASTER, PORT + 1, seconds)
    srv = subprocess.Popen(in_ns(NS_MASTER, sys.executable, "-c", server), stdout=subprocess.PIPE, text=True)
    import time
    time.sleep(0.3)
    subprocess.run(in_ns(NS_WORKERS, sys.executable, "-c", client), check=True)
    out, _ = srv.communicate(timeout=30)
    return float(out.strip())


def picture(size, scene):
    """A frame igi-render rendered (one pass of its defaults): the simulated workers' pixels."""
    path = os.path.join(OUT, f"{scene}-{size}.exr")
    if not os.path.exists(path):
        subprocess.run([RENDER, "--scene", scene, "--size", size, "-o", path, "--quiet"], check=True)
    return path


def stats_figures(path, pixels_per_frame, warmup):
    """Median bytes a pixel into the master and the master's hash CPU a frame, from its --stats."""
    per_frame = []
    totals = {}
    with open(path) as f:
        for line in f:
            d = json.loads(line)
            if "workers" in d and "frame" in d:
                per_frame.append(sum(w["bytes_in"] for w in d["workers"].values()))
            elif "outcome" in d:
                totals = d
    measured = per_frame[warmup:] or per_frame
    return (statistics.median(measured) / pixels_per_frame if measured else 0.0), totals


def loadgen_run(a, keys, label, size, tile, pixels, codec, rate, network=True, curve=True):
    w, h = map(int, size.split("x"))
    run_dir = os.path.join(OUT, "run")
    shutil.rmtree(run_dir, ignore_errors=True)
    args = [LOADGEN, "--workers", str(a.workers), "--size", size, "--tile", str(tile), "--pixels", pixels,
            "--pixel-codec", codec, "--picture", picture(size, a.scene), "--fps", str(a.fps), "--frames",
            str(a.frames), "--warmup", str(a.warmup), "--stats", "--dir", run_dir, "--deadline", "300"]
    if network:
        args += ["--master", keys["wrapper"], "--endpoint", f"tcp://{ADDR_MASTER}:{PORT}"]
    if curve:
        args += ["--key", keys["worker.key"], "--master-key", keys["master.pub"],
                 "--master-arg=--key", "--master-arg=" + keys["master.key"],
                 "--master-arg=--authorized-keys", "--master-arg=" + keys["worker.pub"]]
        if not network:
            args += ["--master-arg=--curve"]
    cmd = in_ns(NS_WORKERS, *args) if network else args
    print(" ".join(args[1:]), file=sys.stderr)
    r = subprocess.run(cmd, capture_output=True, text=True, timeout=900)
    print(r.stdout, file=sys.stderr, end="")
    fig = {}
    for line in r.stdout.splitlines():
        line = line.strip()
        if " fps, " in line and "tiles/s" in line:
            parts = line.replace(";", ",").split(", ")
            fig["fps"] = float(parts[0].split()[0])
            for p in parts:
                if p.startswith("master ") and p.endswith(" cores"):
                    fig["cores"] = float(p.split()[1])
                if "us CPU a tile" in p:
                    fig["cpu_us_per_tile"] = float(p.split()[0])
    bytes_per_pixel, totals = stats_figures(os.path.join(run_dir, "stats.json"), w * h, a.warmup)
    tiles = -(-w // tile) * -(-h // tile)
    return {"label": label, "kind": "simulated", "workers": a.workers, "size": size, "tile": tile, "pixels": pixels,
            "codec": codec, "curve": int(curve), "link": rate if network else "loopback", "fps": fig.get("fps", 0.0),
            "bytes_per_pixel": round(bytes_per_pixel, 3),
            "mbit_per_frame": round(bytes_per_pixel * w * h * 8 / 1e6, 2),
            "master_cores": fig.get("cores", 0.0),
            "master_ms_per_frame": round(fig.get("cpu_us_per_tile", 0.0) * tiles / 1e3, 2),
            "exit": r.returncode}


def real_run(a, keys, size, pixels, codec, rate):
    """Real igi-worker processes in the workers' namespace, the master in its own."""
    w, h = map(int, size.split("x"))
    run_dir = os.path.join(OUT, "real")
    shutil.rmtree(run_dir, ignore_errors=True)
    os.makedirs(run_dir)
    stats = os.path.join(run_dir, "stats.json")
    master = subprocess.Popen(in_ns(NS_MASTER, MASTER, "--workers", "0", "--listen", f"tcp://{ADDR_MASTER}:{PORT}",
                                    "--key", keys["master.key"], "--authorized-keys", keys["worker.pub"],
                                    "--min-workers", str(a.real_workers), "--frames", str(a.real_frames), "--size",
                                    size, "--pixels", pixels, "--pixel-codec", codec, "--no-write", "-o",
                                    os.path.join(run_dir, "unused.png"), "--stats", stats),
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    workers = [subprocess.Popen(in_ns(NS_WORKERS, WORKER, "--connect", f"tcp://{ADDR_MASTER}:{PORT}", "--key",
                                      keys["worker.key"], "--master-key", keys["master.pub"], "--threads", "1",
                                      "--cache", os.path.join(run_dir, f"cache-{i}")),
                                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
               for i in range(a.real_workers)]
    out, _ = master.communicate(timeout=900)
    for p in workers:
        try:
            p.wait(timeout=30)
        except subprocess.TimeoutExpired:
            p.kill()
    bytes_per_pixel, totals = stats_figures(stats, w * h, 2)
    times = []
    with open(stats) as f:
        for line in f:
            d = json.loads(line)
            if "completed_at" in d:
                times.append(d["completed_at"])
    steps = [b - c for b, c in zip(times[3:], times[2:-1])]
    fps = 1.0 / statistics.median(steps) if steps else 0.0
    print(f"real workers, {size}, {pixels}/{codec}, {rate}: {fps:.2f} fps, {bytes_per_pixel:.2f} bytes a pixel, "
          f"exit {master.returncode}", file=sys.stderr)
    return {"label": "real workers", "kind": "igi-worker", "workers": a.real_workers, "size": size, "tile": 64,
            "pixels": pixels, "codec": codec, "curve": 1, "link": rate, "fps": round(fps, 2),
            "bytes_per_pixel": round(bytes_per_pixel, 3),
            "mbit_per_frame": round(bytes_per_pixel * w * h * 8 / 1e6, 2),
            "master_cores": round(totals.get("master_cpu_seconds", 0.0) / max(1e-9, totals.get("wall_seconds", 0.0)), 2),
            "master_ms_per_frame": round(1e3 * totals.get("master_cpu_seconds", 0.0) / max(1, a.real_frames), 2),
            "exit": master.returncode}


def make_keys(folder):
    for name in ("master", "worker"):
        subprocess.run([KEYS, "new", os.path.join(folder, name)], check=True, capture_output=True)
    wrapper = os.path.join(folder, "master-in-namespace.sh")
    with open(wrapper, "w") as f:
        f.write(f"#!/bin/sh\nexec ip netns exec {NS_MASTER} {MASTER} \"$@\"\n")
    os.chmod(wrapper, 0o755)
    return {"master.key": os.path.join(folder, "master.key"), "master.pub": os.path.join(folder, "master.pub"),
            "worker.key": os.path.join(folder, "worker.key"), "worker.pub": os.path.join(folder, "worker.pub"),
            "wrapper": wrapper}


def summary(rows, links, delay):
    lines = [f"Link: {', '.join(f'{r} tbf measured {g:.2f} Gbit/s' for r, g in links.items())}; "
             f"delay: {f'{delay} ms each way (netem)' if delay else 'none (this kernel has no sch_netem)'}.", "",
             "| run | workers | size | tile | pixels | codec | CURVE | link | fps | bytes a pixel | Mbit a frame "
             "| master cores | master CPU a frame (ms) | exit |", "|" + "---|" * 14]
    for r in rows:
        lines.append(f"| {r['label']} | {r['workers']} | {r['size']} | {r['tile']} | {r['pixels']} | {r['codec']} | "
                     f"{'yes' if int(r['curve']) else 'no'} | {r['link']} | {r['fps']} | {r['bytes_per_pixel']} | "
                     f"{r['mbit_per_frame']} | {r['master_cores']} | {r['master_ms_per_frame']} | {r['exit']} |")
    return "\n".join(lines) + "\n"


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--rates", default="1gbit,10gbit", help="tbf rates, comma-separated [1gbit,10gbit]")
    p.add_argument("--delay-ms", type=float, default=0.1, help="netem delay each way, where there is netem [0.1]")
    p.add_argument("--workers", type=int, default=64, help="simulated workers [64]")
    p.add_argument("--fps", type=float, default=40.0,
                   help="the simulated workers' pace [40: headroom, so what arrives is what the master and link take]")
    p.add_argument("--frames", type=int, default=60)
    p.add_argument("--warmup", type=int, default=10)
    p.add_argument("--scene", default="rooms", help="the picture's scene [rooms]")
    p.add_argument("--sizes", default="640x480:32,1920x1080:64", help="SIZE:TILE, comma-separated")
    p.add_argument("--wires", default="half/raw,half/zstd,rgb9e5/raw,rgb9e5/zstd,rgb9e5/lz4",
                   help="PIXELS/CODEC, comma-separated")
    p.add_argument("--real-workers", type=int, default=2, help="igi-worker processes for the real runs (0: none) [2]")
    p.add_argument("--real-frames", type=int, default=12)
    a = p.parse_args()
    if os.geteuid() != 0:
        sys.exit("bench-network: needs root (ip netns, tc); traffic stays inside this machine")
    os.makedirs(OUT, exist_ok=True)
    sizes = [(s.split(":")[0], int(s.split(":")[1])) for s in a.sizes.split(",")]
    wires = [w.split("/") for w in a.wires.split(",")]
    rows, links = [], {}
    with tempfile.TemporaryDirectory() as folder, Link() as link:
        keys = make_keys(folder)
        for size, tile in sizes:  # the pictures first, outside the timed runs
            picture(size, a.scene)
        for rate in a.rates.split(","):
            link.shape(rate, a.delay_ms)
            links[rate] = link_throughput()
            print(f"{rate}: the link carries {links[rate]:.2f} Gbit/s", file=sys.stderr)
            for size, tile in sizes:
                for pixels, codec in wires:
                    rows.append(loadgen_run(a, keys, "simulated", size, tile, pixels, codec, rate))
            if a.real_workers > 0:
                for pixels, codec in (("half", "raw"), ("rgb9e5", "zstd")):
                    rows.append(real_run(a, keys, sizes[0][0], pixels, codec, rate))
        size, tile = sizes[-1]
        for curve in (False, True):  # CURVE's own cost: loopback, where the master allows it off
            rows.append(loadgen_run(a, keys, "loopback", size, tile, "rgb9e5", "zstd", "", network=False, curve=curve))
        delay = link.delay
    with open(os.path.join(OUT, "network.csv"), "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        writer.writeheader()
        writer.writerows(rows)
    text = summary(rows, links, delay)
    open(os.path.join(OUT, "summary.md"), "w").write(text)
    print(text)


if __name__ == "__main__":
    main()

"""Figures and a chart of igi-master --motion runs (scripts/bench-motion.sh).

Each RUN folder holds motion.jsonl (a line per frame shown: time since the
first frame, camera pose, level, cost), shown-NNNN.exr (the image shown, for
frames at every 10th pose and after the stop) and camera-POSE.json. Prints a
row per run: frames shown a second while moving, the share of moving frames
within the budget, the longest gap between frames shown while moving, the
median FLIP of moving frames at the reference poses, the flicker between
consecutive moving frames (the median and the largest change of a frame's
mean luminance, as rendered, against the one before, over their mean), the
FLIP of the first frame after the stop, the time after the stop to the first
frame at full resolution (every pixel its own camera ray: a sharp preview or
a full frame) and to FLIP 0.1, 0.05 and 0.03.
Draws FLIP against time after the stop, one line per run (OUT.png), and
writes the rows as JSON beside it (OUT.json).

  plot_motion.py --compare IGI_COMPARE --refs DIR --ref-prefix P --budget-ms B --chart OUT.png RUN [RUN ...]
"""
import argparse
import json
import os
import statistics
import subprocess

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def flip(compare, reference, image):
    out = subprocess.run([compare, reference, image], check=True, capture_output=True, text=True).stdout
    return float(out.splitlines()[1].split()[3])


def analyse(run, args):
    lines = [json.loads(line) for line in open(os.path.join(run, "motion.jsonl"))]
    stop, frames = lines[0]["motion_seconds"], lines[1:]  # the script's clock: the camera stops at `stop`
    poses = sorted(int(name[7:-5]) for name in os.listdir(run) if name.startswith("camera-"))
    last = poses[-1]
    moving = [f for f in frames if f["pose"] < last]
    shown_moving = [f["t"] for f in frames if f["t"] < stop]
    times = [0.0] + shown_moving + [stop]
    gaps = [b - a for a, b in zip(times, times[1:])]
    previews = [f for f in moving if f["level"] != "full"]
    within = sum(f["ms"] <= args.budget_ms for f in previews) / len(previews) if previews else 0.0

    steps = [abs(b["mean"] - a["mean"]) / (0.5 * (a["mean"] + b["mean"])) for a, b in zip(moving, moving[1:])
             if a["mean"] + b["mean"] > 0]

    def ref(pose):
        return os.path.join(args.refs, "%s-%d.exr" % (args.ref_prefix, pose))

    def shown(f):
        return os.path.join(run, "shown-%04d.exr" % f["shown"])

    moving_flips = [flip(args.compare, ref(f["pose"]), shown(f)) for f in moving
                    if f["pose"] % 10 == 0 and os.path.exists(shown(f))]
    after = [(f["t"] - stop, flip(args.compare, ref(last), shown(f))) for f in frames
             if f["pose"] == last and os.path.exists(shown(f))]

    def time_to(target):
        return next(("%.2f" % t for t, v in after if v <= target), "> %.1f" % (after[-1][0] if after else 0.0))

    full_res = next(("%.2f" % (f["t"] - stop) for f in frames if f["pose"] == last and f["divisor"] == 1), "never")
    return {
        "run": os.path.basename(run),
        "to_full_res": full_res,
        "to10": time_to(0.1),
        "fps": len(shown_moving) / stop if stop > 0 else 0.0,
        "within": within,
        "gap": max(gaps) if gaps else 0.0,
        "moving_flip": statistics.median(moving_flips) if moving_flips else float("nan"),
        "flicker": statistics.median(steps) if steps else float("nan"),
        "flicker_max": max(steps) if steps else float("nan"),
        "first_still": after[0][1] if after else float("nan"),
        "to05": time_to(0.05),
        "to03": time_to(0.03),
        "after": after,
    }


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--compare", required=True)
    p.add_argument("--refs", required=True)
    p.add_argument("--ref-prefix", required=True)
    p.add_argument("--budget-ms", type=float, required=True)
    p.add_argument("--chart", required=True)
    p.add_argument("--title", default="")
    p.add_argument("runs", nargs="+")
    args = p.parse_args()
    rows = [analyse(run, args) for run in args.runs]
    print("%-28s %9s %8s %8s %11s %13s %11s %9s %9s %9s %9s" % (
        "run", "fps moving", "in budget", "max gap", "FLIP moving", "flicker (max)", "FLIP 1st still", "full res",
        "to 0.1", "to 0.05", "to 0.03"))
    for r in rows:
        print("%-28s %9.1f %7.0f%% %7.0fms %11.3f %5.1f%% (%4.1f%%) %11.3f %8ss %8ss %8ss %8ss" % (
            r["run"], r["fps"], 100 * r["within"], 1e3 * r["gap"], r["moving_flip"], 100 * r["flicker"],
            100 * r["flicker_max"], r["first_still"], r["to_full_res"], r["to10"], r["to05"], r["to03"]))
    with open(os.path.splitext(args.chart)[0] + ".json", "w") as out:
        json.dump([{k: v for k, v in r.items() if k != "after"} for r in rows], out, indent=1)
    fig, ax = plt.subplots(figsize=(6, 4))
    for r in rows:
        if r["after"]:
            ax.plot([t for t, _ in r["after"]], [v for _, v in r["after"]], marker="o", label=r["run"])
    for target in (0.1, 0.05, 0.03):
        ax.axhline(target, color="gray", linewidth=0.5)
    ax.set_xlabel("seconds after the camera stopped")
    ax.set_ylabel("FLIP against the reference")
    ax.set_yscale("log")
    ax.set_title(args.title)
    ax.legend()
    fig.tight_layout()
    fig.savefig(args.chart, dpi=100)


if __name__ == "__main__":
    main()

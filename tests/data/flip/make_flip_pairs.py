#!/usr/bin/env python3
"""Image pairs for the FLIP test and their mean LDR-FLIP from NVIDIA's
reference implementation (the flip-evaluator package), written to golden.txt.

    .venv/bin/pip install flip-evaluator   # once (scripts/venv.sh makes .venv)
    .venv/bin/python tests/data/flip/make_flip_pairs.py [--renders]

Pairs are made here with numpy, deterministically (a fixed seed), and saved
as 8-bit sRGB PNG, so the C++ test reads exactly the pixels the reference
saw. --renders also adds two renders of the Cornell box (igi and pt, from
build/master/igi-render), which must already be built.
"""
import os
import subprocess
import sys

import numpy as np
from PIL import Image
import flip_evaluator as flip

HERE = os.path.dirname(os.path.abspath(__file__))
W, H = 64, 48


def save(name, rgb):
    Image.fromarray(np.round(np.clip(rgb, 0, 1) * 255).astype(np.uint8), "RGB").save(os.path.join(HERE, name))


def pattern():
    x = np.linspace(0, 1, W, endpoint=False)[None, :, None]
    y = np.linspace(0, 1, H, endpoint=False)[:, None, None]
    img = np.concatenate([0.2 + 0.6 * x + 0 * y, 0.3 + 0.4 * y + 0 * x, 0.5 + 0 * x * y], axis=2)
    img[H // 3:2 * H // 3, W // 3:2 * W // 3] = [0.9, 0.8, 0.2]
    return img


def main():
    rng = np.random.default_rng(20261201)
    base = pattern()
    pairs = {
        "pattern.png": base,
        "noise-small.png": base + rng.uniform(-0.03, 0.03, base.shape),
        "noise-large.png": base + rng.uniform(-0.2, 0.2, base.shape),
        "shifted.png": np.roll(base, 2, axis=1),
        "darker.png": base * 0.85,
        "hue.png": base[:, :, [1, 2, 0]],
    }
    for name, img in pairs.items():
        save(name, img)
    rows = [("pattern.png", t) for t in pairs if t != "pattern.png"]
    if "--renders" in sys.argv:
        root = os.path.abspath(os.path.join(HERE, "..", "..", ".."))
        render = os.path.join(root, "build", "master", "igi-render")
        common = ["--scene", "cornell", "--size", f"{W}x{H}", "--quiet"]
        subprocess.run([render, *common, "--method", "pt", "--spp", "256", "-o", os.path.join(HERE, "cornell-pt.png")], check=True)
        subprocess.run([render, *common, "--method", "igi", "--vpl-paths", "4", "-o", os.path.join(HERE, "cornell-igi.png")], check=True)
        rows.append(("cornell-pt.png", "cornell-igi.png"))
    with open(os.path.join(HERE, "golden.txt"), "w") as out:
        out.write("# reference test mean-LDR-FLIP-at-67-ppd (flip-evaluator %s)\n" % getattr(flip, "__version__", "1.7"))
        for ref, test in rows:
            _, mean, _ = flip.evaluate(os.path.join(HERE, ref), os.path.join(HERE, test), "LDR", applyMagma=False)
            out.write(f"{ref} {test} {mean:.6f}\n")
            print(ref, test, mean)


if __name__ == "__main__":
    main()

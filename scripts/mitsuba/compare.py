#!/usr/bin/env python3
"""Compares two linear EXR images of the same size, the first the reference:

  ratio  = luminance mean of the second / luminance mean of the first
  relMSE = mean over pixels and channels of (b - a)^2 / (a^2 + 0.01)
           (igi's rel_mse, common/image/metrics.h, with a the reference)

  compare.py A.exr B.exr [--max-mean-diff F]

Exit code 0, or 1 with --max-mean-diff F when |ratio - 1| > F.
"""
import argparse
import sys

import mitsuba as mi
import numpy as np

mi.set_variant("scalar_rgb")

LUMINANCE = np.array([0.2126, 0.7152, 0.0722])  # Rec. 709, as igi's luminance()
REL_MSE_EPSILON = 0.01


def read_rgb(path):
    bitmap = mi.Bitmap(path).convert(mi.Bitmap.PixelFormat.RGB, mi.Struct.Type.Float32, srgb_gamma=False)
    return np.array(bitmap, dtype=np.float64)


def compare(a, b):
    """(ratio, relMSE) of image b against reference a."""
    if a.shape != b.shape:
        raise ValueError(f"image sizes differ: {a.shape[1]}x{a.shape[0]} and {b.shape[1]}x{b.shape[0]}")
    ratio = float((b.reshape(-1, 3) @ LUMINANCE).mean() / (a.reshape(-1, 3) @ LUMINANCE).mean())
    rel_mse = float(np.mean((b - a) ** 2 / (a ** 2 + REL_MSE_EPSILON)))
    return ratio, rel_mse


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("first", help="reference EXR (A)")
    parser.add_argument("second", help="EXR compared with it (B)")
    parser.add_argument("--max-mean-diff", type=float, metavar="F", help="exit 1 when |ratio - 1| > F")
    args = parser.parse_args(argv)
    try:
        ratio, rel_mse = compare(read_rgb(args.first), read_rgb(args.second))
    except (RuntimeError, ValueError) as error:
        print(f"compare.py: {error}", file=sys.stderr)
        return 2
    print(f"mean ratio (second/first) {ratio:.4f}  relMSE {rel_mse:.5g}")
    if args.max_mean_diff is not None and abs(ratio - 1.0) > args.max_mean_diff:
        print(f"compare.py: |ratio - 1| = {abs(ratio - 1.0):.4f} > {args.max_mean_diff}", file=sys.stderr)
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

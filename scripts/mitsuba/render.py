#!/usr/bin/env python3
"""Renders a glTF scene with Mitsuba 3 (scalar_rgb, unidirectional path tracer)
as a reference for igi: gltf_to_mitsuba.py maps the scene, this writes a linear
float EXR and prints the image mean (per channel and luminance) and seconds.

  render.py SCENE.gltf|.glb -o OUT.exr --size WxH --spp N [--seed S] [--light-units U]
"""
import argparse
import sys
import time

import mitsuba as mi
import numpy as np

from gltf_reader import GltfError
from gltf_to_mitsuba import scene_dict

LUMINANCE = np.array([0.2126, 0.7152, 0.0722])  # Rec. 709, as igi's luminance()


def size(text):
    width, _, height = text.partition("x")
    if not (width.isdigit() and height.isdigit() and int(width) > 0 and int(height) > 0):
        raise argparse.ArgumentTypeError(f"expected WxH, got '{text}'")
    return int(width), int(height)


def parse_args(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scene", help=".gltf or .glb file")
    parser.add_argument("-o", "--output", required=True, help="output .exr (linear float RGB)")
    parser.add_argument("--size", type=size, required=True, metavar="WxH")
    parser.add_argument("--spp", type=int, required=True, metavar="N", help="samples per pixel")
    parser.add_argument("--seed", type=int, default=0, metavar="S", help="sampler seed [0]")
    parser.add_argument("--light-units", choices=("photometric", "radiometric"), default="photometric",
                        help="the lamps' units, as igi's --light-units [photometric]")
    return parser.parse_args(argv)


def render(path, width, height, spp, seed, light_units="photometric"):
    """The rendered image as a (height, width, 3) float32 array."""
    scene = mi.load_dict(scene_dict(path, width, height, light_units))
    return np.array(mi.render(scene, spp=spp, seed=seed), dtype=np.float32)


def main(argv):
    args = parse_args(argv)
    start = time.perf_counter()
    try:
        image = render(args.scene, *args.size, args.spp, args.seed, args.light_units)
    except GltfError as error:
        print(f"render.py: {error}", file=sys.stderr)
        return 1
    seconds = time.perf_counter() - start
    mi.Bitmap(image, channel_names=["R", "G", "B"]).write(args.output)
    mean = image.reshape(-1, 3).mean(axis=0)
    print(f"{args.output}: mean R {mean[0]:.6g} G {mean[1]:.6g} B {mean[2]:.6g} "
          f"luminance {float(mean @ LUMINANCE):.6g}, {seconds:.2f} s")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))

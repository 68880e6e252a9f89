#!/usr/bin/env python3
"""Writes a test environment map: a 256 x 128 equirectangular Radiance .hdr
(+y up, its middle looking along -z, as igi's --environment reads it) with a
blue-to-white sky above the horizon, brown ground below, and a sun 5 degrees
across at 3,000 W/(m^2 sr), 40 degrees up, 0.6 rad in longitude from -z.
The map of tests/bench/history/RESULTS-to-2026-12-05.md, "Environment maps":
    python3 scripts/make-sky.py sky.hdr"""
import math
import sys


def rgbe(r, g, b):
    v = max(r, g, b)
    if v < 1e-32:
        return bytes([0, 0, 0, 0])
    m, e = math.frexp(v)
    s = m * 256.0 / v
    return bytes([int(r * s), int(g * s), int(b * s), e + 128])


def main(path, width=256, height=128):
    out = bytearray(b"#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y %d +X %d\n" % (height, width))
    sun_polar = math.radians(50)
    for y in range(height):
        theta = (y + 0.5) / height * math.pi
        for x in range(width):
            phi = 2 * math.pi * ((x + 0.5) / width - 0.5)
            if theta < math.pi / 2:
                t = math.cos(theta)
                c = tuple(0.8 * v for v in (0.6 + 0.4 * (1 - t), 0.7 + 0.3 * (1 - t), 1.0))
            else:
                c = (0.25, 0.2, 0.15)
            cos_sun = (math.sin(theta) * math.sin(sun_polar) * math.cos(phi + 0.6) +
                       math.cos(theta) * math.cos(sun_polar))
            if math.acos(max(-1.0, min(1.0, cos_sun))) < math.radians(2.5):
                c = (3000.0, 2800.0, 2500.0)
            out += rgbe(*c)
    with open(path, "wb") as f:
        f.write(out)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "sky.hdr")

#!/usr/bin/env python3
"""Writes conference.obj and conference.mtl: a meeting room after McGuire's
Conference (the research scenes people have are OBJ), small enough to ship.
A 12 x 3 x 8 m room, a long table, 12 chairs (seat, back, four legs), a
whiteboard, a brushed-metal bin and a glass vase; lit only by four ceiling
panels whose light comes through the MTL's Ke (area lights). Walls carry Kd,
the metal Ks and Ns, the glass d and Ni, the floor a map_Kd texture
(floor.png, written here). Y is up, faces counter-clockwise seen from their
front, as OBJ and glTF read them.

  python3 tests/data/conference/make_conference.py [OUT_DIR]
"""
import os
import struct
import sys
import zlib

out = sys.argv[1] if len(sys.argv) > 1 else os.path.dirname(os.path.abspath(__file__))
vertices, uvs, faces = [], [], []  # faces: (material, [(v, vt)...])


def quad(material, a, b, c, d, uv=None):
    """One quad, corners counter-clockwise seen from its front (1-based OBJ indices)."""
    base = len(vertices)
    vertices.extend([a, b, c, d])
    if uv is None:
        faces.append((material, [(base + i + 1, None) for i in range(4)]))
        return
    ub = len(uvs)
    uvs.extend(uv)
    faces.append((material, [(base + i + 1, ub + i + 1) for i in range(4)]))


def box(material, lo, hi):
    """An axis-aligned box, its six faces facing out."""
    (x0, y0, z0), (x1, y1, z1) = lo, hi
    quad(material, (x0, y0, z1), (x1, y0, z1), (x1, y1, z1), (x0, y1, z1))  # +z
    quad(material, (x1, y0, z0), (x0, y0, z0), (x0, y1, z0), (x1, y1, z0))  # -z
    quad(material, (x1, y0, z1), (x1, y0, z0), (x1, y1, z0), (x1, y1, z1))  # +x
    quad(material, (x0, y0, z0), (x0, y0, z1), (x0, y1, z1), (x0, y1, z0))  # -x
    quad(material, (x0, y1, z1), (x1, y1, z1), (x1, y1, z0), (x0, y1, z0))  # +y
    quad(material, (x0, y0, z0), (x1, y0, z0), (x1, y0, z1), (x0, y0, z1))  # -y


W, H, D = 12.0, 3.0, 8.0  # x from -6 to 6, y from 0 to 3, z from -4 to 4
x0, x1, z0, z1 = -W / 2, W / 2, -D / 2, D / 2
quad("floor", (x0, 0, z1), (x1, 0, z1), (x1, 0, z0), (x0, 0, z0), uv=[(0, 0), (6, 0), (6, 4), (0, 4)])
quad("ceiling", (x0, H, z0), (x1, H, z0), (x1, H, z1), (x0, H, z1))
quad("wall", (x0, 0, z0), (x1, 0, z0), (x1, H, z0), (x0, H, z0))  # back, facing +z
quad("wall", (x1, 0, z1), (x0, 0, z1), (x0, H, z1), (x1, H, z1))  # front, facing -z
quad("wall", (x0, 0, z1), (x0, 0, z0), (x0, H, z0), (x0, H, z1))  # left, facing +x
quad("wall", (x1, 0, z0), (x1, 0, z1), (x1, H, z1), (x1, H, z0))  # right, facing -x
for x in (-4.5, -1.5, 1.5, 4.5):  # ceiling panels facing down, 1.6 x 0.8 m, over the table
    quad("panel", (x - 0.8, H - 0.01, -0.4), (x + 0.8, H - 0.01, -0.4), (x + 0.8, H - 0.01, 0.4), (x - 0.8, H - 0.01, 0.4))
quad("board", (-2.0, 0.9, z0 + 0.02), (2.0, 0.9, z0 + 0.02), (2.0, 2.2, z0 + 0.02), (-2.0, 2.2, z0 + 0.02))
box("table", (-4.0, 0.72, -1.0), (4.0, 0.76, 1.0))
for x in (-3.9, 3.8):
    for z in (-0.9, 0.8):
        box("metal", (x, 0.0, z), (x + 0.1, 0.72, z + 0.1))
for side in (-1, 1):
    for x in (-3.0, -1.8, -0.6, 0.6, 1.8, 3.0):
        z = side * 1.45
        box("chair", (x - 0.25, 0.44, z - 0.25), (x + 0.25, 0.48, z + 0.25))
        back = z + side * 0.25
        box("chair", (x - 0.25, 0.48, min(back, back + side * 0.04)), (x + 0.25, 0.95, max(back, back + side * 0.04)))
        for dx in (-0.22, 0.19):
            for dz in (-0.22, 0.19):
                box("metal", (x + dx, 0.0, z + dz), (x + dx + 0.03, 0.44, z + dz + 0.03))
box("bin", (5.0, 0.0, -3.5), (5.4, 0.5, -3.1))
box("glass", (-0.15, 0.76, -0.15), (0.15, 1.16, 0.15))

with open(os.path.join(out, "conference.mtl"), "w") as f:
    f.write("""# igi-cluster's conference room (make_conference.py): Kd, Ks/Ns, Ke, d/Ni and map_Kd
newmtl wall
Kd 0.72 0.70 0.66
newmtl ceiling
Kd 0.80 0.80 0.80
newmtl floor
Kd 1 1 1
map_Kd floor.png
newmtl panel
Kd 0.0 0.0 0.0
Ke 28.0 26.6 23.8
newmtl board
Kd 0.85 0.85 0.85
newmtl table
Kd 0.45 0.30 0.18
newmtl chair
Kd 0.15 0.25 0.50
newmtl metal
Kd 0.05 0.05 0.05
Ks 0.75 0.75 0.78
Ns 200
newmtl bin
Kd 0.02 0.02 0.02
Ks 0.6 0.6 0.6
Ns 40
newmtl glass
Kd 0 0 0
Tf 0.9 1.0 0.95
Ni 1.5
d 0.1
illum 7
""")
with open(os.path.join(out, "conference.obj"), "w") as f:
    f.write("# igi-cluster's conference room (make_conference.py)\nmtllib conference.mtl\n")
    f.writelines(f"v {x:.4f} {y:.4f} {z:.4f}\n" for x, y, z in vertices)
    f.writelines(f"vt {u:.4f} {v:.4f}\n" for u, v in uvs)
    current = None
    for material, corners in faces:
        if material != current:
            f.write(f"usemtl {material}\n")
            current = material
        f.write("f " + " ".join(f"{v}/{t}" if t else f"{v}" for v, t in corners) + "\n")


def png(path, width, height, rgb):
    """An 8-bit RGB PNG (sRGB) from a function of (x, y)."""
    rows = b"".join(b"\0" + bytes(c for x in range(width) for c in rgb(x, y)) for y in range(height))
    chunk = lambda kind, data: (struct.pack(">I", len(data)) + kind + data +
                                struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF))
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)) +
                chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b""))


# Floor boards: two shades of oak, 8 boards to a texture, seams between them.
png(os.path.join(out, "floor.png"), 64, 64,
    lambda x, y: (60, 45, 30) if y % 8 == 0 else ((170, 125, 80) if (y // 8) % 2 else (150, 108, 70)))
print(f"{out}: conference.obj ({len(vertices)} vertices, {len(faces)} quads), conference.mtl, floor.png")

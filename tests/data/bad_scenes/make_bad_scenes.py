#!/usr/bin/env python3
"""Writes the broken scenes of this folder and MANIFEST (run from anywhere;
the files are checked in, this documents how each was made).

Each is a small emissive quad with exactly one thing broken. MANIFEST lists
"file<TAB>substring the error message must contain"; tests/common/scene/test_bad_scenes.cpp
runs igi-render on each and checks the exit status and the message."""
import base64, copy, json, os, struct

here = os.path.dirname(os.path.abspath(__file__))
os.chdir(here)
manifest = []

POSITIONS = [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)]
INDICES = [0, 1, 2, 0, 2, 3]
UVS = [(0, 1), (1, 1), (1, 0), (0, 0)]


def pack_bin(positions=POSITIONS, indices=INDICES, uvs=UVS):
    data = b"".join(struct.pack("<3f", *p) for p in positions)
    data += b"".join(struct.pack("<I", i) for i in indices)
    data += b"".join(struct.pack("<2f", *uv) for uv in uvs)
    return data


def document(data, uri=None):
    """A lit quad: positions, indices and uvs in one buffer, an emissive material."""
    np, ni = len(POSITIONS), len(INDICES)
    return {
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0, "TEXCOORD_0": 2}, "indices": 1, "material": 0}]}],
        "materials": [{"emissiveFactor": [1, 1, 1]}],
        "buffers": [{"byteLength": len(data),
                     "uri": uri or "data:application/octet-stream;base64," + base64.b64encode(data).decode()}],
        "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 12 * np},
                        {"buffer": 0, "byteOffset": 12 * np, "byteLength": 4 * ni},
                        {"buffer": 0, "byteOffset": 12 * np + 4 * ni, "byteLength": 8 * np}],
        "accessors": [{"bufferView": 0, "componentType": 5126, "count": np, "type": "VEC3",
                       "min": [-1, -1, 0], "max": [1, 1, 0]},
                      {"bufferView": 1, "componentType": 5125, "count": ni, "type": "SCALAR"},
                      {"bufferView": 2, "componentType": 5126, "count": np, "type": "VEC2"}],
    }


def write(name, content, expected):
    mode = "w" if isinstance(content, str) else "wb"
    with open(name, mode) as f:
        f.write(content)
    manifest.append((name, expected))


def gltf(name, doc, expected):
    write(name, json.dumps(doc, indent=1), expected)


def glb(doc, data, version=2, magic=b"glTF", edit=lambda text: text):
    """`edit` changes the JSON text (for text json.dumps cannot write)."""
    doc = copy.deepcopy(doc)
    del doc["buffers"][0]["uri"]
    text = edit(json.dumps(doc)).encode()
    text += b" " * (-len(text) % 4)
    data += b"\0" * (-len(data) % 4)
    chunks = struct.pack("<I4s", len(text), b"JSON") + text + struct.pack("<I4s", len(data), b"BIN\0") + data
    return magic + struct.pack("<II", version, 12 + len(chunks)) + chunks


data = pack_bin()
base = document(data)

# File framing.
whole = glb(base, data)
write("truncated.glb", whole[: len(whole) // 2], "truncated")
write("wrong-magic.glb", glb(base, data, magic=b"gLTf"), "missing the 'glTF' magic")
write("wrong-version.glb", glb(base, data, version=1), "version 1, expected 2")
write("invalid-json.gltf", json.dumps(base)[:-40] + "]]", "parse error")
gltf("missing-bin.gltf", document(data, uri="missing-bin.bin"), "missing-bin.bin")
# A URI out of the scene's folder is refused even though the file exists.
gltf("outside-folder.gltf", document(data, uri="../../CMakeLists.txt"), "outside the scene's folder")

# Accessors and buffers.
doc = copy.deepcopy(base)
doc["accessors"][0]["type"] = "VEC2"
gltf("accessor-type-mismatch.gltf", doc, "accessors[0] (POSITION of meshes[0].primitives[0]): type VEC2, expected VEC3")
doc = copy.deepcopy(base)
doc["accessors"][0]["count"] = 5
gltf("accessor-count-mismatch.gltf", doc, "count 5 (stride 12, byteOffset 0) exceeds bufferView 0 (48 bytes)")
doc = copy.deepcopy(base)
doc["accessors"][1]["count"] = 2**31
gltf("huge-accessor-count.gltf", doc, "count 2147483648 (stride 4, byteOffset 0) exceeds bufferView 1")
doc = copy.deepcopy(base)
doc["bufferViews"][0]["byteLength"] = 2**40
gltf("huge-buffer-view.gltf", doc, "bufferViews[0]: byteOffset 0 + byteLength 1099511627776 exceeds buffer 0")
doc = copy.deepcopy(base)
doc["buffers"][0]["byteLength"] = 2**40
gltf("huge-buffer.gltf", doc, "Failed to decode 'uri'")
write("indices-out-of-range.glb", glb(base, pack_bin(indices=[0, 1, 2, 0, 2, 7])),
      "index 7 at element 5 is out of range: the primitive has 4 vertices")
# tinygltf reads a negative or fractional offset or stride as absent (0).
doc = copy.deepcopy(base)
doc["accessors"][0]["byteOffset"] = -4
gltf("negative-byte-offset.gltf", doc, "accessors[0]: byteOffset -4, expected an integer >= 0")
doc = copy.deepcopy(base)
doc["bufferViews"][0]["byteStride"] = 12.5
write("fractional-byte-stride.glb", glb(doc, data), "bufferViews[0]: byteStride 12.5, expected an integer >= 0")

# JSON nested past the loader's 64 levels (20,000 overflowed tinygltf's stack:
# test_bad_scenes.cpp deepens deep-extras.gltf to that).
doc = copy.deepcopy(base)
doc["nodes"][0]["extras"] = "DEEP"
write("deep-extras.gltf", json.dumps(doc).replace('"DEEP"', "[" * 65 + "]" * 65), "nested deeper than 64 levels")
doc = copy.deepcopy(base)
doc["extensions"] = {"EXT_deep": "DEEP"}
write("deep-extensions.glb", glb(doc, data, edit=lambda text: text.replace('"DEEP"', '{"a":' * 65 + "0" + "}" * 65)),
      "nested deeper than 64 levels")

# Extensions: one the loader does not read, marked required, must be refused.
doc = copy.deepcopy(base)
doc["extensionsUsed"] = doc["extensionsRequired"] = ["KHR_draco_mesh_compression"]
gltf("unknown-required-extension.gltf", doc,
     "extensionsRequired[0]: KHR_draco_mesh_compression is required but not supported")

# Values.
nan = float("nan")
write("nan-position.glb", glb(base, pack_bin(positions=[(-1, -1, 0), (1, nan, 0), (1, 1, 0), (-1, 1, 0)])),
      "accessors[0] (POSITION of meshes[0].primitives[0]): element 1 is not finite")
inf = float("inf")
gltf("infinite-position.gltf", document(pack_bin(positions=[(-1, -1, 0), (1, -1, 0), (inf, 1, 0), (-1, 1, 0)])),
     "element 2 is not finite")
doc = copy.deepcopy(base)
doc["nodes"][0]["translation"] = [1e300, 0, 0]
gltf("infinite-node-translation.gltf", doc, "expected coordinates within +-1e15 m")
doc = copy.deepcopy(base)
doc["materials"][0]["emissiveFactor"] = [0, 0, 0]
doc["extensionsUsed"] = ["KHR_lights_punctual"]
doc["extensions"] = {"KHR_lights_punctual": {"lights": [{"type": "point", "intensity": 1e300}]}}
doc["nodes"].append({"extensions": {"KHR_lights_punctual": {"light": 0}}})
doc["scenes"][0]["nodes"].append(1)
gltf("infinite-light-intensity.gltf", doc, "lights[0]: color x intensity is not finite")
doc = copy.deepcopy(base)
doc["cameras"] = [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}}]
doc["nodes"].append({"camera": 0, "translation": [0, -1e300, 3]})
doc["scenes"][0]["nodes"].append(1)
gltf("infinite-camera.gltf", doc, "nodes[1]: the transform puts cameras[0] at (0.000000, -inf, 3.000000), expected coordinates within +-1e15 m")

# Scene content.
doc = copy.deepcopy(base)
doc["scenes"][0]["nodes"] = []
gltf("no-geometry.gltf", doc, "no geometry")

# Textures.
def textured(uri):
    doc = copy.deepcopy(base)
    doc["materials"][0]["pbrMetallicRoughness"] = {"baseColorTexture": {"index": 0}}
    doc["textures"] = [{"source": 0}]
    doc["images"] = [{"uri": uri}]
    return doc

gltf("missing-texture.gltf", textured("missing-texture.png"),
     "images[0] ('missing-texture.png'): the image file is missing")
write("garbage.png", bytes((i * 97 + 13) % 256 for i in range(64)), None)
gltf("garbage-texture.gltf", textured("garbage.png"), "images[0] ('garbage.png'): neither a PNG nor a JPEG")
png_header = b"\x89PNG\r\n\x1a\n" + struct.pack(">I4sIIBBBBB", 13, b"IHDR", 4, 4, 8, 6, 0, 0, 0) + b"\0\0\0\0"
write("broken.png", png_header + struct.pack(">I4s", 16, b"IDAT") + b"not zlib data!!!" + b"\0" * 4, None)
gltf("broken-texture.gltf", textured("broken.png"), "images[0] ('broken.png'): cannot be decoded")
huge_png = b"\x89PNG\r\n\x1a\n" + struct.pack(">I4sIIBBBBB", 13, b"IHDR", 100000, 100000, 8, 6, 0, 0, 0) + b"\0\0\0\0"
write("huge.png", huge_png, None)
gltf("huge-texture.gltf", textured("huge.png"), "100000 x 100000 pixels")

# Animations: node 0 moved by a translation channel whose key times and
# values sit in a second buffer.
def animated(times, values, interpolation="LINEAR", node=0, path="translation"):
    doc = copy.deepcopy(base)
    data = b"".join(struct.pack("<f", t) for t in times) + b"".join(struct.pack("<3f", *v) for v in values)
    doc["buffers"].append({"byteLength": len(data),
                           "uri": "data:application/octet-stream;base64," + base64.b64encode(data).decode()})
    doc["bufferViews"] += [{"buffer": 1, "byteOffset": 0, "byteLength": 4 * len(times)},
                           {"buffer": 1, "byteOffset": 4 * len(times), "byteLength": 12 * len(values)}]
    doc["accessors"] += [{"bufferView": 3, "componentType": 5126, "count": len(times), "type": "SCALAR"},
                         {"bufferView": 4, "componentType": 5126, "count": len(values), "type": "VEC3"}]
    doc["animations"] = [{"samplers": [{"input": 3, "output": 4, "interpolation": interpolation}],
                          "channels": [{"sampler": 0, "target": {"node": node, "path": path}}]}]
    return doc

moves = [(0, 0, 0), (1, 0, 0), (0, 0, 0)]
gltf("animation-count-mismatch.gltf", animated([0, 1, 2], moves[:2]),
     "animations[0].samplers[0]: output has 2 elements for 3 key times, expected 3")
gltf("animation-cubic-count.gltf", animated([0, 1, 2], moves, "CUBICSPLINE"),
     "output has 3 elements for 3 key times, expected 9 (CUBICSPLINE")
gltf("animation-times-not-increasing.gltf", animated([0, 1, 1], moves),
     "(input of animations[0].samplers[0]): key time 2 (1.000000) does not increase")
gltf("animation-nan-key.gltf", animated([0, nan, 2], moves),
     "(input of animations[0].samplers[0]): element 1 is not finite")
gltf("animation-nan-value.gltf", animated([0, 1, 2], [(0, 0, 0), (nan, 0, 0), (0, 0, 0)]),
     "(output of animations[0].samplers[0]): element 1 is not finite")
gltf("animation-missing-node.gltf", animated([0, 1, 2], moves, node=7),
     "animations[0].channels[0]: target node 7 does not exist (the file has 1)")
gltf("animation-bad-interpolation.gltf", animated([0, 1, 2], moves, "SMOOTH"),
     "animations[0].samplers[0]: interpolation 'SMOOTH', expected LINEAR, STEP or CUBICSPLINE")
gltf("animation-out-of-range.gltf", animated([0, 1, 2], [(0, 0, 0), (3e38, 0, 0), (0, 0, 0)]),
     "animations: at key time 1.000000 a moving part or light reaches")
doc = animated([0, 1, 2], moves)
doc["nodes"][0]["matrix"] = [1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1]
# Every key at the origin, but tangents of +-1e30 m/s carry the curve far out between them.
gltf("animation-cubic-overshoot.gltf",
     animated([0, 1], [(0, 0, 0), (0, 0, 0), (1e30, 0, 0), (-1e30, 0, 0), (0, 0, 0), (0, 0, 0)], "CUBICSPLINE"),
     "animations: between keys, at time 0.")
gltf("animation-of-matrix-node.gltf", doc, "nodes[0]: animated, but has a matrix")

def animated_camera(values, path):
    doc = animated([0, 1, 2], values, node=1, path=path)
    doc["cameras"] = [{"type": "perspective", "perspective": {"yfov": 0.8, "znear": 0.1}}]
    doc["nodes"].append({"camera": 0, "translation": [0, 0, 3]})
    doc["scenes"][0]["nodes"].append(1)
    return doc

gltf("animation-camera-out-of-range.gltf",
     animated_camera([(0, 0, 3), (0, 3e38, 3), (0, 0, 3)], "translation"),
     "animations: at key time 1.000000 the camera reaches (0.000000, 3000000005")
gltf("animation-camera-collapses.gltf", animated_camera([(1, 1, 1), (0, 0, 0), (1, 1, 1)], "scale"),
     "animations: at key time 1.000000 the camera's view collapses")

with open("MANIFEST", "w") as f:
    f.write("# file<TAB>substring igi-render's error must contain (written by make_bad_scenes.py)\n")
    for name, expected in manifest:
        if expected is not None:
            f.write(f"{name}\t{expected}\n")

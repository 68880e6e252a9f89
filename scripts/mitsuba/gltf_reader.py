"""A minimal glTF 2.0 reader (json + numpy) for the Mitsuba reference path.

Reads .gltf (buffers and images as data: URIs or files in the scene's own
folder) and .glb, accessors (no sparse ones), and the default scene's node
hierarchy with world matrices. It knows nothing of Mitsuba: gltf_to_mitsuba.py
maps what it reads. Anything it cannot read raises GltfError naming the file
and the element.
"""
import base64
import json
import os
import struct
import urllib.parse

import numpy as np

GLB_MAGIC, GLB_JSON, GLB_BIN = 0x46546C67, 0x4E4F534A, 0x004E4942
COMPONENT_TYPES = {5120: "<i1", 5121: "<u1", 5122: "<i2", 5123: "<u2", 5125: "<u4", 5126: "<f4"}
TYPE_SIZES = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4}


class GltfError(Exception):
    pass


def read_glb(data, path):
    """(json dict, BIN chunk bytes or None) of a .glb file's bytes."""
    if len(data) < 12 or struct.unpack_from("<I", data, 0)[0] != GLB_MAGIC:
        raise GltfError(f"{path}: GLB header: missing the 'glTF' magic")
    version, length = struct.unpack_from("<II", data, 4)
    if version != 2 or length > len(data):
        raise GltfError(f"{path}: GLB header: version {version}, length {length} of {len(data)} bytes")
    chunks, at = [], 12
    while at + 8 <= length:
        chunk_length, kind = struct.unpack_from("<II", data, at)
        chunks.append((kind, data[at + 8:at + 8 + chunk_length]))
        at += 8 + chunk_length
    if not chunks or chunks[0][0] != GLB_JSON:
        raise GltfError(f"{path}: GLB: expected the JSON chunk first")
    binary = chunks[1][1] if len(chunks) > 1 and chunks[1][0] == GLB_BIN else None
    return json.loads(chunks[0][1].decode("utf-8")), binary


def quaternion_matrix(q):
    x, y, z, w = np.asarray(q, dtype=np.float64) / np.linalg.norm(q)
    return np.array([
        [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
        [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
        [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
    ])


def local_matrix(node):
    """The node's 4x4 transform: its column-major matrix, or T * R * S."""
    if "matrix" in node:
        return np.array(node["matrix"], dtype=np.float64).reshape(4, 4).T
    out = np.eye(4)
    out[:3, :3] = quaternion_matrix(node.get("rotation", [0, 0, 0, 1])) @ np.diag(node.get("scale", [1, 1, 1]))
    out[:3, 3] = node.get("translation", [0, 0, 0])
    return out


def extension_names(value):
    """Every extension named anywhere in a JSON value, declared or not."""
    names = set()
    if isinstance(value, dict):
        names.update(value.get("extensions", {}).keys())
        names.update(value.get("extensionsUsed", []), value.get("extensionsRequired", []))
        for item in value.values():
            names |= extension_names(item)
    elif isinstance(value, list):
        for item in value:
            names |= extension_names(item)
    return names


class Gltf:
    """A parsed glTF file: doc (the JSON), buffers (bytes) and readers."""

    def __init__(self, path):
        self.path = path
        self.folder = os.path.dirname(os.path.abspath(path))
        try:
            with open(path, "rb") as f:
                data = f.read()
        except OSError as error:
            raise GltfError(f"{path}: cannot read the scene ({error.strerror})")
        if path.lower().endswith(".glb"):
            self.doc, glb_bin = read_glb(data, path)
        else:
            self.doc, glb_bin = json.loads(data.decode("utf-8")), None
        self.buffers = [self.read_buffer(i, glb_bin) for i in range(len(self.doc.get("buffers", [])))]

    def fail(self, element, why):
        raise GltfError(f"{self.path}: {element}: {why}")

    def element(self, kind, index):
        items = self.doc.get(kind, [])
        if not isinstance(index, int) or not 0 <= index < len(items):
            self.fail(kind, f"index {index} does not exist (the file has {len(items)})")
        return items[index]

    def read_uri(self, uri, element):
        """Bytes of a data: URI or of a file in the scene's folder."""
        if uri.startswith("data:"):
            header, _, payload = uri.partition(",")
            if not header.endswith(";base64"):
                self.fail(element, "data URI is not base64")
            return base64.b64decode(payload)
        relative = urllib.parse.unquote(uri)
        if os.path.isabs(relative) or ".." in relative.replace("\\", "/").split("/"):
            self.fail(element, f"'{uri}' is outside the scene's folder")
        try:
            with open(os.path.join(self.folder, relative), "rb") as f:
                return f.read()
        except OSError as error:
            self.fail(element, f"cannot read '{uri}' ({error.strerror})")

    def read_buffer(self, index, glb_bin):
        buffer, element = self.doc["buffers"][index], f"buffers[{index}]"
        if "uri" in buffer:
            data = self.read_uri(buffer["uri"], element)
        elif index == 0 and glb_bin is not None:
            data = glb_bin
        else:
            self.fail(element, "no uri and no GLB BIN chunk")
        if len(data) < buffer.get("byteLength", 0):
            self.fail(element, f"{len(data)} bytes, byteLength says {buffer['byteLength']}")
        return data

    def view_bytes(self, index):
        view = self.element("bufferViews", index)
        data = self.buffers[view["buffer"]] if view.get("buffer", -1) in range(len(self.buffers)) else None
        start, length = view.get("byteOffset", 0), view.get("byteLength", 0)
        if data is None or start + length > len(data):
            self.fail(f"bufferViews[{index}]", "outside its buffer")
        return data[start:start + length], view.get("byteStride")

    def accessor(self, index):
        """An accessor as a (count, components) array of its component type."""
        acc, element = self.element("accessors", index), f"accessors[{index}]"
        if "sparse" in acc:
            self.fail(element, "sparse accessors are not supported")
        if acc.get("componentType") not in COMPONENT_TYPES or acc.get("type") not in TYPE_SIZES:
            self.fail(element, f"componentType {acc.get('componentType')} type {acc.get('type')} not supported")
        dtype, components, count = np.dtype(COMPONENT_TYPES[acc["componentType"]]), TYPE_SIZES[acc["type"]], acc["count"]
        if "bufferView" not in acc:
            return np.zeros((count, components), dtype)
        data, stride = self.view_bytes(acc["bufferView"])
        item = dtype.itemsize * components
        stride, offset = stride or item, acc.get("byteOffset", 0)
        if count and offset + stride * (count - 1) + item > len(data):
            self.fail(element, "reads past the end of its bufferView")
        return np.ndarray((count, components), dtype, buffer=data, offset=offset, strides=(stride, dtype.itemsize))

    def float_accessor(self, index):
        """An accessor as float64, normalized integers mapped to [0, 1] or [-1, 1]."""
        values, acc = self.accessor(index), self.doc["accessors"][index]
        if values.dtype.kind == "f" or not acc.get("normalized", False):
            return values.astype(np.float64)
        return np.maximum(values / float(np.iinfo(values.dtype).max), -1.0)

    def image_bytes(self, index):
        image = self.element("images", index)
        if "uri" in image:
            return self.read_uri(image["uri"], f"images[{index}]")
        if "bufferView" in image:
            return self.view_bytes(image["bufferView"])[0]
        self.fail(f"images[{index}]", "neither a uri nor a bufferView")

    def world_nodes(self):
        """[(node index, node, 4x4 world matrix)] of the default scene, depth first in file order."""
        scene = self.element("scenes", self.doc.get("scene", 0)) if self.doc.get("scenes") else {"nodes": []}
        stack = [(n, np.eye(4)) for n in reversed(scene.get("nodes", []))]
        seen, out = set(), []
        while stack:
            index, parent = stack.pop()
            node = self.element("nodes", index)
            if index in seen:
                self.fail(f"nodes[{index}]", "reached twice: a glTF node has at most one parent and no cycles")
            seen.add(index)
            world = parent @ local_matrix(node)
            out.append((index, node, world))
            stack.extend((child, world) for child in reversed(node.get("children", [])))
        return out

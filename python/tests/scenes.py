"""glTF scenes built here for the suite (no committed assets): a torus
with normals and UVs (a seam where the unwrap closes) drawn by two
nodes, a ring of positions only, a line primitive swm keeps as written,
two materials, a PNG image in a bufferView, a texture, a sampler and an
animation. The same document as ``.glb`` bytes or as ``.gltf`` JSON with
its buffer in a ``data:`` URI.
"""

from __future__ import annotations

import base64
import json
import struct
from typing import Any, Dict, List, Optional, Tuple

import numpy as np

#: A 1×1 PNG, as tests/gltf_scene.rs has it (a valid image).
PNG = bytes.fromhex(
    "89504e470d0a1a0a0000000d4948445200000001000000010802000000907753de0000"
    "000c4944415408d763f8cfc000000301010018dd8db00000000049454e44ae426082"
)

ARRAY_BUFFER, ELEMENT_ARRAY_BUFFER = 34962, 34963


def torus(around: int, tube: int, big: float, small: float) -> Tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """A torus unwrapped onto [0, 1]²: ``(around + 1) × (tube + 1)``
    vertices, the last column and row repeating the first ones' positions
    bit for bit with u or v = 1 (the UV seams). Returns positions,
    normals, UVs (float32) and triangles (uint32)."""
    p, n, uv = [], [], []
    for j in range(tube + 1):
        b = 2 * np.pi * (j % tube) / tube
        for i in range(around + 1):
            a = 2 * np.pi * (i % around) / around
            normal = (np.cos(a) * np.cos(b), np.sin(a) * np.cos(b), np.sin(b))
            centre = (big * np.cos(a), big * np.sin(a), 0.0)
            p.append([c + small * d for c, d in zip(centre, normal)])
            n.append(normal)
            uv.append((i / around, j / tube))
    row = around + 1
    f = []
    for j in range(tube):
        for i in range(around):
            a, b = j * row + i, j * row + i + 1
            f += [(a, b, b + row), (a, b + row, a + row)]
    return (np.array(p, np.float32), np.array(n, np.float32), np.array(uv, np.float32),
            np.array(f, np.uint32))


class Builder:
    """The JSON and BIN of a glTF document, one tightly packed bufferView
    per accessor."""

    def __init__(self) -> None:
        self.bin = bytearray()
        self.views: List[Dict[str, Any]] = []
        self.accessors: List[Dict[str, Any]] = []

    def view(self, data: bytes, target: Optional[int] = None) -> int:
        while len(self.bin) % 4:
            self.bin.append(0)
        v: Dict[str, Any] = {"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data)}
        if target is not None:
            v["target"] = target
        self.bin += data
        self.views.append(v)
        return len(self.views) - 1

    def floats(self, a: np.ndarray, kind: str, target: Optional[int] = ARRAY_BUFFER, bounds: bool = False) -> int:
        a = np.ascontiguousarray(a, np.float32)
        acc: Dict[str, Any] = {"bufferView": self.view(a.tobytes(), target), "componentType": 5126,
                               "count": len(a), "type": kind}
        if bounds:
            flat = a.reshape(len(a), -1)
            acc["min"] = [float(x) for x in flat.min(axis=0)]
            acc["max"] = [float(x) for x in flat.max(axis=0)]
        self.accessors.append(acc)
        return len(self.accessors) - 1

    def indices(self, f: np.ndarray) -> int:
        a = np.ascontiguousarray(f, np.uint32).reshape(-1)
        self.accessors.append({"bufferView": self.view(a.tobytes(), ELEMENT_ARRAY_BUFFER),
                               "componentType": 5125, "count": len(a), "type": "SCALAR"})
        return len(self.accessors) - 1


def scene_document(lines: bool = True) -> Tuple[Dict[str, Any], bytes]:
    """The scene's JSON and its buffer. With ``lines``, a third mesh draws
    a line strip (kept as written by swm, and named)."""
    b = Builder()
    p, n, uv, f = torus(24, 12, 1.0, 0.35)
    donut = {
        "attributes": {
            "POSITION": b.floats(p, "VEC3", bounds=True),
            "NORMAL": b.floats(n, "VEC3"),
            "TEXCOORD_0": b.floats(uv, "VEC2"),
        },
        "indices": b.indices(f),
        "material": 0,
    }
    rp, _, _, rf = torus(32, 8, 2.0, 0.1)
    ring = {"attributes": {"POSITION": b.floats(rp, "VEC3", bounds=True)}, "indices": b.indices(rf),
            "material": 1}
    meshes = [{"name": "Donut", "primitives": [donut]}, {"name": "Ring", "primitives": [ring]}]
    nodes: List[Dict[str, Any]] = [
        {"name": "donut-a", "mesh": 0, "translation": [-2.0, 0.0, 0.0]},
        {"name": "arm", "children": [2], "rotation": [0.0, 0.0, 0.38268343, 0.9238795]},
        {"name": "donut-b", "mesh": 0, "translation": [2.0, 0.0, 0.0], "scale": [0.5, 0.5, 0.5]},
        {"name": "ring", "mesh": 1},
    ]
    if lines:
        wire = np.array([[0, 0, 0], [0, 0, 1], [0, 1, 1], [1, 1, 1]], np.float32)
        meshes.append({"name": "Wire", "primitives": [
            {"attributes": {"POSITION": b.floats(wire, "VEC3", bounds=True)}, "mode": 3}]})
        nodes.append({"name": "wire", "mesh": 2})
    times = np.array([0.0, 1.0, 2.0], np.float32)
    moves = np.array([[-2, 0, 0], [-2, 1, 0], [-2, 0, 0]], np.float32)
    animation = {
        "name": "bob",
        "samplers": [{"input": b.floats(times, "SCALAR", None, bounds=True),
                      "output": b.floats(moves, "VEC3", None), "interpolation": "LINEAR"}],
        "channels": [{"sampler": 0, "target": {"node": 0, "path": "translation"}}],
    }
    image = b.view(PNG)
    doc = {
        "asset": {"version": "2.0", "generator": "swm python tests"},
        "scene": 0,
        "scenes": [{"nodes": [0, 1, 3] + ([4] if lines else [])}],
        "nodes": nodes,
        "meshes": meshes,
        "materials": [
            {"name": "icing", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0},
                                                        "metallicFactor": 0.0}},
            {"name": "steel", "pbrMetallicRoughness": {"baseColorFactor": [0.6, 0.6, 0.7, 1.0]}},
        ],
        "images": [{"bufferView": image, "mimeType": "image/png"}],
        "samplers": [{"magFilter": 9729, "minFilter": 9987}],
        "textures": [{"sampler": 0, "source": 0}],
        "animations": [animation],
        "accessors": b.accessors,
        "bufferViews": b.views,
        "buffers": [{"byteLength": len(b.bin)}],
    }
    return doc, bytes(b.bin)


def glb(doc: Dict[str, Any], bin_chunk: bytes) -> bytes:
    """A GLB file (glTF 2.0 §4.4) of a document and its buffer."""
    text = json.dumps(doc, separators=(",", ":")).encode()
    text += b" " * (-len(text) % 4)
    data = bin_chunk + b"\0" * (-len(bin_chunk) % 4)
    out = struct.pack("<II", len(text), 0x4E4F534A) + text + struct.pack("<II", len(data), 0x004E4942) + data
    return struct.pack("<4sII", b"glTF", 2, 12 + len(out)) + out


def scene_glb(lines: bool = True) -> bytes:
    """The scene as ``.glb`` bytes."""
    return glb(*scene_document(lines))


def scene_gltf(lines: bool = True) -> bytes:
    """The scene as ``.gltf`` JSON, its buffer in a base64 ``data:`` URI."""
    doc, bin_chunk = scene_document(lines)
    doc["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64.b64encode(bin_chunk).decode()
    return json.dumps(doc).encode()


def parse_glb(data: bytes) -> Tuple[Dict[str, Any], bytes]:
    """The JSON and BIN chunk of a GLB file."""
    assert data[:4] == b"glTF", data[:4]
    (n,) = struct.unpack_from("<I", data, 12)
    doc = json.loads(data[20 : 20 + n])
    rest = data[20 + n :]
    bin_chunk = b""
    if len(rest) >= 8:
        (m,) = struct.unpack_from("<I", rest, 0)
        bin_chunk = rest[8 : 8 + m]
    return doc, bin_chunk


def accessor(doc: Dict[str, Any], bin_chunk: bytes, index: int) -> np.ndarray:
    """A float or index accessor of a GLB's BIN chunk, as an array."""
    acc = doc["accessors"][index]
    view = doc["bufferViews"][acc["bufferView"]]
    dims = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4}[acc["type"]]
    dtype = {5126: np.float32, 5125: np.uint32, 5123: np.uint16, 5121: np.uint8}[acc["componentType"]]
    start = view.get("byteOffset", 0) + acc.get("byteOffset", 0)
    stride = view.get("byteStride", dims * np.dtype(dtype).itemsize)
    assert stride == dims * np.dtype(dtype).itemsize, "tightly packed accessors only"
    a = np.frombuffer(bin_chunk, dtype, acc["count"] * dims, start)
    return a.reshape(acc["count"], dims)

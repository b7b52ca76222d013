#!/usr/bin/env python3
"""Builds the textured benchmark scene of BENCHMARKS.md ("glTF scenes")
from the shared corpus: spot.obj with its UVs and a generated 256x256
checker texture, drawn by two nodes (one animated), suzanne.obj with its
normals (quads fanned into triangles), stanford-bunny.obj and fandisk.obj
as positions only under a second material; one GLB, written to the path
given (default scene.glb). Standard library only.

    python3 tools/bench/gltf_scene.py ../shared/corpus scene.glb
"""
import json
import math
import struct
import sys
import zlib
from pathlib import Path


def read_obj(path):
    """Split vertices (one per distinct v/vt/vn of a corner), attributes
    present, triangles (polygons fanned)."""
    v, vt, vn, corners, tris = [], [], [], {}, []
    verts = []
    for line in open(path):
        p = line.split()
        if not p:
            continue
        if p[0] == "v":
            v.append(tuple(map(float, p[1:4])))
        elif p[0] == "vt":
            vt.append(tuple(map(float, p[1:3])))
        elif p[0] == "vn":
            vn.append(tuple(map(float, p[1:4])))
        elif p[0] == "f":
            ids = []
            for c in p[1:]:
                k = tuple(int(x) - 1 if x else -1 for x in (c.split("/") + ["", ""])[:3])
                if k not in corners:
                    corners[k] = len(verts)
                    verts.append(k)
                ids.append(corners[k])
            for i in range(1, len(ids) - 1):
                tris.append((ids[0], ids[i], ids[i + 1]))
    pos = [v[k[0]] for k in verts]
    uv = [(vt[k[1]][0], 1.0 - vt[k[1]][1]) for k in verts] if vt else None
    nrm = None
    if vn:
        nrm = []
        for k in verts:
            n = vn[k[2]]
            l = math.sqrt(sum(c * c for c in n)) or 1.0
            nrm.append(tuple(c / l for c in n))
    return pos, uv, nrm, tris


def png(size=256, cell=32):
    rows = b"".join(
        b"\0" + bytes(
            c
            for x in range(size)
            for c in ((230, 200, 60) if (x // cell + y // cell) % 2 else (40, 60, 160))
        )
        for y in range(size)
    )
    def chunk(t, d):
        return struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d))
    ihdr = struct.pack(">IIBBBBB", size, size, 8, 2, 0, 0, 0)
    return b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", ihdr) + chunk(b"IDAT", zlib.compress(rows, 9)) + chunk(b"IEND", b"")


class Glb:
    def __init__(self):
        self.bin, self.views, self.accessors = bytearray(), [], []

    def view(self, data, target=None):
        self.bin += b"\0" * (-len(self.bin) % 4)
        v = {"buffer": 0, "byteOffset": len(self.bin), "byteLength": len(data)}
        if target:
            v["target"] = target
        self.bin += data
        self.views.append(v)
        return len(self.views) - 1

    def floats(self, rows, ty, target=34962, bounds=False):
        flat = [c for r in rows for c in r]
        a = {"bufferView": self.view(struct.pack(f"<{len(flat)}f", *flat), target),
             "componentType": 5126, "count": len(rows), "type": ty}
        if bounds:
            a["min"] = [min(r[k] for r in rows) for k in range(len(rows[0]))]
            a["max"] = [max(r[k] for r in rows) for k in range(len(rows[0]))]
        self.accessors.append(a)
        return len(self.accessors) - 1

    def indices(self, tris):
        flat = [i for t in tris for i in t]
        wide = max(flat) >= 65535
        data = struct.pack(f"<{len(flat)}{'I' if wide else 'H'}", *flat)
        self.accessors.append({"bufferView": self.view(data, 34963),
                               "componentType": 5125 if wide else 5123,
                               "count": len(flat), "type": "SCALAR"})
        return len(self.accessors) - 1

    def mesh(self, name, path, material):
        pos, uv, nrm, tris = read_obj(path)
        attrs = {"POSITION": self.floats(pos, "VEC3", bounds=True)}
        if nrm:
            attrs["NORMAL"] = self.floats(nrm, "VEC3")
        if uv:
            attrs["TEXCOORD_0"] = self.floats(uv, "VEC2")
        prim = {"attributes": attrs, "indices": self.indices(tris), "material": material}
        return {"name": name, "primitives": [prim]}


def main():
    corpus = Path(sys.argv[1] if len(sys.argv) > 1 else "../shared/corpus")
    out = Path(sys.argv[2] if len(sys.argv) > 2 else "scene.glb")
    g = Glb()
    meshes = [
        g.mesh("spot", corpus / "spot.obj", 0),
        g.mesh("suzanne", corpus / "suzanne.obj", 1),
        g.mesh("bunny", corpus / "stanford-bunny.obj", 1),
        g.mesh("fandisk", corpus / "fandisk.obj", 1),
    ]
    times = g.floats([(0.0,), (1.0,), (2.0,)], "SCALAR", None, bounds=True)
    moves = g.floats([(0.0, 0.0, 0.0), (0.0, 0.5, 0.0), (0.0, 0.0, 0.0)], "VEC3", None)
    image = g.view(png())
    doc = {
        "asset": {"version": "2.0", "generator": "tools/bench/gltf_scene.py"},
        "scene": 0,
        "scenes": [{"nodes": [0]}],
        "nodes": [
            {"name": "root", "children": [1, 2, 3, 4, 5]},
            {"name": "spot", "mesh": 0},
            {"name": "spot again", "mesh": 0, "translation": [2.0, 0.0, 0.0], "rotation": [0.0, 0.7071068, 0.0, 0.7071068]},
            {"name": "suzanne", "mesh": 1, "translation": [-2.0, 0.0, 0.0]},
            {"name": "bunny", "mesh": 2, "translation": [0.0, 0.0, -2.0], "scale": [5.0, 5.0, 5.0]},
            {"name": "fandisk", "mesh": 3, "translation": [0.0, 0.0, 3.0], "scale": [0.1, 0.1, 0.1]},
        ],
        "meshes": meshes,
        "materials": [
            {"name": "checker", "pbrMetallicRoughness": {"baseColorTexture": {"index": 0}, "metallicFactor": 0.0}},
            {"name": "clay", "pbrMetallicRoughness": {"baseColorFactor": [0.8, 0.5, 0.4, 1.0]}},
        ],
        "textures": [{"sampler": 0, "source": 0}],
        "samplers": [{"magFilter": 9729, "minFilter": 9987}],
        "images": [{"bufferView": image, "mimeType": "image/png"}],
        "animations": [{"channels": [{"sampler": 0, "target": {"node": 1, "path": "translation"}}],
                        "samplers": [{"input": times, "output": moves}]}],
        "accessors": g.accessors,
        "bufferViews": g.views,
        "buffers": [{"byteLength": len(g.bin)}],
    }
    js = json.dumps(doc, separators=(",", ":")).encode()
    js += b" " * (-len(js) % 4)
    g.bin += b"\0" * (-len(g.bin) % 4)
    total = 12 + 8 + len(js) + 8 + len(g.bin)
    out.write_bytes(b"glTF" + struct.pack("<II", 2, total) + struct.pack("<I", len(js)) + b"JSON" + js
                    + struct.pack("<I", len(g.bin)) + b"BIN\0" + bytes(g.bin))


if __name__ == "__main__":
    main()

"""swm against Google Draco, gltfpack and meshoptimizer's simplifier, in one run.

Two tables, each from its own command line (both run from the repository
root):

    python3 tools/bench/side_by_side.py SWM_BIN [MESH ...] [--venv DIR] [--reps N] [--bpv R]

    python3 tools/bench/side_by_side.py SWM_BIN --efforts [MESH ...] [--rates 0.5,1,2,4,8]
        [--max] [--or-smallest] [--reps N] [--threads N] [--venv DIR] [--npm DIR]

The first (no --efforts) is the original side by side: swm lossless and
SwingWrapper against Draco and meshopt_simplify (described below, "The
codec table"). The second (--efforts) times `swm encode --effort` levels
against `draco_encoder` and gltfpack and measures each swm file's L2
(below, "The effort table"); the full run for BENCHMARKS.md, on a quiet
machine, is

    CARGO_TARGET_DIR=target cargo build --release -p swm-cli
    python3 tools/bench/side_by_side.py target/release/swm --efforts --max --reps 3

(every mesh of ../shared/corpus at 0.5, 1, 2, 4 and 8 b/v; --max adds
`--effort max`, minutes per cell on the large meshes at high rates, hours
for the whole corpus; leave it out for fast and default alone).

SWM_BIN is a release `swm` (`cargo build --release -p swm-cli`, then
`target/release/swm`); this script builds nothing. MESH defaults to
`stanford-bunny.obj` and `horse.ply` in `../shared/corpus` (relative to the
repository root), or with --efforts to every .obj and .ply there, smallest
file first; when that folder is absent and no mesh is given, it prints
"skipped: ../shared/corpus not found" and exits 0.

The peers live outside the repository: DIR (default /tmp/swm-bench-venv)
is a virtual environment, created when missing and given `DracoPy` and
`meshoptimizer` (versions pinned below), then the script runs itself
again with that environment's Python; with --efforts, the npm package
`gltfpack` (pinned below) is installed with `npm install --prefix` into
the folder given by --npm (default /tmp/swm-bench-npm) when missing (npm
and Node.js needed).

- Draco: the `draco_encoder` and `draco_decoder` executables that the
  DracoPy wheel installs into DIR/bin (Draco 1.5.7), and DracoPy's
  `decode` (the same library) for an in-process decode time.
- meshoptimizer's simplifier: `meshopt_simplify` through the
  `meshoptimizer` package (the Python wrapper from meshoptimizer's own
  repository, which compiles the library's C++ sources when pip installs
  it, so DIR needs a C++ compiler once), called once per repetition on
  arrays already in memory: the simplifier alone, no file I/O.
- gltfpack (--efforts only): the npm package's command line, which runs
  gltfpack's WebAssembly build under Node.js (slower than a native
  gltfpack build, and its wall time includes starting Node.js).

The codec table
---------------

Per mesh and repetition, in this order (repetitions interleave the tools,
so each median sees the same load on a shared machine):

1. `swm encode IN --mode lossless --qp 11 --json` and `swm decode` of it;
2. `swm encode IN --mode swing --bpv R --json` and `swm decode` of it;
3. `draco_encoder -i IN -cl 10 -qp 11` with normals, texture coordinates
   and generic attributes skipped (swm codes positions and triangles
   only), `draco_decoder` of it, and `DracoPy.decode` of the same bytes
   (Draco reads float32 or int32 PLY positions only: a PLY with double
   positions, such as bunny-1m, is handed to it as a float32 binary PLY
   of the same vertices and triangles, written once before timing);
4. `meshopt_simplify` of IN to the triangle count swm's R b/v file
   decodes to (target error 1.0, relative: the count decides).

Decoders write binary PLY on both sides. Two kinds of time:

- wall: the whole command, timed from here (process start, reading the
  input, writing the output);
- in-process: what the tool reports for the codec call alone (`swm`'s
  `encode_seconds`/`decode_seconds` from --json; Draco's "(N ms to
  encode/decode)", whole milliseconds) or, for DracoPy and meshopt,
  `time.perf_counter` around the Python call (DracoPy's includes copying
  the result into NumPy arrays).

swm runs with RAYON_NUM_THREADS=1, so every tool uses one core. Prints a
Markdown table of medians, the ratio swm / peer measured in this run
(below 1: swm is faster or smaller) and the file sizes.

The effort table (--efforts)
----------------------------

Before timing, each mesh is written once as a GLB for gltfpack (float32
positions and uint32 triangle indices, nothing else, so that every tool
codes positions and triangles only) and, where Draco needs it, as a
float32 PLY (above). Then per mesh, per rate R (--rates, bits per input
vertex) and repetition, in this order:

1. `swm encode IN -o OUT --bpv R --effort E --json` for E = fast,
   default and (with --max) max, with RAYON_NUM_THREADS=N (--threads,
   default 1: one core, as the peers); wall time, the in-process
   `encode_seconds` and the file's bytes;
2. `draco_encoder -i IN -o OUT -cl 10 -qp 11` (positions and triangles
   only, as above): wall time and its own "(N ms to encode)". Draco's
   file does not depend on R; it runs at every rate so that each bar
   compares times taken under the same load;
3. `gltfpack -i IN.glb -o OUT.glb -si S -cc`, where S is the triangle
   count of swm's default file (as decoded) over the input's triangle
   count, so that both keep about as many triangles (gltfpack's default
   `-se 0.01` error limit and 14-bit positions kept: it can stop above
   that count, and its own count is printed); wall time, bytes, and the
   triangle count its `-v` log reports.

In the first repetition only, untimed and between the timed commands:
each swm file is decoded (`swm decode OUT -o OUT.ply --json`, the
decoded mesh a user gets, post-processing hint followed) and measured
against IN with `swm distance IN OUT.ply --json`; the table gives its
`l2_relative` as x 1e-4 of IN's bounding-box diagonal (the "x 1e-4 of the
diagonal" figure `swm distance` prints). Later repetitions check that
each file has the same bytes (a size that varied shows as "a/b").

Printed: two Markdown tables of medians over the repetitions: times
(each level's wall and in-process time, wall / Draco's wall, and whether
issue 45's bar holds: `fast` wall <= max(2 x Draco's wall, 0.3 s),
`default` wall <= max(10 x Draco's wall, 0.5 s); `max` has no bar), and
sizes and L2 (with gltfpack's bytes and triangles); then how many cells
meet each bar, and the geometric-mean L2 of each level over the cells
where every level wrote a file. A cell whose `swm encode` fails shows the
error and the run goes on: at 0.5 b/v the smallest meshes (woody,
suzanne) ask for fewer bytes than their smallest file, which `swm encode`
refuses unless given `--or-smallest` (pass --or-smallest to this script
to time that smallest file instead; the table's command line says which).
"""

from __future__ import annotations

import argparse
import json
import os
import re
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
CORPUS = ROOT.parent / "shared" / "corpus"
DEFAULT_MESHES = ["stanford-bunny.obj", "horse.ply"]
DEFAULT_VENV = Path("/tmp/swm-bench-venv")
# Pinned so that reruns compare the same peers.
PEERS = ["DracoPy==2.2.0", "meshoptimizer==0.2.30a0", "numpy"]
GLTFPACK = "gltfpack@1.3.0"
DEFAULT_NPM = Path("/tmp/swm-bench-npm")
DEFAULT_RATES = "0.5,1,2,4,8"
REEXEC_MARK = "SWM_SIDE_BY_SIDE_IN_VENV"


class Failure(Exception):
    """A one-line reason to stop (missing tool, failed command)."""


def last_line(text: str | bytes) -> str:
    if isinstance(text, bytes):
        text = text.decode(errors="replace")
    lines = [l.strip() for l in text.strip().splitlines() if l.strip()]
    return lines[-1] if lines else "(no output)"


def run(cmd: list[str], env: dict | None = None) -> tuple[float, str]:
    """Runs `cmd`; returns (wall seconds, stdout). Raises Failure on error."""
    start = time.perf_counter()
    try:
        p = subprocess.run(cmd, capture_output=True, env=env)
    except OSError as e:
        raise Failure(f"cannot run {cmd[0]}: {e.strerror}") from None
    wall = time.perf_counter() - start
    if p.returncode != 0:
        raise Failure(f"{Path(cmd[0]).name} failed (exit {p.returncode}): "
                      f"{last_line(p.stderr or p.stdout)}")
    return wall, p.stdout.decode(errors="replace")


# --- the virtual environment ------------------------------------------------

def venv_python(venv: Path) -> Path:
    return venv / "bin" / "python"


def ensure_venv(venv: Path) -> None:
    py = venv_python(venv)
    if not py.exists():
        print(f"creating {venv} ...", file=sys.stderr)
        try:
            run([sys.executable, "-m", "venv", str(venv)])
        except Failure as e:
            raise Failure(f"cannot create the virtual environment {venv}: {e}") from None
    probe = subprocess.run([str(py), "-c", "import DracoPy, meshoptimizer, numpy"],
                           capture_output=True)
    if probe.returncode != 0:
        print(f"installing {' '.join(PEERS)} into {venv} ...", file=sys.stderr)
        try:
            run([str(py), "-m", "pip", "install", "--quiet", "--pre", *PEERS])
        except Failure as e:
            raise Failure(f"cannot install the peers into {venv} "
                          f"(meshoptimizer needs a C++ compiler): {e}") from None


# --- meshes for the simplifier ----------------------------------------------

def read_obj(path: Path):
    import numpy as np
    verts, faces = [], []
    with open(path, "r", errors="replace") as f:
        for line in f:
            if line.startswith("v "):
                verts.append([float(x) for x in line.split()[1:4]])
            elif line.startswith("f "):
                idx = []
                for tok in line.split()[1:]:
                    i = int(tok.split("/")[0])
                    idx.append(i - 1 if i > 0 else len(verts) + i)
                for k in range(1, len(idx) - 1):  # fan of a polygon
                    faces.append((idx[0], idx[k], idx[k + 1]))
    return np.array(verts, dtype=np.float32), np.array(faces, dtype=np.uint32)


PLY_TYPES = {"char": "i1", "int8": "i1", "uchar": "u1", "uint8": "u1",
             "short": "i2", "int16": "i2", "ushort": "u2", "uint16": "u2",
             "int": "i4", "int32": "i4", "uint": "u4", "uint32": "u4",
             "float": "f4", "float32": "f4", "double": "f8", "float64": "f8"}


def read_ply(path: Path):
    """Binary little-endian or ASCII PLY: vertex x, y, z and face lists."""
    import numpy as np
    data = path.read_bytes()
    end = data.find(b"end_header")
    if end < 0:
        raise Failure(f"{path}: not a PLY file")
    body = data[data.index(b"\n", end) + 1:]
    fmt, elements = None, []
    for line in data[:end].decode("ascii", "replace").splitlines():
        w = line.split()
        if not w:
            continue
        if w[0] == "format":
            fmt = w[1]
        elif w[0] == "element":
            elements.append((w[1], int(w[2]), []))
        elif w[0] == "property":
            elements[-1][2].append(w[1:])
    if fmt == "ascii":
        tokens = body.split()
        pos, verts, faces = 0, None, None
        for name, count, props in elements:
            if name == "vertex":
                n = len(props)
                rows = np.array(tokens[pos:pos + n * count], dtype=np.float64).reshape(count, n)
                names = [p[-1] for p in props]
                verts = rows[:, [names.index(a) for a in "xyz"]].astype(np.float32)
                pos += n * count
            elif name == "face":
                out = []
                for _ in range(count):
                    k = int(tokens[pos])
                    idx = [int(t) for t in tokens[pos + 1:pos + 1 + k]]
                    pos += 1 + k
                    out += [(idx[0], idx[j], idx[j + 1]) for j in range(1, k - 1)]
                faces = np.array(out, dtype=np.uint32)
            else:
                raise Failure(f"{path}: ASCII PLY element '{name}' before the faces is not supported")
        return verts, faces
    if fmt != "binary_little_endian":
        raise Failure(f"{path}: PLY format '{fmt}' is not supported by this script")
    offset, verts, faces = 0, None, None
    for name, count, props in elements:
        if any(p[0] == "list" for p in props):
            if name != "face" or len(props) != 1:
                raise Failure(f"{path}: PLY element '{name}' with lists is not supported")
            _, ct, it, _ = props[0]
            ct, it = np.dtype("<" + PLY_TYPES[ct]), np.dtype("<" + PLY_TYPES[it])
            # Fast path: every face a triangle.
            tri = np.dtype([("n", ct), ("i", it, (3,))])
            rec = np.frombuffer(body, dtype=tri, count=count, offset=offset) \
                if len(body) - offset >= tri.itemsize * count else None
            if rec is not None and np.all(rec["n"] == 3):
                faces = rec["i"].astype(np.uint32)
                offset += tri.itemsize * count
            else:
                out = []
                for _ in range(count):
                    k = int(np.frombuffer(body, ct, 1, offset)[0])
                    idx = np.frombuffer(body, it, k, offset + ct.itemsize)
                    offset += ct.itemsize + it.itemsize * k
                    out += [(idx[0], idx[j], idx[j + 1]) for j in range(1, k - 1)]
                faces = np.array(out, dtype=np.uint32)
        else:
            dt = np.dtype([(p[1], "<" + PLY_TYPES[p[0]]) for p in props])
            rec = np.frombuffer(body, dtype=dt, count=count, offset=offset)
            offset += dt.itemsize * count
            if name == "vertex":
                verts = np.stack([rec[a] for a in "xyz"], axis=1).astype(np.float32)
        if verts is not None and faces is not None:
            break
    return verts, faces


def read_mesh(path: Path):
    suffix = path.suffix.lower()
    if suffix == ".obj":
        v, f = read_obj(path)
    elif suffix == ".ply":
        v, f = read_ply(path)
    else:
        raise Failure(f"{path}: the meshopt step reads .obj and .ply only")
    if v is None or f is None or len(f) == 0:
        raise Failure(f"{path}: no vertices or no faces found for the meshopt step")
    return v, f


# --- measuring --------------------------------------------------------------

def ms_reported(stdout: str, what: str) -> float:
    m = re.search(r"\((\d+) ms to " + what + r"\)", stdout)
    if not m:
        raise Failure(f"draco_{what}r printed no '(N ms to {what})': {last_line(stdout)}")
    return int(m.group(1)) / 1000.0


def ply_position_type(path: Path) -> str | None:
    """The type of a PLY file's vertex `x` property, or None."""
    head = path.read_bytes()[:4096].decode("ascii", "replace")
    in_vertex = False
    for line in head.splitlines():
        w = line.split()
        if w[:1] == ["element"]:
            in_vertex = w[1:2] == ["vertex"]
        elif in_vertex and w[:1] == ["property"] and w[-1:] == ["x"]:
            return w[1]
        elif w[:1] == ["end_header"]:
            break
    return None


def draco_input(mesh: Path, verts, faces, tmp: Path) -> Path:
    """`mesh`, or a float32 binary PLY of it where Draco cannot read its
    positions (PLY doubles)."""
    if mesh.suffix.lower() != ".ply" or ply_position_type(mesh) not in ("double", "float64"):
        return mesh
    import numpy as np
    out = tmp / "draco-input.ply"
    header = ("ply\nformat binary_little_endian 1.0\n"
              f"element vertex {len(verts)}\nproperty float x\nproperty float y\nproperty float z\n"
              f"element face {len(faces)}\nproperty list uchar uint vertex_indices\nend_header\n")
    tri = np.zeros(len(faces), dtype=[("n", "u1"), ("i", "<u4", (3,))])
    tri["n"], tri["i"] = 3, faces
    out.write_bytes(header.encode("ascii") + verts.astype("<f4").tobytes() + tri.tobytes())
    return out


def measure(mesh: Path, swm: str, venv: Path, reps: int, bpv: float) -> dict:
    import numpy as np
    import DracoPy
    import meshoptimizer

    enc, dec = str(venv / "bin" / "draco_encoder"), str(venv / "bin" / "draco_decoder")
    swm_env = dict(os.environ, RAYON_NUM_THREADS="1")
    verts, faces = read_mesh(mesh)
    indices = np.ascontiguousarray(faces.reshape(-1))
    verts = np.ascontiguousarray(verts)
    t = {k: [] for k in ["l_enc_wall", "l_enc_in", "l_dec_wall", "l_dec_in",
                         "s_enc_wall", "s_enc_in", "s_dec_wall", "s_dec_in",
                         "d_enc_wall", "d_enc_in", "d_dec_wall", "d_dec_in", "d_dec_py",
                         "mo_in"]}
    info: dict = {}
    with tempfile.TemporaryDirectory(prefix="swm-side-") as tmp:
        tmp = Path(tmp)
        for_draco = draco_input(mesh, verts, faces, tmp)
        for _ in range(reps):
            # swm lossless, qp 11
            w, out = run([swm, "encode", str(mesh), "-o", str(tmp / "l.swm"),
                          "--mode", "lossless", "--qp", "11", "--json"], swm_env)
            t["l_enc_wall"].append(w)
            j = json.loads(out)
            t["l_enc_in"].append(j["encode_seconds"])
            info["l_bytes"] = (tmp / "l.swm").stat().st_size
            info["in_tris"] = j["triangles"]
            info["in_verts"] = j["input_vertices"]
            w, out = run([swm, "decode", str(tmp / "l.swm"), "-o", str(tmp / "l.ply"), "--json"], swm_env)
            t["l_dec_wall"].append(w)
            t["l_dec_in"].append(json.loads(out)["decode_seconds"])
            # swm SwingWrapper at R b/v
            w, out = run([swm, "encode", str(mesh), "-o", str(tmp / "s.swm"),
                          "--mode", "swing", "--bpv", str(bpv), "--json"], swm_env)
            t["s_enc_wall"].append(w)
            t["s_enc_in"].append(json.loads(out)["encode_seconds"])
            info.setdefault("s_bytes", set()).add((tmp / "s.swm").stat().st_size)
            w, out = run([swm, "decode", str(tmp / "s.swm"), "-o", str(tmp / "s.ply"), "--json"], swm_env)
            t["s_dec_wall"].append(w)
            j = json.loads(out)
            t["s_dec_in"].append(j["decode_seconds"])
            info.setdefault("s_tris", set()).add(j["decoded_triangles"])
            # Draco, cl 10, qp 11, positions only
            w, out = run([enc, "-i", str(for_draco), "-o", str(tmp / "d.drc"), "-cl", "10", "-qp", "11",
                          "-qn", "-1", "-qt", "-1", "-qg", "-1"])
            t["d_enc_wall"].append(w)
            t["d_enc_in"].append(ms_reported(out, "encode"))
            info["d_bytes"] = (tmp / "d.drc").stat().st_size
            w, out = run([dec, "-i", str(tmp / "d.drc"), "-o", str(tmp / "d.ply")])
            t["d_dec_wall"].append(w)
            t["d_dec_in"].append(ms_reported(out, "decode"))
            drc = (tmp / "d.drc").read_bytes()
            start = time.perf_counter()
            decoded = DracoPy.decode(drc)
            t["d_dec_py"].append(time.perf_counter() - start)
            info["d_tris"] = len(decoded.faces)
            # meshopt_simplify to the triangle count of swm's file
            target = max(info["s_tris"])
            dest = np.zeros(len(indices), dtype=np.uint32)
            start = time.perf_counter()
            n = meshoptimizer.simplify(dest, indices, verts, target_index_count=3 * target,
                                       target_error=1.0)
            t["mo_in"].append(time.perf_counter() - start)
            info["mo_tris"] = n // 3
    med = {k: statistics.median(v) for k, v in t.items()}
    med["reps"] = reps
    med.update(info)
    return med


# --- the table --------------------------------------------------------------

def fmt_s(s: float, tris: int | None = None) -> str:
    t = f"{s * 1000:.1f} ms" if s < 1 else f"{s:.2f} s"
    if tris is None:
        return t
    # Draco reports whole milliseconds: 0 ms on a small mesh.
    return f"{t} ({tris / s / 1e6:.2f} M tri/s)" if s > 0 else f"{t} (below 1 ms)"


def table(name: str, m: dict, bpv: float) -> list[str]:
    rows = []

    def row(what: str, swm_txt: str, peer: str, peer_txt: str, ratio: float | None) -> None:
        r = "-" if ratio is None else f"{ratio:.2f}"
        rows.append(f"| {name} | {what} | {swm_txt} | {peer} | {peer_txt} | {r} |")

    def timed(what: str, a: str, peer: str, b: str, ta: int | None = None,
              tb: int | None = None) -> None:
        row(what, fmt_s(m[a], ta), peer, fmt_s(m[b], tb), m[a] / m[b] if m[b] > 0 else None)

    sb = sorted(m["s_bytes"])
    st = sorted(m["s_tris"])
    n, d, s = m["in_tris"], m["d_tris"], st[0]
    row("file, lossless qp 11 (bytes)", f"{m['l_bytes']:,}", "Draco cl 10, qp 11",
        f"{m['d_bytes']:,}", m["l_bytes"] / m["d_bytes"])
    timed("lossless encode, wall", "l_enc_wall", "draco_encoder, wall", "d_enc_wall", n, n)
    timed("lossless encode, in-process", "l_enc_in", "draco_encoder, reported", "d_enc_in", n, n)
    timed("lossless decode, wall", "l_dec_wall", "draco_decoder, wall", "d_dec_wall", n, d)
    timed("lossless decode, in-process", "l_dec_in", "draco_decoder, reported", "d_dec_in", n, d)
    timed("lossless decode, in-process", "l_dec_in", "DracoPy.decode", "d_dec_py", n, d)
    what = f"swing {bpv:g} b/v decode ({'/'.join(f'{b:,}' for b in sb)} bytes, " \
           f"{'/'.join(f'{x:,}' for x in st)} tri), wall"
    timed(what, "s_dec_wall", "draco_decoder (lossless), wall", "d_dec_wall", s, d)
    timed(f"swing {bpv:g} b/v decode, in-process", "s_dec_in", "draco_decoder (lossless), reported",
          "d_dec_in", s, d)
    timed(f"swing {bpv:g} b/v decode, in-process", "s_dec_in", "DracoPy.decode (lossless)",
          "d_dec_py", s, d)
    simp = f"meshopt_simplify to {m['mo_tris']:,} tri, in-process"
    timed(f"swing {bpv:g} b/v encode, wall", "s_enc_wall", simp, "mo_in", n, n)
    timed(f"swing {bpv:g} b/v encode, in-process", "s_enc_in", simp, "mo_in", n, n)
    return rows


# --- the effort table (--efforts) -------------------------------------------

EFFORTS = ["fast", "default", "max"]
# Issue 45's bars: wall time at most max(factor x Draco's wall, floor).
BARS = {"fast": (2.0, 0.3), "default": (10.0, 0.5)}


def ensure_gltfpack(npm_dir: Path) -> Path:
    """The gltfpack command of the npm package in `npm_dir`, installed
    there (never in the repository) when missing."""
    exe = npm_dir / "node_modules" / ".bin" / "gltfpack"
    if not exe.exists():
        if shutil.which("npm") is None:
            raise Failure("npm not found: gltfpack is installed with npm (Node.js needed)")
        print(f"installing {GLTFPACK} into {npm_dir} ...", file=sys.stderr)
        npm_dir.mkdir(parents=True, exist_ok=True)
        run(["npm", "install", "--prefix", str(npm_dir), "--no-audit", "--no-fund",
             "--no-save", GLTFPACK])
    if not exe.exists():
        raise Failure(f"gltfpack not found in {exe.parent} after npm install")
    return exe


def write_glb(verts, faces, out: Path) -> None:
    """A GLB of one triangle mesh: float32 positions, uint32 indices."""
    import numpy as np
    pos = np.ascontiguousarray(verts, dtype="<f4")
    idx = np.ascontiguousarray(faces, dtype="<u4").reshape(-1)
    pos_bytes, idx_bytes = pos.tobytes(), idx.tobytes()  # both multiples of 4
    doc = {
        "asset": {"version": "2.0", "generator": "swm tools/bench/side_by_side.py"},
        "scene": 0, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
        "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1, "mode": 4}]}],
        "buffers": [{"byteLength": len(pos_bytes) + len(idx_bytes)}],
        "bufferViews": [
            {"buffer": 0, "byteOffset": 0, "byteLength": len(pos_bytes), "target": 34962},
            {"buffer": 0, "byteOffset": len(pos_bytes), "byteLength": len(idx_bytes), "target": 34963},
        ],
        "accessors": [
            {"bufferView": 0, "componentType": 5126, "count": len(pos), "type": "VEC3",
             "min": [float(x) for x in pos.min(axis=0)], "max": [float(x) for x in pos.max(axis=0)]},
            {"bufferView": 1, "componentType": 5125, "count": len(idx), "type": "SCALAR"},
        ],
    }
    js = json.dumps(doc, separators=(",", ":")).encode()
    js += b" " * (-len(js) % 4)
    binary = pos_bytes + idx_bytes
    body = (len(js).to_bytes(4, "little") + b"JSON" + js
            + len(binary).to_bytes(4, "little") + b"BIN\0" + binary)
    out.write_bytes(b"glTF" + (2).to_bytes(4, "little")
                    + (12 + len(body)).to_bytes(4, "little") + body)


def gltfpack_triangles(log: str) -> int | None:
    """The output triangle count in gltfpack's -v log, when it says."""
    m = re.search(r"output: \d+ mesh primitives \((\d+) triangles", log)
    return int(m.group(1)) if m else None


def measure_efforts(mesh: Path, swm: str, venv: Path, gltfpack: Path, reps: int,
                    rates: list[float], efforts: list[str], threads: int,
                    or_smallest: bool) -> list[dict]:
    enc = str(venv / "bin" / "draco_encoder")
    extra = ["--or-smallest"] if or_smallest else []
    swm_env = dict(os.environ, RAYON_NUM_THREADS=str(threads))
    verts, faces = read_mesh(mesh)
    cells = []
    with tempfile.TemporaryDirectory(prefix="swm-side-") as tmp:
        tmp = Path(tmp)
        for_draco = draco_input(mesh, verts, faces, tmp)
        glb = tmp / "input.glb"
        write_glb(verts, faces, glb)
        for bpv in rates:
            print(f"  {mesh.name} at {bpv:g} b/v ...", file=sys.stderr)
            c: dict = {"bpv": bpv, "in_tris": len(faces), "errors": {},
                       "wall": {e: [] for e in efforts}, "in": {e: [] for e in efforts},
                       "bytes": {e: set() for e in efforts}, "tris": {}, "l2": {},
                       "d_wall": [], "d_in": [], "g_wall": [], "g_bytes": set()}
            for rep in range(reps):
                for e in efforts:
                    if e in c["errors"]:
                        continue
                    out = tmp / f"{e}.swm"
                    try:
                        w, text = run([swm, "encode", str(mesh), "-o", str(out), "--bpv", f"{bpv:g}",
                                       "--effort", e, "--json", *extra], swm_env)
                    except Failure as err:
                        # "swm failed (exit 1): swm: error: IN: why" -> "why"
                        c["errors"][e] = str(err).split(f"{mesh}: ", 1)[-1]
                        continue
                    c["wall"][e].append(w)
                    c["in"][e].append(json.loads(text)["encode_seconds"])
                    c["bytes"][e].add(out.stat().st_size)
                    if rep == 0:
                        # Untimed: the decoded mesh and its L2 to the input.
                        _, text = run([swm, "decode", str(out), "-o", str(tmp / f"{e}.ply"), "--json"])
                        c["tris"][e] = json.loads(text)["decoded_triangles"]
                        _, text = run([swm, "distance", str(mesh), str(tmp / f"{e}.ply"), "--json"])
                        c["l2"][e] = json.loads(text)["l2_relative"]
                # Draco, cl 10, qp 11, positions only (as the codec table)
                w, text = run([enc, "-i", str(for_draco), "-o", str(tmp / "d.drc"), "-cl", "10",
                               "-qp", "11", "-qn", "-1", "-qt", "-1", "-qg", "-1"])
                c["d_wall"].append(w)
                c["d_in"].append(ms_reported(text, "encode"))
                c["d_bytes"] = (tmp / "d.drc").stat().st_size
                # gltfpack to about the triangle count of swm's default file
                if "si" not in c:
                    ref = next((e for e in ("default", "fast", "max") if e in c["tris"]), None)
                    c["si"] = None if ref is None else \
                        min(1.0, max(c["tris"][ref] / len(faces), 1e-6))
                if c["si"] is not None:
                    w, text = run([str(gltfpack), "-i", str(glb), "-o", str(tmp / "g.glb"),
                                   "-si", f"{c['si']:.6f}", "-cc", "-v"])
                    c["g_wall"].append(w)
                    c["g_bytes"].add((tmp / "g.glb").stat().st_size)
                    c["g_tris"] = gltfpack_triangles(text)
            cells.append(c)
    return cells


def fmt_t(s: float) -> str:
    if s < 0.1:
        return f"{s * 1000:.1f} ms"
    return f"{s * 1000:.0f} ms" if s < 1 else f"{s:.2f} s"


def fmt_sizes(sizes: set) -> str:
    return "/".join(f"{b:,}" for b in sorted(sizes))


def bar(effort: str, wall: float, draco: float) -> tuple[bool, str]:
    factor, floor = BARS[effort]
    limit = max(factor * draco, floor)
    ok = wall <= limit
    return ok, f"{'ok' if ok else 'OVER'} (<= {fmt_t(limit)})"


def effort_tables(results: list[tuple[str, list[dict]]], efforts: list[str]) -> list[str]:
    med = statistics.median
    head_t = ["mesh", "b/v", "draco_encoder -cl 10, wall (reported)", "gltfpack -si S -cc, wall"]
    head_s = ["mesh", "b/v"]
    for e in efforts:
        head_t += [f"{e}: wall (in-process)", f"{e} / Draco"] + ([f"{e}: bar"] if e in BARS else [])
        head_s += [f"{e}: bytes", f"{e}: L2"]
    head_s += ["gltfpack: S, bytes (triangles)", "Draco cl 10 qp 11 (lossless): bytes"]
    times = ["| " + " | ".join(head_t) + " |", "|" + "---|" * 2 + "---:|" * (len(head_t) - 2)]
    sizes = ["| " + " | ".join(head_s) + " |", "|" + "---|" * 2 + "---:|" * (len(head_s) - 2)]
    held = {e: [0, 0] for e in BARS if e in efforts}
    l2s = {e: [] for e in efforts}
    failed = []
    for name, cells in results:
        for c in cells:
            d = med(c["d_wall"])
            g = fmt_t(med(c["g_wall"])) if c["g_wall"] else "-"
            rt = [name, f"{c['bpv']:g}", f"{fmt_t(d)} ({1000 * med(c['d_in']):.0f} ms)", g]
            rs = [name, f"{c['bpv']:g}"]
            for e in efforts:
                if e in c["errors"] and not c["wall"][e]:
                    err = c["errors"][e].replace("|", "\\|")
                    rt += [f"failed: {err}", "-"] + (["-"] if e in BARS else [])
                    failed.append(f"{name} at {c['bpv']:g} b/v, `{e}`")
                    rs += ["-", "-"]
                    continue
                w = med(c["wall"][e])
                rt += [f"{fmt_t(w)} ({fmt_t(med(c['in'][e]))})", f"{w / d:.1f}x"]
                if e in BARS:
                    ok, txt = bar(e, w, d)
                    held[e][0] += ok
                    held[e][1] += 1
                    rt.append(txt)
                rs += [f"{fmt_sizes(c['bytes'][e])} ({c['tris'][e]:,} tri)", f"{1e4 * c['l2'][e]:.3f}"]
            if c["g_wall"]:
                gt = f"{c['g_tris']:,}" if c.get("g_tris") is not None else "?"
                rs.append(f"{c['si']:.4f}: {fmt_sizes(c['g_bytes'])} ({gt} tri)")
            else:
                rs.append("-")
            rs.append(f"{c['d_bytes']:,}")
            times.append("| " + " | ".join(rt) + " |")
            sizes.append("| " + " | ".join(rs) + " |")
            if all(e in c["l2"] for e in efforts):
                for e in efforts:
                    l2s[e].append(c["l2"][e])
    lines = times + [""] + sizes + [""]
    for e, (ok, n) in held.items():
        factor, floor = BARS[e]
        lines.append(f"- `{e}`: wall within max({factor:g} x Draco's wall, {floor:g} s) "
                     f"in {ok} of {n} cells")
    if failed:
        lines.append(f"- no file (`swm encode` failed) in {len(failed)} cells: {'; '.join(failed)}")
    n = len(l2s[efforts[0]])
    if n:
        geo = {e: statistics.geometric_mean(v) for e, v in l2s.items()}
        txt = ", ".join(f"`{e}` {1e4 * g:.3f}" for e, g in geo.items())
        lines.append(f"- geometric-mean L2 (x 1e-4 of the diagonal) over the {n} cells where "
                     f"every level wrote a file: {txt}")
        if "max" in geo:
            lines.append("- geometric-mean L2 over `max`'s: " + ", ".join(
                f"`{e}` {geo[e] / geo['max']:.3f}" for e in efforts if e != "max"))
    return lines


def run_efforts(args, meshes: list[Path], swm: str, venv: Path) -> int:
    try:
        rates = [float(r) for r in args.rates.split(",") if r.strip()]
    except ValueError:
        raise Failure(f"--rates: not a list of numbers: {args.rates}") from None
    if not rates or any(not r > 0 for r in rates):
        raise Failure(f"--rates: positive bits per vertex, comma-separated: {args.rates}")
    efforts = EFFORTS if args.max else EFFORTS[:2]
    gltfpack = ensure_gltfpack(Path(args.npm).resolve())
    load0 = os.getloadavg()
    version = run([swm, "--version"])[1].strip()
    gv = gltfpack_version(gltfpack)
    results = []
    for mesh in meshes:
        print(f"measuring {mesh.name} ...", file=sys.stderr)
        cells = measure_efforts(mesh, swm, venv, gltfpack, args.reps, rates, efforts, args.threads,
                                args.or_smallest)
        results.append((f"{mesh.name} ({cells[0]['in_tris']:,} tri)", cells))
    load1 = os.getloadavg()
    lines = [
        f"{version} (RAYON_NUM_THREADS={args.threads}), Draco 1.5.7 (DracoPy 2.2.0 wheel), "
        f"{gv} (npm {GLTFPACK}, WebAssembly under Node.js {node_version()}); "
        f"{args.reps} repetitions, medians; L2 x 1e-4 of the input's bounding-box diagonal "
        f"(`swm distance`); {time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}",
        "",
        "Command: `" + " ".join(["python3", "tools/bench/side_by_side.py", *sys.argv[1:]]) + "`",
        "",
    ]
    lines += effort_tables(results, efforts)
    lines += ["", f"load average (1 min) {load0[0]:.2f} at the start, {load1[0]:.2f} at the end"]
    print("\n".join(lines))
    return 0


def gltfpack_version(gltfpack: Path) -> str:
    p = subprocess.run([str(gltfpack), "-h"], capture_output=True)
    for line in (p.stdout + p.stderr).decode(errors="replace").splitlines():
        if line.startswith("gltfpack"):
            return line.strip()
    return "gltfpack"


def node_version() -> str:
    try:
        return subprocess.run(["node", "--version"], capture_output=True).stdout.decode().strip()
    except OSError:
        return "?"


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("swm_bin", help="a release swm binary (target/release/swm)")
    p.add_argument("meshes", nargs="*", help="input meshes (default: bunny and horse from ../shared/corpus)")
    p.add_argument("--venv", default=str(DEFAULT_VENV), help="virtual environment for the peers")
    p.add_argument("--reps", type=int, default=5, help="repetitions per measurement (median)")
    p.add_argument("--bpv", type=float, default=1.0, help="SwingWrapper rate, bits per input vertex")
    p.add_argument("--efforts", action="store_true",
                   help="the effort table: swm encode --effort fast/default (and max) against "
                        "draco_encoder and gltfpack, with L2 (default meshes: all of ../shared/corpus)")
    p.add_argument("--rates", default=DEFAULT_RATES,
                   help=f"with --efforts: bits per input vertex, comma-separated (default {DEFAULT_RATES})")
    p.add_argument("--max", action="store_true",
                   help="with --efforts: also time --effort max (minutes per cell on large meshes)")
    p.add_argument("--threads", type=int, default=1,
                   help="with --efforts: RAYON_NUM_THREADS for swm encode (default 1)")
    p.add_argument("--or-smallest", action="store_true",
                   help="with --efforts: pass --or-smallest to swm encode (a rate below the "
                        "smallest file then times that file instead of failing)")
    p.add_argument("--npm", default=str(DEFAULT_NPM),
                   help="with --efforts: folder for the gltfpack npm package")
    args = p.parse_intermixed_args()
    if not args.efforts and (args.max or args.or_smallest or args.rates != DEFAULT_RATES):
        raise Failure("--rates, --max and --or-smallest go with --efforts")
    if args.threads < 1:
        raise Failure("--threads: at least 1")

    if args.meshes:
        meshes = [Path(m) for m in args.meshes]
        missing = [str(m) for m in meshes if not m.is_file()]
        if missing:
            raise Failure(f"mesh not found: {', '.join(missing)}")
    else:
        if not CORPUS.is_dir():
            print("skipped: ../shared/corpus not found")
            return 0
        if args.efforts:
            meshes = sorted((m for m in CORPUS.iterdir() if m.suffix.lower() in (".obj", ".ply")),
                            key=lambda m: (m.stat().st_size, m.name))
        else:
            meshes = [CORPUS / m for m in DEFAULT_MESHES]
    swm = shutil.which(args.swm_bin) or args.swm_bin
    if not (Path(swm).is_file() and os.access(swm, os.X_OK)):
        raise Failure(f"swm binary not found: {args.swm_bin} (build it: cargo build --release -p swm-cli)")
    venv = Path(args.venv).resolve()

    if os.environ.get(REEXEC_MARK) != str(venv):
        ensure_venv(venv)
        os.environ[REEXEC_MARK] = str(venv)
        py = str(venv_python(venv))
        os.execv(py, [py, str(Path(__file__).resolve()), *sys.argv[1:]])

    for tool in ("draco_encoder", "draco_decoder"):
        if not os.access(venv / "bin" / tool, os.X_OK):
            raise Failure(f"{tool} not found in {venv}/bin (the DracoPy wheel installs it)")
    try:
        import DracoPy  # noqa: F401
        import meshoptimizer  # noqa: F401
    except ImportError as e:
        raise Failure(f"{e} in {venv} (delete it to reinstall, or pip install {' '.join(PEERS)})") from None

    if args.efforts:
        return run_efforts(args, meshes, swm, venv)

    load0 = os.getloadavg()
    version = run([swm, "--version"])[1].strip()
    lines = [
        f"{version} (RAYON_NUM_THREADS=1), Draco 1.5.7 (DracoPy 2.2.0 wheel), "
        f"meshoptimizer Python package {meshoptimizer_version()}; {args.reps} repetitions, medians "
        f"(encode throughput counts input triangles, decode throughput output triangles); "
        f"{time.strftime('%Y-%m-%d %H:%M UTC', time.gmtime())}",
        "",
        "| mesh | swm step | swm | peer step | peer | swm / peer |",
        "|---|---|---:|---|---:|---:|",
    ]
    for mesh in meshes:
        print(f"measuring {mesh.name} ...", file=sys.stderr)
        m = measure(mesh, swm, venv, args.reps, args.bpv)
        lines += table(f"{mesh.name} ({m['in_tris']:,} tri)", m, args.bpv)
    load1 = os.getloadavg()
    lines += ["", f"load average (1 min) {load0[0]:.2f} at the start, {load1[0]:.2f} at the end"]
    print("\n".join(lines))
    return 0


def meshoptimizer_version() -> str:
    from importlib.metadata import version
    return version("meshoptimizer")


if __name__ == "__main__":
    try:
        sys.exit(main())
    except Failure as e:
        print(f"side_by_side: {e}", file=sys.stderr)
        sys.exit(1)
    except KeyboardInterrupt:
        sys.exit(130)

"""swm against Google Draco and meshoptimizer's simplifier, in one run.

    python3 tools/bench/side_by_side.py SWM_BIN [MESH ...] [--venv DIR] [--reps N] [--bpv R]

SWM_BIN is a release `swm` (`cargo build --release -p swm-cli`, then
`target/release/swm`); this script builds nothing. MESH defaults to
`stanford-bunny.obj` and `horse.ply` in `../shared/corpus` (relative to the
repository root); when that folder is absent and no mesh is given, it
prints "skipped: ../shared/corpus not found" and exits 0.

The peers live in a virtual environment, never in the repository: DIR
(default /tmp/swm-bench-venv) is created when missing and given
`DracoPy` and `meshoptimizer` (versions pinned below), then the script
runs itself again with that environment's Python.

- Draco: the `draco_encoder` and `draco_decoder` executables that the
  DracoPy wheel installs into DIR/bin (Draco 1.5.7), and DracoPy's
  `decode` (the same library) for an in-process decode time.
- meshoptimizer's simplifier: `meshopt_simplify` through the
  `meshoptimizer` package (the Python wrapper from meshoptimizer's own
  repository, which compiles the library's C++ sources when pip installs
  it, so DIR needs a C++ compiler once), called once per repetition on
  arrays already in memory: the simplifier alone, no file I/O.

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
    return t if tris is None else f"{t} ({tris / s / 1e6:.2f} M tri/s)"


def table(name: str, m: dict, bpv: float) -> list[str]:
    rows = []

    def row(what: str, swm_txt: str, peer: str, peer_txt: str, ratio: float) -> None:
        rows.append(f"| {name} | {what} | {swm_txt} | {peer} | {peer_txt} | {ratio:.2f} |")

    def timed(what: str, a: str, peer: str, b: str, ta: int | None = None,
              tb: int | None = None) -> None:
        row(what, fmt_s(m[a], ta), peer, fmt_s(m[b], tb), m[a] / m[b])

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


def main() -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("swm_bin", help="a release swm binary (target/release/swm)")
    p.add_argument("meshes", nargs="*", help="input meshes (default: bunny and horse from ../shared/corpus)")
    p.add_argument("--venv", default=str(DEFAULT_VENV), help="virtual environment for the peers")
    p.add_argument("--reps", type=int, default=5, help="repetitions per measurement (median)")
    p.add_argument("--bpv", type=float, default=1.0, help="SwingWrapper rate, bits per input vertex")
    args = p.parse_args()

    if args.meshes:
        meshes = [Path(m) for m in args.meshes]
        missing = [str(m) for m in meshes if not m.is_file()]
        if missing:
            raise Failure(f"mesh not found: {', '.join(missing)}")
    else:
        if not CORPUS.is_dir():
            print("skipped: ../shared/corpus not found")
            return 0
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

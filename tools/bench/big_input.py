"""A ten-million-triangle input for `swm encode` (issue 22, item 3).

Generates the input in a temporary directory, never in the repository:
bunny-1m (../shared/corpus/bunny-1m.ply, 1,111,216 triangles) with every
triangle cut into nine (each edge in thirds, one point at the centre),
10,000,944 triangles and 5,002,920 vertices on exactly the same surface,
so the encoder's error against it means what it means on bunny-1m. Then
times one `swm encode` of it with `/usr/bin/time -v` (wall and user
time, peak resident memory) and prints the encoder's `--json` summary.

    python3 tools/bench/big_input.py target/release/swm [--bpv 1 | --size N]
        [--keep DIR] [-- extra encode arguments]

Needs numpy (`pip install numpy` in a virtual environment). The
subdivided mesh shares each edge's two new points between the edge's
two triangles (numbered from the edge's lower vertex), so it stays the
closed-with-holes manifold bunny-1m is, and every new triangle keeps its
parent's orientation.
"""

import argparse
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

CORPUS = Path(__file__).resolve().parents[2].parent / "shared" / "corpus"


def read_ply(path):
    """bunny-1m's binary PLY: double x, y, z; uchar count, int indices."""
    data = path.read_bytes()
    head_end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:head_end].decode("ascii").split("\n")
    nv = nf = None
    for line in header:
        parts = line.split()
        if parts[:2] == ["element", "vertex"]:
            nv = int(parts[2])
        elif parts[:2] == ["element", "face"]:
            nf = int(parts[2])
    if "property double x" not in header or nv is None or nf is None:
        sys.exit(f"{path}: not the binary PLY layout this script reads")
    v = np.frombuffer(data, dtype="<f8", count=nv * 3, offset=head_end).reshape(-1, 3)
    rec = np.dtype([("n", "u1"), ("i", "<i4", 3)])
    f = np.frombuffer(data, dtype=rec, count=nf, offset=head_end + nv * 24)
    if not (f["n"] == 3).all():
        sys.exit(f"{path}: not a triangle mesh")
    return v, f["i"].astype(np.int64)


def split_in_nine(v, f):
    """Each triangle (a, b, c) into nine over the barycentric grid of
    step 1/3: grid point (i, j) is a + i/3 (b − a) + j/3 (c − a)."""
    nv, nf = len(v), len(f)
    a, b, c = f[:, 0], f[:, 1], f[:, 2]
    # Directed edges a→b, b→c, c→a; one record per undirected edge.
    u = np.concatenate([a, b, c])
    w = np.concatenate([b, c, a])
    lo, hi = np.minimum(u, w), np.maximum(u, w)
    keys, edge = np.unique(lo * nv + hi, return_inverse=True)
    ne = len(keys)
    # Point at 1/3 from u along u→w: the edge's first point if u is its
    # lower end, else its second.
    first = nv + 2 * edge + np.where(u < w, 0, 1)
    second = nv + 2 * edge + np.where(u < w, 1, 0)
    t1 = first.reshape(3, nf)
    t2 = second.reshape(3, nf)
    centre = nv + 2 * ne + np.arange(nf)
    k_lo, k_hi = keys // nv, keys % nv
    e1 = v[k_lo] + (v[k_hi] - v[k_lo]) / 3.0
    e2 = v[k_lo] + 2.0 * (v[k_hi] - v[k_lo]) / 3.0
    edge_points = np.empty((2 * ne, 3))
    edge_points[0::2], edge_points[1::2] = e1, e2
    centres = (v[a] + v[b] + v[c]) / 3.0
    positions = np.concatenate([v, edge_points, centres])
    g = {
        (0, 0): a, (3, 0): b, (0, 3): c,
        (1, 0): t1[0], (2, 0): t2[0],   # along a→b
        (2, 1): t1[1], (1, 2): t2[1],   # along b→c
        (0, 2): t1[2], (0, 1): t2[2],   # along c→a
        (1, 1): centre,
    }
    tris = []
    for i in range(3):
        for j in range(3 - i):
            tris.append((g[(i, j)], g[(i + 1, j)], g[(i, j + 1)]))
            if i + j <= 1:
                tris.append((g[(i + 1, j)], g[(i + 1, j + 1)], g[(i, j + 1)]))
    faces = np.stack([np.stack(t, axis=1) for t in tris], axis=1).reshape(-1, 3)
    return positions, faces


def write_ply(path, v, f):
    rec = np.zeros(len(f), dtype=np.dtype([("n", "u1"), ("i", "<i4", 3)]))
    rec["n"] = 3
    rec["i"] = f
    with open(path, "wb") as out:
        out.write(
            (
                "ply\nformat binary_little_endian 1.0\n"
                f"element vertex {len(v)}\nproperty double x\nproperty double y\n"
                f"property double z\nelement face {len(f)}\n"
                "property list uchar int vertex_indices\nend_header\n"
            ).encode("ascii")
        )
        out.write(np.ascontiguousarray(v, dtype="<f8").tobytes())
        out.write(rec.tobytes())


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("swm", help="the swm binary to time")
    rate = ap.add_mutually_exclusive_group()
    rate.add_argument("--bpv", type=float, default=None)
    rate.add_argument("--size", type=int, default=None)
    ap.add_argument("--keep", help="write the input here and keep it")
    args, extra = ap.parse_known_args()
    args.extra = [a for a in extra if a != "--"]
    src = CORPUS / "bunny-1m.ply"
    if not src.exists():
        sys.exit(f"skipped: {CORPUS} not found")
    work = Path(args.keep) if args.keep else Path(tempfile.mkdtemp(prefix="swm-big-"))
    work.mkdir(parents=True, exist_ok=True)
    big = work / "bunny-10m.ply"
    if not big.exists():
        t = time.time()
        v, f = read_ply(src)
        pv, pf = split_in_nine(v, f)
        write_ply(big, pv, pf)
        print(f"generated {big}: {len(pv):,} vertices, {len(pf):,} triangles "
              f"in {time.time() - t:.1f} s", flush=True)
    out = work / "bunny-10m.swm"
    rate_args = ["--size", str(args.size)] if args.size else ["--bpv", str(args.bpv or 1.0)]
    cmd = ["/usr/bin/time", "-v", args.swm, "encode", str(big), "--mode", "swing",
           *rate_args, "-o", str(out), "--force", "--json", *args.extra]
    print("$", " ".join(cmd), flush=True)
    run = subprocess.run(cmd, capture_output=True, text=True)
    stats = {}
    for line in run.stderr.splitlines():
        line = line.strip()
        for key in ("Elapsed (wall clock) time", "User time (seconds)",
                    "Maximum resident set size (kbytes)", "Exit status"):
            if line.startswith(key):
                stats[key] = line.split(":", 1)[1].strip() if key != "Elapsed (wall clock) time" \
                    else line.rsplit(": ", 1)[1]
    print(json.dumps(stats, indent=1))
    if run.returncode != 0:
        print(run.stderr[-2000:], file=sys.stderr)
        sys.exit(run.returncode)
    summary = json.loads(run.stdout)
    keep = {k: summary.get(k) for k in ("bytes", "triangles", "vertices", "edge_length",
                                        "angle_bits", "encode_seconds")}
    rc = summary.get("rate_control") or {}
    keep["runs"] = len(rc.get("attempts", []))
    keep["failed_runs"] = sum(1 for a in rc.get("attempts", []) if "failed" in a)
    keep["peak_memory_bytes (encoder's account)"] = rc.get("peak_memory_bytes")
    print(json.dumps(keep, indent=1))
    if not args.keep:
        for p in (big, out):
            if p.exists():
                os.remove(p)
        os.rmdir(work)


if __name__ == "__main__":
    main()

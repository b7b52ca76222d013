"""Cost of encoding through Python against the Rust API, on horse.ply.

    python python/benches/encode_horse.py [SWM_BIN] [--rounds N] [--bpv R]

Alternates, ROUNDS times: `swm encode horse.ply --bpv R --json` (its
`encode_seconds` times the library call `swm::encode` alone, in the
release CLI) and `swm.encode(vertices, faces, bpv=R)` from Python
(timed around the Python call: argument checks, the copy into the
library's mesh, the encode, the bytes object). Prints both medians and
their ratio, and checks that both give the same bytes. Alternating keeps
the two sides under the same load on a shared machine; on a busy one,
the CPU times (all threads; the CLI's include reading the mesh and
writing the file, a few tens of milliseconds) are steadier than wall
times.
"""

from __future__ import annotations

import argparse
import json
import resource
import statistics
import subprocess
import tempfile
import time
from pathlib import Path

import swm

ROOT = Path(__file__).resolve().parents[2]


def main() -> None:
    p = argparse.ArgumentParser()
    p.add_argument("swm_bin", nargs="?", default=str(ROOT / "target" / "release" / "swm"))
    p.add_argument("--rounds", type=int, default=7)
    p.add_argument("--bpv", type=float, default=1.0)
    p.add_argument("--mesh", default=str(ROOT.parent / "shared" / "corpus" / "horse.ply"))
    args = p.parse_args()
    vertices, faces = swm.read(args.mesh)
    rust, python, rust_cpu, python_cpu = [], [], [], []

    def children_cpu() -> float:
        r = resource.getrusage(resource.RUSAGE_CHILDREN)
        return r.ru_utime + r.ru_stime

    with tempfile.TemporaryDirectory() as tmp:
        out = Path(tmp) / "horse.swm"
        for _ in range(args.rounds):
            cpu = children_cpu()
            run = subprocess.run(
                [args.swm_bin, "encode", args.mesh, "-o", str(out), "--bpv", str(args.bpv), "--json"],
                capture_output=True, check=True,
            )
            rust_cpu.append(children_cpu() - cpu)
            rust.append(json.loads(run.stdout)["encode_seconds"])
            cpu = time.process_time()
            start = time.perf_counter()
            data = swm.encode(vertices, faces, bpv=args.bpv)
            python.append(time.perf_counter() - start)
            python_cpu.append(time.process_time() - cpu)
            assert data == out.read_bytes(), "Python and the CLI disagree"
    r, py = statistics.median(rust), statistics.median(python)
    print(f"{Path(args.mesh).name}, {len(vertices)} vertices, --bpv {args.bpv}, {args.rounds} rounds")
    print(f"  Rust API (swm encode --json, encode_seconds): median {r:.3f} s  {sorted(round(x, 3) for x in rust)}")
    print(f"  Python swm.encode:                            median {py:.3f} s  {sorted(round(x, 3) for x in python)}")
    print(f"  Python / Rust: {py / r:.3f} (wall)")
    rc, pc = statistics.median(rust_cpu), statistics.median(python_cpu)
    print(f"  CPU time: Rust CLI run median {rc:.3f} s, Python encode median {pc:.3f} s, "
          f"Python / Rust {pc / rc:.3f}")


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""Checks `swm distance` against Metro as MeshLab implements it.

For fandisk, stanford-bunny and horse from ../shared/corpus, builds
decimated versions (MeshLab's quadric edge collapse to 1/4 and 1/16 of the
faces) and noise-perturbed versions (MeshLab's random vertex displacement
of 0.1% and 0.5% of the diagonal), then measures each against its original
both with MeshLab's Hausdorff-distance filter (face sampling only, N
samples in each direction) and with `swm distance --samples N` in the
same area-uniform sampling. Relative values divide by the original's
bounding-box diagonal on both sides. Prints a Markdown table and exits 1
if any relative L2 differs by more than 3% or any Hausdorff by more
than 6%.

Usage (pymeshlab from PyPI; a release build of swm):
    python3 -m venv /tmp/pml && /tmp/pml/bin/pip install pymeshlab
    cargo build --release -p swm-cli
    /tmp/pml/bin/python tools/metro/compare.py target/release/swm [N]
"""

import json
import os
import subprocess
import sys
import tempfile

import pymeshlab as ml

HERE = os.path.dirname(os.path.abspath(__file__))
CORPUS = os.path.normpath(os.path.join(HERE, "..", "..", "..", "shared", "corpus"))
MESHES = ["fandisk.obj", "stanford-bunny.obj", "horse.ply"]
L2_TOLERANCE = 0.03
HAUSDORFF_TOLERANCE = 0.06


def variants(path, out_dir):
    """Yields (label, file) for each derived mesh of `path`."""
    stem = os.path.splitext(os.path.basename(path))[0]
    for fraction in (4, 16):
        ms = ml.MeshSet()
        ms.load_new_mesh(path)
        ms.meshing_merge_close_vertices()
        faces = ms.current_mesh().face_number()
        ms.meshing_decimation_quadric_edge_collapse(
            targetfacenum=faces // fraction, optimalplacement=True, preservenormal=True
        )
        f = os.path.join(out_dir, f"{stem}-dec{fraction}.ply")
        ms.save_current_mesh(f, save_vertex_normal=False, save_vertex_color=False)
        yield f"decimated 1/{fraction}", f
    for percent in (0.1, 0.5):
        ms = ml.MeshSet()
        ms.load_new_mesh(path)
        ms.apply_coord_random_displacement(
            displacement=ml.PercentageValue(percent), randomseed=1, updatenormals=False
        )
        f = os.path.join(out_dir, f"{stem}-noise{percent}.ply")
        ms.save_current_mesh(f, save_vertex_normal=False, save_vertex_color=False)
        yield f"noise {percent}%", f


def meshlab(reference, other, samples):
    """(l2, hausdorff, diagonal) by MeshLab's filter, both directions."""
    ms = ml.MeshSet()
    ms.load_new_mesh(reference)
    ms.load_new_mesh(other)
    big = ml.PercentageValue(100)
    run = lambda a, b: ms.get_hausdorff_distance(
        sampledmesh=a, targetmesh=b, samplevert=False, sampleedge=False,
        samplefauxedge=False, sampleface=True, samplenum=samples, maxdist=big,
    )
    forward, backward = run(0, 1), run(1, 0)
    diagonal = forward["diag_mesh_0"]
    return (
        max(forward["RMS"], backward["RMS"]),
        max(forward["max"], backward["max"]),
        diagonal,
    )


def swm(binary, reference, other, samples):
    out = subprocess.run(
        [binary, "distance", reference, other, "--samples", str(samples),
         "--sampling", "faces", "--json"],
        check=True, capture_output=True, text=True,
    )
    d = json.loads(out.stdout)
    return d["l2"], d["hausdorff"]


def main():
    binary = sys.argv[1]
    samples = int(sys.argv[2]) if len(sys.argv) > 2 else 1_000_000
    rows, worst = [], (0.0, 0.0)
    with tempfile.TemporaryDirectory() as tmp:
        for name in MESHES:
            path = os.path.join(CORPUS, name)
            for label, other in variants(path, tmp):
                l2_m, h_m, diag = meshlab(path, other, samples)
                l2_s, h_s = swm(binary, path, other, samples)
                dl2 = abs(l2_s - l2_m) / l2_m
                dh = abs(h_s - h_m) / h_m
                worst = (max(worst[0], dl2), max(worst[1], dh))
                rows.append((name, label, 1e4 * l2_m / diag, 1e4 * l2_s / diag, dl2,
                             1e4 * h_m / diag, 1e4 * h_s / diag, dh))
    print(f"{samples} area-uniform face samples per direction; units 1e-4 of the"
          " original's bounding-box diagonal\n")
    print("| mesh | variant | L2 MeshLab | L2 swm | diff | Hausdorff MeshLab | Hausdorff swm | diff |")
    print("|---|---|---:|---:|---:|---:|---:|---:|")
    for r in rows:
        print(f"| {r[0]} | {r[1]} | {r[2]:.3f} | {r[3]:.3f} | {100 * r[4]:.2f}% "
              f"| {r[5]:.2f} | {r[6]:.2f} | {100 * r[7]:.2f}% |")
    print(f"\nlargest difference: L2 {100 * worst[0]:.2f}% (limit 3%), "
          f"Hausdorff {100 * worst[1]:.2f}% (limit 6%)")
    sys.exit(0 if worst[0] <= L2_TOLERANCE and worst[1] <= HAUSDORFF_TOLERANCE else 1)


if __name__ == "__main__":
    main()

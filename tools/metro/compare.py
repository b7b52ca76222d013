#!/usr/bin/env python3
"""Checks `swm distance` against Metro as MeshLab implements it.

For fandisk, stanford-bunny and horse from ../shared/corpus, builds
decimated versions (MeshLab's quadric edge collapse to 1/4 and 1/16 of the
faces) and noise-perturbed versions (MeshLab's random vertex displacement
of 0.1% and 0.5% of the diagonal), then measures each against its original
in both directions with MeshLab's Hausdorff-distance filter and with
`swm distance`, N samples per direction:

* L2 (the larger one-sided RMS) from area-uniform face samples only:
  MeshLab `sampleface` (Monte Carlo), `swm distance --sampling faces`
  (stratified). This is the thesis's L2, an area integral; vertex and
  edge samples would weight it by a convention that differs between the
  tools (MeshLab puts N samples on the edges, Metro and swm
  sqrt(N / area) per unit length).
* Hausdorff (the larger one-sided maximum) from vertex, edge and face
  samples: MeshLab `samplevert`, `sampleedge` and `sampleface`, `swm
  distance --sampling metro`. Both take every vertex and N face samples.
  The farthest point of a decimated or perturbed mesh is usually a
  vertex, which area sampling alone hits with probability zero, so
  face-only maxima are noisy estimates (tens of percent apart between
  runs of the same tool).

MeshLab samples every vertex of the vertex list, swm only the vertices
that faces use, so unreferenced vertices are removed in MeshLab first
(the Stanford bunny has 1,113). Relative values divide by the original's
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
    """(l2, hausdorff, diagonal) by MeshLab's filter, both directions: L2
    from face samples, Hausdorff from vertex, edge and face samples."""
    ms = ml.MeshSet()
    for path in (reference, other):
        ms.load_new_mesh(path)
        ms.meshing_remove_unreferenced_vertices()
    run = lambda a, b, every: ms.get_hausdorff_distance(
        sampledmesh=a, targetmesh=b, samplevert=every, sampleedge=every,
        samplefauxedge=False, sampleface=True, samplenum=samples,
        maxdist=ml.PercentageValue(100),
    )
    faces = run(0, 1, False), run(1, 0, False)
    every = run(0, 1, True), run(1, 0, True)
    return (
        max(s["RMS"] for s in faces),
        max(s["max"] for s in every),
        faces[0]["diag_mesh_0"],
    )


def swm(binary, reference, other, samples):
    """(l2, hausdorff) by `swm distance`, sampled as `meshlab` does."""
    def run(sampling):
        out = subprocess.run(
            [binary, "distance", reference, other, "--samples", str(samples),
             "--sampling", sampling, "--json"],
            check=True, capture_output=True, text=True,
        )
        return json.loads(out.stdout)
    return run("faces")["l2"], run("metro")["hausdorff"]


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
    print(f"N = {samples}: L2 from N face samples per direction, Hausdorff from"
          " every vertex, edge samples and N face samples per direction; units 1e-4"
          " of the original's bounding-box diagonal\n")
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

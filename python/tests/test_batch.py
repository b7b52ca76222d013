"""`python -m swm.batch` on Dask distributed: a run over the shared and the
generated corpus on a local two-worker cluster with a worker killed
mid-run, a rerun that encodes only what is missing or damaged, a run on an
existing cluster started the way README describes for several machines,
and the pieces (manifests, atomic writes, the worker task) on their own."""

from __future__ import annotations

import csv
import dataclasses
import os
import signal
import stat
import subprocess
import sys
import time
import warnings
from pathlib import Path
from typing import Dict, List, Optional

import numpy as np
import pytest

import swm
from swm import batch
from conftest import ROOT, mesh_files
from scenes import scene_glb, scene_gltf
from test_attributes import tube_obj

pytest.importorskip("distributed", reason="Dask distributed not installed (pip install 'dask[distributed]')")
psutil = pytest.importorskip("psutil", reason="psutil not installed (it comes with dask[distributed])")

BPV = "1"  # a low rate: the cheapest retiling.
SAMPLES = "2000"
# Skipped from the shared corpus: a million vertices take minutes to retile.
TOO_SLOW = {"bunny-1m.ply"}


def read_summary(path: Path) -> Dict[str, Dict[str, str]]:
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    assert rows and tuple(rows[0].keys()) == batch.COLUMNS
    return {Path(r["input"]).name: r for r in rows}


def swm_files(out: Path) -> List[Path]:
    return sorted(out.rglob("*.swm"))


def leftovers(out: Path) -> List[Path]:
    return sorted(p for p in out.rglob("*") if p.name.endswith(".tmp"))


def fits(path: Path) -> bool:
    """Whether the simplified method has a file of the test's rate: a mesh
    whose smallest file is larger (beetle: 274 bytes where 1 b/v gives
    144) is refused with a SizeError by design, which test_binding
    checks; the batch's kill-and-rerun checks want files."""
    try:
        swm.encode(*swm.read(path), mode="lossless", bpv=float(BPV))
        return True
    except swm.SizeError:
        return False


@pytest.fixture(scope="module")
def library(tmp_path_factory, generated_corpus: Path) -> Dict[str, object]:
    """A manifest over both corpora (the shared one when present) and one
    malformed file, and where the inputs come from."""
    root = tmp_path_factory.mktemp("library")
    shared = os.environ.get("SWM_SHARED_CORPUS") or str(ROOT.parent / "shared" / "corpus")
    inputs = list(mesh_files(generated_corpus))
    if Path(shared, "README.md").is_file():
        inputs += [p for p in mesh_files(Path(shared)) if p.name not in TOO_SLOW and fits(p)]
    else:
        warnings.warn("skipped: ../shared/corpus not found; the batch runs over the generated corpus only")
    bad = root / "bad" / "bad.obj"
    bad.parent.mkdir()
    bad.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n")
    manifest = root / "manifest.txt"
    manifest.write_text(
        "# the corpora and one broken file\n" + "".join(f"{p}\n" for p in inputs) + f"\n{bad}\n{inputs[0]}\n"
    )
    return {"manifest": manifest, "inputs": inputs, "bad": bad, "root": root}


def batch_command(manifest: Path, out: Path, *extra: str) -> List[str]:
    return [sys.executable, "-m", "swm.batch", str(manifest), "--out", str(out), "--bpv", BPV,
            "--samples", SAMPLES, *extra]


def worker_processes(driver: int) -> List["psutil.Process"]:
    """The Dask worker processes a local cluster started under `driver`."""
    found = []
    for p in psutil.Process(driver).children(recursive=True):
        try:
            cmd = " ".join(p.cmdline())
        except psutil.NoSuchProcess:
            continue
        if "spawn_main" in cmd and "resource_tracker" not in cmd:
            found.append(p)
    return found


def check_outputs(out: Path, names: List[str]) -> Dict[str, bytes]:
    """Every expected output exists and decodes; nothing half-written.
    Returns the files' bytes by name."""
    files = {p.name: p.read_bytes() for p in swm_files(out)}
    assert sorted(files) == sorted(names)
    for name, data in files.items():
        v, f = swm.decode(data)
        assert len(f) > 0, name
    assert leftovers(out) == []
    return files


def output_path(out: Path, name: str) -> Path:
    (path,) = [p for p in swm_files(out) if p.name == name]
    return path


def test_batch_with_a_worker_killed_then_a_rerun(library, tmp_path):
    manifest, inputs = library["manifest"], library["inputs"]
    out = tmp_path / "out"
    # Outputs keep each input's path below the folder common to all of
    # them; the checks find them by name.
    names = [Path(p).with_suffix(".swm").name for p in inputs]

    # Run 1: kill one of the two workers once the first file is done.
    proc = subprocess.Popen(batch_command(manifest, out, "--workers", "2"), stderr=subprocess.PIPE,
                            text=True, start_new_session=True)
    lines: List[str] = []
    killed: Optional[int] = None
    deadline = time.monotonic() + 600
    assert proc.stderr is not None
    for line in proc.stderr:
        lines.append(line)
        if killed is None and line.startswith("["):
            workers = worker_processes(proc.pid)
            assert len(workers) == 2, workers
            killed = workers[0].pid
            os.kill(killed, signal.SIGKILL)
        assert time.monotonic() < deadline, "batch run too slow"
    proc.wait(timeout=60)
    log = "".join(lines)
    assert killed is not None, log
    # The nanny saw its worker die and started another while the run went on.
    assert "Restarting worker" in log, log
    # Exit 1: the broken file failed; every other input has its file.
    assert proc.returncode == 1, log
    rows = read_summary(out / "summary.csv")
    assert len(rows) == len(inputs) + 1, log
    assert rows["bad.obj"]["status"] == "failed"
    assert rows["bad.obj"]["error"].startswith("FormatError: malformed OBJ file at line 4: vertex index"), rows["bad.obj"]
    for name, row in rows.items():
        if name == "bad.obj":
            continue
        # A task whose worker died after its rename finds its file there
        # when it is run again: skipped, not lost.
        assert row["status"] in ("encoded", "skipped"), row
        assert row["error"] == "" and int(row["bytes"]) > 0
        assert float(row["bits_per_vertex"]) == pytest.approx(8 * int(row["bytes"]) / int(row["vertices"]))
        # Relative to the bounding-box diagonal; suzanne at 1 bit per
        # vertex is the coarsest (about 0.12).
        assert 0 < float(row["l2_estimate"]) < 0.2, row
        # What made each file (the automatic mode's choice), also for a
        # file found there: a simplified file is not called lossless.
        assert row["method"] in ("swing", "simplified", "displaced"), row
    assert sum(r["status"] == "encoded" for r in rows.values()) >= len(inputs) - 2
    files = check_outputs(out, names)
    # The batch's files are those swm.encode makes (small inputs checked).
    for p in inputs:
        if p.name in ("torus.obj", "cube.obj", "icosphere.obj"):
            assert files[p.with_suffix(".swm").name] == swm.encode(*swm.read(p), bpv=float(BPV))
    pa = pytest.importorskip("pyarrow.parquet", reason="pyarrow not installed")
    table = pa.read_table(out / "summary.parquet").to_pylist()
    assert [r["input"] for r in table] == [r for r in (row["input"] for row in csv.DictReader(open(out / "summary.csv")))]

    # Damage the output as an interrupted earlier run could have (or a
    # careless hand): two files gone, one cut short, a stale temporary.
    torus = output_path(out, "torus.swm")
    for name in ("torus.swm", "uv-sphere.swm"):
        output_path(out, name).unlink()
    cut = output_path(out, "cube.swm")
    cut.write_bytes(files["cube.swm"][: len(files["cube.swm"]) // 2])
    (torus.parent / ".torus.swm.abc123.tmp").write_bytes(b"half")

    # Run 2 encodes exactly those three, and gets the same bytes.
    rerun = subprocess.run(batch_command(manifest, out), capture_output=True, text=True, timeout=600)
    assert rerun.returncode == 1, rerun.stderr
    rows = read_summary(out / "summary.csv")
    encoded = sorted(n for n, r in rows.items() if r["status"] == "encoded")
    assert encoded == ["cube.obj", "torus.obj", "uv-sphere.obj"], rerun.stderr
    assert all(r["status"] == "skipped" for n, r in rows.items() if n not in encoded + ["bad.obj"])
    assert "swm.batch: 3 encoded" in rerun.stderr
    assert check_outputs(out, names) == files


def test_batch_on_an_existing_cluster(generated_corpus, tmp_path):
    """The multi-machine recipe of README.md, on one machine: a scheduler,
    workers joining it through the scheduler file, the batch given its
    address."""
    dask = Path(sys.executable).parent / "dask"
    if not dask.exists():
        pytest.skip("the dask command not found beside the Python interpreter")
    file = tmp_path / "scheduler.json"
    scheduler = subprocess.Popen([str(dask), "scheduler", "--scheduler-file", str(file), "--port", "0",
                                  "--no-dashboard"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    worker = None
    try:
        for _ in range(300):
            if file.exists() and file.stat().st_size > 0:
                break
            time.sleep(0.1)
        worker = subprocess.Popen([str(dask), "worker", "--scheduler-file", str(file), "--nworkers", "1",
                                   "--nthreads", "2", "--no-dashboard"],
                                  stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        import json

        address = json.loads(file.read_text())["address"]
        out = tmp_path / "out"
        run = subprocess.run([sys.executable, "-m", "swm.batch", str(generated_corpus), "--out", str(out),
                              "--mode", "lossless", "--address", address], capture_output=True, text=True,
                             timeout=300)
        assert run.returncode == 0, run.stderr
        assert f"on the cluster at {address}" in run.stderr
        rows = read_summary(out / "summary.csv")
        assert sorted(rows) == sorted(p.name for p in mesh_files(generated_corpus))
        assert {r["method"] for r in rows.values()} == {"lossless"}
        check_outputs(out, [p.with_suffix(".swm").name for p in mesh_files(generated_corpus)])
    finally:
        for p in (worker, scheduler):
            if p is not None:
                p.terminate()
                try:
                    p.wait(timeout=30)
                except subprocess.TimeoutExpired:
                    p.kill()


# -- the pieces ------------------------------------------------------------


def test_manifests(tmp_path):
    (tmp_path / "lib" / "a").mkdir(parents=True)
    for name in ("a/x.obj", "a/y.PLY", "z.stl", "notes.txt", "w.swm", "a/s.glb", "t.GLTF", "t.bin"):
        (tmp_path / "lib" / name).write_text("")
    jobs = batch.plan(tmp_path / "lib", tmp_path / "out", {}, 10)
    assert [(Path(j.input).relative_to(tmp_path), Path(j.output).relative_to(tmp_path)) for j in jobs] == [
        (Path("lib/a/s.glb"), Path("out/a/s.glb")),
        (Path("lib/a/x.obj"), Path("out/a/x.swm")),
        (Path("lib/a/y.PLY"), Path("out/a/y.swm")),
        (Path("lib/t.GLTF"), Path("out/t.glb")),
        (Path("lib/z.stl"), Path("out/z.swm")),
    ]
    assert batch.same_outputs(jobs) == []
    (tmp_path / "lib" / "a" / "s.gltf").write_text("")
    jobs = batch.plan(tmp_path / "lib", tmp_path / "out", {}, 10)
    assert batch.same_outputs(jobs) == [
        (str(tmp_path / "lib/a/s.glb"), str(tmp_path / "lib/a/s.gltf"), str(tmp_path / "out/a/s.glb"))]
    listing = tmp_path / "lib" / "list.txt"
    listing.write_text("# comment\n\na/x.obj\n  a/y.PLY  \na/x.obj\n" + str(tmp_path / "lib" / "z.stl") + "\n")
    jobs = batch.plan(listing, tmp_path / "out", {}, 10)
    assert [Path(j.output).relative_to(tmp_path) for j in jobs] == [
        Path("out/a/x.swm"), Path("out/a/y.swm"), Path("out/z.swm")
    ]


def test_write_atomic(tmp_path, monkeypatch):
    target = tmp_path / "d" / "f.swm"
    (tmp_path / "d").mkdir()
    (tmp_path / "d" / ".f.swm.old.tmp").write_bytes(b"stale")
    batch.write_atomic(target, b"new")
    assert target.read_bytes() == b"new"
    assert os.listdir(tmp_path / "d") == ["f.swm"]
    # The mode the CLI gives its outputs: 0o666 less the umask, not
    # mkstemp's 0o600 (other users of a shared file system read them).
    for umask in (0o022, 0o077, 0o002):
        old = os.umask(umask)
        try:
            batch.write_atomic(target, b"new")
        finally:
            os.umask(old)
        assert stat.S_IMODE(os.stat(target).st_mode) == 0o666 & ~umask, oct(umask)

    class Boom(Exception):
        pass

    def failing_fsync(fd: int) -> None:
        raise Boom()

    # A write that fails midway leaves the old file and no temporary.
    monkeypatch.setattr(os, "fsync", failing_fsync)
    with pytest.raises(Boom):
        batch.write_atomic(target, b"newer")
    monkeypatch.undo()
    assert target.read_bytes() == b"new"
    assert os.listdir(tmp_path / "d") == ["f.swm"]


def test_compress_task(generated_corpus, tmp_path):
    mesh = generated_corpus / "torus.obj"
    job = batch.Job(str(mesh), str(tmp_path / "t.swm"), {"mode": "swing", "bpv": 2.0}, 1000)
    row = batch.compress(job)
    assert row["status"] == "encoded" and row["method"] == "swing" and row["error"] == ""
    assert (tmp_path / "t.swm").read_bytes() == swm.encode(*swm.read(mesh), mode="swing", bpv=2.0)
    assert batch.compress(job)["status"] == "skipped"
    # An unusable output is replaced.
    (tmp_path / "t.swm").write_bytes(b"SWM garbage")
    assert batch.compress(job)["status"] == "encoded"
    # No retiling fits a size of 1 byte; with the fallback the mesh is
    # stored lossless, without it the row records the library's error.
    tiny = batch.Job(str(mesh), str(tmp_path / "u.swm"), {"mode": "swing", "max_size": 1}, 1000)
    assert batch.compress(tiny)["method"] == "lossless"
    no_fallback = batch.Job(str(mesh), str(tmp_path / "v.swm"), {"mode": "swing", "max_size": 1}, 1000,
                            fallback=False)
    row = batch.compress(no_fallback)
    assert row["status"] == "failed" and row["error"].startswith("RetileError: ")
    assert not (tmp_path / "v.swm").exists()
    # The automatic mode: the method column is the one the encoder chose;
    # a size no file meets is the row's error (no fallback would fit it).
    data, report = swm.encode(*swm.read(mesh), size=600, report=True)
    row = batch.compress(batch.Job(str(mesh), str(tmp_path / "a.swm"), {"size": 600}, 1000))
    assert row["method"] == report["method"] and (tmp_path / "a.swm").read_bytes() == data
    row = batch.compress(batch.Job(str(mesh), str(tmp_path / "s.swm"), {"mode": "lossless", "size": 600}, 1000))
    assert row["method"] == "simplified" and int(row["bytes"]) <= 600
    # Found there on a rerun, each file keeps its label: from the earlier
    # summary, or without one from the file (fewer triangles than the
    # input's: simplified).
    for name, options, method in (("s.swm", {"mode": "lossless", "size": 600}, "simplified"),
                                  ("l.swm", {"mode": "lossless"}, "lossless"),
                                  ("t.swm", {"mode": "swing", "bpv": 2.0}, "swing")):
        job = batch.Job(str(mesh), str(tmp_path / name), options, 1000)
        assert batch.compress(job)["status"] in ("encoded", "skipped")
        for earlier in (None, method):
            row = batch.compress(dataclasses.replace(job, earlier_method=earlier))
            assert (row["status"], row["method"]) == ("skipped", method), (name, earlier)
    # The earlier summary is read by output path.
    summary = tmp_path / "summary.csv"
    batch.write_summary([row], summary)
    assert batch.earlier_methods(summary) == {str(tmp_path / "t.swm"): "swing"}
    assert batch.earlier_methods(tmp_path / "none.csv") == {}
    row = batch.compress(batch.Job(str(mesh), str(tmp_path / "w.swm"), {"size": 10, "max_size": 10}, 1000))
    assert row["status"] == "failed" and row["error"].startswith("SizeError: no file of 10 bytes")
    assert not (tmp_path / "w.swm").exists()
    # An I/O error is not the mesh's fault: it propagates, for Dask to retry.
    with pytest.raises(swm.IoError):
        batch.compress(batch.Job(str(tmp_path / "missing.obj"), str(tmp_path / "m.swm")))


def test_usage_errors(generated_corpus, tmp_path):
    for args, message in (
        (["--angle-bits", "6"], "--mode auto takes no --angle-bits"),
        (["--qp", "12"], "--mode auto takes no --qp"),
        (["--mode", "swing", "--qp", "12"], "--mode swing takes no --qp"),
        (["--mode", "lossless", "--edge-length", "0.1"], "--mode lossless takes no --edge-length"),
        (["--mode", "lossless", "--bpv", "2", "--qp", "12"], "--mode lossless takes no --qp with --size or --bpv"),
        (["--mode", "lossless", "--max-size", "500"], "--mode lossless takes no --max-size without --size or --bpv"),
        (["--mode", "swing", "--effort", "fast"], "--mode swing takes no --effort"),
        (["--mode", "swing", "--max-error", "0.001"], "--mode swing takes no --max-error"),
        (["--mode", "lossless", "--effort", "max"], "--mode lossless takes no --effort without"),
        (["--bpv", "2", "--max-error", "0.001"], "not allowed with argument"),
        (["--mode", "swing", "--qt", "12"], "--mode swing takes no --qt"),
        (["--qt", "25"], "qt = 25: must be between 2 and 24"),
        (["--qn", "3"], "qn = 3: must be between 4 and 16"),
    ):
        run = subprocess.run([sys.executable, "-m", "swm.batch", str(generated_corpus), "--out", str(tmp_path),
                              *args], capture_output=True, text=True)
        assert run.returncode == 2 and message in run.stderr, (args, run.stderr)
    # The options each mode takes pass to swm.encode as they are.
    parse = batch._parser().parse_args
    assert batch._options(parse(["m", "--out", "o"])) == {"mode": "auto"}
    assert batch._options(parse(["m", "--out", "o", "--mode", "lossless", "--size", "500", "--max-size", "400"])) == {
        "mode": "lossless", "size": 500, "max_size": 400}
    assert batch._options(parse(["m", "--out", "o", "--mode", "lossless", "--qp", "14"])) == {
        "mode": "lossless", "qp": 14}
    assert batch._options(parse(["m", "--out", "o", "--effort", "fast", "--max-error", "0.002"])) == {
        "mode": "auto", "effort": "fast", "max_error": 0.002}
    # What they give is swm.encode's file for the same options.
    v, f = swm.read(generated_corpus / "torus.obj")
    fast = swm.encode(v, f, **batch._options(parse(["m", "--out", "o", "--effort", "fast"])))
    assert fast == swm.encode(v, f, effort="fast") != swm.encode(v, f)
    run = subprocess.run([sys.executable, "-m", "swm.batch", str(tmp_path / "nope"), "--out", str(tmp_path)],
                         capture_output=True, text=True)
    assert run.returncode == 2 and "no such file or directory" in run.stderr



# -- glTF scenes -----------------------------------------------------------


def scene_library(root: Path, generated_corpus: Path) -> Path:
    """A folder of two scenes (one with a line strip swm keeps as
    written, one `.gltf` with an embedded buffer, in a subfolder), a
    mesh and a broken scene."""
    lib = root / "scenes"
    (lib / "sub").mkdir(parents=True)
    (lib / "textured.glb").write_bytes(scene_glb())
    (lib / "sub" / "plain.gltf").write_bytes(scene_gltf(lines=False))
    (lib / "broken.glb").write_bytes(scene_glb()[:300])
    (lib / "torus.obj").write_bytes((generated_corpus / "torus.obj").read_bytes())
    return lib


def test_batch_compresses_folders_of_scenes(generated_corpus, tmp_path):
    lib = scene_library(tmp_path, generated_corpus)
    out = tmp_path / "out"
    command = [sys.executable, "-m", "swm.batch", str(lib), "--out", str(out), "--bpv", "8", "--workers", "1",
               "--samples", SAMPLES]
    run = subprocess.run(command, capture_output=True, text=True, timeout=600)
    # Exit 1: the broken scene failed; the rest have their files.
    assert run.returncode == 1, run.stderr
    rows = read_summary(out / "summary.csv")
    assert sorted(rows) == ["broken.glb", "plain.gltf", "textured.glb", "torus.obj"]
    broken = rows["broken.glb"]
    assert (broken["kind"], broken["status"]) == ("scene", "failed") and broken["error"].startswith("FormatError: ")
    assert not (out / "broken.glb").exists() and leftovers(out) == []
    want, report = swm.encode_scene(lib / "textured.glb", bpv=8.0, report=True)
    textured = rows["textured.glb"]
    assert (out / "textured.glb").read_bytes() == want
    assert textured["kind"] == "scene" and textured["status"] == "encoded"
    assert textured["method"] == "+".join(dict.fromkeys(p["method"] for p in report["primitives"] if p["coded"]))
    # A rate: every primitive at its share, the textured one too.
    assert "lossless" not in textured["method"]
    assert int(textured["input_bytes"]) == (lib / "textured.glb").stat().st_size
    assert int(textured["bytes"]) == len(want) < int(textured["input_bytes"])
    assert int(textured["swm_bytes"]) == report["swm_bytes"]
    assert int(textured["vertices"]) == 325 + 297
    assert float(textured["bits_per_vertex"]) == pytest.approx(8 * report["swm_bytes"] / (325 + 297))
    # Nothing silently lost: the line strip, in the row and on stderr.
    assert textured["uncompressed"] == 'mesh 2 "Wire" primitive 0 (lines (mode 3))'
    assert 'kept uncompressed: mesh 2 "Wire"' in run.stderr
    # A scene of triangles only is measured as swm.read reads it; one
    # with lines is not (swm.read refuses lines).
    assert textured["l2_estimate"] == ""
    plain = rows["plain.gltf"]
    assert Path(plain["output"]) == out / "sub" / "plain.glb" and plain["uncompressed"] == ""
    assert 0 <= float(plain["l2_estimate"]) < 0.05, plain
    assert (out / "sub" / "plain.glb").read_bytes() == swm.encode_scene(lib / "sub" / "plain.gltf", bpv=8.0)
    assert rows["torus.obj"]["kind"] == "mesh" and rows["torus.obj"]["swm_bytes"] == rows["torus.obj"]["bytes"]
    for name in ("textured.glb", "sub/plain.glb"):
        swm.decode_scene(out / name)
    pa = pytest.importorskip("pyarrow.parquet", reason="pyarrow not installed")
    table = {Path(r["input"]).name: r for r in pa.read_table(out / "summary.parquet").to_pylist()}
    assert table["textured.glb"]["swm_bytes"] == report["swm_bytes"] and table["textured.glb"]["l2_estimate"] is None

    # A rerun without the summary: every output is found, decoded and
    # skipped, each scene's methods read from its file; a damaged scene
    # is compressed again.
    (out / "summary.csv").unlink()
    (out / "sub" / "plain.glb").write_bytes(want[: len(want) // 3])
    run = subprocess.run(command, capture_output=True, text=True, timeout=600)
    assert run.returncode == 1, run.stderr
    again = read_summary(out / "summary.csv")
    assert again["plain.gltf"]["status"] == "encoded" and again["textured.glb"]["status"] == "skipped"
    assert (out / "sub" / "plain.glb").read_bytes() == swm.encode_scene(lib / "sub" / "plain.gltf", bpv=8.0)
    for name in ("textured.glb", "plain.gltf"):
        for key in ("method", "bytes", "swm_bytes", "vertices", "input_bytes"):
            assert again[name][key] == rows[name][key], (name, key)
    assert again["textured.glb"]["uncompressed"] == 'mesh 2 "Wire" primitive 0'
    assert leftovers(out) == []


def test_compress_scene_task(tmp_path):
    scene = tmp_path / "s.glb"
    scene.write_bytes(scene_glb(lines=False))
    job = batch.Job(str(scene), str(tmp_path / "out" / "s.glb"), {"mode": "lossless"}, 1000)
    row = batch.compress(job)
    assert (row["kind"], row["status"], row["method"], row["error"]) == ("scene", "encoded", "lossless", "")
    data = (tmp_path / "out" / "s.glb").read_bytes()
    assert data == swm.encode_scene(scene, mode="lossless")
    # Lossless: the decoded scene is the input within the quantization.
    assert 0 <= row["l2_estimate"] < 1e-3
    assert batch.compress(job)["status"] == "skipped"
    # --gltf-fallback: an uncompressed copy beside each swm file, so the
    # extension is used but not required.
    kept = dataclasses.replace(job, output=str(tmp_path / "out" / "f.glb"), gltf_fallback=True)
    assert batch.compress(kept)["status"] == "encoded"
    with_copy = (tmp_path / "out" / "f.glb").read_bytes()
    assert with_copy == swm.encode_scene(scene, mode="lossless", fallback=True) != data
    doc, _ = batch.glb_chunks(with_copy)
    assert "SWM_mesh_compression" in doc["extensionsUsed"] and "extensionsRequired" not in doc
    assert batch.plan(tmp_path, tmp_path / "o", {}, 10, gltf_fallback=True)[0].gltf_fallback
    assert batch._parser().parse_args(["m", "--out", "o", "--gltf-fallback"]).gltf_fallback
    # What made each primitive, read back from the file, against the input.
    info = swm.scene_info(scene)
    assert batch.scene_methods(data, info) == "lossless"
    small = batch.Job(str(scene), str(tmp_path / "out" / "t.glb"), {"bpv": 4.0}, 1000)
    row = batch.compress(small)
    # A rate: every primitive at its share, the textured one too.
    assert "lossless" not in row["method"]
    assert batch.scene_methods((tmp_path / "out" / "t.glb").read_bytes(), info) == row["method"]
    assert batch.compress(dataclasses.replace(small, earlier_method="x"))["method"] == "x"
    # An unusable output is replaced.
    (tmp_path / "out" / "s.glb").write_bytes(b"glTF garbage")
    assert batch.compress(job)["status"] == "encoded"
    with pytest.raises(swm.FormatError):
        batch.scene_methods(b"glTF garbage")
    # An I/O error propagates, for Dask to retry; a bad scene is the row's.
    with pytest.raises(swm.IoError):
        batch.compress(batch.Job(str(tmp_path / "missing.glb"), str(tmp_path / "m.glb")))
    (tmp_path / "bad.gltf").write_text("{\"asset\": 7}")
    row = batch.compress(batch.Job(str(tmp_path / "bad.gltf"), str(tmp_path / "out" / "bad.glb")))
    assert row["status"] == "failed" and row["error"].startswith("FormatError: ")
    assert not (tmp_path / "out" / "bad.glb").exists()


def test_scene_usage_errors(tmp_path):
    (tmp_path / "lib").mkdir()
    (tmp_path / "lib" / "a.glb").write_bytes(scene_glb())
    for extra, message in ((["--max-size", "900"], "--max-size does not apply to glTF scenes"),):
        run = subprocess.run([sys.executable, "-m", "swm.batch", str(tmp_path / "lib"), "--out",
                              str(tmp_path / "out"), *extra], capture_output=True, text=True)
        assert run.returncode == 2 and message in run.stderr, run.stderr
    (tmp_path / "lib" / "a.gltf").write_bytes(scene_gltf())
    run = subprocess.run([sys.executable, "-m", "swm.batch", str(tmp_path / "lib"), "--out", str(tmp_path / "out")],
                         capture_output=True, text=True)
    assert run.returncode == 2 and "would both write" in run.stderr, run.stderr
    assert not (tmp_path / "out").exists()


def test_compress_keeps_a_meshs_attributes(tmp_path):
    """A mesh's texture coordinates and normals go into its file; what a
    file does not keep is in the row's `dropped`, with why."""
    obj = tube_obj(tmp_path / "tube.obj")
    row = batch.compress(batch.Job(str(obj), str(tmp_path / "a.swm"), {"bpv": 24.0}, 1000))
    assert row["status"] == "encoded" and row["method"] == "simplified", row
    data = (tmp_path / "a.swm").read_bytes()
    v, f, attrs = swm.read(obj, attributes=True)
    assert data == swm.encode(v, f, attributes=attrs, bpv=24.0)
    assert sorted(swm.decode(data, attributes=True)[2]) == ["uv"]
    # The tube's radial normals follow its surface: left to the decoder.
    assert row["dropped"].startswith("normals not kept: the normals follow the geometry"), row
    # Its positions, once each: the seam's copies are not counted twice.
    assert int(row["vertices"]) == len(np.unique(v, axis=0)) < len(v)
    row = batch.compress(batch.Job(str(obj), str(tmp_path / "l.swm"), {"mode": "lossless"}, 1000))
    assert row["dropped"] == "" and sorted(swm.decode((tmp_path / "l.swm").read_bytes(), attributes=True)[2]) == [
        "normals", "uv"]
    # The swing method carries no texture coordinates; a rerun finds the
    # file and says so.
    job = batch.Job(str(obj), str(tmp_path / "s.swm"), {"mode": "swing", "bpv": 8.0}, 1000)
    row = batch.compress(job)
    assert row["method"] == "swing"
    assert row["dropped"] == "normals, uv not kept: the swing method's file cannot carry texture coordinates"
    row = batch.compress(job)
    assert row["status"] == "skipped" and row["dropped"] == "normals, uv not in the file"
    # Nor does the displaced method: its row says so too, not an error.
    row = batch.compress(batch.Job(str(obj), str(tmp_path / "d.swm"), {"mode": "displaced", "bpv": 24.0}, 1000))
    assert row["status"] == "encoded" and row["method"] == "displaced", row
    assert row["dropped"] == "normals, uv not kept: the displaced method's file cannot carry texture coordinates"
    # A `vt` on some corners only: the reader's note.
    part = tmp_path / "part.obj"
    part.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nf 1/1 2/1 3/1\nf 2 4 3\n")
    row = batch.compress(batch.Job(str(part), str(tmp_path / "p.swm"), {"mode": "lossless"}, 1000))
    assert row["status"] == "encoded" and row["dropped"].startswith("texture coordinates not read"), row

"""Batch compression of a mesh library on Dask distributed.

    python -m swm.batch MANIFEST --out DIR [--bpv R | --size B | --edge-length L]
                        [--mode auto|swing|displaced|lossless] [--qn N] [--qt N] [--qg N] [--gltf-fallback]
                        [--address tcp://HOST:8786]

MANIFEST is a directory (every .obj, .ply, .off and .stl mesh and every
.glb and .gltf scene under it) or a text file listing one input path per
line (blank lines and ``#`` comments skipped; relative paths are taken
from the manifest's folder). Each mesh ``base/a/b.obj`` becomes
``DIR/a/b.swm``, each glTF scene ``base/a/c.gltf`` (or ``.glb``) a
compressed scene ``DIR/a/c.glb`` (:func:`swm.encode_scene`, as ``swm
encode c.gltf -o c.glb``: every triangle primitive coded inside
``SWM_mesh_compression``, nodes, materials, textures and animations
kept), ``base`` being the manifest directory or the deepest folder
common to the listed paths. Two inputs that would write the same output
(``a.obj`` beside ``a.ply``, ``c.glb`` beside ``c.gltf``) are a usage
error.

Without ``--address`` the encodes run on a local cluster (``--workers``
processes, one thread each); with it (or ``--scheduler-file``), on the
existing Dask cluster it names, whose workers must have this package installed and see the
inputs and DIR at the same paths (a shared file system).

What a run guarantees:

* Every output is written under a temporary name in its own folder,
  synced, then renamed: a file at an output path is always complete,
  whatever is killed when.
* An input whose output exists and decodes (a scene: every coded
  primitive, :func:`swm.decode_scene`) is skipped, so a rerun after an
  interruption encodes only what is missing (or damaged). A scene is
  decoded before it is written, too: a file that would not decode is
  never written.
* ``--mode`` and the target options are those of ``swm encode`` (and
  :func:`swm.encode`), with its defaults and its rules: ``auto`` (the
  default) writes whichever of SwingWrapper and simplify-then-lossless
  the encoder measures closer to the input, ``swing`` retiles,
  ``lossless`` keeps every triangle (``--qp``) or, with ``--size`` or
  ``--bpv``, simplifies to fit. ``--effort`` and ``--max-error`` are
  ``swm encode``'s too (the effort level of the automatic and simplified
  searches; the smallest file within an error). Options the mode has no
  use for are a usage error. A scene takes them as ``swm encode`` does
  (:func:`swm.encode_scene`): every primitive at its share of the
  target, attributes and all (``--size`` is then the budget of the
  scene's swm files; without a size, rate or error bound, primitives
  with attributes are coded losslessly with them); ``--max-size`` does not apply to scenes (a usage
  error when the inputs hold one). A mesh is read with its texture
  coordinates, normals and colours (:func:`swm.read` with
  ``attributes=True``) and encoded with them (``--mode swing`` cannot
  carry them: the ``dropped`` column says so, as it names every stream a
  file does not keep, and why). ``--qn``, ``--qt`` and ``--qg`` are the
  attribute quantization of ``swm encode``; ``--gltf-fallback`` keeps an
  uncompressed copy of each coded primitive of a scene, for viewers
  without swm, as ``swm encode --gltf-fallback``.
* In ``--mode swing``, when the encoder finds no retiling of a mesh
  (``swm.RetileError``), the mesh is encoded lossless instead
  (``--fallback lossless``, the default; ``--fallback none`` records the
  failure). ``--mode auto`` needs no fallback: the library itself falls
  back to the simplified file. The ``method`` column says what made each
  file.
* A task that fails for a reason outside the mesh (an I/O error, a worker
  that died under it) is retried (``--retries``); one the library refuses
  (a malformed file, a topology the codec cannot take) is recorded, not
  retried, since it would fail the same way again.
* A progress line per finished input, on stderr; at the end a summary
  table (``DIR/summary.csv``, and ``DIR/summary.parquet`` when pyarrow is
  installed) with the columns of :data:`COLUMNS`. The exit status is 0
  when every input was encoded or skipped, 1 when some failed, 2 on bad
  usage.
"""

from __future__ import annotations

import argparse
import csv
import dataclasses
import io
import os
import secrets
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any, Dict, Iterable, List, Mapping, Optional, Sequence, Tuple

import numpy as np

import swm

#: Extensions of the mesh files a directory manifest takes.
MESH_EXTENSIONS = (".obj", ".ply", ".off", ".stl")
#: Extensions of the glTF scenes a directory manifest takes; each becomes
#: a compressed ``.glb``.
SCENE_EXTENSIONS = (".glb", ".gltf")

#: Columns of the summary table. ``kind`` is ``mesh`` or ``scene``;
#: ``status`` is ``encoded``, ``skipped`` (a valid output was already
#: there) or ``failed``; ``method`` is what made the file: ``swing``,
#: ``simplified`` (simplification, then the lossless coder),
#: ``lossless`` (every input triangle), ``displaced``, ``mixed``; for a
#: scene, the methods of its coded primitives joined by ``+`` in
#: document order without repeats (``lossless+simplified``), or
#: ``none`` when it has no primitive swm codes. For a skipped input it is
#: what the earlier run's summary says made that file, or, without one,
#: what the file shows (:func:`method_of`, :func:`scene_methods`);
#: ``input_bytes`` and ``bytes`` are the input's and the output's size;
#: ``swm_bytes`` the bytes of swm data in the output (a mesh: all of
#: them; a scene: its coded primitives' swm files, beside the textures
#: and the rest it keeps); ``vertices`` the input's vertices (with
#: attribute streams, its positions once each however many texture
#: coordinates or normals they carry; a scene: those of its coded
#: primitives, as written); ``bits_per_vertex`` is
#: ``8 * swm_bytes / vertices``; ``l2_estimate`` is the symmetric L2
#: distance between input and decoded mesh over the input's bounding-box
#: diagonal, from area-uniform face samples (``--samples``; a scene's
#: drawn triangles, every node's instance in world space, as
#: :func:`swm.read` reads a scene, empty when it draws points or lines);
#: ``seconds`` is the encode time (empty for a skipped input);
#: ``uncompressed``, for a scene, every primitive kept as written
#: (``mesh 2 "Fox" primitive 0 (JOINTS_0, WEIGHTS_0)``, joined by
#: ``; ``; a skipped scene's without the reason); ``dropped``, for a
#: mesh, the attribute streams of the input (texture coordinates,
#: normals, colours) its file does not carry, with why (the reader could
#: not attach them, normals left to the decoder, no room, the swing
#: method); ``error`` the failure's message.
COLUMNS = (
    "input",
    "output",
    "kind",
    "status",
    "method",
    "input_bytes",
    "bytes",
    "swm_bytes",
    "vertices",
    "bits_per_vertex",
    "l2_estimate",
    "seconds",
    "uncompressed",
    "dropped",
    "error",
)


@dataclass(frozen=True)
class Job:
    """One input to encode: everything a worker needs, picklable."""

    input: str
    output: str
    options: Dict[str, Any] = field(default_factory=dict)
    samples: int = 10_000
    #: Encode lossless when SwingWrapper retiling fails (``mode="swing"``;
    #: the automatic mode falls back by itself).
    fallback: bool = True
    #: What made the output, as an earlier run's summary records it
    #: (``None``: no summary, or no row for it), for a skipped input.
    earlier_method: Optional[str] = None
    #: A scene keeps an uncompressed copy of each coded primitive beside
    #: its swm file (``swm encode --gltf-fallback``).
    gltf_fallback: bool = False


def find_inputs(manifest: Path) -> List[Path]:
    """The inputs a manifest names, in order, without repeats."""
    if manifest.is_dir():
        found = [
            p
            for p in manifest.rglob("*")
            if p.is_file() and p.suffix.lower() in MESH_EXTENSIONS + SCENE_EXTENSIONS
        ]
        return sorted(found)
    paths: List[Path] = []
    seen = set()
    for line in manifest.read_text().splitlines():
        line = line.strip()
        if not line or line.startswith("#"):
            continue
        p = Path(line)
        if not p.is_absolute():
            p = manifest.parent / p
        p = Path(os.path.normpath(p.absolute()))
        if p not in seen:
            seen.add(p)
            paths.append(p)
    return paths


def plan(
    manifest: Path,
    out: Path,
    options: Dict[str, Any],
    samples: int,
    fallback: bool = True,
    gltf_fallback: bool = False,
) -> List[Job]:
    """One job per input, each with its output path under ``out``."""
    inputs = find_inputs(manifest)
    if manifest.is_dir():
        base = manifest
    elif inputs:
        base = Path(os.path.commonpath([p.parent for p in inputs]))
    else:
        base = manifest.parent
    jobs = []
    for p in inputs:
        rel = p.relative_to(base).with_suffix(".glb" if is_scene(p) else ".swm")
        jobs.append(Job(str(p), str(out / rel), dict(options), samples, fallback, gltf_fallback=gltf_fallback))
    return jobs


def is_scene(path: Any) -> bool:
    """Whether ``path`` names a glTF scene (``.glb``, ``.gltf``)."""
    return Path(path).suffix.lower() in SCENE_EXTENSIONS


def same_outputs(jobs: Sequence[Job]) -> List[Tuple[str, str, str]]:
    """Pairs of inputs that would write the same output, as ``(first,
    second, output)``."""
    seen: Dict[str, str] = {}
    clashes = []
    for j in jobs:
        if j.output in seen:
            clashes.append((seen[j.output], j.input, j.output))
        else:
            seen[j.output] = j.input
    return clashes


def _temp_prefix(path: Path) -> str:
    return f".{path.name}."


def _create_temp(folder: Path, prefix: str) -> Tuple[int, str]:
    """A new file ``PREFIX<random>.tmp`` in ``folder``, created exclusively
    (never an existing entry, never through a symbolic link) with mode
    0o666 less the umask, as ``swm``'s CLI creates its outputs
    (``tempfile.mkstemp`` would give 0o600, unreadable to the other users
    of a shared file system)."""
    flags = os.O_WRONLY | os.O_CREAT | os.O_EXCL | getattr(os, "O_NOFOLLOW", 0)
    for _ in range(100):
        temp = str(folder / f"{prefix}{secrets.token_hex(6)}.tmp")
        try:
            return os.open(temp, flags, 0o666), temp
        except FileExistsError:
            continue
    raise FileExistsError(f"{folder}: no free temporary name for {prefix}*.tmp")


def write_atomic(path: Path, data: bytes) -> None:
    """Writes ``data`` to ``path`` complete or not at all: a temporary file
    in the same folder (so the rename stays on one file system), synced,
    then renamed over ``path``. Leftovers of an earlier attempt at the same
    output (a worker killed while writing) are removed first. The file
    gets the mode the CLI gives its outputs: 0o666 less the umask."""
    path.parent.mkdir(parents=True, exist_ok=True)
    prefix = _temp_prefix(path)
    for stale in path.parent.glob(prefix + "*.tmp"):
        try:
            stale.unlink()
        except FileNotFoundError:
            pass
    fd, temp = _create_temp(path.parent, prefix)
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
            f.flush()
            os.fsync(f.fileno())
        os.replace(temp, path)
    except BaseException:
        try:
            os.unlink(temp)
        except FileNotFoundError:
            pass
        raise
    # The rename itself reaches the disk with the folder's entry.
    dir_fd = os.open(path.parent, os.O_RDONLY)
    try:
        os.fsync(dir_fd)
    finally:
        os.close(dir_fd)


def verified(path: Path, scene: bool = False) -> Optional[Tuple[bytes, Any]]:
    """The bytes of ``path`` and their decoded mesh (a scene: the
    expanded document's bytes) if it exists and decodes, else ``None``."""
    try:
        data = path.read_bytes()
    except FileNotFoundError:
        return None
    try:
        return data, swm.decode_scene(data) if scene else swm.decode(data)
    except swm.SwmError:
        return None


def method_of(data: bytes, faces: Any, earlier: Optional[str] = None) -> str:
    """What made an existing ``.swm`` file: ``earlier`` (an earlier run's
    summary) when the file's mode agrees with it; else ``swing`` for a
    SwingWrapper file, and for a lossless-mode one ``simplified`` when it
    holds fewer triangles than the input's ``faces`` without repeated
    corners (what cleaning keeps, bar duplicates), ``lossless`` otherwise."""
    info = swm.info(data)
    if info["mode"] == "swing":
        return "swing"
    if earlier in ("lossless", "simplified"):
        return earlier

    f = np.asarray(faces)
    proper = int(np.count_nonzero((f[:, 0] != f[:, 1]) & (f[:, 1] != f[:, 2]) & (f[:, 0] != f[:, 2])))
    return "simplified" if info["triangles"] < proper else "lossless"


def compress(job: Job) -> Dict[str, Any]:
    """Encodes one input (on a worker) and returns its summary row.

    Errors the library reports about the mesh are part of the row; any
    other exception (I/O included) propagates so that Dask retries."""
    if is_scene(job.input):
        return compress_scene(job)
    row: Dict[str, Any] = {c: None for c in COLUMNS}
    row.update(input=job.input, output=job.output, kind="mesh", uncompressed="", dropped="", error="")
    output = Path(job.output)
    try:
        # The mesh with its texture coordinates, normals and colours (the
        # split form), and what the reader could not attach, for the row.
        # (`swm.read` would warn; a worker's warnings reach no one.)
        vertices, faces, streams, unread = swm._swm.read(os.fspath(job.input), attributes=True)
        row["input_bytes"] = os.stat(job.input).st_size
        dropped = [f"{', '.join(unread)} {swm._UNREAD}"] if unread else []
        found = verified(output)
        if found is not None:
            data, decoded = found
            row["status"] = "skipped"
            method = method_of(data, faces, job.earlier_method)
            kept = swm.decode(data, attributes=True)[2]
            lost = [k for k in streams if k not in kept]
            if lost:
                dropped.append(f"{', '.join(lost)} not in the file")
        else:
            start = time.perf_counter()
            # SwingWrapper and displaced files cannot carry texture
            # coordinates (`swm.encode` refuses them there): the surface
            # alone then, and the row says what it left out (the other
            # streams they resample at their vertices).
            mode = job.options.get("mode")
            remeshed = mode in ("swing", "displaced") and any(k.startswith("uv") for k in streams)
            try:
                data, report = swm.encode(vertices, faces, **job.options, report=True,
                                          attributes=None if remeshed else streams)
                method = report["method"]
                a = report["attributes"]
                if remeshed:
                    dropped.append(f"{', '.join(streams)} not kept: the {mode} method's file cannot carry "
                                   "texture coordinates")
                elif a["dropped"] and a["dropped_because"] is not None:
                    dropped.append(f"{', '.join(a['dropped'])} not kept: {a['dropped_because']['message']}")
            except swm.RetileError:
                if not job.fallback:
                    raise
                data = swm.encode(vertices, faces, mode="lossless", attributes=streams)
                method = "lossless"
            row["seconds"] = time.perf_counter() - start
            write_atomic(output, data)
            row["status"] = "encoded"
            decoded = swm.decode(data)
        d = swm.distance((vertices, faces), decoded, samples=job.samples, sampling="faces")
        # Positions once however many texture coordinates or normals they
        # carry (the split form repeats a position on a seam), as the
        # encoder's rate counts them.
        n = len(np.unique(vertices, axis=0)) if streams else len(vertices)
        row.update(
            method=method,
            bytes=len(data),
            swm_bytes=len(data),
            vertices=n,
            bits_per_vertex=8 * len(data) / max(n, 1),
            l2_estimate=d["l2_relative"],
            dropped="; ".join(dropped),
        )
    except swm.IoError:
        raise
    except swm.SwmError as e:
        row.update(status="failed", error=f"{type(e).__name__}: {e}")
    return row


def _scene_options(options: Dict[str, Any]) -> Dict[str, Any]:
    """:func:`swm.encode`'s options as :func:`swm.encode_scene` takes
    them (``main`` refuses ``max_size`` when the inputs hold a scene)."""
    return {k: v for k, v in options.items() if k != "max_size"}


def glb_chunks(data: bytes) -> Tuple[Dict[str, Any], bytes]:
    """The JSON and the BIN chunk of a GLB file (glTF 2.0 §4.4), as the
    batch writes them; ``swm.FormatError`` for anything else."""
    import json
    import struct

    def bad(what: str) -> swm.FormatError:
        return swm.FormatError(f"not a GLB file the batch wrote: {what}")

    if len(data) < 20 or data[:4] != b"glTF":
        raise bad("no GLB header")
    (length,) = struct.unpack_from("<I", data, 8)
    if length != len(data):
        raise bad("its length field is not its size")
    at, doc, bin_chunk = 12, None, b""
    while at + 8 <= len(data):
        size, kind = struct.unpack_from("<II", data, at)
        chunk = data[at + 8 : at + 8 + size]
        if len(chunk) != size:
            raise bad("a chunk runs past the end")
        if kind == 0x4E4F534A and doc is None:
            doc = json.loads(chunk)
        elif kind == 0x004E4942 and not bin_chunk:
            bin_chunk = chunk
        at += 8 + size
    if not isinstance(doc, dict):
        raise bad("no JSON chunk")
    return doc, bin_chunk


def _joined(methods: Iterable[str]) -> str:
    """Methods in order without repeats, joined by ``+``; ``none`` for none."""
    out: List[str] = []
    for m in methods:
        if m not in out:
            out.append(m)
    return "+".join(out) or "none"


def scene_methods(data: bytes, input_scene: Optional[Sequence[Mapping[str, Any]]] = None) -> str:
    """What made an existing compressed scene's primitives, as the
    ``method`` column spells it: each coded primitive's swm file is read
    (:func:`swm.info`) and named as :func:`method_of` names a mesh's
    file, against the input primitive's triangles (``input_scene``,
    :func:`swm.scene_info` of the input; without it a lossless-mode file
    is called ``lossless``)."""
    doc, bin_chunk = glb_chunks(data)
    triangles = {(p["mesh"], p["primitive"]): p["triangles"] for p in input_scene or []}
    methods: List[str] = []
    for m, mesh in enumerate(doc.get("meshes", [])):
        for k, prim in enumerate(mesh.get("primitives", [])):
            ext = prim.get("extensions", {}).get("SWM_mesh_compression")
            if ext is None:
                continue
            view = doc["bufferViews"][ext["bufferView"]]
            start = view.get("byteOffset", 0)
            info = swm.info(bin_chunk[start : start + view["byteLength"]])
            if info["mode"] != "lossless":
                methods.append(info["mode"])
            elif info["triangles"] < triangles.get((m, k), 0):
                methods.append("simplified")
            else:
                methods.append("lossless")
    return _joined(methods)


def _scene_l2(input_path: str, decoded: bytes, samples: int) -> Optional[float]:
    """The L2 estimate between the input scene and the decoded one, each
    read as :func:`swm.read` reads a scene (every drawn triangle in world
    space); ``None`` when either cannot be read so (points or lines)."""
    import tempfile

    try:
        a = swm.read(input_path)
    except swm.SwmError:
        return None
    with tempfile.TemporaryDirectory(prefix="swm-batch-") as folder:
        plain = Path(folder) / "decoded.glb"
        plain.write_bytes(decoded)
        try:
            b = swm.read(plain)
        except swm.SwmError:
            return None
    return swm.distance(a, b, samples=samples, sampling="faces")["l2_relative"]


def _label(p: Mapping[str, Any]) -> str:
    """A primitive as the library's report names it (``mesh 2 "Fox"
    primitive 0``)."""
    name = f' "{p["name"]}"' if p.get("name") is not None else ""
    return f"mesh {p['mesh']}{name} primitive {p['primitive']}"


def compress_scene(job: Job) -> Dict[str, Any]:
    """Compresses one glTF scene (on a worker) and returns its row; as
    :func:`compress`, errors the library reports about the scene are the
    row's and the others propagate. The output is decoded before it is
    written: a scene that does not decode is never written."""
    row: Dict[str, Any] = {c: None for c in COLUMNS}
    row.update(input=job.input, output=job.output, kind="scene", uncompressed="", dropped="", error="")
    output = Path(job.output)
    try:
        input_scene = swm.scene_info(job.input)
        row["input_bytes"] = os.stat(job.input).st_size
        found = verified(output, scene=True)
        if found is not None:
            data, decoded = found
            row["status"] = "skipped"
            method = job.earlier_method or scene_methods(data, input_scene)
            coded = {(p["mesh"], p["primitive"]): p for p in swm.scene_info(data) if p["swm_bytes"] is not None}
            swm_bytes = sum(p["swm_bytes"] or 0 for p in coded.values())
            vertices = sum(p["vertices"] for p in input_scene if (p["mesh"], p["primitive"]) in coded)
            row["uncompressed"] = "; ".join(
                _label(p) for p in input_scene if (p["mesh"], p["primitive"]) not in coded
            )
        else:
            start = time.perf_counter()
            data, report = swm.encode_scene(job.input, **_scene_options(job.options), report=True,
                                            fallback=job.gltf_fallback)
            decoded = swm.decode_scene(data)
            row["seconds"] = time.perf_counter() - start
            write_atomic(output, data)
            row["status"] = "encoded"
            coded_prims = [p for p in report["primitives"] if p["coded"]]
            method = _joined(p["method"] for p in coded_prims)
            swm_bytes = report["swm_bytes"]
            vertices = sum(p["input_vertices"] for p in coded_prims)
            row["uncompressed"] = "; ".join(report["uncompressed"])
        row.update(
            method=method,
            bytes=len(data),
            swm_bytes=swm_bytes,
            vertices=vertices,
            bits_per_vertex=8 * swm_bytes / max(vertices, 1),
            l2_estimate=_scene_l2(job.input, decoded, job.samples),
        )
    except swm.IoError:
        raise
    except swm.SwmError as e:
        row.update(status="failed", error=f"{type(e).__name__}: {e}")
    return row


def earlier_methods(csv_path: Path) -> Dict[str, str]:
    """Output path -> method, from an earlier run's summary at ``csv_path``
    (empty when there is none or it cannot be read)."""
    try:
        with open(csv_path, newline="") as f:
            return {
                r["output"]: r["method"]
                for r in csv.DictReader(f)
                if r.get("status") in ("encoded", "skipped") and r.get("method")
            }
    except (OSError, csv.Error, KeyError):
        return {}


def failed_row(job: Job, error: BaseException) -> Dict[str, Any]:
    """The row of a task that ran out of retries."""
    row: Dict[str, Any] = {c: None for c in COLUMNS}
    row.update(
        input=job.input,
        output=job.output,
        status="failed",
        error=f"{type(error).__name__}: {error}".replace("\n", " "),
    )
    return row


def write_summary(rows: Sequence[Dict[str, Any]], csv_path: Path) -> List[Path]:
    """Writes the CSV summary (and a Parquet copy when pyarrow is there),
    atomically; returns the paths written."""
    text = io.StringIO()
    writer = csv.DictWriter(text, fieldnames=COLUMNS, lineterminator="\n")
    writer.writeheader()
    for row in rows:
        writer.writerow({k: "" if row.get(k) is None else row[k] for k in COLUMNS})
    write_atomic(csv_path, text.getvalue().encode())
    written = [csv_path]
    try:
        import pyarrow as pa
        import pyarrow.parquet as pq
    except ImportError:
        return written
    # Typed columns, so that a run with nothing encoded (all `seconds`
    # empty) gives the same schema as any other.
    types = {"input_bytes": pa.int64(), "bytes": pa.int64(), "swm_bytes": pa.int64(),
             "vertices": pa.int64(), "bits_per_vertex": pa.float64(),
             "l2_estimate": pa.float64(), "seconds": pa.float64()}
    schema = pa.schema([(k, types.get(k, pa.string())) for k in COLUMNS])
    table = pa.Table.from_pylist([{k: r.get(k) for k in COLUMNS} for r in rows], schema=schema)
    sink = pa.BufferOutputStream()
    pq.write_table(table, sink)
    parquet = csv_path.with_suffix(".parquet")
    write_atomic(parquet, sink.getvalue().to_pybytes())
    written.append(parquet)
    return written


def _progress(done: int, total: int, row: Dict[str, Any]) -> None:
    width = len(str(total))
    if row["status"] == "failed":
        what = f"failed: {row['error']}"
    else:
        l2 = "" if row["l2_estimate"] is None else f", L2 {row['l2_estimate']:.3e}"
        what = (
            f"{row['status']}, {row['method']}, {row['bytes']} bytes, "
            f"{row['bits_per_vertex']:.3f} bits/vertex{l2}"
        )
        if row.get("uncompressed"):
            what += f"; kept uncompressed: {row['uncompressed']}"
        if row.get("dropped"):
            what += f"; {row['dropped']}"
    print(f"[{done:>{width}}/{total}] {row['input']}: {what}", file=sys.stderr, flush=True)


def run(jobs: Sequence[Job], client: Any, retries: int) -> List[Dict[str, Any]]:
    """Runs the jobs on a Dask client; rows in the order of ``jobs``."""
    from distributed import as_completed

    # `pure=False`: each run encodes anew (skipping is decided on the
    # worker, from the file system, not from Dask's cache of results).
    futures = [client.submit(compress, job, retries=retries, pure=False) for job in jobs]
    index = {f.key: i for i, f in enumerate(futures)}
    rows: List[Optional[Dict[str, Any]]] = [None] * len(jobs)
    for done, future in enumerate(as_completed(futures), 1):
        i = index[future.key]
        if future.status == "finished":
            row = future.result()
        elif future.status == "error":
            # Out of retries, or its worker died under it more often than
            # the scheduler allows (`KilledWorker`).
            row = failed_row(jobs[i], future.exception())
        else:
            row = failed_row(jobs[i], RuntimeError(f"task {future.status}"))
        rows[i] = row
        _progress(done, len(jobs), row)
    return [r for r in rows if r is not None]


def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="python -m swm.batch",
        description="Encode a library of meshes into .swm files on Dask distributed.",
    )
    p.add_argument("manifest", type=Path, help="a directory of meshes or a file listing mesh paths")
    p.add_argument("--out", type=Path, required=True, help="folder of the .swm files")
    p.add_argument(
        "--mode",
        choices=("auto", "swing", "displaced", "lossless"),
        default="auto",
        help="auto (default): the best of the effort level's methods at the size; "
        "swing: retiling; displaced: displaced subdivision at --size/--bpv; "
        "lossless: every triangle, or simplified to --size/--bpv",
    )
    target = p.add_mutually_exclusive_group()
    target.add_argument(
        "--bpv", type=float, help="bits per input vertex (auto and swing: default 2; lossless: simplify to fit)"
    )
    target.add_argument("--size", type=int, help="bytes per file (lossless: simplify to fit)")
    target.add_argument("--edge-length", type=float, help="swing and auto: the edge length L")
    target.add_argument(
        "--max-error", type=float,
        help="auto and lossless: the smallest file whose L2 to the input is at most E "
        "(relative to the bounding-box diagonal, as swm encode --max-error)",
    )
    p.add_argument(
        "--effort", choices=("fast", "default", "max"),
        help="auto and lossless with a target: how hard the encoder searches, as swm encode "
        "--effort (default: default)",
    )
    p.add_argument("--angle-bits", type=int, help="swing: bits per dihedral angle (default: chosen by rate control, as swm encode)")
    p.add_argument("--max-size", type=int, help="never more bytes than this (lossless: with --size or --bpv)")
    p.add_argument("--qp", type=int, help="lossless without a size: bits per coordinate (default 12)")
    p.add_argument("--qn", type=int, help="auto and lossless: bits per octahedral coordinate of a normal (default 8)")
    p.add_argument("--qt", type=int, help="auto and lossless: bits per texture coordinate (default 10)")
    p.add_argument("--qg", type=int, help="auto and lossless: bits per colour or generic component (default 8)")
    p.add_argument(
        "--fallback",
        choices=("lossless", "none"),
        default="lossless",
        help="swing: what to do with a mesh no retiling fits (default: encode it lossless)",
    )
    p.add_argument(
        "--gltf-fallback",
        action="store_true",
        help="scenes: keep an uncompressed copy of each coded primitive, for viewers without swm "
        "(swm encode --gltf-fallback)",
    )
    where = p.add_mutually_exclusive_group()
    where.add_argument(
        "--address", help="an existing Dask scheduler, tcp://HOST:PORT (default: a local cluster)"
    )
    where.add_argument(
        "--scheduler-file", type=Path, help="an existing Dask scheduler, by its scheduler file"
    )
    p.add_argument("--workers", type=int, default=2, help="local cluster: worker processes")
    p.add_argument("--threads", type=int, default=1, help="local cluster: threads per worker")
    p.add_argument("--retries", type=int, default=2, help="retries of a failed task")
    p.add_argument(
        "--samples", type=int, default=10_000, help="face samples of the L2 estimate"
    )
    p.add_argument(
        "--summary", type=Path, help="summary CSV (default OUT/summary.csv; .parquet beside it)"
    )
    return p


#: One triangle, to check the quantization options with the library's
#: own rule before the run.
_TRIANGLE = ([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], [[0, 1, 2]])


def _options(args: argparse.Namespace) -> Dict[str, Any]:
    """The options of :func:`swm.encode`, refusing (``ValueError``) those
    the mode has no use for, as ``swm encode`` does."""
    sized = args.size is not None or args.bpv is not None or args.max_error is not None
    refused = {
        "auto": {"--qp": args.qp, "--angle-bits": args.angle_bits},
        "swing": {"--qp": args.qp, "--max-error": args.max_error, "--effort": args.effort,
                  "--qn": args.qn, "--qt": args.qt, "--qg": args.qg},
        "lossless": {
            "--edge-length": args.edge_length,
            "--angle-bits": args.angle_bits,
            "--qp with --size or --bpv": args.qp if sized else None,
            "--max-size without --size or --bpv": None if sized else args.max_size,
            "--effort without --size, --bpv or --max-error": None if sized else args.effort,
        },
    }[args.mode]
    given = [k for k, v in refused.items() if v is not None]
    if given:
        raise ValueError(f"--mode {args.mode} takes no {', '.join(given)}")
    options: Dict[str, Any] = {"mode": args.mode}
    for key in ("angle_bits", "bpv", "size", "edge_length", "max_size", "qp", "effort", "max_error",
                "qn", "qt", "qg"):
        if getattr(args, key) is not None:
            options[key] = getattr(args, key)
    return options


def main(argv: Optional[Iterable[str]] = None) -> int:
    parser = _parser()
    args = parser.parse_args(None if argv is None else list(argv))
    try:
        options = _options(args)
    except ValueError as e:
        parser.error(str(e))
    if not args.manifest.exists():
        parser.error(f"{args.manifest}: no such file or directory")
    if args.samples < 1:
        parser.error("--samples must be at least 1")
    out = args.out.absolute()
    jobs = plan(args.manifest.absolute(), out, options, args.samples, args.fallback == "lossless",
                args.gltf_fallback)
    summary = args.summary.absolute() if args.summary else out / "summary.csv"
    earlier = earlier_methods(summary)
    jobs = [dataclasses.replace(j, earlier_method=earlier.get(j.output)) for j in jobs]
    if not jobs:
        print(f"swm.batch: {args.manifest}: no mesh or scene files", file=sys.stderr)
        return 1
    for first, second, output in same_outputs(jobs)[:1]:
        parser.error(f"{first} and {second} would both write {output}")
    if args.max_size is not None and any(is_scene(j.input) for j in jobs):
        parser.error("--max-size does not apply to glTF scenes (--size is the whole scene's swm budget)")
    # Bits out of range are refused before any work, as swm encode does.
    try:
        swm.encode(*_TRIANGLE, **{k: v for k, v in options.items() if k in ("qn", "qt", "qg")},
                   mode="lossless")
    except swm.ParameterError as e:
        parser.error(str(e))
    from distributed import Client, LocalCluster

    start = time.perf_counter()
    if args.address or args.scheduler_file:
        if args.address:
            client = Client(args.address)
        else:
            client = Client(scheduler_file=str(args.scheduler_file))
        cluster = None
    else:
        cluster = LocalCluster(
            n_workers=args.workers,
            threads_per_worker=args.threads,
            processes=True,
            dashboard_address=None,
        )
        client = Client(cluster)
    try:
        where = (
            f"the cluster at {client.scheduler.address}"
            if cluster is None
            else f"a local cluster of {args.workers} workers"
        )
        print(f"swm.batch: {len(jobs)} inputs on {where}", file=sys.stderr, flush=True)
        rows = run(jobs, client, args.retries)
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
    written = write_summary(rows, summary)
    counts = {s: sum(r["status"] == s for r in rows) for s in ("encoded", "skipped", "failed")}
    print(
        f"swm.batch: {counts['encoded']} encoded, {counts['skipped']} skipped, "
        f"{counts['failed']} failed in {time.perf_counter() - start:.1f} s; "
        f"summary {', '.join(str(p) for p in written)}",
        file=sys.stderr,
    )
    return 1 if counts["failed"] else 0


if __name__ == "__main__":
    sys.exit(main())

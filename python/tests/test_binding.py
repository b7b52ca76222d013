"""The binding against the command line: same bytes, same meshes, same
figures, same messages; errors by kind; array checks; the GIL."""

from __future__ import annotations

import errno
import json
import re
import struct
import subprocess
import threading
import time
import zlib
from pathlib import Path

import numpy as np
import pytest

import swm
from conftest import cli_error, run_cli

# (CLI arguments, the same options for swm.encode). Low rates keep the
# retiling cheap; every mode (the automatic one, the default, included),
# both lossless kinds (exact, simplified to a size) and the targets appear.
OPTIONS = [
    ([], {}),
    (["--size", "400", "--max-size", "410"], {"size": 400, "max_size": 410}),
    (["--mode", "swing", "--bpv", "3", "--angle-bits", "10"], {"mode": "swing", "bpv": 3.0, "angle_bits": 10}),
    (["--mode", "swing", "--size", "400"], {"mode": "swing", "size": 400}),
    (["--mode", "lossless", "--qp", "14"], {"mode": "lossless", "qp": 14}),
    (["--mode", "lossless", "--size", "600"], {"mode": "lossless", "size": 600}),
]

#: The report's `attributes` for a mesh encoded without attribute streams.
NO_ATTRIBUTES = {"kept": [], "dropped": [], "dropped_because": None, "texcoord_error": None}


@pytest.fixture(scope="session")
def small_meshes(generated_corpus: Path) -> list:
    return [generated_corpus / "torus.obj", generated_corpus / "cube.obj"]


@pytest.fixture(scope="session")
def torus(generated_corpus: Path):
    return swm.read(generated_corpus / "torus.obj")


def bits_equal(a: np.ndarray, b: np.ndarray) -> bool:
    return a.dtype == b.dtype and a.shape == b.shape and a.tobytes() == b.tobytes()


@pytest.mark.parametrize("cli_args,options", OPTIONS)
def test_encode_gives_the_cli_bytes(swm_bin, small_meshes, tmp_path, cli_args, options):
    for mesh in small_meshes:
        out = tmp_path / (mesh.stem + ".swm")
        run_cli(swm_bin, "encode", mesh, "-o", out, *cli_args)
        v, f = swm.read(mesh)
        assert swm.encode(v, f, **options) == out.read_bytes(), (mesh, options)


def test_encode_gives_the_cli_bytes_on_the_shared_corpus(swm_bin, shared_corpus, tmp_path):
    mesh = shared_corpus / "woody.obj"
    out = tmp_path / "woody.swm"
    run_cli(swm_bin, "encode", mesh, "-o", out, "--bpv", "4")
    assert swm.encode(*swm.read(mesh), bpv=4) == out.read_bytes()


@pytest.mark.parametrize(
    "cli_args,options",
    [([], {}), (["--sharpen"], {"sharpen": True}), (["--sharpen", "--bend", "1"], {"sharpen": True, "bend": 1})],
)
def test_decode_equals_the_cli_decode_bit_for_bit(swm_bin, generated_corpus, tmp_path, cli_args, options):
    mesh = generated_corpus / "cube.obj"
    for mode_args, name in ((["--mode", "swing", "--bpv", "3"], "swing"), (["--mode", "lossless"], "lossless")):
        packed = tmp_path / f"{name}.swm"
        run_cli(swm_bin, "encode", mesh, "-o", packed, *mode_args)
        cli_ply = tmp_path / f"{name}-cli.ply"
        run_cli(swm_bin, "decode", packed, "-o", cli_ply, *cli_args)
        v, f = swm.decode(packed.read_bytes(), **options)
        assert v.dtype == np.float32 and f.dtype == np.uint32
        cv, cf = swm.read(cli_ply)
        assert bits_equal(v, cv) and bits_equal(f, cf), (name, options)
        # And the file the binding writes is the CLI's, byte for byte.
        py_ply = tmp_path / f"{name}-py.ply"
        swm.write(py_ply, v, f)
        assert py_ply.read_bytes() == cli_ply.read_bytes()


GOLDEN = Path(__file__).resolve().parents[2] / "format-spec" / "golden"


@pytest.mark.parametrize("max_level", [None, 0, 1, 2, 5])
def test_displaced_decodes_as_the_cli_level_by_level(swm_bin, tmp_path, max_level):
    packed = GOLDEN / "displaced-v1.2.swm"
    cli_ply = tmp_path / "displaced-cli.ply"
    extra = [] if max_level is None else ["--max-level", str(max_level)]
    run_cli(swm_bin, "decode", packed, "-o", cli_ply, *extra)
    v, f = swm.decode(packed.read_bytes(), max_level=max_level)
    cv, cf = swm.read(cli_ply)
    assert bits_equal(v, cv) and bits_equal(f, cf), max_level
    # 564 base triangles, four times as many per level, two levels.
    levels = 2 if max_level is None else min(max_level, 2)
    assert len(f) == 564 * 4**levels
    if max_level is None:
        info = swm.info(packed.read_bytes())
        cli = json.loads(run_cli(swm_bin, "info", packed, "--json").stdout)
        assert info["mode"] == cli["mode"] == "displaced"
        assert info["level_bytes"] == cli["level_bytes"] and len(info["level_bytes"]) == 2
        for key in ["prediction", "steps", "bends", "bare_base", "base_bytes"]:
            assert info[key] == cli[key], key
        assert info["prediction"] == "loop" and info["bare_base"] is False


def test_decode_normals(torus):
    data = swm.encode(*torus, mode="swing", bpv=4)
    v, f, n = swm.decode(data, normals=True)
    assert n.shape == v.shape and n.dtype == np.float32
    assert np.allclose(np.linalg.norm(n, axis=1), 1.0, atol=1e-5)
    # The normals point away from the torus' central circle (its axis is z).
    radial = v.copy()
    radial[:, 2] = 0
    centre = radial / np.linalg.norm(radial, axis=1, keepdims=True) * np.linalg.norm(
        torus[0][:, :2], axis=1
    ).mean()
    assert (np.sum((v - centre) * n, axis=1) > 0).mean() > 0.99


@pytest.mark.parametrize("cli_args,options", [([], {}), (["--mode", "lossless"], {"mode": "lossless"})])
def test_info_has_the_cli_json(swm_bin, generated_corpus, tmp_path, cli_args, options):
    packed = tmp_path / "torus.swm"
    run_cli(swm_bin, "encode", generated_corpus / "torus.obj", "-o", packed, *cli_args)
    cli = json.loads(run_cli(swm_bin, "info", packed, "--json").stdout)
    assert swm.info(packed.read_bytes()) == cli


def test_distance_has_the_cli_json(swm_bin, generated_corpus, tmp_path):
    a = generated_corpus / "torus.obj"
    packed, b = tmp_path / "t.swm", tmp_path / "t.ply"
    run_cli(swm_bin, "encode", a, "-o", packed)
    run_cli(swm_bin, "decode", packed, "-o", b)
    for cli_args, options in (
        ([], {}),
        (["--samples", "5000", "--sampling", "faces"], {"samples": 5000, "sampling": "faces"}),
    ):
        cli = json.loads(run_cli(swm_bin, "distance", a, b, "--json", *cli_args).stdout)
        assert swm.distance(swm.read(a), swm.read(b), **options) == cli


# -- errors: classes by kind, messages the library's ----------------------


def test_malformed_files_raise_format_error_with_the_cli_message(swm_bin, torus, tmp_path):
    data = swm.encode(*torus, mode="swing", bpv=3)
    for name, bad in (("empty", b""), ("truncated", data[: len(data) // 2]), ("garbage", b"x" * 64)):
        path = tmp_path / f"{name}.swm"
        path.write_bytes(bad)
        with pytest.raises(swm.FormatError) as e:
            swm.decode(bad)
        assert isinstance(e.value, ValueError) and isinstance(e.value, swm.SwmError)
        assert str(e.value) == cli_error(swm_bin, "decode", path, "-o", tmp_path / "x.ply")
        with pytest.raises(swm.FormatError):
            swm.info(bad)


def test_newer_version_raises_unsupported_error(torus):
    data = bytearray(swm.encode(*torus, mode="swing", bpv=3))
    data[4] = 9  # the major version (format-spec/01-container.md)
    data[-4:] = struct.pack("<I", zlib.crc32(bytes(data[:-4])))
    with pytest.raises(swm.UnsupportedError, match="version 9"):
        swm.decode(bytes(data))


def test_limits_raise_limit_error(torus):
    data = swm.encode(*torus, mode="lossless")
    with pytest.raises(swm.LimitError):
        swm.decode(data, limits=swm.Limits(max_vertices=10))
    v, _ = swm.decode(data, limits=swm.Limits(max_vertices=len(torus[0])))
    assert len(v) == len(torus[0])
    assert swm.Limits().max_faces == 1 << 29


def test_file_errors(tmp_path):
    with pytest.raises(swm.IoError) as e:
        swm.read(tmp_path / "missing.obj")
    assert isinstance(e.value, OSError) and e.value.errno == errno.ENOENT
    assert e.value.filename == str(tmp_path / "missing.obj")
    with pytest.raises(swm.ParameterError, match="unknown mesh format"):
        swm.read(tmp_path / "mesh.xyz")
    with pytest.raises(swm.ParameterError, match="read but not written"):
        swm.write(tmp_path / "mesh.gltf", np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0]], np.float32),
                  np.array([[0, 1, 2]], np.uint32))
    bad = tmp_path / "bad.obj"
    bad.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n")
    with pytest.raises(swm.FormatError, match="line 4"):
        swm.read(bad)


def test_non_orientable_mesh_raises_topology_error():
    # A Möbius strip: a band of quads whose ends meet with a half twist.
    n = 24
    t = np.linspace(0, 2 * np.pi, n, endpoint=False)
    v = []
    for s in (-0.3, 0.3):
        v.append(
            np.stack(
                [
                    (1 + s * np.cos(t / 2)) * np.cos(t),
                    (1 + s * np.cos(t / 2)) * np.sin(t),
                    s * np.sin(t / 2),
                ],
                axis=1,
            )
        )
    vertices = np.concatenate(v).astype(np.float32)
    faces = []
    for i in range(n):
        a, b = i, n + i
        if i + 1 < n:
            c, d = i + 1, n + i + 1
        else:  # the twist: the far side's edge comes back reversed
            c, d = n, 0
        faces += [(a, c, b), (b, c, d)]
    with pytest.raises(swm.TopologyError, match="not orientable"):
        swm.encode(vertices, np.array(faces), mode="lossless")


def test_bad_options():
    v, f = np.eye(3, dtype=np.float32), np.array([[0, 1, 2]], dtype=np.uint32)
    with pytest.raises(ValueError, match=r'mode must be "auto", "swing", "displaced" or "lossless", got "fast"'):
        swm.encode(v, f, mode="fast")
    with pytest.raises(ValueError, match="at most one of bpv, size, edge_length and max_error"):
        swm.encode(v, f, bpv=2, size=100)
    with pytest.raises(swm.ParameterError, match=r"angle bits = 1000: must be between 4 and 12"):
        swm.encode(v, f, mode="swing", angle_bits=1000)
    with pytest.raises(swm.ParameterError, match=r"qp = 3: must be between 6 and 24"):
        swm.encode(v, f, mode="lossless", qp=3)
    with pytest.raises(swm.ParameterError, match="size = -5"):
        swm.encode(v, f, size=-5)
    with pytest.raises(swm.ParameterError, match="bits per vertex"):
        swm.encode(v, f, bpv=-1.0)
    with pytest.raises(ValueError, match="sampling"):
        swm.distance((v, f), (v, f), sampling="grid")
    with pytest.raises(TypeError, match="bytes"):
        swm.decode("not bytes")  # type: ignore[arg-type]


@pytest.mark.parametrize(
    "options,refused",
    [
        ({"angle_bits": 6}, r'mode="auto" takes no angle_bits'),
        ({"qp": 12}, r'mode="auto" takes no qp'),
        ({"mode": "swing", "qp": 12}, r'mode="swing" takes no qp'),
        ({"mode": "lossless", "edge_length": 0.1}, r'mode="lossless" takes no edge_length'),
        ({"mode": "lossless", "angle_bits": 6}, r'mode="lossless" takes no angle_bits'),
        ({"mode": "lossless", "size": 500, "qp": 12}, r'mode="lossless" takes no qp with size or bpv'),
        ({"mode": "lossless", "bpv": 2, "qp": 12}, r'mode="lossless" takes no qp with size or bpv'),
        ({"mode": "lossless", "max_size": 500}, r'mode="lossless" takes max_size only with size or bpv'),
    ],
)
def test_options_the_mode_has_no_use_for_are_refused(torus, options, refused):
    # Refused before any work, as `swm encode` refuses them.
    with pytest.raises(ValueError, match=refused) as e:
        swm.encode(*torus, **options)
    assert not isinstance(e.value, swm.SwmError)


def test_the_cli_refuses_the_same_combinations(swm_bin, generated_corpus, tmp_path):
    mesh, out = generated_corpus / "cube.obj", tmp_path / "x.swm"
    for args in (["--angle-bits", "6"], ["--qp", "12"], ["--mode", "swing", "--qp", "12"],
                 ["--mode", "lossless", "--edge-length", "0.1"], ["--mode", "lossless", "--size", "500", "--qp", "12"],
                 ["--mode", "lossless", "--max-size", "500"]):
        run = subprocess.run([str(swm_bin), "encode", mesh, "-o", out, *args], capture_output=True)
        assert run.returncode == 2, (args, run.stderr.decode())


def test_auto_is_the_default_and_reports_the_cli_choice(swm_bin, generated_corpus, tmp_path):
    mesh = generated_corpus / "torus.obj"
    out = tmp_path / "torus.swm"
    cli = json.loads(run_cli(swm_bin, "encode", mesh, "-o", out, "--json").stdout)
    v, f = swm.read(mesh)
    data, report = swm.encode(v, f, report=True)
    assert data == out.read_bytes() == swm.encode(v, f, mode="auto", bpv=2)
    # The choice, both candidates' sizes and errors, as `--json` has them.
    assert report["choice"] == cli["method"]
    assert report["method"] == cli["method"]["chosen"] in ("swing", "simplified")
    assert report["simplified"] == cli.get("simplified")
    # The check as `--json` reports it, less the CLI's judgement.
    check = dict(cli["check"])
    assert check.pop("problems") == []
    assert report["check"] == check and 0 < check["l2_relative"] < 0.05
    both = report["choice"]
    assert both["swing"] is not None and both["simplified"] is not None and both["swing_failure"] is None
    chosen, other = both[both["chosen"]], both[{"swing": "simplified", "simplified": "swing"}[both["chosen"]]]
    assert chosen["bytes"] == len(data) and chosen["l2_rel"] <= other["l2_rel"]
    assert swm.info(data)["mode"] == {"swing": "swing", "simplified": "lossless"}[both["chosen"]]


def test_lossless_with_a_size_simplifies_to_fit(torus):
    v, f = torus
    data, report = swm.encode(v, f, mode="lossless", size=700, report=True)
    assert swm.info(data)["mode"] == "lossless" and len(data) <= 700
    assert report["method"] == "simplified" and report["choice"] is None
    kept = report["simplified"]
    assert kept["input_faces"] == len(f) and 0 < kept["faces"] < len(f) and 6 <= kept["qp"] <= 16
    dv, df = swm.decode(data)
    assert len(df) == kept["faces"]
    # A cap below the size wins; bpv is a size too.
    assert len(swm.encode(v, f, mode="lossless", size=700, max_size=500)) <= 500
    assert len(swm.encode(v, f, mode="lossless", bpv=8 * 700 / len(v))) <= 700
    # Without a size: every triangle, at qp bits (default 12).
    exact, report = swm.encode(v, f, mode="lossless", report=True)
    # Nothing to check either: every triangle, each vertex within half a step.
    assert report == {"method": "lossless", "choice": None, "simplified": None, "check": None,
                      "attributes": NO_ATTRIBUTES, "smallest_instead": None}
    assert len(swm.decode(exact)[1]) == len(f)
    assert exact == swm.encode(v, f, mode="lossless", qp=12) != swm.encode(v, f, mode="lossless", qp=14)


def test_swing_mode_report(torus):
    data, report = swm.encode(*torus, mode="swing", bpv=3, report=True)
    check = report.pop("check")
    assert report == {"method": "swing", "choice": None, "simplified": None, "attributes": NO_ATTRIBUTES,
                      "smallest_instead": None}
    # The file as decoded, measured against the torus as swm distance would.
    dv, df = swm.decode(data)
    assert (check["decoded_vertices"], check["decoded_triangles"]) == (len(dv), len(df))
    assert 0 < check["l2_relative"] <= check["hausdorff_relative"] < 0.05
    assert swm.info(data)["mode"] == "swing"


def test_displaced_mode(torus):
    """mode="displaced": a mode-2 file at the size, decoded whole or to its
    base; the options it has no use for are refused."""
    v, f = torus
    budget = 12 * len(v) // 8
    data, report = swm.encode(v, f, mode="displaced", bpv=12, report=True)
    assert report["method"] == "displaced" and report["choice"] is None, report
    assert 0.97 * budget <= len(data) <= budget, (len(data), budget)
    assert swm.info(data)["mode"] == "displaced"
    dv, df = swm.decode(data)
    bv, bf = swm.decode(data, max_level=0)
    assert len(bf) < len(df) and len(bv) < len(dv)
    for bad in ({"qp": 10}, {"angle_bits": 6}, {"edge_length": 0.1}, {"max_error": 1e-3}, {"qt": 10}):
        with pytest.raises(ValueError, match="displaced"):
            swm.encode(v, f, mode="displaced", **bad)


# Auto: SwingWrapper gives its nearest file when none is as small as the
# size, so only a cap makes a size too small there (the retiling fails
# under it, and so does simplification).
@pytest.mark.parametrize(
    "cli_args,options",
    [
        (["--mode", "lossless", "--size", "10"], {"mode": "lossless", "size": 10}),
        (["--size", "10", "--max-size", "10"], {"size": 10, "max_size": 10}),
    ],
)
def test_a_size_too_small_raises_size_error(swm_bin, generated_corpus, tmp_path, cli_args, options):
    mesh = generated_corpus / "torus.obj"
    with pytest.raises(swm.SizeError) as e:
        swm.encode(*swm.read(mesh), **options)
    error = e.value
    assert isinstance(error, ValueError) and isinstance(error, swm.SwmError)
    m = re.fullmatch(r"no file of 10 bytes can hold this mesh: the smallest possible is (\d+) bytes", str(error))
    assert m, str(error)
    assert error.requested == 10 and error.smallest == int(m.group(1)) > 10
    # The CLI's message, which adds its own way out (or_smallest= here);
    # and the smallest size named is one that works.
    said = cli_error(swm_bin, "encode", mesh, "-o", tmp_path / "x.swm", *cli_args)
    assert said == str(error) + " (--or-smallest writes it)"
    data = swm.encode(*swm.read(mesh), mode="lossless", size=error.smallest)
    assert len(data) <= error.smallest


def test_or_smallest_writes_the_smallest_file_and_says_so(swm_bin, generated_corpus, tmp_path):
    mesh = generated_corpus / "torus.obj"
    with pytest.raises(swm.SizeError) as e:
        swm.encode(*swm.read(mesh), size=10)
    data, report = swm.encode(*swm.read(mesh), size=10, or_smallest=True, report=True)
    assert report["smallest_instead"] == {"requested": 10, "smallest": e.value.smallest}
    assert len(data) <= e.value.smallest * 1.03
    # The same bytes as the CLI's --or-smallest, and as asking for that size.
    out = tmp_path / "s.swm"
    subprocess.run([swm_bin, "encode", mesh, "-o", out, "--size", "10", "--or-smallest"], check=True, capture_output=True)
    assert out.read_bytes() == data
    _, fits = swm.encode(*swm.read(mesh), size=200_000, or_smallest=True, report=True)
    assert fits["smallest_instead"] is None
    # A cap below the smallest file still raises.
    with pytest.raises(swm.SizeError):
        swm.encode(*swm.read(mesh), size=10, max_size=10, or_smallest=True)


# -- arrays: dtypes, shapes, layouts ----------------------------------------


def test_wrong_dtypes_and_shapes_get_clear_errors(torus):
    v, f = torus
    with pytest.raises(TypeError, match=r"vertices must be a floating-point array.*got dtype int64"):
        swm.encode(v.astype(np.int64), f)
    with pytest.raises(TypeError, match=r"faces must be an integer array.*got dtype float32"):
        swm.encode(v, f.astype(np.float32))
    with pytest.raises(TypeError, match="got dtype <U1"):
        swm.encode([["a", "b", "c"]], f)
    with pytest.raises(ValueError, match=r"vertices must have shape \(n, 3\), got shape \(1536, 2\)"):
        swm.encode(v[:, :2], f)
    with pytest.raises(ValueError, match=r"faces must have shape \(m, 3\), got shape \(9216,\)"):
        swm.encode(v, f.ravel())
    with pytest.raises(ValueError, match="vertex index -1"):
        swm.encode(v, np.array([[0, 1, -1]]))
    with pytest.raises(ValueError, match=r"b vertices must have shape"):
        swm.distance((v, f), (v.ravel(), f))
    # An index past the last vertex is the library's error, as for a file.
    with pytest.raises(swm.FormatError, match="vertex index 5000 is out of range"):
        swm.encode(v, np.array([[0, 1, 5000]], dtype=np.uint32))
    with pytest.raises(swm.FormatError, match="NaN or infinite"):
        swm.encode(np.where(np.arange(len(v))[:, None] == 7, np.nan, v), f)


def test_other_dtypes_and_layouts_give_the_same_bytes(torus):
    v, f = torus
    expected = swm.encode(v, f, mode="swing", bpv=3)
    assert swm.encode(v.astype(np.float64), f.astype(np.int64), mode="swing", bpv=3) == expected
    assert swm.encode(np.asfortranarray(v), np.asfortranarray(f), mode="swing", bpv=3) == expected
    assert swm.encode(v.tolist(), f.tolist(), mode="swing", bpv=3) == expected
    wide = np.zeros((len(v), 6), np.float32)
    wide[:, ::2] = v
    assert swm.encode(wide[:, ::2], f, mode="swing", bpv=3) == expected
    assert swm.decode(bytearray(expected))[0].tobytes() == swm.decode(memoryview(expected))[0].tobytes()


def test_outputs_are_plain_numpy_arrays(torus):
    v, f = swm.decode(swm.encode(*torus, mode="lossless"))
    for a, dtype in ((v, np.float32), (f, np.uint32)):
        assert isinstance(a, np.ndarray) and a.dtype == dtype and a.flags.c_contiguous
        assert a.ndim == 2 and a.shape[1] == 3
    # Writable and owned by NumPy's memory management: no views into freed memory.
    v += 1
    del f


# -- the GIL ---------------------------------------------------------------


def test_the_gil_is_released_while_encoding(generated_corpus):
    # Python code runs in this thread while the other one is inside the
    # library. Were the GIL held there, this thread could not run until
    # each encode returned: ticks would fall between encodes, none while
    # one is running. The encodes are made long enough (a finer retiling
    # each time one takes under 50 ms) for that to tell, on any machine:
    # the check is about where the ticks fall, not how fast anything is.
    v, f = swm.read(generated_corpus / "double-torus.obj")
    spans: list = []
    done = threading.Event()

    def encode() -> None:
        bpv = 4.0
        for _ in range(6):
            start = time.perf_counter()
            swm.encode(v, f, mode="swing", bpv=bpv)
            end = time.perf_counter()
            spans.append((start, end))
            if end - start >= 0.05:
                break
            bpv *= 2
        done.set()

    ticks: list = []
    worker = threading.Thread(target=encode)
    worker.start()
    while not done.is_set():
        ticks.append(time.perf_counter())
        time.sleep(0.001)
    worker.join()
    start, end = spans[-1]
    assert end - start >= 0.05 or len(spans) == 6, spans
    inside = sum(start < t < end for t in ticks)
    # Released: about one tick per millisecond of the last encode; held:
    # none (a tick or two at its edges at most).
    assert inside >= 10, (inside, end - start)


# -- trimesh -----------------------------------------------------------------


def test_trimesh_round_trip(torus):
    trimesh = pytest.importorskip("trimesh", reason="trimesh not installed (pip install trimesh)")
    data = swm.encode(*torus, mode="swing", bpv=3)
    v, f, n = swm.decode(data, normals=True)
    mesh = swm.to_trimesh(v, f, n)
    assert isinstance(mesh, trimesh.Trimesh)
    assert len(mesh.vertices) == len(v) and len(mesh.faces) == len(f)
    back_v, back_f = swm.from_trimesh(mesh)
    assert bits_equal(back_v, v) and bits_equal(back_f, f)
    # A trimesh works wherever a mesh is taken.
    assert swm.distance(mesh, (v, f))["hausdorff_relative"] < 1e-12
    assert swm.encode(*swm.from_trimesh(swm.to_trimesh(*torus)), mode="swing", bpv=3) == data

"""Whole glTF scenes through the binding (issue 47, items 4 and 5):
`swm.encode_scene` writes the command line's bytes and report, keeps the
node tree, materials, textures, images and animations, and names what it
leaves uncompressed; `swm.decode_scene` expands the extension back to
plain accessors within the quantization; bad documents raise typed
errors naming the file."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

import swm
from conftest import ROOT, run_cli
from scenes import PNG, accessor, parse_glb, scene_document, scene_glb, scene_gltf, torus

KEPT = ("scene", "scenes", "nodes", "materials", "samplers", "textures", "asset")


def without_json_only(report: dict) -> dict:
    """The CLI's `--json` for a scene without what the binding does not
    report (the timing) and the flag that says it is a scene."""
    return {k: v for k, v in report.items() if k not in ("scene", "encode_seconds")}


def test_encode_scene_is_the_clis(swm_bin, tmp_path: Path):
    scene = tmp_path / "scene.glb"
    scene.write_bytes(scene_glb())
    for options, flags in (({}, []), ({"bpv": 8.0}, ["--bpv", "8"]), ({"mode": "lossless"}, ["--mode", "lossless"]),
                           ({"mode": "lossless", "qt": 14, "qn": 12, "qp": 16},
                            ["--mode", "lossless", "--qt", "14", "--qn", "12", "--qp", "16"]),
                           ({"size": 3000, "fallback": True}, ["--size", "3000", "--gltf-fallback"])):
        out = run_cli(swm_bin, "encode", scene, "-o", tmp_path / "out.glb", "--json", *flags)
        cli = json.loads(out.stdout)
        want = (tmp_path / "out.glb").read_bytes()
        data, report = swm.encode_scene(scene, report=True, **options)
        assert data == want, options
        # From bytes: the same file (no external buffers to find).
        assert swm.encode_scene(scene.read_bytes(), **options) == want, options
        assert report == without_json_only(cli), options
    # The line strip is kept as written and named, with why.
    assert report["uncompressed"] == ['mesh 2 "Wire" primitive 0 (lines (mode 3))']
    donut, ring, wire = report["primitives"]
    # With a size, the textured donut is coded at its share by the method
    # that keeps its seams, attributes and all.
    assert donut["coded"] and donut["method"] == "simplified" and donut["attributes"] == ["NORMAL", "TEXCOORD_0"]
    assert ring["coded"] and not wire["coded"]
    assert report["swm_bytes"] == donut["bytes"] + ring["bytes"] and report["input_bytes"] == scene.stat().st_size
    assert report["requested"] == 3000 and report["bytes"] == len(data)


def test_decode_scene_keeps_the_scene(swm_bin, tmp_path: Path):
    source = scene_glb()
    doc, _ = parse_glb(source)
    data = swm.encode_scene(source, mode="lossless")
    coded, _ = parse_glb(data)
    assert coded["extensionsRequired"] == ["SWM_mesh_compression"]
    (tmp_path / "out.glb").write_bytes(data)
    run_cli(swm_bin, "decode", tmp_path / "out.glb", "-o", tmp_path / "plain.glb")
    plain, report = swm.decode_scene(tmp_path / "out.glb", report=True)
    assert plain == (tmp_path / "plain.glb").read_bytes()
    # The donut's seam copies stay (their UVs differ); the ring, of
    # positions only, has its 33 × 9 grid's repeated column and row merged.
    assert report == {"bytes": len(plain), "primitives": 2, "decoded_vertices": 325 + 32 * 8,
                      "decoded_triangles": 576 + 512}
    got, bin_chunk = parse_glb(plain)
    # Node tree, materials, textures, images and the scene as written;
    # the animation's sampler accessors are renumbered, not changed.
    for key in KEPT:
        assert got[key] == doc[key], key
    # The image's bytes as they were, in a renumbered bufferView.
    (image,) = got["images"]
    assert image["mimeType"] == "image/png"
    view = got["bufferViews"][image["bufferView"]]
    start = view.get("byteOffset", 0)
    assert bin_chunk[start : start + view["byteLength"]] == PNG
    assert "extensionsUsed" not in got or "SWM_mesh_compression" not in got["extensionsUsed"]
    (anim,) = got["animations"]
    assert anim["channels"] == doc["animations"][0]["channels"]
    times = accessor(got, bin_chunk, anim["samplers"][0]["input"])
    assert times[:, 0].tolist() == [0.0, 1.0, 2.0]
    assert [len(m["primitives"]) for m in got["meshes"]] == [1, 1, 1]
    assert got["meshes"][2]["primitives"][0]["mode"] == 3
    # The donut within the quantization: positions on 12 bits over its
    # box, UVs within half a step of 10 bits, unit normals within 2°,
    # and the UV seams intact (each decoded vertex is an input vertex).
    p, n, uv, f = torus(24, 12, 1.0, 0.35)
    prim = got["meshes"][0]["primitives"][0]
    dp = accessor(got, bin_chunk, prim["attributes"]["POSITION"])
    dn = accessor(got, bin_chunk, prim["attributes"]["NORMAL"])
    duv = accessor(got, bin_chunk, prim["attributes"]["TEXCOORD_0"])
    df = accessor(got, bin_chunk, prim["indices"]).reshape(-1, 3)
    assert len(dp) == len(p) and len(df) == len(f)
    step = (p.max(axis=0) - p.min(axis=0)).max() / 4095
    near = (np.abs(dp[:, None, :] - p[None, :, :]).max(axis=2) <= step) & (
        np.abs(duv[:, None, :] - uv[None, :, :]).max(axis=2) <= 0.5 / 1023 + 1e-6)
    assert near.any(axis=1).all() and near.any(axis=0).all()
    which = near.argmax(axis=1)
    assert (np.einsum("ij,ij->i", dn, n[which]) > np.cos(np.radians(2))).all()
    # No face spans a seam: u and v within one chart across each face.
    u = duv[df]
    assert (np.ptp(u, axis=1) < 0.5).all()


def test_gltf_in_and_out(tmp_path: Path):
    text = scene_gltf()
    data = swm.encode_scene(text, format="gltf", mode="lossless")
    doc = json.loads(data)
    assert doc["buffers"][0]["uri"].startswith("data:application/octet-stream;base64,")
    # The .gltf output decodes to the .glb one's scene.
    glb = swm.encode_scene(scene_glb(), mode="lossless")
    assert swm.decode_scene(data) == swm.decode_scene(glb)
    plain = json.loads(swm.decode_scene(data, format="gltf"))
    assert plain["nodes"] == scene_document()[0]["nodes"]
    # A .gltf whose buffer is a file beside it: read from its folder, or
    # from `base` when given as bytes.
    doc, bin_chunk = scene_document()
    doc["buffers"][0]["uri"] = "scene.bin"
    (tmp_path / "scene.bin").write_bytes(bin_chunk)
    (tmp_path / "scene.gltf").write_text(json.dumps(doc))
    from_path = swm.encode_scene(tmp_path / "scene.gltf", mode="lossless")
    assert from_path == glb
    assert swm.encode_scene((tmp_path / "scene.gltf").read_bytes(), base=tmp_path, mode="lossless") == glb
    with pytest.raises(swm.SwmError):
        swm.encode_scene((tmp_path / "scene.gltf").read_bytes(), mode="lossless")


def test_scene_info_lists_the_primitives():
    data = swm.encode_scene(scene_glb(), mode="lossless")
    info = swm.scene_info(data)
    assert [(p["mesh"], p["name"], p["swm_bytes"] is not None) for p in info] == [
        (0, "Donut", True), (1, "Ring", True), (2, "Wire", False)]
    assert info[0]["attributes"] == ["POSITION", "NORMAL", "TEXCOORD_0"]
    assert info[0]["vertices"] == 325 and info[0]["triangles"] == 576
    assert [p["swm_bytes"] for p in swm.scene_info(scene_glb())] == [None, None, None]


def test_scene_options_follow_encode(tmp_path: Path):
    source = scene_glb(lines=False)
    default, report = swm.encode_scene(source, report=True, mode="lossless")
    fine, fine_report = swm.encode_scene(source, report=True, mode="lossless", qt=16, qn=14)
    assert fine_report["primitives"][0]["bytes"] > report["primitives"][0]["bytes"]
    assert fine_report["primitives"][1]["bytes"] == report["primitives"][1]["bytes"]
    assert report["uncompressed"] == []
    for bad in ({"qt": 25}, {"qn": 3}, {"qg": 1}):
        with pytest.raises(swm.ParameterError):
            swm.encode_scene(source, **bad)
    with pytest.raises(ValueError, match="swing"):
        swm.encode_scene(source, mode="swing", qt=12)
    with pytest.raises(ValueError, match="at most one"):
        swm.encode_scene(source, bpv=2.0, size=1000)
    with pytest.raises(ValueError, match="format"):
        swm.encode_scene(source, format="obj")
    with pytest.raises(TypeError):
        swm.encode_scene(source, max_size=1000)  # the size is the whole scene's
    with pytest.raises(TypeError, match="bytes or the path"):
        swm.encode_scene(42)
    # A size is the budget of the scene's swm files.
    _, small = swm.encode_scene(source, report=True, size=1500)
    assert small["requested"] == 1500 and small["swm_bytes"] <= 1500 * 1.03


def test_bad_scenes_raise_typed_errors(tmp_path: Path):
    good = scene_glb()
    for bad in (b"", b"glTF", good[:40], good[: len(good) // 2], b"{not json", b"\0" * 64):
        with pytest.raises(swm.FormatError):
            swm.encode_scene(bad)
        with pytest.raises(swm.SwmError):
            swm.decode_scene(bad)
    cut = tmp_path / "cut.glb"
    cut.write_bytes(good[: len(good) // 2])
    with pytest.raises(swm.FormatError) as e:
        swm.encode_scene(cut)
    assert e.value.filename == str(cut) and "\n" not in str(e.value)
    with pytest.raises(swm.IoError) as e:
        swm.encode_scene(tmp_path / "missing.glb")
    assert e.value.filename == str(tmp_path / "missing.glb")
    # Already compressed: decode it first.
    coded = swm.encode_scene(good)
    with pytest.raises(swm.FormatError, match="already compressed"):
        swm.encode_scene(coded)
    # A coded scene whose swm bytes are damaged: an error, never a crash.
    doc, bin_chunk = parse_glb(coded)
    view = doc["bufferViews"][doc["meshes"][0]["primitives"][0]["extensions"]["SWM_mesh_compression"]["bufferView"]]
    start = view.get("byteOffset", 0)
    broken = bytearray(coded)
    at = coded.index(bin_chunk) + start
    for i in range(at + 8, at + view["byteLength"], 17):
        broken[i] ^= 0x5A
    with pytest.raises(swm.SwmError):
        swm.decode_scene(bytes(broken))
    # Limits bound what a document may make the decoder allocate.
    with pytest.raises(swm.LimitError):
        swm.decode_scene(coded, limits=swm.Limits(max_vertices=100))


def test_the_web_demos_scene():
    """web/demo's sample scene, compressed by swm: expanded, compressed
    again, expanded again, its scene the same."""
    sample = ROOT / "web" / "demo" / "sample-scene.glb"
    if not sample.is_file():
        pytest.skip(f"{sample} not found")
    assert any(p["swm_bytes"] for p in swm.scene_info(sample))
    with pytest.raises(swm.FormatError, match="already compressed"):
        swm.encode_scene(sample)
    plain = swm.decode_scene(sample)
    data, report = swm.encode_scene(plain, report=True, mode="lossless")
    assert any(p["coded"] for p in report["primitives"])
    again = swm.decode_scene(data)
    first, second = parse_glb(plain)[0], parse_glb(again)[0]
    for key in ("nodes", "materials", "scenes"):
        assert first.get(key) == second.get(key), key
    assert [len(m["primitives"]) for m in first["meshes"]] == [len(m["primitives"]) for m in second["meshes"]]

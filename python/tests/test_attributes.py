"""Attributes through the binding: texture coordinates, normals and
colours in and out of the lossless mode (format 1.2's ATTR), per vertex
in the split form, and into trimesh's visuals."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

import swm
from conftest import run_cli

AROUND, RINGS = 16, 6


def tube():
    """An open cylinder with a UV seam: column AROUND repeats column 0's
    positions with u = 1 instead of 0, as a UV-unwrapped mesh has it.
    Normals are radial. Returns (vertices, faces, {"uv", "normals"})."""
    angle = np.linspace(0.0, 2.0 * np.pi, AROUND + 1)
    angle[-1] = 0.0  # the seam column's positions are column 0's, bit for bit
    heights = np.linspace(0.0, 1.0, RINGS)
    v, uv, n = [], [], []
    for j, z in enumerate(heights):
        for i in range(AROUND + 1):
            c, s = np.cos(angle[i]), np.sin(angle[i])
            v.append((c, s, z))
            n.append((c, s, 0.0))
            uv.append((i / AROUND, j / (RINGS - 1)))
    f = []
    row = AROUND + 1
    for j in range(RINGS - 1):
        for i in range(AROUND):
            a, b = j * row + i, j * row + i + 1
            f += [(a, b, b + row), (a, b + row, a + row)]
    attrs = {"uv": np.array(uv, np.float32), "normals": np.array(n, np.float32)}
    return np.array(v, np.float32), np.array(f, np.uint32), attrs


def matches(v, attrs, want_v, want_attrs, tolerance):
    """Every decoded vertex has an input vertex within `tolerance` (per
    name, "position" for positions) in its position and every stream, and
    every input vertex is met that way: the same split mesh, whatever the
    vertex order."""
    assert sorted(attrs) == sorted(want_attrs)
    def close(a, av, b, bv):
        d = np.abs(a[:, None, :] - b[None, :, :]).max(axis=2) <= tolerance["position"]
        for k in av:
            d &= np.abs(av[k][:, None, :] - bv[k][None, :, :]).max(axis=2) <= tolerance[k]
        return d
    c = close(v, attrs, want_v, want_attrs)
    assert c.any(axis=1).all(), "a decoded vertex matches no input vertex"
    assert c.any(axis=0).all(), "an input vertex is missing from the decoded mesh"


TOLERANCE = {
    # qp 12 over an extent of 2; texture coordinates on 10 bits over [0, 1];
    # normals on 8 bits per octahedral coordinate, within about 1 degree.
    "position": 2.0 / 4095,
    "uv": 1.0 / 1023,
    "normals": 0.02,
    "colors": 1.0 / 255,
}


def test_python_encode_and_decode_round_trip_uv_and_normals():
    v, f, attrs = tube()
    data = swm.encode(v, f, mode="lossless", attributes=attrs)
    dv, df, dattrs = swm.decode(data, attributes=True)
    for k, a in dattrs.items():
        assert a.dtype == np.float32 and a.shape == (len(dv), attrs[k].shape[1]), k
    # The seam stays: its positions come once per side, as in the input.
    assert len(dv) == len(v) and len(df) == len(f)
    matches(dv, dattrs, v, attrs, TOLERANCE)
    # The mesh alone is `decode`'s, but for the seam's copies.
    plain_v, plain_f = swm.decode(data)
    assert len(plain_v) == len(v) - RINGS and len(plain_f) == len(f)
    # Normals computed from the surface come before the dict.
    nv, nf, normals, nattrs = swm.decode(data, normals=True, attributes=True)
    assert normals.shape == nv.shape and sorted(nattrs) == ["normals", "uv"]


def test_a_cli_encoded_obj_decodes_with_its_attributes(swm_bin, tmp_path: Path):
    v, f, attrs = tube()
    obj = tmp_path / "tube.obj"
    with open(obj, "w") as out:
        for p in v:
            out.write("v %r %r %r\n" % tuple(map(float, p)))
        for t in attrs["uv"]:
            out.write("vt %r %r\n" % tuple(map(float, t)))
        for n in attrs["normals"]:
            out.write("vn %r %r %r\n" % tuple(map(float, n)))
        for t in f + 1:
            out.write("f " + " ".join(f"{i}/{i}/{i}" for i in t) + "\n")
    run_cli(swm_bin, "encode", obj, "-o", tmp_path / "tube.swm", "--mode", "lossless")
    data = (tmp_path / "tube.swm").read_bytes()
    dv, df, dattrs = swm.decode(data, attributes=True)
    matches(dv, dattrs, v, attrs, TOLERANCE)
    # The Python encoder writes the CLI's bytes for the same streams
    # (whatever the dict's order), and `info` lists them as the CLI does.
    swapped = {"normals": attrs["normals"], "uv": attrs["uv"]}
    assert swm.encode(v, f, mode="lossless", attributes=attrs) == data
    assert swm.encode(v, f, mode="lossless", attributes=swapped) == data
    cli = json.loads(run_cli(swm_bin, "info", tmp_path / "tube.swm", "--json").stdout)
    assert swm.info(data)["attributes"] == cli["attributes"]
    assert [a["kind"] for a in cli["attributes"]] == ["normals", "texture coordinates 0"]


def test_colours_and_further_sets():
    v, f, attrs = tube()
    rgba = np.random.default_rng(7).random((len(v), 4)).astype(np.float32)
    # Same colour on both sides of the seam: colours have no seam here.
    rgba[AROUND :: AROUND + 1] = rgba[0 :: AROUND + 1]
    streams = {"colors": rgba, "uv1": attrs["uv"] * 2.0, "generic3": v[:, 2:3].copy()}
    data = swm.encode(v, f, mode="lossless", attributes=streams)
    dv, df, dattrs = swm.decode(data, attributes=True)
    tolerance = dict(TOLERANCE, uv1=2.0 / 1023, generic3=1.0 / 255)
    matches(dv, dattrs, v, streams, tolerance)


def test_a_file_without_attributes_decodes_the_same_either_way(generated_corpus: Path):
    v, f = swm.read(generated_corpus / "torus.obj")
    data = swm.encode(v, f, mode="lossless")
    av, af, attrs = swm.decode(data, attributes=True)
    bv, bf = swm.decode(data)
    assert attrs == {} and av.tobytes() == bv.tobytes() and af.tobytes() == bf.tobytes()
    # An empty dict asks for nothing: the same bytes.
    assert swm.encode(v, f, mode="lossless", attributes={}) == data


def test_lossy_modes_keep_the_attributes():
    v, f, attrs = tube()
    # The tube's radial normals follow its surface: a lossy encode (the
    # automatic mode, the lossless mode with a size, which simplifies)
    # leaves them to the decoder, which recomputes them.
    for options, kept in (
        ({"bpv": 24}, ["uv"]),
        ({"mode": "lossless", "bpv": 24}, ["uv"]),
    ):
        data, report = swm.encode(v, f, attributes=attrs, report=True, **options)
        dv, df, dattrs = swm.decode(data, attributes=True)
        assert sorted(dattrs) == kept, options
        assert report["method"] in ("simplified", "lossless"), options
        # The seam stays: no face spans it (u near 0 beside u near 1).
        u = dattrs["uv"][:, 0][df]
        assert (u.max(axis=1) - u.min(axis=1) < 0.5).all(), options


def test_bad_attributes_are_refused():
    v, f, attrs = tube()
    with pytest.raises(ValueError, match="swing or displaced"):
        swm.encode(v, f, mode="swing", attributes=attrs)
    for bad in ("uv0", "normal", "colors01", "generic"):
        with pytest.raises(ValueError, match="unknown attribute"):
            swm.encode(v, f, mode="lossless", attributes={bad: attrs["uv"]})
    with pytest.raises(ValueError, match="rows"):
        swm.encode(v, f, mode="lossless", attributes={"uv": attrs["uv"][:-1]})
    with pytest.raises(ValueError, match="columns"):
        swm.encode(v, f, mode="lossless", attributes={"normals": attrs["uv"]})
    with pytest.raises(TypeError):
        swm.encode(v, f, mode="lossless", attributes=[attrs["uv"]])
    nan = attrs["uv"].copy()
    nan[3, 0] = np.nan
    with pytest.raises(swm.SwmError):
        swm.encode(v, f, mode="lossless", attributes={"uv": nan})


def test_truncated_attribute_files_raise_swm_errors():
    v, f, attrs = tube()
    data = swm.encode(v, f, mode="lossless", attributes=attrs)
    for cut in range(0, len(data), 7):
        with pytest.raises(swm.SwmError):
            swm.decode(data[:cut], attributes=True)


def test_trimesh_gets_normals_and_visuals():
    trimesh = pytest.importorskip("trimesh", reason="trimesh not installed (pip install trimesh)")
    v, f, attrs = tube()
    dv, df, dattrs = swm.decode(swm.encode(v, f, mode="lossless", attributes=attrs), attributes=True)
    mesh = swm.to_trimesh(dv, df, attributes=dattrs)
    assert isinstance(mesh.visual, trimesh.visual.TextureVisuals)
    assert np.array_equal(mesh.visual.uv, dattrs["uv"])
    assert np.allclose(mesh.vertex_normals, dattrs["normals"], atol=1e-2)
    assert len(mesh.vertices) == len(dv)  # nothing merged at the seam

    rgb = np.tile(np.array([[1.0, 0.5, 0.0]], np.float32), (len(v), 1))
    dv, df, dattrs = swm.decode(
        swm.encode(v, f, mode="lossless", attributes={"colors": rgb}), attributes=True
    )
    mesh = swm.to_trimesh(dv, df, attributes=dattrs)
    assert isinstance(mesh.visual, trimesh.visual.ColorVisuals)
    got = mesh.visual.vertex_colors[:, :3].astype(int)
    assert (np.abs(got - [255, 128, 0]) <= 1).all()

"""Attributes through the binding: texture coordinates, normals and
colours in and out of the lossless mode (format 1.2's ATTR), per vertex
in the split form, and into trimesh's visuals."""

from __future__ import annotations

import json
import subprocess
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


def test_retiled_and_displaced_files_keep_colours(generated_corpus: Path):
    """SwingWrapper and displaced subdivision make their own vertices and
    resample the colours there from the input: a colour linear in the
    height stays so at every decoded vertex."""
    v, f = swm.read(generated_corpus / "torus.obj")
    lo, hi = v[:, 2].min(), v[:, 2].max()
    height = lambda p: np.clip((p[:, 2:3] - lo) / (hi - lo), 0.0, 1.0)
    colours = np.repeat(height(v), 3, axis=1).astype(np.float32)
    for mode in ("swing", "displaced"):
        data, report = swm.encode(v, f, mode=mode, bpv=16.0, attributes={"colors": colours},
                                  report=True)
        assert report["method"] == mode and report["attributes"]["kept"] == ["colors"], report
        dv, df, dattrs = swm.decode(data, attributes=True)
        assert sorted(dattrs) == ["colors"], mode
        # The colour read where a decoded vertex stands on the input:
        # within a quantization step and the distance the vertex moves off
        # the input's faces.
        assert np.abs(dattrs["colors"] - height(dv)).max() < 0.05, mode


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


def tube_obj(path: Path) -> Path:
    """The tube as an OBJ with its `vt` and `vn`, for the command line."""
    v, f, attrs = tube()
    with open(path, "w") as out:
        for p in v:
            out.write("v %r %r %r\n" % tuple(map(float, p)))
        for t in attrs["uv"]:
            out.write("vt %r %r\n" % tuple(map(float, t)))
        for n in attrs["normals"]:
            out.write("vn %r %r %r\n" % tuple(map(float, n)))
        for t in f + 1:
            out.write("f " + " ".join(f"{i}/{i}/{i}" for i in t) + "\n")
    return path


# The CLI's names of the streams (`--json`'s attribute_report) and the
# binding's (the keys of the attributes dict).
CLI_NAMES = {"normals": "normals", "texture coordinates 0": "uv"}


def test_the_report_says_which_attributes_were_kept_and_why():
    v, f, attrs = tube()
    # The tube's radial normals follow its surface: a lossy file leaves
    # them to the decoder and says so, with the angle it measured.
    _, report = swm.encode(v, f, attributes=attrs, bpv=24, report=True)
    a = report["attributes"]
    assert a["kept"] == ["uv"] and a["dropped"] == ["normals"], a
    why = a["dropped_because"]
    assert why["reason"] == "smooth_normals" and 0 <= why["rms_degrees"] < 10, why
    assert "normals follow the geometry" in why["message"]
    # A lossy file that keeps the UVs measures them, in texels of 1024².
    e = a["texcoord_error"]
    assert e["texture_size"] == 1024 and e["samples"] > 0
    assert 0 <= e["rms_texels"] <= e["max_texels"] < 2, e
    # keep_normals keeps them, as --keep-normals does.
    data, report = swm.encode(v, f, attributes=attrs, bpv=24, report=True, keep_normals=True)
    a = report["attributes"]
    assert (a["kept"], a["dropped"], a["dropped_because"]) == (["normals", "uv"], [], None)
    assert sorted(swm.decode(data, attributes=True)[2]) == ["normals", "uv"]
    # The lossless mode keeps every stream and measures nothing.
    _, report = swm.encode(v, f, attributes=attrs, mode="lossless", report=True)
    assert report["attributes"] == {
        "kept": ["normals", "uv"], "dropped": [], "dropped_because": None, "texcoord_error": None}
    # A size below the smallest file with the streams: the surface alone,
    # and the report names that smallest size.
    data, report = swm.encode(v, f, attributes=attrs, size=80, report=True)
    a = report["attributes"]
    assert a["kept"] == [] and sorted(a["dropped"]) == ["normals", "uv"], a
    why = a["dropped_because"]
    assert why["reason"] == "no_room" and why["smallest"] > 80 and str(why["smallest"]) in why["message"]
    assert swm.decode(data, attributes=True)[2] == {} and len(data) <= 80
    # Without attributes, an empty report of the same shape.
    _, report = swm.encode(v, f, bpv=24, report=True)
    assert report["attributes"] == {"kept": [], "dropped": [], "dropped_because": None, "texcoord_error": None}


def test_the_attribute_report_is_the_clis(swm_bin, tmp_path: Path):
    v, f, attrs = tube()
    obj = tube_obj(tmp_path / "tube.obj")
    for options, flags in (({"bpv": 24}, ["--bpv", "24"]),
                           ({"bpv": 24, "keep_normals": True}, ["--bpv", "24", "--keep-normals"]),
                           ({"size": 80}, ["--size", "80"])):
        out = run_cli(swm_bin, "encode", obj, "-o", tmp_path / "t.swm", "--json", *flags)
        cli = json.loads(out.stdout)["attribute_report"]
        data, report = swm.encode(v, f, attributes=attrs, report=True, **options)
        assert data == (tmp_path / "t.swm").read_bytes(), options
        a = report["attributes"]
        assert a["kept"] == [CLI_NAMES[k] for k in cli["kept"]], options
        assert a["dropped"] == [CLI_NAMES[k] for k in cli["dropped"]], options
        assert (a["dropped_because"] or {}).get("message") == cli["dropped_because"], options
        assert a["texcoord_error"] == cli["texcoord_error"], options


def test_quantization_bits_are_the_clis(swm_bin, tmp_path: Path):
    v, f, attrs = tube()
    obj = tube_obj(tmp_path / "tube.obj")
    default = swm.encode(v, f, mode="lossless", attributes=attrs)
    # The defaults are swm encode's: 8, 10, 8.
    assert swm.encode(v, f, mode="lossless", attributes=attrs, qn=8, qt=10, qg=8) == default
    fine = swm.encode(v, f, mode="lossless", attributes=attrs, qn=12, qt=14)
    run_cli(swm_bin, "encode", obj, "-o", tmp_path / "fine.swm", "--mode", "lossless", "--qn", "12", "--qt", "14")
    assert fine == (tmp_path / "fine.swm").read_bytes() and len(fine) > len(default)
    info = {a["kind"]: a["bits"] for a in swm.info(fine)["attributes"]}
    assert info == {"normals": 12, "texture coordinates 0": 14}
    # Finer bits, closer texture coordinates: within half a step of 2^14 - 1.
    dv, df, dattrs = swm.decode(fine, attributes=True)
    matches(dv, dattrs, v, attrs, dict(TOLERANCE, uv=0.5 / (2**14 - 1) + 1e-6, normals=0.002))
    coarse = swm.encode(v, f, mode="lossless", attributes=attrs, qt=4)
    u = swm.decode(coarse, attributes=True)[2]["uv"]
    assert len(np.unique(u[:, 0])) <= 16
    # qg sets colours (and generic streams).
    rgb = np.random.default_rng(3).random((len(v), 3)).astype(np.float32)
    q4 = swm.encode(v, f, mode="lossless", attributes={"colors": rgb}, qg=4)
    assert {a["kind"]: a["bits"] for a in swm.info(q4)["attributes"]} == {"colours 0": 4}
    # The automatic mode takes them too.
    data = swm.encode(v, f, attributes=attrs, bpv=24, qt=12, keep_normals=True)
    assert {a["kind"]: a["bits"] for a in swm.info(data)["attributes"]}["texture coordinates 0"] == 12


def test_quantization_bits_out_of_range_are_refused(swm_bin, tmp_path: Path):
    v, f, attrs = tube()
    obj = tube_obj(tmp_path / "tube.obj")
    for name, bad, low, high in (("qn", 3, 4, 16), ("qn", 17, 4, 16), ("qt", 1, 2, 24), ("qt", 25, 2, 24),
                                 ("qg", 0, 2, 24), ("qg", 25, 2, 24), ("qn", -1, 4, 16)):
        # Refused whatever the mesh's streams, as the command line's parser does.
        for streams in (attrs, None):
            with pytest.raises(swm.ParameterError, match=f"^{name} = {bad}: must be between {low} and {high}$"):
                swm.encode(v, f, mode="lossless", attributes=streams, **{name: bad})
        out = subprocess.run([str(swm_bin), "encode", str(obj), "-o", str(tmp_path / "x.swm"), "--mode",
                              "lossless", f"--{name}={bad}"], capture_output=True)
        assert out.returncode == 2 and f"{low}..={high}" in out.stderr.decode(), out.stderr
    assert not (tmp_path / "x.swm").exists()
    # The swing mode codes no texture coordinates: their bits are
    # refused; the others it takes.
    with pytest.raises(ValueError, match="swing"):
        swm.encode(v, f, mode="swing", qt=12)
    colours = {"colors": np.repeat(v[:, 2:3], 3, axis=1).astype(np.float32)}
    for extra in ({"qn": 8}, {"qg": 10}, {"keep_normals": True}):
        swm.encode(v, f, mode="swing", bpv=24.0, attributes=colours, **extra)
    fine = swm.encode(v, f, mode="swing", bpv=24.0, attributes=colours, qg=12, report=True)[1]
    assert fine["attributes"]["kept"] == ["colors"], fine
    with pytest.raises(TypeError):
        swm.encode(v, f, mode="lossless", qt=10.5)


def test_read_gives_the_files_attributes(swm_bin, tmp_path: Path):
    v, f, attrs = tube()
    obj = tube_obj(tmp_path / "tube.obj")
    rv, rf, rattrs = swm.read(obj, attributes=True)
    assert sorted(rattrs) == ["normals", "uv"] and len(rf) == len(f)
    matches(rv, rattrs, v, attrs, {"position": 1e-6, "uv": 1e-6, "normals": 1e-6})
    # Without attributes: the raw mesh, as before.
    pv, pf = swm.read(obj)
    assert pv.shape == v.shape and np.array_equal(pf, f)
    # What swm.encode makes of them is swm encode's file of the OBJ.
    for options, flags in (({"mode": "lossless"}, ["--mode", "lossless"]), ({"bpv": 24}, ["--bpv", "24"])):
        run_cli(swm_bin, "encode", obj, "-o", tmp_path / "t.swm", *flags)
        assert swm.encode(rv, rf, attributes=rattrs, **options) == (tmp_path / "t.swm").read_bytes(), options
    # A `vt` on some corners only: not attached, and said so.
    part = tmp_path / "part.obj"
    part.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 1 1 0\nvt 0 0\nf 1/1 2/1 3/1\nf 2 4 3\n")
    with pytest.warns(UserWarning, match=r"part\.obj: texture coordinates not read"):
        _, _, got = swm.read(part, attributes=True)
    assert got == {}


def test_read_attributes_of_the_shared_corpus(shared_corpus: Path, swm_bin, tmp_path: Path):
    """spot's texture coordinates (with seams), suzanne's and beetle's
    normals, read as swm encode reads them: the same bytes."""
    spot = shared_corpus / "spot.obj"
    v, f, attrs = swm.read(spot, attributes=True)
    assert sorted(attrs) == ["uv"] and attrs["uv"].shape == (len(v), 2)
    # The seams: some positions come once per side.
    assert len(v) > len(np.unique(v, axis=0))
    data, report = swm.encode(v, f, attributes=attrs, bpv=2, report=True)
    run_cli(swm_bin, "encode", spot, "-o", tmp_path / "spot.swm", "--bpv", "2")
    assert data == (tmp_path / "spot.swm").read_bytes()
    assert report["attributes"]["kept"] == ["uv"] and report["attributes"]["texcoord_error"] is not None
    for name in ("suzanne.obj", "beetle.obj"):
        v, f, attrs = swm.read(shared_corpus / name, attributes=True)
        assert sorted(attrs) == ["normals"], name
        run_cli(swm_bin, "encode", shared_corpus / name, "-o", tmp_path / "m.swm", "--mode", "lossless")
        assert swm.encode(v, f, attributes=attrs, mode="lossless") == (tmp_path / "m.swm").read_bytes(), name



def test_normals_that_crowd_the_surface_out(shared_corpus: Path, swm_bin, tmp_path: Path):
    """beetle's crease normals at 454 bytes: the file without them, the
    reason and its figures in the report, the CLI's bytes; kept when
    asked to."""
    v, f, attrs = swm.read(shared_corpus / "beetle.obj", attributes=True)
    data, report = swm.encode(v, f, attributes=attrs, size=454, report=True)
    why = report["attributes"]["dropped_because"]
    assert report["attributes"]["dropped"] == ["normals"]
    assert why["reason"] == "costly_normals"
    assert 10.0 < why["rms_degrees"] < 15.0
    assert why["l2_kept"] > 4 * report["check"]["l2_relative"]
    run_cli(swm_bin, "encode", shared_corpus / "beetle.obj", "-o", tmp_path / "b.swm", "--size", "454")
    assert data == (tmp_path / "b.swm").read_bytes()
    _, kept = swm.encode(v, f, attributes=attrs, size=454, keep_normals=True, report=True)
    assert kept["attributes"]["kept"] == ["normals"]

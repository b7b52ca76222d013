"""swm: lossy triangle-mesh compression by SwingWrapper remeshing.

The functions call the Rust library directly (the extension module
``swm._swm``), not the command line; the GIL is released while they work.
Meshes are NumPy arrays: vertices ``(n, 3)`` float32, faces ``(m, 3)``
uint32. Inputs of another float or integer dtype are converted (float64
positions are rounded to float32, as the codec stores them); other dtypes
and shapes raise ``TypeError`` / ``ValueError`` saying what was expected.

Defaults are those of ``swm encode``: the same mesh and options give the
same ``.swm`` bytes as the command line, and :func:`decode` gives the mesh
``swm decode`` writes, bit for bit.
"""

from __future__ import annotations

import os
from typing import Any, Literal, Mapping, Optional, Tuple, Union, overload

import numpy as np
import numpy.typing as npt

from . import _swm
from ._swm import Limits
from .reports import (
    AttributeReport,
    AttributesDropped,
    EncodeReport,
    PrimitiveReport,
    SceneDecodeReport,
    ScenePrimitive,
    SceneReport,
    TexcoordError,
)
from .errors import (
    FormatError,
    IoError,
    LimitError,
    ParameterError,
    RetileError,
    SizeError,
    SwmError,
    TopologyError,
    UnsupportedError,
)

__version__: str = _swm.__version__

Vertices = npt.NDArray[np.float32]
Faces = npt.NDArray[np.uint32]
Normals = npt.NDArray[np.float32]
#: One attribute stream, ``(n, dims)`` float32, one row per vertex.
Attribute = npt.NDArray[np.float32]
#: Attribute streams by name (``"normals"``, ``"uv"``, ``"colors"``, ...).
Attributes = Mapping[str, npt.ArrayLike]
#: A mesh as ``(vertices, faces)``, or any object with ``vertices`` and
#: ``faces`` attributes (a ``trimesh.Trimesh``, for one).
MeshLike = Any
BytesLike = Union[bytes, bytearray, memoryview]
PathLike = Union[str, "os.PathLike[str]"]

_U32_MAX = np.iinfo(np.uint32).max


def _vertices(array: Any, what: str = "vertices") -> Vertices:
    """``array`` as C-contiguous float32 ``(n, 3)``, or a clear error."""
    a = np.asarray(array)
    if a.dtype.kind != "f":
        raise TypeError(
            f"{what} must be a floating-point array of shape (n, 3) "
            f"(float32 preferred), got dtype {a.dtype}"
        )
    if a.ndim != 2 or a.shape[1] != 3:
        raise ValueError(f"{what} must have shape (n, 3), got shape {a.shape}")
    return np.ascontiguousarray(a, dtype=np.float32)


def _faces(array: Any, what: str = "faces") -> Faces:
    """``array`` as C-contiguous uint32 ``(m, 3)``, or a clear error."""
    a = np.asarray(array)
    if a.dtype.kind not in "iu":
        raise TypeError(
            f"{what} must be an integer array of shape (m, 3) "
            f"(uint32 preferred), got dtype {a.dtype}"
        )
    if a.ndim != 2 or a.shape[1] != 3:
        raise ValueError(f"{what} must have shape (m, 3), got shape {a.shape}")
    if a.dtype != np.uint32 and a.size:
        low, high = int(a.min()), int(a.max())
        if low < 0 or high > _U32_MAX:
            bad = low if low < 0 else high
            raise ValueError(f"{what} holds vertex index {bad}, outside 0..{_U32_MAX}")
    return np.ascontiguousarray(a, dtype=np.uint32)


def _attributes(attributes: Any) -> "dict[str, Attribute]":
    """A dict of attribute arrays as C-contiguous float32 ``(n, dims)``."""
    if not isinstance(attributes, Mapping):
        raise TypeError(f"attributes must be a dict of arrays, got {type(attributes).__name__}")
    out = {}
    for name, array in attributes.items():
        a = np.asarray(array)
        if a.dtype.kind not in "fiu":
            raise TypeError(f"attribute {name!r} must be a float array, got dtype {a.dtype}")
        if a.ndim != 2:
            raise ValueError(f"attribute {name!r} must have shape (n, dims), got shape {a.shape}")
        out[name] = np.ascontiguousarray(a, dtype=np.float32)
    return out


def _bytes(data: Any) -> bytes:
    if isinstance(data, bytes):
        return data
    if isinstance(data, (bytearray, memoryview)):
        return bytes(data)
    raise TypeError(f"data must be bytes, bytearray or memoryview, got {type(data).__name__}")


def _mesh(mesh: MeshLike, what: str) -> Tuple[Vertices, Faces]:
    if hasattr(mesh, "vertices") and hasattr(mesh, "faces"):
        v, f = mesh.vertices, mesh.faces
    else:
        try:
            v, f = mesh
        except (TypeError, ValueError):
            raise TypeError(
                f"{what} must be a (vertices, faces) pair or have .vertices and .faces, "
                f"got {type(mesh).__name__}"
            ) from None
    return _vertices(v, f"{what} vertices"), _faces(f, f"{what} faces")


@overload
def encode(
    vertices: npt.ArrayLike,
    faces: npt.ArrayLike,
    *,
    bpv: Optional[float] = None,
    size: Optional[int] = None,
    edge_length: Optional[float] = None,
    mode: str = "auto",
    max_size: Optional[int] = None,
    angle_bits: Optional[int] = None,
    qp: Optional[int] = None,
    report: Literal[False] = False,
    effort: str = "default",
    max_error: Optional[float] = None,
    attributes: Optional[Attributes] = None,
    qn: Optional[int] = None,
    qt: Optional[int] = None,
    qg: Optional[int] = None,
    keep_normals: bool = False,
    or_smallest: bool = False,
) -> bytes: ...


@overload
def encode(
    vertices: npt.ArrayLike,
    faces: npt.ArrayLike,
    *,
    bpv: Optional[float] = None,
    size: Optional[int] = None,
    edge_length: Optional[float] = None,
    mode: str = "auto",
    max_size: Optional[int] = None,
    angle_bits: Optional[int] = None,
    qp: Optional[int] = None,
    report: Literal[True],
    effort: str = "default",
    max_error: Optional[float] = None,
    attributes: Optional[Attributes] = None,
    qn: Optional[int] = None,
    qt: Optional[int] = None,
    qg: Optional[int] = None,
    keep_normals: bool = False,
    or_smallest: bool = False,
) -> Tuple[bytes, EncodeReport]: ...


@overload
def encode(
    vertices: npt.ArrayLike,
    faces: npt.ArrayLike,
    *,
    bpv: Optional[float] = None,
    size: Optional[int] = None,
    edge_length: Optional[float] = None,
    mode: str = "auto",
    max_size: Optional[int] = None,
    angle_bits: Optional[int] = None,
    qp: Optional[int] = None,
    report: bool,
    effort: str = "default",
    max_error: Optional[float] = None,
    attributes: Optional[Attributes] = None,
    qn: Optional[int] = None,
    qt: Optional[int] = None,
    qg: Optional[int] = None,
    keep_normals: bool = False,
    or_smallest: bool = False,
) -> Union[bytes, Tuple[bytes, EncodeReport]]: ...


def encode(
    vertices: npt.ArrayLike,
    faces: npt.ArrayLike,
    *,
    bpv: Optional[float] = None,
    size: Optional[int] = None,
    edge_length: Optional[float] = None,
    mode: str = "auto",
    max_size: Optional[int] = None,
    angle_bits: Optional[int] = None,
    qp: Optional[int] = None,
    report: bool = False,
    effort: str = "default",
    max_error: Optional[float] = None,
    attributes: Optional[Attributes] = None,
    qn: Optional[int] = None,
    qt: Optional[int] = None,
    qg: Optional[int] = None,
    keep_normals: bool = False,
    or_smallest: bool = False,
) -> Union[bytes, Tuple[bytes, EncodeReport]]:
    """Cleans and encodes a mesh into the bytes of a ``.swm`` file.

    The options and defaults are those of ``swm encode``. The target is
    one of ``bpv`` (bits per input vertex; 2 when no target is given),
    ``size`` (bytes), ``edge_length`` (the retiling edge L) or
    ``max_error`` (the smallest file whose L2 distance to the input is at
    most this, relative to the bounding-box diagonal: ``2e-4``; modes
    ``"auto"`` and ``"lossless"``); ``max_size`` is a size in bytes never
    to exceed. ``effort`` is ``"fast"``, ``"default"`` or ``"max"``, as
    ``swm encode --effort``: which methods the automatic mode weighs and
    how far each searches. ``mode`` is:

    * ``"auto"`` (the default): the methods of the effort level
      (SwingWrapper retiling where it fits the level's budget, quadric
      simplification then lossless coding, displaced subdivision at low
      rates, and at ``"max"`` every one of them and a method per
      component) at the target size; each is decoded and measured against
      the input (L2) and the closest is written. A retiling that fails
      falls back to the simplified file.
      With ``edge_length``, the simplified candidate gets the retiled
      file's size. Takes no ``angle_bits`` and no ``qp`` (the encoder
      chooses them): a ``ValueError`` says so.
    * ``"swing"``: SwingWrapper retiling only, ``size`` met within 3%,
      with ``angle_bits`` bits per dihedral angle (by default chosen as
      ``swm encode`` does: 6, or 5 when rate control finds the angles
      spread widely). Takes no ``qp``.
    * ``"displaced"``: displaced subdivision only (format 1.2): a
      simplified base, levels of 1-to-4 subdivision and one scalar per
      new vertex, at ``size`` or ``bpv`` within 3%; ``decode``'s
      ``max_level`` decodes a coarser level. Takes no ``qp``,
      ``angle_bits``, ``edge_length``, ``max_error`` or ``qt``.
    * ``"lossless"``: without ``size`` or ``bpv``, the input's own
      triangles with positions on ``qp`` bits (default 12; ``max_size``
      refused). With ``size`` or ``bpv``, the mesh is first simplified
      (greedy quadric edge collapse) to the largest face count and the
      quantization that fit the size, ``max_size`` included; ``qp`` is
      then refused. ``edge_length`` and ``angle_bits`` are refused.

    A size no file can meet raises :class:`SizeError` (which names the
    smallest possible size), unless ``or_smallest=True``, which writes
    that smallest file instead (the report's ``smallest_instead`` then
    holds ``requested`` and ``smallest``, as ``swm encode --or-smallest``); options the mode has no use for raise
    ``ValueError``. With ``report=True`` the result is ``(bytes, report)``,
    ``report`` a dict: ``method``, what made the file (``"swing"``,
    ``"simplified"``, ``"displaced"``, ``"mixed"``, a method per
    component, or ``"lossless"``); ``choice``, in the automatic mode, the ``method``
    object of ``swm encode --json`` (``chosen``, ``effort``, each
    candidate of the level under its method's name as
    ``{"bytes", "l2_rel"}`` or ``None``, ``<name>_failure``, why it
    made no file, or ``None``, and ``candidates``, the same in the
    chooser's order as ``{"method", "file", "failure"}``),
    else ``None``; ``simplified``, when a simplified file was written,
    ``{"input_faces", "faces", "qp"}``, else ``None``; ``check``, the
    file decoded and measured against the input as ``swm distance``
    measures it (``decoded_vertices``, ``decoded_triangles``,
    ``area_ratio``, ``l2_relative``, ``hausdorff_relative``,
    ``samples``), ``None`` in the lossless mode at a fixed ``qp``;
    ``attributes``, what became of the ``attributes`` given
    (:class:`swm.reports.AttributeReport`, ``swm encode --json``'s
    ``attribute_report``): ``kept`` and ``dropped``, lists of their keys
    (``"normals"``, ``"uv"``, ...); ``dropped_because``, ``None`` or a
    dict whose ``reason`` is ``"smooth_normals"`` (the normals follow the
    geometry within ``rms_degrees`` RMS, so a lossy file leaves them to
    the decoder to recompute; ``keep_normals=True`` keeps them),
    ``"costly_normals"`` (normals of their own that, at this size, cost
    the surface more than they give; ``l2_kept`` is the L2 of the file
    that kept them; ``keep_normals=True`` keeps them),
    ``"no_room"`` (the size is below ``smallest``, the smallest file
    that keeps them) or ``"method"`` (a ``method`` whose file cannot
    carry them), with the library's sentence in ``message``;
    ``texcoord_error``, for a lossy file that keeps ``"uv"``, the decoded
    texture coordinates' error (``rms_texels``, ``max_texels`` of a
    ``texture_size``² texture, ``samples``), else ``None``. Without
    ``attributes`` it is ``{"kept": [], "dropped": [],
    "dropped_because": None, "texcoord_error": None}``.

    ``attributes`` (any mode, with or without a size; ``"swing"`` and
    ``"displaced"`` refuse texture coordinates, which their files cannot
    carry, and resample the others at their own vertices) is a dict
    of per-vertex float arrays, one row per vertex, as
    ``decode(..., attributes=True)`` returns them: ``"normals"`` (n, 3),
    ``"uv"`` (n, 2) and further sets ``"uv1"``, ...; ``"colors"`` (n, 3)
    or (n, 4) in 0..1 and ``"colors1"``, ...; ``"generic0"``, ... (n, 1
    to 4). They are coded in the file's ``ATTR`` section (format 1.2),
    quantized as ``qn``, ``qt`` and ``qg`` say; vertices that differ only
    by their values (a UV seam) stay apart. A lossy file simplifies the
    mesh with them, never across a seam, and its size counts their bytes;
    normals that follow the geometry are left for the decoder to
    recompute unless ``keep_normals=True`` (the report's ``attributes``
    says what was kept).

    ``qn``, ``qt`` and ``qg`` are the bits of the attribute quantization,
    as ``swm encode --qn --qt --qg`` and Draco's ``-qn -qt -qg``, with
    their defaults and ranges: ``qn`` bits per octahedral coordinate of a
    normal (default 8, 4 to 16), ``qt`` bits per texture coordinate
    (default 10: a texel of a 1024² texture over a unit chart; 2 to 24),
    ``qg`` bits per colour or generic component (default 8, 2 to 24). A
    value outside its range raises :class:`ParameterError` naming it,
    whatever streams the mesh has; ``mode="swing"`` takes no ``qt``
    (``ValueError``: its files carry no texture coordinates).

    Deterministic: the same arrays and options give the same bytes.
    """
    return _swm.encode(
        _vertices(vertices),
        _faces(faces),
        bpv=bpv,
        size=size,
        edge_length=edge_length,
        mode=mode,
        max_size=max_size,
        angle_bits=angle_bits,
        qp=qp,
        report=report,
        effort=effort,
        max_error=max_error,
        attributes=None if attributes is None else _attributes(attributes),
        qn=qn,
        qt=qt,
        qg=qg,
        keep_normals=keep_normals,
        or_smallest=or_smallest,
    )


def decode(
    data: BytesLike,
    *,
    sharpen: Optional[bool] = None,
    bend: Optional[int] = None,
    normals: bool = False,
    limits: Optional[Limits] = None,
    max_level: Optional[int] = None,
    attributes: bool = False,
) -> Tuple[Any, ...]:
    """Decodes ``.swm`` bytes into ``(vertices, faces)``.

    ``sharpen=True`` restores the sharp edges and corners retiling
    chamfered (EdgeSharpener); ``bend=N`` subdivides N times after that
    (Bender, four times the triangles per step). Left ``None``, each
    follows the file's post-processing hint (``info(data)["post"]``), the
    encoder's measured choice; a file without one decodes plain. ``normals=True`` adds a
    third array of unit vertex normals, computed from the surface.
    ``attributes=True`` adds, last, a dict of the file's attribute
    streams (a lossless file's texture coordinates, normals and colours;
    empty for a file without them): ``"normals"`` (n, 3), ``"uv"`` (n, 2),
    ``"colors"`` (n, 3) or (n, 4), further sets ``"uv1"``, ``"colors1"``,
    ..., and ``"generic0"``, ..., all float32 with one row per vertex.
    The mesh is then in the split form GPUs and trimesh use: a vertex per
    distinct position and values, so a position on a UV seam comes once
    per side (a file without streams decodes to the same arrays either
    way). :func:`to_trimesh` takes the dict. Every byte is treated as
    hostile: a bad file raises :class:`FormatError` (or another
    :class:`SwmError`) and nothing beyond ``limits`` is allocated.
    ``max_level=N`` decodes only the first N subdivision levels of a
    displaced-subdivision file (0: its base mesh), as ``swm decode
    --max-level N``; ``None`` decodes every level, and other modes
    ignore it.
    """
    return _swm.decode(
        _bytes(data),
        sharpen=sharpen,
        bend=bend,
        normals=normals,
        limits=limits,
        max_level=max_level,
        attributes=attributes,
    )


def info(data: BytesLike, *, limits: Optional[Limits] = None) -> "dict[str, Any]":
    """A ``.swm`` file's figures without decoding its geometry: the keys
    and values ``swm info --json`` prints (mode, version, counts, bits per
    triangle and per vertex, sections, CLERS histogram, ...)."""
    return _swm.info(_bytes(data), limits=limits)


def distance(
    a: MeshLike,
    b: MeshLike,
    *,
    samples: Optional[int] = None,
    sampling: str = "metro",
) -> "dict[str, Any]":
    """Metro distance between mesh ``a`` (the reference) and mesh ``b``,
    with the keys of ``swm distance --json``: ``l2``, ``hausdorff``,
    ``mean``, ``l2_relative``, ``hausdorff_relative`` (over a's bounding
    box diagonal), ``diagonal``, and the one-sided ``forward`` (a to b) and
    ``backward`` figures. ``samples`` is the number of face samples per
    surface (default: ten per face of the larger mesh); ``sampling`` is
    ``"metro"`` (vertices, edges and faces) or ``"faces"`` (area-uniform
    face samples only)."""
    av, af = _mesh(a, "a")
    bv, bf = _mesh(b, "b")
    return _swm.distance(av, af, bv, bf, samples=samples, sampling=sampling)


#: Why :func:`read` did not attach attributes a file carries, after their names.
_UNREAD = "not read: not every face corner names them, or a value is malformed"


@overload
def read(
    path: PathLike, *, limits: Optional[Limits] = None, attributes: Literal[False] = False
) -> Tuple[Vertices, Faces]: ...


@overload
def read(
    path: PathLike, *, limits: Optional[Limits] = None, attributes: Literal[True]
) -> Tuple[Vertices, Faces, "dict[str, Attribute]"]: ...


@overload
def read(
    path: PathLike, *, limits: Optional[Limits] = None, attributes: bool
) -> Union[Tuple[Vertices, Faces], Tuple[Vertices, Faces, "dict[str, Attribute]"]]: ...


def read(
    path: PathLike, *, limits: Optional[Limits] = None, attributes: bool = False
) -> Union[Tuple[Vertices, Faces], Tuple[Vertices, Faces, "dict[str, Attribute]"]]:
    """Reads a mesh file (.obj, .ply, .off, .stl, .gltf, .glb; the extension picks the
    format) as ``swm encode`` reads it: the raw mesh, polygons
    fan-triangulated, nothing merged.

    ``attributes=True`` adds, last, the file's attribute streams as
    :func:`decode` gives them (``"normals"``, ``"uv"``, ``"colors"``,
    ...; OBJ ``vt``/``vn``/vertex colours, PLY, OFF and glTF
    ``NORMAL``/``TEXCOORD_n``/``COLOR_0``), the mesh then in the split
    form (a vertex per distinct position and values, so a position on a UV
    seam comes once per side): what :func:`encode` takes as
    ``attributes``. Attributes the file carries that cannot be attached
    (not every face corner names them, a malformed value) are named in a
    ``UserWarning``, as ``swm encode`` names them on standard error."""
    if not attributes:
        return _swm.read(os.fspath(path), limits=limits)
    v, f, streams, dropped = _swm.read(os.fspath(path), limits=limits, attributes=True)
    if dropped:
        import warnings

        warnings.warn(f"{os.fspath(path)}: {', '.join(dropped)} {_UNREAD}", UserWarning, stacklevel=2)
    return v, f, streams


def write(path: PathLike, vertices: npt.ArrayLike, faces: npt.ArrayLike) -> None:
    """Writes a mesh file (.obj, .ply, .off, .stl or .glb, by extension).
    The file is written in full under a temporary name and then renamed,
    so ``path`` never holds half a file."""
    _swm.write(os.fspath(path), _vertices(vertices), _faces(faces))


#: A glTF document: its bytes, or the path of a ``.glb`` or ``.gltf`` file.
SceneLike = Union[BytesLike, PathLike]


def _scene(
    scene: SceneLike, base: Optional[PathLike]
) -> Tuple[Optional[bytes], Optional[str], Optional[str]]:
    """The document as the extension module takes it: ``(data, path,
    base)``, one of ``data`` and ``path`` given."""
    folder = None if base is None else os.fspath(base)
    if isinstance(scene, (bytes, bytearray, memoryview)):
        return _bytes(scene), None, folder
    if isinstance(scene, (str, os.PathLike)):
        return None, os.fspath(scene), folder
    raise TypeError(
        f"scene must be bytes or the path of a .glb or .gltf file, got {type(scene).__name__}"
    )


@overload
def encode_scene(
    scene: SceneLike,
    *,
    base: Optional[PathLike] = None,
    bpv: Optional[float] = None,
    size: Optional[int] = None,
    edge_length: Optional[float] = None,
    mode: str = "auto",
    angle_bits: Optional[int] = None,
    qp: Optional[int] = None,
    report: Literal[False] = False,
    effort: str = "default",
    max_error: Optional[float] = None,
    qn: Optional[int] = None,
    qt: Optional[int] = None,
    qg: Optional[int] = None,
    keep_normals: bool = False,
    fallback: bool = False,
    format: str = "glb",
    limits: Optional[Limits] = None,
) -> bytes: ...


@overload
def encode_scene(
    scene: SceneLike,
    *,
    base: Optional[PathLike] = None,
    bpv: Optional[float] = None,
    size: Optional[int] = None,
    edge_length: Optional[float] = None,
    mode: str = "auto",
    angle_bits: Optional[int] = None,
    qp: Optional[int] = None,
    report: Literal[True],
    effort: str = "default",
    max_error: Optional[float] = None,
    qn: Optional[int] = None,
    qt: Optional[int] = None,
    qg: Optional[int] = None,
    keep_normals: bool = False,
    fallback: bool = False,
    format: str = "glb",
    limits: Optional[Limits] = None,
) -> Tuple[bytes, SceneReport]: ...


@overload
def encode_scene(
    scene: SceneLike,
    *,
    base: Optional[PathLike] = None,
    bpv: Optional[float] = None,
    size: Optional[int] = None,
    edge_length: Optional[float] = None,
    mode: str = "auto",
    angle_bits: Optional[int] = None,
    qp: Optional[int] = None,
    report: bool,
    effort: str = "default",
    max_error: Optional[float] = None,
    qn: Optional[int] = None,
    qt: Optional[int] = None,
    qg: Optional[int] = None,
    keep_normals: bool = False,
    fallback: bool = False,
    format: str = "glb",
    limits: Optional[Limits] = None,
) -> Union[bytes, Tuple[bytes, SceneReport]]: ...


def encode_scene(
    scene: SceneLike,
    *,
    base: Optional[PathLike] = None,
    bpv: Optional[float] = None,
    size: Optional[int] = None,
    edge_length: Optional[float] = None,
    mode: str = "auto",
    angle_bits: Optional[int] = None,
    qp: Optional[int] = None,
    report: bool = False,
    effort: str = "default",
    max_error: Optional[float] = None,
    qn: Optional[int] = None,
    qt: Optional[int] = None,
    qg: Optional[int] = None,
    keep_normals: bool = False,
    fallback: bool = False,
    format: str = "glb",
    limits: Optional[Limits] = None,
) -> Union[bytes, Tuple[bytes, SceneReport]]:
    """Compresses a glTF scene: each triangle primitive is coded as an
    swm file inside the glTF extension ``SWM_mesh_compression``
    (format-spec/09-gltf.md) and everything else (nodes, transforms,
    materials, textures, images, cameras, animations, skins, other
    primitives) is kept as written. The same call as ``swm encode
    scene.glb -o out.glb``: the same document and options give the same
    bytes.

    ``scene`` is the document's bytes or the path of a ``.glb`` or
    ``.gltf`` file; external buffers are read from the file's folder, or
    for bytes from ``base`` (without it such a document is refused).
    ``format`` is the output's container: ``"glb"`` (default) or
    ``"gltf"`` (JSON with its buffer embedded as a ``data:`` URI).

    The options are :func:`encode`'s, with its defaults and rules, and
    apply as ``swm encode`` applies them to a scene: with ``size``,
    ``bpv`` or ``max_error`` every primitive is coded by ``mode`` at its
    share of the target, with its normals, texture coordinates and
    colours (on ``qn``, ``qt``, ``qg`` bits; ``size`` is the budget of
    all the swm files, shared in proportion to each primitive's area;
    ``bpv`` counts the positions; ``max_error`` and ``edge_length``
    apply to each primitive as it is); without them a primitive with
    attributes is coded losslessly with them (positions on ``qp`` bits,
    12 by default) and one of positions only at the default rate. There is no ``max_size``. ``fallback=True``
    keeps an uncompressed copy of each coded primitive beside its swm
    file, so that viewers without swm still draw it (the extension is
    then only in ``extensionsUsed``).

    A primitive swm does not code (points, lines, a skin's joints and
    weights, morph targets, tangents, an extension) is kept as written and
    named, with why, in the report's ``uncompressed``. With
    ``report=True`` the result is ``(bytes, report)``, ``report`` a
    :class:`swm.reports.SceneReport`: the keys of ``swm encode --json``
    for a scene (``bytes``, ``input_bytes``, ``swm_bytes``,
    ``requested``, ``primitives``, ``uncompressed``,
    ``unknown_extensions``). A malformed document raises
    :class:`FormatError` (with ``filename`` set when read from a path),
    as does one already compressed by swm or by
    ``EXT_meshopt_compression``; nothing beyond ``limits`` is allocated
    reading it.
    """
    data, path, folder = _scene(scene, base)
    return _swm.encode_scene(
        data,
        path=path,
        base=folder,
        bpv=bpv,
        size=size,
        edge_length=edge_length,
        mode=mode,
        angle_bits=angle_bits,
        qp=qp,
        report=report,
        effort=effort,
        max_error=max_error,
        qn=qn,
        qt=qt,
        qg=qg,
        keep_normals=keep_normals,
        fallback=fallback,
        format=format,
        limits=limits,
    )


@overload
def decode_scene(
    scene: SceneLike,
    *,
    base: Optional[PathLike] = None,
    format: str = "glb",
    limits: Optional[Limits] = None,
    report: Literal[False] = False,
) -> bytes: ...


@overload
def decode_scene(
    scene: SceneLike,
    *,
    base: Optional[PathLike] = None,
    format: str = "glb",
    limits: Optional[Limits] = None,
    report: Literal[True],
) -> Tuple[bytes, SceneDecodeReport]: ...


@overload
def decode_scene(
    scene: SceneLike,
    *,
    base: Optional[PathLike] = None,
    format: str = "glb",
    limits: Optional[Limits] = None,
    report: bool,
) -> Union[bytes, Tuple[bytes, SceneDecodeReport]]: ...


def decode_scene(
    scene: SceneLike,
    *,
    base: Optional[PathLike] = None,
    format: str = "glb",
    limits: Optional[Limits] = None,
    report: bool = False,
) -> Union[bytes, Tuple[bytes, SceneDecodeReport]]:
    """Expands every primitive of a glTF scene coded in
    ``SWM_mesh_compression`` back to plain accessors and removes the
    extension, as ``swm decode out.glb -o plain.glb``: a document any
    glTF viewer reads. ``scene``, ``base`` and ``format`` are as for
    :func:`encode_scene`. Every byte is hostile: a bad document or swm
    file raises :class:`FormatError` (or another :class:`SwmError`), and
    ``limits`` bound each file and all of them together. With
    ``report=True`` the result is ``(bytes, report)``,
    :class:`swm.reports.SceneDecodeReport`: ``bytes``, ``primitives``
    expanded, ``decoded_vertices`` and ``decoded_triangles`` over them."""
    data, path, folder = _scene(scene, base)
    return _swm.decode_scene(data, path=path, base=folder, format=format, limits=limits, report=report)


def scene_info(
    scene: SceneLike,
    *,
    base: Optional[PathLike] = None,
    limits: Optional[Limits] = None,
) -> "list[ScenePrimitive]":
    """The primitives of a glTF document, coded or not, from its JSON
    alone (nothing is decoded), as ``swm info out.glb --json`` lists
    them: each a :class:`swm.reports.ScenePrimitive` (``mesh``,
    ``primitive``, ``name``, ``swm_bytes``, ``None`` for a primitive not
    coded, ``vertices``, ``triangles``, ``attributes``)."""
    data, path, folder = _scene(scene, base)
    return _swm.scene_info(data, path=path, base=folder, limits=limits)


def _trimesh() -> Any:
    try:
        import trimesh
    except ImportError:
        raise ImportError(
            "trimesh is not installed (pip install trimesh, or pip install 'swm[trimesh]')"
        ) from None
    return trimesh


def to_trimesh(
    vertices: npt.ArrayLike,
    faces: npt.ArrayLike,
    normals: Any = None,
    attributes: Optional[Attributes] = None,
) -> Any:
    """A ``trimesh.Trimesh`` of the arrays, as they are (``process=False``:
    trimesh merges nothing and drops nothing).

    ``attributes``, the dict of ``decode(..., attributes=True)``, gives
    ``vertex_normals`` its ``"normals"`` (unless ``normals`` is given) and
    ``visual`` a ``TextureVisuals(uv=...)`` of its ``"uv"`` or, without
    one, a ``ColorVisuals(vertex_colors=...)`` of its ``"colors"``
    (trimesh's visual holds one of the two; the other streams are in
    ``vertex_attributes`` under their names)."""
    trimesh = _trimesh()
    attributes = {} if attributes is None else _attributes(attributes)
    if normals is None:
        normals = attributes.get("normals")
    shown = "uv" if "uv" in attributes else "colors" if "colors" in attributes else None
    visual = None
    if shown == "uv":
        visual = trimesh.visual.TextureVisuals(uv=attributes["uv"][:, :2])
    elif shown == "colors":
        # trimesh keeps colours as 8-bit RGBA; the file's are 0..1.
        rgba = np.clip(np.rint(attributes["colors"] * 255.0), 0, 255).astype(np.uint8)
        visual = trimesh.visual.ColorVisuals(vertex_colors=rgba)
    rest = {k: v for k, v in attributes.items() if k not in ("normals", shown)}
    return trimesh.Trimesh(
        vertices=_vertices(vertices),
        faces=_faces(faces),
        vertex_normals=None if normals is None else _vertices(normals, "normals"),
        visual=visual,
        vertex_attributes=rest,
        process=False,
    )


def from_trimesh(mesh: Any) -> Tuple[Vertices, Faces]:
    """``(vertices, faces)`` of a ``trimesh.Trimesh`` as float32 / uint32."""
    _trimesh()
    return _mesh(mesh, "mesh")


__all__ = [
    "encode",
    "decode",
    "info",
    "distance",
    "read",
    "write",
    "encode_scene",
    "decode_scene",
    "scene_info",
    "to_trimesh",
    "from_trimesh",
    "Limits",
    "SwmError",
    "IoError",
    "FormatError",
    "ParameterError",
    "LimitError",
    "TopologyError",
    "UnsupportedError",
    "RetileError",
    "SizeError",
    "EncodeReport",
    "AttributeReport",
    "AttributesDropped",
    "TexcoordError",
    "SceneReport",
    "PrimitiveReport",
    "SceneDecodeReport",
    "ScenePrimitive",
    "__version__",
]

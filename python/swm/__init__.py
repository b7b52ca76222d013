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
) -> Tuple[bytes, "dict[str, Any]"]: ...


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
) -> Union[bytes, Tuple[bytes, "dict[str, Any]"]]:
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
      simplification then lossless coding, and at ``"max"`` a method per
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
    * ``"lossless"``: without ``size`` or ``bpv``, the input's own
      triangles with positions on ``qp`` bits (default 12; ``max_size``
      refused). With ``size`` or ``bpv``, the mesh is first simplified
      (greedy quadric edge collapse) to the largest face count and the
      quantization that fit the size, ``max_size`` included; ``qp`` is
      then refused. ``edge_length`` and ``angle_bits`` are refused.

    A size no file can meet raises :class:`SizeError` (which names the
    smallest possible size); options the mode has no use for raise
    ``ValueError``. With ``report=True`` the result is ``(bytes, report)``,
    ``report`` a dict: ``method``, what made the file (``"swing"``,
    ``"simplified"``, ``"mixed"``, a method per component, or
    ``"lossless"``); ``choice``, in the automatic mode, the ``method``
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
    ``samples``), ``None`` in the lossless mode at a fixed ``qp``.

    ``attributes`` (``mode="auto"`` or ``"lossless"``, with or without a
    size; ``"swing"`` and ``"displaced"`` refuse them) is a dict
    of per-vertex float arrays, one row per vertex, as
    ``decode(..., attributes=True)`` returns them: ``"normals"`` (n, 3),
    ``"uv"`` (n, 2) and further sets ``"uv1"``, ...; ``"colors"`` (n, 3)
    or (n, 4) in 0..1 and ``"colors1"``, ...; ``"generic0"``, ... (n, 1
    to 4). They are coded in the file's ``ATTR`` section (format 1.2) at
    ``swm encode``'s default quantization (normals 8 bits per octahedral
    coordinate, texture coordinates 10 bits, colours and generic streams
    8); vertices that differ only by their values (a UV seam) stay apart.
    A lossy file simplifies the mesh with them, never across a seam, and
    its size counts their bytes.

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


def read(path: PathLike, *, limits: Optional[Limits] = None) -> Tuple[Vertices, Faces]:
    """Reads a mesh file (.obj, .ply, .off, .stl, .gltf, .glb; the extension picks the
    format) as ``swm encode`` reads it: the raw mesh, polygons
    fan-triangulated, nothing merged."""
    return _swm.read(os.fspath(path), limits=limits)


def write(path: PathLike, vertices: npt.ArrayLike, faces: npt.ArrayLike) -> None:
    """Writes a mesh file (.obj, .ply, .off, .stl or .glb, by extension).
    The file is written in full under a temporary name and then renamed,
    so ``path`` never holds half a file."""
    _swm.write(os.fspath(path), _vertices(vertices), _faces(faces))


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
    "__version__",
]

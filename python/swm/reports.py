"""The shapes of the dicts :func:`swm.encode` and :func:`swm.encode_scene`
return with ``report=True`` (and of :func:`swm.decode_scene`'s and
:func:`swm.scene_info`'s), as ``TypedDict`` classes for type checkers.
At run time they are plain dicts; the keys are those of the matching
``swm encode --json`` objects.
"""

from __future__ import annotations

from typing import Any, Dict, List, Optional, TypedDict


class TexcoordError(TypedDict):
    """The decoded texture coordinates (set 0) measured against the
    input's, in texels of a ``texture_size``² texture over the unit
    square."""

    rms_texels: float
    max_texels: float
    texture_size: float
    samples: int


class _DroppedBase(TypedDict):
    reason: str
    message: str


class AttributesDropped(_DroppedBase, total=False):
    """Why an encode dropped attribute streams. ``reason`` is one of:

    * ``"smooth_normals"``: the input's normals follow its geometry
      (within ``rms_degrees`` RMS): decoders recompute them from the
      decoded surface, so a lossy file does not code them
      (``keep_normals=True`` codes them);
    * ``"costly_normals"``: the input's normals do not follow its
      geometry (``rms_degrees`` RMS off it), but at the size asked for
      they cost the surface more than they give: the file that kept them
      was ``l2_kept`` (relative L2) off the input, more than the file
      without them plus their error at 1e-4 of the diagonal a degree
      (``keep_normals=True`` keeps them);
    * ``"no_room"``: the size asked for is below ``smallest``, the
      smallest file that keeps them, so the file codes the surface alone;
    * ``"method"``: the ``method`` that made the file cannot carry them
      (``swm.encode`` refuses attributes in such a mode, so this comes
      from no call of this package today);
    * ``"other"``: a reason newer than this binding.

    ``message`` is the library's sentence for it.
    """

    rms_degrees: float
    l2_kept: float
    smallest: int
    method: str


class AttributeReport(TypedDict):
    """What an encode did with the ``attributes`` it was given, under the
    keys of that dict (``"normals"``, ``"uv"``, ``"colors"``, ...):
    ``kept``, the streams the file carries; ``dropped``, those it does
    not; ``dropped_because``, why (``None`` when nothing was dropped);
    ``texcoord_error``, for a lossy file that keeps ``"uv"``, how far the
    decoded texture coordinates are from the input's (``None``
    otherwise). All empty or ``None`` for a mesh encoded without
    attributes."""

    kept: List[str]
    dropped: List[str]
    dropped_because: Optional[AttributesDropped]
    texcoord_error: Optional[TexcoordError]


class EncodeReport(TypedDict):
    """What :func:`swm.encode` reports with ``report=True`` (its
    docstring describes each key)."""

    method: str
    choice: Optional[Dict[str, Any]]
    simplified: Optional[Dict[str, Any]]
    check: Optional[Dict[str, Any]]
    attributes: AttributeReport
    smallest_instead: Optional[Dict[str, int]]


class _PrimitiveBase(TypedDict):
    mesh: int
    primitive: int
    name: Optional[str]
    coded: bool


class PrimitiveReport(_PrimitiveBase, total=False):
    """One primitive of a scene :func:`swm.encode_scene` read. A coded
    one (``coded`` true) has ``method``, ``bytes`` (its swm file),
    ``share`` (its part of the scene's size, or ``None``), the
    ``input_vertices`` and ``input_triangles`` it had, the ``vertices``
    and ``triangles`` it decodes to, and its coded ``attributes`` by glTF
    semantic; one kept as written has ``kept_because``."""

    method: str
    bytes: int
    share: Optional[int]
    input_vertices: int
    input_triangles: int
    vertices: int
    triangles: int
    attributes: List[str]
    kept_because: str


class SceneReport(TypedDict):
    """What :func:`swm.encode_scene` reports with ``report=True``, the
    keys of ``swm encode scene.glb -o out.glb --json`` (but the time):
    ``bytes`` and ``input_bytes``, the output's and the input's size;
    ``swm_bytes``, its swm files together; ``requested``, the scene's
    size budget when it had one; ``primitives``, every primitive in
    document order; ``uncompressed``, each primitive kept as written,
    with why, in words; ``unknown_extensions``, the extensions passed
    through that swm does not know."""

    bytes: int
    input_bytes: int
    swm_bytes: int
    requested: Optional[int]
    primitives: List[PrimitiveReport]
    uncompressed: List[str]
    unknown_extensions: List[str]


class SceneDecodeReport(TypedDict):
    """What :func:`swm.decode_scene` reports with ``report=True``."""

    bytes: int
    primitives: int
    decoded_vertices: int
    decoded_triangles: int


class ScenePrimitive(TypedDict):
    """One primitive as :func:`swm.scene_info` lists it: ``swm_bytes``,
    its swm file's size (``None`` when it is not coded); ``vertices``,
    its POSITION count; ``triangles`` (0 unless it draws a triangle
    list); ``attributes``, its glTF semantics, POSITION first."""

    mesh: int
    primitive: int
    name: Optional[str]
    swm_bytes: Optional[int]
    vertices: int
    triangles: int
    attributes: List[str]


__all__ = [
    "AttributeReport",
    "AttributesDropped",
    "EncodeReport",
    "PrimitiveReport",
    "SceneDecodeReport",
    "ScenePrimitive",
    "SceneReport",
    "TexcoordError",
]

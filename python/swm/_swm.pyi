"""Type stubs of the extension module ``swm._swm`` (see ``swm/__init__.py``
for the documented wrappers, which normalize NumPy inputs first)."""

from os import PathLike
from typing import Any, Literal, Optional, Tuple, Union, overload

import numpy as np
import numpy.typing as npt

from .reports import EncodeReport, SceneDecodeReport, ScenePrimitive, SceneReport

__version__: str

_V = npt.NDArray[np.float32]
_F = npt.NDArray[np.uint32]

class Limits:
    """Caps on what decoding or reading an untrusted file may allocate."""

    @property
    def max_vertices(self) -> int: ...
    @property
    def max_faces(self) -> int: ...
    @property
    def max_alloc_bytes(self) -> int: ...
    def __init__(
        self,
        *,
        max_vertices: Optional[int] = None,
        max_faces: Optional[int] = None,
        max_alloc_bytes: Optional[int] = None,
    ) -> None: ...

@overload
def encode(
    vertices: _V,
    faces: _F,
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
    attributes: Optional[dict[str, _V]] = None,
    qn: Optional[int] = None,
    qt: Optional[int] = None,
    qg: Optional[int] = None,
    keep_normals: bool = False,
    or_smallest: bool = False,
) -> bytes: ...
@overload
def encode(
    vertices: _V,
    faces: _F,
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
    attributes: Optional[dict[str, _V]] = None,
    qn: Optional[int] = None,
    qt: Optional[int] = None,
    qg: Optional[int] = None,
    keep_normals: bool = False,
    or_smallest: bool = False,
) -> Tuple[bytes, EncodeReport]: ...
@overload
def encode(
    vertices: _V,
    faces: _F,
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
    attributes: Optional[dict[str, _V]] = None,
    qn: Optional[int] = None,
    qt: Optional[int] = None,
    qg: Optional[int] = None,
    keep_normals: bool = False,
    or_smallest: bool = False,
) -> Union[bytes, Tuple[bytes, EncodeReport]]: ...
def decode(
    data: bytes,
    *,
    sharpen: Optional[bool] = None,
    bend: Optional[int] = None,
    normals: bool = False,
    limits: Optional[Limits] = None,
    max_level: Optional[int] = None,
    attributes: bool = False,
) -> Tuple[Any, ...]: ...
def info(data: bytes, *, limits: Optional[Limits] = None) -> dict[str, Any]: ...
def distance(
    a_vertices: _V,
    a_faces: _F,
    b_vertices: _V,
    b_faces: _F,
    *,
    samples: Optional[int] = None,
    sampling: str = "metro",
) -> dict[str, Any]: ...
@overload
def read(
    path: Union[str, PathLike[str]], *, limits: Optional[Limits] = None, attributes: Literal[False] = False
) -> Tuple[_V, _F]: ...
@overload
def read(
    path: Union[str, PathLike[str]], *, limits: Optional[Limits] = None, attributes: Literal[True]
) -> Tuple[_V, _F, dict[str, _V], list[str]]: ...
@overload
def read(
    path: Union[str, PathLike[str]], *, limits: Optional[Limits] = None, attributes: bool
) -> Union[Tuple[_V, _F], Tuple[_V, _F, dict[str, _V], list[str]]]: ...
def write(path: Union[str, PathLike[str]], vertices: _V, faces: _F) -> None: ...

_Path = Union[str, PathLike[str]]

@overload
def encode_scene(
    data: Optional[bytes] = None,
    *,
    path: Optional[_Path] = None,
    base: Optional[_Path] = None,
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
    data: Optional[bytes] = None,
    *,
    path: Optional[_Path] = None,
    base: Optional[_Path] = None,
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
    data: Optional[bytes] = None,
    *,
    path: Optional[_Path] = None,
    base: Optional[_Path] = None,
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
@overload
def decode_scene(
    data: Optional[bytes] = None,
    *,
    path: Optional[_Path] = None,
    base: Optional[_Path] = None,
    format: str = "glb",
    limits: Optional[Limits] = None,
    report: Literal[False] = False,
) -> bytes: ...
@overload
def decode_scene(
    data: Optional[bytes] = None,
    *,
    path: Optional[_Path] = None,
    base: Optional[_Path] = None,
    format: str = "glb",
    limits: Optional[Limits] = None,
    report: Literal[True],
) -> Tuple[bytes, SceneDecodeReport]: ...
@overload
def decode_scene(
    data: Optional[bytes] = None,
    *,
    path: Optional[_Path] = None,
    base: Optional[_Path] = None,
    format: str = "glb",
    limits: Optional[Limits] = None,
    report: bool,
) -> Union[bytes, Tuple[bytes, SceneDecodeReport]]: ...
def scene_info(
    data: Optional[bytes] = None,
    *,
    path: Optional[_Path] = None,
    base: Optional[_Path] = None,
    limits: Optional[Limits] = None,
) -> list[ScenePrimitive]: ...

"""Exceptions of the swm package: one class per kind of ``swm::Error``.

Every class derives from :class:`SwmError`; where a built-in exception
means the same thing the class derives from it too, so that
``except OSError`` or ``except ValueError`` also catch them. The message
(``str(e)``) is the library's own one-line text. Errors from
:func:`swm.read` and :func:`swm.write` carry the path in ``filename``.
"""

from __future__ import annotations

from typing import Optional


class SwmError(Exception):
    """Base class of every error the swm library reports."""

    filename: Optional[str] = None

    def __str__(self) -> str:
        # OSError would format errno and filename into the message; the
        # message stays the library's, whatever attributes are set.
        return str(self.args[0]) if self.args else ""


class IoError(SwmError, OSError):
    """Reading or writing failed at the operating-system level."""


class FormatError(SwmError, ValueError):
    """The data is malformed or corrupt (a mesh file or a .swm file)."""


class ParameterError(SwmError, ValueError):
    """An option is out of range, or a file name has an unknown extension."""


class LimitError(SwmError):
    """The input needs more than the :class:`swm.Limits` allow."""


class TopologyError(SwmError, ValueError):
    """The mesh's topology cannot be handled (e.g. non-orientable)."""


class UnsupportedError(SwmError):
    """The file needs a newer decoder (version, mode, section or flag)."""


class RetileError(SwmError):
    """SwingWrapper retiling found no edge length that works or fits."""


class SizeError(SwmError, ValueError):
    """No file of the requested size (or ``max_size``) can hold the mesh.

    ``requested`` is the size asked for and ``smallest`` the smallest file
    the encoder can make of the mesh, both in bytes (``None`` on an
    instance not raised by the library)."""

    requested: Optional[int] = None
    smallest: Optional[int] = None


__all__ = [
    "SwmError",
    "IoError",
    "FormatError",
    "ParameterError",
    "LimitError",
    "TopologyError",
    "UnsupportedError",
    "RetileError",
    "SizeError",
]

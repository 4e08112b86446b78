"""Macrocon: retrieval and re-embedding of macro constraints for quad meshing (ctypes binding).

The native library is found next to this package (wheel) or through ``MACROCON_LIBRARY``; its ABI
major version is checked at import.
"""
from ._native import ABI_MAJOR, library_version
from .core import (
    DESCRIPTOR_CURV9,
    DESCRIPTOR_MEAN_CURVATURE,
    Context,
    Mesh,
    Patch,
    shutdown,
    version,
)
from .errors import (
    BufferTooSmallError,
    CancelledError,
    Error,
    InvalidArgumentError,
    InvalidLibraryError,
    InvalidMeshError,
    NotADiskError,
    NotFoundError,
    NullPointerError,
    NumericalError,
    StructSizeError,
    UnsupportedError,
    status_name,
)

__version__ = "0.1.0"

__all__ = [
    "ABI_MAJOR", "library_version", "version", "shutdown", "Context", "Mesh", "Patch",
    "DESCRIPTOR_CURV9", "DESCRIPTOR_MEAN_CURVATURE", "Error", "InvalidArgumentError", "NullPointerError",
    "StructSizeError", "BufferTooSmallError", "CancelledError", "InvalidMeshError", "NotADiskError",
    "NumericalError", "InvalidLibraryError", "UnsupportedError", "NotFoundError", "status_name",
]

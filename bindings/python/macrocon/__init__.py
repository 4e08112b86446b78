"""Macrocon: retrieval and re-embedding of macro constraints for quad meshing (ctypes binding).

The native library is found next to this package (wheel) or through ``MACROCON_LIBRARY``; its ABI
major version is checked at import. ``starter_library()`` is the path of the starter constraint
library (in the wheel: next to this package).
"""
from ._native import ABI_MAJOR, library_path, library_version, starter_library
from .core import (
    DESCRIPTOR_CURV9,
    DESCRIPTOR_MEAN_CURVATURE,
    Context,
    LogCallbackWarning,
    Mesh,
    Patch,
    PatchInfo,
    PatchRepairs,
    close_all,
    shutdown,
    version,
)
from .library import (
    Entry,
    EntryInfo,
    Field,
    FieldKind,
    Library,
    LibraryInfo,
    Polyline,
    PolylineKind,
    QueryResult,
    Suggestion,
    RetrievalDescriptor,
    Singularities,
)
from .mapping import CutMesh, CutMeshInfo, Direction, Map, MapInfo, Orientation, PolylineSet, StopReason
from .errors import (
    BufferTooSmallError,
    CancelledError,
    EntryIndexError,
    Error,
    FileNotFoundError_,
    InvalidArgumentError,
    InvalidLibraryError,
    InvalidMeshError,
    NotADiskError,
    NotFoundError,
    NullPointerError,
    NumericalError,
    OutOfMemoryError,
    IOError_,
    StructSizeError,
    UnsupportedError,
    status_name,
)

__version__ = "0.1.0"

__all__ = [
    "ABI_MAJOR", "library_version", "library_path", "starter_library", "version", "shutdown", "Context", "LogCallbackWarning", "Mesh", "Patch", "PatchRepairs",
    "DESCRIPTOR_CURV9", "DESCRIPTOR_MEAN_CURVATURE", "Error", "InvalidArgumentError", "NullPointerError",
    "StructSizeError", "BufferTooSmallError", "CancelledError", "InvalidMeshError", "NotADiskError",
    "NumericalError", "InvalidLibraryError", "UnsupportedError", "NotFoundError", "status_name", "close_all",
    "Library", "Entry", "EntryInfo", "LibraryInfo", "QueryResult", "Suggestion", "Polyline", "PolylineKind", "Singularities",
    "Field", "FieldKind", "RetrievalDescriptor", "Map", "MapInfo", "PolylineSet", "StopReason", "Direction",
    "Orientation", "OutOfMemoryError", "IOError_", "FileNotFoundError_", "EntryIndexError", "PatchInfo",
    "CutMesh", "CutMeshInfo",
]

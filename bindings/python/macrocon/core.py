"""Pythonic wrappers: Context, Mesh, Patch. Arrays in and out are numpy arrays."""
from __future__ import annotations

import atexit
import ctypes
from typing import Callable, Optional

import numpy as np

from . import _native
from .errors import CancelledError, Error, check

ProgressCallback = Callable[[float], bool]

DESCRIPTOR_CURV9 = 1
DESCRIPTOR_MEAN_CURVATURE = 2
_DESCRIPTORS = {"curv9": DESCRIPTOR_CURV9, "mean_curvature": DESCRIPTOR_MEAN_CURVATURE}


def version() -> tuple[int, int, int]:
    """(major, minor, patch) of the loaded native library."""
    return _native.library_version()


def shutdown() -> None:
    """Waits for the SDK's worker threads (registered with atexit; safe to call more than once)."""
    check(_native.lib.mcon_shutdown())


atexit.register(lambda: _native.lib.mcon_shutdown())


class _Handle:
    """Owns one reference of a C handle; ``close()`` or the context manager releases it."""

    _release: Callable[[ctypes.c_void_p], int]

    def __init__(self, handle: ctypes.c_void_p):
        self._handle = handle

    @property
    def handle(self) -> ctypes.c_void_p:
        if not self._handle:
            raise ValueError(f"{type(self).__name__} is closed")
        return self._handle

    def close(self) -> None:
        if self._handle:
            type(self)._release(self._handle)
            self._handle = None

    def __enter__(self):
        return self

    def __exit__(self, *exc) -> None:
        self.close()

    def __del__(self):
        try:
            self.close()
        except Exception:  # never raise from a finalizer
            pass


class _Progress:
    """Adapts a Python callable to mcon_progress_callback; exceptions cancel and are re-raised."""

    def __init__(self, fn: Optional[ProgressCallback]):
        self.fn = fn
        self.error: Optional[BaseException] = None
        self.c_fn = _native.PROGRESS_CALLBACK(self._call) if fn else _native.PROGRESS_CALLBACK()

    def _call(self, _user, fraction: float) -> int:
        try:
            return 1 if self.fn(fraction) is not False else 0
        except BaseException as exc:  # noqa: BLE001 - re-raised after the C call returns
            self.error = exc
            return 0

    def check(self, status: int) -> None:
        if self.error is not None and status == 7:
            raise self.error
        check(status)


class Context(_Handle):
    """Owns the SDK's thread pool. ``max_threads=0`` uses every hardware thread."""

    _release = _native.lib.mcon_context_release

    def __init__(self, max_threads: int = 0):
        options = _native.ContextOptions()
        check(_native.lib.mcon_context_options_init(ctypes.byref(options)))
        options.max_threads = int(max_threads)
        handle = ctypes.c_void_p()
        check(_native.lib.mcon_context_create(ctypes.byref(options), ctypes.byref(handle)))
        super().__init__(handle)


def _as_array(name: str, array, dtypes: tuple, columns: int) -> np.ndarray:
    a = np.asarray(array)
    if a.dtype not in dtypes:
        raise TypeError(f"{name} must have dtype {' or '.join(str(np.dtype(d)) for d in dtypes)}, got {a.dtype}")
    if a.ndim != 2 or a.shape[1] != columns:
        raise ValueError(f"{name} must have shape (n, {columns}), got {a.shape}")
    if not a.flags.c_contiguous:
        raise ValueError(f"{name} must be C-contiguous (use numpy.ascontiguousarray)")
    return a


class Mesh(_Handle):
    """A validated triangle mesh. ``positions``: (n, 3) float32/float64, ``triangles``: (m, 3) uint32."""

    _release = _native.lib.mcon_mesh_release

    def __init__(self, context: Context, positions, triangles):
        p = _as_array("positions", positions, (np.float32, np.float64), 3)
        t = _as_array("triangles", triangles, (np.uint32,), 3)
        desc = _native.MeshDesc()
        check(_native.lib.mcon_mesh_desc_init(ctypes.byref(desc)))
        desc.positions = p.ctypes.data
        desc.position_type = 1 if p.dtype == np.float32 else 2
        desc.vertex_count = p.shape[0]
        desc.indices = t.ctypes.data
        desc.triangle_count = t.shape[0]
        handle = ctypes.c_void_p()
        check(_native.lib.mcon_mesh_create(context.handle, ctypes.byref(desc), ctypes.byref(handle)))
        super().__init__(handle)
        self.context = context  # keep the Python object alive as long as the mesh

    @property
    def counts(self) -> tuple[int, int]:
        nv, nt = _native.c_size(), _native.c_size()
        check(_native.lib.mcon_mesh_get_counts(self.handle, ctypes.byref(nv), ctypes.byref(nt)))
        return nv.value, nt.value


class Patch(_Handle):
    """A geodesic disk cut out of a host mesh, normalized to geodesic radius 1."""

    _release = _native.lib.mcon_patch_release

    def __init__(self, handle: ctypes.c_void_p):
        super().__init__(handle)
        self._info = None

    @classmethod
    def extract(
        cls,
        mesh: Mesh,
        radius: float,
        center_vertex: Optional[int] = None,
        center_triangle: Optional[int] = None,
        barycentric=(1 / 3, 1 / 3, 1 / 3),
        fill_holes: bool = True,
        snap_fraction: Optional[float] = None,
        progress: Optional[ProgressCallback] = None,
    ) -> "Patch":
        options = _native.PatchOptions()
        check(_native.lib.mcon_patch_options_init(ctypes.byref(options)))
        if (center_vertex is None) == (center_triangle is None):
            raise ValueError("give exactly one of center_vertex and center_triangle")
        if center_vertex is not None:
            options.center_vertex = int(center_vertex)
        else:
            options.center_vertex = _native.INVALID_INDEX
            options.center_triangle = int(center_triangle)
            for i, b in enumerate(barycentric):
                options.center_barycentric[i] = float(b)
        options.radius = float(radius)
        options.flags = 1 if fill_holes else 0
        if snap_fraction is not None:
            options.snap_fraction = float(snap_fraction)
        cb = _Progress(progress)
        options.progress = cb.c_fn
        handle = ctypes.c_void_p()
        status = _native.lib.mcon_patch_extract(mesh.handle, ctypes.byref(options), ctypes.byref(handle))
        cb.check(status)
        return cls(handle)

    @property
    def info(self) -> _native.PatchInfo:
        if self._info is None:
            info = _native.PatchInfo()
            check(_native.lib.mcon_patch_info_init(ctypes.byref(info)))
            check(_native.lib.mcon_patch_get_info(self.handle, ctypes.byref(info)))
            self._info = info
        return self._info

    @property
    def vertex_count(self) -> int:
        return self.info.vertex_count

    @property
    def triangle_count(self) -> int:
        return self.info.triangle_count

    def _doubles(self, fn, columns: int) -> np.ndarray:
        out = np.empty((self.vertex_count, columns), dtype=np.float64)
        check(fn(self.handle, out.ctypes.data_as(_native.c_double_p), out.size))
        return out

    @property
    def positions(self) -> np.ndarray:
        """(n, 3) normalized positions; host = center + radius * p."""
        return self._doubles(_native.lib.mcon_patch_get_positions, 3)

    @property
    def uv(self) -> np.ndarray:
        """(n, 2) unit-disk parametrization."""
        return self._doubles(_native.lib.mcon_patch_get_uv, 2)

    @property
    def triangles(self) -> np.ndarray:
        out = np.empty((self.triangle_count, 3), dtype=np.uint32)
        check(_native.lib.mcon_patch_get_triangles(self.handle, out.ctypes.data_as(_native.c_uint32_p), out.size))
        return out

    @property
    def host_vertices(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(v0, v1, t): patch vertex i lies at (1 - t) host[v0] + t host[v1]; v0 == 0xFFFFFFFF if it fills a hole."""
        n = self.vertex_count
        v0, v1, t = np.empty(n, np.uint32), np.empty(n, np.uint32), np.empty(n, np.float64)
        check(
            _native.lib.mcon_patch_get_host_vertices(
                self.handle,
                v0.ctypes.data_as(_native.c_uint32_p),
                v1.ctypes.data_as(_native.c_uint32_p),
                t.ctypes.data_as(_native.c_double_p),
                n,
            )
        )
        return v0, v1, t

    @property
    def host_triangles(self) -> np.ndarray:
        out = np.empty(self.triangle_count, np.uint32)
        check(_native.lib.mcon_patch_get_host_triangles(self.handle, out.ctypes.data_as(_native.c_uint32_p), out.size))
        return out

    def descriptors(self, kind: str = "curv9") -> np.ndarray:
        """(n, d) per-vertex descriptors: 'curv9' (d = 9) or 'mean_curvature' (d = 1)."""
        if kind not in _DESCRIPTORS:
            raise ValueError(f"unknown descriptor {kind!r}; one of {sorted(_DESCRIPTORS)}")
        dim = ctypes.c_uint32()
        check(_native.lib.mcon_descriptor_get_dimension(_DESCRIPTORS[kind], ctypes.byref(dim)))
        out = np.empty((self.vertex_count, dim.value), np.float64)
        check(
            _native.lib.mcon_patch_compute_descriptors(
                self.handle, _DESCRIPTORS[kind], out.ctypes.data_as(_native.c_double_p), out.size
            )
        )
        return out


__all__ = ["Context", "Mesh", "Patch", "Error", "CancelledError", "version", "shutdown"]

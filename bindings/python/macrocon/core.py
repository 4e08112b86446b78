"""Pythonic wrappers: Context, Mesh, Patch. Arrays in and out are numpy arrays."""
from __future__ import annotations

import atexit
import ctypes
import itertools
import sys
import warnings
import weakref
from dataclasses import dataclass
from typing import Callable, Optional

import numpy as np

from . import _native
from ._arrays import checked, ptr, strided_rows
from .errors import CancelledError, Error, InvalidArgumentError, check, check_path

ProgressCallback = Callable[[float], bool]
#: ``log(status, message)``: every error message of a context as it is raised (any thread).
LogCallback = Callable[[int, str], None]

DESCRIPTOR_CURV9 = 1
DESCRIPTOR_MEAN_CURVATURE = 2
_DESCRIPTORS = {"curv9": DESCRIPTOR_CURV9, "mean_curvature": DESCRIPTOR_MEAN_CURVATURE}


def version() -> tuple[int, int, int]:
    """(major, minor, patch) of the loaded native library."""
    return _native.library_version()


def shutdown() -> None:
    """Waits for the SDK's worker threads. Release every handle first (or call ``close_all``).

    Registered with atexit (see ``_exit_hook``); safe to call more than once.
    """
    check(_native.lib.mcon_shutdown())


#: Every open handle object, so the exit hook can release what the program left open:
#: mcon_shutdown refuses while a context is alive (docs/design.md §5: without it TBB's workers
#: outlive the interpreter's teardown).
_live: "weakref.WeakSet[_Handle]" = weakref.WeakSet()

#: Status of the exit hook's mcon_shutdown call (None until it ran); for tests and diagnostics.
exit_status: Optional[int] = None


def close_all() -> None:
    """Releases every open handle of this process (objects become closed)."""
    # Dependents first; the C side keeps its own references, so the order only matters for speed.
    for handle in sorted(list(_live), key=lambda h: isinstance(h, Context)):
        handle.close()


def _exit_hook() -> None:
    global exit_status
    close_all()
    exit_status = _native.lib.mcon_shutdown()
    if exit_status != 0:
        msg = ctypes.c_char_p()
        _native.lib.mcon_get_last_error(None, ctypes.byref(msg))
        sys.stderr.write(f"macrocon: mcon_shutdown at exit failed: {(msg.value or b'').decode()}\n")


atexit.register(_exit_hook)


def _closest_points(function, handle, points) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    p = checked("points", points, np.float64, (None, 3))
    n = p.shape[0]
    t, b, d = np.empty(n, np.uint32), np.empty((n, 3)), np.empty(n)
    check(function(handle, ptr(p), n, ptr(t), ptr(b), ptr(d)))
    return t, b, d


def require_type(value, cls, name: str) -> None:
    """A TypeError (instead of a NULL handle reaching the C side) for None or a wrong object."""
    if not isinstance(value, cls):
        raise TypeError(f"{name} must be a macrocon.{cls.__name__}, got {type(value).__name__}")


class _Handle:
    """Owns one reference of a C handle; ``close()`` or the context manager releases it."""

    _release: Callable[[ctypes.c_void_p], int]

    def __init__(self, handle: ctypes.c_void_p):
        self._handle = handle
        _live.add(self)

    @property
    def handle(self) -> ctypes.c_void_p:
        """The C handle (a ctypes pointer) for calls into ``_native.lib``; ValueError once closed."""
        if not self._handle:
            raise ValueError(f"{type(self).__name__} is closed")
        return self._handle

    @property
    def closed(self) -> bool:
        """True once ``close()`` released the C handle."""
        return not self._handle

    def close(self) -> None:
        """Releases this object's reference of the C handle (safe to call more than once)."""
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

    def _repr_fields(self) -> str:
        """What ``repr`` shows of an open handle (sizes); the subclasses override it."""
        return ""

    def __repr__(self) -> str:
        name = f"macrocon.{type(self).__name__}"
        if not self._handle:
            return f"<{name} closed>"
        try:
            fields = self._repr_fields()
        except Exception as exc:  # noqa: BLE001 - repr must not raise (debuggers, logs)
            fields = f"<{type(exc).__name__}>"
        return f"<{name} {fields}>" if fields else f"<{name}>"


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


class LogCallbackWarning(RuntimeWarning):
    """A context's log callback raised; the exception is kept in ``Context.log_exceptions``."""


class _Log:
    """One context's log callback and the exceptions it raised (never let into C)."""

    #: At most this many raised exceptions are kept (a logger failing on every message must not
    #: grow without bound); ``dropped`` counts the rest.
    KEEP = 100

    def __init__(self, fn: LogCallback):
        self.fn = fn
        self.exceptions: list[BaseException] = []
        self.dropped = 0

    def deliver(self, status: int, message: Optional[bytes]) -> None:
        # Decoded like errors.check decodes mcon_get_last_error, so the text equals Error.message.
        text = message.decode("utf-8", "replace") if message else ""
        try:
            self.fn(int(status), text)
        except BaseException as exc:  # noqa: BLE001 - must not propagate into C (ctypes would only print it)
            if len(self.exceptions) < self.KEEP:
                self.exceptions.append(exc)
            else:
                self.dropped += 1
            try:
                warnings.warn(LogCallbackWarning(f"macrocon log callback raised {exc!r} (kept in Context.log_exceptions)"))
            except BaseException:  # noqa: BLE001 - e.g. -W error turns the warning itself into an exception
                pass


#: Log callbacks by key. The C side gets one module-lifetime trampoline and the key as user_data,
#: never a per-context ctypes object: the native context outlives its Python object while a
#: dependent handle (mesh, patch, map, library) still holds it, and a message raised then must not
#: call a freed CFUNCTYPE thunk. A key whose Context object is gone is simply not found.
_log_targets: "dict[int, _Log]" = {}
_log_keys = itertools.count(1)


def _log_trampoline(user_data: Optional[int], status: int, message: Optional[bytes]) -> None:
    # ctypes takes the GIL for the call, also on TBB worker threads the interpreter never saw.
    try:
        target = _log_targets.get(user_data or 0)
        if target is not None:
            target.deliver(status, message)
    except BaseException:  # noqa: BLE001 - nothing may unwind into C, not even at interpreter teardown
        pass


_LOG_TRAMPOLINE = _native.LOG_CALLBACK(_log_trampoline)


class Context(_Handle):
    """Owns the SDK's thread pool. ``max_threads=0`` uses every hardware thread.

    ``log(status, message)``, if given, receives every error message raised in this context (by
    calls on the context and on meshes, patches, maps and libraries made in it), with the same
    status and text as the :class:`Error` the failing call raises. It may run on any thread.
    An exception raised by ``log`` never reaches the C side: it is kept in ``log_exceptions``
    (the first 100), reported as a :class:`LogCallbackWarning`, and the failing call still raises
    its own :class:`Error`. The callback stays registered as long as this object lives (meshes,
    patches and libraries made in the context keep it alive), also after ``close()``.
    """

    _release = _native.lib.mcon_context_release

    def __init__(self, max_threads: int = 0, log: Optional[LogCallback] = None):
        if log is not None and not callable(log):
            raise TypeError(f"log must be callable(status: int, message: str), got {type(log).__name__}")
        options = _native.ContextOptions()
        check(_native.lib.mcon_context_options_init_sized(ctypes.byref(options), ctypes.sizeof(options)))
        options.max_threads = int(max_threads)
        self.max_threads = int(max_threads)  # as requested; 0 = every hardware thread
        self._log: Optional[_Log] = None
        key = 0
        if log is not None:
            self._log = _Log(log)
            key = next(_log_keys)
            _log_targets[key] = self._log
            options.log_callback = _LOG_TRAMPOLINE
            options.log_user_data = key
        handle = ctypes.c_void_p()
        try:
            check(_native.lib.mcon_context_create(ctypes.byref(options), ctypes.byref(handle)))
        except BaseException:
            _log_targets.pop(key, None)
            raise
        super().__init__(handle)
        if key:
            # Runs after __del__ (which releases the native reference), so the callback is
            # unregistered only once this object, and every Python object holding it, is gone.
            weakref.finalize(self, _log_targets.pop, key, None)

    @property
    def log_exceptions(self) -> list:
        """Exceptions the log callback raised (oldest first, at most 100; empty without ``log``)."""
        return list(self._log.exceptions) if self._log is not None else []

    def _repr_fields(self) -> str:
        return f"max_threads={self.max_threads}" + (" log" if self._log is not None else "")


def _as_array(name: str, array, dtypes: tuple, columns: int) -> np.ndarray:
    a = np.asarray(array)
    if a.dtype not in dtypes:
        raise TypeError(f"{name} must have dtype {' or '.join(str(np.dtype(d)) for d in dtypes)}, got {a.dtype}")
    if a.ndim != 2 or a.shape[1] != columns:
        raise ValueError(f"{name} must have shape (n, {columns}), got {a.shape}")
    if not a.flags.c_contiguous:
        raise ValueError(f"{name} must be C-contiguous (use numpy.ascontiguousarray)")
    return a


def _mesh_desc(positions, triangles) -> tuple:
    """An mcon_mesh_desc over the caller's arrays, and the arrays it points into (keep them alive
    until the call returns). Both may be row-strided (mcon_mesh_desc has position_stride and
    index_stride): e.g. ``vertices[:, 0:3]`` of a wider (n, k) vertex buffer or ``rec["pos"]`` of an
    aligned structured array are read in place, see ``_arrays.strided_rows``."""
    p, p_stride = strided_rows("positions", positions, (np.float32, np.float64), 3)
    t, t_stride = strided_rows("triangles", triangles, tuple(_INDEX_FORMATS), 3)
    desc = _native.MeshDesc()
    check(_native.lib.mcon_mesh_desc_init_sized(ctypes.byref(desc), ctypes.sizeof(desc)))
    desc.positions, desc.position_type = p.ctypes.data, 1 if p.dtype == np.float32 else 2
    desc.position_stride, desc.vertex_count = p_stride, p.shape[0]
    desc.indices, desc.index_stride, desc.triangle_count = t.ctypes.data, t_stride, t.shape[0]
    # Read in place in its own format: no conversion to uint32 (== rather than a dict lookup: numpy's
    # longlong and long are equal int64 dtypes but need not hash alike).
    desc.index_format = next(f for d, f in _INDEX_FORMATS.items() if t.dtype == d)
    return desc, (p, t)


#: Triangle dtypes passed as they are (mcon_index_format): uint32, int32 (Maya, USD) and int64
#: (numpy's default integer). Native byte order only; anything else is a TypeError naming these.
_INDEX_FORMATS = {np.dtype(np.uint32): _native.INDEX_FORMAT_UINT32, np.dtype(np.int32): _native.INDEX_FORMAT_INT32,
                  np.dtype(np.int64): _native.INDEX_FORMAT_INT64}


def _guide_cut_options(snap_fraction: Optional[float], simplify_fraction: Optional[float],
                       fair_passes: Optional[int] = None, fair_max_shift: Optional[float] = None):
    """mcon_guide_cut_options with the defaults, overridden where given."""
    o = _native.GuideCutOptions()
    check(_native.lib.mcon_guide_cut_options_init_sized(ctypes.byref(o), ctypes.sizeof(o)))
    if snap_fraction is not None:
        o.snap_fraction = float(snap_fraction)
    if simplify_fraction is not None:
        o.simplify_fraction = float(simplify_fraction)
    if fair_passes is not None:
        n = int(fair_passes)
        if not 0 <= n <= 0xFFFFFFFF:  # ctypes would wrap a negative count
            raise ValueError(f"fair_passes must be 0 (off) to 100, got {fair_passes}")
        o.fair_passes = n
    if fair_max_shift is not None:
        o.fair_max_shift = float(fair_max_shift)
    return o


class Mesh(_Handle):
    """A validated triangle mesh. ``positions``: (n, 3) float32/float64, ``triangles``: (m, 3) uint32,
    int32 or int64 (read as they are, no conversion; a negative or too large index is an
    InvalidMeshError, any other dtype a TypeError).

    Both may be row-strided views (interleaved vertex records, column slices, structured array
    fields) as long as each row's 3 values are contiguous and aligned; they are read in place.

    ``validate_locally=True`` (MCON_MESH_VALIDATE_LOCALLY) accepts defects no operation reads (a
    zero-area triangle, an edge of three triangles, a pinched or isolated vertex elsewhere on the
    body): ``Patch.extract`` then checks only the part of the host it reads, ``cut_guides`` the
    whole mesh, each raising InvalidMeshError that counts the offenders.
    """

    _release = _native.lib.mcon_mesh_release

    def __init__(self, context: Context, positions, triangles, validate_locally: bool = False):
        require_type(context, Context, "context")
        require_type(validate_locally, bool, "validate_locally")
        desc, keep = _mesh_desc(positions, triangles)
        desc.flags = _native.MESH_VALIDATE_LOCALLY if validate_locally else 0
        handle = ctypes.c_void_p()
        check(_native.lib.mcon_mesh_create(context.handle, ctypes.byref(desc), ctypes.byref(handle)))
        del keep  # the borrowed arrays lived through the call (the library copied them)
        super().__init__(handle)
        self.context = context  # keep the Python object alive as long as the mesh

    @property
    def counts(self) -> tuple[int, int]:
        """(vertex count, triangle count)."""
        nv, nt = _native.c_size(), _native.c_size()
        check(_native.lib.mcon_mesh_get_counts(self.handle, ctypes.byref(nv), ctypes.byref(nt)))
        return nv.value, nt.value

    @property
    def orientation(self) -> _native.MeshOrientationInfo:
        """What creating the mesh changed to orient it consistently and outward."""
        info = _native.MeshOrientationInfo()
        check(_native.lib.mcon_mesh_orientation_info_init_sized(ctypes.byref(info), ctypes.sizeof(info)))
        check(_native.lib.mcon_mesh_get_orientation(self.handle, ctypes.byref(info)))
        return info

    @property
    def reoriented_triangles(self) -> np.ndarray:
        """(m,) uint8: 1 where a triangle's corners 1 and 2 were swapped."""
        out = np.zeros(self.counts[1], dtype=np.uint8)
        check(_native.lib.mcon_mesh_get_reoriented_triangles(
            self.handle, out.ctypes.data_as(ctypes.POINTER(ctypes.c_uint8)), out.size))
        return out

    @property
    def triangles(self) -> np.ndarray:
        """(m, 3) uint32: the oriented triangles."""
        out = np.zeros((self.counts[1], 3), dtype=np.uint32)
        check(_native.lib.mcon_mesh_get_triangles(self.handle, out.ctypes.data_as(_native.c_uint32_p), out.size))
        return out

    def closest_points(self, points) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """The closest surface point to each of ``points`` ((n, 3) float64): (triangles (n,) uint32,
        barycentric (n, 3) in the triangle's corner order, distances (n,))."""
        return _closest_points(_native.lib.mcon_mesh_closest_points, self.handle, points)

    def cut_guides(self, guide_sets, snap_fraction: Optional[float] = None,
                   simplify_fraction: Optional[float] = None, fair_passes: Optional[int] = None,
                   fair_max_shift: Optional[float] = None):
        """Cuts the guides of several macro constraints into this whole mesh: ``guide_sets`` is a
        list of PolylineSets, each transferred onto a patch extracted from this mesh. Returns a
        :class:`CutMesh` covering every face, so its cross field and QuadWild files cover the
        whole model. Options as ``Patch.cut_guides``."""
        from .mapping import CutMesh, PolylineSet  # mapping imports this module

        sets = list(guide_sets)
        for i, s in enumerate(sets):
            require_type(s, PolylineSet, f"guide_sets[{i}]")
        o = _guide_cut_options(snap_fraction, simplify_fraction, fair_passes, fair_max_shift)
        handles = (ctypes.c_void_p * max(len(sets), 1))(*[s.handle for s in sets])
        out = ctypes.c_void_p()
        check(_native.lib.mcon_mesh_cut_guides(self.handle, handles, len(sets), ctypes.byref(o), ctypes.byref(out)))
        return CutMesh(out)

    def _repr_fields(self) -> str:
        nv, nt = self.counts
        return f"vertices={nv} triangles={nt}"


@dataclass(frozen=True)
class PatchInfo:
    """What extracting a patch measured (mcon_patch_info), as ``Patch.info`` returns it."""

    vertex_count: int
    triangle_count: int
    filled_triangle_count: int  # triangles that are not from the host mesh (filled holes)
    boundary_loops: int  # 1 for a valid patch
    euler_characteristic: int  # 1 for a valid patch
    radius: float  # geodesic radius in host units (the normalization scale)
    center: tuple  # (x, y, z) in host coordinates (the normalization origin)
    center_patch_triangle: int  # the center as a point of the patch: this triangle ...
    center_barycentric: tuple  # ... at these barycentric coordinates
    max_geodesic_distance: float  # measured again on the normalized patch: about 1
    param_flipped_triangles: int  # inverted triangles of the disk parametrization: 0
    # The host's orientation repair (Mesh.orientation): host triangles reoriented, host components
    # turned outward and made consistent, and how many of this patch's triangles lie in a
    # reoriented host triangle.
    host_reoriented_triangles: int
    host_outward_turned_components: int
    host_inconsistent_components: int
    reoriented_triangles: int

    @classmethod
    def _from_c(cls, i: _native.PatchInfo) -> "PatchInfo":
        return cls(i.vertex_count, i.triangle_count, i.filled_triangle_count, i.boundary_loops, i.euler_characteristic,
                   i.radius, tuple(i.center), i.center_patch_triangle, tuple(i.center_barycentric),
                   i.max_geodesic_distance, i.param_flipped_triangles, i.host_reoriented_triangles,
                   i.host_outward_turned_components, i.host_inconsistent_components, i.reoriented_triangles)


@dataclass(frozen=True)
class PatchRepairs:
    """What ``Patch.extract(..., repair=True)`` changed in the part of the host the patch read
    (mcon_patch_repair_info; all 0 without the repair)."""

    zero_area_triangles_removed: int  # zero-area triangles taken out (also those a merge emptied)
    triangles_split: int  # neighbours of a removed cap split at its corner
    vertices_merged: int  # coincident corners of a zero-area triangle made one vertex
    pinched_vertices_split: int  # host vertices of the patch that joined separate fans


class Patch(_Handle):
    """A geodesic disk cut out of a host mesh, normalized to geodesic radius 1."""

    _release = _native.lib.mcon_patch_release

    def __init__(self, handle: ctypes.c_void_p):
        super().__init__(handle)
        self._info = None
        self.context: Optional[Context] = None  # set by the constructors: keeps the log callback registered

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
        repair: bool = False,
    ) -> "Patch":
        """Cuts the geodesic disk of ``radius`` (host units) around a center on ``mesh``.

        The center is either host vertex ``center_vertex`` or the point of host triangle
        ``center_triangle`` at ``barycentric`` coordinates (3 weights, default its centroid); give
        exactly one of ``center_vertex`` and ``center_triangle`` (0-based). ``fill_holes`` fills enclosed
        pockets and inner holes (new triangles: ``info.filled_triangle_count``). Iso-line crossings
        closer to a vertex than ``snap_fraction`` of the local edge length snap onto it (range
        [0, 0.45]; None keeps the default 0.2). ``progress(fraction)`` is called as the cut
        proceeds; returning False cancels (CancelledError). ``repair`` (on a mesh made with
        ``validate_locally=True``) removes zero-area triangles and splits pinched vertices in the part
        of the host the patch reads instead of refusing them; ``Patch.repairs`` says what changed.
        Raises NotADiskError if the region is not a disk, InvalidArgumentError for an out-of-range
        center or radius, InvalidMeshError for a defect it does not repair.
        """
        require_type(mesh, Mesh, "mesh")
        options = _native.PatchOptions()
        check(_native.lib.mcon_patch_options_init_sized(ctypes.byref(options), ctypes.sizeof(options)))
        if (center_vertex is None) == (center_triangle is None):
            raise ValueError("give exactly one of center_vertex and center_triangle")
        if center_vertex is not None:
            if int(center_vertex) < 0:  # the C type would only say "outside the range of uint32"
                nv = mesh.counts[0]
                raise InvalidArgumentError(
                    2, f"center_vertex is {int(center_vertex)}, outside the range 0..{nv - 1}: vertex numbers "
                       f"count from 0 (the mesh has {nv} vertices)")
            options.center_vertex = int(center_vertex)
        else:
            if int(center_triangle) < 0:
                nt = mesh.counts[1]
                raise InvalidArgumentError(
                    2, f"center_triangle is {int(center_triangle)}, outside the range 0..{nt - 1}: triangle "
                       f"numbers count from 0 (the mesh has {nt} triangles)")
            options.center_vertex = _native.INVALID_INDEX
            options.center_triangle = int(center_triangle)
            for i, b in enumerate(barycentric):
                options.center_barycentric[i] = float(b)
        options.radius = float(radius)
        options.flags = (1 if fill_holes else 0) | (2 if repair else 0)  # MCON_PATCH_FILL_HOLES, _REPAIR_REGION
        if snap_fraction is not None:
            options.snap_fraction = float(snap_fraction)
        cb = _Progress(progress)
        options.progress = cb.c_fn
        handle = ctypes.c_void_p()
        status = _native.lib.mcon_patch_extract(mesh.handle, ctypes.byref(options), ctypes.byref(handle))
        cb.check(status)
        patch = cls(handle)
        patch.context = mesh.context  # errors on the patch go to this context's log callback
        return patch

    @classmethod
    def from_arrays(
        cls,
        context: Context,
        positions,
        triangles,
        center_triangle: int,
        center_barycentric=(1 / 3, 1 / 3, 1 / 3),
        origin=(0.0, 0.0, 0.0),
        scale: float = 1.0,
    ) -> "Patch":
        """A patch from an already normalized disk mesh (e.g. a library entry); nothing is cut.

        ``origin`` and ``scale`` place it in its own host units (host = origin + scale * p), where
        3D outputs of transfers onto this patch are expressed.
        """
        require_type(context, Context, "context")
        desc, keep = _mesh_desc(positions, triangles)
        frame = _native.PatchFrame()
        check(_native.lib.mcon_patch_frame_init_sized(ctypes.byref(frame), ctypes.sizeof(frame)))
        frame.center_triangle = int(center_triangle)
        if len(center_barycentric) != 3 or len(origin) != 3:
            raise ValueError("center_barycentric and origin need 3 values each")
        for i in range(3):
            frame.center_barycentric[i] = float(center_barycentric[i])
            frame.origin[i] = float(origin[i])
        frame.scale = float(scale)
        handle = ctypes.c_void_p()
        check(_native.lib.mcon_patch_create_from_arrays(context.handle, ctypes.byref(desc), ctypes.byref(frame),
                                                        ctypes.byref(handle)))
        del keep
        patch = cls(handle)
        patch.context = context
        return patch

    def cross_field(
        self,
        guides=None,
        alignment_weight: Optional[float] = None,
        align_to_boundary: bool = False,
        boundary_weight: Optional[float] = None,
    ) -> tuple[np.ndarray, np.ndarray]:
        """A smooth per-face 4-RoSy field following ``guides`` (a PolylineSet on this patch, or None).

        Returns (directions (m, 3), confidence (m,)).
        """
        from .mapping import PolylineSet  # mapping imports this module

        if guides is not None:
            require_type(guides, PolylineSet, "guides")
        o = _native.CrossFieldOptions()
        check(_native.lib.mcon_cross_field_options_init_sized(ctypes.byref(o), ctypes.sizeof(o)))
        if alignment_weight is not None:
            o.alignment_weight = float(alignment_weight)
        o.align_to_boundary = 1 if align_to_boundary else 0
        if boundary_weight is not None:
            o.boundary_weight = float(boundary_weight)
        m = self.triangle_count
        directions, confidence = np.empty((m, 3), np.float64), np.empty(m, np.float64)
        check(_native.lib.mcon_patch_compute_cross_field(self.handle, None if guides is None else guides.handle,
                                                         ctypes.byref(o), directions.ctypes.data,
                                                         confidence.ctypes.data, m))
        return directions, confidence

    def cut_guides(self, guides, snap_fraction: Optional[float] = None, simplify_fraction: Optional[float] = None,
                   fair_passes: Optional[int] = None, fair_max_shift: Optional[float] = None):
        """Cuts ``guides`` (a PolylineSet transferred onto this patch) into the patch: returns a
        :class:`CutMesh` in which every guide is a chain of edges (for a quad mesher's features).

        ``snap_fraction`` (default 0.25) and ``simplify_fraction`` (default 0.05) are fractions of an
        edge length; ``fair_passes`` (default 3, 0 = off) passes of chain fairing move chain vertices
        at most ``fair_max_shift`` (default 0.1) edge lengths; see mcon_guide_cut_options."""
        from .mapping import CutMesh, PolylineSet  # mapping imports this module

        require_type(guides, PolylineSet, "guides")
        o = _guide_cut_options(snap_fraction, simplify_fraction, fair_passes, fair_max_shift)
        out = ctypes.c_void_p()
        check(_native.lib.mcon_patch_cut_guides(self.handle, guides.handle, ctypes.byref(o), ctypes.byref(out)))
        return CutMesh(out)

    def write_rosy(self, directions, path) -> None:
        """Writes a QuadWild ``.rosy`` file; directions (triangle_count, 3) float64.

        A ``.gz`` path is refused (QuadWild reads a compressed ``.rosy`` as zeros)."""
        import os

        d = _as_array("directions", directions, (np.float64,), 3)
        if d.shape[0] != self.triangle_count:
            raise ValueError(f"directions has {d.shape[0]} rows, the patch {self.triangle_count} triangles")
        check_path(_native.lib.mcon_patch_write_rosy(self.handle, d.ctypes.data, d.shape[0], os.fsencode(path)), path,
                   writing=True)

    @property
    def info(self) -> PatchInfo:
        """A :class:`PatchInfo` (frozen dataclass): sizes, center, radius and checks of the cut."""
        if self._info is None:
            info = _native.PatchInfo()
            check(_native.lib.mcon_patch_info_init_sized(ctypes.byref(info), ctypes.sizeof(info)))
            check(_native.lib.mcon_patch_get_info(self.handle, ctypes.byref(info)))
            self._info = PatchInfo._from_c(info)
        return self._info

    @property
    def repairs(self) -> "PatchRepairs":
        """A :class:`PatchRepairs`: what ``repair=True`` changed (all 0 otherwise)."""
        r = _native.PatchRepairInfo()
        check(_native.lib.mcon_patch_repair_info_init_sized(ctypes.byref(r), ctypes.sizeof(r)))
        check(_native.lib.mcon_patch_get_repairs(self.handle, ctypes.byref(r)))
        return PatchRepairs(r.zero_area_triangles_removed, r.triangles_split, r.vertices_merged,
                            r.pinched_vertices_split)

    @property
    def vertex_count(self) -> int:
        """Number of patch vertices."""
        return self.info.vertex_count

    @property
    def triangle_count(self) -> int:
        """Number of patch triangles."""
        return self.info.triangle_count

    def _repr_fields(self) -> str:
        i = self.info
        return (f"vertices={i.vertex_count} triangles={i.triangle_count} radius={i.radius:g} "
                f"boundary_loops={i.boundary_loops}")

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
        """(m, 3) uint32 vertex indices, counter-clockwise as in the host."""
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
        """(m,) uint32: the host triangle each patch triangle lies in; 0xFFFFFFFF if it fills a hole."""
        out = np.empty(self.triangle_count, np.uint32)
        check(_native.lib.mcon_patch_get_host_triangles(self.handle, out.ctypes.data_as(_native.c_uint32_p), out.size))
        return out

    def closest_points(self, points) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """As :meth:`Mesh.closest_points` on this patch, with ``points`` and the distances in host
        units; triangles are the patch's own."""
        return _closest_points(_native.lib.mcon_patch_closest_points, self.handle, points)

    def distance_from_point(self, triangle: int, barycentric) -> np.ndarray:
        """(n,) geodesic distance (heat method, normalized units) of every vertex from the point at
        ``barycentric`` (3 weights, >= 0, sum 1) in patch triangle ``triangle``."""
        _native.check_value("triangle", triangle, ctypes.c_uint32)
        b = np.asarray(barycentric, np.float64).reshape(-1)
        if b.size != 3:
            raise ValueError(f"barycentric must hold 3 weights, got {b.size}")
        point = _native.SurfacePoint(int(triangle), (ctypes.c_double * 3)(*b.tolist()))
        out = np.empty(self.vertex_count, np.float64)
        check(_native.lib.mcon_patch_compute_distance_from_point(self.handle, ctypes.byref(point),
                                                                 out.ctypes.data_as(_native.c_double_p), out.size))
        return out

    def distance_from_vertices(self, vertices) -> np.ndarray:
        """(n,) geodesic distance of every vertex from the nearest of ``vertices`` (patch vertex
        numbers; order and repeats ignored), e.g. landmarks for map guidance channels."""
        v = np.asarray(vertices)
        if v.ndim != 1 or v.size == 0 or not np.issubdtype(v.dtype, np.integer):
            raise ValueError("vertices must be a non-empty 1-D array of vertex numbers")
        if v.min() < 0 or v.max() > 0xFFFFFFFF:
            raise ValueError("vertices must be in 0..2**32-1")
        v = np.ascontiguousarray(v, np.uint32)
        out = np.empty(self.vertex_count, np.float64)
        check(_native.lib.mcon_patch_compute_distance_from_vertices(self.handle, v.ctypes.data, v.size,
                                                                    out.ctypes.data_as(_native.c_double_p), out.size))
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


__all__ = ["Context", "Mesh", "Patch", "PatchInfo", "LogCallbackWarning", "Error", "CancelledError", "version", "shutdown", "close_all"]

"""Re-embedding maps and constraint transfer (mcon_map_*, mcon_polyline_set_*)."""
from __future__ import annotations

import ctypes
from dataclasses import dataclass
from enum import IntEnum
from typing import Dict, List, Optional, Sequence, Tuple

import numpy as np

from . import _native
from ._arrays import checked, ptr, rows, strided_rows, vector3
from .core import Patch, ProgressCallback, _Handle, _Progress, require_type
from .errors import check
from .library import FieldKind, Polyline


class StopReason(IntEnum):
    """Why the map optimization stopped (``MapInfo.stop_reason``)."""

    CONVERGED = 1
    STALLED = 2
    ITERATION_CAP = 3
    CANCELLED = 4


class Direction(IntEnum):
    """Which patch's vertices ``Map.correspondences`` locates on the other."""

    SOURCE_TO_TARGET = 1
    TARGET_TO_SOURCE = 2


class Orientation(IntEnum):
    """mcon_map_orientation: let the descriptors decide, or force one orientation."""
    AUTOMATIC = 0
    PRESERVE = 1
    REVERSE = 2


_ORIENTATIONS = {"automatic": Orientation.AUTOMATIC, "preserve": Orientation.PRESERVE,
                 "reverse": Orientation.REVERSE}


@dataclass(frozen=True)
class MapInfo:
    """What computing a map measured (mcon_map_info), as ``Map.info`` returns it: overlap, energies,
    iterations and why it stopped, the orientation decision and its evidence, timings."""

    source_vertex_count: int
    target_vertex_count: int
    source_vertices_inside: int
    target_vertices_inside: int
    overlap_ratio: float
    matching_score: float
    energy_total: float
    energy_descriptor: float
    energy_distortion: float
    energy_area: float
    energy_injectivity: float
    iterations: int
    stop_reason: StopReason
    reflected: bool
    levels: int
    flipped_triangles: int
    alignment_score: float
    alignment_seconds: float
    optimization_seconds: float
    # Evidence of the orientation decision: rigid scores of each orientation's best candidate
    # (-1: not tried), whether both were optimized and compared, and their level-0 energies
    # (-1: not compared).
    alignment_score_unreflected: float
    alignment_score_reflected: float
    orientation_compared: bool
    level0_energy_unreflected: float
    level0_energy_reflected: float
    frame_decided: bool = False  # the world-frame start decided (use_world_frame)
    # Coarse to fine in mesh resolution (Map.compute's coarse_stages): the coarse source's vertices
    # (0: not used), the stages run on it, the folds of its prolonged map that were untangled, and
    # whether they could not be (those stages then ran again on the full source).
    coarse_vertices: int = 0
    coarse_stages: int = 0
    coarse_folds: int = 0
    coarse_fallback: bool = False


class PolylineSet(_Handle):
    """Polylines re-traced on a target patch (every segment inside one target triangle)."""

    _release = _native.lib.mcon_polyline_set_release

    @property
    def counts(self) -> Tuple[int, int]:
        """(polyline count, point count)."""
        n, p = _native.c_size(), _native.c_size()
        check(_native.lib.mcon_polyline_set_get_counts(self.handle, ctypes.byref(n), ctypes.byref(p)))
        return n.value, p.value

    def __len__(self) -> int:
        return self.counts[0]

    def polyline_arrays(self) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(sizes uint32, closed bool, input_polyline uint32), one per polyline."""
        n = self.counts[0]
        sizes, closed, source = np.zeros(n, np.uint32), np.zeros(n, np.uint8), np.zeros(n, np.uint32)
        check(_native.lib.mcon_polyline_set_get_polylines(self.handle, ptr(sizes), ptr(closed), ptr(source), n))
        return sizes, closed.astype(bool), source

    def _repr_fields(self) -> str:
        n, p = self.counts
        return f"polylines={n} points={p}"

    def point_arrays(self) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
        """(triangles (p,) uint32, barycentric (p, 3), xyz (p, 3) in the target's host units)."""
        p = self.counts[1]
        tri, bary, xyz = np.zeros(p, np.uint32), np.zeros((p, 3)), np.zeros((p, 3))
        check(_native.lib.mcon_polyline_set_get_points(self.handle, ptr(tri), ptr(bary), ptr(xyz), p))
        return tri, bary, xyz

    def polylines(self) -> List[Polyline]:
        """The set as Polyline objects (kind GUIDE), e.g. to store in a library entry of the target."""
        sizes, closed, _ = self.polyline_arrays()
        tri, bary, _ = self.point_arrays()
        starts = np.concatenate([[0], np.cumsum(sizes, dtype=np.int64)])
        return [Polyline(tri[a:b].copy(), bary[a:b].copy(), closed=bool(c))
                for a, b, c in zip(starts[:-1], starts[1:], closed)]


@dataclass(frozen=True)
class CutMeshInfo:
    """What cutting guides into a patch made (mcon_cut_mesh_info), as ``CutMesh.info`` returns it."""

    vertex_count: int
    triangle_count: int
    guide_count: int
    guide_vertex_count: int
    guide_edge_count: int
    cut_triangle_count: int
    min_angle_created: float  # degrees
    min_angle_of_cut_input: float  # degrees
    snapped_to_vertices: int
    merged_crossings: int
    dropped_points: int
    shortcuts: int
    moved_vertices: int
    unplaced_points: int  # Mesh.cut_guides only: points on hole-filling triangles, dropped
    split_guides: int  # Mesh.cut_guides only: guides split into pieces there
    faired_vertices: int  # chain vertices moved by fairing (fair_passes)


class CutMesh(_Handle):
    """A patch with its guides cut in: every guide a chain of edges (``Patch.cut_guides``), or the
    whole host mesh with the guides of several patches cut in (``Mesh.cut_guides``).

    Positions are in the host's units; each vertex keeps its point on the patch (on the mesh for
    ``Mesh.cut_guides``)."""

    _release = _native.lib.mcon_cut_mesh_release

    @property
    def info(self) -> CutMeshInfo:
        """A :class:`CutMeshInfo` (frozen dataclass): sizes and the smallest angle the cut made."""
        i = _native.CutMeshInfo()
        check(_native.lib.mcon_cut_mesh_info_init_sized(ctypes.byref(i), ctypes.sizeof(i)))
        check(_native.lib.mcon_cut_mesh_get_info(self.handle, ctypes.byref(i)))
        return CutMeshInfo(*(getattr(i, f) for f, _ in _native.CutMeshInfo._fields_[1:]))

    def _repr_fields(self) -> str:
        i = self.info
        return f"vertices={i.vertex_count} triangles={i.triangle_count} guide_edges={i.guide_edge_count}"

    @property
    def positions(self) -> np.ndarray:
        """(n, 3) float64 vertex positions in the patch's host units."""
        n = self.info.vertex_count
        out = np.zeros((n, 3))
        check(_native.lib.mcon_cut_mesh_get_positions(self.handle, ptr(out), 3 * n))
        return out

    @property
    def triangles(self) -> np.ndarray:
        """(m, 3) uint32 triangles, in the patch's winding."""
        m = self.info.triangle_count
        out = np.zeros((m, 3), np.uint32)
        check(_native.lib.mcon_cut_mesh_get_triangles(self.handle, ptr(out), 3 * m))
        return out

    def host_points(self) -> Tuple[np.ndarray, np.ndarray]:
        """Per vertex its point on the patch: (patch triangles (n,) uint32, barycentric (n, 3))."""
        n = self.info.vertex_count
        tri, bary = np.zeros(n, np.uint32), np.zeros((n, 3))
        check(_native.lib.mcon_cut_mesh_get_host_points(self.handle, ptr(tri), ptr(bary), n))
        return tri, bary

    @property
    def guide_edges(self) -> np.ndarray:
        """(k, 2) uint32: the distinct guide edges as vertex pairs."""
        k = self.info.guide_edge_count
        out = np.zeros((k, 2), np.uint32)
        check(_native.lib.mcon_cut_mesh_get_guide_edges(self.handle, ptr(out), 2 * k))
        return out

    @property
    def guides(self) -> List[np.ndarray]:
        """One uint32 vertex chain per guide (a closed guide repeats its first vertex at the end)."""
        i = self.info
        sizes, chain = np.zeros(i.guide_count, np.uint32), np.zeros(i.guide_vertex_count, np.uint32)
        check(_native.lib.mcon_cut_mesh_get_guides(self.handle, ptr(sizes), i.guide_count, ptr(chain),
                                                   i.guide_vertex_count))
        starts = np.concatenate([[0], np.cumsum(sizes, dtype=np.int64)])
        return [chain[a:b].copy() for a, b in zip(starts[:-1], starts[1:])]

    @property
    def guide_origins(self) -> np.ndarray:
        """(guides, 2) uint32: per guide chain its guide set (0 for ``Patch.cut_guides``) and the
        polyline of that set it comes from."""
        n = self.info.guide_count
        sets, lines = np.zeros(n, np.uint32), np.zeros(n, np.uint32)
        check(_native.lib.mcon_cut_mesh_get_guide_origins(self.handle, ptr(sets), ptr(lines), n))
        return np.stack([sets, lines], axis=1)

    def carry_field(self, values) -> np.ndarray:
        """A per-vertex field of the patch (of the mesh for ``Mesh.cut_guides``; (vertices,) or
        (vertices, d) float64) at the cut mesh's vertices, interpolated at their host points."""
        a = np.ascontiguousarray(np.asarray(values, dtype=np.float64))
        one = a.ndim == 1
        a2 = a.reshape(a.shape[0], 1) if one else a
        if a2.ndim != 2 or a2.shape[1] < 1:
            raise ValueError(f"values must be (patch vertices,) or (patch vertices, d), got shape {a.shape}")
        d = a2.shape[1]
        out = np.zeros((self.info.vertex_count, d))
        check(_native.lib.mcon_cut_mesh_carry_field(self.handle, d, ptr(a2), a2.size, ptr(out), out.size))
        return out[:, 0] if one else out

    def cross_field(self) -> np.ndarray:
        """(m, 3) per-face cross directions: exactly along the guide edges on their faces, smooth elsewhere."""
        m = self.info.triangle_count
        out = np.zeros((m, 3))
        check(_native.lib.mcon_cut_mesh_compute_cross_field(self.handle, ptr(out), m))
        return out

    def write_quadwild(self, path_prefix) -> None:
        """Writes QuadWild's inputs side by side: ``<prefix>.obj``, ``.rosy``, ``.sharp``, and a
        ``.quadwild.json`` manifest (face count, the OBJ's hash, QuadWild's command lines)."""
        import os

        from .errors import check_path

        prefix = os.fspath(path_prefix)
        check_path(_native.lib.mcon_cut_mesh_write_quadwild(self.handle, os.fsencode(prefix)), prefix + ".obj",
                   writing=True)


def _unstrided_rows(name: str, array, dtype, copy: bool, accepted: Optional[str] = None) -> np.ndarray:
    """Per-vertex input of a C function that takes no stride (mcon_map_transfer_field and
    _labels read vertex-major packed rows): a row-strided array cannot be passed in place, so it is
    a ValueError unless the caller asked for ``copy=True``, which packs it once."""
    a = np.asarray(array)
    if copy:
        a = np.ascontiguousarray(a)
    elif not a.flags.c_contiguous:
        raise ValueError(f"{name} must be C-contiguous: the C function takes no row stride (pass copy=True to pack "
                         "a strided array, or use numpy.ascontiguousarray)")
    if accepted is not None and a.dtype != np.dtype(dtype):
        raise TypeError(f"{name} must have dtype {accepted}, got {a.dtype}")
    return rows(name, a, dtype)


def _points(name: str, triangles, barycentric) -> Tuple[np.ndarray, np.ndarray]:
    t = checked(f"{name} triangles", triangles, np.uint32, (None,))
    b = checked(f"{name} barycentric", barycentric, np.float64, (t.shape[0], 3))
    return t, b


class Map(_Handle):
    """The re-embedding map Phi from a source patch onto a target patch (locally injective, partial)."""

    _release = _native.lib.mcon_map_release

    def __init__(self, handle: ctypes.c_void_p, source: Patch, target: Patch):
        super().__init__(handle)
        self.source, self.target = source, target
        # The C map keeps its own references to both patches: its methods work after the Python
        # patches are closed, so the vertex counts are read once, here.
        self._source_vertices, self._target_vertices = source.vertex_count, target.vertex_count

    @classmethod
    def compute(
        cls,
        source: Patch,
        target: Patch,
        seed: int = 0,
        alignment_samples: Optional[int] = None,
        allow_reflection: bool = True,
        max_iterations: Optional[int] = None,
        progress: Optional[ProgressCallback] = None,
        orientation: str = "automatic",
        source_guidance=None,
        target_guidance=None,
        guidance_weight: Optional[float] = None,
        refine_sigma_factor: Optional[float] = None,
        use_world_frame: bool = False,
        world_frame_mirror: bool = False,
        world_frame_anchor: Optional[float] = None,
        source_up=None,
        target_up=None,
        coarse_stages: Optional[int] = None,
        coarse_vertices: Optional[int] = None,
    ) -> "Map":
        """orientation: "automatic" (the descriptors decide; allow_reflection restricts it),
        "preserve" or "reverse" (forced, e.g. a "flip" that recomputes with the orientation
        opposite to info.reflected).

        source_guidance / target_guidance: optional float64 arrays, (source vertices, d) and
        (target vertices, d) (or (n,) for d = 1; rows may be strided), of per-vertex values that
        must agree between corresponding points (painted region ids, landmark distances), for
        what the geometry cannot tell apart; each column is normalized over both patches and
        scaled by guidance_weight. Give both or neither.

        refine_sigma_factor: Gaussian width factor of the refinement pass after the finest level
        (0 turns the pass off; else in (0, 1]).

        use_world_frame: both patches sit in one world frame (two meshes in the same DCC scene): the
        similarity-ICP alignment of their host positions becomes the rigid start and decides
        orientation and reflection (info.frame_decided); needs orientation "automatic".
        world_frame_mirror: mirror the source x -> -x first (a left part onto a right one).
        world_frame_anchor: with use_world_frame, the weight (finite, >= 0; 0 = off) of the term
        that keeps each source point near the target point closest to it in 3D after that alignment.

        source_up / target_up: up directions (3 finite numbers each, in each host's own
        coordinates; give both or neither) that the rigid start must respect, so the map is never
        upside down; a vector (nearly) normal to its patch at the center is an InvalidArgumentError.

        coarse_stages / coarse_vertices: the first coarse_stages optimization stages (default 3,
        0 = off) run on a copy of the source coarsened to max(coarse_vertices, n / 4) vertices
        (default 1000) when the source has at least 2 * coarse_vertices (info.coarse_*).

        Options left at None keep mcon_map_options_init's defaults."""
        require_type(source, Patch, "source")
        require_type(target, Patch, "target")
        if not isinstance(orientation, str) or orientation not in _ORIENTATIONS:
            raise ValueError(f"orientation must be one of {sorted(_ORIENTATIONS)}, got {orientation!r}")
        o = _native.MapOptions()
        check(_native.lib.mcon_map_options_init_sized(ctypes.byref(o), ctypes.sizeof(o)))
        o.seed = int(seed)
        if alignment_samples is not None:
            o.alignment_samples = int(alignment_samples)
        o.allow_reflection = 1 if allow_reflection else 0
        if max_iterations is not None:
            o.max_iterations = int(max_iterations)
        o.orientation = int(_ORIENTATIONS[orientation])
        o.use_world_frame = 1 if use_world_frame else 0
        o.world_frame_mirror = 1 if world_frame_mirror else 0
        if world_frame_anchor is not None:
            o.world_frame_anchor = float(world_frame_anchor)
        if (source_up is None) != (target_up is None):
            raise ValueError("source_up and target_up must be given together")
        if source_up is not None:
            for name, up, field in (("source_up", source_up, o.source_up), ("target_up", target_up, o.target_up)):
                field[:] = vector3(name, up)
            o.use_up_hints = 1
        if refine_sigma_factor is not None:
            o.refine_sigma_factor = float(refine_sigma_factor)
        if coarse_stages is not None:
            o.coarse_stages = int(coarse_stages)
        if coarse_vertices is not None:
            o.coarse_vertices = int(coarse_vertices)
        if (source_guidance is None) != (target_guidance is None):
            raise ValueError("source_guidance and target_guidance must be given together")
        if source_guidance is not None:
            # gs / gt are locals until the function returns, so the memory stays valid for the call.
            gs, ss = strided_rows("source_guidance", source_guidance, np.float64, vector=True)
            gt, st = strided_rows("target_guidance", target_guidance, np.float64, vector=True)
            if gs.shape[1] != gt.shape[1]:
                raise ValueError(f"source_guidance and target_guidance need the same number of columns, got "
                                 f"{gs.shape[1]} and {gt.shape[1]}")
            if gs.shape[0] != source.vertex_count or gt.shape[0] != target.vertex_count:
                raise ValueError(f"guidance needs one row per patch vertex: source {source.vertex_count}, target "
                                 f"{target.vertex_count}, got {gs.shape[0]} and {gt.shape[0]}")
            o.source_guidance, o.source_guidance_stride = ptr(gs), ss
            o.target_guidance, o.target_guidance_stride = ptr(gt), st
            o.guidance_dimension = gs.shape[1]
            if guidance_weight is not None:
                o.guidance_weight = float(guidance_weight)
        cb = _Progress(progress)
        o.progress = cb.c_fn
        handle = ctypes.c_void_p()
        cb.check(_native.lib.mcon_map_compute(source.handle, target.handle, ctypes.byref(o), ctypes.byref(handle)))
        return cls(handle, source, target)

    def _repr_fields(self) -> str:
        i = self.info
        return (f"source_vertices={i.source_vertex_count} target_vertices={i.target_vertex_count} "
                f"overlap={i.overlap_ratio:.3g} iterations={i.iterations} stop={i.stop_reason.name} "
                f"reflected={i.reflected}")

    @property
    def info(self) -> MapInfo:
        """A :class:`MapInfo` (frozen dataclass) of the computed map."""
        i = _native.MapInfo()
        check(_native.lib.mcon_map_info_init_sized(ctypes.byref(i), ctypes.sizeof(i)))
        check(_native.lib.mcon_map_get_info(self.handle, ctypes.byref(i)))
        return MapInfo(i.source_vertex_count, i.target_vertex_count, i.source_vertices_inside, i.target_vertices_inside,
                       i.overlap_ratio, i.matching_score, i.energy_total, i.energy_descriptor, i.energy_distortion,
                       i.energy_area, i.energy_injectivity, i.iterations, StopReason(i.stop_reason), bool(i.reflected),
                       i.levels, i.flipped_triangles, i.alignment_score, i.alignment_seconds, i.optimization_seconds,
                       i.alignment_score_unreflected, i.alignment_score_reflected, bool(i.orientation_compared),
                       i.level0_energy_unreflected, i.level0_energy_reflected, bool(i.frame_decided),
                       i.coarse_vertices, i.coarse_stages, i.coarse_folds, bool(i.coarse_fallback))

    @property
    def energy_terms(self) -> Dict[str, float]:
        """The energy terms in evaluation order: name -> final unweighted value."""
        n = ctypes.c_uint32()
        check(_native.lib.mcon_map_get_energy_term_count(self.handle, ctypes.byref(n)))
        out = {}
        for k in range(n.value):
            name, value = ctypes.c_char_p(), ctypes.c_double()
            check(_native.lib.mcon_map_get_energy_term(self.handle, k, ctypes.byref(name), ctypes.byref(value)))
            out[name.value.decode("utf-8")] = value.value
        return out

    def correspondences(self, direction: Direction = Direction.SOURCE_TO_TARGET) -> Tuple[np.ndarray, np.ndarray]:
        """Per vertex of the direction's domain: (triangle of the other patch, -1 = outside; barycentric (n, 3))."""
        d = Direction(direction)
        n = self._source_vertices if d == Direction.SOURCE_TO_TARGET else self._target_vertices
        tri, bary = np.zeros(n, np.int32), np.zeros((n, 3))
        check(_native.lib.mcon_map_get_correspondences(self.handle, int(d), ptr(tri), ptr(bary), n))
        return tri, bary

    @property
    def phi(self) -> np.ndarray:
        """(source vertices, 2): the deformed source disk in the target disk's plane."""
        out = np.zeros((self._source_vertices, 2))
        check(_native.lib.mcon_map_get_phi(self.handle, ptr(out), out.size))
        return out

    @property
    def outside_mask(self) -> np.ndarray:
        """(target vertices,) bool: True where a target vertex has no source preimage."""
        out = np.zeros(self._target_vertices, np.uint8)
        check(_native.lib.mcon_map_get_outside_mask(self.handle, ptr(out), out.size))
        return out.astype(bool)

    def transfer_points(self, triangles, barycentric) -> Tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Source points -> (target triangles (0xFFFFFFFF = outside), barycentric (n, 3), xyz (n, 3))."""
        t, b = _points("points", triangles, barycentric)
        n = t.shape[0]
        ot, ob, oxyz = np.zeros(n, np.uint32), np.zeros((n, 3)), np.zeros((n, 3))
        check(_native.lib.mcon_map_transfer_points(self.handle, ptr(t), ptr(b), n, ptr(ot), ptr(ob), ptr(oxyz), n))
        return ot, ob, oxyz

    def transfer_polylines(self, polylines: Sequence[Polyline]) -> PolylineSet:
        """Source polylines (e.g. ``Entry.polylines``) mapped and re-traced on the target."""
        if isinstance(polylines, Polyline):
            polylines = [polylines]
        parts_t, parts_b, sizes, closed = [], [], [], []
        for i, line in enumerate(polylines):
            require_type(line, Polyline, "polylines[i]")
            t, b = _points(f"polylines[{i}]", line.faces, line.barycentric)
            parts_t.append(t), parts_b.append(b), sizes.append(t.shape[0]), closed.append(1 if line.closed else 0)
        t = np.concatenate(parts_t) if parts_t else np.zeros(0, np.uint32)
        b = np.concatenate(parts_b) if parts_b else np.zeros((0, 3))
        s, c = np.array(sizes, np.uint32), np.array(closed, np.uint8)
        handle = ctypes.c_void_p()
        check(_native.lib.mcon_map_transfer_polylines(self.handle, ptr(t), ptr(b), t.shape[0], ptr(s), ptr(c), s.size,
                                                      ctypes.byref(handle)))
        return PolylineSet(handle)

    def transfer_field(self, values, kind: FieldKind = FieldKind.SCALAR, copy: bool = False) -> np.ndarray:
        """A per-source-vertex float64 or float32 field (n,) or (n, d) -> (target vertices, d) of the
        same dtype; outside gets 0. float32 goes through mcon_map_transfer_field_f32 (computed in
        double, rounded once), so it is the float64 result of the widened values, cast to float32.

        ``values`` must be C-contiguous: mcon_map_transfer_field has no stride. ``copy=True`` packs
        a strided array (a field inside interleaved records) once before the call instead of
        raising ValueError. Any other dtype is a TypeError (no silent conversion).
        """
        k = FieldKind(kind)
        if k == FieldKind.INTEGER_LABEL:
            raise ValueError("integer labels go through transfer_labels (never blended)")
        dtype = np.float32 if np.asarray(values).dtype == np.float32 else np.float64
        v = _unstrided_rows("values", values, dtype, copy, accepted="float64 or float32")
        if v.shape[0] != self._source_vertices:
            raise ValueError(f"values has {v.shape[0]} rows, the source {self._source_vertices} vertices")
        out = np.zeros((self._target_vertices, v.shape[1]), dtype)
        fn = _native.lib.mcon_map_transfer_field_f32 if dtype == np.float32 else _native.lib.mcon_map_transfer_field
        check(fn(self.handle, int(k), v.shape[1], ptr(v), v.size, ptr(out), out.size))
        return out

    def transfer_labels(self, labels, outside_label: int = -1, copy: bool = False) -> np.ndarray:
        """Per-source-vertex int32 labels (n,) or (n, d) -> (target vertices, d), never blended.

        C-contiguous only (no stride in mcon_map_transfer_labels); ``copy=True`` as in transfer_field.
        """
        v = _unstrided_rows("labels", labels, np.int32, copy)
        if v.shape[0] != self._source_vertices:
            raise ValueError(f"labels has {v.shape[0]} rows, the source {self._source_vertices} vertices")
        out = np.zeros((self._target_vertices, v.shape[1]), np.int32)
        check(_native.lib.mcon_map_transfer_labels(self.handle, v.shape[1], ptr(v), v.size, int(outside_label), ptr(out),
                                                   out.size))
        return out


__all__ = ["Map", "MapInfo", "PolylineSet", "StopReason", "Direction"]

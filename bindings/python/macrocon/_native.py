"""Loading libmacrocon and declaring the C ABI for ctypes (one place, mirrors macrocon.h)."""
from __future__ import annotations

import ctypes
import ctypes.util
import numbers
import os
import sys
from pathlib import Path

#: The C ABI major version this package was written for; must equal the library's.
ABI_MAJOR = 0

c_status = ctypes.c_int32
c_size = ctypes.c_size_t
c_double_p = ctypes.POINTER(ctypes.c_double)
c_uint32_p = ctypes.POINTER(ctypes.c_uint32)

PROGRESS_CALLBACK = ctypes.CFUNCTYPE(ctypes.c_int32, ctypes.c_void_p, ctypes.c_double)
LOG_CALLBACK = ctypes.CFUNCTYPE(None, ctypes.c_void_p, ctypes.c_int32, ctypes.c_char_p)

INVALID_INDEX = 0xFFFFFFFF

# ctypes converts Python ints by truncation (2**32 + 5 becomes 5) and c_char_p stops at the first
# NUL, so every integer and string that crosses the boundary is checked here first: structure
# fields on assignment (Struct) and scalar arguments of every declared function.
_INT_RANGES = {
    t: ((0, 2 ** (8 * ctypes.sizeof(t)) - 1) if t(-1).value > 0 else
        (-(2 ** (8 * ctypes.sizeof(t) - 1)), 2 ** (8 * ctypes.sizeof(t) - 1) - 1))
    for t in (ctypes.c_int8, ctypes.c_uint8, ctypes.c_int16, ctypes.c_uint16, ctypes.c_int32, ctypes.c_uint32,
              ctypes.c_int64, ctypes.c_uint64, ctypes.c_size_t)
}


def check_value(what: str, value, ctype) -> None:
    """InvalidArgumentError for an integer outside ``ctype``'s range or a string with a NUL byte."""
    problem = None
    if ctype in _INT_RANGES and isinstance(value, numbers.Integral) and not isinstance(value, bool):
        lo, hi = _INT_RANGES[ctype]
        if not lo <= int(value) <= hi:
            problem = f"{what} is {int(value)}, outside the range of its C type ({lo}..{hi})"
    elif ctype is ctypes.c_char_p and isinstance(value, (bytes, str)):
        if (b"\0" if isinstance(value, bytes) else "\0") in value:
            problem = f"{what} contains a NUL character, which would cut the string short on the C side"
    if problem:
        from .errors import InvalidArgumentError  # errors imports this module

        raise InvalidArgumentError(2, problem)


class Struct(ctypes.Structure):
    """A ctypes structure whose integer and string fields are range- and NUL-checked on assignment."""

    def __setattr__(self, name, value):
        for field in type(self)._fields_:
            if field[0] == name:
                check_value(f"{type(self).__name__}.{name}", value, field[1])
                break
        super().__setattr__(name, value)


class ContextOptions(Struct):
    _fields_ = [
        ("struct_size", ctypes.c_uint32),
        ("max_threads", ctypes.c_uint32),
        ("log_callback", LOG_CALLBACK),
        ("log_user_data", ctypes.c_void_p),
    ]


class MeshDesc(Struct):
    _fields_ = [
        ("struct_size", ctypes.c_uint32),
        ("positions", ctypes.c_void_p),
        ("position_type", ctypes.c_uint32),
        ("position_stride", c_size),
        ("vertex_count", c_size),
        ("indices", ctypes.c_void_p),
        ("index_stride", c_size),
        ("triangle_count", c_size),
        ("index_format", ctypes.c_uint32),  # appended: mcon_index_format
        ("flags", ctypes.c_uint32),  # appended: mcon_mesh_flags
    ]


#: mcon_mesh_flags (mcon_mesh_desc.flags).
MESH_VALIDATE_LOCALLY = 1 << 0

#: mcon_index_format values (mcon_mesh_desc.index_format).
INDEX_FORMAT_UINT32, INDEX_FORMAT_INT32, INDEX_FORMAT_INT64 = 0, 1, 2


class PatchOptions(Struct):
    _fields_ = [
        ("struct_size", ctypes.c_uint32),
        ("center_vertex", ctypes.c_uint32),
        ("center_triangle", ctypes.c_uint32),
        ("center_barycentric", ctypes.c_double * 3),
        ("radius", ctypes.c_double),
        ("flags", ctypes.c_uint32),
        ("snap_fraction", ctypes.c_double),
        ("progress", PROGRESS_CALLBACK),
        ("progress_user_data", ctypes.c_void_p),
    ]


class PatchInfo(Struct):
    _fields_ = [
        ("struct_size", ctypes.c_uint32),
        ("vertex_count", c_size),
        ("triangle_count", c_size),
        ("filled_triangle_count", c_size),
        ("boundary_loops", ctypes.c_uint32),
        ("euler_characteristic", ctypes.c_int32),
        ("radius", ctypes.c_double),
        ("center", ctypes.c_double * 3),
        ("center_patch_triangle", ctypes.c_uint32),
        ("center_barycentric", ctypes.c_double * 3),
        ("max_geodesic_distance", ctypes.c_double),
        ("param_flipped_triangles", ctypes.c_uint32),
        ("host_reoriented_triangles", c_size),
        ("host_outward_turned_components", ctypes.c_uint32),
        ("host_inconsistent_components", ctypes.c_uint32),
        ("reoriented_triangles", c_size),
    ]


class PatchRepairInfo(Struct):
    _fields_ = [
        ("struct_size", ctypes.c_uint32),
        ("zero_area_triangles_removed", ctypes.c_uint32),
        ("triangles_split", ctypes.c_uint32),
        ("vertices_merged", ctypes.c_uint32),
        ("pinched_vertices_split", ctypes.c_uint32),
    ]


class MeshOrientationInfo(Struct):
    _fields_ = [
        ("struct_size", ctypes.c_uint32),
        ("reoriented_triangles", c_size),
        ("component_count", ctypes.c_uint32),
        ("closed_component_count", ctypes.c_uint32),
        ("inconsistent_component_count", ctypes.c_uint32),
        ("outward_turned_component_count", ctypes.c_uint32),
    ]


# ---- constraint libraries and retrieval (mcon_library_*) ----

class SurfacePoint(Struct):
    _fields_ = [("face", ctypes.c_uint32), ("barycentric", ctypes.c_double * 3)]


class Polyline(Struct):
    _fields_ = [
        ("kind", ctypes.c_uint32),
        ("closed", ctypes.c_uint32),
        ("points", ctypes.c_void_p),
        ("point_count", c_size),
    ]


class Singularity(Struct):
    _fields_ = [("location", SurfacePoint), ("index_quarters", ctypes.c_int32)]


class VertexField(Struct):
    _fields_ = [
        ("name", ctypes.c_char_p),
        ("kind", ctypes.c_uint32),
        ("dimension", ctypes.c_uint32),
        ("values", ctypes.c_void_p),
        ("labels", ctypes.c_void_p),
        ("stride", c_size),
    ]


class LibraryEntryDesc(Struct):
    _fields_ = [
        ("struct_size", ctypes.c_uint32),
        ("patch", ctypes.c_void_p),
        ("id", ctypes.c_uint64),
        ("name", ctypes.c_char_p),
        ("class_label", ctypes.c_char_p),
        ("tags", ctypes.POINTER(ctypes.c_char_p)),
        ("tag_count", c_size),
        ("author", ctypes.c_char_p),
        ("licence", ctypes.c_char_p),
        ("polylines", ctypes.POINTER(Polyline)),
        ("polyline_count", c_size),
        ("singularities", ctypes.c_void_p),
        ("singularity_count", c_size),
        ("fields", ctypes.POINTER(VertexField)),
        ("field_count", c_size),
        ("descriptors", ctypes.c_void_p),
        ("descriptor_dimension", ctypes.c_uint32),
        ("descriptor_stride", c_size),
        ("has_up", ctypes.c_uint32),
        ("up", ctypes.c_double * 3),
    ]


class LibraryInfo(Struct):
    _fields_ = [
        ("struct_size", ctypes.c_uint32),
        ("entry_count", c_size),
        ("descriptor", ctypes.c_uint32),
        ("descriptor_dimension", ctypes.c_uint32),
        ("vocabulary_size", ctypes.c_uint32),
        ("rings", ctypes.c_uint32),
        ("histogram_length", ctypes.c_uint32),
        ("sigma_bof", ctypes.c_double),
        ("seed", ctypes.c_uint64),
        ("format_version", ctypes.c_uint32),
        ("checksum_verified", ctypes.c_uint32),
    ]


class RetrievalOptions(Struct):
    _fields_ = [
        ("struct_size", ctypes.c_uint32),
        ("descriptor", ctypes.c_uint32),
        ("vocabulary_size", ctypes.c_uint32),
        ("rings", ctypes.c_uint32),
        ("sigma_bof", ctypes.c_double),
        ("seed", ctypes.c_uint64),
        ("progress", PROGRESS_CALLBACK),
        ("progress_user_data", ctypes.c_void_p),
    ]


class LibraryEntryInfo(Struct):
    _fields_ = [
        ("struct_size", ctypes.c_uint32),
        ("id", ctypes.c_uint64),
        ("vertex_count", c_size),
        ("triangle_count", c_size),
        ("tag_count", c_size),
        ("polyline_count", c_size),
        ("singularity_count", c_size),
        ("field_count", c_size),
        ("center", SurfacePoint),
        ("source_scale", ctypes.c_double),
        ("source_origin", ctypes.c_double * 3),
        ("has_up", ctypes.c_uint32),
        ("up", ctypes.c_double * 3),
    ]


# ---- re-embedding maps and transfer (mcon_map_*) ----

class PatchFrame(Struct):
    _fields_ = [
        ("struct_size", ctypes.c_uint32),
        ("center_triangle", ctypes.c_uint32),
        ("center_barycentric", ctypes.c_double * 3),
        ("origin", ctypes.c_double * 3),
        ("scale", ctypes.c_double),
    ]


class MapOptions(Struct):
    _fields_ = [
        ("struct_size", ctypes.c_uint32),
        ("seed", ctypes.c_uint64),
        ("alignment_samples", ctypes.c_uint32),
        ("allow_reflection", ctypes.c_uint32),
        ("max_iterations", ctypes.c_uint32),
        ("progress", PROGRESS_CALLBACK),
        ("progress_user_data", ctypes.c_void_p),
        ("orientation", ctypes.c_uint32),
        ("source_guidance", ctypes.c_void_p),
        ("source_guidance_stride", c_size),
        ("target_guidance", ctypes.c_void_p),
        ("target_guidance_stride", c_size),
        ("guidance_dimension", ctypes.c_uint32),
        ("guidance_weight", ctypes.c_double),
        ("refine_sigma_factor", ctypes.c_double),
        ("use_world_frame", ctypes.c_uint32),
        ("world_frame_mirror", ctypes.c_uint32),
        ("world_frame_anchor", ctypes.c_double),
        ("use_up_hints", ctypes.c_uint32),
        ("source_up", ctypes.c_double * 3),
        ("target_up", ctypes.c_double * 3),
        ("coarse_stages", ctypes.c_uint32),
        ("coarse_vertices", ctypes.c_uint32),
    ]


class MapInfo(Struct):
    _fields_ = [
        ("struct_size", ctypes.c_uint32),
        ("source_vertex_count", c_size),
        ("target_vertex_count", c_size),
        ("source_vertices_inside", c_size),
        ("target_vertices_inside", c_size),
        ("overlap_ratio", ctypes.c_double),
        ("matching_score", ctypes.c_double),
        ("energy_total", ctypes.c_double),
        ("energy_descriptor", ctypes.c_double),
        ("energy_distortion", ctypes.c_double),
        ("energy_area", ctypes.c_double),
        ("energy_injectivity", ctypes.c_double),
        ("iterations", ctypes.c_uint32),
        ("stop_reason", ctypes.c_uint32),
        ("reflected", ctypes.c_uint32),
        ("levels", ctypes.c_uint32),
        ("flipped_triangles", ctypes.c_uint32),
        ("alignment_score", ctypes.c_double),
        ("alignment_seconds", ctypes.c_double),
        ("optimization_seconds", ctypes.c_double),
        ("alignment_score_unreflected", ctypes.c_double),
        ("alignment_score_reflected", ctypes.c_double),
        ("orientation_compared", ctypes.c_uint32),
        ("level0_energy_unreflected", ctypes.c_double),
        ("level0_energy_reflected", ctypes.c_double),
        ("frame_decided", ctypes.c_uint32),
        ("coarse_vertices", ctypes.c_uint32),
        ("coarse_stages", ctypes.c_uint32),
        ("coarse_folds", ctypes.c_uint32),
        ("coarse_fallback", ctypes.c_uint32),
    ]


class GuideCutOptions(Struct):
    _fields_ = [
        ("struct_size", ctypes.c_uint32),
        ("snap_fraction", ctypes.c_double),
        ("simplify_fraction", ctypes.c_double),
        ("fair_passes", ctypes.c_uint32),
        ("fair_max_shift", ctypes.c_double),
    ]


class CutMeshInfo(Struct):
    _fields_ = [
        ("struct_size", ctypes.c_uint32),
        ("vertex_count", c_size),
        ("triangle_count", c_size),
        ("guide_count", c_size),
        ("guide_vertex_count", c_size),
        ("guide_edge_count", c_size),
        ("cut_triangle_count", c_size),
        ("min_angle_created", ctypes.c_double),
        ("min_angle_of_cut_input", ctypes.c_double),
        ("snapped_to_vertices", ctypes.c_uint32),
        ("merged_crossings", ctypes.c_uint32),
        ("dropped_points", ctypes.c_uint32),
        ("shortcuts", ctypes.c_uint32),
        ("moved_vertices", ctypes.c_uint32),
        ("unplaced_points", ctypes.c_uint32),
        ("split_guides", ctypes.c_uint32),
        ("faired_vertices", ctypes.c_uint32),
    ]


class CrossFieldOptions(Struct):
    _fields_ = [
        ("struct_size", ctypes.c_uint32),
        ("alignment_weight", ctypes.c_double),
        ("align_to_boundary", ctypes.c_uint32),
        ("boundary_weight", ctypes.c_double),
    ]


def _candidates() -> list[str]:
    env = os.environ.get("MACROCON_LIBRARY")
    if env:
        return [env]
    here = Path(__file__).resolve().parent
    found = sorted(here.glob("libmacrocon.so*")) + sorted(here.glob("macrocon.dll")) + sorted(here.glob("libmacrocon*.dylib"))
    names = [str(p) for p in found]
    system = ctypes.util.find_library("macrocon")
    if system:
        names.append(system)
    return names


def _load() -> ctypes.CDLL:
    errors = []
    for name in _candidates():
        try:
            return ctypes.CDLL(name)
        except OSError as exc:  # keep looking, report all at the end
            errors.append(f"{name}: {exc}")
    raise ImportError(
        "macrocon: cannot load the native library libmacrocon "
        "(set MACROCON_LIBRARY to its path, or install the wheel that bundles it)"
        + ("; tried " + "; ".join(errors) if errors else "")
    )


lib = _load()


def library_path() -> str:
    """The path of the native library this package loaded (as given to the loader)."""
    return lib._name


def starter_library() -> str:
    """The path of the starter constraint library (``starter.mclb``), for ``Library.open``.

    ``MACROCON_STARTER_LIBRARY`` if set (it must exist), else the copy next to this package (the
    wheel), else ``share/macrocon/starter.mclb`` beside the loaded native library's ``lib`` folder
    (an install prefix or the build tree: ``<prefix>/lib[/<triplet>]/libmacrocon.so`` ->
    ``<prefix>/share/macrocon/starter.mclb``). Raises FileNotFoundError naming what was tried.
    """
    env = os.environ.get("MACROCON_STARTER_LIBRARY")
    if env:
        if not Path(env).is_file():
            raise FileNotFoundError(f"macrocon: MACROCON_STARTER_LIBRARY={env!r} is not a file")
        return env
    tried = [Path(__file__).resolve().parent / "starter.mclb"]
    if lib._name and os.sep in lib._name:  # a path, not a bare soname found by the loader
        lib_dir = Path(lib._name).resolve().parent
        tried += [lib_dir.parent / "share" / "macrocon" / "starter.mclb",
                  lib_dir.parent.parent / "share" / "macrocon" / "starter.mclb"]
    for path in tried:
        if path.is_file():
            return str(path)
    raise FileNotFoundError("macrocon: no starter library (starter.mclb); tried "
                            + ", ".join(str(p) for p in tried) + " (set MACROCON_STARTER_LIBRARY)")

_SIGNATURES = {
    "mcon_get_version": [ctypes.POINTER(ctypes.c_uint32)] * 3,
    "mcon_get_status_name": [c_status, ctypes.POINTER(ctypes.c_char_p)],
    "mcon_get_last_error": [ctypes.c_void_p, ctypes.POINTER(ctypes.c_char_p)],
    "mcon_shutdown": [],
    "mcon_context_options_init_sized": [ctypes.POINTER(ContextOptions), ctypes.c_size_t],
    "mcon_context_create": [ctypes.POINTER(ContextOptions), ctypes.POINTER(ctypes.c_void_p)],
    "mcon_context_retain": [ctypes.c_void_p],
    "mcon_context_release": [ctypes.c_void_p],
    "mcon_mesh_desc_init_sized": [ctypes.POINTER(MeshDesc), ctypes.c_size_t],
    "mcon_mesh_create": [ctypes.c_void_p, ctypes.POINTER(MeshDesc), ctypes.POINTER(ctypes.c_void_p)],
    "mcon_mesh_retain": [ctypes.c_void_p],
    "mcon_mesh_release": [ctypes.c_void_p],
    "mcon_mesh_get_counts": [ctypes.c_void_p, ctypes.POINTER(c_size), ctypes.POINTER(c_size)],
    "mcon_mesh_orientation_info_init_sized": [ctypes.POINTER(MeshOrientationInfo), ctypes.c_size_t],
    "mcon_mesh_get_orientation": [ctypes.c_void_p, ctypes.POINTER(MeshOrientationInfo)],
    "mcon_mesh_get_reoriented_triangles": [ctypes.c_void_p, ctypes.POINTER(ctypes.c_uint8), c_size],
    "mcon_mesh_get_triangles": [ctypes.c_void_p, c_uint32_p, c_size],
    "mcon_mesh_closest_points": [ctypes.c_void_p, ctypes.c_void_p, c_size, ctypes.c_void_p, ctypes.c_void_p,
                                 ctypes.c_void_p],
    "mcon_patch_options_init_sized": [ctypes.POINTER(PatchOptions), ctypes.c_size_t],
    "mcon_patch_extract": [ctypes.c_void_p, ctypes.POINTER(PatchOptions), ctypes.POINTER(ctypes.c_void_p)],
    "mcon_patch_retain": [ctypes.c_void_p],
    "mcon_patch_release": [ctypes.c_void_p],
    "mcon_patch_info_init_sized": [ctypes.POINTER(PatchInfo), ctypes.c_size_t],
    "mcon_patch_get_info": [ctypes.c_void_p, ctypes.POINTER(PatchInfo)],
    "mcon_patch_repair_info_init_sized": [ctypes.POINTER(PatchRepairInfo), ctypes.c_size_t],
    "mcon_patch_get_repairs": [ctypes.c_void_p, ctypes.POINTER(PatchRepairInfo)],
    "mcon_patch_get_positions": [ctypes.c_void_p, c_double_p, c_size],
    "mcon_patch_get_triangles": [ctypes.c_void_p, c_uint32_p, c_size],
    "mcon_patch_get_uv": [ctypes.c_void_p, c_double_p, c_size],
    "mcon_patch_get_host_vertices": [ctypes.c_void_p, c_uint32_p, c_uint32_p, c_double_p, c_size],
    "mcon_patch_get_host_triangles": [ctypes.c_void_p, c_uint32_p, c_size],
    "mcon_patch_compute_distance_from_point": [ctypes.c_void_p, ctypes.POINTER(SurfacePoint), ctypes.c_void_p, c_size],
    "mcon_patch_compute_distance_from_vertices": [ctypes.c_void_p, ctypes.c_void_p, c_size, ctypes.c_void_p, c_size],
    "mcon_patch_closest_points": [ctypes.c_void_p, ctypes.c_void_p, c_size, ctypes.c_void_p, ctypes.c_void_p,
                                  ctypes.c_void_p],
    "mcon_descriptor_get_dimension": [ctypes.c_int32, ctypes.POINTER(ctypes.c_uint32)],
    "mcon_patch_compute_descriptors": [ctypes.c_void_p, ctypes.c_int32, c_double_p, c_size],
    # constraint libraries and retrieval; array pointers are c_void_p (numpy .ctypes.data or None)
    "mcon_library_entry_desc_init_sized": [ctypes.POINTER(LibraryEntryDesc), ctypes.c_size_t],
    "mcon_library_create": [ctypes.c_void_p, ctypes.POINTER(ctypes.c_void_p)],
    "mcon_library_open": [ctypes.c_void_p, ctypes.c_char_p, ctypes.POINTER(ctypes.c_void_p)],
    "mcon_library_open_memory": [ctypes.c_void_p, ctypes.c_void_p, c_size, ctypes.POINTER(ctypes.c_void_p)],
    "mcon_library_retain": [ctypes.c_void_p],
    "mcon_library_release": [ctypes.c_void_p],
    "mcon_library_save": [ctypes.c_void_p, ctypes.c_char_p],
    "mcon_library_save_memory": [ctypes.c_void_p, ctypes.c_void_p, c_size, ctypes.POINTER(c_size)],
    "mcon_library_info_init_sized": [ctypes.POINTER(LibraryInfo), ctypes.c_size_t],
    "mcon_library_get_info": [ctypes.c_void_p, ctypes.POINTER(LibraryInfo)],
    "mcon_library_get_count": [ctypes.c_void_p, ctypes.POINTER(c_size)],
    "mcon_library_get_string": [ctypes.c_void_p, ctypes.c_uint32, ctypes.c_void_p, c_size, ctypes.POINTER(c_size)],
    "mcon_library_set_string": [ctypes.c_void_p, ctypes.c_uint32, ctypes.c_char_p],
    "mcon_library_set_descriptor": [ctypes.c_void_p, ctypes.c_uint32],
    "mcon_retrieval_descriptor_from_name": [ctypes.c_char_p, ctypes.POINTER(ctypes.c_uint32)],
    "mcon_library_add_entry": [ctypes.c_void_p, ctypes.POINTER(LibraryEntryDesc), ctypes.POINTER(ctypes.c_uint64)],
    "mcon_library_remove_entry": [ctypes.c_void_p, ctypes.c_uint64],
    "mcon_library_find_entry": [ctypes.c_void_p, ctypes.c_uint64, ctypes.POINTER(c_size)],
    "mcon_library_merge": [ctypes.c_void_p, ctypes.c_void_p],
    "mcon_retrieval_options_init_sized": [ctypes.POINTER(RetrievalOptions), ctypes.c_size_t],
    "mcon_library_build_retrieval": [ctypes.c_void_p, ctypes.POINTER(RetrievalOptions)],
    "mcon_library_query": [ctypes.c_void_p, ctypes.c_void_p, c_size, ctypes.c_void_p, ctypes.c_void_p,
                           ctypes.c_void_p, c_size, ctypes.POINTER(c_size)],
    "mcon_library_query_distinct": [ctypes.c_void_p, ctypes.c_void_p, c_size, ctypes.c_void_p, ctypes.c_void_p,
                                    ctypes.c_void_p, ctypes.c_void_p, c_size, ctypes.POINTER(c_size)],
    "mcon_library_query_descriptors": [ctypes.c_void_p, ctypes.c_void_p, ctypes.c_void_p, ctypes.c_uint32, c_size,
                                       c_size, ctypes.c_void_p, ctypes.c_void_p, ctypes.c_void_p, c_size,
                                       ctypes.POINTER(c_size)],
    "mcon_library_entry_info_init_sized": [ctypes.POINTER(LibraryEntryInfo), ctypes.c_size_t],
    "mcon_library_get_entry_info": [ctypes.c_void_p, c_size, ctypes.POINTER(LibraryEntryInfo)],
    "mcon_library_get_entry_string": [ctypes.c_void_p, c_size, ctypes.c_uint32, c_size, ctypes.c_void_p, c_size,
                                      ctypes.POINTER(c_size)],
    "mcon_library_get_entry_positions": [ctypes.c_void_p, c_size, ctypes.c_void_p, c_size],
    "mcon_library_get_entry_triangles": [ctypes.c_void_p, c_size, ctypes.c_void_p, c_size],
    "mcon_library_get_entry_polyline": [ctypes.c_void_p, c_size, c_size, ctypes.POINTER(ctypes.c_uint32),
                                        ctypes.POINTER(ctypes.c_uint32), ctypes.POINTER(c_size), ctypes.c_void_p, c_size],
    "mcon_library_get_entry_singularities": [ctypes.c_void_p, c_size, ctypes.c_void_p, c_size],
    "mcon_library_get_entry_field": [ctypes.c_void_p, c_size, c_size, ctypes.POINTER(ctypes.c_uint32),
                                     ctypes.POINTER(ctypes.c_uint32), ctypes.c_void_p, ctypes.c_void_p, c_size],
    "mcon_library_get_entry_retrieval": [ctypes.c_void_p, c_size, ctypes.c_void_p, c_size, ctypes.c_void_p, c_size],
    # maps and transfer
    "mcon_patch_frame_init_sized": [ctypes.POINTER(PatchFrame), ctypes.c_size_t],
    "mcon_patch_create_from_arrays": [ctypes.c_void_p, ctypes.POINTER(MeshDesc), ctypes.POINTER(PatchFrame),
                                      ctypes.POINTER(ctypes.c_void_p)],
    "mcon_map_options_init_sized": [ctypes.POINTER(MapOptions), ctypes.c_size_t],
    "mcon_map_compute": [ctypes.c_void_p, ctypes.c_void_p, ctypes.POINTER(MapOptions), ctypes.POINTER(ctypes.c_void_p)],
    "mcon_map_retain": [ctypes.c_void_p],
    "mcon_map_release": [ctypes.c_void_p],
    "mcon_map_info_init_sized": [ctypes.POINTER(MapInfo), ctypes.c_size_t],
    "mcon_map_get_info": [ctypes.c_void_p, ctypes.POINTER(MapInfo)],
    "mcon_map_get_energy_term_count": [ctypes.c_void_p, ctypes.POINTER(ctypes.c_uint32)],
    "mcon_map_get_energy_term": [ctypes.c_void_p, ctypes.c_uint32, ctypes.POINTER(ctypes.c_char_p),
                                 ctypes.POINTER(ctypes.c_double)],
    "mcon_map_get_correspondences": [ctypes.c_void_p, ctypes.c_int32, ctypes.c_void_p, ctypes.c_void_p, c_size],
    "mcon_map_get_phi": [ctypes.c_void_p, ctypes.c_void_p, c_size],
    "mcon_map_get_outside_mask": [ctypes.c_void_p, ctypes.c_void_p, c_size],
    "mcon_map_transfer_points": [ctypes.c_void_p, ctypes.c_void_p, ctypes.c_void_p, c_size, ctypes.c_void_p,
                                 ctypes.c_void_p, ctypes.c_void_p, c_size],
    "mcon_map_transfer_polylines": [ctypes.c_void_p, ctypes.c_void_p, ctypes.c_void_p, c_size, ctypes.c_void_p,
                                    ctypes.c_void_p, c_size, ctypes.POINTER(ctypes.c_void_p)],
    "mcon_polyline_set_retain": [ctypes.c_void_p],
    "mcon_polyline_set_release": [ctypes.c_void_p],
    "mcon_polyline_set_get_counts": [ctypes.c_void_p, ctypes.POINTER(c_size), ctypes.POINTER(c_size)],
    "mcon_polyline_set_get_polylines": [ctypes.c_void_p, ctypes.c_void_p, ctypes.c_void_p, ctypes.c_void_p, c_size],
    "mcon_polyline_set_get_points": [ctypes.c_void_p, ctypes.c_void_p, ctypes.c_void_p, ctypes.c_void_p, c_size],
    "mcon_map_transfer_field": [ctypes.c_void_p, ctypes.c_int32, ctypes.c_uint32, ctypes.c_void_p, c_size,
                                ctypes.c_void_p, c_size],
    "mcon_map_transfer_field_f32": [ctypes.c_void_p, ctypes.c_int32, ctypes.c_uint32, ctypes.c_void_p, c_size,
                                    ctypes.c_void_p, c_size],
    "mcon_map_transfer_labels": [ctypes.c_void_p, ctypes.c_uint32, ctypes.c_void_p, c_size, ctypes.c_int32,
                                 ctypes.c_void_p, c_size],
    "mcon_cross_field_options_init_sized": [ctypes.POINTER(CrossFieldOptions), ctypes.c_size_t],
    "mcon_patch_compute_cross_field": [ctypes.c_void_p, ctypes.c_void_p, ctypes.POINTER(CrossFieldOptions),
                                       ctypes.c_void_p, ctypes.c_void_p, c_size],
    "mcon_patch_write_rosy": [ctypes.c_void_p, ctypes.c_void_p, c_size, ctypes.c_char_p],
    "mcon_guide_cut_options_init_sized": [ctypes.POINTER(GuideCutOptions), ctypes.c_size_t],
    "mcon_cut_mesh_info_init_sized": [ctypes.POINTER(CutMeshInfo), ctypes.c_size_t],
    "mcon_patch_cut_guides": [ctypes.c_void_p, ctypes.c_void_p, ctypes.POINTER(GuideCutOptions),
                              ctypes.POINTER(ctypes.c_void_p)],
    "mcon_mesh_cut_guides": [ctypes.c_void_p, ctypes.c_void_p, c_size, ctypes.POINTER(GuideCutOptions),
                             ctypes.POINTER(ctypes.c_void_p)],
    "mcon_cut_mesh_get_guide_origins": [ctypes.c_void_p, ctypes.c_void_p, ctypes.c_void_p, c_size],
    "mcon_cut_mesh_retain": [ctypes.c_void_p],
    "mcon_cut_mesh_release": [ctypes.c_void_p],
    "mcon_cut_mesh_get_info": [ctypes.c_void_p, ctypes.POINTER(CutMeshInfo)],
    "mcon_cut_mesh_get_positions": [ctypes.c_void_p, ctypes.c_void_p, c_size],
    "mcon_cut_mesh_get_triangles": [ctypes.c_void_p, ctypes.c_void_p, c_size],
    "mcon_cut_mesh_get_host_points": [ctypes.c_void_p, ctypes.c_void_p, ctypes.c_void_p, c_size],
    "mcon_cut_mesh_get_guide_edges": [ctypes.c_void_p, ctypes.c_void_p, c_size],
    "mcon_cut_mesh_get_guides": [ctypes.c_void_p, ctypes.c_void_p, c_size, ctypes.c_void_p, c_size],
    "mcon_cut_mesh_carry_field": [ctypes.c_void_p, ctypes.c_uint32, ctypes.c_void_p, c_size, ctypes.c_void_p, c_size],
    "mcon_cut_mesh_compute_cross_field": [ctypes.c_void_p, ctypes.c_void_p, c_size],
    "mcon_cut_mesh_write_quadwild": [ctypes.c_void_p, ctypes.c_char_p],
}

#: Functions this package declares that the loaded library does not export (a build older than
#: the header, or an API still being implemented). Calling one raises NotImplementedError.
MISSING: list[str] = []


def _missing(name: str):
    def call(*_args):
        raise NotImplementedError(f"{name} is declared in macrocon.h but not exported by the loaded libmacrocon")

    return call


def _checked_call(name: str, fn, argtypes):
    """``fn`` with its integer and string arguments checked (check_value) before the call."""
    checks = [(i, t) for i, t in enumerate(argtypes) if t in _INT_RANGES or t is ctypes.c_char_p]

    def call(*args):
        for i, t in checks:
            if i < len(args):
                check_value(f"{name} argument {i + 1}", args[i], t)
        return fn(*args)

    call.__name__ = name
    return call


for _name, _args in _SIGNATURES.items():
    try:
        _fn = getattr(lib, _name)
    except AttributeError:
        MISSING.append(_name)
        setattr(lib, _name, _missing(_name))
        continue
    _fn.argtypes = _args
    _fn.restype = c_status
    if any(t in _INT_RANGES or t is ctypes.c_char_p for t in _args):
        setattr(lib, _name, _checked_call(_name, _fn, _args))


def library_version() -> tuple[int, int, int]:
    """(major, minor, patch) of the loaded native library (``mcon_get_version``)."""
    major, minor, patch = ctypes.c_uint32(), ctypes.c_uint32(), ctypes.c_uint32()
    lib.mcon_get_version(ctypes.byref(major), ctypes.byref(minor), ctypes.byref(patch))
    return major.value, minor.value, patch.value


if library_version()[0] != ABI_MAJOR:
    raise ImportError(
        f"macrocon: the native library has ABI major version {library_version()[0]}, "
        f"this Python package needs {ABI_MAJOR}"
    )

if sys.byteorder != "little":  # pragma: no cover - the SDK ships little-endian builds only
    raise ImportError("macrocon: big-endian platforms are not supported")

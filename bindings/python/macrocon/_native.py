"""Loading libmacrocon and declaring the C ABI for ctypes (one place, mirrors macrocon.h)."""
from __future__ import annotations

import ctypes
import ctypes.util
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


class ContextOptions(ctypes.Structure):
    _fields_ = [
        ("struct_size", ctypes.c_uint32),
        ("max_threads", ctypes.c_uint32),
        ("log_callback", LOG_CALLBACK),
        ("log_user_data", ctypes.c_void_p),
    ]


class MeshDesc(ctypes.Structure):
    _fields_ = [
        ("struct_size", ctypes.c_uint32),
        ("positions", ctypes.c_void_p),
        ("position_type", ctypes.c_uint32),
        ("position_stride", c_size),
        ("vertex_count", c_size),
        ("indices", ctypes.c_void_p),
        ("index_stride", c_size),
        ("triangle_count", c_size),
    ]


class PatchOptions(ctypes.Structure):
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


class PatchInfo(ctypes.Structure):
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

_SIGNATURES = {
    "mcon_get_version": [ctypes.POINTER(ctypes.c_uint32)] * 3,
    "mcon_get_status_name": [c_status, ctypes.POINTER(ctypes.c_char_p)],
    "mcon_get_last_error": [ctypes.c_void_p, ctypes.POINTER(ctypes.c_char_p)],
    "mcon_shutdown": [],
    "mcon_context_options_init": [ctypes.POINTER(ContextOptions)],
    "mcon_context_create": [ctypes.POINTER(ContextOptions), ctypes.POINTER(ctypes.c_void_p)],
    "mcon_context_retain": [ctypes.c_void_p],
    "mcon_context_release": [ctypes.c_void_p],
    "mcon_mesh_desc_init": [ctypes.POINTER(MeshDesc)],
    "mcon_mesh_create": [ctypes.c_void_p, ctypes.POINTER(MeshDesc), ctypes.POINTER(ctypes.c_void_p)],
    "mcon_mesh_retain": [ctypes.c_void_p],
    "mcon_mesh_release": [ctypes.c_void_p],
    "mcon_mesh_get_counts": [ctypes.c_void_p, ctypes.POINTER(c_size), ctypes.POINTER(c_size)],
    "mcon_patch_options_init": [ctypes.POINTER(PatchOptions)],
    "mcon_patch_extract": [ctypes.c_void_p, ctypes.POINTER(PatchOptions), ctypes.POINTER(ctypes.c_void_p)],
    "mcon_patch_retain": [ctypes.c_void_p],
    "mcon_patch_release": [ctypes.c_void_p],
    "mcon_patch_info_init": [ctypes.POINTER(PatchInfo)],
    "mcon_patch_get_info": [ctypes.c_void_p, ctypes.POINTER(PatchInfo)],
    "mcon_patch_get_positions": [ctypes.c_void_p, c_double_p, c_size],
    "mcon_patch_get_triangles": [ctypes.c_void_p, c_uint32_p, c_size],
    "mcon_patch_get_uv": [ctypes.c_void_p, c_double_p, c_size],
    "mcon_patch_get_host_vertices": [ctypes.c_void_p, c_uint32_p, c_uint32_p, c_double_p, c_size],
    "mcon_patch_get_host_triangles": [ctypes.c_void_p, c_uint32_p, c_size],
    "mcon_descriptor_get_dimension": [ctypes.c_int32, ctypes.POINTER(ctypes.c_uint32)],
    "mcon_patch_compute_descriptors": [ctypes.c_void_p, ctypes.c_int32, c_double_p, c_size],
}

for _name, _args in _SIGNATURES.items():
    _fn = getattr(lib, _name)
    _fn.argtypes = _args
    _fn.restype = c_status


def library_version() -> tuple[int, int, int]:
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

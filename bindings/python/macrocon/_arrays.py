"""Checks on numpy arrays handed to the C side: dtype, shape and contiguity, before any call.

The C API copies every input array before it returns, so a checked array only has to stay
alive for the duration of the call; callers keep the returned array in a local variable (or in a
``keep`` list) until then.
"""
from __future__ import annotations

from typing import Optional, Sequence

import numpy as np

#: numpy layout of mcon_surface_point (uint32 face, 4 bytes padding, 3 doubles) and of
#: mcon_singularity (a surface point, then int32 index_quarters, padded to 40 bytes).
SURFACE_POINT = np.dtype([("face", "<u4"), ("barycentric", "<f8", (3,))], align=True)
SINGULARITY = np.dtype([("location", SURFACE_POINT), ("index_quarters", "<i4")], align=True)
assert SURFACE_POINT.itemsize == 32 and SINGULARITY.itemsize == 40


def checked(name: str, array, dtype, shape: Sequence[Optional[int]]) -> np.ndarray:
    """``array`` as an ndarray of exactly ``dtype`` and ``shape`` (None = any length), C-contiguous.

    Never converts silently: a wrong dtype is a TypeError, a wrong shape or layout a ValueError.
    """
    a = np.asarray(array)
    if a.dtype != np.dtype(dtype):
        raise TypeError(f"{name} must have dtype {np.dtype(dtype)}, got {a.dtype}")
    if a.ndim != len(shape) or any(s is not None and s != d for s, d in zip(shape, a.shape)):
        want = "(" + ", ".join("n" if s is None else str(s) for s in shape) + ("," if len(shape) == 1 else "") + ")"
        raise ValueError(f"{name} must have shape {want}, got {a.shape}")
    if not a.flags.c_contiguous:
        raise ValueError(f"{name} must be C-contiguous (use numpy.ascontiguousarray)")
    return a


def rows(name: str, array, dtype) -> np.ndarray:
    """A per-vertex array: (n,) is taken as (n, 1); (n, d) stays as is."""
    a = np.asarray(array)
    if a.ndim == 1:
        a = a.reshape(-1, 1)
    return checked(name, a, dtype, (None, None))


def ptr(a: Optional[np.ndarray]) -> Optional[int]:
    """The data pointer for a c_void_p argument (None for NULL)."""
    return None if a is None else a.ctypes.data

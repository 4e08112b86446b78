"""Checks on numpy arrays handed to the C side: dtype, shape and layout, before any call.

Where the C API takes a byte stride for an input (mesh positions and indices, library fields and
descriptors, query descriptors), ``strided_rows`` accepts row-strided arrays and passes their
stride; every other input must be C-contiguous (``checked`` / ``rows``).

The C API copies every input array before it returns, so a checked array only has to stay
alive for the duration of the call; callers keep the returned array in a local variable (or in a
``keep`` list) until then.
"""
from __future__ import annotations

from typing import Optional, Sequence, Tuple

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


def vector3(name: str, value) -> Tuple[float, float, float]:
    """A direction given as 3 numbers (a sequence or an array of 3); ValueError naming it otherwise.
    Finiteness and zero length are the C API's to refuse (NON_FINITE, INVALID_ARGUMENT)."""
    v = np.asarray(value, dtype=np.float64).reshape(-1)
    if v.shape != (3,):
        raise ValueError(f"{name} must have 3 components, got shape {np.shape(value)}")
    return float(v[0]), float(v[1]), float(v[2])


def rows(name: str, array, dtype) -> np.ndarray:
    """A per-vertex array: (n,) is taken as (n, 1); (n, d) stays as is."""
    a = np.asarray(array)
    if a.ndim == 1:
        a = a.reshape(-1, 1)
    return checked(name, a, dtype, (None, None))


def strided_rows(name: str, array, dtypes, columns: Optional[int] = None, vector: bool = False) -> Tuple[np.ndarray, int]:
    """``array`` as per-row input for a C parameter that takes a byte stride, without copying.

    Returns ``(a, stride)``: ``a`` is the same memory (keep it alive until the call returns) and
    ``stride`` the byte distance between rows to pass to the C side (0 = tightly packed, used when
    there are fewer than two rows, whose stride numpy leaves arbitrary). Accepted: a 2-D array
    (1-D too if ``vector``, taken as one column) of one of ``dtypes`` whose rows may lie anywhere
    ``a.strides[0] > 0`` bytes apart, as long as

    - the elements of a row are contiguous (``a.strides[1] == itemsize``),
    - rows do not overlap (``a.strides[0] >= columns * itemsize``) and
    - the data pointer and ``a.strides[0]`` are multiples of the dtype's alignment (the C side
      declares ``const double*`` / ``const uint32_t*``: a packed, unaligned structured field
      needs ``align=True``).

    So a column slice ``big[:, 2:5]`` of a wider array and a field ``rec["pos"]`` of an aligned
    structured array go through as they are. Anything else (negative or zero row strides,
    non-contiguous columns, Fortran order) is a ValueError, never a silent copy.
    """
    dtypes = tuple(np.dtype(d) for d in (dtypes if isinstance(dtypes, (tuple, list)) else (dtypes,)))
    a = np.asarray(array)
    if a.dtype not in dtypes:
        raise TypeError(f"{name} must have dtype {' or '.join(str(d) for d in dtypes)}, got {a.dtype}")
    if vector and a.ndim == 1:
        a = a[:, None]  # a view: keeps a column slice's stride
    if a.ndim != 2 or (columns is not None and a.shape[1] != columns):
        want = f"(n, {columns})" if columns is not None else "(n, d)"
        raise ValueError(f"{name} must have shape {want}{' or (n,)' if vector else ''}, got {a.shape}")
    itemsize, align = a.dtype.itemsize, a.dtype.alignment
    row_bytes = a.shape[1] * itemsize
    if a.shape[0] > 0 and a.shape[1] > 1 and a.strides[1] != itemsize:  # numpy gives empty arrays strides (0, 0)
        raise ValueError(f"{name}: the values of a row must be contiguous (strides[1] == {itemsize}), got strides "
                         f"{a.strides}: rows may be strided, columns not (numpy.ascontiguousarray makes a C-contiguous copy)")
    if a.shape[0] < 2:
        stride = 0
    else:
        stride = a.strides[0]
        if stride <= 0:
            raise ValueError(f"{name}: row stride {stride} is not positive (reversed or broadcast rows); "
                             "use numpy.ascontiguousarray")
        if stride < row_bytes:
            raise ValueError(f"{name}: row stride {stride} is smaller than a row ({row_bytes} bytes)")
        if stride % align:
            raise ValueError(f"{name}: row stride {stride} is not a multiple of the {a.dtype} alignment ({align}); "
                             "use an aligned structured dtype (align=True) or numpy.ascontiguousarray")
    if a.size and a.ctypes.data % align:
        raise ValueError(f"{name}: data is not {align}-byte aligned for {a.dtype} (an unaligned structured field? "
                         "use align=True or numpy.ascontiguousarray)")
    return a, stride


def ptr(a: Optional[np.ndarray]) -> Optional[int]:
    """The data pointer for a c_void_p argument (None for NULL)."""
    return None if a is None else a.ctypes.data

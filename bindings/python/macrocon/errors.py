"""Exceptions raised for non-OK status codes of the C ABI."""
from __future__ import annotations

import ctypes
import errno
import os

from . import _native


class Error(Exception):
    """A Macrocon call failed. ``status`` is the C status code, ``message`` the library's text."""

    status: int = 1

    def __init__(self, status: int, message: str):
        super().__init__(f"{status_name(status)}: {message}")
        self.status = status
        self.message = message


class InvalidArgumentError(Error, ValueError):
    """MCON_ERROR_INVALID_ARGUMENT: an argument is outside its documented range."""


class NullPointerError(InvalidArgumentError):
    """MCON_ERROR_NULL_POINTER: a required pointer or handle was NULL (e.g. a closed handle)."""


class StructSizeError(Error):
    """MCON_ERROR_STRUCT_SIZE: an options or info struct is smaller than the library's first version."""


class OutOfMemoryError(Error, MemoryError):
    """MCON_ERROR_OUT_OF_MEMORY: the library could not allocate."""


class BufferTooSmallError(Error):
    """MCON_ERROR_BUFFER_TOO_SMALL: an output array is smaller than the result (a binding bug)."""


class CancelledError(Error):
    """MCON_ERROR_CANCELLED: a progress callback returned False; every object stays valid."""


class IOError_(Error, OSError):
    """MCON_ERROR_IO: a file could not be read or written (also an ``OSError``)."""


class FileNotFoundError_(IOError_, FileNotFoundError):
    """MCON_ERROR_IO for a path that does not exist: a file to read, or the folder of a file to write.

    Also a builtin ``FileNotFoundError`` (and still an :class:`IOError_` and :class:`Error`, as
    before); ``filename`` is the missing path, ``errno`` is ENOENT, and the message names the path.
    """

    __str__ = Exception.__str__  # the message, as for every Error (OSError's would be "[Errno 2] ...")


class InvalidMeshError(Error, ValueError):
    """Bad geometry: non-finite, out-of-range/repeated indices, degenerate, non-manifold, isolated,
    non-orientable."""


class NotADiskError(Error):
    """MCON_ERROR_NOT_A_DISK: the cut region is not a topological disk (the message says why)."""


class NumericalError(Error, ArithmeticError):
    """MCON_ERROR_NUMERICAL: a linear solve or an optimization failed numerically."""


class InvalidLibraryError(Error):
    """MCON_ERROR_INVALID_LIBRARY: a library file or buffer failed validation (the message says where)."""


class UnsupportedError(Error):
    """MCON_ERROR_UNSUPPORTED: a feature or format version this build does not know."""


class NotFoundError(Error, KeyError):
    """MCON_ERROR_NOT_FOUND: no entry has this id or name (also a ``KeyError``)."""


class EntryIndexError(InvalidArgumentError, IndexError):
    """An entry index outside the library (``Library.entry``, ``lib[i]``): the message gives the
    valid range. Also an ``IndexError``, and an :class:`InvalidArgumentError` (status 2) as the
    C side reported it before."""


_BY_STATUS = {
    2: InvalidArgumentError,
    3: NullPointerError,
    4: StructSizeError,
    5: OutOfMemoryError,
    6: BufferTooSmallError,
    7: CancelledError,
    8: IOError_,
    10: InvalidMeshError,
    11: InvalidMeshError,
    12: InvalidMeshError,
    13: InvalidMeshError,
    14: InvalidMeshError,
    15: InvalidMeshError,
    16: InvalidMeshError,
    17: InvalidMeshError,
    18: InvalidMeshError,
    20: NotADiskError,
    21: NumericalError,
    30: InvalidLibraryError,
    31: UnsupportedError,
    32: NotFoundError,
}


def status_name(status: int) -> str:
    """The C name of a status code, e.g. ``"MCON_ERROR_NOT_FOUND"`` (``MCON_STATUS_<n>`` if unknown)."""
    name = ctypes.c_char_p()
    if _native.lib.mcon_get_status_name(status, ctypes.byref(name)) != 0 or not name.value:
        return f"MCON_STATUS_{status}"
    return name.value.decode()


def check(status: int) -> None:
    """Raises the matching Error subclass unless ``status`` is MCON_OK."""
    if status == 0:
        return
    message = ctypes.c_char_p()
    _native.lib.mcon_get_last_error(None, ctypes.byref(message))
    text = message.value.decode("utf-8", "replace") if message.value else ""
    raise _BY_STATUS.get(status, Error)(status, text)


def check_path(status: int, path, writing: bool = False) -> None:
    """``check`` for a call that opened ``path``: an IO failure on a path that does not exist (to
    read), or whose folder does not exist (to write), is a :class:`FileNotFoundError_` naming it."""
    try:
        check(status)
    except IOError_ as exc:
        missing = os.fsdecode(path)
        if writing:
            missing = os.path.dirname(os.path.abspath(missing))
        if os.path.exists(missing):
            raise
        message = exc.message
        if missing not in message:  # the C message usually names the path it could not open
            message += f" ({'no such folder to write in' if writing else 'no such file'}: {missing!r})"
        err = FileNotFoundError_(exc.status, message)
        err.errno, err.strerror, err.filename = errno.ENOENT, os.strerror(errno.ENOENT), missing
        raise err from None

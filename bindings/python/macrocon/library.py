"""Constraint libraries and retrieval (mcon_library_*): ``Library``, its entries and queries."""
from __future__ import annotations

import ctypes
import operator
import os
from dataclasses import dataclass
from enum import IntEnum
from typing import Dict, Iterator, List, Optional, Sequence, Union

import numpy as np

from . import _native
from ._arrays import SINGULARITY, SURFACE_POINT, checked, ptr, strided_rows, vector3
from .core import Context, Patch, ProgressCallback, _Handle, _Progress, require_type
from .errors import EntryIndexError, NotFoundError, check, check_path


class FieldKind(IntEnum):
    """mcon_field_kind: how a per-vertex field is stored and transferred."""

    SCALAR = 1
    VECTOR3 = 2
    TANGENT_VECTOR = 3
    INTEGER_LABEL = 4
    UV = 5


class PolylineKind(IntEnum):
    """mcon_polyline_kind: a guide the cross field follows, or a sharp feature line."""

    GUIDE = 1
    FEATURE = 2


class RetrievalDescriptor(IntEnum):
    """The per-vertex descriptor retrieval builds its vocabulary from (CUSTOM: the caller's own)."""

    CURV9 = 1
    HKS = 3
    WKS = 4
    CUSTOM = 256


@dataclass
class Polyline:
    """Points on a patch: ``faces`` (n,) uint32 triangle indices, ``barycentric`` (n, 3) float64."""

    faces: np.ndarray
    barycentric: np.ndarray
    kind: PolylineKind = PolylineKind.GUIDE
    closed: bool = False

    def points(self, name: str = "polyline") -> np.ndarray:
        """The points as an mcon_surface_point array (checked)."""
        f = checked(f"{name}.faces", self.faces, np.uint32, (None,))
        b = checked(f"{name}.barycentric", self.barycentric, np.float64, (f.shape[0], 3))
        out = np.zeros(f.shape[0], SURFACE_POINT)
        out["face"], out["barycentric"] = f, b
        return out


@dataclass
class Singularities:
    """Cross-field singularities: location (faces, barycentric) and index in quarter turns (+1 = valence 3)."""

    faces: np.ndarray
    barycentric: np.ndarray
    index_quarters: np.ndarray

    def records(self) -> np.ndarray:
        """The singularities as an mcon_singularity array (checked)."""
        f = checked("singularities.faces", self.faces, np.uint32, (None,))
        b = checked("singularities.barycentric", self.barycentric, np.float64, (f.shape[0], 3))
        q = checked("singularities.index_quarters", self.index_quarters, np.int32, (f.shape[0],))
        out = np.zeros(f.shape[0], SINGULARITY)
        out["location"]["face"], out["location"]["barycentric"], out["index_quarters"] = f, b, q
        return out

    def __len__(self) -> int:
        return len(self.faces)


@dataclass
class Field:
    """A named per-vertex field: ``values`` (n, dimension), float64 (int32 for INTEGER_LABEL).

    ``values`` may be row-strided (a column slice of a wider array, a field of an aligned
    structured array): ``Library.add_entry`` passes its row stride to the C side.
    """

    name: str
    kind: FieldKind
    values: np.ndarray


@dataclass(frozen=True)
class LibraryInfo:
    """A library's size and retrieval configuration (mcon_library_info), as ``Library.info`` returns it."""

    entry_count: int
    descriptor: RetrievalDescriptor
    descriptor_dimension: int
    vocabulary_size: int
    rings: int
    histogram_length: int
    sigma_bof: float
    seed: int
    format_version: int = 0        # of the file or bytes it was opened from; 0 = made in memory
    checksum_verified: bool = False  # False for format 1 files, which carry no checksum


@dataclass(frozen=True)
class EntryInfo:
    """Sizes and placement of one library entry (mcon_library_entry_info), as ``Entry.info`` holds it.

    ``center_face`` / ``center_barycentric``: the patch center on the entry's mesh;
    ``source_scale`` / ``source_origin``: where it sat in its source (host = origin + scale * p);
    ``up``: its source's up direction in source coordinates, or None if the entry stores none.
    """

    id: int
    vertex_count: int
    triangle_count: int
    tag_count: int
    polyline_count: int
    singularity_count: int
    field_count: int
    center_face: int
    center_barycentric: tuple
    source_scale: float
    source_origin: tuple
    up: Optional[tuple] = None


@dataclass(frozen=True)
class Suggestion:
    """One distinct suggestion: its best entry, distance, confidence (summing to 1 over the
    suggestions of one query) and how many more entries of its class follow it."""

    index: int
    distance: float
    confidence: float
    alternative_count: int


@dataclass(frozen=True)
class QueryResult:
    """The nearest entries, best first: ids (uint64), indices (uint32), L1 histogram distances."""

    ids: np.ndarray
    indices: np.ndarray
    distances: np.ndarray

    def __len__(self) -> int:
        return len(self.ids)


def _utf8(name: str, text: Optional[str]) -> Optional[bytes]:
    if text is None:
        return None
    if not isinstance(text, str):
        raise TypeError(f"{name} must be a str, got {type(text).__name__}")
    _native.check_value(name, text, ctypes.c_char_p)  # a NUL would cut the name short in C
    return text.encode("utf-8")


def _read_string(function, *args) -> str:
    """A string out of the C convention: ``function(*args, text, capacity, &size)`` once for the
    size (text NULL), then into a buffer of it."""
    size = _native.c_size()
    check(function(*args, None, 0, ctypes.byref(size)))
    buf = ctypes.create_string_buffer(size.value)
    check(function(*args, buf, size.value, ctypes.byref(size)))
    return buf.value.decode("utf-8")


class Entry:
    """A read-only view of entry ``index`` of a library (valid until the library is modified)."""

    def __init__(self, library: "Library", index: int):
        self.library = library
        self.index = index
        self.info = library._entry_info(index)

    @property
    def up(self) -> Optional[tuple]:
        """The up direction of the entry's source (source coordinates), or None if it stores none;
        pass it as ``source_up`` when mapping the entry."""
        return self.info.up

    @property
    def id(self) -> int:
        """The entry's id (unique in its library, kept by save/open; see ``Library.find``)."""
        return self.info.id

    def _string(self, which: int, item: int = 0) -> str:
        return _read_string(_native.lib.mcon_library_get_entry_string, self.library.handle, self.index, which, item)

    @property
    def name(self) -> str:
        """The entry's name ('' if none; names need not be unique)."""
        return self._string(1)

    @property
    def class_label(self) -> str:
        """Its class label; ``query_distinct`` counts entries of one class once (side suffix ignored)."""
        return self._string(2)

    @property
    def author(self) -> str:
        """Who made the entry ('' if not given)."""
        return self._string(3)

    @property
    def licence(self) -> str:
        """Its licence, e.g. an SPDX id ('' if not given)."""
        return self._string(4)

    @property
    def tags(self) -> List[str]:
        """Its tags, in the order they were added."""
        return [self._string(5, i) for i in range(self.info.tag_count)]

    @property
    def positions(self) -> np.ndarray:
        """(vertex_count, 3) float64 normalized positions of the entry's patch."""
        out = np.empty((self.info.vertex_count, 3), np.float64)
        check(_native.lib.mcon_library_get_entry_positions(self.library.handle, self.index, ptr(out), out.size))
        return out

    @property
    def triangles(self) -> np.ndarray:
        """(triangle_count, 3) uint32 vertex indices of the entry's patch."""
        out = np.empty((self.info.triangle_count, 3), np.uint32)
        check(_native.lib.mcon_library_get_entry_triangles(self.library.handle, self.index, ptr(out), out.size))
        return out

    @property
    def polylines(self) -> List[Polyline]:
        """The guide and feature polylines stored with the entry (points on its patch)."""
        result = []
        for i in range(self.info.polyline_count):
            kind, closed, n = ctypes.c_uint32(), ctypes.c_uint32(), _native.c_size()
            h = self.library.handle
            check(_native.lib.mcon_library_get_entry_polyline(h, self.index, i, ctypes.byref(kind), ctypes.byref(closed),
                                                              ctypes.byref(n), None, 0))
            pts = np.zeros(n.value, SURFACE_POINT)
            check(_native.lib.mcon_library_get_entry_polyline(h, self.index, i, None, None, None, ptr(pts), n.value))
            result.append(Polyline(pts["face"].copy(), pts["barycentric"].copy(), PolylineKind(kind.value),
                                   bool(closed.value)))
        return result

    @property
    def singularities(self) -> Singularities:
        """The cross-field singularities stored with the entry."""
        rec = np.zeros(self.info.singularity_count, SINGULARITY)
        check(_native.lib.mcon_library_get_entry_singularities(self.library.handle, self.index, ptr(rec), rec.size))
        return Singularities(rec["location"]["face"].copy(), rec["location"]["barycentric"].copy(),
                             rec["index_quarters"].copy())

    def field(self, number: int) -> Field:
        """Field ``number`` (0-based, < ``info.field_count``) with its name, kind and values."""
        kind, dim = ctypes.c_uint32(), ctypes.c_uint32()
        h = self.library.handle
        check(_native.lib.mcon_library_get_entry_field(h, self.index, number, ctypes.byref(kind), ctypes.byref(dim),
                                                       None, None, 0))
        k = FieldKind(kind.value)
        out = np.empty((self.info.vertex_count, dim.value), np.int32 if k == FieldKind.INTEGER_LABEL else np.float64)
        values, labels = (None, ptr(out)) if k == FieldKind.INTEGER_LABEL else (ptr(out), None)
        check(_native.lib.mcon_library_get_entry_field(h, self.index, number, None, None, values, labels, out.size))
        return Field(self._string(6, number), k, out)

    @property
    def fields(self) -> Dict[str, Field]:
        """Every field of the entry, by name."""
        return {f.name: f for f in (self.field(i) for i in range(self.info.field_count))}

    @property
    def descriptors(self) -> np.ndarray:
        """(vertex_count, descriptor_dimension) stored descriptors."""
        dim = self.library.info.descriptor_dimension
        out = np.empty((self.info.vertex_count, dim), np.float64)
        check(_native.lib.mcon_library_get_entry_retrieval(self.library.handle, self.index, ptr(out), out.size, None, 0))
        return out

    @property
    def histogram(self) -> np.ndarray:
        """(histogram_length,) float32 bag-of-features histogram (empty before build_retrieval)."""
        out = np.empty(self.library.info.histogram_length, np.float32)
        check(_native.lib.mcon_library_get_entry_retrieval(self.library.handle, self.index, None, 0, ptr(out), out.size))
        return out

    def __repr__(self) -> str:
        return f"<macrocon.Entry {self.index} id={self.id} {self.name!r}>"


class Library(_Handle):
    """A constraint library: macro-constraint entries plus the retrieval configuration."""

    _release = _native.lib.mcon_library_release

    def __init__(self, context: Context, _handle: Optional[ctypes.c_void_p] = None, *,
                 descriptor: Optional[RetrievalDescriptor] = None):
        """An empty library; ``descriptor`` (default CURV9) is what its entries are described by."""
        require_type(context, Context, "context")
        if _handle is None:
            _handle = ctypes.c_void_p()
            check(_native.lib.mcon_library_create(context.handle, ctypes.byref(_handle)))
        super().__init__(_handle)
        self.context = context
        if descriptor is not None:
            self.set_descriptor(descriptor)

    def set_descriptor(self, descriptor: RetrievalDescriptor) -> None:
        """The built-in descriptor of an empty library (one with entries changes it through
        ``build_retrieval``)."""
        _native.check_value("descriptor", descriptor, ctypes.c_uint32)
        check(_native.lib.mcon_library_set_descriptor(self.handle, int(descriptor)))

    def _string(self, which: int) -> str:
        return _read_string(_native.lib.mcon_library_get_string, self.handle, which)

    @property
    def name(self) -> str:
        """The library's name ('' if none), kept by save/open."""
        return self._string(1)

    @name.setter
    def name(self, text: str) -> None:
        check(_native.lib.mcon_library_set_string(self.handle, 1, _utf8("name", text)))

    @property
    def description(self) -> str:
        """The library's description ('' if none), kept by save/open."""
        return self._string(2)

    @description.setter
    def description(self, text: str) -> None:
        check(_native.lib.mcon_library_set_string(self.handle, 2, _utf8("description", text)))

    @property
    def descriptor_name(self) -> str:
        """The stored name of the library's descriptor: 'curv9', 'hks', 'wks' or a custom one's."""
        return self._string(3)

    @classmethod
    def open(cls, context: Context, path: Union[str, os.PathLike]) -> "Library":
        """Validates and opens a library file: FileNotFoundError (a :class:`FileNotFoundError_`
        naming the path) if there is none, else IOError_, InvalidLibraryError, UnsupportedError."""
        require_type(context, Context, "context")
        handle = ctypes.c_void_p()
        check_path(_native.lib.mcon_library_open(context.handle, os.fsencode(path), ctypes.byref(handle)), path)
        return cls(context, handle)

    @classmethod
    def open_memory(cls, context: Context, data: Union[bytes, bytearray, memoryview]) -> "Library":
        """The same from bytes (copied by the library)."""
        require_type(context, Context, "context")
        if not isinstance(data, (bytes, bytearray, memoryview)):
            raise TypeError(f"data must be bytes-like, got {type(data).__name__}")
        buf = np.frombuffer(bytes(data), np.uint8)
        handle = ctypes.c_void_p()
        check(_native.lib.mcon_library_open_memory(context.handle, ptr(buf), buf.size, ctypes.byref(handle)))
        return cls(context, handle)

    def save(self, path: Union[str, os.PathLike]) -> None:
        """Writes atomically: on failure the previous file at ``path`` is untouched. A folder that
        does not exist is a FileNotFoundError naming it."""
        check_path(_native.lib.mcon_library_save(self.handle, os.fsencode(path)), path, writing=True)

    def to_bytes(self) -> bytes:
        """The library file's bytes (what ``save`` writes; ``open_memory`` reads them back)."""
        size = _native.c_size()
        check(_native.lib.mcon_library_save_memory(self.handle, None, 0, ctypes.byref(size)))
        buf = ctypes.create_string_buffer(size.value)
        check(_native.lib.mcon_library_save_memory(self.handle, buf, size.value, ctypes.byref(size)))
        return buf.raw[: size.value]

    @property
    def info(self) -> LibraryInfo:
        """A :class:`LibraryInfo` (frozen dataclass): entry count and retrieval configuration."""
        i = _native.LibraryInfo()
        check(_native.lib.mcon_library_info_init_sized(ctypes.byref(i), ctypes.sizeof(i)))
        check(_native.lib.mcon_library_get_info(self.handle, ctypes.byref(i)))
        return LibraryInfo(i.entry_count, RetrievalDescriptor(i.descriptor), i.descriptor_dimension, i.vocabulary_size,
                           i.rings, i.histogram_length, i.sigma_bof, i.seed, i.format_version,
                           bool(i.checksum_verified))

    def __len__(self) -> int:
        n = _native.c_size()
        check(_native.lib.mcon_library_get_count(self.handle, ctypes.byref(n)))
        return n.value

    def add_entry(
        self,
        patch: Patch,
        *,
        name: str = "",
        class_label: str = "",
        tags: Sequence[str] = (),
        author: str = "",
        licence: str = "",
        polylines: Sequence[Polyline] = (),
        singularities: Optional[Singularities] = None,
        fields: Sequence[Field] = (),
        descriptors: Optional[np.ndarray] = None,
        id: int = 0,
        up: Optional[Sequence[float]] = None,
    ) -> int:
        """Validates and appends one entry; returns its id. Every array is checked before the call.
        ``up``: the up direction of the patch's host in its coordinates (3 numbers, not all 0), stored
        with the entry as the source_up of later maps (``MapOptions.source_up``)."""
        require_type(patch, Patch, "patch")
        keep: list = []  # everything the C side reads during the call
        desc = _native.LibraryEntryDesc()
        check(_native.lib.mcon_library_entry_desc_init_sized(ctypes.byref(desc), ctypes.sizeof(desc)))
        desc.patch = patch.handle
        desc.id = int(id)
        desc.name, desc.class_label = _utf8("name", name), _utf8("class_label", class_label)
        desc.author, desc.licence = _utf8("author", author), _utf8("licence", licence)
        if isinstance(tags, str):
            raise TypeError("tags must be a sequence of str, not one str")
        tag_bytes = [_utf8("tag", t) for t in tags]
        c_tags = (ctypes.c_char_p * max(1, len(tag_bytes)))(*tag_bytes)
        keep += [tag_bytes, c_tags]
        desc.tags, desc.tag_count = ctypes.cast(c_tags, ctypes.POINTER(ctypes.c_char_p)), len(tag_bytes)
        c_lines = (_native.Polyline * max(1, len(polylines)))()
        for i, line in enumerate(polylines):
            require_type(line, Polyline, "polylines[i]")
            pts = line.points(f"polylines[{i}]")
            keep.append(pts)
            c_lines[i].kind, c_lines[i].closed = int(line.kind), int(bool(line.closed))
            c_lines[i].points, c_lines[i].point_count = ptr(pts), pts.size
        keep.append(c_lines)
        desc.polylines, desc.polyline_count = ctypes.cast(c_lines, ctypes.POINTER(_native.Polyline)), len(polylines)
        if singularities is not None:
            require_type(singularities, Singularities, "singularities")
            rec = singularities.records()
            keep.append(rec)
            desc.singularities, desc.singularity_count = ptr(rec), rec.size
        c_fields = (_native.VertexField * max(1, len(fields)))()
        for i, f in enumerate(fields):
            require_type(f, Field, "fields[i]")
            kind = FieldKind(f.kind)
            labels = kind == FieldKind.INTEGER_LABEL
            # mcon_vertex_field.stride: a field inside interleaved per-vertex records is read in place.
            values, stride = strided_rows(f"fields[{i}].values", f.values, np.int32 if labels else np.float64,
                                          vector=True)
            fname = _utf8(f"fields[{i}].name", f.name)
            keep += [values, fname]
            c_fields[i].name, c_fields[i].kind, c_fields[i].dimension = fname, int(kind), values.shape[1]
            c_fields[i].stride = stride
            if labels:
                c_fields[i].labels = ptr(values)
            else:
                c_fields[i].values = ptr(values)
            if values.shape[0] != patch.vertex_count:
                raise ValueError(f"fields[{i}] has {values.shape[0]} rows, the patch {patch.vertex_count} vertices")
        keep.append(c_fields)
        desc.fields, desc.field_count = ctypes.cast(c_fields, ctypes.POINTER(_native.VertexField)), len(fields)
        if descriptors is not None:
            d, stride = strided_rows("descriptors", descriptors, np.float64, vector=True)
            keep.append(d)
            desc.descriptors, desc.descriptor_dimension, desc.descriptor_stride = ptr(d), d.shape[1], stride
        if up is not None:
            desc.has_up = 1
            desc.up[:] = vector3("up", up)
        out_id = ctypes.c_uint64()
        check(_native.lib.mcon_library_add_entry(self.handle, ctypes.byref(desc), ctypes.byref(out_id)))
        del keep
        return out_id.value

    def remove(self, id: int) -> None:
        """Removes the entry with this id (NotFoundError if none); later indices shift down."""
        check(_native.lib.mcon_library_remove_entry(self.handle, int(id)))

    def find(self, id: Union[int, str, None] = None, *, name: Optional[str] = None) -> int:
        """The index of the entry with this id (an int, as before) or this name (a str, or
        ``name=``). NotFoundError (a KeyError) naming the id or the name if there is none; a name
        that several entries carry is a NotFoundError too, listing their ids (use the id)."""
        if name is not None:
            if id is not None:
                raise TypeError("give the entry's id or its name, not both")
            return self._find_name(name)
        if isinstance(id, str):
            return self._find_name(id)
        if id is None or isinstance(id, bool):
            raise TypeError(f"find takes an entry id (int) or name (str), got {type(id).__name__}")
        index = _native.c_size()
        check(_native.lib.mcon_library_find_entry(self.handle, operator.index(id), ctypes.byref(index)))
        return index.value

    def _find_name(self, name: str) -> int:
        if not isinstance(name, str):
            raise TypeError(f"name must be a str, got {type(name).__name__}")
        matches = [i for i in range(len(self)) if Entry(self, i).name == name]
        if len(matches) == 1:
            return matches[0]
        if not matches:
            raise NotFoundError(32, f"no entry is named {name!r} ({len(self)} entries)")
        ids = ", ".join(str(self._entry_info(i).id) for i in matches)
        raise NotFoundError(32, f"{len(matches)} entries are named {name!r} (ids {ids}): find or entry by id")

    def _index(self, index) -> int:
        """``index`` (negative counts from the end) checked against the entry count."""
        if isinstance(index, bool):
            raise TypeError("an entry index must be an int, got bool")
        try:
            i = operator.index(index)
        except TypeError:
            raise TypeError(f"an entry index must be an int (or a name: str), got {type(index).__name__}") from None
        n = len(self)
        if not -n <= i < n:
            valid = "the library is empty" if n == 0 else f"valid: 0..{n - 1}, or -{n}..-1 from the end"
            raise EntryIndexError(2, f"entry index {i} is out of range ({n} entries; {valid})")
        return i + n if i < 0 else i

    def merge(self, other: "Library") -> None:
        """Appends copies of ``other``'s entries (taken ids are renumbered)."""
        require_type(other, Library, "other")
        check(_native.lib.mcon_library_merge(self.handle, other.handle))

    def build_retrieval(
        self,
        descriptor: RetrievalDescriptor = RetrievalDescriptor.CURV9,
        vocabulary_size: Optional[int] = None,
        rings: Optional[int] = None,
        sigma_bof: Optional[float] = None,
        seed: int = 0,
        progress: Optional[ProgressCallback] = None,
    ) -> None:
        """Descriptors, normalization, vocabulary and histograms; None keeps the library default."""
        o = _native.RetrievalOptions()
        check(_native.lib.mcon_retrieval_options_init_sized(ctypes.byref(o), ctypes.sizeof(o)))
        o.descriptor = int(RetrievalDescriptor(descriptor))
        if vocabulary_size is not None:
            o.vocabulary_size = int(vocabulary_size)
        if rings is not None:
            o.rings = int(rings)
        if sigma_bof is not None:
            o.sigma_bof = float(sigma_bof)
        o.seed = int(seed)
        cb = _Progress(progress)
        o.progress = cb.c_fn
        cb.check(_native.lib.mcon_library_build_retrieval(self.handle, ctypes.byref(o)))

    def _results(self, n: int):
        if int(n) <= 0:
            raise ValueError("n must be >= 1")
        cap = min(int(n), len(self))
        return (np.zeros(cap, np.uint64), np.zeros(cap, np.uint32), np.zeros(cap, np.float64), _native.c_size())

    def query(self, patch: Patch, n: int = 5) -> QueryResult:
        """The ``n`` entries nearest to ``patch`` (the library computes the patch's descriptor)."""
        require_type(patch, Patch, "patch")
        ids, idx, dist, count = self._results(n)
        check(_native.lib.mcon_library_query(self.handle, patch.handle, int(n), ptr(ids), ptr(idx), ptr(dist), ids.size,
                                             ctypes.byref(count)))
        k = count.value
        return QueryResult(ids[:k], idx[:k], dist[:k])

    def query_distinct(self, patch: Patch, n: int = 5) -> List[Suggestion]:
        """Up to ``n`` distinct suggestions: entries of one class (side suffix ignored) count once."""
        require_type(patch, Patch, "patch")
        m = max(1, min(int(n), len(self)))
        idx, alt = np.zeros(m, np.uint32), np.zeros(m, np.uint32)
        dist, conf = np.zeros(m), np.zeros(m)
        count = ctypes.c_size_t()
        check(_native.lib.mcon_library_query_distinct(self.handle, patch.handle, int(n), ptr(idx), ptr(dist), ptr(conf),
                                                      ptr(alt), m, ctypes.byref(count)))
        return [Suggestion(int(idx[k]), float(dist[k]), float(conf[k]), int(alt[k])) for k in range(count.value)]

    def query_descriptors(self, patch: Patch, descriptors: np.ndarray, n: int = 5) -> QueryResult:
        """The same with the caller's (vertex_count, dimension) float64 descriptors of ``patch``.

        The rows may be strided (e.g. a column slice of a wider per-vertex table): they are read in
        place with their byte stride, see ``_arrays.strided_rows``.
        """
        require_type(patch, Patch, "patch")
        d, stride = strided_rows("descriptors", descriptors, np.float64, vector=True)
        if d.shape[0] != patch.vertex_count:
            raise ValueError(f"descriptors has {d.shape[0]} rows, the patch {patch.vertex_count} vertices")
        ids, idx, dist, count = self._results(n)
        check(_native.lib.mcon_library_query_descriptors(self.handle, patch.handle, ptr(d), d.shape[1], stride, int(n),
                                                         ptr(ids), ptr(idx), ptr(dist), ids.size, ctypes.byref(count)))
        k = count.value
        return QueryResult(ids[:k], idx[:k], dist[:k])

    def _entry_info(self, index: int) -> EntryInfo:
        i = _native.LibraryEntryInfo()
        check(_native.lib.mcon_library_entry_info_init_sized(ctypes.byref(i), ctypes.sizeof(i)))
        check(_native.lib.mcon_library_get_entry_info(self.handle, int(index), ctypes.byref(i)))
        return EntryInfo(i.id, i.vertex_count, i.triangle_count, i.tag_count, i.polyline_count, i.singularity_count,
                         i.field_count, i.center.face, tuple(i.center.barycentric), i.source_scale,
                         tuple(i.source_origin), tuple(i.up) if i.has_up else None)

    def entry(self, index: Union[int, str, None] = None, *, id: Optional[int] = None,
              name: Optional[str] = None) -> Entry:
        """The :class:`Entry` at ``index`` (0-based; negative counts from the end), or with this
        name (a str, or ``name=``), or with this id (``id=``). Give exactly one. An index outside
        the library is an :class:`EntryIndexError` (an IndexError) giving the valid range; an
        unknown name or id a NotFoundError (a KeyError) naming it (see ``find``). ``lib[key]`` is
        the same as ``lib.entry(key)``."""
        given = [k for k, v in (("index", index), ("id", id), ("name", name)) if v is not None]
        if len(given) != 1:
            raise TypeError("give exactly one of an index, id= or name=" + (f" (got {', '.join(given)})" if given else ""))
        if id is not None:
            return Entry(self, self.find(id))
        if name is not None or isinstance(index, str):
            return Entry(self, self._find_name(name if name is not None else index))
        return Entry(self, self._index(index))

    __getitem__ = entry

    def __iter__(self) -> Iterator[Entry]:
        return (Entry(self, i) for i in range(len(self)))

    def _repr_fields(self) -> str:
        i = self.info
        return f"entries={i.entry_count} descriptor={i.descriptor.name} vocabulary={i.vocabulary_size}"


__all__ = ["Library", "Entry", "EntryInfo", "LibraryInfo", "QueryResult", "Polyline", "Singularities", "Field",
           "FieldKind", "PolylineKind", "RetrievalDescriptor"]

"""Constraint libraries through the Python binding: round trips, queries, errors, cancellation."""
import ctypes

import numpy as np
import pytest

import macrocon
from macrocon import _native
from conftest import center, vertex_normals

CENTERS = [(12, 12), (20, 20), (28, 14), (14, 27), (26, 26)]


def extract(mesh, i, j, radius=0.22):
    return macrocon.Patch.extract(mesh, radius=radius, center_vertex=center(41, i, j))


def example_constraints(patch):
    """A guide through three triangles, a closed feature loop, two singularities and one field of
    every kind, all derived from the patch so they are valid on it."""
    m, n = patch.triangle_count, patch.vertex_count
    third = np.full((3, 3), 1 / 3)
    guide = macrocon.Polyline(np.array([0, m // 2, m - 1], np.uint32), third.copy())
    loop = macrocon.Polyline(np.array([1, 2, 3, 4], np.uint32), np.tile([[0.2, 0.3, 0.5]], (4, 1)),
                             kind=macrocon.PolylineKind.FEATURE, closed=True)
    sing = macrocon.Singularities(np.array([5, m // 3], np.uint32), np.array([[0.6, 0.2, 0.2], [1 / 3] * 3]),
                                  np.array([1, -1], np.int32))
    pos, tri = patch.positions, patch.triangles
    normals = vertex_normals(pos, tri)
    tangent = np.cross(normals, [0.0, 0.0, 1.0])  # tangent (short where the normal is vertical)
    tangent -= (tangent * normals).sum(1, keepdims=True) * normals
    fields = [
        macrocon.Field("weights", macrocon.FieldKind.SCALAR, np.stack([pos[:, 0] ** 2, 1 - pos[:, 1] ** 2], 1)),
        macrocon.Field("colour", macrocon.FieldKind.VECTOR3, np.abs(pos)),
        macrocon.Field("flow", macrocon.FieldKind.TANGENT_VECTOR, np.ascontiguousarray(tangent)),
        macrocon.Field("part", macrocon.FieldKind.INTEGER_LABEL, (np.arange(n) % 3).astype(np.int32)),
        macrocon.Field("uv", macrocon.FieldKind.UV, patch.uv),
    ]
    return [guide, loop], sing, fields


@pytest.fixture
def patches(host):
    mesh, _, _ = host
    ps = [extract(mesh, i, j) for i, j in CENTERS]
    yield ps
    for p in ps:
        p.close()


@pytest.fixture
def filled(context, patches):
    lib = macrocon.Library(context)
    for k, patch in enumerate(patches):
        lines, sing, fields = example_constraints(patch)
        lib.add_entry(patch, name=f"entry {k}", class_label="bump", tags=["test", f"k{k}"], author="pytest",
                      licence="CC0-1.0", polylines=lines, singularities=sing, fields=fields)
    yield lib
    lib.close()


def test_empty_library(context):
    with macrocon.Library(context) as lib:
        assert len(lib) == 0
        info = lib.info
        assert info.entry_count == 0 and info.vocabulary_size == 0
        assert info.descriptor == macrocon.RetrievalDescriptor.CURV9
    assert lib._handle is None  # the context manager released it


def test_add_entry_and_read_everything_back(filled, patches):
    assert len(filled) == len(patches)
    ids = [e.id for e in filled]
    assert len(set(ids)) == len(ids) and 0 not in ids
    e = filled[1]
    patch = patches[1]
    assert (e.name, e.class_label, e.author, e.licence) == ("entry 1", "bump", "pytest", "CC0-1.0")
    assert e.tags == ["test", "k1"]
    assert e.info.vertex_count == patch.vertex_count and e.info.triangle_count == patch.triangle_count
    assert np.allclose(e.positions, patch.positions, atol=1e-5)
    assert np.array_equal(e.triangles, patch.triangles)
    lines, sing, fields = example_constraints(patch)
    got = e.polylines
    assert [(p.kind, p.closed) for p in got] == [(macrocon.PolylineKind.GUIDE, False),
                                                 (macrocon.PolylineKind.FEATURE, True)]
    for a, b in zip(got, lines):
        assert np.array_equal(a.faces, b.faces)
        assert np.allclose(a.barycentric, b.barycentric, atol=1e-6)
    s = e.singularities
    assert np.array_equal(s.faces, sing.faces) and np.array_equal(s.index_quarters, sing.index_quarters)
    assert np.allclose(s.barycentric, sing.barycentric, atol=1e-6)
    stored = e.fields
    assert list(stored) == [f.name for f in fields]
    for f in fields:
        g = stored[f.name]
        assert g.kind == f.kind
        want = f.values.reshape(patch.vertex_count, -1)
        if f.kind == macrocon.FieldKind.INTEGER_LABEL:
            assert g.values.dtype == np.int32 and np.array_equal(g.values, want)
        else:  # stored as float32
            assert np.allclose(g.values, want, rtol=1e-6, atol=1e-6)
    d = e.descriptors
    assert d.shape == (patch.vertex_count, 9)
    # Computed by the library from its stored (float32) geometry: close, not identical.
    ref = patch.descriptors("curv9")
    assert np.max(np.abs(d - ref)) < 1e-3 * np.max(np.abs(ref))


def test_save_open_round_trips_are_byte_identical(context, filled, tmp_path):
    data = filled.to_bytes()
    assert data[4:8] == b"MCLB" or data[:4] == b"MCLB"
    path = tmp_path / "lib.mclb"
    filled.save(path)
    assert path.read_bytes() == data
    with macrocon.Library.open(context, path) as a, macrocon.Library.open_memory(context, data) as b:
        assert len(a) == len(b) == len(filled)
        assert a.to_bytes() == data and b.to_bytes() == data
        assert [e.name for e in b] == [e.name for e in filled]
        assert np.array_equal(b[3].fields["part"].values, filled[3].fields["part"].values)


def test_remove_find_merge(context, filled):
    ids = [e.id for e in filled]
    assert filled.find(ids[2]) == 2
    filled.remove(ids[2])
    assert len(filled) == 4
    assert filled.find(ids[3]) == 2  # later entries shift down
    with pytest.raises(macrocon.NotFoundError) as err:
        filled.find(ids[2])
    assert err.value.status == 32
    with pytest.raises(macrocon.NotFoundError):
        filled.remove(ids[2])
    with macrocon.Library(context) as other:
        other.merge(filled)
        other.merge(filled)
        assert len(other) == 8
        merged = [e.id for e in other]
        assert len(set(merged)) == 8  # taken ids were renumbered
        assert [e.name for e in other] == [e.name for e in filled] * 2


def test_build_retrieval_and_query_finds_the_entry_itself(filled, patches):
    with pytest.raises(macrocon.InvalidArgumentError):  # no vocabulary yet
        filled.query(patches[0], 3)
    filled.build_retrieval(vocabulary_size=16, seed=7)
    info = filled.info
    assert 0 < info.vocabulary_size <= 16
    assert info.histogram_length == info.vocabulary_size * info.rings and info.seed == 7
    h = filled[0].histogram
    assert h.shape == (info.histogram_length,) and np.all(np.isfinite(h)) and h.sum() > 0
    ids = [e.id for e in filled]
    for k, patch in enumerate(patches):
        r = filled.query(patch, 3)
        assert len(r) == 3
        assert r.indices[0] == k and r.ids[0] == ids[k]
        assert np.all(np.diff(r.distances) >= 0) and r.distances[0] <= 1e-6
    assert len(filled.query(patches[0], 100)) == len(filled)  # min(n, count)
    with pytest.raises(ValueError):
        filled.query(patches[0], 0)


def test_custom_descriptors_and_query_descriptors(context, patches):
    with macrocon.Library(context) as lib:
        for patch in patches:
            d = patch.descriptors("mean_curvature")
            lib.add_entry(patch, name="custom", descriptors=np.hstack([d, d * d]))
        lib.build_retrieval(descriptor=macrocon.RetrievalDescriptor.CUSTOM, vocabulary_size=8)
        assert lib.info.descriptor == macrocon.RetrievalDescriptor.CUSTOM
        assert lib.info.descriptor_dimension == 2
        d = patches[2].descriptors("mean_curvature")
        r = lib.query_descriptors(patches[2], np.hstack([d, d * d]), 2)
        assert r.indices[0] == 2
        with pytest.raises(macrocon.InvalidArgumentError):  # wrong dimension
            lib.query_descriptors(patches[2], d, 2)
        with pytest.raises(TypeError):
            lib.query_descriptors(patches[2], d.astype(np.float32), 2)


def test_build_retrieval_cancels_and_leaves_the_library_unchanged(filled):
    before = filled.to_bytes()
    calls = []
    with pytest.raises(macrocon.CancelledError) as err:
        filled.build_retrieval(vocabulary_size=16, progress=lambda f: calls.append(f) or False)
    assert err.value.status == 7 and len(calls) == 1
    assert filled.info.vocabulary_size == 0 and filled.to_bytes() == before

    def boom(_):
        raise RuntimeError("stop from Python")

    with pytest.raises(RuntimeError, match="stop from Python"):
        filled.build_retrieval(vocabulary_size=16, progress=boom)
    fractions = []
    filled.build_retrieval(vocabulary_size=16, progress=lambda f: fractions.append(f) or True)
    assert fractions and all(0 <= f <= 1 for f in fractions) and filled.info.vocabulary_size > 0


def test_array_checks_before_the_call(context, patches):
    patch = patches[0]
    lines, sing, fields = example_constraints(patch)
    with macrocon.Library(context) as lib:
        bad = macrocon.Field("w", macrocon.FieldKind.SCALAR, fields[0].values.astype(np.float32))
        with pytest.raises(TypeError, match="float64"):
            lib.add_entry(patch, fields=[bad])
        bad = macrocon.Field("w", macrocon.FieldKind.SCALAR, np.asfortranarray(fields[0].values))
        with pytest.raises(ValueError, match="C-contiguous"):
            lib.add_entry(patch, fields=[bad])
        bad = macrocon.Field("w", macrocon.FieldKind.SCALAR, fields[0].values[:-1].copy())
        with pytest.raises(ValueError, match="rows"):
            lib.add_entry(patch, fields=[bad])
        bad = macrocon.Field("l", macrocon.FieldKind.INTEGER_LABEL, np.zeros(patch.vertex_count, np.int64))
        with pytest.raises(TypeError, match="int32"):
            lib.add_entry(patch, fields=[bad])
        with pytest.raises(TypeError, match="uint32"):
            lib.add_entry(patch, polylines=[macrocon.Polyline(np.array([0, 1]), np.full((2, 3), 1 / 3))])
        with pytest.raises(ValueError, match="shape"):
            lib.add_entry(patch, polylines=[macrocon.Polyline(np.array([0, 1], np.uint32), np.full((3, 3), 1 / 3))])
        with pytest.raises(TypeError, match="Patch"):
            lib.add_entry(None)
        with pytest.raises(TypeError):
            lib.add_entry(patch, tags="one string")
        assert len(lib) == 0  # nothing reached the library


def test_the_library_rejects_bad_values_with_status_and_message(context, patches):
    patch = patches[0]
    with macrocon.Library(context) as lib:
        far = macrocon.Polyline(np.array([0, patch.triangle_count + 10], np.uint32), np.full((2, 3), 1 / 3))
        with pytest.raises(macrocon.InvalidArgumentError) as err:
            lib.add_entry(patch, polylines=[far])
        assert err.value.status == 2 and err.value.message
        weights = macrocon.Polyline(np.array([0, 1], np.uint32), np.array([[0.5, 0.5, 0.5], [1 / 3] * 3]))
        with pytest.raises(macrocon.InvalidArgumentError):
            lib.add_entry(patch, polylines=[weights])
        nan = np.zeros(patch.vertex_count)
        nan[3] = np.nan
        with pytest.raises(macrocon.Error) as err:
            lib.add_entry(patch, fields=[macrocon.Field("x", macrocon.FieldKind.SCALAR, nan)])
        assert err.value.status == 10  # MCON_ERROR_NON_FINITE
        twice = [macrocon.Field("x", macrocon.FieldKind.SCALAR, np.zeros(patch.vertex_count))] * 2
        with pytest.raises(macrocon.InvalidArgumentError):
            lib.add_entry(patch, fields=twice)
        zero = macrocon.Singularities(np.array([0], np.uint32), np.full((1, 3), 1 / 3), np.array([0], np.int32))
        with pytest.raises(macrocon.InvalidArgumentError):
            lib.add_entry(patch, singularities=zero)
        assert len(lib) == 0  # the library is unchanged after each error
        with pytest.raises(macrocon.InvalidArgumentError):
            lib.entry(5)


def test_null_and_closed_handles(context, patches):
    count = _native.c_size()
    with pytest.raises(macrocon.NullPointerError) as err:
        macrocon.errors.check(_native.lib.mcon_library_get_count(None, ctypes.byref(count)))
    assert err.value.status == 3
    with pytest.raises(macrocon.NullPointerError):
        macrocon.errors.check(_native.lib.mcon_library_create(context.handle, None))
    lib = macrocon.Library(context)
    lib.close()
    lib.close()
    with pytest.raises(ValueError, match="closed"):
        len(lib)
    with pytest.raises(ValueError, match="closed"):
        lib.add_entry(patches[0])
    with pytest.raises(TypeError):
        macrocon.Library(None)


def test_forged_library_bytes_are_rejected(context, filled):
    data = filled.to_bytes()
    with pytest.raises(macrocon.InvalidLibraryError) as err:
        macrocon.Library.open_memory(context, b"not a library at all, just some bytes")
    assert err.value.status == 30 and err.value.message
    for cut in (8, len(data) // 2, len(data) - 1):
        with pytest.raises(macrocon.InvalidLibraryError):
            macrocon.Library.open_memory(context, data[:cut])
    rng = np.random.default_rng(5)
    opened = rejected = 0
    for _ in range(40):  # random corruption: a clean error or a library that still validates, never a crash
        forged = bytearray(data)
        for pos in rng.integers(0, len(data), 4):
            forged[pos] ^= 0xFF
        try:
            with macrocon.Library.open_memory(context, bytes(forged)) as lib:
                len(lib)
                opened += 1
        except (macrocon.InvalidLibraryError, macrocon.UnsupportedError):
            rejected += 1
    assert opened + rejected == 40 and rejected > 0


def test_open_errors(context, tmp_path):
    with pytest.raises(macrocon.IOError_) as err:
        macrocon.Library.open(context, tmp_path / "missing.mclb")
    assert err.value.status == 8
    with pytest.raises(TypeError):
        macrocon.Library.open_memory(context, "text")


def test_distinct_suggestions_group_one_class(context, patches):
    """Every entry of `filled` is class "bump": one suggestion, the rest its alternatives; with a
    class each (left and right suffixes ignored) every entry is its own suggestion."""
    with macrocon.Library(context) as lib:
        for k, patch in enumerate(patches):
            lib.add_entry(patch, name=f"e{k}", class_label="bump_l" if k % 2 else "bump_r")
        lib.build_retrieval(vocabulary_size=16, seed=7)
        s = lib.query_distinct(patches[0], 3)
        assert len(s) == 1 and s[0].index == 0 and s[0].alternative_count == len(patches) - 1
        assert s[0].confidence == 1.0
    with macrocon.Library(context) as lib:
        for k, patch in enumerate(patches):
            lib.add_entry(patch, name=f"e{k}", class_label=f"class{k}")
        lib.build_retrieval(vocabulary_size=16, seed=7)
        s = lib.query_distinct(patches[1], 3)
        assert [x.alternative_count for x in s] == [0, 0, 0] and s[0].index == 1
        assert abs(sum(x.confidence for x in s) - 1) < 1e-12
        assert s[0].confidence >= s[1].confidence >= s[2].confidence
        with pytest.raises(macrocon.InvalidArgumentError):
            lib.query_distinct(patches[0], 0)


def test_descriptor_chosen_at_creation_name_and_description(context, patches):
    lib = macrocon.Library(context, descriptor=macrocon.RetrievalDescriptor.WKS)
    assert lib.descriptor_name == "wks"
    lib.name = "bumps \u00e9t\u00e9"
    lib.description = "five bumps"
    for patch in patches[:2]:
        lib.add_entry(patch, name="b")
    assert lib.info.descriptor == macrocon.RetrievalDescriptor.WKS
    assert lib.info.descriptor_dimension == 100
    again = macrocon.Library.open_memory(context, lib.to_bytes())
    assert (again.name, again.description, again.descriptor_name) == ("bumps \u00e9t\u00e9", "five bumps", "wks")
    with pytest.raises(macrocon.InvalidArgumentError, match="build_retrieval"):
        lib.set_descriptor(macrocon.RetrievalDescriptor.HKS)  # it has entries now
    with pytest.raises(macrocon.InvalidArgumentError, match="NUL"):
        lib.name = "a\0b"
    with pytest.raises(macrocon.InvalidArgumentError):
        macrocon.Library(context, descriptor=2**32 + 1)
    assert lib.name == "bumps \u00e9t\u00e9"
    again.close()
    lib.close()


def test_an_entry_stores_its_up_direction(context, patches, tmp_path):
    with macrocon.Library(context) as lib:
        lib.add_entry(patches[0], name="plain")
        lib.add_entry(patches[1], name="upright", up=np.array([0.0, 2.0, 0.5]))
        assert lib[0].up is None
        assert lib[1].up == (0.0, 2.0, 0.5) == lib[1].info.up
        path = str(tmp_path / "up.mclb")
        lib.save(path)
        with macrocon.Library.open(context, path) as back:
            assert back[0].info.up is None and back[1].info.up == (0.0, 2.0, 0.5)
        with pytest.raises(ValueError, match="up must have 3 components"):
            lib.add_entry(patches[2], up=[0.0, 1.0])
        with pytest.raises(macrocon.InvalidArgumentError, match="zero vector"):
            lib.add_entry(patches[2], up=(0, 0, 0))
        with pytest.raises(macrocon.Error, match="not finite"):
            lib.add_entry(patches[2], up=(0, float("nan"), 1))
        assert len(lib) == 2

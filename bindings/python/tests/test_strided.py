"""Row-strided (interleaved) numpy inputs: passed in place with their byte stride wherever the C
API takes one, bit-identical to the packed arrays; layouts the C side cannot express are refused."""
import numpy as np
import pytest

import macrocon
from macrocon import core
from conftest import bumpy, center

N = 41
CENTERS = [(12, 12), (20, 20), (28, 14), (14, 27)]

#: A vendor's interleaved vertex record (aligned like the C struct it mirrors).
VERTEX = np.dtype([("id", "<u4"), ("pos", "<f8", (3,)), ("normal", "<f4", (3,)), ("label", "<i4", (2,)),
                   ("weights", "<f8", (2,))], align=True)


def wide(a: np.ndarray, left: int, right: int, fill) -> np.ndarray:
    """``a`` inside a wider array (left and right columns of junk): returns the column slice view."""
    big = np.full((a.shape[0], left + a.shape[1] + right), fill, a.dtype)
    big[:, left:left + a.shape[1]] = a
    view = big[:, left:left + a.shape[1]]
    assert not view.flags.c_contiguous and view.base is big
    return view


def records(p: np.ndarray) -> np.ndarray:
    rec = np.zeros(p.shape[0], VERTEX)
    rec["id"] = np.arange(p.shape[0])
    rec["pos"] = p
    rec["normal"] = 7.0
    rec["label"] = np.stack([np.arange(p.shape[0]) % 3, np.arange(p.shape[0]) % 5], 1)
    rec["weights"] = np.stack([p[:, 0] ** 2, 1 - p[:, 1] ** 2], 1)
    return rec


def patch_arrays(patch):
    v0, v1, t = patch.host_vertices
    return [patch.positions, patch.uv, patch.triangles, v0, v1, t, patch.host_triangles, patch.descriptors("curv9")]


def assert_same_patch(a, b):
    for x, y in zip(patch_arrays(a), patch_arrays(b)):
        assert x.dtype == y.dtype and np.array_equal(x, y)  # bit-identical, not merely close


@pytest.mark.parametrize("dtype", [np.float64, np.float32])
def test_mesh_from_a_column_slice_equals_the_packed_mesh(context, dtype):
    p, t = bumpy(N, dtype)
    pv = wide(p, 2, 3, np.nan)      # NaN junk: reading a byte outside the slice would fail the mesh
    tv = wide(t, 1, 1, 0xFFFFFFFF)  # out-of-range junk indices likewise
    desc, keep = core._mesh_desc(pv, tv)
    # Zero-copy: the descriptor points into the caller's buffers with their row strides.
    assert desc.positions == pv.ctypes.data and desc.position_stride == pv.strides[0] == 8 * p.itemsize
    assert desc.indices == tv.ctypes.data and desc.index_stride == tv.strides[0] == 20
    del keep
    with macrocon.Mesh(context, p, t) as packed, macrocon.Mesh(context, pv, tv) as strided:
        assert strided.counts == packed.counts
        for i, j in CENTERS[:2]:
            with macrocon.Patch.extract(packed, 0.22, center_vertex=center(N, i, j)) as a, \
                    macrocon.Patch.extract(strided, 0.22, center_vertex=center(N, i, j)) as b:
                assert_same_patch(a, b)


def test_mesh_from_a_structured_array_field_equals_the_packed_mesh(context):
    p, t = bumpy(N)
    rec = records(p)
    pos = rec["pos"]
    assert pos.strides == (VERTEX.itemsize, 8) and VERTEX.itemsize == 72
    desc, keep = core._mesh_desc(pos, t)
    assert desc.positions == rec.ctypes.data + VERTEX.fields["pos"][1] and desc.position_stride == 72
    assert desc.index_stride == 12
    del keep
    with macrocon.Mesh(context, p, t) as packed, macrocon.Mesh(context, pos, t) as strided:
        with macrocon.Patch.extract(packed, 0.22, center_vertex=center(N, 20, 20)) as a, \
                macrocon.Patch.extract(strided, 0.22, center_vertex=center(N, 20, 20)) as b:
            assert_same_patch(a, b)
            info = a.info
            # Patch.from_arrays takes the same strided positions (an entry's mesh in a record array).
            rec2 = records(a.positions)
            args = (a.triangles, info.center_patch_triangle, tuple(info.center_barycentric), tuple(info.center),
                    info.radius)
            with macrocon.Patch.from_arrays(context, a.positions, *args) as fa, \
                    macrocon.Patch.from_arrays(context, rec2["pos"], *args) as fb:
                assert_same_patch(fa, fb)


def test_layouts_the_c_side_cannot_express_raise_value_error(context):
    p, t = bumpy(11)
    big = np.zeros((p.shape[0], 6))
    big[:, 0:6:2] = p
    bad = {
        "reversed rows (negative stride)": p[::-1],
        "every other column": big[:, 0:6:2],
        "Fortran order": np.asfortranarray(p),
        "broadcast rows (zero stride)": np.broadcast_to(p[0], p.shape),
        "overlapping rows": np.lib.stride_tricks.as_strided(big, shape=(p.shape[0], 3), strides=(16, 8)),
        "unaligned stride": np.lib.stride_tricks.as_strided(np.zeros(p.size * 16, np.uint8).view(np.float64),
                                                            shape=(p.shape[0], 3), strides=(28, 8)),
    }
    unaligned = np.zeros(p.shape[0], np.dtype([("tag", "u1"), ("pos", "<f8", (3,))]))  # packed: 25-byte records
    unaligned["pos"] = p
    bad["packed structured field"] = unaligned["pos"]
    for what, positions in bad.items():
        with pytest.raises(ValueError):
            macrocon.Mesh(context, positions, t)
        with pytest.raises(ValueError):
            macrocon.Patch.from_arrays(context, positions, t, 0)
    with pytest.raises(ValueError, match="columns not"):
        macrocon.Mesh(context, big[:, 0:6:2], t)
    with pytest.raises(ValueError, match="not positive"):
        macrocon.Mesh(context, p, t[::-1])
    with pytest.raises(ValueError, match="alignment"):
        macrocon.Mesh(context, bad["unaligned stride"], t)
    with pytest.raises(TypeError):  # dtype is never converted, strided or not
        macrocon.Mesh(context, wide(p.astype(np.float16), 1, 0, 0), t)


@pytest.fixture
def patches(context):
    p, t = bumpy(N)
    with macrocon.Mesh(context, p, t) as mesh:
        ps = [macrocon.Patch.extract(mesh, 0.22, center_vertex=center(N, i, j)) for i, j in CENTERS]
    yield ps
    for q in ps:
        q.close()


def fields_of(patch, strided: bool):
    """The same scalar, vector and label fields, packed or as views into interleaved records."""
    rec = records(patch.positions)
    table = wide(np.hstack([patch.uv, np.abs(patch.positions)]), 3, 2, np.inf)  # uv | colour columns
    if strided:
        uv, colour, weights, labels = table[:, 0:2], table[:, 2:5], rec["weights"], rec["label"]
        assert not any(a.flags.c_contiguous for a in (uv, colour, weights, labels))
    else:
        uv, colour = patch.uv, np.abs(patch.positions)
        weights, labels = rec["weights"].copy(), rec["label"].copy()
    return [
        macrocon.Field("weights", macrocon.FieldKind.SCALAR, weights),
        macrocon.Field("colour", macrocon.FieldKind.VECTOR3, colour),
        macrocon.Field("part", macrocon.FieldKind.INTEGER_LABEL, labels),
        macrocon.Field("first", macrocon.FieldKind.INTEGER_LABEL, rec["label"][:, 0] if strided
                       else rec["label"][:, 0].copy()),  # (n,) with a 72-byte stride
        macrocon.Field("uv", macrocon.FieldKind.UV, uv),
    ]


def custom_descriptors(patch, strided: bool):
    # Mean curvature at three scales (fancy indexing returns Fortran order: pack it).
    d = np.ascontiguousarray(patch.descriptors("curv9")[:, [1, 4, 7]])
    return wide(d, 1, 4, np.nan) if strided else d


def library(context, patches, strided: bool):
    lib = macrocon.Library(context)
    for k, patch in enumerate(patches):
        lib.add_entry(patch, name=f"e{k}", fields=fields_of(patch, strided),
                      descriptors=custom_descriptors(patch, strided))
    lib.build_retrieval(descriptor=macrocon.RetrievalDescriptor.CUSTOM, vocabulary_size=8, seed=5)
    return lib


def test_library_fields_and_descriptors_from_strided_rows_equal_packed(context, patches):
    with library(context, patches, False) as packed, library(context, patches, True) as strided:
        assert strided.to_bytes() == packed.to_bytes()  # the whole file, bit for bit
        for k, patch in enumerate(patches):
            for name, field in strided[k].fields.items():
                ref = packed[k].fields[name]
                assert field.kind == ref.kind and np.array_equal(field.values, ref.values)
            assert np.array_equal(strided[k].fields["part"].values, records(patch.positions)["label"])
            assert np.array_equal(strided[k].descriptors, packed[k].descriptors)


def test_query_descriptors_with_strided_rows_equals_packed(context, patches):
    with library(context, patches, False) as lib:
        for k, patch in enumerate(patches):
            a = lib.query_descriptors(patch, custom_descriptors(patch, False), 3)
            b = lib.query_descriptors(patch, custom_descriptors(patch, True), 3)
            assert a.indices[0] == k
            for x, y in ((a.ids, b.ids), (a.indices, b.indices), (a.distances, b.distances)):
                assert np.array_equal(x, y)
        patch = patches[0]
        d = custom_descriptors(patch, False)
        with pytest.raises(ValueError):  # every other column
            lib.query_descriptors(patch, np.repeat(d, 2, axis=1)[:, ::2], 3)
        with pytest.raises(ValueError):  # reversed rows
            lib.query_descriptors(patch, d[::-1], 3)
        with pytest.raises(ValueError):  # Fortran order
            lib.query_descriptors(patch, np.asfortranarray(d), 3)


def test_strided_fields_with_bad_layouts_raise_value_error(context, patches):
    patch = patches[0]
    labels = records(patch.positions)["label"]
    with macrocon.Library(context) as lib:
        for values, kind in ((patch.uv[::-1], macrocon.FieldKind.UV),
                             (np.asfortranarray(patch.uv), macrocon.FieldKind.UV),
                             (np.broadcast_to(labels[0], labels.shape), macrocon.FieldKind.INTEGER_LABEL)):
            with pytest.raises(ValueError):
                lib.add_entry(patch, fields=[macrocon.Field("f", kind, values)])
        with pytest.raises(ValueError):
            lib.add_entry(patch, descriptors=custom_descriptors(patch, False)[::-1])
        assert len(lib) == 0

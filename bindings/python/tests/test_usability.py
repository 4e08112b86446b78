"""What a new user meets first: docstrings, reprs, info dataclasses, missing-file errors and entry
lookup by index, name or id (issue 17, "Using it from Python, C# and the CLI")."""
import dataclasses
import inspect

import numpy as np
import pytest

import macrocon
from macrocon import _native
from conftest import bumpy, center


@pytest.fixture
def region(context):
    p, t = bumpy(41)
    with macrocon.Mesh(context, p, t) as mesh:
        with macrocon.Patch.extract(mesh, radius=0.3, center_vertex=center(41, 20, 20)) as patch:
            yield mesh, patch


# ---- Patch.info -----------------------------------------------------------------------------------

def test_patch_info_is_a_frozen_dataclass_with_every_c_field(context, region):
    mesh, patch = region
    info = patch.info
    assert isinstance(info, macrocon.PatchInfo) and dataclasses.is_dataclass(info)
    c_fields = [f[0] for f in _native.PatchInfo._fields_ if f[0] != "struct_size"]
    assert [f.name for f in dataclasses.fields(info)] == c_fields
    with pytest.raises(dataclasses.FrozenInstanceError):
        info.radius = 2.0
    assert info.vertex_count == patch.vertex_count == patch.positions.shape[0]
    assert info.triangle_count == patch.triangle_count == patch.triangles.shape[0]
    assert isinstance(info.center, tuple) and len(info.center) == 3
    assert isinstance(info.center_barycentric, tuple) and abs(sum(info.center_barycentric) - 1) < 1e-9
    assert info.radius == pytest.approx(0.3) and info.boundary_loops == 1 and info.euler_characteristic == 1
    # The center it reports is the host vertex it was cut around.
    p, _ = bumpy(41)
    assert np.allclose(info.center, p[center(41, 20, 20)])
    assert dataclasses.asdict(info)["vertex_count"] == patch.vertex_count
    # from_arrays: the center given comes back in the info.
    with macrocon.Patch.from_arrays(context, patch.positions, patch.triangles, center_triangle=7,
                                    center_barycentric=(0.2, 0.3, 0.5)) as copy:
        assert copy.info.center_patch_triangle == 7
        assert copy.info.center_barycentric == pytest.approx((0.2, 0.3, 0.5))


# ---- repr -----------------------------------------------------------------------------------------

def test_repr_of_every_handle_shows_its_sizes_and_closed_state(context, region):
    mesh, patch = region
    assert repr(context) == "<macrocon.Context max_threads=2>"
    nv, nt = mesh.counts
    assert repr(mesh) == f"<macrocon.Mesh vertices={nv} triangles={nt}>"
    r = repr(patch)
    assert r.startswith("<macrocon.Patch ") and f"vertices={patch.vertex_count} " in r
    assert f"triangles={patch.triangle_count} " in r and "radius=0.3 " in r and "boundary_loops=1" in r
    with macrocon.Library(context) as lib:
        assert repr(lib) == "<macrocon.Library entries=0 descriptor=CURV9 vocabulary=0>"
        lib.add_entry(patch, name="a")
        lib.add_entry(patch, name="b")
        assert repr(lib) == "<macrocon.Library entries=2 descriptor=CURV9 vocabulary=0>"
        assert repr(lib[1]) == f"<macrocon.Entry 1 id={lib[1].id} 'b'>"
    with macrocon.Map.compute(patch, patch, max_iterations=5) as phi:
        r = repr(phi)
        i = phi.info
        assert r.startswith("<macrocon.Map ") and f"source_vertices={patch.vertex_count} " in r
        assert f"target_vertices={patch.vertex_count} " in r and f"iterations={i.iterations} " in r
        assert f"stop={i.stop_reason.name} " in r and f"reflected={i.reflected}>" in r
        tri = np.arange(0, patch.triangle_count, 50, dtype=np.uint32)
        line = macrocon.Polyline(tri, np.full((tri.size, 3), 1 / 3))
        with phi.transfer_polylines([line]) as traced:
            n, p = traced.counts
            assert n >= 1 and repr(traced) == f"<macrocon.PolylineSet polylines={n} points={p}>"
    patch.close()
    assert repr(patch) == "<macrocon.Patch closed>"  # never raises, even on a closed handle
    mesh.close()
    assert repr(mesh) == "<macrocon.Mesh closed>"


# ---- missing files --------------------------------------------------------------------------------

def test_opening_a_missing_library_is_a_file_not_found_error_naming_the_path(context, tmp_path):
    for path in (tmp_path / "missing.mclb", str(tmp_path / "also missing.mclb")):
        with pytest.raises(FileNotFoundError) as err:
            macrocon.Library.open(context, path)
        e = err.value
        assert str(path) in str(e) and e.filename == str(path) and e.errno == 2
        # Still what existing callers catch.
        assert isinstance(e, macrocon.IOError_) and isinstance(e, macrocon.Error) and e.status == 8


def test_a_path_that_exists_but_cannot_be_read_stays_an_io_error(context, tmp_path):
    with pytest.raises(macrocon.IOError_) as err:
        macrocon.Library.open(context, tmp_path)  # a folder, not a file
    assert not isinstance(err.value, FileNotFoundError)


def test_writing_into_a_missing_folder_is_a_file_not_found_error_naming_it(context, region, tmp_path):
    _, patch = region
    folder = tmp_path / "no such folder"
    with macrocon.Library(context) as lib:
        with pytest.raises(FileNotFoundError) as err:
            lib.save(folder / "lib.mclb")
        assert err.value.filename == str(folder) and str(folder) in str(err.value)
        lib.save(tmp_path / "lib.mclb")  # an existing folder still works
    directions = np.tile([1.0, 0.0, 0.0], (patch.triangle_count, 1))
    with pytest.raises(FileNotFoundError) as err:
        patch.write_rosy(directions, folder / "field.rosy")
    assert err.value.filename == str(folder) and isinstance(err.value, macrocon.IOError_)


# ---- entry and find by index, name or id -----------------------------------------------------------

@pytest.fixture
def named(context, region):
    _, patch = region
    with macrocon.Library(context) as lib:
        ids = [lib.add_entry(patch, name=n) for n in ("left ear", "nose", "twin", "twin")]
        yield lib, ids


def test_find_and_entry_by_id_name_and_index(named):
    lib, ids = named
    assert [lib.find(i) for i in ids] == [0, 1, 2, 3]  # by id, as before
    assert lib.find(id=ids[1]) == 1 and lib.find(np.uint64(ids[2])) == 2
    assert lib.find("nose") == 1 and lib.find(name="left ear") == 0
    assert lib.entry(1).name == "nose" and lib.entry(index=0).id == ids[0]
    assert lib.entry(-1).index == 3 and lib[-4].index == 0 and lib[np.uint32(2)].index == 2
    assert lib.entry("nose").index == 1 and lib["left ear"].id == ids[0] and lib.entry(name="nose").id == ids[1]
    assert lib.entry(id=ids[3]).index == 3


def test_a_center_outside_the_mesh_says_numbers_count_from_0_and_names_the_range(region):
    mesh, _ = region
    nv, nt = mesh.counts
    for kwargs, what, count in (({"center_vertex": -1}, "center_vertex is -1", nv),
                                ({"center_triangle": -3}, "center_triangle is -3", nt)):
        with pytest.raises(macrocon.InvalidArgumentError) as err:
            macrocon.Patch.extract(mesh, 0.3, **kwargs)
        text = str(err.value)
        assert what in text and "count from 0" in text and f"0..{count - 1}" in text, text
    with pytest.raises(macrocon.InvalidArgumentError, match=f"has {nv} vertices"):
        macrocon.Patch.extract(mesh, 0.3, center_vertex=nv)  # too large: the C API names the count


def test_an_index_outside_the_library_names_the_valid_range(context, named):
    lib, _ = named
    for bad in (4, -5, 100):
        with pytest.raises(IndexError) as err:
            lib.entry(bad)
        assert f"entry index {bad} " in str(err.value) and "0..3" in str(err.value) and "-4..-1" in str(err.value)
        assert isinstance(err.value, macrocon.InvalidArgumentError)  # what it was before
    with pytest.raises(IndexError, match="0..3"):
        lib[4]
    with macrocon.Library(context) as empty:
        with pytest.raises(macrocon.EntryIndexError, match="empty"):
            empty.entry(0)


def test_an_unknown_or_ambiguous_name_or_id_is_a_key_error_naming_it(named):
    lib, ids = named
    with pytest.raises(KeyError) as err:
        lib.find("mouth")
    assert "'mouth'" in str(err.value) and isinstance(err.value, macrocon.NotFoundError)
    with pytest.raises(KeyError, match="mouth"):
        lib["mouth"]
    with pytest.raises(KeyError) as err:
        lib.entry(name="twin")
    assert "2 entries are named 'twin'" in str(err.value) and f"ids {ids[2]}, {ids[3]}" in str(err.value)
    unknown = max(ids) + 1000
    with pytest.raises(KeyError, match=f"no entry has id {unknown}"):
        lib.entry(id=unknown)
    with pytest.raises(macrocon.NotFoundError, match=f"no entry has id {unknown}"):
        lib.find(unknown)


def test_entry_and_find_reject_what_is_neither_an_index_a_name_nor_an_id(named):
    lib, ids = named
    for call in (lambda: lib.entry(), lambda: lib.entry(0, name="nose"), lambda: lib.entry(id=ids[0], name="nose"),
                 lambda: lib.entry(1.0), lambda: lib.entry(True), lambda: lib.find(), lambda: lib.find(1.5),
                 lambda: lib.find(ids[0], name="nose"), lambda: lib.find(name=3)):
        with pytest.raises(TypeError):
            call()


# ---- docstrings ----------------------------------------------------------------------------------

def _is_generated_dataclass_doc(cls) -> bool:
    # @dataclass writes "Name(field: type, ...)" into a class that has no docstring of its own.
    return dataclasses.is_dataclass(cls) and (cls.__doc__ or "").startswith(cls.__name__ + "(")


def _undocumented():
    missing = []
    for name in macrocon.__all__:
        value = getattr(macrocon, name)
        if inspect.isclass(value):
            if not (value.__doc__ or "").strip() or _is_generated_dataclass_doc(value):
                missing.append(name)
            # Public members defined by this package (the class or a macrocon base such as _Handle);
            # what numpy, enum, int or Exception define is theirs to document.
            seen = set()
            for base in value.__mro__:
                if not base.__module__.startswith("macrocon"):
                    continue
                for member, raw in vars(base).items():
                    if member.startswith("_") or member in seen:
                        continue
                    seen.add(member)
                    if isinstance(raw, (staticmethod, classmethod)):
                        raw = raw.__func__
                    if isinstance(raw, property) or inspect.isfunction(raw):
                        if not (inspect.getdoc(raw) or "").strip():
                            missing.append(f"{name}.{member}")
        elif callable(value):
            if not (inspect.getdoc(value) or "").strip():
                missing.append(name)
    return missing


def test_every_public_class_function_method_and_property_has_a_docstring():
    assert _undocumented() == []


def test_the_docstring_walk_sees_methods_properties_and_inherited_members():
    # The walk above must reach what it claims to check, or an empty result proves nothing.
    assert macrocon.Patch.extract.__doc__ and "center_triangle" in macrocon.Patch.extract.__doc__
    assert inspect.getdoc(macrocon.Mesh.close)  # inherited from the private _Handle base
    assert inspect.getdoc(macrocon.Entry.name)  # a property
    for cls in (macrocon.PatchInfo, macrocon.LibraryInfo, macrocon.EntryInfo, macrocon.MapInfo):
        assert not _is_generated_dataclass_doc(cls), cls

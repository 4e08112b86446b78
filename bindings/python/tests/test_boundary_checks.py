"""What must not cross the ctypes boundary unchecked: out-of-range integers (ctypes truncates them:
2**32 + 5 used to pick vertex 5) and strings with NUL (c_char_p cuts them short)."""
import numpy as np
import pytest

import macrocon
from conftest import center


def test_out_of_range_integers_are_rejected_not_truncated(host):
    mesh, _, _ = host
    for bad in (2**32 + 5, 2**32, -1):
        with pytest.raises(macrocon.InvalidArgumentError) as err:
            macrocon.Patch.extract(mesh, radius=0.25, center_vertex=bad)
        assert "outside the range" in err.value.message and str(bad) in err.value.message
    with pytest.raises(macrocon.InvalidArgumentError):
        macrocon.Patch.extract(mesh, radius=0.25, center_triangle=2**32)


def test_library_ids_vocabulary_and_names_are_checked(context, host):
    mesh, _, _ = host
    with macrocon.Patch.extract(mesh, radius=0.25, center_vertex=center(41, 20, 21)) as patch, \
            macrocon.Library(context) as library:
        with pytest.raises(macrocon.InvalidArgumentError):
            library.add_entry(patch, id=2**64)
        with pytest.raises(macrocon.InvalidArgumentError) as err:
            library.add_entry(patch, name="uv\0x")
        assert "NUL" in err.value.message
        with pytest.raises(macrocon.InvalidArgumentError):
            library.add_entry(patch, tags=["ok", "a\0b"])
        assert len(library) == 0  # nothing was stored by the rejected calls
        library.add_entry(patch, id=2**64 - 1, name="fine")
        with pytest.raises(macrocon.InvalidArgumentError):
            library.build_retrieval(vocabulary_size=2**32 + 8)


def test_direct_ctypes_calls_are_checked_too():
    from macrocon import _native

    with pytest.raises(macrocon.InvalidArgumentError):
        _native.lib.mcon_library_remove_entry(None, 2**64)
    with pytest.raises(macrocon.InvalidArgumentError):
        _native.lib.mcon_library_save(None, b"a\0b")


def test_empty_mesh_reports_empty_mesh_not_a_stride(context):
    for p in (np.zeros((0, 3)), np.empty((0, 3))):
        with pytest.raises(macrocon.InvalidMeshError) as err:
            macrocon.Mesh(context, p, np.zeros((0, 3), np.uint32))
        assert err.value.status == 17, err.value.message  # MCON_ERROR_EMPTY_MESH


def test_map_works_after_its_patches_are_closed(host):
    mesh, _, _ = host
    source = macrocon.Patch.extract(mesh, radius=0.25, center_vertex=center(41, 20, 21))
    target = macrocon.Patch.extract(mesh, radius=0.25, center_vertex=center(41, 21, 21))
    with macrocon.Map.compute(source, target, seed=3, alignment_samples=64, max_iterations=5) as phi:
        before = phi.correspondences()
        source.close()
        target.close()
        after = phi.correspondences()  # the C map holds its own references
        assert np.array_equal(before[0], after[0])

import subprocess
import sys
import textwrap

import numpy as np
import pytest

import macrocon
from conftest import grid


def test_version_and_abi():
    major, minor, patch = macrocon.version()
    assert major == macrocon.ABI_MAJOR
    assert (major, minor, patch) >= (0, 1, 0)
    assert macrocon.status_name(20) == "MCON_ERROR_NOT_A_DISK"


def test_mesh_from_float32_and_float64(context):
    for dtype in (np.float32, np.float64):
        p, t = grid(5, dtype=dtype)
        with macrocon.Mesh(context, p, t) as mesh:
            assert mesh.counts == (25, 32)


def test_mesh_errors_carry_status_and_message(context):
    p, t = grid(5)
    p[7, 1] = np.nan
    with pytest.raises(macrocon.InvalidMeshError) as err:
        macrocon.Mesh(context, p, t)
    assert err.value.status == 10
    assert "vertex 7" in err.value.message

    p, t = grid(5)
    t[3, 2] = 999
    with pytest.raises(macrocon.InvalidMeshError) as err:
        macrocon.Mesh(context, p, t)
    assert err.value.status == 11


def test_array_checks_happen_before_the_call(context):
    p, t = grid(5)
    with pytest.raises(TypeError, match="uint32 or int32 or int64"):
        macrocon.Mesh(context, p, t.astype(np.int16))
    with pytest.raises(ValueError):
        macrocon.Mesh(context, p[:, :2].copy(), t)
    with pytest.raises(ValueError):
        macrocon.Mesh(context, np.asfortranarray(p), t)


def test_patch_extraction_round_trip(context):
    p, t = grid(41)
    with macrocon.Mesh(context, p, t) as mesh:
        patch = macrocon.Patch.extract(mesh, radius=0.3, center_vertex=20 * 41 + 20)
        info = patch.info
        assert info.boundary_loops == 1
        assert info.euler_characteristic == 1
        assert info.param_flipped_triangles == 0
        assert abs(info.max_geodesic_distance - 1.0) < 0.1
        pos, uv, tri = patch.positions, patch.uv, patch.triangles
        assert pos.shape == (patch.vertex_count, 3) and uv.shape == (patch.vertex_count, 2)
        assert tri.shape == (patch.triangle_count, 3) and tri.max() < patch.vertex_count
        assert np.all(np.linalg.norm(uv, axis=1) <= 1 + 1e-9)
        # Host link reproduces the normalized positions.
        v0, v1, s = patch.host_vertices
        host = (1 - s)[:, None] * p[v0] + s[:, None] * p[v1]
        expected = (host - np.array(info.center[:])) / info.radius
        assert np.allclose(expected, pos, atol=1e-9)
        assert np.all(patch.host_triangles < t.shape[0])
        d = patch.descriptors("curv9")
        assert d.shape == (patch.vertex_count, 9)
        assert np.all(np.isfinite(d))
        assert np.allclose(d, 0, atol=1e-6)  # a plane has no curvature
        patch.close()


def test_not_a_disk_and_bad_arguments(context):
    p, t = grid(11)
    with macrocon.Mesh(context, p, t) as mesh:
        with pytest.raises(macrocon.InvalidArgumentError):
            macrocon.Patch.extract(mesh, radius=-1.0, center_vertex=60)
        with pytest.raises(macrocon.InvalidArgumentError):
            macrocon.Patch.extract(mesh, radius=0.3, center_vertex=10_000)
        with pytest.raises(ValueError):
            macrocon.Patch.extract(mesh, radius=0.3)


def test_progress_can_cancel_and_exceptions_propagate(context):
    p, t = grid(31)
    with macrocon.Mesh(context, p, t) as mesh:
        seen = []
        with pytest.raises(macrocon.CancelledError):
            macrocon.Patch.extract(mesh, radius=0.3, center_vertex=15 * 31 + 15,
                                   progress=lambda f: seen.append(f) or len(seen) < 2)
        assert len(seen) == 2

        def boom(_):
            raise RuntimeError("from the callback")

        with pytest.raises(RuntimeError, match="from the callback"):
            macrocon.Patch.extract(mesh, radius=0.3, center_vertex=15 * 31 + 15, progress=boom)


def test_closed_handles_are_rejected(context):
    p, t = grid(5)
    mesh = macrocon.Mesh(context, p, t)
    mesh.close()
    mesh.close()  # idempotent
    with pytest.raises(ValueError):
        _ = mesh.counts


def test_process_exits_cleanly_after_parallel_work():
    """Objects left open at exit: the exit hook releases them and mcon_shutdown succeeds."""
    script = textwrap.dedent(
        """
        import atexit, sys
        sys.path.insert(0, %r)
        # Registered before macrocon is imported, so it runs after macrocon's exit hook (atexit is LIFO).
        atexit.register(lambda: print("exit_status", sys.modules["macrocon"].core.exit_status))
        import numpy as np, macrocon
        from conftest import grid
        p, t = grid(81)
        ctx = macrocon.Context()
        mesh = macrocon.Mesh(ctx, p, t)
        kept = [macrocon.Patch.extract(mesh, radius=r, center_vertex=40 * 81 + 40) for r in (0.2, 0.3, 0.4)]
        for patch in kept:
            patch.descriptors("curv9")
        print("done")
        """
        % str(__import__("pathlib").Path(__file__).parent)
    )
    for _ in range(3):
        proc = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=300)
        assert proc.returncode == 0, proc.stderr
        assert proc.stdout.split() == ["done", "exit_status", "0"], proc.stdout + proc.stderr


def test_shutdown_refuses_while_a_context_lives_and_close_all_fixes_it():
    script = textwrap.dedent(
        """
        import macrocon
        ctx = macrocon.Context()
        try:
            macrocon.shutdown()
        except macrocon.InvalidArgumentError as e:
            print("refused", "still alive" in e.message)
        macrocon.close_all()
        macrocon.shutdown()
        print("ok", ctx._handle is None)
        """
    )
    proc = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    assert proc.stdout.split() == ["refused", "True", "ok", "True"]


def test_reversed_triangles_are_repaired_and_reported(context):
    p, t = grid(31)
    x, y = p[:, 0], p[:, 1]
    p[:, 2] = 0.15 * np.sin(5 * x + 1) * np.cos(3 * y) + 0.1 * x * x * y
    flipped = t.copy()
    flipped[::3, [1, 2]] = flipped[::3, [2, 1]]
    with macrocon.Mesh(context, p, t) as a, macrocon.Mesh(context, p, flipped) as b:
        assert b.orientation.inconsistent_component_count == 1
        assert b.orientation.component_count == 1
        assert b.orientation.reoriented_triangles in (len(t[::3]), len(t) - len(t[::3]))
        assert b.reoriented_triangles.shape == (len(t),)
        assert int(b.reoriented_triangles.sum()) == b.orientation.reoriented_triangles
        np.testing.assert_array_equal(a.triangles, b.triangles)
        pa = macrocon.Patch.extract(a, radius=0.3, center_vertex=15 * 31 + 15)
        pb = macrocon.Patch.extract(b, radius=0.3, center_vertex=15 * 31 + 15)
        assert pb.info.host_reoriented_triangles == b.orientation.reoriented_triangles
        assert pb.info.host_inconsistent_components == 1
        np.testing.assert_array_equal(pa.descriptors("curv9"), pb.descriptors("curv9"))


@pytest.mark.parametrize("dtype", [np.uint32, np.int32, np.int64, np.intc, np.longlong])
def test_mesh_and_patch_accept_uint32_int32_and_int64_triangles(context, dtype):
    """Triangles pass in their own dtype (mcon_mesh_desc.index_format): the same mesh from every
    accepted dtype is the same mesh, and the same patch bit for bit."""
    p, t = grid(9)
    with macrocon.Mesh(context, p, t) as ref, macrocon.Mesh(context, p, t.astype(dtype)) as mesh:
        assert mesh.counts == ref.counts == (81, 128)
        assert np.array_equal(mesh.triangles, ref.triangles)
    with macrocon.Patch.from_arrays(context, p, t, 60) as ref, \
            macrocon.Patch.from_arrays(context, p, t.astype(dtype), 60) as patch:
        assert np.array_equal(patch.triangles, ref.triangles)
        assert np.array_equal(patch.positions, ref.positions) and np.array_equal(patch.uv, ref.uv)


def test_int64_triangles_are_read_in_place_strided_and_range_checked(context):
    p, t = grid(5)
    wide = np.zeros((t.shape[0], 5), np.int64)  # int64 rows with a tag column either side
    wide[:, 0], wide[:, 4] = -1, 1 << 40
    wide[:, 1:4] = t
    with macrocon.Mesh(context, p, wide[:, 1:4]) as mesh:  # a strided view: 40-byte rows
        assert np.array_equal(mesh.triangles, t)
    for dtype in (np.int32, np.int64):
        bad = t.astype(dtype)
        bad[3, 1] = -2
        with pytest.raises(macrocon.InvalidMeshError) as err:
            macrocon.Mesh(context, p, bad)
        assert err.value.status == 11 and "triangle 3" in err.value.message and "-2" in err.value.message
    big = t.astype(np.int64)
    big[5, 0] = 1 << 33  # would be vertex 0 if truncated to 32 bits
    with pytest.raises(macrocon.InvalidMeshError) as err:
        macrocon.Mesh(context, p, big)
    assert err.value.status == 11 and str(1 << 33) in err.value.message and "[0, 25)" in err.value.message
    for bad_dtype in (np.int16, np.uint64, np.float64, np.dtype(">i4")):
        with pytest.raises(TypeError, match="uint32 or int32 or int64"):
            macrocon.Mesh(context, p, t.astype(bad_dtype))
        with pytest.raises(TypeError, match="uint32 or int32 or int64"):
            macrocon.Patch.from_arrays(context, p, t.astype(bad_dtype), 0)


def test_validate_locally_accepts_defects_away_from_the_patch(context):
    # A 21 x 21 grid on [0, 4]^2 with a duplicated triangle and an isolated vertex near (4, 4).
    p, t = grid(21, size=4.0)
    far = int(np.argmax(p[t].mean(axis=1).sum(axis=1)))  # the triangle nearest (4, 4)
    t = np.vstack([t, t[far]])
    p = np.vstack([p, [[9.0, 9.0, 9.0]]])
    with pytest.raises(macrocon.InvalidMeshError) as err:
        macrocon.Mesh(context, p, t)  # whole-mesh validation, the default
    assert "is used by 3 triangles" in err.value.message
    with pytest.raises(TypeError):
        macrocon.Mesh(context, p, t, validate_locally=1)

    clean_p, clean_t = grid(21, size=4.0)
    with macrocon.Mesh(context, p, t, validate_locally=True) as mesh, \
            macrocon.Mesh(context, clean_p, clean_t) as clean:
        near = 4 * 21 + 4  # vertex (0.8, 0.8)
        with macrocon.Patch.extract(mesh, 0.5, center_vertex=near) as a, \
                macrocon.Patch.extract(clean, 0.5, center_vertex=near) as b:
            assert np.array_equal(a.positions, b.positions)
        with pytest.raises(macrocon.InvalidMeshError) as err:
            macrocon.Patch.extract(mesh, 0.3, center_vertex=19 * 21 + 19)
        assert "within 3 radii of the center" in err.value.message
        with pytest.raises(macrocon.InvalidMeshError) as err:
            mesh.cut_guides([])
        assert "reads the whole mesh" in err.value.message


def test_repair_removes_zero_area_triangles_and_splits_pinched_vertices(context):
    # The 21 x 21 grid with a zero-area cap on the bottom edge (5, 0)-(6, 0) and a sheet glued at
    # the interior vertex (15, 10).
    p, t = grid(21, size=4.0)
    a, b = 5, 6
    p = np.vstack([p, [(p[a] + p[b]) / 2], p[15 + 10 * 21] + [[0.3, 0, 0.6], [0, 0.3, 0.6]]])
    n = len(p)
    t = np.vstack([t, [[b, a, n - 3], [15 + 10 * 21, n - 2, n - 1]]]).astype(np.uint32)
    clean_p, clean_t = grid(21, size=4.0)
    with macrocon.Mesh(context, p, t, validate_locally=True) as mesh, macrocon.Mesh(context, clean_p, clean_t) as clean:
        with pytest.raises(macrocon.InvalidMeshError) as err:
            macrocon.Patch.extract(mesh, 0.5, center_vertex=5 + 21)
        assert "MCON_PATCH_REPAIR_REGION" in err.value.message
        with macrocon.Patch.extract(mesh, 0.5, center_vertex=5 + 21, repair=True) as cap:
            assert cap.repairs == macrocon.PatchRepairs(1, 1, 0, 0)
        with macrocon.Patch.extract(mesh, 0.5, center_vertex=14 + 10 * 21, repair=True) as pinched, \
                macrocon.Patch.extract(clean, 0.5, center_vertex=14 + 10 * 21) as reference:
            assert pinched.repairs.pinched_vertices_split == 1
            assert np.array_equal(pinched.positions, reference.positions)
            assert reference.repairs == macrocon.PatchRepairs(0, 0, 0, 0)
        with pytest.raises(macrocon.InvalidArgumentError):
            macrocon.Patch.extract(clean, 0.5, center_vertex=30, repair=True)  # nothing deferred to repair


def test_closest_points_on_the_mesh_and_a_patch(context):
    p, t = grid(41)
    with macrocon.Mesh(context, p, t) as mesh:
        q = np.array([[0.3, 0.6, 0.2], [1.3, 0.5, 0.0]])
        tri, bary, dist = mesh.closest_points(q)
        assert tri.dtype == np.uint32 and bary.shape == (2, 3)
        np.testing.assert_allclose(dist, [0.2, 0.3], atol=1e-12)
        corners = mesh.triangles[tri]
        foot = np.einsum("ik,ikj->ij", bary, p[corners])
        np.testing.assert_allclose(foot, [[0.3, 0.6, 0.0], [1.0, 0.5, 0.0]], atol=1e-12)
        patch = macrocon.Patch.extract(mesh, radius=0.3, center_vertex=20 * 41 + 20)
        ptri, _, pdist = patch.closest_points(np.array([[0.55, 0.5, -0.1]]))  # host units
        assert ptri[0] < patch.triangle_count
        assert abs(pdist[0] - 0.1) < 1e-9
        with pytest.raises(TypeError, match="points must have dtype float64"):
            mesh.closest_points(q.astype(np.float32))
        with pytest.raises(ValueError, match=r"points must have shape \(n, 3\)"):
            mesh.closest_points(q[:, :2])
        bad = q.copy()
        bad[1, 2] = np.nan
        with pytest.raises(macrocon.Error, match="coordinate 2 of point 1 is not finite"):
            mesh.closest_points(bad)


def test_geodesic_distances_on_a_flat_patch(context):
    """On a plane the heat method's distance is Euclidean (normalized units, up to its error)."""
    p, t = grid(41)
    with macrocon.Mesh(context, p, t) as mesh:
        patch = macrocon.Patch.extract(mesh, radius=0.3, center_vertex=20 * 41 + 20)
        info = patch.info
        d = patch.distance_from_point(info.center_patch_triangle, info.center_barycentric)
        r = np.linalg.norm(patch.positions, axis=1)
        assert np.abs(d - r).max() < 0.06
        centre = int(np.argmin(r))
        dv = patch.distance_from_vertices([centre, centre])
        assert dv[centre] == 0.0 and np.abs(dv - r).max() < 0.06
        assert np.array_equal(dv, patch.distance_from_vertices(np.array([centre], np.int64)))
        with pytest.raises(macrocon.InvalidArgumentError, match="not a vertex of the patch"):
            patch.distance_from_vertices([patch.vertex_count])
        with pytest.raises(ValueError):
            patch.distance_from_vertices([])
        with pytest.raises(macrocon.InvalidArgumentError):
            patch.distance_from_point(info.center_patch_triangle, [0.5, 0.5, 0.5])
        patch.close()

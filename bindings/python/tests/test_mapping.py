"""Re-embedding maps, transfer and cross fields through the Python binding."""
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pytest

import macrocon
from conftest import center

FAST = dict(alignment_samples=400, max_iterations=30)


@pytest.fixture
def target(host):
    mesh, _, _ = host
    with macrocon.Patch.extract(mesh, radius=0.25, center_vertex=center(41, 20, 21)) as patch:
        yield patch


@pytest.fixture
def source(context, target):
    """The target's own normalized mesh as a from-arrays patch: the map should be near identity."""
    info = target.info
    with macrocon.Patch.from_arrays(context, target.positions, target.triangles, info.center_patch_triangle,
                                    tuple(info.center_barycentric), origin=tuple(info.center),
                                    scale=info.radius) as patch:
        yield patch


@pytest.fixture
def phi(source, target):
    with macrocon.Map.compute(source, target, seed=3, **FAST) as m:
        yield m


def test_patch_from_arrays(context, target, source):
    assert source.vertex_count == target.vertex_count and source.triangle_count == target.triangle_count
    assert np.allclose(source.positions, target.positions)
    assert source.info.boundary_loops == 1 and source.info.param_flipped_triangles == 0
    v0, v1, t = source.host_vertices
    assert np.array_equal(v0, np.arange(source.vertex_count)) and np.array_equal(v0, v1) and np.all(t == 0)
    assert np.array_equal(source.host_triangles, np.arange(source.triangle_count))


def test_patch_from_arrays_errors(context, target):
    pos, tri = target.positions, target.triangles
    with pytest.raises(macrocon.InvalidArgumentError):  # MCON_INVALID_INDEX center
        macrocon.Patch.from_arrays(context, pos, tri, 0xFFFFFFFF)
    with pytest.raises(macrocon.InvalidArgumentError):
        macrocon.Patch.from_arrays(context, pos, tri, 0, scale=-1.0)
    # A closed surface (an octahedron) is no disk.
    octa = np.array([[1, 0, 0], [-1, 0, 0], [0, 1, 0], [0, -1, 0], [0, 0, 1], [0, 0, -1]], np.float64)
    faces = np.array([[0, 2, 4], [2, 1, 4], [1, 3, 4], [3, 0, 4], [2, 0, 5], [1, 2, 5], [3, 1, 5], [0, 3, 5]],
                     np.uint32)
    with pytest.raises(macrocon.NotADiskError) as err:
        macrocon.Patch.from_arrays(context, octa, faces, 0)
    assert err.value.status == 20
    with pytest.raises(TypeError, match="uint32 or int32 or int64"):  # int32/int64 are accepted, not int16
        macrocon.Patch.from_arrays(context, pos, tri.astype(np.int16), 0)


def test_map_info_and_correspondences(phi, source, target):
    info = phi.info
    assert isinstance(info, macrocon.MapInfo)
    assert info.source_vertex_count == source.vertex_count and info.target_vertex_count == target.vertex_count
    assert info.flipped_triangles == 0 and info.stop_reason in (macrocon.StopReason.CONVERGED,
                                                                 macrocon.StopReason.STALLED,
                                                                 macrocon.StopReason.ITERATION_CAP)
    assert 0 <= info.matching_score <= 1 and 0 < info.overlap_ratio <= 1 + 1e-9
    assert not info.reflected  # the surface has no mirror symmetry
    assert info.source_vertices_inside > 0.8 * source.vertex_count
    for direction, domain, other, inside in (
        (macrocon.Direction.SOURCE_TO_TARGET, source, target, info.source_vertices_inside),
        (macrocon.Direction.TARGET_TO_SOURCE, target, source, info.target_vertices_inside),
    ):
        tri, bary = phi.correspondences(direction)
        assert tri.shape == (domain.vertex_count,) and bary.shape == (domain.vertex_count, 3)
        ok = tri >= 0
        assert ok.sum() == inside
        assert np.all(tri[ok] < other.triangle_count)
        assert np.allclose(bary[ok].sum(1), 1, atol=1e-9) and np.all(bary[ok] >= -1e-9)
        assert np.all(bary[~ok] == 0)
    mask = phi.outside_mask
    assert mask.dtype == bool and mask.shape == (target.vertex_count,)
    assert (~mask).sum() == info.target_vertices_inside
    assert phi.phi.shape == (source.vertex_count, 2)
    # Near identity: phi stays close to the target's own parametrization of the same vertices.
    assert np.median(np.linalg.norm(phi.phi - target.uv, axis=1)) < 0.1
    terms = phi.energy_terms
    assert list(terms)[:4] == ["descriptor", "distortion", "area", "injectivity"]
    assert terms["descriptor"] == info.energy_descriptor and terms["area"] == info.energy_area
    assert terms["distortion"] == info.energy_distortion and terms["injectivity"] == info.energy_injectivity


def test_transfer_points_fields_and_labels(phi, source, target):
    # Source vertex k as a point of one of its triangles.
    tri = source.triangles
    faces = np.arange(0, source.triangle_count, 7, dtype=np.uint32)
    bary = np.tile([[0.2, 0.3, 0.5]], (faces.size, 1))
    ot, ob, xyz = phi.transfer_points(faces, bary)
    inside = ot != 0xFFFFFFFF
    assert inside.mean() > 0.8
    assert np.allclose(ob[inside].sum(1), 1, atol=1e-9)
    expected = (bary[:, :, None] * source.positions[tri[faces]]).sum(1)
    host = np.array(target.info.center) + target.info.radius * expected  # target host units
    assert np.median(np.linalg.norm(xyz[inside] - host[inside], axis=1)) < 0.1 * target.info.radius

    pos = source.positions
    moved = phi.transfer_field(pos, macrocon.FieldKind.VECTOR3)
    assert moved.shape == (target.vertex_count, 3)
    outside = phi.outside_mask
    assert np.all(moved[outside] == 0)
    assert np.median(np.linalg.norm(moved[~outside] - target.positions[~outside], axis=1)) < 0.1
    scalar = phi.transfer_field(pos[:, 0].copy())
    assert scalar.shape == (target.vertex_count, 1)
    assert np.allclose(scalar[:, 0], moved[:, 0], atol=1e-9)  # interpolation is per channel
    uv = phi.transfer_field(source.uv, macrocon.FieldKind.UV)
    assert uv.shape == (target.vertex_count, 2)
    tangent = np.zeros_like(pos)
    tangent[:, 0] = 1.0
    pushed = phi.transfer_field(tangent, macrocon.FieldKind.TANGENT_VECTOR)
    assert pushed.shape == (target.vertex_count, 3) and np.all(np.isfinite(pushed))

    labels = (np.arange(source.vertex_count) % 5).astype(np.int32)
    out = phi.transfer_labels(labels, outside_label=-7)
    assert out.shape == (target.vertex_count, 1) and out.dtype == np.int32
    assert np.all(out[outside, 0] == -7)
    assert set(np.unique(out[~outside, 0])) <= set(range(5))  # never blended

    with pytest.raises(TypeError, match="float64 or float32"):
        phi.transfer_field(pos.astype(np.float16))
    with pytest.raises(TypeError, match="float64 or float32"):
        phi.transfer_field(pos.astype(np.int64))
    with pytest.raises(ValueError, match="rows"):
        phi.transfer_field(pos[:-1].copy())
    with pytest.raises(ValueError):
        phi.transfer_field(labels, macrocon.FieldKind.INTEGER_LABEL)
    with pytest.raises(TypeError):
        phi.transfer_labels(labels.astype(np.int64))
    with pytest.raises(macrocon.InvalidArgumentError):  # a VECTOR3 has 3 channels
        phi.transfer_field(source.uv, macrocon.FieldKind.VECTOR3)
    with pytest.raises(macrocon.InvalidArgumentError):  # weights that do not sum to 1
        phi.transfer_points(faces[:1], np.array([[0.5, 0.5, 0.5]]))


def test_transfer_of_a_strided_field_equals_the_packed_one(context, phi, source, target):
    """mcon_map_transfer_field/_labels take no stride: a field inside interleaved records is refused
    in place (ValueError) and packed once with copy=True; stored in a library entry (whose
    mcon_vertex_field has a stride) it is read in place, and both transfers equal the packed one."""
    rec_t = np.dtype([("tag", "<u4"), ("colour", "<f8", (3,)), ("part", "<i4"), ("w", "<f8")], align=True)
    n = source.vertex_count
    rec = np.zeros(n, rec_t)
    rec["colour"], rec["part"], rec["w"] = np.abs(source.positions), np.arange(n) % 4, source.uv[:, 0]
    packed, strided = np.ascontiguousarray(rec["colour"]), rec["colour"]
    ref = phi.transfer_field(packed, macrocon.FieldKind.VECTOR3)
    with pytest.raises(ValueError, match="copy=True"):
        phi.transfer_field(strided, macrocon.FieldKind.VECTOR3)
    assert np.array_equal(phi.transfer_field(strided, macrocon.FieldKind.VECTOR3, copy=True), ref)
    assert np.array_equal(phi.transfer_field(rec["w"], copy=True), phi.transfer_field(rec["w"].copy()))
    ref_labels = phi.transfer_labels(rec["part"].copy())
    with pytest.raises(ValueError, match="copy=True"):
        phi.transfer_labels(rec["part"])
    assert np.array_equal(phi.transfer_labels(rec["part"], copy=True), ref_labels)
    with pytest.raises(TypeError):  # copy never converts the dtype
        phi.transfer_labels(rec["tag"], copy=True)
    # Through a library entry: the strided field is stored (float32) and transferred from there.
    with macrocon.Library(context) as a, macrocon.Library(context) as b:
        a.add_entry(source, fields=[macrocon.Field("colour", macrocon.FieldKind.VECTOR3, packed),
                                    macrocon.Field("part", macrocon.FieldKind.INTEGER_LABEL, rec["part"].copy())])
        b.add_entry(source, fields=[macrocon.Field("colour", macrocon.FieldKind.VECTOR3, strided),
                                    macrocon.Field("part", macrocon.FieldKind.INTEGER_LABEL, rec["part"])])
        fa, fb = a[0].fields, b[0].fields
        assert np.array_equal(fa["colour"].values, fb["colour"].values)
        assert np.array_equal(phi.transfer_field(fb["colour"].values, macrocon.FieldKind.VECTOR3),
                              phi.transfer_field(fa["colour"].values, macrocon.FieldKind.VECTOR3))
        assert np.array_equal(phi.transfer_labels(fb["part"].values), ref_labels)


def test_transfer_polylines_and_cross_field(phi, source, target, tmp_path):
    # A guide along a row of source triangles through the middle of the patch.
    uv = source.uv
    tri = source.triangles
    centroid = uv[tri].mean(1)
    row = np.where(np.abs(centroid[:, 1]) < 0.05)[0]
    row = row[np.argsort(centroid[row, 0])].astype(np.uint32)
    guide = macrocon.Polyline(row, np.full((row.size, 3), 1 / 3))
    with phi.transfer_polylines([guide]) as lines:
        n, p = lines.counts
        assert n >= 1 and p >= row.size // 2
        sizes, closed, origin = lines.polyline_arrays()
        assert sizes.sum() == p and np.all(sizes >= 2) and not closed.any() and np.all(origin == 0)
        t, b, xyz = lines.point_arrays()
        assert np.all(t < target.triangle_count) and np.allclose(b.sum(1), 1, atol=1e-9)
        assert np.all(np.isfinite(xyz))
        assert sum(len(x.faces) for x in lines.polylines()) == p

        d, conf = target.cross_field(lines, alignment_weight=10.0)
        assert d.shape == (target.triangle_count, 3) and conf.shape == (target.triangle_count,)
        assert np.allclose(np.linalg.norm(d, axis=1), 1, atol=1e-6)
        assert np.all((conf >= 0) & (conf <= 1))
        with pytest.raises(macrocon.InvalidArgumentError):  # these guides live on the target
            source.cross_field(lines)
    smooth, _ = target.cross_field(None)
    assert np.allclose(np.linalg.norm(smooth, axis=1), 1, atol=1e-6)
    path = tmp_path / "field.rosy"
    target.write_rosy(d, path)
    head = path.read_text().split()
    assert str(target.triangle_count) in head[:3]
    with pytest.raises(ValueError, match="without .gz"):
        target.write_rosy(d, tmp_path / "field.rosy.gz")  # QuadWild reads it as zeros
    assert not (tmp_path / "field.rosy.gz").exists()
    with pytest.raises(macrocon.IOError_):
        target.write_rosy(d, tmp_path / "no such dir" / "f.rosy")
    with pytest.raises(ValueError):
        target.write_rosy(d[:-1].copy(), path)
    with pytest.raises(TypeError):
        target.cross_field(guides="not a set")


def test_map_progress_cancel_and_errors(source, target):
    calls = []
    with pytest.raises(macrocon.CancelledError):
        macrocon.Map.compute(source, target, progress=lambda f: calls.append(f) or False, **FAST)
    assert len(calls) == 1

    def boom(_):
        raise KeyError("from progress")

    with pytest.raises(KeyError):
        macrocon.Map.compute(source, target, progress=boom, **FAST)
    with pytest.raises(macrocon.InvalidArgumentError):
        macrocon.Map.compute(source, target, alignment_samples=0)
    with pytest.raises(TypeError):
        macrocon.Map.compute(None, target)
    m = macrocon.Map.compute(source, target, **FAST)
    m.close()
    with pytest.raises(ValueError, match="closed"):
        m.info


def test_maps_are_deterministic(source, target):
    with macrocon.Map.compute(source, target, seed=11, **FAST) as a, \
            macrocon.Map.compute(source, target, seed=11, **FAST) as b:
        assert np.array_equal(a.phi, b.phi)
        assert a.info.energy_total == b.info.energy_total


CLEAN_EXIT = """
import atexit, sys
sys.path.insert(0, {tests!r})
# Registered before macrocon is imported, so it runs after macrocon's exit hook (atexit is LIFO).
atexit.register(lambda: print("exit_status", sys.modules["macrocon"].core.exit_status, flush=True))
import numpy as np, macrocon
from conftest import bumpy
p, t = bumpy(61)
ctx = macrocon.Context()
mesh = macrocon.Mesh(ctx, p, t)
patches = [macrocon.Patch.extract(mesh, radius=0.2, center_vertex=j * 61 + i) for i, j in ((20, 20), (40, 30), (25, 40))]
lib = macrocon.Library(ctx)
for q in patches:
    lib.add_entry(q, name="x")
lib.build_retrieval(vocabulary_size=16)        # parallel k-means and histograms
{map_work}
print("done", len(lib.query(patches[0], 2)), flush=True)
# Everything is left open on purpose: the exit hook releases it, then calls mcon_shutdown.
"""

MAP_WORK = "m = macrocon.Map.compute(patches[0], patches[1], alignment_samples=2000, max_iterations=30)"


@pytest.mark.parametrize("with_map", [False, True], ids=["library", "library+map"])
def test_process_exits_cleanly_after_parallel_library_and_map_work(with_map):
    script = CLEAN_EXIT.format(tests=str(Path(__file__).parent), map_work=MAP_WORK if with_map else "")
    for _ in range(3):  # the crash this guards against was intermittent
        proc = subprocess.run([sys.executable, "-c", textwrap.dedent(script)], capture_output=True, text=True,
                              timeout=600)
        assert proc.returncode == 0, proc.stderr
        lines = proc.stdout.split("\n")
        assert "done 2" in lines
        assert "exit_status 0" in lines, proc.stdout + proc.stderr


def test_the_readme_flow_end_to_end(context, host, tmp_path):
    """Query a library, re-embed the best entry onto the region, transfer its fields and guides."""
    from test_library import example_constraints

    mesh, _, _ = host
    with macrocon.Library(context) as lib:
        for i, j in ((12, 12), (20, 20), (28, 14)):
            with macrocon.Patch.extract(mesh, radius=0.22, center_vertex=center(41, i, j)) as q:
                lines, sing, fields = example_constraints(q)
                lib.add_entry(q, name=f"{i},{j}", polylines=lines, singularities=sing, fields=fields)
        lib.build_retrieval(vocabulary_size=16)
        path = tmp_path / "starter.mclb"
        lib.save(path)
    with macrocon.Library.open(context, path) as lib, \
            macrocon.Patch.extract(mesh, radius=0.22, center_vertex=center(41, 20, 20)) as region:
        best = lib.query(region, n=3)
        entry = lib[int(best.indices[0])]
        assert entry.name == "20,20"
        info = entry.info
        with macrocon.Patch.from_arrays(context, entry.positions, entry.triangles, info.center_face,
                                        info.center_barycentric) as source, \
                macrocon.Map.compute(source, region, progress=lambda f: True, **FAST) as phi:
            uv = phi.transfer_field(entry.fields["uv"].values, macrocon.FieldKind.UV)
            assert uv.shape == (region.vertex_count, 2)
            part = phi.transfer_labels(entry.fields["part"].values)
            assert part.shape == (region.vertex_count, 1)
            with phi.transfer_polylines(entry.polylines) as guides:
                directions, _ = region.cross_field(guides)
            region.write_rosy(directions, tmp_path / "region.rosy")
            assert (tmp_path / "region.rosy").stat().st_size > 0


def test_forced_orientation_and_its_evidence(source, target):
    """The flip workflow: automatic, then each orientation forced; the info reports the evidence."""
    with macrocon.Map.compute(source, target, seed=3, **FAST) as auto:
        a = auto.info
    assert a.alignment_score_unreflected >= 0 and a.alignment_score_reflected >= 0
    assert a.alignment_score == (a.alignment_score_reflected if a.reflected else a.alignment_score_unreflected)
    if a.orientation_compared:
        assert a.level0_energy_unreflected > 0 and a.level0_energy_reflected > 0
    else:
        assert a.level0_energy_unreflected == -1 and a.level0_energy_reflected == -1
    for name, reflected in (("preserve", False), ("reverse", True)):
        with macrocon.Map.compute(source, target, seed=3, orientation=name, **FAST) as m:
            i = m.info
            assert i.reflected is reflected, name
            assert i.flipped_triangles == 0
            assert i.orientation_compared is False
            assert i.level0_energy_unreflected == -1 and i.level0_energy_reflected == -1
            # Same seed: both orientations' rigid candidates are scored as in the automatic run.
            assert i.alignment_score_unreflected == a.alignment_score_unreflected
            assert i.alignment_score_reflected == a.alignment_score_reflected
            # phi is locally injective in the forced orientation.
            uv = m.phi[source.triangles]
            cross = ((uv[:, 1, 0] - uv[:, 0, 0]) * (uv[:, 2, 1] - uv[:, 0, 1])
                     - (uv[:, 1, 1] - uv[:, 0, 1]) * (uv[:, 2, 0] - uv[:, 0, 0]))
            assert np.all(-cross > 0 if reflected else cross > 0), name
    for bad in ("flip", "AUTOMATIC", 1, None):
        with pytest.raises(ValueError, match="orientation"):
            macrocon.Map.compute(source, target, orientation=bad, **FAST)


def test_refinement_pass_is_a_stage_and_can_be_switched_off(source, target):
    """refine_sigma_factor: the default pass shows as a 4th stage; 0 turns it off; out of range raises."""
    with macrocon.Map.compute(source, target, seed=3, **FAST) as refined, \
            macrocon.Map.compute(source, target, seed=3, refine_sigma_factor=0.0, **FAST) as plain:
        assert refined.info.levels == 4 and plain.info.levels == 3
        assert refined.info.flipped_triangles == 0 and plain.info.flipped_triangles == 0
    for bad in (-0.1, 1.5, float("nan")):
        with pytest.raises(macrocon.InvalidArgumentError, match="refine_sigma_factor"):
            macrocon.Map.compute(source, target, refine_sigma_factor=bad, **FAST)


def test_coarse_stages_are_reported_and_can_be_switched_off(source, target):
    """coarse_stages / coarse_vertices: a source of >= 2 * coarse_vertices vertices runs its first two
    stages on a coarse copy (info.coarse_*); coarse_stages=0 keeps the full source; out of range raises."""
    n = source.vertex_count
    assert n >= 300
    cv = max(100, n // 3)
    with macrocon.Map.compute(source, target, seed=3, coarse_vertices=cv, **FAST) as coarse, \
            macrocon.Map.compute(source, target, seed=3, coarse_vertices=cv, coarse_stages=0, **FAST) as full:
        assert coarse.info.coarse_stages >= 1 and cv <= coarse.info.coarse_vertices <= 0.6 * n
        assert not coarse.info.coarse_fallback and coarse.info.flipped_triangles == 0
        assert full.info.coarse_vertices == 0 and full.info.coarse_stages == 0
    for bad in ({"coarse_stages": 9}, {"coarse_vertices": 99}):
        with pytest.raises(macrocon.InvalidArgumentError, match="coarse_stages must be in"):
            macrocon.Map.compute(source, target, **bad, **FAST)


def test_guidance_decides_what_the_geometry_cannot(context):
    """A flat disk onto itself fits any rotation; guidance pairing p with R p makes it that rotation."""
    from conftest import grid

    p, t = grid(41)
    with macrocon.Mesh(context, p, t) as mesh, \
            macrocon.Patch.extract(mesh, radius=0.3, center_vertex=center(41, 20, 20)) as disk:
        xyz = disk.positions
        angle = 2.0
        c, s = np.cos(angle), np.sin(angle)
        # Guidance as a column slice of a wider array: rows are strided, passed without a copy.
        wide = np.zeros((len(xyz), 4))
        wide[:, 1:3] = xyz[:, :2]
        target_g = np.stack([c * xyz[:, 0] + s * xyz[:, 1], -s * xyz[:, 0] + c * xyz[:, 1]], axis=1)  # R^-1 p
        with macrocon.Map.compute(disk, disk, seed=3, alignment_samples=400, source_guidance=wide[:, 1:3],
                                  target_guidance=target_g, guidance_weight=10.0) as m:
            assert m.info.reflected is False
            tri, bary = m.correspondences()
            inside = tri >= 0
            assert inside.mean() > 0.75
            q = np.einsum("vk,vkd->vd", bary[inside], xyz[disk.triangles[tri[inside]]])
            want = np.stack([c * xyz[:, 0] - s * xyz[:, 1], s * xyz[:, 0] + c * xyz[:, 1]], axis=1)[inside]
            # The grid's heat distances from the center have a 4-fold bias that pulls toward 90
            # degrees: weight 3 stops ~10 degrees short (0.10), weight 10 lands within 0.013; no
            # rotation at all would be ~1.1.
            assert np.linalg.norm(q[:, :2] - want, axis=1).mean() < 0.05
        with pytest.raises(ValueError, match="together"):
            macrocon.Map.compute(disk, disk, source_guidance=target_g)
        with pytest.raises(ValueError, match="one row per patch vertex"):
            macrocon.Map.compute(disk, disk, source_guidance=target_g[1:], target_guidance=target_g[1:])
        with pytest.raises(ValueError, match="same number of columns"):
            macrocon.Map.compute(disk, disk, source_guidance=target_g, target_guidance=target_g[:, 0])
        with pytest.raises(TypeError):
            macrocon.Map.compute(disk, disk, source_guidance=target_g.astype(np.float32), target_guidance=target_g)
        bad = target_g.copy()
        bad[5, 1] = np.nan
        with pytest.raises(macrocon.Error) as e:
            macrocon.Map.compute(disk, disk, source_guidance=target_g, target_guidance=bad)
        assert e.value.status == 10  # MCON_ERROR_NON_FINITE
        assert "target_guidance" in e.value.message


def test_world_frame_start_is_opt_in_and_reported(host):
    """Two patches of one mesh share the world frame: use_world_frame lets it decide."""
    mesh, _, _ = host
    with macrocon.Patch.extract(mesh, radius=0.25, center_vertex=center(41, 20, 21)) as a, \
            macrocon.Patch.extract(mesh, radius=0.25, center_vertex=center(41, 21, 21)) as b:
        with macrocon.Map.compute(a, b, seed=3, **FAST) as plain:
            assert plain.info.frame_decided is False
        with macrocon.Map.compute(a, b, seed=3, use_world_frame=True, **FAST) as framed:
            assert framed.info.frame_decided is True
            assert framed.info.reflected is False  # the same surface: no mirror in the world frame
        with pytest.raises(macrocon.InvalidArgumentError):
            macrocon.Map.compute(a, b, use_world_frame=True, orientation="preserve", **FAST)
        # The anchor term: on by default with the world frame, off at 0, checked.
        with macrocon.Map.compute(a, b, seed=3, use_world_frame=True, **FAST) as anchored:
            assert anchored.energy_terms["anchor"] > 0
        with macrocon.Map.compute(a, b, seed=3, use_world_frame=True, world_frame_anchor=0, **FAST) as free:
            assert free.energy_terms["anchor"] == 0
        for bad in (-1.0, float("nan")):
            with pytest.raises(macrocon.InvalidArgumentError):
                macrocon.Map.compute(a, b, use_world_frame=True, world_frame_anchor=bad, **FAST)
        # Up hints: both or neither, 3 components, not normal to the patch.
        with macrocon.Map.compute(a, b, seed=3, source_up=(0, 1, 0), target_up=[0.0, 2.0, 0.0], **FAST) as hinted:
            assert hinted.info.flipped_triangles == 0
        with pytest.raises(ValueError):
            macrocon.Map.compute(a, b, source_up=(0, 1, 0), **FAST)
        with pytest.raises(ValueError):
            macrocon.Map.compute(a, b, source_up=(0, 1), target_up=(0, 1, 0), **FAST)
        with pytest.raises(macrocon.InvalidArgumentError):
            macrocon.Map.compute(a, b, source_up=(0, 0, 0), target_up=(0, 1, 0), **FAST)


@pytest.mark.parametrize("kind", [macrocon.FieldKind.SCALAR, macrocon.FieldKind.VECTOR3,
                                  macrocon.FieldKind.TANGENT_VECTOR, macrocon.FieldKind.UV])
def test_float32_transfer_matches_the_float64_one(phi, source, kind):
    """float32 values (mcon_map_transfer_field_f32) come back float32: the float64 transfer of the
    widened values rounded once, and within float precision of the float64 transfer of the originals."""
    values = source.uv if kind == macrocon.FieldKind.UV else source.positions
    if kind == macrocon.FieldKind.SCALAR:
        values = np.stack([values[:, 0], values[:, 1] ** 2], axis=1)
    if kind == macrocon.FieldKind.TANGENT_VECTOR:
        values = np.zeros_like(values)
        values[:, 0] = 1.0
    v32 = np.ascontiguousarray(values, np.float32)
    out32 = phi.transfer_field(v32, kind)
    assert out32.dtype == np.float32
    ref = phi.transfer_field(v32.astype(np.float64), kind)
    assert np.array_equal(out32, ref.astype(np.float32))
    full = phi.transfer_field(np.ascontiguousarray(values, np.float64), kind)
    assert np.allclose(out32, full, rtol=1e-5, atol=1e-5)
    assert np.all(out32[phi.outside_mask] == 0)


def test_cut_guides_gives_edge_chains_and_quadwild_files(phi, source, target, tmp_path):
    uv, tri = source.uv, source.triangles
    centroid = uv[tri].mean(1)
    row = np.where(np.abs(centroid[:, 1]) < 0.05)[0]
    row = row[np.argsort(centroid[row, 0])].astype(np.uint32)
    guide = macrocon.Polyline(row, np.full((row.size, 3), 1 / 3))
    with phi.transfer_polylines([guide]) as lines, target.cut_guides(lines) as cut:
        info = cut.info
        assert isinstance(info, macrocon.CutMeshInfo)
        assert info.triangle_count > target.triangle_count and info.guide_edge_count > 5
        assert info.min_angle_created > 1.0
        assert "guide_edges=" in repr(cut)
        faces = cut.triangles
        edges = {tuple(sorted(e)) for f in faces for e in ((f[0], f[1]), (f[1], f[2]), (f[2], f[0]))}
        for chain in cut.guides:
            for a, b in zip(chain[:-1], chain[1:]):
                assert tuple(sorted((a, b))) in edges
        assert {tuple(e) for e in cut.guide_edges} <= edges
        # The host-unit x coordinate of the patch, carried, is the cut vertices' x.
        x = target.info.center[0] + target.info.radius * target.positions[:, 0]
        assert np.allclose(cut.carry_field(x), cut.positions[:, 0], atol=1e-9)
        assert cut.carry_field(np.stack([x, x], 1)).shape == (info.vertex_count, 2)
        tris, bary = cut.host_points()
        assert np.all(tris < target.triangle_count) and np.allclose(bary.sum(1), 1)
        assert cut.cross_field().shape == (info.triangle_count, 3)
        cut.write_quadwild(tmp_path / "nose")
        assert int((tmp_path / "nose.rosy").read_text().split()[0]) == info.triangle_count
        assert int((tmp_path / "nose.sharp").read_text().split()[0]) == info.guide_edge_count
        with pytest.raises(macrocon.InvalidArgumentError, match="snap_fraction"):
            target.cut_guides(lines, snap_fraction=0.6)
        # Fairing (on by default) moves chain vertices only; 0 passes turns it off.
        with target.cut_guides(lines, fair_passes=0) as raw:
            assert raw.info.faired_vertices == 0
            assert np.array_equal(raw.triangles, cut.triangles)
            assert info.faired_vertices > 0 and not np.array_equal(raw.positions, cut.positions)
        with pytest.raises(macrocon.InvalidArgumentError, match="fair_max_shift"):
            target.cut_guides(lines, fair_max_shift=0.9)
        with pytest.raises(ValueError, match="fair_passes"):
            target.cut_guides(lines, fair_passes=-1)
        with pytest.raises(macrocon.InvalidArgumentError, match="another patch"):
            source.cut_guides(lines)
        with pytest.raises(FileNotFoundError):
            cut.write_quadwild(tmp_path / "no such dir" / "x")


def test_mesh_cut_guides_covers_the_whole_host(context, host, phi, source, target, tmp_path):
    mesh, p, t = host
    uv, tri = source.uv, source.triangles
    centroid = uv[tri].mean(1)
    row = np.where(np.abs(centroid[:, 1]) < 0.05)[0]
    row = row[np.argsort(centroid[row, 0])].astype(np.uint32)
    guide = macrocon.Polyline(row, np.full((row.size, 3), 1 / 3))
    with phi.transfer_polylines([guide]) as lines, mesh.cut_guides([lines]) as cut:
        info = cut.info
        assert info.triangle_count > t.shape[0] and info.guide_edge_count > 5
        assert info.unplaced_points == 0 and info.split_guides == 0
        assert cut.guide_origins.tolist() == [[0, 0]]
        # Host points are mesh triangles; a mesh field (the y coordinate) is carried exactly.
        tris, bary = cut.host_points()
        assert np.all(tris < t.shape[0])
        assert np.allclose(cut.carry_field(p[:, 1]), cut.positions[:, 1], atol=1e-9)
        assert cut.cross_field().shape == (info.triangle_count, 3)
        cut.write_quadwild(tmp_path / "whole")
        assert int((tmp_path / "whole.rosy").read_text().split()[0]) == info.triangle_count
        with pytest.raises(macrocon.InvalidArgumentError, match="mesh vertices"):
            cut.carry_field(p[:-1, 1])
        with pytest.raises(TypeError, match=r"guide_sets\[0\]"):
            mesh.cut_guides([guide])
        # A mesh the patch was not cut from is refused by name.
        with macrocon.Mesh(context, p + [0.01, 0, 0], t) as other:
            with pytest.raises(macrocon.InvalidArgumentError, match="not cut from this mesh"):
                other.cut_guides([lines])
    with mesh.cut_guides([]) as plain:
        assert plain.info.triangle_count == t.shape[0] and plain.info.guide_count == 0

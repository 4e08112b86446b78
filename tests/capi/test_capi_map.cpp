// mcon_map_compute and its queries on two nose patches of the MakeHuman sample body; patches from
// arrays; thread-count independence; cancellation.
#include <atomic>
#include <cstddef>
#include <set>

#include "map_test_util.h"

using namespace map_test;

namespace {

struct Noses {
  ContextPtr ctx;
  MeshPtr mesh;
  PatchPtr source, target;
};

Noses noses(uint32_t max_threads = 0) {
  Noses n;
  n.ctx = make_context(max_threads);
  n.mesh = make_mesh(n.ctx.get(), body().arrays);
  n.source = extract(n.mesh.get(), 297, 0.45);
  n.target = extract(n.mesh.get(), 297, 0.55);
  return n;
}

// Triangles of phi whose orientation disagrees with the map's (reflected maps flip every one).
size_t wrongly_oriented(mcon_map map, mcon_patch source, bool reflected) {
  const PatchArrays s = arrays_of_patch(source);
  std::vector<double> phi(2 * s.nv());
  EXPECT_EQ(mcon_map_get_phi(map, phi.data(), phi.size()), MCON_OK);
  size_t wrong = 0;
  for (size_t f = 0; f < s.nt(); ++f) {
    const double* a = &phi[2 * s.tri[3 * f]];
    const double* b = &phi[2 * s.tri[3 * f + 1]];
    const double* c = &phi[2 * s.tri[3 * f + 2]];
    const double area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    wrong += (reflected ? -area : area) > 0 ? 0 : 1;
  }
  return wrong;
}

void expect_valid_map(mcon_map map, mcon_patch source, mcon_patch target) {
  const PatchArrays s = arrays_of_patch(source), t = arrays_of_patch(target);
  mcon_map_info info;
  ASSERT_EQ(mcon_map_info_init(&info), MCON_OK);
  ASSERT_EQ(mcon_map_get_info(map, &info), MCON_OK) << last_message();
  EXPECT_EQ(info.source_vertex_count, s.nv());
  EXPECT_EQ(info.target_vertex_count, t.nv());
  EXPECT_EQ(info.flipped_triangles, 0u);
  EXPECT_GT(info.overlap_ratio, 0.5);
  EXPECT_LE(info.overlap_ratio, 1.0 + 1e-9);
  EXPECT_GE(info.iterations, 1u);
  EXPECT_GE(info.levels, 1u);
  EXPECT_TRUE(info.stop_reason == MCON_MAP_STOP_CONVERGED || info.stop_reason == MCON_MAP_STOP_STALLED ||
              info.stop_reason == MCON_MAP_STOP_ITERATION_CAP);
  EXPECT_TRUE(std::isfinite(info.energy_total));
  EXPECT_GE(info.matching_score, 0.0);
  EXPECT_LE(info.matching_score, 1.0);
  EXPECT_GT(info.source_vertices_inside, s.nv() / 2);

  // Source -> target: target triangles with valid weights; counts agree with the info.
  std::vector<int32_t> tri(s.nv());
  std::vector<double> bary(3 * s.nv());
  ASSERT_EQ(mcon_map_get_correspondences(map, MCON_MAP_SOURCE_TO_TARGET, tri.data(), bary.data(), s.nv()), MCON_OK);
  size_t inside = 0;
  for (size_t v = 0; v < s.nv(); ++v) {
    if (tri[v] < 0) {
      EXPECT_EQ(bary[3 * v] + bary[3 * v + 1] + bary[3 * v + 2], 0.0);
      continue;
    }
    ++inside;
    EXPECT_LT(static_cast<size_t>(tri[v]), t.nt());
    EXPECT_NEAR(bary[3 * v] + bary[3 * v + 1] + bary[3 * v + 2], 1.0, 1e-9);
  }
  EXPECT_EQ(inside, info.source_vertices_inside);

  // Target -> source, and the outside mask is exactly the target vertices without a preimage.
  std::vector<int32_t> tri2(t.nv());
  ASSERT_EQ(mcon_map_get_correspondences(map, MCON_MAP_TARGET_TO_SOURCE, tri2.data(), nullptr, t.nv()), MCON_OK);
  std::vector<uint8_t> mask(t.nv(), 7);
  ASSERT_EQ(mcon_map_get_outside_mask(map, mask.data(), mask.size()), MCON_OK);
  size_t inside2 = 0;
  for (size_t w = 0; w < t.nv(); ++w) {
    EXPECT_LT(tri2[w], static_cast<int32_t>(s.nt()));
    EXPECT_EQ(mask[w], tri2[w] < 0 ? 1 : 0);
    inside2 += tri2[w] >= 0;
  }
  EXPECT_EQ(inside2, info.target_vertices_inside);
  EXPECT_GT(inside2, 0u);

  // phi: no inverted triangle (counted here again, in the map's orientation).
  EXPECT_EQ(wrongly_oriented(map, source, info.reflected != 0), 0u);
}

}  // namespace

TEST(CapiMap, NoseOntoNoseIsLocallyInjectiveInBothDirections) {
  Noses n = noses();
  const mcon_map_options o = fast_options();
  const MapPtr forward = compute(n.source.get(), n.target.get(), o);
  ASSERT_TRUE(forward);
  expect_valid_map(forward.get(), n.source.get(), n.target.get());
  const MapPtr backward = compute(n.target.get(), n.source.get(), o);
  ASSERT_TRUE(backward);
  expect_valid_map(backward.get(), n.target.get(), n.source.get());
  mcon_map_info info;
  mcon_map_info_init(&info);
  ASSERT_EQ(mcon_map_get_info(forward.get(), &info), MCON_OK);
  EXPECT_EQ(info.reflected, 0u);  // a nose onto the same nose keeps its orientation
}

TEST(CapiMap, ForcedOrientationsAreObeyedAndReportTheirEvidence) {
  // The nose is nearly mirror-symmetric: the "flip" workflow forces either orientation. Both must
  // come back locally injective in their own orientation, with both rigid scores reported.
  Noses n = noses();
  mcon_map_info automatic;
  {
    const MapPtr map = compute(n.source.get(), n.target.get(), fast_options());
    ASSERT_TRUE(map);
    ASSERT_EQ(mcon_map_info_init(&automatic), MCON_OK);
    ASSERT_EQ(mcon_map_get_info(map.get(), &automatic), MCON_OK);
    EXPECT_GE(automatic.alignment_score_unreflected, 0.0);
    EXPECT_GE(automatic.alignment_score_reflected, 0.0);  // allow_reflection is on by default
    EXPECT_EQ(automatic.alignment_score,
              automatic.reflected ? automatic.alignment_score_reflected : automatic.alignment_score_unreflected);
    if (automatic.orientation_compared) {
      EXPECT_GT(automatic.level0_energy_unreflected, 0.0);
      EXPECT_GT(automatic.level0_energy_reflected, 0.0);
    } else {
      EXPECT_EQ(automatic.level0_energy_unreflected, -1.0);
      EXPECT_EQ(automatic.level0_energy_reflected, -1.0);
    }
  }
  for (uint32_t orientation : {static_cast<uint32_t>(MCON_MAP_ORIENTATION_PRESERVE),
                               static_cast<uint32_t>(MCON_MAP_ORIENTATION_REVERSE)}) {
    SCOPED_TRACE(orientation);
    mcon_map_options o = fast_options();
    o.orientation = orientation;
    const MapPtr map = compute(n.source.get(), n.target.get(), o);
    ASSERT_TRUE(map);
    mcon_map_info info;
    ASSERT_EQ(mcon_map_info_init(&info), MCON_OK);
    ASSERT_EQ(mcon_map_get_info(map.get(), &info), MCON_OK);
    const bool reverse = orientation == MCON_MAP_ORIENTATION_REVERSE;
    EXPECT_EQ(info.reflected, reverse ? 1u : 0u);
    EXPECT_EQ(info.flipped_triangles, 0u);
    EXPECT_EQ(wrongly_oriented(map.get(), n.source.get(), reverse), 0u);
    // Forced: no comparison, and the start is that orientation's best rigid candidate.
    EXPECT_EQ(info.orientation_compared, 0u);
    EXPECT_EQ(info.level0_energy_unreflected, -1.0);
    EXPECT_EQ(info.level0_energy_reflected, -1.0);
    EXPECT_EQ(info.alignment_score, reverse ? info.alignment_score_reflected : info.alignment_score_unreflected);
    // Both orientations' rigid candidates are scored whatever is forced, with the same seed: the
    // scores are those of the automatic run.
    EXPECT_EQ(info.alignment_score_unreflected, automatic.alignment_score_unreflected);
    EXPECT_EQ(info.alignment_score_reflected, automatic.alignment_score_reflected);
    EXPECT_GT(info.source_vertices_inside, 0u);
  }
  // Reverse with automatic reflections switched off is still an explicit request, obeyed.
  mcon_map_options o = fast_options();
  o.orientation = MCON_MAP_ORIENTATION_REVERSE;
  o.allow_reflection = 0;
  const MapPtr map = compute(n.source.get(), n.target.get(), o);
  ASSERT_TRUE(map);
  mcon_map_info info;
  ASSERT_EQ(mcon_map_info_init(&info), MCON_OK);
  ASSERT_EQ(mcon_map_get_info(map.get(), &info), MCON_OK);
  EXPECT_EQ(info.reflected, 1u);
  EXPECT_EQ(info.flipped_triangles, 0u);
}

TEST(CapiMap, TheMapKeepsItsPatchesAlive) {
  Noses n = noses();
  const MapPtr map = compute(n.source.get(), n.target.get(), fast_options());
  ASSERT_TRUE(map);
  const size_t ns = arrays_of_patch(n.source.get()).nv(), nt = arrays_of_patch(n.target.get()).nv();
  n.source.reset();
  n.target.reset();
  n.mesh.reset();
  n.ctx.reset();
  // Everything but the map is released: its queries and transfers still work.
  std::vector<uint8_t> mask(nt);
  ASSERT_EQ(mcon_map_get_outside_mask(map.get(), mask.data(), mask.size()), MCON_OK) << last_message();
  const std::vector<double> ones(ns, 2.0);
  std::vector<double> out(nt, -1);
  ASSERT_EQ(mcon_map_transfer_field(map.get(), MCON_FIELD_SCALAR, 1, ones.data(), ones.size(), out.data(), out.size()),
            MCON_OK)
      << last_message();
  for (size_t w = 0; w < nt; ++w) EXPECT_NEAR(out[w], mask[w] ? 0.0 : 2.0, 1e-12);
  EXPECT_EQ(mcon_map_retain(map.get()), MCON_OK);
  EXPECT_EQ(mcon_map_release(map.get()), MCON_OK);
}

// Over-releasing a patch a map holds used to return MCON_OK and free it under the map.
TEST(CapiMap, OverReleasingAPatchTheMapHoldsIsAnError) {
  Noses n = noses();
  const MapPtr map = compute(n.source.get(), n.target.get(), fast_options());
  ASSERT_TRUE(map);
  mcon_patch source = n.source.release();
  const size_t ns = arrays_of_patch(source).nv();
  ASSERT_EQ(mcon_patch_release(source), MCON_OK);
  EXPECT_EQ(mcon_patch_release(source), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(mcon_patch_release(source), MCON_ERROR_INVALID_ARGUMENT);
  std::vector<int32_t> tri(ns);
  std::vector<double> bary(3 * ns);
  EXPECT_EQ(mcon_map_get_correspondences(map.get(), MCON_MAP_SOURCE_TO_TARGET, tri.data(), bary.data(), ns),
            MCON_OK)
      << last_message();
}

TEST(CapiMap, ResultsAreIdenticalForOneAndTwoThreads) {
  std::vector<double> phi[2];
  std::vector<int32_t> tri[2];
  std::vector<double> bary[2];
  for (int i = 0; i < 2; ++i) {
    Noses n = noses(static_cast<uint32_t>(i + 1));
    const MapPtr map = compute(n.source.get(), n.target.get(), fast_options());
    ASSERT_TRUE(map);
    mcon_map_info info;
    mcon_map_info_init(&info);
    ASSERT_EQ(mcon_map_get_info(map.get(), &info), MCON_OK);
    phi[i].resize(2 * info.source_vertex_count);
    ASSERT_EQ(mcon_map_get_phi(map.get(), phi[i].data(), phi[i].size()), MCON_OK);
    tri[i].resize(info.target_vertex_count);
    bary[i].resize(3 * info.target_vertex_count);
    ASSERT_EQ(mcon_map_get_correspondences(map.get(), MCON_MAP_TARGET_TO_SOURCE, tri[i].data(), bary[i].data(),
                                           tri[i].size()),
              MCON_OK);
  }
  EXPECT_EQ(phi[0], phi[1]);  // bit-identical, not merely close
  EXPECT_EQ(tri[0], tri[1]);
  EXPECT_EQ(bary[0], bary[1]);
}

namespace {
struct CancelAfter {
  std::atomic<int> calls{0};
  int allow = 0;
  double last = -1;
  static int32_t call(void* user, double fraction) {
    auto* self = static_cast<CancelAfter*>(user);
    EXPECT_GE(fraction, self->last);  // never backwards
    EXPECT_LE(fraction, 1.0);
    self->last = fraction;
    return ++self->calls > self->allow ? 0 : 1;
  }
};
}  // namespace

TEST(CapiMap, ProgressReportsAndCancellationLeavesNothing) {
  Noses n = noses();
  for (int allow : {0, 3}) {
    CancelAfter cancel;
    cancel.allow = allow;
    mcon_map_options o = fast_options();
    o.progress = &CancelAfter::call;
    o.progress_user_data = &cancel;
    mcon_map map = reinterpret_cast<mcon_map>(&o);  // must become NULL
    EXPECT_EQ(mcon_map_compute(n.source.get(), n.target.get(), &o, &map), MCON_ERROR_CANCELLED) << allow;
    EXPECT_EQ(map, nullptr);
    EXPECT_EQ(cancel.calls.load(), allow + 1);  // no call after the cancel
    EXPECT_NE(last_message().find("cancel"), std::string::npos) << last_message();
  }
  // A callback that lets it finish sees the end.
  CancelAfter all;
  all.allow = 1 << 30;
  mcon_map_options o = fast_options();
  o.progress = &CancelAfter::call;
  o.progress_user_data = &all;
  const MapPtr map = compute(n.source.get(), n.target.get(), o);
  ASSERT_TRUE(map);
  EXPECT_GT(all.calls.load(), 2);
  EXPECT_EQ(all.last, 1.0);
  // The patches are still valid after the cancelled calls.
  expect_valid_map(map.get(), n.source.get(), n.target.get());
}

TEST(CapiMap, PatchFromArraysIsADiskAndMapsLikeALibraryEntry) {
  Noses n = noses();
  const PatchArrays s = arrays_of_patch(n.source.get());
  const Arrays entry_arrays{s.xyz, s.tri};
  const mcon_mesh_desc d = desc_of(entry_arrays);
  mcon_patch_frame f;
  ASSERT_EQ(mcon_patch_frame_init(&f), MCON_OK);
  EXPECT_EQ(f.center_triangle, MCON_INVALID_INDEX);
  EXPECT_EQ(f.scale, 1.0);
  f.center_triangle = s.info.center_patch_triangle;
  for (int k = 0; k < 3; ++k) {
    f.center_barycentric[k] = s.info.center_barycentric[k];
    f.origin[k] = s.info.center[k];
  }
  f.scale = s.info.radius;
  mcon_patch p = nullptr;
  ASSERT_EQ(mcon_patch_create_from_arrays(n.ctx.get(), &d, &f, &p), MCON_OK) << last_message();
  const PatchPtr entry(p);
  const PatchArrays e = arrays_of_patch(entry.get());
  EXPECT_EQ(e.xyz, s.xyz);  // copied as given: already normalized
  EXPECT_EQ(e.tri, s.tri);
  EXPECT_EQ(e.info.boundary_loops, 1u);
  EXPECT_EQ(e.info.euler_characteristic, 1);
  EXPECT_EQ(e.info.param_flipped_triangles, 0u);
  EXPECT_EQ(e.info.filled_triangle_count, 0u);
  EXPECT_EQ(e.info.radius, s.info.radius);
  EXPECT_NEAR(e.info.max_geodesic_distance, s.info.max_geodesic_distance, 1e-9);
  for (int k = 0; k < 3; ++k) EXPECT_EQ(e.info.center[k], s.info.center[k]);
  for (size_t v = 0; v < e.nv(); ++v) {
    const double r = std::hypot(e.uv[2 * v], e.uv[2 * v + 1]);
    EXPECT_LE(r, 1.0 + 1e-9);
  }
  // Host links are the identity.
  std::vector<uint32_t> v0(e.nv()), v1(e.nv()), ht(e.nt());
  std::vector<double> t(e.nv());
  ASSERT_EQ(mcon_patch_get_host_vertices(entry.get(), v0.data(), v1.data(), t.data(), e.nv()), MCON_OK);
  ASSERT_EQ(mcon_patch_get_host_triangles(entry.get(), ht.data(), ht.size()), MCON_OK);
  for (size_t v = 0; v < e.nv(); ++v) {
    EXPECT_EQ(v0[v], v);
    EXPECT_EQ(v1[v], v);
    EXPECT_EQ(t[v], 0.0);
  }
  for (size_t k = 0; k < e.nt(); ++k) EXPECT_EQ(ht[k], k);
  // The entry maps onto the extracted target like the patch it was made from.
  const MapPtr map = compute(entry.get(), n.target.get(), fast_options());
  ASSERT_TRUE(map);
  expect_valid_map(map.get(), entry.get(), n.target.get());
}

// Coarse to fine in mesh resolution (mcon_map_options.coarse_stages / coarse_vertices): the
// defaults, what the info reports, the switch to turn it off, the range checks and an older
// struct without the fields.
TEST(CapiMap, CoarseStagesAreReportedCanBeTurnedOffAndAreChecked) {
  Noses n = noses();
  mcon_map_options o = fast_options();
  EXPECT_EQ(o.coarse_stages, 3u);
  EXPECT_EQ(o.coarse_vertices, 1000u);
  mcon_patch_info pi;
  mcon_patch_info_init(&pi);
  ASSERT_EQ(mcon_patch_get_info(n.source.get(), &pi), MCON_OK);
  ASSERT_GE(pi.vertex_count, 400u);  // the test needs a source of >= 2 * 200 vertices
  auto info_of = [&](const mcon_map_options& options) {
    const MapPtr m = compute(n.source.get(), n.target.get(), options);
    mcon_map_info info;
    mcon_map_info_init(&info);
    EXPECT_EQ(mcon_map_get_info(m.get(), &info), MCON_OK);
    EXPECT_EQ(info.flipped_triangles, 0u);
    return info;
  };
  o.coarse_vertices = 200;
  const mcon_map_info coarse = info_of(o);
  EXPECT_GE(coarse.coarse_stages, 1u);  // 3, or fewer where a later stage's folds could not be untangled
  EXPECT_GE(coarse.coarse_vertices, 200u);
  EXPECT_LE(coarse.coarse_vertices, 0.6 * static_cast<double>(pi.vertex_count));
  EXPECT_EQ(coarse.coarse_fallback, 0u);
  o.coarse_stages = 0;
  const mcon_map_info full = info_of(o);
  EXPECT_EQ(full.coarse_vertices, 0u);
  EXPECT_EQ(full.coarse_stages, 0u);
  mcon_map m = nullptr;
  o.coarse_stages = 9;
  EXPECT_EQ(mcon_map_compute(n.source.get(), n.target.get(), &o, &m), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_message().find("coarse_stages must be in [0, 8]"), std::string::npos) << last_message();
  o.coarse_stages = 2;
  o.coarse_vertices = 99;
  EXPECT_EQ(mcon_map_compute(n.source.get(), n.target.get(), &o, &m), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(m, nullptr);
  mcon_map_options older = fast_options();
  older.struct_size = static_cast<uint32_t>(offsetof(mcon_map_options, coarse_stages));
  older.coarse_stages = 77;  // beyond the older struct: not read
  const MapPtr old_map = compute(n.source.get(), n.target.get(), older);
  EXPECT_TRUE(old_map);
}

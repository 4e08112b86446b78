// The C++ wrapper of the map section (macrocon.hpp): Map, PolylineSet, patch_from_arrays,
// compute_cross_field, write_rosy; errors become macrocon::Error with the C status.
#include <array>
#include <cstdio>
#include <set>
#include <stdexcept>
#include <utility>

#include "io/mesh_io.h"
#include "macrocon/macrocon.hpp"
#include "map_test_util.h"

namespace {

macrocon::Patch nose(const macrocon::Mesh& body, double radius) {
  return macrocon::Patch::extract(body, macrocon::PatchOptions::at_vertex(
                                            static_cast<uint32_t>(map_test::body().file_to_mesh[297]), radius));
}

// The bundled body's nose cut at two radii (source 0.45, target 0.55), in a context of its own.
struct NosePair {
  macrocon::Context ctx;
  macrocon::Mesh body =
      macrocon::Mesh::from_arrays(ctx, map_test::body().arrays.positions, map_test::body().arrays.indices);
  macrocon::Patch source = nose(body, 0.45), target = nose(body, 0.55);
};

// The C status of the macrocon::Error a wrapper call throws, or MCON_OK if it throws none.
template <typename F>
mcon_status status_of(F&& f) {
  try {
    std::forward<F>(f)();
  } catch (const macrocon::Error& e) {
    return e.status();
  }
  return MCON_OK;
}

macrocon::MapOptions fast() {
  macrocon::MapOptions o;
  o.alignment_samples = 200;
  o.max_iterations = 30;
  o.seed = 3;
  return o;
}

}  // namespace

TEST(CppMap, ComputeTransferAndCrossField) {
  const NosePair pair;
  const auto& [ctx, body, source, target] = pair;
  const macrocon::Map map = macrocon::Map::compute(source, target, fast());
  const mcon_map_info info = map.info();
  EXPECT_EQ(info.flipped_triangles, 0u);
  EXPECT_EQ(info.source_vertex_count, source.vertex_count());
  EXPECT_EQ(map.phi().size(), 2 * source.vertex_count());
  const auto terms = map.energy_terms();
  ASSERT_GE(terms.size(), 4u);
  EXPECT_EQ(terms[0], std::make_pair(std::string("descriptor"), info.energy_descriptor));
  EXPECT_EQ(terms[1], std::make_pair(std::string("distortion"), info.energy_distortion));
  EXPECT_EQ(terms[2], std::make_pair(std::string("area"), info.energy_area));
  EXPECT_EQ(terms[3], std::make_pair(std::string("injectivity"), info.energy_injectivity));
  const auto mask = map.outside_mask();
  const auto corr = map.correspondences(MCON_MAP_TARGET_TO_SOURCE);
  ASSERT_EQ(corr.first.size(), target.vertex_count());
  for (size_t w = 0; w < mask.size(); ++w) EXPECT_EQ(mask[w], corr.first[w] < 0 ? 1 : 0);

  const std::vector<double> ones(source.vertex_count(), 1.0);
  const std::vector<double> f = map.transfer_field(MCON_FIELD_SCALAR, 1, ones);
  for (size_t w = 0; w < f.size(); ++w) EXPECT_NEAR(f[w], mask[w] ? 0.0 : 1.0, 1e-12);
  // float values: the double transfer rounded once.
  const std::vector<float> f32 = map.transfer_field(MCON_FIELD_SCALAR, 1, std::vector<float>(source.vertex_count(), 1.0f));
  ASSERT_EQ(f32.size(), f.size());
  for (size_t w = 0; w < f.size(); ++w) EXPECT_EQ(f32[w], static_cast<float>(f[w]));
  const std::vector<int32_t> labels(source.vertex_count(), 5);
  const std::vector<int32_t> l = map.transfer_labels(1, labels, -2);
  for (size_t w = 0; w < l.size(); ++w) EXPECT_EQ(l[w], mask[w] ? -2 : 5);

  const mcon_patch_info si = source.info();
  const macrocon::SurfacePoints p =
      map.transfer_points({si.center_patch_triangle},
                          {si.center_barycentric[0], si.center_barycentric[1], si.center_barycentric[2]});
  ASSERT_EQ(p.size(), 1u);
  EXPECT_NE(p.triangles[0], MCON_INVALID_INDEX);

  // A polyline from the center outwards along a few source triangles' centroids.
  const std::vector<uint32_t> tri = {si.center_patch_triangle, 10, 20};
  const std::vector<double> bary = {si.center_barycentric[0], si.center_barycentric[1], si.center_barycentric[2],
                                    1.0 / 3, 1.0 / 3, 1.0 / 3, 1.0 / 3, 1.0 / 3, 1.0 / 3};
  const macrocon::PolylineSet set = map.transfer_polylines(tri, bary, {3});
  ASSERT_GE(set.polyline_count(), 1u);
  EXPECT_EQ(set.input_polylines()[0], 0u);
  EXPECT_EQ(set.points().size(), set.point_count());
  const macrocon::CrossField field = macrocon::compute_cross_field(target, set);
  EXPECT_EQ(field.directions.size(), 3 * target.triangle_count());
  const std::string path = std::string(MACROCON_BINARY_DIR) + "/cpp_map_wrapper.rosy";
  macrocon::write_rosy(target, field.directions, path);
  EXPECT_EQ(mcon::io::read_rosy(path).size(), target.triangle_count());
  std::remove(path.c_str());

  // Guides of another patch are refused with the C status.
  EXPECT_EQ(status_of([&] { (void)macrocon::compute_cross_field(source, set); }), MCON_ERROR_INVALID_ARGUMENT);

  // The guides cut into the target: chains of its edges, a field per triangle, the same counts.
  const macrocon::CutMesh cut = macrocon::CutMesh::cut(target, set);
  const mcon_cut_mesh_info ci = cut.info();
  EXPECT_GE(ci.triangle_count, target.triangle_count());
  EXPECT_EQ(cut.positions().size(), 3 * ci.vertex_count);
  EXPECT_EQ(cut.cross_field().size(), 3 * ci.triangle_count);
  EXPECT_EQ(cut.guide_edges().size(), 2 * ci.guide_edge_count);
  const std::vector<std::uint32_t> faces = cut.triangles();
  std::set<std::pair<std::uint32_t, std::uint32_t>> edges;
  for (size_t t = 0; t < faces.size(); t += 3)
    for (int k = 0; k < 3; ++k) edges.insert(std::minmax(faces[t + k], faces[t + (k + 1) % 3]));
  size_t steps = 0;
  for (const auto& chain : cut.guides())
    for (size_t k = 0; k + 1 < chain.size(); ++k, ++steps) EXPECT_TRUE(edges.count(std::minmax(chain[k], chain[k + 1])));
  EXPECT_GT(steps, 0u);
  EXPECT_EQ(cut.carry_field(std::vector<double>(target.vertex_count(), 2.0), 1),
            std::vector<double>(ci.vertex_count, 2.0));
  // Every cut vertex lies on a target triangle: convex weights that reproduce its position.
  const auto [host_triangles, host_weights] = cut.host_points();
  ASSERT_EQ(host_triangles.size(), ci.vertex_count);
  ASSERT_EQ(host_weights.size(), 3 * ci.vertex_count);
  const std::vector<double> patch_xyz = target.positions(), cut_xyz = cut.positions();
  const std::vector<std::uint32_t> patch_faces = target.triangles();
  const mcon_patch_info ti = target.info();
  for (size_t v = 0; v < ci.vertex_count; ++v) {
    ASSERT_LT(host_triangles[v], target.triangle_count());
    EXPECT_NEAR(host_weights[3 * v] + host_weights[3 * v + 1] + host_weights[3 * v + 2], 1.0, 1e-12);
    for (int d = 0; d < 3; ++d) {
      double at = 0;
      for (int k = 0; k < 3; ++k) at += host_weights[3 * v + k] * patch_xyz[3 * patch_faces[3 * host_triangles[v] + k] + d];
      // A snapped vertex moves onto its guide, at most a fraction of an edge from its host point.
      EXPECT_NEAR(ti.center[d] + ti.radius * at, cut_xyz[3 * v + d], 0.05 * ti.radius) << "cut vertex " << v;
    }
  }
  // No guides: the patch comes back uncut and the empty getters return empty arrays.
  const macrocon::PolylineSet none = map.transfer_polylines({}, {}, {});
  const macrocon::CutMesh uncut = macrocon::CutMesh::cut(target, none);
  EXPECT_EQ(uncut.info().triangle_count, target.triangle_count());
  EXPECT_TRUE(uncut.guide_edges().empty());
  EXPECT_TRUE(uncut.guides().empty());
  EXPECT_EQ(status_of([&] { (void)macrocon::CutMesh::cut(target, set, 0.9); }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(status_of([&] { (void)macrocon::CutMesh::cut(source, set); }), MCON_ERROR_INVALID_ARGUMENT);

  // The same guides cut into the whole body: every host face, chains from set 0.
  const macrocon::CutMesh whole = macrocon::CutMesh::cut_whole_host(body, {set});
  const mcon_cut_mesh_info wi = whole.info();
  EXPECT_GT(wi.triangle_count, body.triangle_count());
  EXPECT_GT(wi.guide_edge_count, 0u);
  for (const auto& origin : whole.guide_origins()) EXPECT_EQ(origin[0], 0u);
  EXPECT_EQ(whole.guide_origins().size(), wi.guide_count);
  const std::vector<double> carried = whole.carry_field(std::vector<double>(body.vertex_count(), 3.0), 1);
  ASSERT_EQ(carried.size(), wi.vertex_count);
  for (double c : carried) ASSERT_NEAR(c, 3.0, 1e-12);
}

TEST(CppMap, ProgressExceptionsAndCancellation) {
  const NosePair pair;
  const auto& [ctx, body, source, target] = pair;
  macrocon::MapOptions o = fast();
  o.progress = [](double) -> bool { throw std::logic_error("from the callback"); };
  EXPECT_THROW(macrocon::Map::compute(source, target, o), std::logic_error);
  o.progress = [](double) { return false; };
  EXPECT_EQ(status_of([&] { (void)macrocon::Map::compute(source, target, o); }), MCON_ERROR_CANCELLED);
  // Not a disk: a closed sphere.
  const map_test::Arrays sphere = capi_test::arrays_of(mcon::test_meshes::make_icosphere(1));
  EXPECT_EQ(status_of([&] { (void)macrocon::patch_from_arrays(ctx, sphere.positions, sphere.indices, 0); }),
            MCON_ERROR_NOT_A_DISK);
  // A patch from its own arrays works and maps.
  const mcon_patch_info si = source.info();
  const macrocon::Patch entry = macrocon::patch_from_arrays(
      ctx, source.positions(), source.triangles(), si.center_patch_triangle,
      {si.center_barycentric[0], si.center_barycentric[1], si.center_barycentric[2]},
      {si.center[0], si.center[1], si.center[2]}, si.radius);
  EXPECT_EQ(entry.info().boundary_loops, 1u);
  EXPECT_EQ(macrocon::Map::compute(entry, target, fast()).info().flipped_triangles, 0u);
}

TEST(CppMap, OrientationOptionReachesTheCApi) {
  // The flip workflow through the wrapper: force the orientation opposite to the automatic call.
  const NosePair pair;
  const auto& [ctx, body, source, target] = pair;
  macrocon::MapOptions o = fast();
  EXPECT_EQ(o.orientation, MCON_MAP_ORIENTATION_AUTOMATIC);
  const mcon_map_info automatic = macrocon::Map::compute(source, target, o).info();
  o.orientation = automatic.reflected ? MCON_MAP_ORIENTATION_PRESERVE : MCON_MAP_ORIENTATION_REVERSE;
  const mcon_map_info flipped = macrocon::Map::compute(source, target, o).info();
  EXPECT_NE(flipped.reflected, automatic.reflected);
  EXPECT_EQ(flipped.flipped_triangles, 0u);
  EXPECT_EQ(flipped.orientation_compared, 0u);
  EXPECT_EQ(flipped.alignment_score_unreflected, automatic.alignment_score_unreflected);
  EXPECT_EQ(flipped.alignment_score_reflected, automatic.alignment_score_reflected);
  o.orientation = static_cast<mcon_map_orientation>(3);  // in the enum's value range, not a member
  EXPECT_EQ(status_of([&] { (void)macrocon::Map::compute(source, target, o); }), MCON_ERROR_INVALID_ARGUMENT)
      << "an invalid orientation was accepted";
}

TEST(CppMap, UpHintsReachTheCApi) {
  const NosePair pair;
  const auto& [ctx, body, source, target] = pair;
  macrocon::MapOptions o = fast();
  o.source_up = std::array<double, 3>{{0, 1, 0}};
  EXPECT_EQ(status_of([&] { (void)macrocon::Map::compute(source, target, o); }), MCON_ERROR_INVALID_ARGUMENT)
      << "a source up without a target up was accepted";
  o.target_up = std::array<double, 3>{{0, 1, 0}};
  const macrocon::Map upright = macrocon::Map::compute(source, target, o);
  EXPECT_EQ(upright.info().flipped_triangles, 0u);
  // The C call with the same hints gives the same map (the wrapper adds nothing of its own).
  mcon_map_options c;
  ASSERT_EQ(mcon_map_options_init(&c), MCON_OK);
  c.alignment_samples = 200;
  c.max_iterations = 30;
  c.seed = 3;
  c.use_up_hints = 1;
  c.source_up[1] = c.target_up[1] = 1;
  mcon_map direct = nullptr;
  ASSERT_EQ(mcon_map_compute(source.get(), target.get(), &c, &direct), MCON_OK);
  const macrocon::Map same = macrocon::Map::adopt(direct);
  EXPECT_EQ(same.phi(), upright.phi());
  o.target_up = std::array<double, 3>{{0, 0, 0}};  // refused by the C API, by name
  EXPECT_EQ(status_of([&] { (void)macrocon::Map::compute(source, target, o); }), MCON_ERROR_INVALID_ARGUMENT);
}

TEST(CppMap, RefineSigmaFactorReachesTheCApi) {
  const NosePair pair;
  const auto& [ctx, body, source, target] = pair;
  macrocon::MapOptions o = fast();
  // The wrapper restates no default: unset members keep mcon_map_options_init's (0.5 here).
  EXPECT_FALSE(o.refine_sigma_factor.has_value());
  mcon_map_options c;
  ASSERT_EQ(mcon_map_options_init(&c), MCON_OK);
  EXPECT_EQ(c.refine_sigma_factor, 0.5);
  EXPECT_EQ(macrocon::Map::compute(source, target, o).info().levels, 4u);
  o.refine_sigma_factor = 0;
  EXPECT_EQ(macrocon::Map::compute(source, target, o).info().levels, 3u);
  o.refine_sigma_factor = 2;
  EXPECT_EQ(status_of([&] { (void)macrocon::Map::compute(source, target, o); }), MCON_ERROR_INVALID_ARGUMENT)
      << "refine_sigma_factor 2 was accepted";
}

TEST(CppMap, GuidanceChannelsDecideWhatTheGeometryCannot) {
  // A flat disk onto itself: every geometric channel is radially symmetric, so any rotation fits.
  // Guidance that pairs source point p with target point R p must make the map that rotation.
  const macrocon::Context ctx;
  const map_test::Arrays a = map_test::arrays_of(mcon::test_meshes::make_disk(10));
  const macrocon::Patch disk = macrocon::patch_from_arrays(ctx, a.positions, a.indices, 0, {{1, 0, 0}});
  const std::vector<double> xyz = disk.positions();
  const std::size_t n = xyz.size() / 3;
  const double angle = 2.0, c = std::cos(angle), s = std::sin(angle);
  macrocon::MapOptions o = fast();
  o.max_iterations = 100;
  o.guidance_dimension = 2;
  o.guidance_weight = 3;
  for (std::size_t v = 0; v < n; ++v) {
    const double x = xyz[3 * v], y = xyz[3 * v + 1];
    o.source_guidance.insert(o.source_guidance.end(), {x, y});
    o.target_guidance.insert(o.target_guidance.end(), {c * x + s * y, -s * x + c * y});  // R^-1 p
  }
  const macrocon::Map map = macrocon::Map::compute(disk, disk, o);
  EXPECT_EQ(map.info().reflected, 0u);
  const auto [tri, bary] = map.correspondences(MCON_MAP_SOURCE_TO_TARGET);
  double err = 0;
  std::size_t inside = 0;
  for (std::size_t v = 0; v < n; ++v) {
    if (tri[v] < 0) continue;
    double q[2] = {0, 0};
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t w = a.indices[3 * static_cast<std::size_t>(tri[v]) + k];
      q[0] += bary[3 * v + k] * xyz[3 * w];
      q[1] += bary[3 * v + k] * xyz[3 * w + 1];
    }
    const double x = xyz[3 * v], y = xyz[3 * v + 1];
    err += std::hypot(q[0] - (c * x - s * y), q[1] - (s * x + c * y));
    ++inside;
  }
  ASSERT_GT(inside, n * 3 / 4);  // the rim ring may land just outside
  EXPECT_LT(err / static_cast<double>(inside), 0.06);  // the plain map (no rotation) is at ~1.1

  o.target_guidance.pop_back();  // one value short
  EXPECT_EQ(status_of([&] { (void)macrocon::Map::compute(disk, disk, o); }), MCON_ERROR_INVALID_ARGUMENT)
      << "short guidance was accepted";
}

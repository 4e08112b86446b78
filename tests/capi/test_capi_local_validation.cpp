// MCON_MESH_VALIDATE_LOCALLY (issue 17): a production host with defects away from the region is
// accepted, a patch there is the same as on a clean host, and each operation reports the defects
// it reads, with their count.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "capi/capi_test_util.h"

using namespace capi_test;

namespace {

constexpr int kN = 21;  // 21 x 21 vertices on [0, 4]^2, spacing 0.2

int grid_vertex(int i, int j) { return j * kN + i; }
int grid_triangle(int i, int j) { return 2 * (j * (kN - 1) + i); }  // the first of quad (i, j)

// The grid lifted to a smooth asymmetric height field, so that patches have curvature to map.
mcon::TriMesh bumpy_grid() {
  mcon::TriMesh m = mcon::test_meshes::make_grid(kN, 4.0);
  for (auto& p : m.positions) p.z() = 0.15 * std::sin(1.5 * p.x() + 1.0) * std::cos(1.1 * p.y()) + 0.05 * p.x() * p.y();
  return m;
}

// The grid with, near the corner (20, 20) far from (3, 3): an isolated vertex, a zero-area
// triangle on a boundary edge, a duplicated triangle (three edges of three triangles each) and a
// second sheet glued at the corner vertex (a pinched vertex).
Arrays defective_host() {
  Arrays a = arrays_of(bumpy_grid());
  auto add_vertex = [&](double x, double y, double z) {
    a.positions.insert(a.positions.end(), {x, y, z});
    return static_cast<uint32_t>(a.vertex_count() - 1);
  };
  add_vertex(9, 9, 9);  // isolated
  const uint32_t p = static_cast<uint32_t>(grid_vertex(15, 20)), q = static_cast<uint32_t>(grid_vertex(16, 20));
  // The midpoint of edge (p, q): the triangle (q, p, mid) has zero area.
  const uint32_t mid = add_vertex(0.5 * (a.positions[3 * p] + a.positions[3 * q]),
                                  0.5 * (a.positions[3 * p + 1] + a.positions[3 * q + 1]),
                                  0.5 * (a.positions[3 * p + 2] + a.positions[3 * q + 2]));
  a.indices.insert(a.indices.end(), {q, p, mid});
  const int t = grid_triangle(17, 17);
  a.indices.insert(a.indices.end(), {a.indices[3 * t], a.indices[3 * t + 1], a.indices[3 * t + 2]});
  const uint32_t corner = static_cast<uint32_t>(grid_vertex(20, 20));
  const double zc = a.positions[3 * corner + 2];
  const uint32_t s = add_vertex(4.5, 4.0, zc + 0.5), u = add_vertex(4.0, 4.5, zc + 0.5);
  a.indices.insert(a.indices.end(), {corner, s, u});
  return a;
}

MeshPtr create(mcon_context ctx, const Arrays& a, uint32_t flags, mcon_status expected = MCON_OK) {
  mcon_mesh_desc d = desc_of(a);
  d.flags = flags;
  mcon_mesh m = nullptr;
  EXPECT_EQ(mcon_mesh_create(ctx, &d, &m), expected) << last_message();
  return MeshPtr(m);
}

mcon_status extract(mcon_mesh mesh, int vertex, double radius, PatchPtr& out) {
  mcon_patch_options o;
  EXPECT_EQ(mcon_patch_options_init(&o), MCON_OK);
  o.center_vertex = static_cast<uint32_t>(vertex);
  o.radius = radius;
  mcon_patch p = nullptr;
  const mcon_status s = mcon_patch_extract(mesh, &o, &p);
  out.reset(p);
  return s;
}

std::vector<double> positions_of(mcon_patch p) {
  mcon_patch_info info;
  EXPECT_EQ(mcon_patch_info_init(&info), MCON_OK);
  EXPECT_EQ(mcon_patch_get_info(p, &info), MCON_OK) << last_message();
  std::vector<double> xyz(3 * info.vertex_count);
  EXPECT_EQ(mcon_patch_get_positions(p, xyz.data(), xyz.size()), MCON_OK) << last_message();
  return xyz;
}

}  // namespace

TEST(CapiLocalValidation, DefectsAwayFromThePatchAreAcceptedAndChangeNothing) {
  ContextPtr ctx = make_context();
  const Arrays bad = defective_host();
  // Whole-mesh validation (the default) rejects the host.
  create(ctx.get(), bad, 0, MCON_ERROR_DEGENERATE_TRIANGLE);
  EXPECT_NE(last_message().find("has zero area"), std::string::npos) << last_message();

  const MeshPtr host = create(ctx.get(), bad, MCON_MESH_VALIDATE_LOCALLY);
  ASSERT_TRUE(host);
  const MeshPtr clean = create(ctx.get(), arrays_of(bumpy_grid()), 0);
  ASSERT_TRUE(clean);
  PatchPtr on_bad, on_clean;
  ASSERT_EQ(extract(host.get(), grid_vertex(4, 4), 0.5, on_bad), MCON_OK) << last_message();
  ASSERT_EQ(extract(clean.get(), grid_vertex(4, 4), 0.5, on_clean), MCON_OK) << last_message();
  EXPECT_EQ(positions_of(on_bad.get()), positions_of(on_clean.get()));

  // And the same map: each patch mapped onto a patch of another part of the clean host.
  PatchPtr target;
  ASSERT_EQ(extract(clean.get(), grid_vertex(6, 5), 0.55, target), MCON_OK) << last_message();
  std::vector<std::vector<double>> phi;
  for (mcon_patch source : {on_bad.get(), on_clean.get()}) {
    mcon_map map = nullptr;
    ASSERT_EQ(mcon_map_compute(source, target.get(), nullptr, &map), MCON_OK) << last_message();
    mcon_map_info info;
    ASSERT_EQ(mcon_map_info_init(&info), MCON_OK);
    ASSERT_EQ(mcon_map_get_info(map, &info), MCON_OK);
    EXPECT_EQ(info.flipped_triangles, 0u);
    std::vector<double> xy(2 * positions_of(source).size() / 3);
    EXPECT_EQ(mcon_map_get_phi(map, xy.data(), xy.size()), MCON_OK) << last_message();
    mcon_map_release(map);
    phi.push_back(xy);
  }
  EXPECT_EQ(phi[0], phi[1]);
  // Orientation does not cross the defects: the sheet glued at the corner keeps the grid's winding
  // (only the zero-area triangle, which ran its edge the grid's way, is reversed).
  mcon_mesh_orientation_info oi;
  ASSERT_EQ(mcon_mesh_orientation_info_init(&oi), MCON_OK);
  ASSERT_EQ(mcon_mesh_get_orientation(host.get(), &oi), MCON_OK);
  EXPECT_EQ(oi.reoriented_triangles, 1u);
  EXPECT_EQ(oi.outward_turned_component_count, 0u);
}

TEST(CapiLocalValidation, EachOperationReportsTheDefectsItReads) {
  ContextPtr ctx = make_context();
  const MeshPtr host = create(ctx.get(), defective_host(), MCON_MESH_VALIDATE_LOCALLY);
  ASSERT_TRUE(host);
  PatchPtr patch;
  // Near the duplicated triangle: its three edges, counted, and where the check looked.
  EXPECT_EQ(extract(host.get(), grid_vertex(18, 15), 0.3, patch), MCON_ERROR_NON_MANIFOLD_EDGE);
  EXPECT_NE(last_message().find("is used by 3 triangles"), std::string::npos) << last_message();
  EXPECT_NE(last_message().find("within 3 radii of the center"), std::string::npos) << last_message();
  EXPECT_NE(last_message().find("mcon_patch_extract"), std::string::npos) << last_message();
  // Near the zero-area triangle on the top boundary.
  EXPECT_EQ(extract(host.get(), grid_vertex(15, 19), 0.2, patch), MCON_ERROR_DEGENERATE_TRIANGLE);
  EXPECT_NE(last_message().find("has zero area"), std::string::npos) << last_message();
  // At the pinched corner, with the other defects out of reach.
  EXPECT_EQ(extract(host.get(), grid_vertex(20, 20), 0.15, patch), MCON_ERROR_NON_MANIFOLD_VERTEX);
  EXPECT_NE(last_message().find("vertex " + std::to_string(grid_vertex(20, 20))), std::string::npos)
      << last_message();

  // The whole-host cut reads every triangle: it reports them all.
  mcon_cut_mesh cut = nullptr;
  EXPECT_EQ(mcon_mesh_cut_guides(host.get(), nullptr, 0, nullptr, &cut), MCON_ERROR_DEGENERATE_TRIANGLE);
  EXPECT_EQ(cut, nullptr);
  EXPECT_NE(last_message().find("reads the whole mesh"), std::string::npos) << last_message();

  // An isolated vertex alone: harmless to a patch, refused by the whole-host cut.
  Arrays stray = arrays_of(bumpy_grid());
  stray.positions.insert(stray.positions.end(), {9.0, 9.0, 9.0});
  const MeshPtr lone = create(ctx.get(), stray, MCON_MESH_VALIDATE_LOCALLY);
  ASSERT_TRUE(lone);
  ASSERT_EQ(extract(lone.get(), grid_vertex(10, 10), 0.5, patch), MCON_OK) << last_message();
  EXPECT_EQ(mcon_mesh_cut_guides(lone.get(), nullptr, 0, nullptr, &cut), MCON_ERROR_ISOLATED_VERTEX);
  EXPECT_EQ(cut, nullptr);
  EXPECT_NE(last_message().find("vertex " + std::to_string(kN * kN) + " is not used by any triangle"), std::string::npos)
      << last_message();
}

TEST(CapiLocalValidation, UnknownFlagsAreRefused) {
  ContextPtr ctx = make_context();
  create(ctx.get(), arrays_of(mcon::test_meshes::make_grid(4)), 1u << 7, MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_message().find("MCON_MESH_VALIDATE_LOCALLY"), std::string::npos) << last_message();
}

// MCON_PATCH_REPAIR_REGION: each defect kind inside the region is repaired and reported.
namespace {

// The clean grid with, each far from the others: a zero-area cap on the bottom boundary edge at
// (5, 0)-(6, 0) (its third corner at the edge's midpoint), a zero-area triangle on the top boundary
// edge at (5, 20)-(6, 20) whose third corner duplicates (5, 20), and a sheet glued at the interior
// vertex (15, 10) (a pinched vertex).
Arrays repairable_host() {
  Arrays a = arrays_of(bumpy_grid());
  auto add_vertex = [&](const double* p) {
    a.positions.insert(a.positions.end(), {p[0], p[1], p[2]});
    return static_cast<uint32_t>(a.vertex_count() - 1);
  };
  auto at = [&](int i, int j) { return a.positions.data() + 3 * grid_vertex(i, j); };
  const uint32_t p = static_cast<uint32_t>(grid_vertex(5, 0)), q = static_cast<uint32_t>(grid_vertex(6, 0));
  const double mid_xyz[3] = {0.5 * (at(5, 0)[0] + at(6, 0)[0]), 0.5 * (at(5, 0)[1] + at(6, 0)[1]),
                             0.5 * (at(5, 0)[2] + at(6, 0)[2])};
  const uint32_t mid = add_vertex(mid_xyz);
  a.indices.insert(a.indices.end(), {q, p, mid});
  const uint32_t r = static_cast<uint32_t>(grid_vertex(5, 20)), s = static_cast<uint32_t>(grid_vertex(6, 20));
  const uint32_t twin = add_vertex(at(5, 20));
  a.indices.insert(a.indices.end(), {s, r, twin});
  const uint32_t pin = static_cast<uint32_t>(grid_vertex(15, 10));
  const double u_xyz[3] = {at(15, 10)[0] + 0.3, at(15, 10)[1], at(15, 10)[2] + 0.6};
  const double w_xyz[3] = {at(15, 10)[0], at(15, 10)[1] + 0.3, at(15, 10)[2] + 0.6};
  const uint32_t u = add_vertex(u_xyz), w = add_vertex(w_xyz);
  a.indices.insert(a.indices.end(), {pin, u, w});
  return a;
}

mcon_status extract_repaired(mcon_mesh mesh, int vertex, double radius, PatchPtr& out, mcon_patch_repair_info& info) {
  mcon_patch_options o;
  EXPECT_EQ(mcon_patch_options_init(&o), MCON_OK);
  o.center_vertex = static_cast<uint32_t>(vertex);
  o.radius = radius;
  o.flags |= MCON_PATCH_REPAIR_REGION;
  mcon_patch p = nullptr;
  const mcon_status s = mcon_patch_extract(mesh, &o, &p);
  out.reset(p);
  EXPECT_EQ(mcon_patch_repair_info_init(&info), MCON_OK);
  if (s == MCON_OK) {
    EXPECT_EQ(mcon_patch_get_repairs(p, &info), MCON_OK) << last_message();
  }
  return s;
}

}  // namespace

TEST(CapiLocalValidation, RepairRemovesZeroAreaTrianglesAndSplitsPinchedVertices) {
  ContextPtr ctx = make_context();
  const MeshPtr host = create(ctx.get(), repairable_host(), MCON_MESH_VALIDATE_LOCALLY);
  ASSERT_TRUE(host);
  const MeshPtr clean = create(ctx.get(), arrays_of(bumpy_grid()), 0);
  PatchPtr patch, reference;
  mcon_patch_repair_info info;

  // The cap: refused without the repair (which the message offers), removed with it, and the
  // triangle across its long edge split at its corner.
  EXPECT_EQ(extract(host.get(), grid_vertex(5, 1), 0.5, patch), MCON_ERROR_DEGENERATE_TRIANGLE);
  EXPECT_NE(last_message().find("MCON_PATCH_REPAIR_REGION"), std::string::npos) << last_message();
  ASSERT_EQ(extract_repaired(host.get(), grid_vertex(5, 1), 0.5, patch, info), MCON_OK) << last_message();
  EXPECT_EQ(info.zero_area_triangles_removed, 1u);
  EXPECT_EQ(info.triangles_split, 1u);
  EXPECT_EQ(info.vertices_merged, 0u);
  EXPECT_EQ(info.pinched_vertices_split, 0u);
  ASSERT_EQ(extract(clean.get(), grid_vertex(5, 1), 0.5, reference), MCON_OK) << last_message();
  // The split adds the cap's corner on the boundary: one vertex more than the clean patch.
  EXPECT_EQ(positions_of(patch.get()).size(), positions_of(reference.get()).size() + 3);

  // Coincident corners: merged, the triangle gone, and the patch the clean host's, bit for bit.
  ASSERT_EQ(extract_repaired(host.get(), grid_vertex(5, 19), 0.5, patch, info), MCON_OK) << last_message();
  EXPECT_EQ(info.zero_area_triangles_removed, 1u);
  EXPECT_EQ(info.vertices_merged, 1u);
  EXPECT_EQ(info.triangles_split, 0u);
  ASSERT_EQ(extract(clean.get(), grid_vertex(5, 19), 0.5, reference), MCON_OK) << last_message();
  EXPECT_EQ(positions_of(patch.get()), positions_of(reference.get()));

  // The pinched vertex: the glued sheet's fan is not the patch's; the patch is the clean one.
  EXPECT_EQ(extract(host.get(), grid_vertex(14, 10), 0.5, patch), MCON_ERROR_NON_MANIFOLD_VERTEX);
  ASSERT_EQ(extract_repaired(host.get(), grid_vertex(14, 10), 0.5, patch, info), MCON_OK) << last_message();
  EXPECT_EQ(info.pinched_vertices_split, 1u);
  EXPECT_EQ(info.zero_area_triangles_removed, 0u);
  ASSERT_EQ(extract(clean.get(), grid_vertex(14, 10), 0.5, reference), MCON_OK) << last_message();
  EXPECT_EQ(positions_of(patch.get()), positions_of(reference.get()));

  // Away from every defect the repair changes nothing and says so.
  ASSERT_EQ(extract_repaired(host.get(), grid_vertex(10, 14), 0.4, patch, info), MCON_OK) << last_message();
  EXPECT_EQ(info.zero_area_triangles_removed + info.triangles_split + info.vertices_merged + info.pinched_vertices_split,
            0u);
}

// A center inside the host triangle that the cap's repair splits: the patch is centered at the same
// host point as without the cap (the piece holding the point is found).
TEST(CapiLocalValidation, RepairKeepsACenterInsideASplitTriangle) {
  ContextPtr ctx = make_context();
  const MeshPtr host = create(ctx.get(), repairable_host(), MCON_MESH_VALIDATE_LOCALLY);
  const MeshPtr clean = create(ctx.get(), arrays_of(bumpy_grid()), 0);
  int splits = 0;
  for (int t : {grid_triangle(5, 0), grid_triangle(5, 0) + 1}) {
    mcon_patch_options o;
    ASSERT_EQ(mcon_patch_options_init(&o), MCON_OK);
    o.center_triangle = static_cast<uint32_t>(t);
    o.center_barycentric[0] = 0.5;
    o.center_barycentric[1] = 0.3;
    o.center_barycentric[2] = 0.2;
    o.radius = 0.5;
    mcon_patch reference = nullptr, repaired = nullptr;
    ASSERT_EQ(mcon_patch_extract(clean.get(), &o, &reference), MCON_OK) << last_message();
    o.flags |= MCON_PATCH_REPAIR_REGION;
    ASSERT_EQ(mcon_patch_extract(host.get(), &o, &repaired), MCON_OK) << last_message();
    mcon_patch_info a, b;
    ASSERT_EQ(mcon_patch_info_init(&a), MCON_OK);
    ASSERT_EQ(mcon_patch_info_init(&b), MCON_OK);
    ASSERT_EQ(mcon_patch_get_info(reference, &a), MCON_OK);
    ASSERT_EQ(mcon_patch_get_info(repaired, &b), MCON_OK);
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(a.center[k], b.center[k], 1e-12) << "triangle " << t;
    EXPECT_NEAR(a.max_geodesic_distance, b.max_geodesic_distance, 0.05) << "triangle " << t;
    mcon_patch_repair_info r;
    ASSERT_EQ(mcon_patch_repair_info_init(&r), MCON_OK);
    ASSERT_EQ(mcon_patch_get_repairs(repaired, &r), MCON_OK);
    splits += static_cast<int>(r.triangles_split);
    mcon_patch_release(reference);
    mcon_patch_release(repaired);
  }
  EXPECT_EQ(splits, 2);  // the split triangle is one of the two: each run split it
}

TEST(CapiLocalValidation, RepairNeedsALocallyValidatedHostAndLeavesEdgesToTheCaller) {
  ContextPtr ctx = make_context();
  const MeshPtr clean = create(ctx.get(), arrays_of(bumpy_grid()), 0);
  PatchPtr patch;
  mcon_patch_repair_info info;
  EXPECT_EQ(extract_repaired(clean.get(), grid_vertex(5, 5), 0.5, patch, info), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_message().find("MCON_MESH_VALIDATE_LOCALLY"), std::string::npos) << last_message();
  // An edge of three triangles is not repaired: still refused, with the repair asked for.
  const MeshPtr host = create(ctx.get(), defective_host(), MCON_MESH_VALIDATE_LOCALLY);
  EXPECT_EQ(extract_repaired(host.get(), grid_vertex(18, 15), 0.3, patch, info), MCON_ERROR_NON_MANIFOLD_EDGE);
  // The repair info of a patch that needed none, and of one made from arrays, is all zero.
  ASSERT_EQ(extract(clean.get(), grid_vertex(5, 5), 0.5, patch), MCON_OK) << last_message();
  ASSERT_EQ(mcon_patch_repair_info_init(&info), MCON_OK);
  ASSERT_EQ(mcon_patch_get_repairs(patch.get(), &info), MCON_OK);
  EXPECT_EQ(info.zero_area_triangles_removed + info.pinched_vertices_split, 0u);
  EXPECT_EQ(mcon_patch_get_repairs(nullptr, &info), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_patch_get_repairs(patch.get(), nullptr), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_patch_repair_info_init(nullptr), MCON_ERROR_NULL_POINTER);
  info.struct_size = 4;  // smaller than the first version of the struct
  EXPECT_EQ(mcon_patch_get_repairs(patch.get(), &info), MCON_ERROR_STRUCT_SIZE) << last_message();
}

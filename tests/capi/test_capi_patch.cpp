// mcon_patch_* and mcon_patch_compute_descriptors on real extractions: arrays read back and
// checked against the host (link, triangles, orientation, geodesic radius), the unit-disk
// parametrization, the info struct, capacities, cancellation, NOT_A_DISK, determinism.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>
#include <map>
#include <utility>
#include <vector>

#include "capi/capi_test_util.h"

using namespace capi_test;

namespace {

using V3 = Eigen::Vector3d;

// Everything a patch returns through the C API.
struct PatchData {
  mcon_patch_info info{};
  std::vector<double> xyz, uv, t;
  std::vector<uint32_t> tris, v0, v1, host_tris;
  V3 position(size_t v) const { return V3(xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]); }
};

PatchData read_patch(mcon_patch p) {
  PatchData d;
  EXPECT_EQ(mcon_patch_info_init(&d.info), MCON_OK);
  EXPECT_EQ(mcon_patch_get_info(p, &d.info), MCON_OK) << last_message();
  const size_t nv = d.info.vertex_count, nt = d.info.triangle_count;
  d.xyz.resize(3 * nv);
  d.uv.resize(2 * nv);
  d.t.resize(nv);
  d.v0.resize(nv);
  d.v1.resize(nv);
  d.tris.resize(3 * nt);
  d.host_tris.resize(nt);
  EXPECT_EQ(mcon_patch_get_positions(p, d.xyz.data(), d.xyz.size()), MCON_OK) << last_message();
  EXPECT_EQ(mcon_patch_get_triangles(p, d.tris.data(), d.tris.size()), MCON_OK) << last_message();
  EXPECT_EQ(mcon_patch_get_uv(p, d.uv.data(), d.uv.size()), MCON_OK) << last_message();
  EXPECT_EQ(mcon_patch_get_host_vertices(p, d.v0.data(), d.v1.data(), d.t.data(), nv), MCON_OK) << last_message();
  EXPECT_EQ(mcon_patch_get_host_triangles(p, d.host_tris.data(), nt), MCON_OK) << last_message();
  return d;
}

mcon_status extract(mcon_mesh mesh, const mcon_patch_options& o, PatchPtr& out) {
  mcon_patch p = nullptr;
  const mcon_status s = mcon_patch_extract(mesh, &o, &p);
  out.reset(p);
  return s;
}

mcon_patch_options at_vertex(uint32_t v, double radius) {
  mcon_patch_options o;
  EXPECT_EQ(mcon_patch_options_init(&o), MCON_OK);
  o.center_vertex = v;
  o.radius = radius;
  return o;
}

V3 host_position(const mcon::TriMesh& host, uint32_t v) { return host.positions[v]; }

// Boundary edges (used once) of a triangle list, and their vertices.
std::vector<bool> boundary_vertices(const PatchData& d) {
  std::map<std::pair<uint32_t, uint32_t>, int> count;
  for (size_t t = 0; t < d.info.triangle_count; ++t)
    for (int k = 0; k < 3; ++k) {
      uint32_t a = d.tris[3 * t + k], b = d.tris[3 * t + (k + 1) % 3];
      ++count[std::minmax(a, b)];
    }
  std::vector<bool> on(d.info.vertex_count, false);
  for (const auto& [e, n] : count)
    if (n == 1) on[e.first] = on[e.second] = true;
  return on;
}

// Every property that ties a patch to its host: link, triangles inside their host triangles with
// the same orientation, the unit-disk parametrization, the info struct.
void check_against_host(const PatchData& d, const mcon::TriMesh& host, double radius, const V3& center) {
  const size_t nv = d.info.vertex_count, nt = d.info.triangle_count;
  ASSERT_GT(nv, 3u);
  ASSERT_GT(nt, 1u);
  EXPECT_EQ(d.info.struct_size, sizeof(mcon_patch_info));
  EXPECT_EQ(d.info.boundary_loops, 1u);
  EXPECT_EQ(d.info.euler_characteristic, 1);
  EXPECT_EQ(d.info.param_flipped_triangles, 0u);
  EXPECT_DOUBLE_EQ(d.info.radius, radius);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(d.info.center[k], center[k], 1e-12);
  EXPECT_NEAR(d.info.max_geodesic_distance, 1.0, 0.1);
  ASSERT_LT(d.info.center_patch_triangle, nt);
  const double bsum = d.info.center_barycentric[0] + d.info.center_barycentric[1] + d.info.center_barycentric[2];
  EXPECT_NEAR(bsum, 1.0, 1e-9);
  // The center as a patch point maps to the origin of the normalized patch.
  V3 c = V3::Zero();
  for (int k = 0; k < 3; ++k) c += d.info.center_barycentric[k] * d.position(d.tris[3 * d.info.center_patch_triangle + k]);
  EXPECT_LT(c.norm(), 1e-9);

  const V3 c_host(d.info.center[0], d.info.center[1], d.info.center[2]);
  std::vector<V3> in_host(nv);
  for (size_t v = 0; v < nv; ++v) {
    // Link: center + radius * p equals the interpolated host position.
    ASSERT_LT(d.v0[v], host.positions.size());
    ASSERT_LT(d.v1[v], host.positions.size());
    ASSERT_GE(d.t[v], 0.0);
    ASSERT_LE(d.t[v], 1.0);
    if (d.v0[v] == d.v1[v]) {
      EXPECT_EQ(d.t[v], 0.0);
    }
    const V3 interpolated = (1 - d.t[v]) * host_position(host, d.v0[v]) + d.t[v] * host_position(host, d.v1[v]);
    in_host[v] = c_host + d.info.radius * d.position(v);
    EXPECT_LT((in_host[v] - interpolated).norm(), 1e-9 * std::max(1.0, radius)) << "vertex " << v;
    // Unit disk.
    EXPECT_LE(std::hypot(d.uv[2 * v], d.uv[2 * v + 1]), 1 + 1e-9) << "vertex " << v;
  }
  const std::vector<bool> boundary = boundary_vertices(d);
  for (size_t v = 0; v < nv; ++v)
    if (boundary[v]) {
      EXPECT_NEAR(std::hypot(d.uv[2 * v], d.uv[2 * v + 1]), 1.0, 1e-9) << "boundary vertex " << v;
    }

  ASSERT_EQ(d.info.filled_triangle_count, 0u);  // no holes in these hosts
  for (size_t t = 0; t < nt; ++t) {
    const uint32_t ht = d.host_tris[t];
    ASSERT_LT(ht, host.triangles.size());
    const auto& tri = host.triangles[ht];
    const V3 a = host.positions[tri[0]], b = host.positions[tri[1]], e = host.positions[tri[2]];
    const V3 n = (b - a).cross(e - a);
    // Each corner lies inside the host triangle (in its plane, barycentric >= 0).
    for (int k = 0; k < 3; ++k) {
      const V3 p = in_host[d.tris[3 * t + k]];
      EXPECT_NEAR(n.normalized().dot(p - a), 0.0, 1e-9) << "triangle " << t;
      const double wa = n.dot((b - p).cross(e - p)) / n.squaredNorm();
      const double wb = n.dot((e - p).cross(a - p)) / n.squaredNorm();
      const double wc = 1 - wa - wb;
      EXPECT_GE(std::min({wa, wb, wc}), -1e-9) << "triangle " << t << " corner " << k << " is outside host " << ht;
    }
    // Counter-clockwise as in the host.
    const V3 p0 = in_host[d.tris[3 * t]], p1 = in_host[d.tris[3 * t + 1]], p2 = in_host[d.tris[3 * t + 2]];
    EXPECT_GT((p1 - p0).cross(p2 - p0).dot(n), 0.0) << "triangle " << t;
    // And not inverted in the parametrization.
    const double* u0 = &d.uv[2 * d.tris[3 * t]];
    const double* u1 = &d.uv[2 * d.tris[3 * t + 1]];
    const double* u2 = &d.uv[2 * d.tris[3 * t + 2]];
    EXPECT_GT((u1[0] - u0[0]) * (u2[1] - u0[1]) - (u1[1] - u0[1]) * (u2[0] - u0[0]), 0.0) << "uv triangle " << t;
  }
}

class CapiPatch : public ::testing::Test {
 protected:
  void SetUp() override {
    ctx_ = make_context();
    grid_ = mcon::test_meshes::make_grid(41, 2.0);  // spacing 0.05
    grid_mesh_ = make_mesh(ctx_.get(), arrays_of(grid_));
    sphere_ = mcon::test_meshes::make_icosphere(3);  // 642 vertices, unit radius
    sphere_mesh_ = make_mesh(ctx_.get(), arrays_of(sphere_));
  }
  ContextPtr ctx_;
  mcon::TriMesh grid_, sphere_;
  MeshPtr grid_mesh_, sphere_mesh_;
};

constexpr uint32_t kGridCenter = 20 * 41 + 20;  // (1, 1)

}  // namespace

TEST_F(CapiPatch, GridPatchMatchesHostAndIsCutAtTheGeodesicRadius) {
  PatchPtr patch;
  ASSERT_EQ(extract(grid_mesh_.get(), at_vertex(kGridCenter, 0.5), patch), MCON_OK) << last_message();
  const PatchData d = read_patch(patch.get());
  check_against_host(d, grid_, 0.5, grid_.positions[kGridCenter]);
  // On a plane geodesic distance is Euclidean: the boundary sits on the circle of radius 1.
  const std::vector<bool> boundary = boundary_vertices(d);
  for (size_t v = 0; v < d.info.vertex_count; ++v) {
    EXPECT_LE(d.position(v).norm(), 1.06) << v;
    if (boundary[v]) {
      EXPECT_NEAR(d.position(v).norm(), 1.0, 0.06) << "boundary vertex " << v;
    }
  }
}

TEST_F(CapiPatch, SpherePatchAroundAPointInsideATriangle) {
  mcon_patch_options o;
  ASSERT_EQ(mcon_patch_options_init(&o), MCON_OK);
  o.center_triangle = 17;
  o.center_barycentric[0] = 0.2;
  o.center_barycentric[1] = 0.3;
  o.center_barycentric[2] = 0.5;
  o.radius = 0.8;
  PatchPtr patch;
  ASSERT_EQ(extract(sphere_mesh_.get(), o, patch), MCON_OK) << last_message();
  const PatchData d = read_patch(patch.get());
  const auto& tri = sphere_.triangles[17];
  const V3 center = 0.2 * sphere_.positions[tri[0]] + 0.3 * sphere_.positions[tri[1]] + 0.5 * sphere_.positions[tri[2]];
  check_against_host(d, sphere_, 0.8, center);
  // Geodesic distance on the unit sphere is the angle: boundary vertices at about 0.8.
  const std::vector<bool> boundary = boundary_vertices(d);
  const V3 dir = center.normalized();
  for (size_t v = 0; v < d.info.vertex_count; ++v) {
    if (!boundary[v]) continue;
    const V3 h = center + 0.8 * d.position(v);
    EXPECT_NEAR(std::acos(std::clamp(h.normalized().dot(dir), -1.0, 1.0)), 0.8, 0.06) << "boundary vertex " << v;
  }
}

TEST_F(CapiPatch, FloatHostKeepsTheLinkToItsOwnPositions) {
  std::vector<float> xyz;
  for (const auto& p : sphere_.positions)
    xyz.insert(xyz.end(), {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())});
  mcon::TriMesh as_float = sphere_;
  for (size_t v = 0; v < as_float.positions.size(); ++v)
    as_float.positions[v] = V3(xyz[3 * v], xyz[3 * v + 1], xyz[3 * v + 2]);
  const Arrays a = arrays_of(sphere_);
  mcon_mesh_desc desc = desc_of(a);
  desc.positions = xyz.data();
  desc.position_type = MCON_SCALAR_FLOAT32;
  mcon_mesh m = nullptr;
  ASSERT_EQ(mcon_mesh_create(ctx_.get(), &desc, &m), MCON_OK) << last_message();
  MeshPtr mesh(m);
  PatchPtr patch;
  ASSERT_EQ(extract(mesh.get(), at_vertex(100, 0.6), patch), MCON_OK) << last_message();
  check_against_host(read_patch(patch.get()), as_float, 0.6, as_float.positions[100]);
}

TEST_F(CapiPatch, InfoStructSizeOlderRejectedNewerAccepted) {
  PatchPtr patch;
  ASSERT_EQ(extract(grid_mesh_.get(), at_vertex(kGridCenter, 0.3), patch), MCON_OK) << last_message();
  mcon_patch_info info;
  std::memset(&info, 0xCD, sizeof(info));
  // The first version ends before the orientation fields; anything smaller is rejected.
  const size_t v1 = offsetof(mcon_patch_info, host_reoriented_triangles);
  info.struct_size = static_cast<uint32_t>(v1 - 8);
  EXPECT_EQ(mcon_patch_get_info(patch.get(), &info), MCON_ERROR_STRUCT_SIZE);
  EXPECT_NE(last_message().find("mcon_patch_info.struct_size"), std::string::npos) << last_message();
  EXPECT_EQ(info.struct_size, v1 - 8);  // nothing written
  EXPECT_EQ(info.vertex_count, static_cast<size_t>(0xCDCDCDCDCDCDCDCDull));
  // A caller built against the first version gets its fields and nothing beyond them.
  info.struct_size = static_cast<uint32_t>(v1);
  ASSERT_EQ(mcon_patch_get_info(patch.get(), &info), MCON_OK) << last_message();
  EXPECT_EQ(info.boundary_loops, 1u);
  EXPECT_EQ(info.host_reoriented_triangles, static_cast<size_t>(0xCDCDCDCDCDCDCDCDull));
  EXPECT_EQ(info.reoriented_triangles, static_cast<size_t>(0xCDCDCDCDCDCDCDCDull));
  info.struct_size = 0;
  EXPECT_EQ(mcon_patch_get_info(patch.get(), &info), MCON_ERROR_STRUCT_SIZE);
  EXPECT_EQ(mcon_patch_get_info(patch.get(), nullptr), MCON_ERROR_NULL_POINTER);

  struct Newer {
    mcon_patch_info v1;
    uint64_t future[2];
  } newer;
  std::memset(&newer, 0xCD, sizeof(newer));
  ASSERT_EQ(mcon_patch_info_init(&newer.v1), MCON_OK);
  newer.v1.struct_size = sizeof(Newer);
  ASSERT_EQ(mcon_patch_get_info(patch.get(), &newer.v1), MCON_OK) << last_message();
  EXPECT_EQ(newer.v1.struct_size, sizeof(Newer));  // the caller's size is kept
  EXPECT_EQ(newer.v1.boundary_loops, 1u);
  EXPECT_EQ(newer.future[0], 0xCDCDCDCDCDCDCDCDull);  // bytes the library does not know stay untouched
  EXPECT_EQ(newer.future[1], 0xCDCDCDCDCDCDCDCDull);
}

TEST_F(CapiPatch, GettersRejectSmallCapacityAndNullOutputsWritingNothing) {
  PatchPtr patch;
  ASSERT_EQ(extract(grid_mesh_.get(), at_vertex(kGridCenter, 0.3), patch), MCON_OK) << last_message();
  mcon_patch_info info;
  ASSERT_EQ(mcon_patch_info_init(&info), MCON_OK);
  ASSERT_EQ(mcon_patch_get_info(patch.get(), &info), MCON_OK);
  const size_t nv = info.vertex_count, nt = info.triangle_count;
  const double dsent = -12345.5;
  const uint32_t usent = 0xABCDEF01u;
  std::vector<double> d(9 * nv + 16, dsent), d2(nv + 16, dsent);
  std::vector<uint32_t> u(3 * nt + 16, usent), u2(nv + 16, usent);
  auto untouched = [&] {
    return std::all_of(d.begin(), d.end(), [&](double x) { return x == dsent; }) &&
           std::all_of(d2.begin(), d2.end(), [&](double x) { return x == dsent; }) &&
           std::all_of(u.begin(), u.end(), [&](uint32_t x) { return x == usent; }) &&
           std::all_of(u2.begin(), u2.end(), [&](uint32_t x) { return x == usent; });
  };
  mcon_patch p = patch.get();
  EXPECT_EQ(mcon_patch_get_positions(p, d.data(), 3 * nv - 1), MCON_ERROR_BUFFER_TOO_SMALL);
  EXPECT_NE(last_message().find(std::to_string(3 * nv) + " are needed"), std::string::npos) << last_message();
  EXPECT_EQ(mcon_patch_get_positions(p, d.data(), 0), MCON_ERROR_BUFFER_TOO_SMALL);
  EXPECT_EQ(mcon_patch_get_triangles(p, u.data(), 3 * nt - 1), MCON_ERROR_BUFFER_TOO_SMALL);
  EXPECT_EQ(mcon_patch_get_uv(p, d.data(), 2 * nv - 1), MCON_ERROR_BUFFER_TOO_SMALL);
  EXPECT_EQ(mcon_patch_get_host_vertices(p, u.data(), u2.data(), d2.data(), nv - 1), MCON_ERROR_BUFFER_TOO_SMALL);
  EXPECT_EQ(mcon_patch_get_host_vertices(p, nullptr, nullptr, d2.data(), nv - 1), MCON_ERROR_BUFFER_TOO_SMALL);
  EXPECT_EQ(mcon_patch_get_host_triangles(p, u.data(), nt - 1), MCON_ERROR_BUFFER_TOO_SMALL);
  EXPECT_EQ(mcon_patch_compute_descriptors(p, MCON_DESCRIPTOR_CURV9, d.data(), 9 * nv - 1), MCON_ERROR_BUFFER_TOO_SMALL);
  EXPECT_EQ(mcon_patch_compute_descriptors(p, MCON_DESCRIPTOR_MEAN_CURVATURE, d.data(), nv - 1),
            MCON_ERROR_BUFFER_TOO_SMALL);
  EXPECT_TRUE(untouched());

  EXPECT_EQ(mcon_patch_get_positions(p, nullptr, 3 * nv), MCON_ERROR_NULL_POINTER);
  EXPECT_NE(last_message().find("out_xyz"), std::string::npos) << last_message();
  EXPECT_EQ(mcon_patch_get_triangles(p, nullptr, 3 * nt), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_patch_get_uv(p, nullptr, 2 * nv), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_patch_get_host_triangles(p, nullptr, nt), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_patch_compute_descriptors(p, MCON_DESCRIPTOR_CURV9, nullptr, 9 * nv), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_patch_compute_descriptors(p, static_cast<mcon_descriptor>(0), d.data(), 9 * nv),
            MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(mcon_patch_compute_descriptors(p, static_cast<mcon_descriptor>(3), d.data(), 9 * nv),
            MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_TRUE(untouched());

  // Host vertices: any output may be NULL; with all NULL nothing is asked and capacity is moot.
  EXPECT_EQ(mcon_patch_get_host_vertices(p, nullptr, nullptr, nullptr, 0), MCON_OK);
  ASSERT_EQ(mcon_patch_get_host_vertices(p, nullptr, u2.data(), nullptr, nv), MCON_OK);
  EXPECT_EQ(u2[nv], usent);  // exactly nv written
  EXPECT_NE(u2[0], usent);
  // Exact capacities work; larger ones write only what is needed.
  ASSERT_EQ(mcon_patch_get_positions(p, d.data(), 3 * nv + 16), MCON_OK);
  EXPECT_EQ(d[3 * nv], dsent);
  ASSERT_EQ(mcon_patch_get_triangles(p, u.data(), 3 * nt), MCON_OK);
}

TEST_F(CapiPatch, ProgressIsMonotoneInUnitRangeAndCancels) {
  struct Log {
    std::vector<double> fractions;
    int cancel_at = -1;  // call index that answers 0
  } log;
  auto callback = [](void* user, double fraction) -> int32_t {
    auto* l = static_cast<Log*>(user);
    l->fractions.push_back(fraction);
    return static_cast<int>(l->fractions.size()) - 1 == l->cancel_at ? 0 : 1;
  };
  mcon_patch_options o = at_vertex(kGridCenter, 0.5);
  o.progress = callback;
  o.progress_user_data = &log;
  PatchPtr patch;
  ASSERT_EQ(extract(grid_mesh_.get(), o, patch), MCON_OK) << last_message();
  ASSERT_GE(log.fractions.size(), 2u);
  for (size_t i = 0; i < log.fractions.size(); ++i) {
    EXPECT_GE(log.fractions[i], 0.0);
    EXPECT_LE(log.fractions[i], 1.0);
    if (i > 0) {
      EXPECT_GE(log.fractions[i], log.fractions[i - 1]);
    }
  }
  const size_t calls = log.fractions.size();

  // Cancel at the first call, and at the last: both end in CANCELLED with no patch; the mesh
  // and the earlier patch stay valid.
  for (int at : {0, static_cast<int>(calls) - 1}) {
    log.fractions.clear();
    log.cancel_at = at;
    PatchPtr cancelled;
    EXPECT_EQ(extract(grid_mesh_.get(), o, cancelled), MCON_ERROR_CANCELLED) << at;
    EXPECT_EQ(cancelled, nullptr);
    EXPECT_NE(last_message().find("cancel"), std::string::npos) << last_message();
    EXPECT_EQ(log.fractions.size(), static_cast<size_t>(at) + 1) << "no call after the cancel";
  }
  size_t nv = 0, nt = 0;
  EXPECT_EQ(mcon_mesh_get_counts(grid_mesh_.get(), &nv, &nt), MCON_OK);
  log.cancel_at = -1;
  PatchPtr again;
  ASSERT_EQ(extract(grid_mesh_.get(), o, again), MCON_OK) << last_message();
  EXPECT_EQ(read_patch(again.get()).xyz, read_patch(patch.get()).xyz);
}

TEST_F(CapiPatch, CylinderWrappingAroundIsNotADisk) {
  // Circumference 2 pi: a radius beyond half of it closes the disk around the cylinder.
  const mcon::TriMesh cyl = mcon::test_meshes::make_cylinder(1.0, 12.0, 32, 49);
  MeshPtr mesh = make_mesh(ctx_.get(), arrays_of(cyl));
  const uint32_t center = 24 * 32;  // middle ring
  PatchPtr patch;
  EXPECT_EQ(extract(mesh.get(), at_vertex(center, 3.6), patch), MCON_ERROR_NOT_A_DISK);
  EXPECT_EQ(patch, nullptr);
  EXPECT_NE(last_message().find("not a disk"), std::string::npos) << last_message();
  // Below half the circumference it is a disk.
  ASSERT_EQ(extract(mesh.get(), at_vertex(center, 2.5), patch), MCON_OK) << last_message();
  check_against_host(read_patch(patch.get()), cyl, 2.5, cyl.positions[center]);
}

TEST_F(CapiPatch, HostHoleIsFilledOnlyWithTheFlagAndFlaggedInTheLinks) {
  // A 21 x 21 grid (spacing 0.1) without the two triangles of one inner quad: a small hole.
  mcon::TriMesh holed = mcon::test_meshes::make_grid(21, 2.0);
  const int a = 10 * 21 + 10;
  const std::vector<int> quad = {a, a + 1, a + 22, a + 21};
  auto in_quad = [&](const mcon::Tri& t) {
    return std::all_of(t.begin(), t.end(), [&](int v) { return std::find(quad.begin(), quad.end(), v) != quad.end(); });
  };
  holed.triangles.erase(std::remove_if(holed.triangles.begin(), holed.triangles.end(), in_quad), holed.triangles.end());
  ASSERT_EQ(holed.triangles.size(), 2u * 20 * 20 - 2);
  MeshPtr mesh = make_mesh(ctx_.get(), arrays_of(holed));
  // Center (0.8, 0.8): the hole is 0.28 to 0.46 away, well inside the radius 0.65, and the grid's
  // own boundary is beyond it.
  const uint32_t center = 8 * 21 + 8;

  mcon_patch_options o = at_vertex(center, 0.65);
  o.flags = 0;
  PatchPtr patch;
  EXPECT_EQ(extract(mesh.get(), o, patch), MCON_ERROR_NOT_A_DISK) << "an unfilled hole makes an annulus";
  EXPECT_EQ(patch, nullptr);
  EXPECT_NE(last_message().find("hole"), std::string::npos) << last_message();

  o.flags = MCON_PATCH_FILL_HOLES;
  ASSERT_EQ(extract(mesh.get(), o, patch), MCON_OK) << last_message();
  const PatchData d = read_patch(patch.get());
  EXPECT_EQ(d.info.boundary_loops, 1u);
  EXPECT_EQ(d.info.euler_characteristic, 1);
  EXPECT_GE(d.info.filled_triangle_count, 2u);
  size_t invalid_triangles = 0;
  for (uint32_t ht : d.host_tris) {
    if (ht == MCON_INVALID_INDEX) {
      ++invalid_triangles;
    } else {
      EXPECT_LT(ht, holed.triangles.size());
    }
  }
  EXPECT_EQ(invalid_triangles, d.info.filled_triangle_count);
  size_t hostless = 0;
  for (size_t v = 0; v < d.info.vertex_count; ++v) {
    // A vertex made for the filling has no host; every other one links to host vertices.
    EXPECT_EQ(d.v0[v] == MCON_INVALID_INDEX, d.v1[v] == MCON_INVALID_INDEX) << v;
    hostless += d.v0[v] == MCON_INVALID_INDEX;
    if (d.v0[v] != MCON_INVALID_INDEX) {
      const V3 h = (1 - d.t[v]) * holed.positions[d.v0[v]] + d.t[v] * holed.positions[d.v1[v]];
      const V3 c(d.info.center[0], d.info.center[1], d.info.center[2]);
      EXPECT_LT((c + d.info.radius * d.position(v) - h).norm(), 1e-9) << v;
    }
    EXPECT_TRUE(std::isfinite(d.xyz[3 * v]) && std::isfinite(d.xyz[3 * v + 1]) && std::isfinite(d.xyz[3 * v + 2]));
  }
  EXPECT_GE(hostless, 1u) << "the hole is capped by a fan around a new vertex";
}

TEST_F(CapiPatch, DescriptorsOfASpherePatch) {
  PatchPtr patch;
  ASSERT_EQ(extract(sphere_mesh_.get(), at_vertex(0, 0.8), patch), MCON_OK) << last_message();
  const PatchData d = read_patch(patch.get());
  const size_t nv = d.info.vertex_count;
  std::vector<double> curv9(9 * nv), mean(nv);
  ASSERT_EQ(mcon_patch_compute_descriptors(patch.get(), MCON_DESCRIPTOR_CURV9, curv9.data(), curv9.size()), MCON_OK)
      << last_message();
  ASSERT_EQ(mcon_patch_compute_descriptors(patch.get(), MCON_DESCRIPTOR_MEAN_CURVATURE, mean.data(), mean.size()),
            MCON_OK)
      << last_message();
  // Normalized by the radius 0.8, the unit sphere has radius 1.25: H = 0.8, K = 0.64, |k|max = 0.8.
  // Per vertex at sigma 0.1 (several edges wide); at the smaller sigmas, below the edge length of
  // this mesh, only on average. The component order shows in identities that hold for any
  // principal curvatures: K <= H^2 and |k|max >= |H|.
  int inner = 0;
  double mean_k[3] = {0, 0, 0}, mean_h[3] = {0, 0, 0}, mean_kmax[3] = {0, 0, 0};
  for (size_t v = 0; v < nv; ++v) {
    if (d.position(v).norm() > 0.5) continue;
    ++inner;
    for (int s = 0; s < 3; ++s) {
      const double k = curv9[9 * v + 3 * s], h = curv9[9 * v + 3 * s + 1], kmax = curv9[9 * v + 3 * s + 2];
      EXPECT_LE(k, h * h + 1e-12) << "vertex " << v << " sigma " << s;
      EXPECT_GE(kmax, std::abs(h) - 1e-12) << "vertex " << v << " sigma " << s;
      mean_k[s] += k;
      mean_h[s] += h;
      mean_kmax[s] += kmax;
    }
    EXPECT_NEAR(curv9[9 * v + 6], 0.64, 0.1) << "K at sigma 0.1, vertex " << v;
    EXPECT_NEAR(curv9[9 * v + 7], 0.8, 0.1) << "H at sigma 0.1, vertex " << v;
    EXPECT_NEAR(curv9[9 * v + 8], 0.8, 0.1) << "|k|max at sigma 0.1, vertex " << v;
    // The re-embedding descriptor is H at sigma 0.1, the last H of CURV9.
    EXPECT_DOUBLE_EQ(mean[v], curv9[9 * v + 7]) << v;
  }
  ASSERT_GT(inner, 5);
  for (int s = 0; s < 3; ++s) {
    EXPECT_NEAR(mean_k[s] / inner, 0.64, 0.1) << "sigma " << s;
    EXPECT_NEAR(mean_h[s] / inner, 0.8, 0.08) << "sigma " << s;
    EXPECT_NEAR(mean_kmax[s] / inner, 0.8, 0.1) << "sigma " << s;
  }
}

// On a plane geodesic distance is Euclidean: from the center point and from a vertex set the heat
// method must give |p - source| (normalized units) up to its discretization error.
TEST_F(CapiPatch, GeodesicDistancesFromAPointAndFromVertices) {
  PatchPtr patch;
  ASSERT_EQ(extract(grid_mesh_.get(), at_vertex(kGridCenter, 0.5), patch), MCON_OK) << last_message();
  const PatchData d = read_patch(patch.get());
  const size_t nv = d.info.vertex_count;
  mcon_surface_point center{d.info.center_patch_triangle,
                            {d.info.center_barycentric[0], d.info.center_barycentric[1], d.info.center_barycentric[2]}};
  std::vector<double> from_center(nv), again(nv);
  ASSERT_EQ(mcon_patch_compute_distance_from_point(patch.get(), &center, from_center.data(), nv), MCON_OK)
      << last_message();
  size_t center_vertex = 0, far_vertex = 0;
  for (size_t v = 0; v < nv; ++v) {
    EXPECT_NEAR(from_center[v], d.position(v).norm(), 0.05) << v;
    if (d.position(v).norm() < d.position(center_vertex).norm()) center_vertex = v;
    if (d.position(v).norm() > d.position(far_vertex).norm()) far_vertex = v;
  }
  // Factored once, the same numbers on every call.
  ASSERT_EQ(mcon_patch_compute_distance_from_point(patch.get(), &center, again.data(), nv), MCON_OK);
  EXPECT_EQ(again, from_center);

  const uint32_t set[] = {static_cast<uint32_t>(far_vertex), static_cast<uint32_t>(center_vertex),
                          static_cast<uint32_t>(far_vertex)};
  std::vector<double> from_set(nv), from_pair(nv);
  ASSERT_EQ(mcon_patch_compute_distance_from_vertices(patch.get(), set, 3, from_set.data(), nv), MCON_OK)
      << last_message();
  ASSERT_EQ(mcon_patch_compute_distance_from_vertices(patch.get(), set, 2, from_pair.data(), nv), MCON_OK);
  EXPECT_EQ(from_set, from_pair);  // a set: order and repeats do not change a bit
  EXPECT_EQ(from_set[center_vertex], 0.0);
  EXPECT_EQ(from_set[far_vertex], 0.0);
  for (size_t v = 0; v < nv; ++v) {
    const double nearest = std::min((d.position(v) - d.position(center_vertex)).norm(),
                                    (d.position(v) - d.position(far_vertex)).norm());
    EXPECT_NEAR(from_set[v], nearest, 0.08) << v;
  }

  // Bad input is refused and nothing is written.
  std::vector<double> untouched(nv, -7.0);
  mcon_surface_point bad = center;
  bad.face = static_cast<uint32_t>(d.info.triangle_count);
  EXPECT_EQ(mcon_patch_compute_distance_from_point(patch.get(), &bad, untouched.data(), nv), MCON_ERROR_INVALID_ARGUMENT);
  bad = center;
  bad.barycentric[0] += 0.5;
  EXPECT_EQ(mcon_patch_compute_distance_from_point(patch.get(), &bad, untouched.data(), nv), MCON_ERROR_INVALID_ARGUMENT);
  bad.barycentric[0] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(mcon_patch_compute_distance_from_point(patch.get(), &bad, untouched.data(), nv), MCON_ERROR_NON_FINITE);
  EXPECT_EQ(mcon_patch_compute_distance_from_point(patch.get(), nullptr, untouched.data(), nv), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_patch_compute_distance_from_point(patch.get(), &center, nullptr, nv), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_patch_compute_distance_from_vertices(patch.get(), nullptr, 1, untouched.data(), nv),
            MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_patch_compute_distance_from_vertices(patch.get(), set, 1, nullptr, nv), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_patch_compute_distance_from_point(patch.get(), &center, untouched.data(), nv - 1),
            MCON_ERROR_BUFFER_TOO_SMALL);
  const uint32_t outside = static_cast<uint32_t>(nv);
  EXPECT_EQ(mcon_patch_compute_distance_from_vertices(patch.get(), &outside, 1, untouched.data(), nv),
            MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_message().find("not a vertex of the patch"), std::string::npos) << last_message();
  EXPECT_EQ(mcon_patch_compute_distance_from_vertices(patch.get(), set, 0, untouched.data(), nv),
            MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(untouched, std::vector<double>(nv, -7.0));
}

TEST_F(CapiPatch, ResultsDoNotDependOnMaxThreads) {
  const Arrays a = arrays_of(sphere_);
  std::vector<double> reference_xyz, reference_uv, reference_curv;
  for (uint32_t threads : {1u, 2u, 0u}) {
    ContextPtr ctx = make_context(threads);
    MeshPtr mesh = make_mesh(ctx.get(), a);
    PatchPtr patch;
    ASSERT_EQ(extract(mesh.get(), at_vertex(5, 0.9), patch), MCON_OK) << last_message();
    const PatchData d = read_patch(patch.get());
    std::vector<double> curv(9 * d.info.vertex_count);
    ASSERT_EQ(mcon_patch_compute_descriptors(patch.get(), MCON_DESCRIPTOR_CURV9, curv.data(), curv.size()), MCON_OK);
    if (reference_xyz.empty()) {
      reference_xyz = d.xyz;
      reference_uv = d.uv;
      reference_curv = curv;
      continue;
    }
    EXPECT_EQ(d.xyz, reference_xyz) << threads;  // bit-identical
    EXPECT_EQ(d.uv, reference_uv) << threads;
    EXPECT_EQ(curv, reference_curv) << threads;
  }
}

TEST_F(CapiPatch, PatchOutlivesItsMeshAndContextAndCountsReferences) {
  ContextPtr ctx = make_context();
  MeshPtr mesh = make_mesh(ctx.get(), arrays_of(grid_));
  PatchPtr patch;
  ASSERT_EQ(extract(mesh.get(), at_vertex(kGridCenter, 0.4), patch), MCON_OK);
  const PatchData before = read_patch(patch.get());
  mesh.reset();
  ctx.reset();
  EXPECT_EQ(mcon_patch_retain(patch.get()), MCON_OK);
  EXPECT_EQ(mcon_patch_release(patch.get()), MCON_OK);
  const PatchData after = read_patch(patch.get());
  EXPECT_EQ(after.xyz, before.xyz);
  std::vector<double> mean(after.info.vertex_count);
  EXPECT_EQ(mcon_patch_compute_descriptors(patch.get(), MCON_DESCRIPTOR_MEAN_CURVATURE, mean.data(), mean.size()),
            MCON_OK)
      << last_message();
  // A patch handle is not a mesh handle.
  size_t nv = 0, nt = 0;
  EXPECT_EQ(mcon_mesh_get_counts(reinterpret_cast<mcon_mesh>(patch.get()), &nv, &nt), MCON_ERROR_INVALID_ARGUMENT);
  PatchPtr none;
  EXPECT_EQ(extract(reinterpret_cast<mcon_mesh>(patch.get()), at_vertex(0, 0.4), none), MCON_ERROR_INVALID_ARGUMENT);
}

// A host with reversed triangles, one under the center: the caller's barycentric weights are in
// the caller's corner order, so the same point gives the same patch as on the consistent host, and
// the patch info reports the host's repair.
TEST(CapiPatchOrientation, ReversedHostGivesTheSamePatchAndReportsTheRepair) {
  ContextPtr ctx = make_context();
  const mcon::TriMesh host = mcon::test_meshes::make_bumpy_grid(21);
  Arrays a = arrays_of(host), b = a;
  const uint32_t center = 421;  // a triangle in the middle of the 800, one of the reversed ones
  for (uint32_t t = 1; t < b.triangle_count(); t += 3) std::swap(b.indices[3 * t + 1], b.indices[3 * t + 2]);
  MeshPtr ma = make_mesh(ctx.get(), a), mb = make_mesh(ctx.get(), b);
  ASSERT_TRUE(ma && mb) << last_message();
  mcon_patch_options o;
  ASSERT_EQ(mcon_patch_options_init(&o), MCON_OK);
  o.center_triangle = center;
  o.center_barycentric[0] = 0.2;
  o.center_barycentric[1] = 0.7;
  o.center_barycentric[2] = 0.1;
  o.radius = 0.5;
  PatchPtr pa, pb;
  ASSERT_EQ(extract(ma.get(), o, pa), MCON_OK) << last_message();
  // The same point in b's corner order (its triangle 421 lists corners 1 and 2 the other way).
  std::swap(o.center_barycentric[1], o.center_barycentric[2]);
  ASSERT_EQ(extract(mb.get(), o, pb), MCON_OK) << last_message();
  const PatchData da = read_patch(pa.get()), db = read_patch(pb.get());
  EXPECT_EQ(da.xyz, db.xyz);
  EXPECT_EQ(da.tris, db.tris);
  EXPECT_EQ(da.info.center[0], db.info.center[0]);
  EXPECT_EQ(da.info.center[1], db.info.center[1]);
  EXPECT_EQ(da.info.center[2], db.info.center[2]);
  EXPECT_EQ(da.info.host_reoriented_triangles, 0u);
  EXPECT_EQ(db.info.host_reoriented_triangles, 267u);
  EXPECT_EQ(db.info.host_inconsistent_components, 1u);
  EXPECT_EQ(db.info.host_outward_turned_components, 0u);
  EXPECT_GT(db.info.reoriented_triangles, 0u);
  EXPECT_LT(db.info.reoriented_triangles, db.info.triangle_count);
}

// mcon_mesh_closest_points / mcon_patch_closest_points: the exact closest surface point of each
// query (triangle, weights that reproduce it, distance), in host units for a patch too; the same
// bits on 1 and 2 threads; bad input refused.
namespace {

V3 point_on(const mcon::TriMesh& m, uint32_t t, const double* w) {
  const auto& tri = m.triangles[t];
  return w[0] * m.positions[tri[0]] + w[1] * m.positions[tri[1]] + w[2] * m.positions[tri[2]];
}

}  // namespace

TEST_F(CapiPatch, ClosestPointsOnTheMeshAndOnAPatch) {
  // Above the grid at height 0.3 (the foot is the closest point), beyond its corner (0, 0), and
  // below a point inside it.
  const std::vector<double> q = {0.37, 1.21, 0.3, -0.3, -0.4, 0.0, 1.5, 0.52, -0.05};
  const V3 expected[3] = {V3(0.37, 1.21, 0), V3(0, 0, 0), V3(1.5, 0.52, 0)};
  const double distance[3] = {0.3, 0.5, 0.05};
  std::vector<uint32_t> tris(3);
  std::vector<double> w(9), d(3);
  ASSERT_EQ(mcon_mesh_closest_points(grid_mesh_.get(), q.data(), 3, tris.data(), w.data(), d.data()), MCON_OK)
      << last_message();
  for (int i = 0; i < 3; ++i) {
    ASSERT_LT(tris[i], grid_.triangles.size());
    EXPECT_NEAR(d[i], distance[i], 1e-12) << i;
    EXPECT_LT((point_on(grid_, tris[i], &w[3 * i]) - expected[i]).norm(), 1e-12) << i;
    EXPECT_NEAR(w[3 * i] + w[3 * i + 1] + w[3 * i + 2], 1.0, 1e-12);
  }

  // The patch of radius 0.5 around (1, 1): a point inside lands on it at the same place (its own
  // triangle numbering), one outside on the patch's rim, farther than from the whole grid.
  PatchPtr patch;
  ASSERT_EQ(extract(grid_mesh_.get(), at_vertex(kGridCenter, 0.5), patch), MCON_OK) << last_message();
  const PatchData pd = read_patch(patch.get());
  mcon::TriMesh host_units;
  for (size_t v = 0; v < pd.info.vertex_count; ++v)
    host_units.positions.push_back(V3(pd.info.center[0], pd.info.center[1], pd.info.center[2]) +
                                   pd.info.radius * pd.position(v));
  for (size_t t = 0; t < pd.info.triangle_count; ++t)
    host_units.triangles.push_back({static_cast<int>(pd.tris[3 * t]), static_cast<int>(pd.tris[3 * t + 1]),
                                    static_cast<int>(pd.tris[3 * t + 2])});
  const std::vector<double> pq = {1.1, 0.9, 0.2, 0.37, 1.21, 0.0};
  std::vector<uint32_t> pt(2);
  std::vector<double> pw(6), pdist(2);
  ASSERT_EQ(mcon_patch_closest_points(patch.get(), pq.data(), 2, pt.data(), pw.data(), pdist.data()), MCON_OK)
      << last_message();
  EXPECT_NEAR(pdist[0], 0.2, 1e-9);
  EXPECT_LT((point_on(host_units, pt[0], &pw[0]) - V3(1.1, 0.9, 0)).norm(), 1e-9);
  EXPECT_GT(pdist[1], 0.1);  // (0.37, 1.21) is about 0.66 from (1, 1): outside the disk
  EXPECT_NEAR((point_on(host_units, pt[1], &pw[3]) - V3(1, 1, 0)).norm(), 0.5, 0.06);

  // Outputs may be NULL; no points is no work; the same bits on one and two threads.
  EXPECT_EQ(mcon_mesh_closest_points(grid_mesh_.get(), q.data(), 3, nullptr, nullptr, d.data()), MCON_OK);
  EXPECT_EQ(mcon_mesh_closest_points(grid_mesh_.get(), nullptr, 0, nullptr, nullptr, nullptr), MCON_OK);
  std::vector<double> many(3 * 2000);
  for (size_t i = 0; i < many.size(); ++i) many[i] = std::fmod(0.6180339887 * static_cast<double>(i), 2.4) - 0.2;
  std::vector<double> w1(3 * 2000), w2(3 * 2000);
  for (uint32_t threads : {1u, 2u}) {
    const ContextPtr ctx = make_context(threads);
    const MeshPtr mesh = make_mesh(ctx.get(), arrays_of(grid_));
    double* out = (threads == 1 ? w1 : w2).data();
    ASSERT_EQ(mcon_mesh_closest_points(mesh.get(), many.data(), 2000, nullptr, out, nullptr), MCON_OK);
  }
  EXPECT_EQ(std::memcmp(w1.data(), w2.data(), w1.size() * sizeof(double)), 0);

  // Bad input: no points array, a non-finite coordinate (named), a missing handle.
  EXPECT_EQ(mcon_mesh_closest_points(grid_mesh_.get(), nullptr, 1, nullptr, nullptr, d.data()),
            MCON_ERROR_NULL_POINTER);
  std::vector<double> bad = q;
  bad[4] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(mcon_patch_closest_points(patch.get(), bad.data(), 3, nullptr, nullptr, d.data()), MCON_ERROR_NON_FINITE);
  EXPECT_NE(last_message().find("coordinate 1 of point 1 is not finite"), std::string::npos) << last_message();
  EXPECT_EQ(mcon_mesh_closest_points(nullptr, q.data(), 3, nullptr, nullptr, d.data()), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_patch_closest_points(nullptr, q.data(), 3, nullptr, nullptr, d.data()), MCON_ERROR_NULL_POINTER);
}

// mcon_patch_cut_guides and the cut mesh's accessors, on a map of the bundled body's nose: the
// guides become chains of the cut mesh's edges, fields are carried, QuadWild's three files agree,
// and bad arguments are refused by name.
#include <cstddef>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include "map_test_util.h"

using namespace map_test;

namespace {

struct CutDeleter {
  void operator()(mcon_cut_mesh c) const { mcon_cut_mesh_release(c); }
};
using CutPtr = std::unique_ptr<mcon_cut_mesh_t, CutDeleter>;

struct CutSetup {
  ContextPtr ctx;
  MeshPtr mesh;
  PatchPtr source, target;
  MapPtr map;
  PatchArrays s, t;
  PolylineSetPtr guides;
};

// A closed loop and a line across it, in the source's uv, transferred through `map`.
PolylineSetPtr loop_and_line(mcon_map map, const PatchArrays& source) {
  std::vector<uint32_t> tri;
  std::vector<double> bary;
  auto add = [&](double u, double v) {
    uint32_t t = 0;
    double b[3];
    EXPECT_TRUE(locate_uv(source, u, v, t, b));
    tri.push_back(t);
    bary.insert(bary.end(), b, b + 3);
  };
  for (int i = 0; i < 30; ++i) add(0.4 * std::cos(2 * 3.141592653589793 * i / 30), 0.4 * std::sin(2 * 3.141592653589793 * i / 30));
  add(-0.6, -0.05);
  add(0.6, 0.08);
  const std::vector<uint32_t> sizes = {30, 2};
  const std::vector<uint8_t> closed = {1, 0};
  mcon_polyline_set set = nullptr;
  EXPECT_EQ(mcon_map_transfer_polylines(map, tri.data(), bary.data(), tri.size(), sizes.data(), closed.data(),
                                        sizes.size(), &set),
            MCON_OK)
      << last_message();
  return PolylineSetPtr(set);
}

CutSetup& setup() {
  static CutSetup* st = [] {
    auto* x = new CutSetup;
    x->ctx = make_context();
    x->mesh = make_mesh(x->ctx.get(), body().arrays);
    x->source = extract(x->mesh.get(), 297, 0.45);
    x->target = extract(x->mesh.get(), 297, 0.55);
    x->map = compute(x->source.get(), x->target.get(), fast_options());
    x->s = arrays_of_patch(x->source.get());
    x->t = arrays_of_patch(x->target.get());
    x->guides = loop_and_line(x->map.get(), x->s);
    return x;
  }();
  return *st;
}

CutPtr cut_of(CutSetup& x, const mcon_guide_cut_options* o = nullptr) {
  mcon_cut_mesh c = nullptr;
  EXPECT_EQ(mcon_patch_cut_guides(x.target.get(), x.guides.get(), o, &c), MCON_OK) << last_message();
  return CutPtr(c);
}

mcon_cut_mesh_info info_of(mcon_cut_mesh c) {
  mcon_cut_mesh_info info;
  EXPECT_EQ(mcon_cut_mesh_info_init(&info), MCON_OK);
  EXPECT_EQ(mcon_cut_mesh_get_info(c, &info), MCON_OK) << last_message();
  return info;
}

// Every array of a cut mesh, sized from its info.
struct CutArrays {
  std::vector<double> xyz, host_bary;
  std::vector<uint32_t> tri, host_tri, sizes, chain;
};
void fetch(mcon_cut_mesh c, const mcon_cut_mesh_info& info, CutArrays& a) {
  a.xyz.resize(3 * info.vertex_count);
  a.host_bary.resize(3 * info.vertex_count);
  a.tri.resize(3 * info.triangle_count);
  a.host_tri.resize(info.vertex_count);
  a.sizes.resize(info.guide_count);
  a.chain.resize(info.guide_vertex_count);
  ASSERT_EQ(mcon_cut_mesh_get_positions(c, a.xyz.data(), a.xyz.size()), MCON_OK) << last_message();
  ASSERT_EQ(mcon_cut_mesh_get_triangles(c, a.tri.data(), a.tri.size()), MCON_OK) << last_message();
  ASSERT_EQ(mcon_cut_mesh_get_host_points(c, a.host_tri.data(), a.host_bary.data(), info.vertex_count), MCON_OK)
      << last_message();
  ASSERT_EQ(mcon_cut_mesh_get_guides(c, a.sizes.data(), a.sizes.size(), a.chain.data(), a.chain.size()), MCON_OK)
      << last_message();
}

std::set<std::pair<uint32_t, uint32_t>> edges_of(const std::vector<uint32_t>& tri) {
  std::set<std::pair<uint32_t, uint32_t>> e;
  for (size_t f = 0; f < tri.size() / 3; ++f)
    for (int k = 0; k < 3; ++k) {
      const uint32_t a = tri[3 * f + k], b = tri[3 * f + (k + 1) % 3];
      e.insert({std::min(a, b), std::max(a, b)});
    }
  return e;
}

}  // namespace

TEST(CapiCutMesh, GuidesAreEdgeChainsOfTheCutMesh) {
  CutSetup& x = setup();
  const CutPtr cut = cut_of(x);
  const mcon_cut_mesh_info info = info_of(cut.get());
  std::printf("cut: %zu vertices, %zu triangles (patch %zu), %zu guide edges, smallest angle made %.1f "
              "(cut patch triangles %.1f), %u moved\n",
              info.vertex_count, info.triangle_count, x.t.nt(), info.guide_edge_count, info.min_angle_created,
              info.min_angle_of_cut_input, info.moved_vertices);
  EXPECT_GT(info.triangle_count, x.t.nt());
  EXPECT_GT(info.guide_edge_count, 20u);
  EXPECT_GE(info.guide_count, 2u);
  EXPECT_GT(info.min_angle_created, 1.0);

  CutArrays arrays;
  ASSERT_NO_FATAL_FAILURE(fetch(cut.get(), info, arrays));
  const auto& [xyz, host_bary, tri, host_tri, sizes, chain] = arrays;
  // Each vertex is at its host point on the patch (host units).
  for (size_t v = 0; v < info.vertex_count; ++v)
    for (int k = 0; k < 3; ++k) {
      double p = 0;
      for (int c = 0; c < 3; ++c) p += host_bary[3 * v + c] * x.t.xyz[3 * x.t.tri[3 * host_tri[v] + c] + k];
      // Patch positions are normalized (host = center + radius * p); the cut mesh's are in host units.
      ASSERT_NEAR(x.t.info.center[k] + x.t.info.radius * p, xyz[3 * v + k], 1e-9) << v;
    }
  // Chains of mesh edges; the guide edges are exactly the chains' steps.
  std::vector<uint32_t> edges(2 * info.guide_edge_count);
  ASSERT_EQ(mcon_cut_mesh_get_guide_edges(cut.get(), edges.data(), edges.size()), MCON_OK);
  const auto mesh_edges = edges_of(tri);
  std::set<std::pair<uint32_t, uint32_t>> steps;
  size_t at = 0;
  for (uint32_t n : sizes) {
    for (uint32_t k = 0; k + 1 < n; ++k) {
      const uint32_t a = chain[at + k], b = chain[at + k + 1];
      steps.insert({std::min(a, b), std::max(a, b)});
      EXPECT_TRUE(mesh_edges.count({std::min(a, b), std::max(a, b)}));
    }
    at += n;
  }
  std::set<std::pair<uint32_t, uint32_t>> listed;
  for (size_t e = 0; e < info.guide_edge_count; ++e) listed.insert({edges[2 * e], edges[2 * e + 1]});
  EXPECT_EQ(listed, steps);

  // A field of the patch, carried: the x coordinate lands on the cut vertices' x.
  std::vector<double> field(x.t.nv()), carried(info.vertex_count);
  for (size_t v = 0; v < x.t.nv(); ++v) field[v] = x.t.info.center[0] + x.t.info.radius * x.t.xyz[3 * v];
  ASSERT_EQ(mcon_cut_mesh_carry_field(cut.get(), 1, field.data(), field.size(), carried.data(), carried.size()), MCON_OK);
  for (size_t v = 0; v < info.vertex_count; ++v) EXPECT_NEAR(carried[v], xyz[3 * v], 1e-9);

  // The cross field runs exactly along the guide edges on their faces.
  std::vector<double> dir(3 * info.triangle_count);
  ASSERT_EQ(mcon_cut_mesh_compute_cross_field(cut.get(), dir.data(), info.triangle_count), MCON_OK);
  size_t along = 0;
  for (const auto& e : listed) {
    double d[3], len = 0;
    for (int k = 0; k < 3; ++k) {
      d[k] = xyz[3 * e.second + k] - xyz[3 * e.first + k];
      len += d[k] * d[k];
    }
    len = std::sqrt(len);
    for (size_t f = 0; f < info.triangle_count; ++f) {
      int hits = 0;
      for (int k = 0; k < 3; ++k) hits += tri[3 * f + k] == e.first || tri[3 * f + k] == e.second;
      if (hits < 2) continue;
      const double c = std::abs(d[0] * dir[3 * f] + d[1] * dir[3 * f + 1] + d[2] * dir[3 * f + 2]) / len;
      if (c > 1 - 1e-9) {
        ++along;
        break;
      }
    }
  }
  // A face that has two guide edges as sides (the guide turns inside it) follows one of them.
  EXPECT_GE(along, listed.size() * 95 / 100);
}

TEST(CapiCutMesh, QuadWildFilesAgreeWithTheCutMesh) {
  CutSetup& x = setup();
  const CutPtr cut = cut_of(x);
  const mcon_cut_mesh_info info = info_of(cut.get());
  const std::string prefix = std::string(MACROCON_BINARY_DIR) + "/capi_cut_mesh_nose";
  ASSERT_EQ(mcon_cut_mesh_write_quadwild(cut.get(), prefix.c_str()), MCON_OK) << last_message();
  std::ifstream obj(prefix + ".obj"), rosy(prefix + ".rosy"), sharp(prefix + ".sharp");
  ASSERT_TRUE(obj && rosy && sharp);
  size_t faces = 0, vertices = 0;
  for (std::string line; std::getline(obj, line);) {
    faces += line.rfind("f ", 0) == 0;
    vertices += line.rfind("v ", 0) == 0;
  }
  EXPECT_EQ(faces, info.triangle_count);
  EXPECT_EQ(vertices, info.vertex_count);
  size_t rosy_count = 0, sharp_count = 0;
  rosy >> rosy_count;
  sharp >> sharp_count;
  EXPECT_EQ(rosy_count, info.triangle_count);
  EXPECT_EQ(sharp_count, info.guide_edge_count);
  // The manifest names the three files, the face count and QuadWild's command line.
  std::ifstream manifest_file(prefix + ".quadwild.json");
  std::stringstream manifest;
  manifest << manifest_file.rdbuf();
  const std::string m = manifest.str();
  EXPECT_NE(m.find("\"faces\": " + std::to_string(info.triangle_count)), std::string::npos) << m;
  EXPECT_NE(m.find("\"sharp_edges\": " + std::to_string(info.guide_edge_count)), std::string::npos) << m;
  EXPECT_NE(m.find("quadwild capi_cut_mesh_nose.obj 2 capi_cut_mesh_nose.rosy capi_cut_mesh_nose.sharp"),
            std::string::npos)
      << m;
  EXPECT_NE(m.find("\"mesh_fnv1a64\": \""), std::string::npos) << m;
  for (const char* ext : {".obj", ".rosy", ".sharp", ".quadwild.json"}) std::remove((prefix + ext).c_str());
}

// Two macro constraints (the nose and an eye) cut into the whole body: one mesh over every face of
// the host with both sets' guides on its edges, one cross field over all of it.
TEST(CapiCutMesh, WholeHostCombinesSeveralConstraints) {
  CutSetup& x = setup();
  const PatchPtr eye_source = extract(x.mesh.get(), 8021, 0.45);
  const PatchPtr eye_target = extract(x.mesh.get(), 8021, 0.55);
  const MapPtr eye_map = compute(eye_source.get(), eye_target.get(), fast_options());
  const PolylineSetPtr eye_guides = loop_and_line(eye_map.get(), arrays_of_patch(eye_source.get()));
  const mcon_polyline_set sets[2] = {x.guides.get(), eye_guides.get()};
  mcon_cut_mesh raw = nullptr;
  ASSERT_EQ(mcon_mesh_cut_guides(x.mesh.get(), sets, 2, nullptr, &raw), MCON_OK) << last_message();
  const CutPtr cut(raw);
  const mcon_cut_mesh_info info = info_of(cut.get());
  const Arrays& host = body().arrays;
  const size_t host_triangles = host.indices.size() / 3, host_vertices = host.positions.size() / 3;
  std::printf("whole body: %zu triangles (host %zu), %zu guides, %zu guide edges, smallest angle made %.1f\n",
              info.triangle_count, host_triangles, info.guide_count, info.guide_edge_count, info.min_angle_created);
  EXPECT_GT(info.triangle_count, host_triangles);
  EXPECT_EQ(info.unplaced_points, 0u);
  CutArrays arrays;
  ASSERT_NO_FATAL_FAILURE(fetch(cut.get(), info, arrays));
  const auto& [xyz, host_bary, tri, host_tri, sizes, chain] = arrays;
  // Every vertex sits at its point on the host mesh, in the mesh's own units.
  for (size_t v = 0; v < info.vertex_count; ++v) {
    ASSERT_LT(host_tri[v], host_triangles);
    for (int k = 0; k < 3; ++k) {
      double p = 0;
      for (int c = 0; c < 3; ++c) p += host_bary[3 * v + c] * host.positions[3 * host.indices[3 * host_tri[v] + c] + k];
      ASSERT_NEAR(p, xyz[3 * v + k], 1e-9) << v;
    }
  }
  // The same surface: the areas agree.
  auto area = [](const std::vector<double>& p, const std::vector<uint32_t>& t) {
    double a = 0;
    for (size_t f = 0; f < t.size() / 3; ++f) {
      const double* q[3] = {&p[3 * t[3 * f]], &p[3 * t[3 * f + 1]], &p[3 * t[3 * f + 2]]};
      const double u[3] = {q[1][0] - q[0][0], q[1][1] - q[0][1], q[1][2] - q[0][2]};
      const double w[3] = {q[2][0] - q[0][0], q[2][1] - q[0][1], q[2][2] - q[0][2]};
      const double c[3] = {u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]};
      a += 0.5 * std::sqrt(c[0] * c[0] + c[1] * c[1] + c[2] * c[2]);
    }
    return a;
  };
  EXPECT_NEAR(area(xyz, tri) / area(host.positions, host.indices), 1.0, 1e-3);
  // Both sets give chains of mesh edges.
  std::vector<uint32_t> from_set(info.guide_count);
  ASSERT_EQ(mcon_cut_mesh_get_guide_origins(cut.get(), from_set.data(), nullptr, info.guide_count), MCON_OK);
  const auto mesh_edges = edges_of(tri);
  size_t at = 0, edges_per_set[2] = {0, 0};
  for (size_t g = 0; g < sizes.size(); ++g) {
    ASSERT_LT(from_set[g], 2u);
    for (uint32_t k = 0; k + 1 < sizes[g]; ++k) {
      const uint32_t a = chain[at + k], b = chain[at + k + 1];
      EXPECT_TRUE(mesh_edges.count({std::min(a, b), std::max(a, b)}));
      ++edges_per_set[from_set[g]];
    }
    at += sizes[g];
  }
  EXPECT_GT(edges_per_set[0], 20u);
  EXPECT_GT(edges_per_set[1], 20u);
  // A field of the mesh is carried; the cross field covers every face with unit directions.
  std::vector<double> field(host_vertices), carried(info.vertex_count);
  for (size_t v = 0; v < host_vertices; ++v) field[v] = host.positions[3 * v + 1];
  ASSERT_EQ(mcon_cut_mesh_carry_field(cut.get(), 1, field.data(), field.size(), carried.data(), carried.size()), MCON_OK);
  for (size_t v = 0; v < info.vertex_count; ++v) EXPECT_NEAR(carried[v], xyz[3 * v + 1], 1e-9);
  std::vector<double> dir(3 * info.triangle_count);
  ASSERT_EQ(mcon_cut_mesh_compute_cross_field(cut.get(), dir.data(), info.triangle_count), MCON_OK);
  for (size_t f = 0; f < info.triangle_count; ++f)
    ASSERT_NEAR(dir[3 * f] * dir[3 * f] + dir[3 * f + 1] * dir[3 * f + 1] + dir[3 * f + 2] * dir[3 * f + 2], 1, 1e-9);

  // Refused: a set on a patch of another mesh, NULL sets, a mesh-sized field of the wrong size.
  Arrays moved = host;
  for (size_t i = 0; i < moved.positions.size(); i += 3) moved.positions[i] += 0.01;
  const MeshPtr other = make_mesh(x.ctx.get(), moved);
  mcon_cut_mesh c = nullptr;
  EXPECT_EQ(mcon_mesh_cut_guides(other.get(), sets, 2, nullptr, &c), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_message().find("guide_sets[0]"), std::string::npos) << last_message();
  EXPECT_EQ(mcon_mesh_cut_guides(x.mesh.get(), nullptr, 2, nullptr, &c), MCON_ERROR_INVALID_ARGUMENT);
  const mcon_polyline_set with_null[2] = {x.guides.get(), nullptr};
  EXPECT_EQ(mcon_mesh_cut_guides(x.mesh.get(), with_null, 2, nullptr, &c), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(c, nullptr);
  field.pop_back();
  EXPECT_EQ(mcon_cut_mesh_carry_field(cut.get(), 1, field.data(), field.size(), carried.data(), carried.size()),
            MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_message().find("mesh vertices"), std::string::npos) << last_message();
  // No set at all: the host itself with its smoothest field.
  ASSERT_EQ(mcon_mesh_cut_guides(x.mesh.get(), nullptr, 0, nullptr, &c), MCON_OK) << last_message();
  const CutPtr plain(c);
  EXPECT_EQ(info_of(plain.get()).triangle_count, host_triangles);
  EXPECT_EQ(info_of(plain.get()).guide_count, 0u);
}

TEST(CapiCutMesh, FairingIsOnByDefaultAndOlderStructsGetIt) {
  CutSetup& x = setup();
  mcon_guide_cut_options o;
  ASSERT_EQ(mcon_guide_cut_options_init(&o), MCON_OK);
  EXPECT_EQ(o.fair_passes, 3u);
  EXPECT_DOUBLE_EQ(o.fair_max_shift, 0.1);
  const CutPtr faired = cut_of(x, &o);
  const mcon_cut_mesh_info fi = info_of(faired.get());
  EXPECT_GT(fi.faired_vertices, 0u);
  o.fair_passes = 0;
  const CutPtr raw = cut_of(x, &o);
  const mcon_cut_mesh_info ri = info_of(raw.get());
  EXPECT_EQ(ri.faired_vertices, 0u);
  EXPECT_EQ(ri.triangle_count, fi.triangle_count);  // fairing moves vertices, it does not cut
  CutArrays a, b;
  ASSERT_NO_FATAL_FAILURE(fetch(faired.get(), fi, a));
  ASSERT_NO_FATAL_FAILURE(fetch(raw.get(), ri, b));
  EXPECT_EQ(a.tri, b.tri);
  EXPECT_NE(a.xyz, b.xyz);
  // A struct from before fairing (ending at simplify_fraction) is accepted and gets the default.
  mcon_guide_cut_options old;
  ASSERT_EQ(mcon_guide_cut_options_init(&old), MCON_OK);
  old.fair_passes = 0;  // beyond the old size: must not be read
  old.struct_size = offsetof(mcon_guide_cut_options, fair_passes);
  const CutPtr from_old = cut_of(x, &old);
  EXPECT_EQ(info_of(from_old.get()).faired_vertices, fi.faired_vertices);
  // So is an old-size info struct, and the new field is left alone.
  mcon_cut_mesh_info old_info;
  ASSERT_EQ(mcon_cut_mesh_info_init(&old_info), MCON_OK);
  old_info.faired_vertices = 12345;
  old_info.struct_size = offsetof(mcon_cut_mesh_info, faired_vertices);
  ASSERT_EQ(mcon_cut_mesh_get_info(faired.get(), &old_info), MCON_OK) << last_message();
  EXPECT_EQ(old_info.faired_vertices, 12345u);
  EXPECT_EQ(old_info.guide_edge_count, fi.guide_edge_count);
  // Out of range or not finite: refused by name.
  mcon_cut_mesh c = nullptr;
  ASSERT_EQ(mcon_guide_cut_options_init(&o), MCON_OK);
  o.fair_passes = 101;
  EXPECT_EQ(mcon_patch_cut_guides(x.target.get(), x.guides.get(), &o, &c), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_message().find("fair_passes"), std::string::npos) << last_message();
  o.fair_passes = 3;
  o.fair_max_shift = 0.7;
  EXPECT_EQ(mcon_patch_cut_guides(x.target.get(), x.guides.get(), &o, &c), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_message().find("fair_max_shift"), std::string::npos) << last_message();
  o.fair_max_shift = std::nan("");
  EXPECT_EQ(mcon_patch_cut_guides(x.target.get(), x.guides.get(), &o, &c), MCON_ERROR_NON_FINITE);
  EXPECT_EQ(c, nullptr);
}

TEST(CapiCutMesh, BadArgumentsAreRefusedByName) {
  CutSetup& x = setup();
  mcon_cut_mesh c = reinterpret_cast<mcon_cut_mesh>(0x1);
  // Guides of another patch.
  EXPECT_EQ(mcon_patch_cut_guides(x.source.get(), x.guides.get(), nullptr, &c), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(c, nullptr);
  EXPECT_NE(last_message().find("another patch"), std::string::npos) << last_message();
  EXPECT_EQ(mcon_patch_cut_guides(x.target.get(), nullptr, nullptr, &c), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_patch_cut_guides(x.target.get(), x.guides.get(), nullptr, nullptr), MCON_ERROR_NULL_POINTER);
  mcon_guide_cut_options o;
  ASSERT_EQ(mcon_guide_cut_options_init(&o), MCON_OK);
  EXPECT_DOUBLE_EQ(o.snap_fraction, 0.25);
  o.snap_fraction = 0.6;
  EXPECT_EQ(mcon_patch_cut_guides(x.target.get(), x.guides.get(), &o, &c), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_message().find("snap_fraction"), std::string::npos) << last_message();
  o.snap_fraction = std::nan("");
  EXPECT_EQ(mcon_patch_cut_guides(x.target.get(), x.guides.get(), &o, &c), MCON_ERROR_NON_FINITE);
  o.struct_size = 4;
  EXPECT_EQ(mcon_patch_cut_guides(x.target.get(), x.guides.get(), &o, &c), MCON_ERROR_STRUCT_SIZE);

  const CutPtr cut = cut_of(x);
  const mcon_cut_mesh_info info = info_of(cut.get());
  std::vector<double> small(3);
  EXPECT_EQ(mcon_cut_mesh_get_positions(cut.get(), small.data(), small.size()), MCON_ERROR_BUFFER_TOO_SMALL);
  std::vector<double> field(x.t.nv() + 1), out(info.vertex_count);
  EXPECT_EQ(mcon_cut_mesh_carry_field(cut.get(), 1, field.data(), field.size(), out.data(), out.size()),
            MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_message().find("patch vertices"), std::string::npos) << last_message();
  field.pop_back();
  field[3] = std::nan("");
  EXPECT_EQ(mcon_cut_mesh_carry_field(cut.get(), 1, field.data(), field.size(), out.data(), out.size()),
            MCON_ERROR_NON_FINITE);
  EXPECT_EQ(mcon_cut_mesh_write_quadwild(cut.get(), ""), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(mcon_cut_mesh_write_quadwild(cut.get(), "/nonexistent-dir/x"), MCON_ERROR_IO);
  // Retain and release balance; the handle stays valid for its guard.
  mcon_cut_mesh extra = cut.get();
  ASSERT_EQ(mcon_cut_mesh_retain(extra), MCON_OK);
  EXPECT_EQ(mcon_cut_mesh_release(extra), MCON_OK);
  // The cut mesh keeps its patch alive.
  mcon_cut_mesh kept = nullptr;
  {
    PatchPtr target = extract(x.mesh.get(), 297, 0.55);
    MapPtr map = compute(x.source.get(), target.get(), fast_options());
    std::vector<uint32_t> tri;
    std::vector<double> bary;
    for (double u : {-0.5, 0.5}) {
      uint32_t t = 0;
      double b[3];
      ASSERT_TRUE(locate_uv(x.s, u, 0.0, t, b));
      tri.push_back(t);
      bary.insert(bary.end(), b, b + 3);
    }
    const uint32_t size = 2;
    mcon_polyline_set set = nullptr;
    ASSERT_EQ(mcon_map_transfer_polylines(map.get(), tri.data(), bary.data(), 2, &size, nullptr, 1, &set), MCON_OK);
    const PolylineSetPtr guard(set);
    ASSERT_EQ(mcon_patch_cut_guides(target.get(), set, nullptr, &kept), MCON_OK) << last_message();
  }
  const mcon_cut_mesh_info k = info_of(kept);
  EXPECT_GT(k.guide_edge_count, 0u);
  std::vector<double> kx(3 * k.vertex_count);
  EXPECT_EQ(mcon_cut_mesh_get_positions(kept, kx.data(), kx.size()), MCON_OK);
  EXPECT_EQ(mcon_cut_mesh_release(kept), MCON_OK);
  EXPECT_EQ(mcon_cut_mesh_release(kept), MCON_ERROR_INVALID_ARGUMENT);
}

TEST(CapiCutMesh, NullHandlesAndOutputsAreRefused) {
  CutSetup& x = setup();
  double d[3];
  uint32_t u[3];
  mcon_cut_mesh_info info;
  ASSERT_EQ(mcon_cut_mesh_info_init(&info), MCON_OK);
  EXPECT_EQ(mcon_guide_cut_options_init(nullptr), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_cut_mesh_info_init(nullptr), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_cut_mesh_get_info(nullptr, &info), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_cut_mesh_get_positions(nullptr, d, 3), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_cut_mesh_get_triangles(nullptr, u, 3), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_cut_mesh_get_host_points(nullptr, u, d, 1), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_cut_mesh_get_guide_edges(nullptr, u, 2), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_cut_mesh_get_guides(nullptr, u, 1, u, 1), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_cut_mesh_carry_field(nullptr, 1, d, 1, d, 1), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_cut_mesh_compute_cross_field(nullptr, d, 1), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_cut_mesh_write_quadwild(nullptr, "x"), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_cut_mesh_retain(nullptr), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_cut_mesh_release(nullptr), MCON_OK);  // as every other release: NULL is a no-op
  const CutPtr cut = cut_of(x);
  EXPECT_EQ(mcon_cut_mesh_get_info(cut.get(), nullptr), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_cut_mesh_get_positions(cut.get(), nullptr, 3), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_cut_mesh_get_triangles(cut.get(), nullptr, 3), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_cut_mesh_get_guide_edges(cut.get(), nullptr, 2), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_cut_mesh_compute_cross_field(cut.get(), nullptr, 1), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_cut_mesh_carry_field(cut.get(), 1, nullptr, 1, d, 1), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_cut_mesh_carry_field(cut.get(), 0, d, 1, d, 1), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(mcon_cut_mesh_write_quadwild(cut.get(), nullptr), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_cut_mesh_get_triangles(cut.get(), u, 3), MCON_ERROR_BUFFER_TOO_SMALL);
  EXPECT_EQ(mcon_cut_mesh_get_guides(cut.get(), u, 0, nullptr, 0), MCON_ERROR_BUFFER_TOO_SMALL);
  EXPECT_EQ(mcon_cut_mesh_compute_cross_field(cut.get(), d, 1), MCON_ERROR_BUFFER_TOO_SMALL);
  info.struct_size = 4;
  EXPECT_EQ(mcon_cut_mesh_get_info(cut.get(), &info), MCON_ERROR_STRUCT_SIZE);
  // The whole-host call and the origins getter: NULL handle, NULL output, short buffer.
  const mcon_polyline_set sets[1] = {x.guides.get()};
  mcon_cut_mesh c = nullptr;
  EXPECT_EQ(mcon_mesh_cut_guides(nullptr, sets, 1, nullptr, &c), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_mesh_cut_guides(x.mesh.get(), sets, 1, nullptr, nullptr), MCON_ERROR_NULL_POINTER);
  mcon_guide_cut_options o;
  ASSERT_EQ(mcon_guide_cut_options_init(&o), MCON_OK);
  o.struct_size = 4;
  EXPECT_EQ(mcon_mesh_cut_guides(x.mesh.get(), sets, 1, &o, &c), MCON_ERROR_STRUCT_SIZE);
  EXPECT_EQ(c, nullptr);
  EXPECT_EQ(mcon_cut_mesh_get_guide_origins(nullptr, u, u, 1), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_cut_mesh_get_guide_origins(cut.get(), u, nullptr, 0), MCON_ERROR_BUFFER_TOO_SMALL);
  EXPECT_EQ(mcon_cut_mesh_get_guide_origins(cut.get(), nullptr, nullptr, 0), MCON_OK);  // nothing asked
}

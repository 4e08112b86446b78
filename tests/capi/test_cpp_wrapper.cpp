// The header-only C++ wrapper (macrocon.hpp): errors as exceptions, RAII handles with copy =
// retain and move = steal, array getters, progress through std::function, version helpers.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

#include "macrocon/macrocon.hpp"
#include "test_meshes.h"

namespace {

struct Flat {
  std::vector<double> xyz;
  std::vector<uint32_t> tris;
};

Flat flat(const mcon::TriMesh& m) {
  Flat f;
  for (const auto& p : m.positions) f.xyz.insert(f.xyz.end(), {p.x(), p.y(), p.z()});
  for (const auto& t : m.triangles)
    for (int v : t) f.tris.push_back(static_cast<uint32_t>(v));
  return f;
}

template <typename F>
macrocon::Error error_of(F&& f) {
  try {
    f();
  } catch (const macrocon::Error& e) {
    return e;
  }
  return macrocon::Error(MCON_OK, "no error thrown");
}

}  // namespace

static_assert(std::is_nothrow_move_constructible_v<macrocon::Context>);
static_assert(std::is_nothrow_move_constructible_v<macrocon::Mesh>);
static_assert(std::is_nothrow_move_constructible_v<macrocon::Patch>);
static_assert(std::is_copy_constructible_v<macrocon::Patch>);

TEST(CppWrapper, VersionHelpersAndStatusNames) {
  const macrocon::Version lib = macrocon::library_version();
  constexpr macrocon::Version hdr = macrocon::header_version();
  EXPECT_EQ(lib.major, hdr.major);
  EXPECT_EQ(lib.minor, hdr.minor);
  EXPECT_EQ(lib.patch, hdr.patch);
  EXPECT_EQ(lib.encoded(), static_cast<uint32_t>(MCON_VERSION));
  EXPECT_TRUE(macrocon::is_compatible());
  EXPECT_EQ(lib.to_string(), std::to_string(MCON_VERSION_MAJOR) + "." + std::to_string(MCON_VERSION_MINOR) + "." +
                                 std::to_string(MCON_VERSION_PATCH));
  EXPECT_EQ(macrocon::status_name(MCON_ERROR_NOT_A_DISK), "MCON_ERROR_NOT_A_DISK");
  EXPECT_EQ(macrocon::status_name(static_cast<mcon_status>(63)), "unknown status 63");
}

TEST(CppWrapper, MeshFromVectorsAndStridedPointers) {
  macrocon::Context ctx;  // a working context with default options
  ASSERT_TRUE(ctx);
  const Flat g = flat(mcon::test_meshes::make_grid(5));
  const macrocon::Mesh from_double = macrocon::Mesh::from_arrays(ctx, g.xyz, g.tris);
  EXPECT_EQ(from_double.vertex_count(), 25u);
  EXPECT_EQ(from_double.triangle_count(), 32u);
  const std::vector<float> xyz_f(g.xyz.begin(), g.xyz.end());
  const macrocon::Mesh from_float = macrocon::Mesh::from_arrays(ctx, xyz_f, g.tris);
  EXPECT_EQ(from_float.vertex_count(), 25u);

  // Strided: 4 floats per vertex (xyz + NaN padding), 4 indices per triangle (abc + bad index).
  std::vector<float> padded;
  for (size_t v = 0; v < 25; ++v)
    padded.insert(padded.end(), {xyz_f[3 * v], xyz_f[3 * v + 1], xyz_f[3 * v + 2], std::nanf("")});
  std::vector<uint32_t> tris4;
  for (size_t t = 0; t < 32; ++t) tris4.insert(tris4.end(), {g.tris[3 * t], g.tris[3 * t + 1], g.tris[3 * t + 2], 999u});
  const macrocon::Mesh strided =
      macrocon::Mesh::from_arrays(ctx, padded.data(), 4 * sizeof(float), 25, tris4.data(), 16, 32);
  EXPECT_EQ(strided.triangle_count(), 32u);
  std::vector<double> padded_d(padded.begin(), padded.end());
  EXPECT_EQ(macrocon::Mesh::from_arrays(ctx, padded_d.data(), 4 * sizeof(double), 25, tris4.data(), 16, 32)
                .vertex_count(),
            25u);
  // Packed reading of the padded arrays hits the NaN.
  EXPECT_EQ(error_of([&] { macrocon::Mesh::from_arrays(ctx, padded.data(), 0, 25, tris4.data(), 16, 32); }).status(),
            MCON_ERROR_NON_FINITE);
}

TEST(CppWrapper, MeshFromInt32AndInt64Vectors) {
  macrocon::Context ctx;
  const Flat g = flat(mcon::test_meshes::make_grid(5));
  const macrocon::Mesh ref = macrocon::Mesh::from_arrays(ctx, g.xyz, g.tris);
  std::vector<std::int32_t> t32(g.tris.begin(), g.tris.end());
  const std::vector<std::int64_t> t64(g.tris.begin(), g.tris.end());
  EXPECT_EQ(macrocon::Mesh::from_arrays(ctx, g.xyz, t32).triangles(), ref.triangles());
  EXPECT_EQ(macrocon::Mesh::from_arrays(ctx, g.xyz, t64).triangles(), ref.triangles());
  const std::vector<float> xyz_f(g.xyz.begin(), g.xyz.end());
  EXPECT_EQ(macrocon::Mesh::from_arrays(ctx, xyz_f, t32).triangles(), ref.triangles());
  t32[7] = -3;
  const macrocon::Error e = error_of([&] { macrocon::Mesh::from_arrays(ctx, g.xyz, t32); });
  EXPECT_EQ(e.status(), MCON_ERROR_INDEX_OUT_OF_RANGE);
  EXPECT_NE(std::string(e.what()).find("triangle 2 uses vertex index -3"), std::string::npos) << e.what();
  t32.pop_back();
  EXPECT_EQ(error_of([&] { macrocon::Mesh::from_arrays(ctx, g.xyz, t32); }).status(), MCON_ERROR_INVALID_ARGUMENT);
}

TEST(CppWrapper, MeshFlagsValidateLocally) {
  macrocon::Context ctx;
  Flat g = flat(mcon::test_meshes::make_grid(6));
  g.xyz.insert(g.xyz.end(), {9.0, 9.0, 9.0});  // an isolated vertex
  EXPECT_EQ(error_of([&] { macrocon::Mesh::from_arrays(ctx, g.xyz, g.tris); }).status(), MCON_ERROR_ISOLATED_VERTEX);
  const macrocon::Mesh m = macrocon::Mesh::from_arrays(ctx, g.xyz, g.tris, MCON_MESH_VALIDATE_LOCALLY);
  EXPECT_EQ(m.vertex_count(), 37u);
  const std::vector<std::int32_t> t32(g.tris.begin(), g.tris.end());
  EXPECT_EQ(macrocon::Mesh::from_arrays(ctx, g.xyz, t32, MCON_MESH_VALIDATE_LOCALLY).vertex_count(), 37u);
}

TEST(CppWrapper, PatchOptionsRepairRegion) {
  macrocon::Context ctx;
  // A 7 x 7 grid with a zero-area cap on its bottom edge (2, 0)-(3, 0).
  Flat g = flat(mcon::test_meshes::make_grid(7));
  const std::uint32_t a = 2, b = 3, mid = 49;
  for (int k = 0; k < 3; ++k) g.xyz.push_back(0.5 * (g.xyz[3 * a + k] + g.xyz[3 * b + k]));
  g.tris.insert(g.tris.end(), {b, a, mid});
  const macrocon::Mesh m = macrocon::Mesh::from_arrays(ctx, g.xyz, g.tris, MCON_MESH_VALIDATE_LOCALLY);
  macrocon::PatchOptions o = macrocon::PatchOptions::at_vertex(9, 0.4);  // (2, 1), next to the cap
  EXPECT_EQ(error_of([&] { macrocon::Patch::extract(m, o); }).status(), MCON_ERROR_DEGENERATE_TRIANGLE);
  o.repair_region = true;
  const macrocon::Patch p = macrocon::Patch::extract(m, o);
  EXPECT_EQ(p.repairs().zero_area_triangles_removed, 1u);
  EXPECT_EQ(p.repairs().triangles_split, 1u);
}

TEST(CppWrapper, ClosestPoints) {
  macrocon::Context ctx;
  const Flat g = flat(mcon::test_meshes::make_grid(11, 2.0));
  const macrocon::Mesh m = macrocon::Mesh::from_arrays(ctx, g.xyz, g.tris);
  const macrocon::ClosestPoints c = m.closest_points({0.5, 0.7, 0.25, 3.0, 1.0, 0.0});
  ASSERT_EQ(c.size(), 2u);
  EXPECT_NEAR(c.distances[0], 0.25, 1e-12);
  EXPECT_NEAR(c.distances[1], 1.0, 1e-12);  // beyond the edge x = 2
  EXPECT_NEAR(c.barycentric[0] + c.barycentric[1] + c.barycentric[2], 1.0, 1e-12);
  const macrocon::Patch p = macrocon::Patch::extract(m, macrocon::PatchOptions::at_vertex(60, 0.5));  // (1, 1)
  const macrocon::ClosestPoints on_patch = p.closest_points({1.1, 0.95, -0.5});
  EXPECT_NEAR(on_patch.distances[0], 0.5, 1e-9);  // host units, below the patch
  EXPECT_LT(on_patch.triangles[0], p.triangle_count());
  EXPECT_EQ(error_of([&] { m.closest_points({1.0, 2.0}); }).status(), MCON_ERROR_INVALID_ARGUMENT);
}

TEST(CppWrapper, GeodesicDistances) {
  macrocon::Context ctx;
  const Flat g = flat(mcon::test_meshes::make_grid(21, 2.0));
  const macrocon::Mesh m = macrocon::Mesh::from_arrays(ctx, g.xyz, g.tris);
  const macrocon::Patch p = macrocon::Patch::extract(m, macrocon::PatchOptions::at_vertex(220, 0.5));  // (1, 1)
  const mcon_patch_info info = p.info();
  const std::vector<double> d = p.distance_from_point(
      {info.center_patch_triangle, {info.center_barycentric[0], info.center_barycentric[1], info.center_barycentric[2]}});
  const std::vector<double> x = p.positions();
  ASSERT_EQ(d.size(), p.vertex_count());
  for (std::size_t v = 0; v < d.size(); ++v)
    EXPECT_NEAR(d[v], std::sqrt(x[3 * v] * x[3 * v] + x[3 * v + 1] * x[3 * v + 1]), 0.08) << v;
  EXPECT_EQ(p.distance_from_vertices({3})[3], 0.0);
  EXPECT_EQ(error_of([&] { p.distance_from_vertices({}); }).status(), MCON_ERROR_INVALID_ARGUMENT);
}

TEST(CppWrapper, ErrorsCarryStatusAndLibraryMessage) {
  macrocon::Context ctx;
  Flat g = flat(mcon::test_meshes::make_grid(4));
  g.xyz[3 * 6] = std::numeric_limits<double>::quiet_NaN();
  const macrocon::Error e = error_of([&] { macrocon::Mesh::from_arrays(ctx, g.xyz, g.tris); });
  EXPECT_EQ(e.status(), MCON_ERROR_NON_FINITE);
  EXPECT_NE(std::string(e.what()).find("vertex 6"), std::string::npos) << e.what();
  EXPECT_NE(std::string(e.what()).find("mcon_mesh_create"), std::string::npos) << e.what();

  g = flat(mcon::test_meshes::make_grid(4));
  g.xyz.pop_back();
  const macrocon::Error sizes = error_of([&] { macrocon::Mesh::from_arrays(ctx, g.xyz, g.tris); });
  EXPECT_EQ(sizes.status(), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(sizes.what()).find("multiples of 3"), std::string::npos) << sizes.what();

  macrocon::Context::Options bad;
  bad.max_threads = 100000;
  EXPECT_EQ(error_of([&] { macrocon::Context c(bad); }).status(), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(error_of([&] { macrocon::Patch::descriptor_dimension(static_cast<mcon_descriptor>(3)); }).status(),
            MCON_ERROR_INVALID_ARGUMENT);
}

TEST(CppWrapper, CopyRetainsMoveStealsDestructorReleases) {
  macrocon::Context a;
  macrocon::Context b = a;  // retain: two references
  // Take a's reference out of the wrapper and drop it by hand: b's own reference must keep the
  // context alive (the sanitizer build catches a use after free if copying did not retain).
  mcon_context raw = a.detach();
  EXPECT_FALSE(a);
  EXPECT_EQ(mcon_context_release(raw), MCON_OK);
  const Flat g = flat(mcon::test_meshes::make_grid(3));
  macrocon::Mesh m = macrocon::Mesh::from_arrays(b, g.xyz, g.tris);
  EXPECT_EQ(m.vertex_count(), 9u);

  // Copy assignment onto a live object releases the old handle and retains the new one.
  macrocon::Mesh other = macrocon::Mesh::from_arrays(b, g.xyz, g.tris);
  other = m;
  EXPECT_EQ(other.get(), m.get());
  other = other;  // self-assignment keeps the handle
  EXPECT_EQ(other.vertex_count(), 9u);

  // Move steals: the source is empty and using it throws instead of passing NULL to C.
  macrocon::Mesh moved = std::move(m);
  EXPECT_FALSE(m);  // NOLINT(bugprone-use-after-move): documented state
  EXPECT_TRUE(moved);
  EXPECT_EQ(moved.get(), other.get());
  const macrocon::Error e = error_of([&] { (void)m.vertex_count(); });
  EXPECT_EQ(e.status(), MCON_ERROR_NULL_POINTER);
  EXPECT_NE(std::string(e.what()).find("moved from"), std::string::npos) << e.what();
  macrocon::Context empty(nullptr);
  EXPECT_FALSE(empty);
  EXPECT_EQ(error_of([&] { macrocon::Mesh::from_arrays(empty, g.xyz, g.tris); }).status(), MCON_ERROR_NULL_POINTER);

  // adopt() takes over a C reference.
  mcon_mesh raw_mesh = moved.detach();
  macrocon::Mesh adopted = macrocon::Mesh::adopt(raw_mesh);
  EXPECT_EQ(adopted.triangle_count(), 8u);
  // The meshes keep the context alive after every Context object is gone.
  b = macrocon::Context(nullptr);
  EXPECT_EQ(adopted.vertex_count(), 9u);
}

TEST(CppWrapper, PatchExtractGettersDescriptorsAndProgress) {
  macrocon::Context ctx;
  const Flat g = flat(mcon::test_meshes::make_grid(21, 2.0));
  const macrocon::Mesh mesh = macrocon::Mesh::from_arrays(ctx, g.xyz, g.tris);
  std::vector<double> fractions;
  macrocon::PatchOptions o = macrocon::PatchOptions::at_vertex(220, 0.5);
  o.progress = [&](double f) {
    fractions.push_back(f);
    return true;
  };
  const macrocon::Patch patch = macrocon::Patch::extract(mesh, o);
  const mcon_patch_info info = patch.info();
  EXPECT_EQ(info.boundary_loops, 1u);
  EXPECT_EQ(info.euler_characteristic, 1);
  EXPECT_DOUBLE_EQ(info.radius, 0.5);
  EXPECT_FALSE(fractions.empty());
  const auto xyz = patch.positions();
  const auto tris = patch.triangles();
  const auto uv = patch.uv();
  const auto host = patch.host_vertices();
  const auto host_tris = patch.host_triangles();
  EXPECT_EQ(xyz.size(), 3 * info.vertex_count);
  EXPECT_EQ(tris.size(), 3 * info.triangle_count);
  EXPECT_EQ(uv.size(), 2 * info.vertex_count);
  EXPECT_EQ(host.v0.size(), info.vertex_count);
  EXPECT_EQ(host_tris.size(), info.triangle_count);
  for (size_t v = 0; v < info.vertex_count; ++v) {
    // Host link: center + radius * p == interpolated host position (flat grid: z = 0).
    const double t = host.t[v];
    for (int k = 0; k < 3; ++k) {
      const double h = (1 - t) * g.xyz[3 * host.v0[v] + k] + t * g.xyz[3 * host.v1[v] + k];
      EXPECT_NEAR(info.center[k] + info.radius * xyz[3 * v + k], h, 1e-12);
    }
    EXPECT_LE(std::hypot(uv[2 * v], uv[2 * v + 1]), 1 + 1e-9);
  }
  const auto curv9 = patch.compute_descriptors(MCON_DESCRIPTOR_CURV9);
  EXPECT_EQ(curv9.size(), 9 * info.vertex_count);
  for (double x : curv9) EXPECT_NEAR(x, 0.0, 1e-6);  // a plane has no curvature
  EXPECT_EQ(patch.compute_descriptors(MCON_DESCRIPTOR_MEAN_CURVATURE).size(), info.vertex_count);

  // The C struct works too and gives the same patch.
  mcon_patch_options c;
  ASSERT_EQ(mcon_patch_options_init(&c), MCON_OK);
  c.center_vertex = 220;
  c.radius = 0.5;
  const macrocon::Patch same = macrocon::Patch::extract(mesh, c);
  EXPECT_EQ(same.positions(), xyz);
  // A copy shares the handle.
  const macrocon::Patch copy = same;
  EXPECT_EQ(copy.get(), same.get());
}

TEST(CppWrapper, ProgressCancelsAndRethrowsCallbackExceptions) {
  macrocon::Context ctx;
  const Flat g = flat(mcon::test_meshes::make_grid(21, 2.0));
  const macrocon::Mesh mesh = macrocon::Mesh::from_arrays(ctx, g.xyz, g.tris);
  macrocon::PatchOptions o = macrocon::PatchOptions::at_vertex(220, 0.5);
  o.progress = [](double) { return false; };
  EXPECT_EQ(error_of([&] { macrocon::Patch::extract(mesh, o); }).status(), MCON_ERROR_CANCELLED);

  struct Custom : std::runtime_error {
    Custom() : std::runtime_error("from the callback") {}
  };
  o.progress = [](double) -> bool { throw Custom(); };
  EXPECT_THROW(macrocon::Patch::extract(mesh, o), Custom);
  // The mesh is still usable.
  o.progress = nullptr;
  EXPECT_GT(macrocon::Patch::extract(mesh, o).vertex_count(), 0u);
  // Options are checked by the library.
  o.radius = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(error_of([&] { macrocon::Patch::extract(mesh, o); }).status(), MCON_ERROR_NON_FINITE);
  EXPECT_EQ(error_of([&] { macrocon::Patch().info(); }).status(), MCON_ERROR_NULL_POINTER);
}

static_assert(std::is_nothrow_move_constructible_v<macrocon::Library>);

TEST(CppWrapper, LibraryAddBuildQuerySaveOpenMergeAndEntries) {
  macrocon::Context ctx;
  const Flat g = flat(mcon::test_meshes::make_bumpy_grid(31));
  const macrocon::Mesh mesh = macrocon::Mesh::from_arrays(ctx, g.xyz, g.tris);
  // Three different regions of the bumpy grid (vertex = row * 31 + column).
  std::vector<macrocon::Patch> patches;
  for (std::uint32_t v : {15u * 31 + 15, 8u * 31 + 8, 22u * 31 + 9})
    patches.push_back(macrocon::Patch::extract(mesh, macrocon::PatchOptions::at_vertex(v, 0.3)));

  macrocon::Library lib = macrocon::Library::create(ctx);
  EXPECT_EQ(lib.size(), 0u);
  std::vector<std::uint64_t> ids;
  for (std::size_t i = 0; i < patches.size(); ++i) {
    macrocon::EntryData data;
    data.name = "region_" + std::to_string(i);
    data.class_label = i == 0 ? "center" : "side";
    data.tags = {"bumpy", "grid"};
    const std::size_t n = patches[i].vertex_count();
    macrocon::Polyline guide;
    guide.points = {{0, {1, 0, 0}}, {1, {0, 1, 0}}};
    data.polylines.push_back(guide);
    data.singularities.push_back(mcon_singularity{{2, {0.25, 0.25, 0.5}}, -1});
    macrocon::VertexField label;
    label.name = "label";
    label.kind = MCON_FIELD_INTEGER_LABEL;
    label.labels.assign(n, static_cast<std::int32_t>(i));
    macrocon::VertexField weight;
    weight.name = "weight";
    weight.values.assign(n, 0.5 * static_cast<double>(i));
    data.fields = {label, weight};
    if (i == 2) data.up = std::array<double, 3>{{0, 0, 1}};  // the grid's host is z-up
    ids.push_back(lib.add(patches[i], data));
  }
  EXPECT_EQ(lib.size(), 3u);
  EXPECT_EQ(lib.find(ids[2]), 2u);

  // No vocabulary yet: queries throw with the library's status and message.
  const macrocon::Error no_vocabulary = error_of([&] { lib.query(patches[0], 1); });
  EXPECT_EQ(no_vocabulary.status(), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(std::string(no_vocabulary.what()).find("vocabulary"), std::string::npos);

  mcon_retrieval_options o = macrocon::Library::default_retrieval_options();
  EXPECT_EQ(o.rings, 1u);
  EXPECT_EQ(o.vocabulary_size, 128u);
  o.vocabulary_size = 8;
  lib.build_retrieval(o);
  EXPECT_EQ(lib.info().vocabulary_size, 8u);
  for (std::size_t i = 0; i < patches.size(); ++i) {
    const auto hits = lib.query(patches[i], 10);
    ASSERT_EQ(hits.size(), 3u);
    EXPECT_EQ(hits[0].id, ids[i]);
    EXPECT_EQ(hits[0].index, i);
    EXPECT_EQ(hits[0].distance, 0.0);
  }

  // Entries read back.
  const macrocon::EntryData e = lib.entry(1);
  EXPECT_EQ(e.id, ids[1]);
  EXPECT_EQ(e.name, "region_1");
  EXPECT_EQ(e.class_label, "side");
  EXPECT_EQ(e.tags, (std::vector<std::string>{"bumpy", "grid"}));
  ASSERT_EQ(e.polylines.size(), 1u);
  EXPECT_EQ(e.polylines[0].kind, static_cast<std::uint32_t>(MCON_POLYLINE_GUIDE));
  EXPECT_EQ(e.polylines[0].points[1].barycentric[1], 1.0);
  ASSERT_EQ(e.singularities.size(), 1u);
  EXPECT_EQ(e.singularities[0].index_quarters, -1);
  ASSERT_EQ(e.fields.size(), 2u);
  EXPECT_EQ(e.fields[0].labels, std::vector<std::int32_t>(patches[1].vertex_count(), 1));
  EXPECT_EQ(e.fields[1].values, std::vector<double>(patches[1].vertex_count(), 0.5));
  EXPECT_EQ(e.descriptors.size(), 9 * patches[1].vertex_count());
  EXPECT_EQ(lib.entry_positions(1).size(), 3 * patches[1].vertex_count());
  EXPECT_EQ(lib.entry_triangles(1).size(), 3 * patches[1].triangle_count());
  EXPECT_EQ(lib.entry_histogram(1).size(), 8u * o.rings);  // k words per ring
  EXPECT_FALSE(e.up.has_value());
  ASSERT_TRUE(lib.entry(2).up.has_value());
  EXPECT_EQ(*lib.entry(2).up, (std::array<double, 3>{{0, 0, 1}}));

  // Bytes round trip; merge of a copy; remove.
  const std::vector<std::uint8_t> bytes = lib.save_memory();
  macrocon::Library copy = macrocon::Library::open_memory(ctx, bytes.data(), bytes.size());
  EXPECT_EQ(copy.save_memory(), bytes);
  lib.merge(copy);
  EXPECT_EQ(lib.size(), 6u);
  EXPECT_EQ(lib.query(patches[2], 2)[1].distance, 0.0);
  lib.remove(ids[0]);
  EXPECT_EQ(lib.size(), 5u);
  EXPECT_EQ(error_of([&] { lib.find(ids[0]); }).status(), MCON_ERROR_NOT_FOUND);
  EXPECT_EQ(error_of([&] { macrocon::Library::open(ctx, "/nonexistent/dir/lib.mclb"); }).status(), MCON_ERROR_IO);

  // Copy = retain (the same library), move = steal.
  macrocon::Library same = lib;
  same.remove(ids[1]);
  EXPECT_EQ(lib.size(), 4u);
  macrocon::Library moved = std::move(same);
  EXPECT_FALSE(same);
  EXPECT_EQ(error_of([&] { same.size(); }).status(), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(moved.size(), 4u);
}

TEST(CppWrapper, LibraryDescriptorStringsAndBuildProgress) {
  macrocon::Context ctx;
  const Flat g = flat(mcon::test_meshes::make_bumpy_grid(31));
  const macrocon::Mesh mesh = macrocon::Mesh::from_arrays(ctx, g.xyz, g.tris);
  macrocon::Library lib = macrocon::Library::create(ctx);
  lib.set_descriptor(macrocon::retrieval_descriptor_from_name("hks"));
  lib.set_string(MCON_LIBRARY_NAME, "grid regions");
  EXPECT_EQ(lib.string(MCON_LIBRARY_DESCRIPTOR), "hks");
  EXPECT_EQ(lib.string(MCON_LIBRARY_NAME), "grid regions");
  EXPECT_EQ(error_of([&] { lib.set_string(MCON_LIBRARY_NAME, std::string("a\0b", 3)); }).status(),
            MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(error_of([&] { macrocon::retrieval_descriptor_from_name("sift"); }).status(), MCON_ERROR_INVALID_ARGUMENT);
  for (std::uint32_t v : {15u * 31 + 15, 8u * 31 + 8})
    lib.add(macrocon::Patch::extract(mesh, macrocon::PatchOptions::at_vertex(v, 0.3)), macrocon::EntryData{});
  EXPECT_EQ(lib.info().descriptor_dimension, 100u);

  mcon_retrieval_options o = macrocon::Library::default_retrieval_options();
  o.descriptor = MCON_RETRIEVAL_DESCRIPTOR_HKS;
  o.vocabulary_size = 4;
  double last = -1;
  lib.build_retrieval(o, [&](double f) {
    last = f;
    return true;
  });
  EXPECT_EQ(last, 1.0);
  EXPECT_EQ(lib.info().vocabulary_size, 4u);
  // A callback's exception cancels the build and comes back out; the library is unchanged.
  o.vocabulary_size = 2;
  EXPECT_THROW(lib.build_retrieval(o, [](double) -> bool { throw std::runtime_error("stop"); }), std::runtime_error);
  EXPECT_EQ(lib.info().vocabulary_size, 4u);
}

TEST(CppWrapper, ShutdownRefusesWhileAContextLivesThenSucceeds) {
  {
    macrocon::Context ctx;
    EXPECT_EQ(error_of([] { macrocon::shutdown(); }).status(), MCON_ERROR_INVALID_ARGUMENT);
  }
  EXPECT_NO_THROW(macrocon::shutdown());
  EXPECT_NO_THROW(macrocon::shutdown());  // twice is fine
  macrocon::Context again;                // and the library works afterwards
  EXPECT_TRUE(again);
}

TEST(CppWrapper, MeshReportsItsOrientationRepair) {
  macrocon::Context ctx;
  const Flat g = flat(mcon::test_meshes::make_icosphere(1));
  Flat inward = g;
  for (std::size_t t = 0; t < inward.tris.size(); t += 3) std::swap(inward.tris[t + 1], inward.tris[t + 2]);
  const macrocon::Mesh a = macrocon::Mesh::from_arrays(ctx, g.xyz, g.tris);
  const macrocon::Mesh b = macrocon::Mesh::from_arrays(ctx, g.xyz, inward.tris);
  EXPECT_EQ(a.orientation().reoriented_triangles, 0u);
  const mcon_mesh_orientation_info o = b.orientation();
  EXPECT_EQ(o.reoriented_triangles, 80u);
  EXPECT_EQ(o.outward_turned_component_count, 1u);
  EXPECT_EQ(o.closed_component_count, 1u);
  EXPECT_EQ(b.reoriented_triangles(), std::vector<std::uint8_t>(80, 1));
  EXPECT_EQ(b.triangles(), g.tris);
  EXPECT_EQ(a.triangles(), g.tris);
  EXPECT_EQ(error_of([] { macrocon::Mesh().orientation(); }).status(), MCON_ERROR_NULL_POINTER);
}

// mcon_mesh_*: strided float and double arrays, copy semantics, and every validation error
// with a message naming the first offending element.
#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "capi/capi_test_util.h"

using namespace capi_test;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// An interleaved vertex as a renderer would have it: the fields around the position hold NaN,
// so reading the wrong bytes makes a NON_FINITE error instead of passing silently.
template <typename Scalar>
struct Vertex {
  Scalar normal[3];
  Scalar position[3];
  Scalar uv[2];
};

// A triangle record with an extra field that is an out-of-range index if read as one.
struct IndexRecord {
  uint32_t material;
  uint32_t abc[3];
};

template <typename Scalar>
void check_strided(mcon_scalar_type type) {
  const mcon::TriMesh grid = mcon::test_meshes::make_grid(6, 2.0, 0.3);
  const Scalar nan = std::numeric_limits<Scalar>::quiet_NaN();
  auto vertices = std::make_unique<Vertex<Scalar>[]>(grid.positions.size());
  for (size_t i = 0; i < grid.positions.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      vertices[i].normal[k] = nan;
      vertices[i].position[k] = static_cast<Scalar>(grid.positions[i][k]);
    }
    vertices[i].uv[0] = vertices[i].uv[1] = nan;
  }
  auto records = std::make_unique<IndexRecord[]>(grid.triangles.size());
  for (size_t t = 0; t < grid.triangles.size(); ++t) {
    records[t].material = 0xFFFFFFFFu;
    for (int k = 0; k < 3; ++k) records[t].abc[k] = static_cast<uint32_t>(grid.triangles[t][k]);
  }

  ContextPtr ctx = make_context();
  mcon_mesh_desc d;
  ASSERT_EQ(mcon_mesh_desc_init(&d), MCON_OK);
  d.positions = &vertices[0].position[0];
  d.position_type = type;
  d.position_stride = sizeof(Vertex<Scalar>);
  d.vertex_count = grid.positions.size();
  d.indices = &records[0].abc[0];
  d.index_stride = sizeof(IndexRecord);
  d.triangle_count = grid.triangles.size();
  mcon_mesh m = nullptr;
  ASSERT_EQ(mcon_mesh_create(ctx.get(), &d, &m), MCON_OK) << last_message();
  MeshPtr mesh(m);
  // The arrays are copied: destroying them leaves the mesh intact.
  vertices.reset();
  records.reset();
  size_t nv = 0, nt = 0;
  ASSERT_EQ(mcon_mesh_get_counts(mesh.get(), &nv, &nt), MCON_OK);
  EXPECT_EQ(nv, grid.positions.size());
  EXPECT_EQ(nt, grid.triangles.size());

  // The same data read with a wrong stride hits the NaN fields or the bad index field.
  std::vector<Vertex<Scalar>> again(grid.positions.size());
  std::vector<IndexRecord> again_records(grid.triangles.size());
  for (size_t i = 0; i < again.size(); ++i) {
    for (int k = 0; k < 3; ++k) {
      again[i].normal[k] = nan;
      again[i].position[k] = static_cast<Scalar>(grid.positions[i][k]);
    }
    again[i].uv[0] = again[i].uv[1] = nan;
  }
  for (size_t t = 0; t < again_records.size(); ++t) {
    again_records[t].material = 0xFFFFFFFFu;
    for (int k = 0; k < 3; ++k) again_records[t].abc[k] = static_cast<uint32_t>(grid.triangles[t][k]);
  }
  d.positions = &again[0].position[0];
  d.indices = &again_records[0].abc[0];
  d.position_stride = 0;  // packed: wrong for this layout
  EXPECT_EQ(mcon_mesh_create(ctx.get(), &d, &m), MCON_ERROR_NON_FINITE);
  d.position_stride = sizeof(Vertex<Scalar>);
  d.index_stride = 0;
  EXPECT_EQ(mcon_mesh_create(ctx.get(), &d, &m), MCON_ERROR_INDEX_OUT_OF_RANGE);
}

// Two triangles of a unit square: the smallest valid mesh (4 vertices).
Arrays square() {
  Arrays a;
  a.positions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  a.indices = {0, 1, 2, 0, 2, 3};
  return a;
}

void expect_error(mcon_context ctx, const Arrays& a, mcon_status expected, const std::string& names) {
  EXPECT_EQ(create_status(ctx, a), expected) << last_message();
  EXPECT_EQ(mcon_get_last_error(nullptr, nullptr), expected);
  EXPECT_NE(last_message().find(names), std::string::npos) << "message \"" << last_message()
                                                             << "\" should name \"" << names << "\"";
  EXPECT_NE(last_message().find("mcon_mesh_create"), std::string::npos) << last_message();
}

// n quads around a circle, the last one joined with a half twist.
Arrays moebius_strip(int n) {
  Arrays a;
  for (int i = 0; i < n; ++i) {
    const double u = 2 * M_PI * i / n;
    for (const double s : {-0.3, 0.3})
      a.positions.insert(a.positions.end(), {(1 + s * std::cos(u / 2)) * std::cos(u),
                                             (1 + s * std::cos(u / 2)) * std::sin(u), s * std::sin(u / 2)});
  }
  for (uint32_t i = 0; i < static_cast<uint32_t>(n); ++i) {
    const uint32_t b = 2 * i, c = i + 1 < static_cast<uint32_t>(n) ? 2 * (i + 1) : 1,
                   d = i + 1 < static_cast<uint32_t>(n) ? 2 * (i + 1) + 1 : 0;
    a.indices.insert(a.indices.end(), {b, c, d, b, d, b + 1});
  }
  return a;
}

mcon_mesh_orientation_info orientation_of(mcon_mesh mesh) {
  mcon_mesh_orientation_info info;
  EXPECT_EQ(mcon_mesh_orientation_info_init(&info), MCON_OK);
  EXPECT_EQ(mcon_mesh_get_orientation(mesh, &info), MCON_OK) << last_message();
  return info;
}

}  // namespace

TEST(CapiMesh, FromStridedFloatArrays) { check_strided<float>(MCON_SCALAR_FLOAT32); }
TEST(CapiMesh, FromStridedDoubleArrays) { check_strided<double>(MCON_SCALAR_FLOAT64); }

TEST(CapiMesh, FromPackedArraysExactlySized) {
  // Exactly sized heap blocks: reading one element too far is caught by the sanitizer build.
  const Arrays src = arrays_of(mcon::test_meshes::make_icosphere(2));
  auto positions = std::make_unique<float[]>(src.positions.size());
  for (size_t i = 0; i < src.positions.size(); ++i) positions[i] = static_cast<float>(src.positions[i]);
  auto indices = std::make_unique<uint32_t[]>(src.indices.size());
  std::memcpy(indices.get(), src.indices.data(), src.indices.size() * sizeof(uint32_t));
  ContextPtr ctx = make_context();
  mcon_mesh_desc d;
  ASSERT_EQ(mcon_mesh_desc_init(&d), MCON_OK);
  d.positions = positions.get();
  d.position_type = MCON_SCALAR_FLOAT32;
  d.vertex_count = src.vertex_count();
  d.indices = indices.get();
  d.triangle_count = src.triangle_count();
  mcon_mesh m = nullptr;
  ASSERT_EQ(mcon_mesh_create(ctx.get(), &d, &m), MCON_OK) << last_message();
  size_t nv = 0, nt = 0;
  EXPECT_EQ(mcon_mesh_get_counts(m, &nv, &nt), MCON_OK);
  EXPECT_EQ(nv, 162u);
  EXPECT_EQ(nt, 320u);
  EXPECT_EQ(mcon_mesh_release(m), MCON_OK);
}

TEST(CapiMesh, DescInitRequiresAnExplicitScalarType) {
  mcon_mesh_desc d;
  std::memset(&d, 0x5A, sizeof(d));
  ASSERT_EQ(mcon_mesh_desc_init(&d), MCON_OK);
  EXPECT_EQ(d.struct_size, sizeof(mcon_mesh_desc));
  EXPECT_EQ(d.positions, nullptr);
  EXPECT_EQ(d.indices, nullptr);
  EXPECT_EQ(d.position_stride, 0u);
  EXPECT_EQ(d.index_stride, 0u);
  EXPECT_EQ(d.vertex_count, 0u);
  EXPECT_EQ(d.triangle_count, 0u);
  EXPECT_EQ(d.position_type, 0u);
  EXPECT_EQ(mcon_mesh_desc_init(nullptr), MCON_ERROR_NULL_POINTER);

  ContextPtr ctx = make_context();
  const Arrays a = square();
  for (uint32_t type : {0u, 3u, 0xFFFFFFFFu}) {
    mcon_mesh_desc bad = desc_of(a);
    bad.position_type = type;
    mcon_mesh m = nullptr;
    EXPECT_EQ(mcon_mesh_create(ctx.get(), &bad, &m), MCON_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(last_message().find("position_type " + std::to_string(type)), std::string::npos) << last_message();
  }
}

TEST(CapiMesh, EachValidationErrorNamesTheFirstOffendingElement) {
  ContextPtr ctx = make_context();
  const Arrays grid = arrays_of(mcon::test_meshes::make_grid(4));  // 16 vertices, 18 triangles

  Arrays a = grid;
  a.positions[3 * 5 + 2] = kNaN;
  expect_error(ctx.get(), a, MCON_ERROR_NON_FINITE, "vertex 5");
  a = grid;
  a.positions[3 * 7] = std::numeric_limits<double>::infinity();
  a.positions[3 * 9] = kNaN;
  expect_error(ctx.get(), a, MCON_ERROR_NON_FINITE, "vertex 7");

  a = grid;
  a.indices[3 * 4 + 1] = 16;
  expect_error(ctx.get(), a, MCON_ERROR_INDEX_OUT_OF_RANGE, "triangle 4");
  EXPECT_NE(last_message().find("16"), std::string::npos) << last_message();
  a.indices[3 * 4 + 1] = 0xFFFFFFFFu;
  expect_error(ctx.get(), a, MCON_ERROR_INDEX_OUT_OF_RANGE, "4294967295");

  a = grid;
  a.indices[3 * 3 + 2] = a.indices[3 * 3];
  expect_error(ctx.get(), a, MCON_ERROR_REPEATED_INDEX, "triangle 3");

  // Degenerate: move a vertex onto the line through two others of its triangle.
  a = square();
  a.positions = {0, 0, 0, 1, 0, 0, 2, 0, 0, 0, 1, 0};
  expect_error(ctx.get(), a, MCON_ERROR_DEGENERATE_TRIANGLE, "triangle 0");

  // A third triangle on edge (0, 2) of the square.
  a = square();
  a.positions.insert(a.positions.end(), {0.5, 0.5, 1});
  a.indices.insert(a.indices.end(), {0, 2, 4});
  expect_error(ctx.get(), a, MCON_ERROR_NON_MANIFOLD_EDGE, "edge (0, 2)");
  // A Moebius strip (a strip of 12 quads closed with a half twist) has no consistent orientation.
  a = moebius_strip(12);
  expect_error(ctx.get(), a, MCON_ERROR_NON_ORIENTABLE, "not orientable");
  EXPECT_NE(last_message().find("cut the surface"), std::string::npos) << last_message();

  // Bowtie: two triangles sharing only vertex 2.
  a.positions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 2, 1, 0, 2, 2, 0};
  a.indices = {0, 1, 2, 2, 3, 4};
  expect_error(ctx.get(), a, MCON_ERROR_NON_MANIFOLD_VERTEX, "vertex 2");

  a = square();
  a.positions.insert(a.positions.end(), {5, 5, 5});
  expect_error(ctx.get(), a, MCON_ERROR_ISOLATED_VERTEX, "vertex 4");

  a = square();
  a.indices.clear();
  expect_error(ctx.get(), a, MCON_ERROR_EMPTY_MESH, "0 triangles");
  a = Arrays{};
  expect_error(ctx.get(), a, MCON_ERROR_EMPTY_MESH, "0 vertices");
}

TEST(CapiMesh, RejectsNullPointersStridesAndStructSize) {
  ContextPtr ctx = make_context();
  const Arrays a = square();
  mcon_mesh m = nullptr;
  mcon_mesh_desc d = desc_of(a);

  EXPECT_EQ(mcon_mesh_create(nullptr, &d, &m), MCON_ERROR_NULL_POINTER);
  EXPECT_NE(last_message().find("context"), std::string::npos) << last_message();
  EXPECT_EQ(mcon_mesh_create(ctx.get(), nullptr, &m), MCON_ERROR_NULL_POINTER);
  EXPECT_NE(last_message().find("desc"), std::string::npos) << last_message();
  EXPECT_EQ(mcon_mesh_create(ctx.get(), &d, nullptr), MCON_ERROR_NULL_POINTER);
  EXPECT_NE(last_message().find("out_mesh"), std::string::npos) << last_message();

  d.positions = nullptr;
  EXPECT_EQ(mcon_mesh_create(ctx.get(), &d, &m), MCON_ERROR_NULL_POINTER);
  EXPECT_NE(last_message().find("positions"), std::string::npos) << last_message();
  d = desc_of(a);
  d.indices = nullptr;
  EXPECT_EQ(mcon_mesh_create(ctx.get(), &d, &m), MCON_ERROR_NULL_POINTER);
  EXPECT_NE(last_message().find("indices"), std::string::npos) << last_message();

  d = desc_of(a);
  d.position_stride = 16;  // less than 3 doubles
  EXPECT_EQ(mcon_mesh_create(ctx.get(), &d, &m), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_message().find("position_stride 16"), std::string::npos) << last_message();
  d = desc_of(a);
  d.index_stride = 8;
  EXPECT_EQ(mcon_mesh_create(ctx.get(), &d, &m), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_message().find("index_stride 8"), std::string::npos) << last_message();
  // A stride that would wrap around the address space is refused before anything is read.
  d = desc_of(a);
  d.position_stride = std::numeric_limits<size_t>::max() / 2;
  EXPECT_EQ(mcon_mesh_create(ctx.get(), &d, &m), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_message().find("overflow"), std::string::npos) << last_message();
  d = desc_of(a);
  d.index_stride = std::numeric_limits<size_t>::max() - 4;  // 2 triangles: 1 * stride + 12 wraps
  EXPECT_EQ(mcon_mesh_create(ctx.get(), &d, &m), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_message().find("indices"), std::string::npos) << last_message();

  d = desc_of(a);
  for (uint32_t size : {0u, 8u, static_cast<uint32_t>(offsetof(mcon_mesh_desc, index_format) - 1)}) {
    d.struct_size = size;
    EXPECT_EQ(mcon_mesh_create(ctx.get(), &d, &m), MCON_ERROR_STRUCT_SIZE) << size;
    EXPECT_NE(last_message().find("mcon_mesh_desc.struct_size"), std::string::npos) << last_message();
  }
  // A newer header's larger struct works.
  struct Newer {
    mcon_mesh_desc v1;
    double future[4];
  } newer{desc_of(a), {kNaN, kNaN, kNaN, kNaN}};
  newer.v1.struct_size = sizeof(Newer);
  ASSERT_EQ(mcon_mesh_create(ctx.get(), &newer.v1, &m), MCON_OK) << last_message();
  EXPECT_EQ(mcon_mesh_release(m), MCON_OK);

  // Handles of the wrong type.
  Garbage g;
  d = desc_of(a);
  EXPECT_EQ(mcon_mesh_create(reinterpret_cast<mcon_context>(&g), &d, &m), MCON_ERROR_INVALID_ARGUMENT);
  MeshPtr mesh = make_mesh(ctx.get(), a);
  EXPECT_EQ(mcon_mesh_create(reinterpret_cast<mcon_context>(mesh.get()), &d, &m), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_message().find("not a valid context"), std::string::npos) << last_message();
}

TEST(CapiMesh, GetCountsRetainReleaseRejectBadArguments) {
  ContextPtr ctx = make_context();
  MeshPtr mesh = make_mesh(ctx.get(), square());
  size_t nv = 7, nt = 7;
  EXPECT_EQ(mcon_mesh_get_counts(nullptr, &nv, &nt), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_mesh_get_counts(mesh.get(), nullptr, &nt), MCON_ERROR_NULL_POINTER);
  EXPECT_NE(last_message().find("vertex_count"), std::string::npos) << last_message();
  EXPECT_EQ(mcon_mesh_get_counts(mesh.get(), &nv, nullptr), MCON_ERROR_NULL_POINTER);
  Garbage g;
  EXPECT_EQ(mcon_mesh_get_counts(reinterpret_cast<mcon_mesh>(&g), &nv, &nt), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(mcon_mesh_get_counts(reinterpret_cast<mcon_mesh>(ctx.get()), &nv, &nt), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_message().find("not a valid mesh"), std::string::npos) << last_message();
  EXPECT_EQ(nv, 7u);  // nothing written on failure
  EXPECT_EQ(nt, 7u);

  EXPECT_EQ(mcon_mesh_retain(nullptr), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_mesh_release(nullptr), MCON_OK);
  EXPECT_EQ(mcon_mesh_retain(reinterpret_cast<mcon_mesh>(ctx.get())), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(mcon_mesh_release(reinterpret_cast<mcon_mesh>(ctx.get())), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(mcon_mesh_retain(reinterpret_cast<mcon_mesh>(&g)), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(mcon_mesh_release(reinterpret_cast<mcon_mesh>(&g)), MCON_ERROR_INVALID_ARGUMENT);

  // retain + release leaves one reference: the mesh still works.
  EXPECT_EQ(mcon_mesh_retain(mesh.get()), MCON_OK);
  EXPECT_EQ(mcon_mesh_release(mesh.get()), MCON_OK);
  EXPECT_EQ(mcon_mesh_get_counts(mesh.get(), &nv, &nt), MCON_OK);
  EXPECT_EQ(nv, 4u);
  EXPECT_EQ(nt, 2u);
}

// Inconsistent winding used to be rejected as NON_MANIFOLD_EDGE; it is repaired and reported.
TEST(CapiMesh, InconsistentAndInwardWindingIsRepairedAndReported) {
  ContextPtr ctx = make_context();
  Arrays a = square();
  a.indices = {0, 1, 2, 0, 3, 2};  // the second triangle of the square reversed
  MeshPtr mesh = make_mesh(ctx.get(), a);
  ASSERT_TRUE(mesh) << last_message();
  mcon_mesh_orientation_info info = orientation_of(mesh.get());
  EXPECT_EQ(info.reoriented_triangles, 1u);
  EXPECT_EQ(info.component_count, 1u);
  EXPECT_EQ(info.inconsistent_component_count, 1u);
  EXPECT_EQ(info.outward_turned_component_count, 0u);  // a plane has no outside: the first triangle wins
  uint8_t flags[2] = {9, 9};
  ASSERT_EQ(mcon_mesh_get_reoriented_triangles(mesh.get(), flags, 2), MCON_OK);
  EXPECT_EQ(flags[0], 0);
  EXPECT_EQ(flags[1], 1);
  uint32_t tri[6] = {};
  ASSERT_EQ(mcon_mesh_get_triangles(mesh.get(), tri, 6), MCON_OK);
  EXPECT_EQ(std::vector<uint32_t>(tri, tri + 6), (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));

  // An inward sphere is turned outward as a whole.
  mcon::TriMesh sphere = mcon::test_meshes::make_icosphere(2);
  for (mcon::Tri& t : sphere.triangles) std::swap(t[1], t[2]);
  MeshPtr inward = make_mesh(ctx.get(), arrays_of(sphere));
  ASSERT_TRUE(inward) << last_message();
  info = orientation_of(inward.get());
  EXPECT_EQ(info.reoriented_triangles, sphere.triangles.size());
  EXPECT_EQ(info.closed_component_count, 1u);
  EXPECT_EQ(info.outward_turned_component_count, 1u);
  EXPECT_EQ(info.inconsistent_component_count, 0u);
}

TEST(CapiMesh, OrientationGettersRejectBadArguments) {
  ContextPtr ctx = make_context();
  MeshPtr mesh = make_mesh(ctx.get(), square());
  ASSERT_TRUE(mesh);
  mcon_mesh_orientation_info info;
  EXPECT_EQ(mcon_mesh_orientation_info_init(nullptr), MCON_ERROR_NULL_POINTER);
  ASSERT_EQ(mcon_mesh_orientation_info_init(&info), MCON_OK);
  EXPECT_EQ(mcon_mesh_get_orientation(nullptr, &info), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_mesh_get_orientation(mesh.get(), nullptr), MCON_ERROR_NULL_POINTER);
  info.struct_size = 3;
  EXPECT_EQ(mcon_mesh_get_orientation(mesh.get(), &info), MCON_ERROR_STRUCT_SIZE);
  uint8_t flags[2];
  EXPECT_EQ(mcon_mesh_get_reoriented_triangles(nullptr, flags, 2), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_mesh_get_reoriented_triangles(mesh.get(), nullptr, 2), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_mesh_get_reoriented_triangles(mesh.get(), flags, 1), MCON_ERROR_BUFFER_TOO_SMALL);
  uint32_t tri[6];
  EXPECT_EQ(mcon_mesh_get_triangles(nullptr, tri, 6), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_mesh_get_triangles(mesh.get(), nullptr, 6), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_mesh_get_triangles(mesh.get(), tri, 5), MCON_ERROR_BUFFER_TOO_SMALL);
}

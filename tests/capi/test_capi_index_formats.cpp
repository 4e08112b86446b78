// mcon_mesh_desc.index_format: uint32, int32 and int64 triangle arrays (packed and strided) give
// the same mesh, the same patches and the same map bit for bit; negative and too large indices
// are INDEX_OUT_OF_RANGE naming the triangle, the value and the valid range; an unknown format is
// INVALID_ARGUMENT naming the field; a caller whose struct_size ends before the field gets uint32.
#include <gtest/gtest.h>

#include <cstddef>
#include <cstring>
#include <limits>
#include <memory>
#include <string>
#include <type_traits>
#include <vector>

#include "map_test_util.h"

using namespace map_test;

namespace {

// The triangles of `a` as Index values, packed.
template <typename Index>
std::vector<Index> converted(const Arrays& a) {
  return std::vector<Index>(a.indices.begin(), a.indices.end());
}

template <typename Index>
mcon_index_format format_of() {
  if (std::is_same<Index, std::int64_t>::value) return MCON_INDEX_FORMAT_INT64;
  if (std::is_same<Index, std::int32_t>::value) return MCON_INDEX_FORMAT_INT32;
  return MCON_INDEX_FORMAT_UINT32;
}

mcon_mesh_desc desc_with(const Arrays& a, const void* indices, mcon_index_format format, size_t stride = 0) {
  mcon_mesh_desc d = desc_of(a);
  d.indices = static_cast<const uint32_t*>(indices);
  d.index_format = format;
  d.index_stride = stride;
  return d;
}

MeshPtr create(mcon_context ctx, const mcon_mesh_desc& d) {
  mcon_mesh m = nullptr;
  EXPECT_EQ(mcon_mesh_create(ctx, &d, &m), MCON_OK) << last_message();
  return MeshPtr(m);
}

std::vector<uint32_t> triangles_of(mcon_mesh m) {
  size_t nv = 0, nt = 0;
  EXPECT_EQ(mcon_mesh_get_counts(m, &nv, &nt), MCON_OK);
  std::vector<uint32_t> t(3 * nt);
  EXPECT_EQ(mcon_mesh_get_triangles(m, t.data(), t.size()), MCON_OK);
  return t;
}

// A triangle record of a production mesh: a material id before the indices and a tag after them,
// both out-of-range indices if read as ones (so a wrong stride or offset is an error).
template <typename Index>
struct Record {
  Index material;
  Index abc[3];
  Index tag;
};

template <typename Index>
std::vector<Record<Index>> records_of(const Arrays& a) {
  std::vector<Record<Index>> r(a.triangle_count());
  for (size_t t = 0; t < r.size(); ++t) {
    r[t].material = static_cast<Index>(-1);
    r[t].tag = static_cast<Index>(0x7FFFFFF0);
    for (int k = 0; k < 3; ++k) r[t].abc[k] = static_cast<Index>(a.indices[3 * t + k]);
  }
  return r;
}

template <typename Index>
void expect_same_mesh_packed_and_strided() {
  ContextPtr ctx = make_context();
  const Arrays a = arrays_of(mcon::test_meshes::make_grid(6, 2.0, 0.3));
  MeshPtr ref = make_mesh(ctx.get(), a);
  const std::vector<Index> packed = converted<Index>(a);
  MeshPtr m = create(ctx.get(), desc_with(a, packed.data(), format_of<Index>()));
  ASSERT_NE(m, nullptr);
  EXPECT_EQ(triangles_of(m.get()), triangles_of(ref.get()));
  // Explicitly packed: the stride of 3 indices of this type.
  MeshPtr explicit_stride = create(ctx.get(), desc_with(a, packed.data(), format_of<Index>(), 3 * sizeof(Index)));
  ASSERT_NE(explicit_stride, nullptr);
  EXPECT_EQ(triangles_of(explicit_stride.get()), triangles_of(ref.get()));
  const auto records = records_of<Index>(a);
  MeshPtr strided = create(ctx.get(), desc_with(a, &records[0].abc[0], format_of<Index>(), sizeof(Record<Index>)));
  ASSERT_NE(strided, nullptr);
  EXPECT_EQ(triangles_of(strided.get()), triangles_of(ref.get()));
}

void expect_out_of_range(mcon_context ctx, const mcon_mesh_desc& d, const std::string& value) {
  mcon_mesh m = reinterpret_cast<mcon_mesh>(&m);
  EXPECT_EQ(mcon_mesh_create(ctx, &d, &m), MCON_ERROR_INDEX_OUT_OF_RANGE) << value;
  EXPECT_EQ(m, nullptr);
  const std::string msg = last_message();
  EXPECT_NE(msg.find("triangle 4 "), std::string::npos) << msg;
  EXPECT_NE(msg.find("vertex index " + value + ","), std::string::npos) << msg;
  EXPECT_NE(msg.find("valid range [0, 16)"), std::string::npos) << msg;
}

}  // namespace

TEST(CapiIndexFormats, DescInitDefaultsToUint32) {
  mcon_mesh_desc d;
  std::memset(&d, 0x5A, sizeof d);
  ASSERT_EQ(mcon_mesh_desc_init(&d), MCON_OK);
  EXPECT_EQ(d.index_format, static_cast<uint32_t>(MCON_INDEX_FORMAT_UINT32));
  EXPECT_EQ(MCON_INDEX_FORMAT_UINT32, 0);
  EXPECT_EQ(MCON_INDEX_FORMAT_INT32, 1);
  EXPECT_EQ(MCON_INDEX_FORMAT_INT64, 2);
  // Appended at the end: everything before it kept its offset.
  EXPECT_EQ(offsetof(mcon_mesh_desc, index_format), offsetof(mcon_mesh_desc, triangle_count) + sizeof(size_t));
}

TEST(CapiIndexFormats, Uint32PackedAndStrided) { expect_same_mesh_packed_and_strided<uint32_t>(); }
TEST(CapiIndexFormats, Int32PackedAndStrided) { expect_same_mesh_packed_and_strided<int32_t>(); }
TEST(CapiIndexFormats, Int64PackedAndStrided) { expect_same_mesh_packed_and_strided<int64_t>(); }

TEST(CapiIndexFormats, TheStrideMustHoldThreeIndicesOfTheFormat) {
  ContextPtr ctx = make_context();
  const Arrays a = arrays_of(mcon::test_meshes::make_grid(4));
  const std::vector<int64_t> wide = converted<int64_t>(a);
  mcon_mesh m = nullptr;
  // 12 bytes is a uint32 triangle, not an int64 one.
  mcon_mesh_desc d = desc_with(a, wide.data(), MCON_INDEX_FORMAT_INT64, 12);
  EXPECT_EQ(mcon_mesh_create(ctx.get(), &d, &m), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_message().find("index_stride 12 is smaller than one triangle (24 bytes)"), std::string::npos)
      << last_message();
  const std::vector<int32_t> narrow = converted<int32_t>(a);
  d = desc_with(a, narrow.data(), MCON_INDEX_FORMAT_INT32, 8);
  EXPECT_EQ(mcon_mesh_create(ctx.get(), &d, &m), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_message().find("(12 bytes)"), std::string::npos) << last_message();
  // The address-space check uses the format's triangle size too.
  d = desc_with(a, wide.data(), MCON_INDEX_FORMAT_INT64, std::numeric_limits<size_t>::max() - 20);
  EXPECT_EQ(mcon_mesh_create(ctx.get(), &d, &m), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_message().find("overflow"), std::string::npos) << last_message();
}

TEST(CapiIndexFormats, NegativeAndTooLargeIndicesAreOutOfRange) {
  ContextPtr ctx = make_context();
  const Arrays a = arrays_of(mcon::test_meshes::make_grid(4));  // 16 vertices, 18 triangles
  for (const int32_t bad : {-1, std::numeric_limits<int32_t>::min(), 16, std::numeric_limits<int32_t>::max()}) {
    std::vector<int32_t> t = converted<int32_t>(a);
    t[3 * 4 + 1] = bad;
    expect_out_of_range(ctx.get(), desc_with(a, t.data(), MCON_INDEX_FORMAT_INT32), std::to_string(bad));
  }
  // int64: also values that would be valid if truncated to 32 bits (2^32 -> 0, 2^32 + 3 -> 3).
  for (const int64_t bad : {int64_t{-1}, int64_t{-5}, std::numeric_limits<int64_t>::min(), int64_t{16},
                            int64_t{1} << 32, (int64_t{1} << 32) + 3, std::numeric_limits<int64_t>::max()}) {
    std::vector<int64_t> t = converted<int64_t>(a);
    t[3 * 4 + 1] = bad;
    expect_out_of_range(ctx.get(), desc_with(a, t.data(), MCON_INDEX_FORMAT_INT64), std::to_string(bad));
  }
  // uint32 keeps its message shape (now with the range).
  std::vector<uint32_t> t = a.indices;
  t[3 * 4 + 1] = 0xFFFFFFFFu;
  expect_out_of_range(ctx.get(), desc_with(a, t.data(), MCON_INDEX_FORMAT_UINT32), "4294967295");
  // The same through mcon_patch_create_from_arrays.
  std::vector<int64_t> w = converted<int64_t>(a);
  w[3 * 4 + 1] = -7;
  const mcon_mesh_desc d = desc_with(a, w.data(), MCON_INDEX_FORMAT_INT64);
  mcon_patch_frame f;
  ASSERT_EQ(mcon_patch_frame_init(&f), MCON_OK);
  f.center_triangle = 0;
  mcon_patch p = nullptr;
  EXPECT_EQ(mcon_patch_create_from_arrays(ctx.get(), &d, &f, &p), MCON_ERROR_INDEX_OUT_OF_RANGE);
  EXPECT_NE(last_message().find("triangle 4 uses vertex index -7"), std::string::npos) << last_message();
}

TEST(CapiIndexFormats, UnknownFormatIsInvalidArgumentNamingTheField) {
  ContextPtr ctx = make_context();
  const Arrays a = arrays_of(mcon::test_meshes::make_grid(4));
  for (const uint32_t format : {3u, 4u, 0x80000000u, 0xFFFFFFFFu}) {
    mcon_mesh_desc d = desc_of(a);
    d.index_format = format;
    mcon_mesh m = nullptr;
    EXPECT_EQ(mcon_mesh_create(ctx.get(), &d, &m), MCON_ERROR_INVALID_ARGUMENT) << format;
    EXPECT_NE(last_message().find("index_format " + std::to_string(format)), std::string::npos) << last_message();
    EXPECT_NE(last_message().find("mcon_index_format"), std::string::npos) << last_message();
    mcon_patch_frame f;
    ASSERT_EQ(mcon_patch_frame_init(&f), MCON_OK);
    f.center_triangle = 0;
    mcon_patch p = nullptr;
    EXPECT_EQ(mcon_patch_create_from_arrays(ctx.get(), &d, &f, &p), MCON_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(last_message().find("index_format " + std::to_string(format)), std::string::npos) << last_message();
  }
}

TEST(CapiIndexFormats, OlderStructSizeReadsUint32WhateverFollows) {
  ContextPtr ctx = make_context();
  const Arrays a = arrays_of(mcon::test_meshes::make_grid(4));
  MeshPtr ref = make_mesh(ctx.get(), a);
  const size_t v1 = offsetof(mcon_mesh_desc, index_format);
  // A caller compiled against the first header: its struct ends at triangle_count, and whatever
  // lies behind it (here INT64, and an invalid value) is not its index_format.
  for (const uint32_t behind : {static_cast<uint32_t>(MCON_INDEX_FORMAT_INT64), 0xFFFFFFFFu}) {
    for (const size_t size : {v1, v1 + 1, v1 + 3}) {  // ends before or inside the field
      mcon_mesh_desc d = desc_of(a);
      d.index_format = behind;
      d.struct_size = static_cast<uint32_t>(size);
      MeshPtr m = create(ctx.get(), d);
      ASSERT_NE(m, nullptr) << size;
      EXPECT_EQ(triangles_of(m.get()), triangles_of(ref.get()));
    }
  }
  mcon_mesh_desc d = desc_of(a);
  d.struct_size = static_cast<uint32_t>(v1 - 1);
  mcon_mesh m = nullptr;
  EXPECT_EQ(mcon_mesh_create(ctx.get(), &d, &m), MCON_ERROR_STRUCT_SIZE);
  EXPECT_NE(last_message().find("expected at least " + std::to_string(v1)), std::string::npos) << last_message();
  // The full struct reads the field.
  const std::vector<int64_t> wide = converted<int64_t>(a);
  d = desc_with(a, wide.data(), MCON_INDEX_FORMAT_INT64);
  EXPECT_EQ(d.struct_size, sizeof(mcon_mesh_desc));
  MeshPtr full = create(ctx.get(), d);
  ASSERT_NE(full, nullptr);
  EXPECT_EQ(triangles_of(full.get()), triangles_of(ref.get()));
}

namespace {

struct PatchBits {
  std::vector<double> xyz, uv, t;
  std::vector<uint32_t> tri, v0, v1, host_tri;
  bool operator==(const PatchBits& o) const {
    auto same = [](const std::vector<double>& x, const std::vector<double>& y) {
      return x.size() == y.size() && std::memcmp(x.data(), y.data(), x.size() * sizeof(double)) == 0;
    };
    return same(xyz, o.xyz) && same(uv, o.uv) && same(t, o.t) && tri == o.tri && v0 == o.v0 && v1 == o.v1 &&
           host_tri == o.host_tri;
  }
};

PatchBits bits_of(mcon_patch p) {
  const PatchArrays a = arrays_of_patch(p);
  PatchBits b{a.xyz, a.uv, std::vector<double>(a.nv()), a.tri, std::vector<uint32_t>(a.nv()),
              std::vector<uint32_t>(a.nv()), std::vector<uint32_t>(a.nt())};
  EXPECT_EQ(mcon_patch_get_host_vertices(p, b.v0.data(), b.v1.data(), b.t.data(), a.nv()), MCON_OK);
  EXPECT_EQ(mcon_patch_get_host_triangles(p, b.host_tri.data(), a.nt()), MCON_OK);
  return b;
}

std::vector<double> phi_of(mcon_map m, size_t source_vertices) {
  std::vector<double> phi(2 * source_vertices);
  EXPECT_EQ(mcon_map_get_phi(m, phi.data(), phi.size()), MCON_OK);
  return phi;
}

PatchPtr from_arrays(mcon_context ctx, const PatchArrays& a, const void* tri, mcon_index_format format) {
  mcon_mesh_desc d;
  EXPECT_EQ(mcon_mesh_desc_init(&d), MCON_OK);
  d.positions = a.xyz.data();
  d.position_type = MCON_SCALAR_FLOAT64;
  d.vertex_count = a.nv();
  d.indices = static_cast<const uint32_t*>(tri);
  d.index_format = format;
  d.triangle_count = a.nt();
  mcon_patch_frame f;
  EXPECT_EQ(mcon_patch_frame_init(&f), MCON_OK);
  f.center_triangle = a.info.center_patch_triangle;
  for (int k = 0; k < 3; ++k) {
    f.center_barycentric[k] = a.info.center_barycentric[k];
    f.origin[k] = a.info.center[k];
  }
  f.scale = a.info.radius;
  mcon_patch p = nullptr;
  EXPECT_EQ(mcon_patch_create_from_arrays(ctx, &d, &f, &p), MCON_OK) << last_message();
  return PatchPtr(p);
}

}  // namespace

// The sample body through all three formats: the same host mesh, the same extracted patches, the
// same from-arrays patches and the same map, bit for bit.
TEST(CapiIndexFormats, BodyPatchesAndMapAreBitIdenticalAcrossFormats) {
  ContextPtr ctx = make_context();
  const Arrays& a = body().arrays;
  const std::vector<int32_t> t32 = converted<int32_t>(a);
  const std::vector<int64_t> t64 = converted<int64_t>(a);
  MeshPtr mu = make_mesh(ctx.get(), a);
  MeshPtr mi = create(ctx.get(), desc_with(a, t32.data(), MCON_INDEX_FORMAT_INT32));
  MeshPtr ml = create(ctx.get(), desc_with(a, t64.data(), MCON_INDEX_FORMAT_INT64));
  ASSERT_TRUE(mu && mi && ml);
  EXPECT_EQ(triangles_of(mi.get()), triangles_of(mu.get()));
  EXPECT_EQ(triangles_of(ml.get()), triangles_of(mu.get()));

  PatchPtr su = extract(mu.get(), 297, 0.45), tu = extract(mu.get(), 297, 0.55);
  PatchPtr si = extract(mi.get(), 297, 0.45), tl = extract(ml.get(), 297, 0.55);
  ASSERT_TRUE(su && tu && si && tl);
  EXPECT_TRUE(bits_of(si.get()) == bits_of(su.get()));
  EXPECT_TRUE(bits_of(tl.get()) == bits_of(tu.get()));

  // From-arrays patches of the source patch's own mesh, in each format.
  const PatchArrays s = arrays_of_patch(su.get());
  const std::vector<int32_t> s32(s.tri.begin(), s.tri.end());
  const std::vector<int64_t> s64(s.tri.begin(), s.tri.end());
  PatchPtr fu = from_arrays(ctx.get(), s, s.tri.data(), MCON_INDEX_FORMAT_UINT32);
  PatchPtr fi = from_arrays(ctx.get(), s, s32.data(), MCON_INDEX_FORMAT_INT32);
  PatchPtr fl = from_arrays(ctx.get(), s, s64.data(), MCON_INDEX_FORMAT_INT64);
  ASSERT_TRUE(fu && fi && fl);
  EXPECT_TRUE(bits_of(fi.get()) == bits_of(fu.get()));
  EXPECT_TRUE(bits_of(fl.get()) == bits_of(fu.get()));

  // The map from the uint32 patches and from the int32/int64 ones.
  MapPtr ref = compute(fu.get(), tu.get(), fast_options());
  MapPtr other = compute(fl.get(), tl.get(), fast_options());
  ASSERT_TRUE(ref && other);
  const std::vector<double> pr = phi_of(ref.get(), s.nv()), po = phi_of(other.get(), s.nv());
  ASSERT_EQ(pr.size(), po.size());
  EXPECT_EQ(std::memcmp(pr.data(), po.data(), pr.size() * sizeof(double)), 0);
  mcon_map_info ir, info_o;
  ASSERT_EQ(mcon_map_info_init(&ir), MCON_OK);
  ASSERT_EQ(mcon_map_info_init(&info_o), MCON_OK);
  ASSERT_EQ(mcon_map_get_info(ref.get(), &ir), MCON_OK);
  ASSERT_EQ(mcon_map_get_info(other.get(), &info_o), MCON_OK);
  EXPECT_EQ(std::memcmp(&ir.energy_total, &info_o.energy_total, sizeof(double)), 0);
  EXPECT_EQ(ir.iterations, info_o.iterations);
}

// Helpers for the constraint library tests (C ABI only): small patches cut from the MakeHuman
// sample body, entries carrying every kind of constraint and field, and reading entries back.
#pragma once

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "capi/capi_test_util.h"
#include "io/mesh_io.h"

namespace capi_test {

struct LibraryDeleter {
  void operator()(mcon_library l) const { EXPECT_EQ(mcon_library_release(l), MCON_OK); }
};
using LibraryPtr = std::unique_ptr<mcon_library_t, LibraryDeleter>;

// Landmark vertices of the sample body (samples/data/makehuman-landmarks.json) and a class each.
struct Landmark {
  uint32_t vertex;
  const char* name;
  const char* class_label;
};
inline const std::vector<Landmark>& landmarks() {
  // One side only: the MakeHuman base mesh is mirror-symmetric, and mirrored patches have the same
  // (mirror-invariant) descriptors, i.e. L1 distance 0.
  static const std::vector<Landmark> l = {{8021, "eye_l", "eye"},  {131, "face", "face"},  {297, "nose", "nose"},
                                          {537, "mouth", "mouth"}, {12222, "ear_l", "ear"}, {9865, "hand_l", "hand"}};
  return l;
}
// Small disks: 50-320 vertices each, so the suite stays fast under ASan.
constexpr double kRadius = 0.25;

// The body surface of the sample (group 'body': the first 13378 faces), read once.
inline const Arrays& body_arrays() {
  static const Arrays arrays = [] {
    mcon::io::MeshFileOptions o;
    o.face_end = 13378;
    return arrays_of(mcon::io::read_mesh(std::string(MACROCON_SOURCE_DIR) + "/samples/data/makehuman-body.obj.gz", o).mesh);
  }();
  return arrays;
}

inline LibraryPtr make_library(mcon_context ctx) {
  mcon_library l = nullptr;
  EXPECT_EQ(mcon_library_create(ctx, &l), MCON_OK) << last_message();
  return LibraryPtr(l);
}

inline PatchPtr make_patch(mcon_mesh mesh, uint32_t vertex, double radius = kRadius) {
  mcon_patch_options o;
  EXPECT_EQ(mcon_patch_options_init(&o), MCON_OK);
  o.center_vertex = vertex;
  o.radius = radius;
  mcon_patch p = nullptr;
  EXPECT_EQ(mcon_patch_extract(mesh, &o, &p), MCON_OK) << last_message();
  return PatchPtr(p);
}

inline mcon_patch_info patch_info(mcon_patch p) {
  mcon_patch_info i;
  EXPECT_EQ(mcon_patch_info_init(&i), MCON_OK);
  EXPECT_EQ(mcon_patch_get_info(p, &i), MCON_OK) << last_message();
  return i;
}

// Owns the arrays an mcon_library_entry_desc points into.
struct EntryContent {
  std::vector<mcon_surface_point> guide, feature;
  std::vector<mcon_polyline> polylines;
  std::vector<mcon_singularity> singularities;
  std::vector<double> sizing, direction, normal, uv;
  std::vector<int32_t> region;
  std::vector<mcon_vertex_field> fields;
  std::vector<const char*> tags;
  mcon_library_entry_desc desc{};
};

// A desc for `patch` with a guide, a closed feature, two singularities and one field of every kind
// (values derived from the vertex index, so a round trip can be checked exactly).
inline void fill_entry(EntryContent& c, mcon_patch patch, const char* name, const char* class_label, bool full = true) {
  const mcon_patch_info info = patch_info(patch);
  const size_t n = info.vertex_count;
  EXPECT_EQ(mcon_library_entry_desc_init(&c.desc), MCON_OK);
  c.desc.patch = patch;
  c.desc.name = name;
  c.desc.class_label = class_label;
  if (!full) return;
  c.desc.author = "Vendor GmbH";
  c.desc.licence = "CC-BY-4.0";
  c.tags.push_back("face");
  c.tags.push_back("symmetric");
  c.desc.tags = c.tags.data();
  c.desc.tag_count = c.tags.size();
  const uint32_t m = static_cast<uint32_t>(info.triangle_count);
  c.guide = {{0, {1, 0, 0}}, {m / 2, {0.25, 0.25, 0.5}}, {m - 1, {0, 0, 1}}};
  c.feature = {{1, {0.5, 0.5, 0}}, {2, {0.2, 0.3, 0.5}}, {3, {0, 0.5, 0.5}}};
  c.polylines = {{MCON_POLYLINE_GUIDE, 0, c.guide.data(), c.guide.size()},
                 {MCON_POLYLINE_FEATURE, 1, c.feature.data(), c.feature.size()}};
  c.desc.polylines = c.polylines.data();
  c.desc.polyline_count = c.polylines.size();
  c.singularities = {{{4, {0.5, 0.25, 0.25}}, 1}, {{m - 2, {0.1, 0.1, 0.8}}, -1}};
  c.desc.singularities = c.singularities.data();
  c.desc.singularity_count = c.singularities.size();
  for (size_t v = 0; v < n; ++v) {
    c.sizing.push_back(0.5 + static_cast<double>(v));
    c.direction.insert(c.direction.end(), {1.0, 0.0, 0.25 * static_cast<double>(v % 4)});
    c.normal.insert(c.normal.end(), {0.0, 0.0, 1.0});
    c.uv.insert(c.uv.end(), {0.125 * static_cast<double>(v % 8), -0.5});
    c.region.push_back(static_cast<int32_t>(v % 3) - 1);
  }
  c.fields = {{"sizing", MCON_FIELD_SCALAR, 1, c.sizing.data(), nullptr, 0},
              {"direction", MCON_FIELD_TANGENT_VECTOR, 3, c.direction.data(), nullptr, 0},
              {"normal", MCON_FIELD_VECTOR3, 3, c.normal.data(), nullptr, 3 * sizeof(double)},
              {"uv", MCON_FIELD_UV, 2, c.uv.data(), nullptr, 0},
              {"region", MCON_FIELD_INTEGER_LABEL, 1, nullptr, c.region.data(), 0}};
  c.desc.fields = c.fields.data();
  c.desc.field_count = c.fields.size();
}

inline mcon_library_info library_info(mcon_library l) {
  mcon_library_info i;
  EXPECT_EQ(mcon_library_info_init(&i), MCON_OK);
  EXPECT_EQ(mcon_library_get_info(l, &i), MCON_OK) << last_message();
  return i;
}

inline size_t library_count(mcon_library l) {
  size_t n = 0;
  EXPECT_EQ(mcon_library_get_count(l, &n), MCON_OK) << last_message();
  return n;
}

inline std::vector<uint8_t> save_bytes(mcon_library l) {
  size_t size = 0;
  EXPECT_EQ(mcon_library_save_memory(l, nullptr, 0, &size), MCON_OK) << last_message();
  std::vector<uint8_t> bytes(size);
  EXPECT_EQ(mcon_library_save_memory(l, bytes.data(), bytes.size(), &size), MCON_OK) << last_message();
  return bytes;
}

inline std::vector<uint8_t> read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<uint8_t>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

inline void write_bytes(const std::string& path, const std::vector<uint8_t>& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
}

struct QueryResult {
  std::vector<uint64_t> ids;
  std::vector<uint32_t> indices;
  std::vector<double> distances;
  bool operator==(const QueryResult& o) const {
    return ids == o.ids && indices == o.indices && distances == o.distances;
  }
};

inline QueryResult query(mcon_library l, mcon_patch p, size_t n) {
  QueryResult r;
  r.ids.resize(n);
  r.indices.resize(n);
  r.distances.resize(n);
  size_t count = 0;
  EXPECT_EQ(mcon_library_query(l, p, n, r.ids.data(), r.indices.data(), r.distances.data(), n, &count), MCON_OK)
      << last_message();
  r.ids.resize(count);
  r.indices.resize(count);
  r.distances.resize(count);
  return r;
}

inline mcon_retrieval_options small_options(uint32_t k = 16) {
  mcon_retrieval_options o;
  EXPECT_EQ(mcon_retrieval_options_init(&o), MCON_OK);
  o.vocabulary_size = k;
  return o;
}

inline std::string temp_path(const std::string& name) {
  return std::string(MACROCON_BINARY_DIR) + "/test_capi_library_" + name;
}

}  // namespace capi_test

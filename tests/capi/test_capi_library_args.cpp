// Negative tests of every mcon_library_* function: NULL and foreign handles, NULL outputs, bad
// struct_size, too-small capacities, bad indices and enum values, bad constraints and fields,
// forged and truncated files, unwritable save targets. Every failure must leave the library as it
// was (checked by comparing its saved bytes).
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <thread>

#include "capi/test_capi_library_util.h"

using namespace capi_test;

namespace {

class LibraryArgs : public ::testing::Test {
 protected:
  void SetUp() override {
    ctx_ = make_context();
    mesh_ = make_mesh(ctx_.get(), body_arrays());
    patch_ = make_patch(mesh_.get(), 297);  // the nose
    other_ = make_patch(mesh_.get(), 8021);
    lib_ = make_library(ctx_.get());
    EntryContent a, b;
    fill_entry(a, patch_.get(), "nose", "nose");
    fill_entry(b, other_.get(), "eye", "eye");
    ASSERT_EQ(mcon_library_add_entry(lib_.get(), &a.desc, nullptr), MCON_OK) << last_message();
    ASSERT_EQ(mcon_library_add_entry(lib_.get(), &b.desc, nullptr), MCON_OK) << last_message();
    mcon_retrieval_options o = small_options(4);
    ASSERT_EQ(mcon_library_build_retrieval(lib_.get(), &o), MCON_OK) << last_message();
    bytes_ = save_bytes(lib_.get());
    info_ = library_info(lib_.get());
    mcon_library_entry_info_init(&entry_);
    ASSERT_EQ(mcon_library_get_entry_info(lib_.get(), 0, &entry_), MCON_OK);
  }
  void expect_unchanged() { EXPECT_EQ(save_bytes(lib_.get()), bytes_); }

  ContextPtr ctx_;
  MeshPtr mesh_;
  PatchPtr patch_, other_;
  LibraryPtr lib_;
  std::vector<uint8_t> bytes_;
  mcon_library_info info_{};
  mcon_library_entry_info entry_{};
};

#define EXPECT_STATUS(call, status) EXPECT_EQ((call), (status)) << last_message()

TEST_F(LibraryArgs, NullAndForeignHandles) {
  Garbage g;
  auto bad = reinterpret_cast<mcon_library>(&g);
  size_t n = 0, size = 0, index = 0;
  uint64_t id = 0;
  mcon_library out = nullptr;
  mcon_library_info info;
  mcon_library_info_init(&info);
  mcon_library_entry_info ei;
  mcon_library_entry_info_init(&ei);
  mcon_retrieval_options o = small_options(4);
  EntryContent c;
  fill_entry(c, patch_.get(), "x", "x", false);
  double d[3];
  uint32_t u[3];
  float h[4];
  for (mcon_library l : {static_cast<mcon_library>(nullptr), bad}) {
    const mcon_status s = l == nullptr ? MCON_ERROR_NULL_POINTER : MCON_ERROR_INVALID_ARGUMENT;
    EXPECT_STATUS(mcon_library_retain(l), s);
    if (l != nullptr) {
      EXPECT_STATUS(mcon_library_release(l), s);
    }
    EXPECT_STATUS(mcon_library_save(l, "x.mclb"), s);
    EXPECT_STATUS(mcon_library_save_memory(l, nullptr, 0, &size), s);
    EXPECT_STATUS(mcon_library_get_info(l, &info), s);
    EXPECT_STATUS(mcon_library_get_count(l, &n), s);
    EXPECT_STATUS(mcon_library_get_string(l, MCON_LIBRARY_NAME, nullptr, 0, &size), s);
    EXPECT_STATUS(mcon_library_set_string(l, MCON_LIBRARY_NAME, "x"), s);
    EXPECT_STATUS(mcon_library_set_descriptor(l, MCON_RETRIEVAL_DESCRIPTOR_HKS), s);
    EXPECT_STATUS(mcon_library_add_entry(l, &c.desc, &id), s);
    EXPECT_STATUS(mcon_library_remove_entry(l, 1), s);
    EXPECT_STATUS(mcon_library_find_entry(l, 1, &index), s);
    EXPECT_STATUS(mcon_library_merge(l, lib_.get()), s);
    EXPECT_STATUS(mcon_library_merge(lib_.get(), l), s);
    EXPECT_STATUS(mcon_library_build_retrieval(l, &o), s);
    EXPECT_STATUS(mcon_library_query(l, patch_.get(), 1, &id, nullptr, nullptr, 1, &n), s);
    EXPECT_STATUS(mcon_library_query_descriptors(l, patch_.get(), d, 1, 0, 1, &id, nullptr, nullptr, 1, &n), s);
    EXPECT_STATUS(mcon_library_get_entry_info(l, 0, &ei), s);
    EXPECT_STATUS(mcon_library_get_entry_string(l, 0, MCON_ENTRY_NAME, 0, nullptr, 0, &size), s);
    EXPECT_STATUS(mcon_library_get_entry_positions(l, 0, d, 3), s);
    EXPECT_STATUS(mcon_library_get_entry_triangles(l, 0, u, 3), s);
    EXPECT_STATUS(mcon_library_get_entry_polyline(l, 0, 0, u, nullptr, nullptr, nullptr, 0), s);
    EXPECT_STATUS(mcon_library_get_entry_singularities(l, 0, nullptr, 0), s);
    EXPECT_STATUS(mcon_library_get_entry_field(l, 0, 0, u, nullptr, nullptr, nullptr, 0), s);
    EXPECT_STATUS(mcon_library_get_entry_retrieval(l, 0, nullptr, 0, h, 4), s);
  }
  EXPECT_EQ(mcon_library_release(nullptr), MCON_OK);  // like free(NULL)
  // Contexts and patches passed where they are needed.
  for (mcon_context cx : {static_cast<mcon_context>(nullptr), reinterpret_cast<mcon_context>(&g)}) {
    const mcon_status s = cx == nullptr ? MCON_ERROR_NULL_POINTER : MCON_ERROR_INVALID_ARGUMENT;
    out = reinterpret_cast<mcon_library>(&g);
    EXPECT_STATUS(mcon_library_create(cx, &out), s);
    EXPECT_EQ(out, nullptr);
    EXPECT_STATUS(mcon_library_open(cx, "x.mclb", &out), s);
    EXPECT_STATUS(mcon_library_open_memory(cx, bytes_.data(), bytes_.size(), &out), s);
  }
  for (mcon_patch p : {static_cast<mcon_patch>(nullptr), reinterpret_cast<mcon_patch>(&g)}) {
    const mcon_status s = p == nullptr ? MCON_ERROR_NULL_POINTER : MCON_ERROR_INVALID_ARGUMENT;
    EXPECT_STATUS(mcon_library_query(lib_.get(), p, 1, &id, nullptr, nullptr, 1, &n), s);
    EXPECT_STATUS(mcon_library_query_descriptors(lib_.get(), p, d, 9, 0, 1, &id, nullptr, nullptr, 1, &n), s);
    c.desc.patch = p;
    EXPECT_STATUS(mcon_library_add_entry(lib_.get(), &c.desc, &id), s);
  }
  expect_unchanged();
}

TEST_F(LibraryArgs, NullOutputsAndStructSizes) {
  EXPECT_STATUS(mcon_library_entry_desc_init(nullptr), MCON_ERROR_NULL_POINTER);
  EXPECT_STATUS(mcon_retrieval_options_init(nullptr), MCON_ERROR_NULL_POINTER);
  EXPECT_STATUS(mcon_library_info_init(nullptr), MCON_ERROR_NULL_POINTER);
  EXPECT_STATUS(mcon_library_entry_info_init(nullptr), MCON_ERROR_NULL_POINTER);
  EXPECT_STATUS(mcon_library_create(ctx_.get(), nullptr), MCON_ERROR_NULL_POINTER);
  mcon_library out = nullptr;
  EXPECT_STATUS(mcon_library_open(ctx_.get(), nullptr, &out), MCON_ERROR_NULL_POINTER);
  EXPECT_STATUS(mcon_library_open(ctx_.get(), "x", nullptr), MCON_ERROR_NULL_POINTER);
  EXPECT_STATUS(mcon_library_open_memory(ctx_.get(), nullptr, 10, &out), MCON_ERROR_NULL_POINTER);
  EXPECT_STATUS(mcon_library_open_memory(ctx_.get(), bytes_.data(), bytes_.size(), nullptr), MCON_ERROR_NULL_POINTER);
  EXPECT_STATUS(mcon_library_save(lib_.get(), nullptr), MCON_ERROR_NULL_POINTER);
  EXPECT_STATUS(mcon_library_save_memory(lib_.get(), nullptr, 0, nullptr), MCON_ERROR_NULL_POINTER);
  EXPECT_STATUS(mcon_library_get_info(lib_.get(), nullptr), MCON_ERROR_NULL_POINTER);
  EXPECT_STATUS(mcon_library_get_count(lib_.get(), nullptr), MCON_ERROR_NULL_POINTER);
  EXPECT_STATUS(mcon_library_add_entry(lib_.get(), nullptr, nullptr), MCON_ERROR_NULL_POINTER);
  EXPECT_STATUS(mcon_library_find_entry(lib_.get(), 1, nullptr), MCON_ERROR_NULL_POINTER);
  EXPECT_STATUS(mcon_library_get_entry_info(lib_.get(), 0, nullptr), MCON_ERROR_NULL_POINTER);
  EXPECT_STATUS(mcon_library_get_entry_positions(lib_.get(), 0, nullptr, 1000), MCON_ERROR_NULL_POINTER);
  EXPECT_STATUS(mcon_library_get_entry_triangles(lib_.get(), 0, nullptr, 1000), MCON_ERROR_NULL_POINTER);
  EXPECT_STATUS(mcon_library_get_entry_singularities(lib_.get(), 0, nullptr, 10), MCON_ERROR_NULL_POINTER);
  EXPECT_STATUS(mcon_library_query(lib_.get(), patch_.get(), 1, nullptr, nullptr, nullptr, 1, nullptr),
                MCON_ERROR_NULL_POINTER);
  size_t n = 0;
  EXPECT_STATUS(mcon_library_query_descriptors(lib_.get(), patch_.get(), nullptr, 9, 0, 1, nullptr, nullptr, nullptr,
                                               1, &n),
                MCON_ERROR_NULL_POINTER);

  // struct_size below the first version: refused, nothing written.
  mcon_library_info info;
  mcon_library_info_init(&info);
  info.struct_size = 4;
  EXPECT_STATUS(mcon_library_get_info(lib_.get(), &info), MCON_ERROR_STRUCT_SIZE);
  mcon_library_entry_info ei;
  mcon_library_entry_info_init(&ei);
  ei.struct_size = 8;
  EXPECT_STATUS(mcon_library_get_entry_info(lib_.get(), 0, &ei), MCON_ERROR_STRUCT_SIZE);
  EXPECT_EQ(ei.id, 0u);
  mcon_retrieval_options o = small_options(4);
  o.struct_size = 8;
  EXPECT_STATUS(mcon_library_build_retrieval(lib_.get(), &o), MCON_ERROR_STRUCT_SIZE);
  EntryContent c;
  fill_entry(c, patch_.get(), "x", "x");
  c.desc.struct_size = 16;
  EXPECT_STATUS(mcon_library_add_entry(lib_.get(), &c.desc, nullptr), MCON_ERROR_STRUCT_SIZE);
  // A larger struct (a newer caller) is fine; only the known part is written.
  struct Bigger {
    mcon_library_info info;
    uint64_t tail;
  } big;
  mcon_library_info_init(&big.info);
  big.info.struct_size = sizeof(Bigger);
  big.tail = 0xfeedu;
  EXPECT_STATUS(mcon_library_get_info(lib_.get(), &big.info), MCON_OK);
  EXPECT_EQ(big.info.entry_count, 2u);
  EXPECT_EQ(big.tail, 0xfeedu);
  expect_unchanged();
}

TEST_F(LibraryArgs, CapacitiesIndicesAndEnumValues) {
  const size_t nv = entry_.vertex_count, nt = entry_.triangle_count;
  std::vector<double> xyz(3 * nv);
  std::vector<uint32_t> tris(3 * nt);
  EXPECT_STATUS(mcon_library_get_entry_positions(lib_.get(), 0, xyz.data(), xyz.size() - 1), MCON_ERROR_BUFFER_TOO_SMALL);
  EXPECT_STATUS(mcon_library_get_entry_triangles(lib_.get(), 0, tris.data(), tris.size() - 1), MCON_ERROR_BUFFER_TOO_SMALL);
  EXPECT_STATUS(mcon_library_get_entry_positions(lib_.get(), 2, xyz.data(), xyz.size()), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_STATUS(mcon_library_get_entry_triangles(lib_.get(), SIZE_MAX, tris.data(), tris.size()),
                MCON_ERROR_INVALID_ARGUMENT);
  mcon_library_entry_info ei;
  mcon_library_entry_info_init(&ei);
  EXPECT_STATUS(mcon_library_get_entry_info(lib_.get(), 2, &ei), MCON_ERROR_INVALID_ARGUMENT);

  // Strings.
  size_t size = 0;
  char small[3];
  EXPECT_STATUS(mcon_library_get_entry_string(lib_.get(), 0, MCON_ENTRY_NAME, 0, small, sizeof small, &size),
                MCON_ERROR_BUFFER_TOO_SMALL);
  EXPECT_EQ(size, 5u);  // "nose" + NUL, reported even when the buffer is too small
  EXPECT_STATUS(mcon_library_get_entry_string(lib_.get(), 0, MCON_ENTRY_TAG, 2, nullptr, 0, &size),
                MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_STATUS(mcon_library_get_entry_string(lib_.get(), 0, MCON_ENTRY_FIELD_NAME, 5, nullptr, 0, &size),
                MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_STATUS(mcon_library_get_entry_string(lib_.get(), 0, static_cast<mcon_entry_string>(99), 0, nullptr, 0, &size),
                MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_STATUS(mcon_library_get_entry_string(lib_.get(), 7, MCON_ENTRY_NAME, 0, nullptr, 0, &size),
                MCON_ERROR_INVALID_ARGUMENT);

  // Polylines, singularities, fields, retrieval data.
  mcon_surface_point points[3];
  EXPECT_STATUS(mcon_library_get_entry_polyline(lib_.get(), 0, 0, nullptr, nullptr, nullptr, points, 2),
                MCON_ERROR_BUFFER_TOO_SMALL);
  EXPECT_STATUS(mcon_library_get_entry_polyline(lib_.get(), 0, 2, nullptr, nullptr, nullptr, points, 3),
                MCON_ERROR_INVALID_ARGUMENT);
  mcon_singularity sing[2];
  EXPECT_STATUS(mcon_library_get_entry_singularities(lib_.get(), 0, sing, 1), MCON_ERROR_BUFFER_TOO_SMALL);
  std::vector<double> values(3 * nv);
  std::vector<int32_t> labels(nv);
  EXPECT_STATUS(mcon_library_get_entry_field(lib_.get(), 0, 1, nullptr, nullptr, values.data(), nullptr, 3 * nv - 1),
                MCON_ERROR_BUFFER_TOO_SMALL);
  EXPECT_STATUS(mcon_library_get_entry_field(lib_.get(), 0, 5, nullptr, nullptr, values.data(), nullptr, 3 * nv),
                MCON_ERROR_INVALID_ARGUMENT);
  // The wrong one of values / labels.
  EXPECT_STATUS(mcon_library_get_entry_field(lib_.get(), 0, 4, nullptr, nullptr, values.data(), nullptr, 3 * nv),
                MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_STATUS(mcon_library_get_entry_field(lib_.get(), 0, 0, nullptr, nullptr, nullptr, labels.data(), nv),
                MCON_ERROR_INVALID_ARGUMENT);
  std::vector<double> desc(9 * nv);
  std::vector<float> hist(info_.histogram_length);
  EXPECT_STATUS(mcon_library_get_entry_retrieval(lib_.get(), 0, desc.data(), desc.size() - 1, nullptr, 0),
                MCON_ERROR_BUFFER_TOO_SMALL);
  EXPECT_STATUS(mcon_library_get_entry_retrieval(lib_.get(), 0, nullptr, 0, hist.data(), hist.size() - 1),
                MCON_ERROR_BUFFER_TOO_SMALL);
  EXPECT_STATUS(mcon_library_get_entry_retrieval(lib_.get(), 0, desc.data(), desc.size(), hist.data(), hist.size()),
                MCON_OK);

  // Queries: n = 0, capacity below min(n, count).
  uint64_t ids[2];
  size_t count = 0;
  EXPECT_STATUS(mcon_library_query(lib_.get(), patch_.get(), 0, ids, nullptr, nullptr, 2, &count),
                MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_STATUS(mcon_library_query(lib_.get(), patch_.get(), 2, ids, nullptr, nullptr, 1, &count),
                MCON_ERROR_BUFFER_TOO_SMALL);
  EXPECT_STATUS(mcon_library_query(lib_.get(), patch_.get(), 5, ids, nullptr, nullptr, 2, &count), MCON_OK);
  EXPECT_EQ(count, 2u);
  // Caller descriptors on a built-in library, or of the wrong dimension.
  EXPECT_STATUS(mcon_library_query_descriptors(lib_.get(), patch_.get(), desc.data(), 9, 0, 1, ids, nullptr, nullptr,
                                               2, &count),
                MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_STATUS(mcon_library_query_descriptors(lib_.get(), patch_.get(), desc.data(), 8, 0, 1, ids, nullptr, nullptr,
                                               2, &count),
                MCON_ERROR_INVALID_ARGUMENT);

  // Removing / finding unknown ids; save_memory into too small a buffer.
  EXPECT_STATUS(mcon_library_remove_entry(lib_.get(), 77), MCON_ERROR_NOT_FOUND);
  size_t index = 0;
  EXPECT_STATUS(mcon_library_find_entry(lib_.get(), 0, &index), MCON_ERROR_NOT_FOUND);
  std::vector<uint8_t> buffer(bytes_.size() - 1);
  size = 0;
  EXPECT_STATUS(mcon_library_save_memory(lib_.get(), buffer.data(), buffer.size(), &size), MCON_ERROR_BUFFER_TOO_SMALL);
  EXPECT_EQ(size, bytes_.size());
  expect_unchanged();
}

TEST_F(LibraryArgs, BuildRetrievalOptionsAreChecked) {
  auto build = [&](auto change) {
    mcon_retrieval_options o = small_options(4);
    change(o);
    return mcon_library_build_retrieval(lib_.get(), &o);
  };
  EXPECT_STATUS(build([](auto& o) { o.descriptor = 2; }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_STATUS(build([](auto& o) { o.descriptor = MCON_RETRIEVAL_DESCRIPTOR_CUSTOM; }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_STATUS(build([](auto& o) { o.vocabulary_size = 0; }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_STATUS(build([](auto& o) { o.rings = 0; }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_STATUS(build([](auto& o) { o.rings = 65; }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_STATUS(build([](auto& o) { o.sigma_bof = -1; }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_STATUS(build([](auto& o) { o.sigma_bof = std::nan(""); }), MCON_ERROR_NON_FINITE);
  expect_unchanged();
  // An empty library has nothing to build on.
  LibraryPtr empty = make_library(ctx_.get());
  mcon_retrieval_options o = small_options(4);
  EXPECT_STATUS(mcon_library_build_retrieval(empty.get(), &o), MCON_ERROR_INVALID_ARGUMENT);
  // NULL options = the defaults.
  EXPECT_STATUS(mcon_library_build_retrieval(lib_.get(), nullptr), MCON_OK);
  EXPECT_EQ(library_info(lib_.get()).rings, 1u);
}

TEST_F(LibraryArgs, BadConstraintsAndFieldsAreRefusedWithoutChange) {
  auto add = [&](auto change) {
    EntryContent c;
    fill_entry(c, patch_.get(), "bad", "bad");
    change(c);
    uint64_t id = 12345;
    const mcon_status s = mcon_library_add_entry(lib_.get(), &c.desc, &id);
    if (s != MCON_OK) {
      EXPECT_EQ(id, 12345u) << "out_id written on failure";
    }
    return s;
  };
  const uint32_t m = static_cast<uint32_t>(patch_info(patch_.get()).triangle_count);
  EXPECT_STATUS(add([&](EntryContent& c) { c.guide[1].face = m; }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_message().find("polylines[0].points[1]"), std::string::npos) << last_message();
  EXPECT_STATUS(add([](EntryContent& c) { c.guide[0].barycentric[0] = 1.5; }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_STATUS(add([](EntryContent& c) { c.guide[0].barycentric[1] = 0.5; }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_STATUS(add([](EntryContent& c) { c.feature[0].barycentric[0] = -0.5; }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_STATUS(add([](EntryContent& c) { c.guide[2].barycentric[2] = std::nan(""); }), MCON_ERROR_NON_FINITE);
  EXPECT_STATUS(add([](EntryContent& c) { c.polylines[1].point_count = 2; }), MCON_ERROR_INVALID_ARGUMENT);  // closed
  EXPECT_STATUS(add([](EntryContent& c) { c.polylines[0].kind = 3; }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_STATUS(add([](EntryContent& c) { c.polylines[0].points = nullptr; }), MCON_ERROR_NULL_POINTER);
  EXPECT_STATUS(add([](EntryContent& c) { c.desc.polylines = nullptr; }), MCON_ERROR_NULL_POINTER);
  EXPECT_STATUS(add([&](EntryContent& c) { c.singularities[0].location.face = m + 5; }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_STATUS(add([](EntryContent& c) { c.singularities[0].index_quarters = 0; }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_STATUS(add([](EntryContent& c) { c.singularities[1].location.barycentric[0] = INFINITY; }),
                MCON_ERROR_NON_FINITE);
  EXPECT_STATUS(add([](EntryContent& c) { c.desc.singularities = nullptr; }), MCON_ERROR_NULL_POINTER);
  // Fields.
  EXPECT_STATUS(add([](EntryContent& c) { c.sizing[3] = std::nan(""); }), MCON_ERROR_NON_FINITE);
  EXPECT_STATUS(add([](EntryContent& c) { c.uv[1] = 1e300; }), MCON_ERROR_NON_FINITE);  // not a float
  EXPECT_STATUS(add([](EntryContent& c) { c.fields[1].dimension = 2; }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_STATUS(add([](EntryContent& c) { c.fields[0].dimension = 0; }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_STATUS(add([](EntryContent& c) { c.fields[0].kind = 9; }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_STATUS(add([](EntryContent& c) { c.fields[0].name = ""; }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_STATUS(add([](EntryContent& c) { c.fields[0].name = nullptr; }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_STATUS(add([](EntryContent& c) { c.fields[1].name = "sizing"; }), MCON_ERROR_INVALID_ARGUMENT);  // repeated
  EXPECT_STATUS(add([](EntryContent& c) { c.fields[0].values = nullptr; }), MCON_ERROR_NULL_POINTER);
  EXPECT_STATUS(add([](EntryContent& c) { c.fields[4].labels = nullptr; }), MCON_ERROR_NULL_POINTER);
  EXPECT_STATUS(add([](EntryContent& c) { c.fields[2].stride = 8; }), MCON_ERROR_INVALID_ARGUMENT);  // < a row
  EXPECT_STATUS(add([](EntryContent& c) { c.desc.fields = nullptr; }), MCON_ERROR_NULL_POINTER);
  EXPECT_STATUS(add([](EntryContent& c) { c.desc.tags = nullptr; }), MCON_ERROR_NULL_POINTER);
  // Caller descriptors on a built-in library; a taken id.
  std::vector<double> d(9 * entry_.vertex_count, 1.0);
  EXPECT_STATUS(add([&](EntryContent& c) {
                  c.desc.descriptors = d.data();
                  c.desc.descriptor_dimension = 9;
                }),
                MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_STATUS(add([](EntryContent& c) { c.desc.id = 1; }), MCON_ERROR_INVALID_ARGUMENT);
  expect_unchanged();
  EXPECT_EQ(library_count(lib_.get()), 2u);
  // The same entry without the mistakes is accepted.
  EXPECT_STATUS(add([](EntryContent&) {}), MCON_OK);
  EXPECT_EQ(library_count(lib_.get()), 3u);
}

TEST_F(LibraryArgs, StringsThatAreNotUtf8AreRefused) {
  auto add = [&](auto change) {
    EntryContent c;
    fill_entry(c, patch_.get(), "ok", "ok");
    change(c);
    return mcon_library_add_entry(lib_.get(), &c.desc, nullptr);
  };
  const char* bad = "caf\xc3";  // a lead byte without its continuation
  const std::vector<std::pair<std::function<void(EntryContent&)>, std::string>> cases = {
      {[&](EntryContent& c) { c.desc.name = bad; }, "desc.name is not valid UTF-8 (byte 0xc3 at offset 3)"},
      {[&](EntryContent& c) { c.desc.class_label = bad; }, "desc.class_label is not valid UTF-8"},
      {[&](EntryContent& c) { c.desc.author = bad; }, "desc.author is not valid UTF-8"},
      {[&](EntryContent& c) { c.desc.licence = bad; }, "desc.licence is not valid UTF-8"},
      {[&](EntryContent& c) { c.tags[1] = bad; }, "desc.tags[1] is not valid UTF-8"},
      {[&](EntryContent& c) { c.fields[3].name = "\xff" "uv"; }, "fields[3].name is not valid UTF-8 (byte 0xff at offset 0)"},
  };
  for (const auto& [change, message] : cases) {
    EXPECT_STATUS(add(change), MCON_ERROR_INVALID_ARGUMENT);
    EXPECT_NE(last_message().find(message), std::string::npos) << last_message();
  }
  expect_unchanged();
  // Non-ASCII UTF-8 is fine, and reads back byte for byte.
  EXPECT_STATUS(add([](EntryContent& c) { c.desc.name = "Gr\xc3\xb6\xc3\x9f" "e \xe2\x82\xac"; }), MCON_OK);
  char name[64] = {};
  ASSERT_EQ(mcon_library_get_entry_string(lib_.get(), 2, MCON_ENTRY_NAME, 0, name, sizeof name, nullptr), MCON_OK);
  EXPECT_STREQ(name, "Gr\xc3\xb6\xc3\x9f" "e \xe2\x82\xac");
}

TEST_F(LibraryArgs, BadCustomDescriptors) {
  LibraryPtr lib = make_library(ctx_.get());
  const size_t n = entry_.vertex_count;
  std::vector<double> d(2 * n, 0.25);
  auto add = [&](uint32_t dimension, size_t stride) {
    EntryContent c;
    fill_entry(c, patch_.get(), "c", "c", false);
    c.desc.descriptors = d.data();
    c.desc.descriptor_dimension = dimension;
    c.desc.descriptor_stride = stride;
    return mcon_library_add_entry(lib.get(), &c.desc, nullptr);
  };
  EXPECT_STATUS(add(0, 0), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_STATUS(add(2, 8), MCON_ERROR_INVALID_ARGUMENT);  // stride below a row
  d[5] = std::nan("");
  EXPECT_STATUS(add(2, 0), MCON_ERROR_NON_FINITE);
  d[5] = 1e200;
  EXPECT_STATUS(add(2, 0), MCON_ERROR_NON_FINITE);  // not representable as float
  d[5] = 0.5;
  EXPECT_EQ(library_count(lib.get()), 0u);
  EXPECT_STATUS(add(2, 0), MCON_OK);
  EXPECT_STATUS(add(1, 0), MCON_ERROR_INVALID_ARGUMENT);  // not the library's dimension
  EXPECT_EQ(library_count(lib.get()), 1u);
}

TEST_F(LibraryArgs, ForgedAndTruncatedFilesAreInvalidLibraries) {
  mcon_library out = nullptr;
  // Truncations at a few sizes, including an empty buffer.
  for (size_t size : {size_t{0}, size_t{8}, size_t{16}, bytes_.size() / 2, bytes_.size() - 1}) {
    out = reinterpret_cast<mcon_library>(&out);
    const mcon_status s = mcon_library_open_memory(ctx_.get(), bytes_.data(), size, &out);
    EXPECT_EQ(s, MCON_ERROR_INVALID_LIBRARY) << size << ": " << last_message();
    EXPECT_EQ(out, nullptr);
  }
  // A forged identifier, and a forged id (0) in the first entry... found by searching for it.
  std::vector<uint8_t> forged = bytes_;
  std::memcpy(forged.data() + 4, "XXXX", 4);
  EXPECT_STATUS(mcon_library_open_memory(ctx_.get(), forged.data(), forged.size(), &out), MCON_ERROR_INVALID_LIBRARY);
  // Random-ish byte flips across the whole buffer: each is refused or loads a valid library,
  // never a crash.
  int refused = 0;
  for (size_t i = 0; i < bytes_.size(); i += 97) {
    forged = bytes_;
    forged[i] ^= 0xA5;
    mcon_library l = nullptr;
    const mcon_status s = mcon_library_open_memory(ctx_.get(), forged.data(), forged.size(), &l);
    if (s == MCON_OK) {
      EXPECT_EQ(mcon_library_release(l), MCON_OK);
    } else {
      EXPECT_TRUE(s == MCON_ERROR_INVALID_LIBRARY || s == MCON_ERROR_UNSUPPORTED) << i << ": " << last_message();
      ++refused;
    }
  }
  EXPECT_GT(refused, 0);
  // The same through files.
  const std::string path = temp_path("forged.mclb");
  write_bytes(path, std::vector<uint8_t>(bytes_.begin(), bytes_.begin() + static_cast<long>(bytes_.size() / 3)));
  EXPECT_STATUS(mcon_library_open(ctx_.get(), path.c_str(), &out), MCON_ERROR_INVALID_LIBRARY);
  EXPECT_EQ(out, nullptr);
  std::remove(path.c_str());
  EXPECT_STATUS(mcon_library_open(ctx_.get(), temp_path("does-not-exist.mclb").c_str(), &out), MCON_ERROR_IO);
}

TEST_F(LibraryArgs, OpeningAFileRewrittenInPlaceNeverCrashes) {
  // A writer truncating and refilling the file while mcon_library_open reads it: every open
  // returns a handle or a status, never dies of a signal (in a child, so a crash fails this test).
  const std::string path = temp_path("rewritten.mclb");
  write_bytes(path, bytes_);
  std::fflush(nullptr);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    std::atomic<bool> stop{false};
    std::thread writer([&] {
      const int fd = ::open(path.c_str(), O_WRONLY);
      std::uint32_t x = 7;
      while (fd >= 0 && !stop.load()) {
        x = x * 1664525u + 1013904223u;
        const std::size_t cut = x % bytes_.size();
        if (::ftruncate(fd, static_cast<off_t>(cut)) != 0 ||
            ::pwrite(fd, bytes_.data() + cut, bytes_.size() - cut, static_cast<off_t>(cut)) < 0 ||
            ::ftruncate(fd, 0) != 0 || ::pwrite(fd, bytes_.data(), bytes_.size(), 0) < 0)
          break;
      }
      if (fd >= 0) ::close(fd);
    });
    int code = 0, refused = 0;
    const auto start = std::chrono::steady_clock::now();
    for (int i = 0; i < 3000 && std::chrono::steady_clock::now() - start < std::chrono::milliseconds(1500); ++i) {
      mcon_library l = nullptr;
      const mcon_status s = mcon_library_open(ctx_.get(), path.c_str(), &l);
      if (s == MCON_OK) {
        mcon_library_release(l);
      } else if (s == MCON_ERROR_INVALID_LIBRARY || s == MCON_ERROR_IO) {
        ++refused;
      } else {
        code = 20;
      }
    }
    stop.store(true);
    writer.join();
    ::_exit(code != 0 ? code : refused > 0 ? 0 : 21);  // 21: no open saw a torn file
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0)
      << (WIFSIGNALED(status) ? "killed by signal " + std::to_string(WTERMSIG(status))
                              : "exit status " + std::to_string(WEXITSTATUS(status)));
  std::remove(path.c_str());
}

TEST_F(LibraryArgs, SavingWhereItCannotFailsWithIoAndKeepsTheOldFile) {
  const std::string dir = temp_path("save_dir");
  ::mkdir(dir.c_str(), 0755);
  const std::string path = dir + "/lib.mclb";
  LibraryPtr old = make_library(ctx_.get());
  ASSERT_EQ(mcon_library_save(old.get(), path.c_str()), MCON_OK) << last_message();
  const std::vector<uint8_t> before = read_bytes(path);
  // Missing directory, a directory as the target, an empty path.
  EXPECT_STATUS(mcon_library_save(lib_.get(), (dir + "/missing/lib.mclb").c_str()), MCON_ERROR_IO);
  EXPECT_STATUS(mcon_library_save(lib_.get(), dir.c_str()), MCON_ERROR_IO);
  EXPECT_STATUS(mcon_library_save(lib_.get(), ""), MCON_ERROR_IO);
  // A read-only directory: in a child that is not root (root ignores permission bits).
  ASSERT_EQ(::chmod(dir.c_str(), 0555), 0);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    if (::geteuid() == 0 && (::setgid(65534) != 0 || ::setuid(65534) != 0)) ::_exit(10);
    ::_exit(mcon_library_save(lib_.get(), path.c_str()) == MCON_ERROR_IO ? 0 : 11);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << status;
  ASSERT_EQ(::chmod(dir.c_str(), 0755), 0);
  EXPECT_EQ(read_bytes(path), before);
  // Saving works again, and replaces the file.
  ASSERT_EQ(mcon_library_save(lib_.get(), path.c_str()), MCON_OK);
  EXPECT_EQ(read_bytes(path), bytes_);
  std::remove(path.c_str());
  ::rmdir(dir.c_str());
}

TEST_F(LibraryArgs, SavingIntoAnUnreadableDirectoryFailsBeforeReplacingTheFile) {
  // Writable but not readable (0333): the directory cannot be opened for its fsync. That must be
  // found before the rename, so MCON_ERROR_IO leaves the old file as it was.
  const std::string dir = temp_path("unreadable_dir");
  ::mkdir(dir.c_str(), 0755);
  const std::string path = dir + "/lib.mclb";
  LibraryPtr old = make_library(ctx_.get());
  ASSERT_EQ(mcon_library_save(old.get(), path.c_str()), MCON_OK) << last_message();
  const std::vector<uint8_t> before = read_bytes(path);
  ASSERT_EQ(::chmod(dir.c_str(), 0333), 0);
  std::fflush(nullptr);
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {  // root ignores permission bits: drop to 'nobody'
    if (::geteuid() == 0 && (::setgid(65534) != 0 || ::setuid(65534) != 0)) ::_exit(10);
    if (mcon_library_save(lib_.get(), path.c_str()) != MCON_ERROR_IO) ::_exit(11);
    ::_exit(last_message().find("nothing was replaced") != std::string::npos ? 0 : 12);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << status;
  ASSERT_EQ(::chmod(dir.c_str(), 0755), 0);
  EXPECT_EQ(read_bytes(path), before);
  std::remove(path.c_str());
  EXPECT_EQ(::rmdir(dir.c_str()), 0);  // empty: the temporary file was removed too
}

}  // namespace

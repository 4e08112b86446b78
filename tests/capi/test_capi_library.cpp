// Constraint libraries through the C ABI on real patches of the MakeHuman sample body: entries with
// every kind of constraint and field, retrieval, queries, save/open round trips (same answers,
// same bytes), remove, merge, custom descriptors, descriptor changes, thread-count independence,
// progress and cancellation.
#include <gtest/gtest.h>

#include <set>

#include <cmath>
#include <cstddef>
#include <cstring>
#include <map>

#include "capi/test_capi_library_util.h"

using namespace capi_test;

namespace {

class LibraryTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ctx_ = make_context();
    mesh_ = make_mesh(ctx_.get(), body_arrays());
    for (const Landmark& l : landmarks()) patches_.push_back(make_patch(mesh_.get(), l.vertex));
  }

  // One full entry per landmark; returns the ids.
  std::vector<uint64_t> add_all(mcon_library lib, bool full = true) {
    std::vector<uint64_t> ids;
    for (size_t i = 0; i < patches_.size(); ++i) {
      EntryContent c;
      fill_entry(c, patches_[i].get(), landmarks()[i].name, landmarks()[i].class_label, full);
      uint64_t id = 0;
      EXPECT_EQ(mcon_library_add_entry(lib, &c.desc, &id), MCON_OK) << last_message();
      ids.push_back(id);
    }
    return ids;
  }

  LibraryPtr built_library(uint64_t seed = 0) {
    LibraryPtr lib = make_library(ctx_.get());
    add_all(lib.get());
    mcon_retrieval_options o = small_options();
    o.seed = seed;
    EXPECT_EQ(mcon_library_build_retrieval(lib.get(), &o), MCON_OK) << last_message();
    return lib;
  }

  ContextPtr ctx_;
  MeshPtr mesh_;
  std::vector<PatchPtr> patches_;
};

// Every entry of `a` reads back the same as in `b`, through every getter.
void expect_same_entries(mcon_library a, mcon_library b) {
  ASSERT_EQ(library_count(a), library_count(b));
  const mcon_library_info ia = library_info(a), ib = library_info(b);
  EXPECT_EQ(ia.vocabulary_size, ib.vocabulary_size);
  EXPECT_EQ(ia.sigma_bof, ib.sigma_bof);
  for (size_t e = 0; e < library_count(a); ++e) {
    mcon_library_entry_info ea, eb;
    mcon_library_entry_info_init(&ea);
    mcon_library_entry_info_init(&eb);
    ASSERT_EQ(mcon_library_get_entry_info(a, e, &ea), MCON_OK) << last_message();
    ASSERT_EQ(mcon_library_get_entry_info(b, e, &eb), MCON_OK) << last_message();
    EXPECT_EQ(std::memcmp(&ea, &eb, sizeof ea), 0) << "entry info " << e;
    std::vector<double> pa(3 * ea.vertex_count), pb(pa.size());
    ASSERT_EQ(mcon_library_get_entry_positions(a, e, pa.data(), pa.size()), MCON_OK);
    ASSERT_EQ(mcon_library_get_entry_positions(b, e, pb.data(), pb.size()), MCON_OK);
    EXPECT_EQ(pa, pb);
    std::vector<uint32_t> ta(3 * ea.triangle_count), tb(ta.size());
    ASSERT_EQ(mcon_library_get_entry_triangles(a, e, ta.data(), ta.size()), MCON_OK);
    ASSERT_EQ(mcon_library_get_entry_triangles(b, e, tb.data(), tb.size()), MCON_OK);
    EXPECT_EQ(ta, tb);
    std::vector<double> da(ea.vertex_count * ia.descriptor_dimension), db(da.size());
    std::vector<float> ha(ia.histogram_length), hb(ha.size());
    ASSERT_EQ(mcon_library_get_entry_retrieval(a, e, da.data(), da.size(), ha.data(), ha.size()), MCON_OK);
    ASSERT_EQ(mcon_library_get_entry_retrieval(b, e, db.data(), db.size(), hb.data(), hb.size()), MCON_OK);
    EXPECT_EQ(da, db);
    EXPECT_EQ(ha, hb);
  }
}

TEST_F(LibraryTest, EntriesReadBackEveryConstraintAndField) {
  LibraryPtr lib = make_library(ctx_.get());
  EntryContent c;
  fill_entry(c, patches_[2].get(), "nose_01", "nose");
  uint64_t id = 0;
  ASSERT_EQ(mcon_library_add_entry(lib.get(), &c.desc, &id), MCON_OK) << last_message();
  EXPECT_EQ(id, 1u);
  const mcon_patch_info pi = patch_info(patches_[2].get());

  const mcon_library_info info = library_info(lib.get());
  EXPECT_EQ(info.entry_count, 1u);
  EXPECT_EQ(info.descriptor, static_cast<uint32_t>(MCON_RETRIEVAL_DESCRIPTOR_CURV9));
  EXPECT_EQ(info.descriptor_dimension, 9u);
  EXPECT_EQ(info.vocabulary_size, 0u);

  mcon_library_entry_info ei;
  ASSERT_EQ(mcon_library_entry_info_init(&ei), MCON_OK);
  ASSERT_EQ(mcon_library_get_entry_info(lib.get(), 0, &ei), MCON_OK) << last_message();
  EXPECT_EQ(ei.id, id);
  EXPECT_EQ(ei.vertex_count, pi.vertex_count);
  EXPECT_EQ(ei.triangle_count, pi.triangle_count);
  EXPECT_EQ(ei.tag_count, 2u);
  EXPECT_EQ(ei.polyline_count, 2u);
  EXPECT_EQ(ei.singularity_count, 2u);
  EXPECT_EQ(ei.field_count, 5u);
  EXPECT_EQ(ei.center.face, pi.center_patch_triangle);
  EXPECT_DOUBLE_EQ(ei.source_scale, kRadius);
  for (int k = 0; k < 3; ++k) EXPECT_DOUBLE_EQ(ei.source_origin[k], pi.center[k]);

  // Positions are the patch's, stored as float.
  std::vector<double> patch_xyz(3 * pi.vertex_count), xyz(patch_xyz.size());
  ASSERT_EQ(mcon_patch_get_positions(patches_[2].get(), patch_xyz.data(), patch_xyz.size()), MCON_OK);
  ASSERT_EQ(mcon_library_get_entry_positions(lib.get(), 0, xyz.data(), xyz.size()), MCON_OK) << last_message();
  for (size_t i = 0; i < xyz.size(); ++i) EXPECT_EQ(xyz[i], static_cast<double>(static_cast<float>(patch_xyz[i])));
  std::vector<uint32_t> patch_tris(3 * pi.triangle_count), tris(patch_tris.size());
  ASSERT_EQ(mcon_patch_get_triangles(patches_[2].get(), patch_tris.data(), patch_tris.size()), MCON_OK);
  ASSERT_EQ(mcon_library_get_entry_triangles(lib.get(), 0, tris.data(), tris.size()), MCON_OK);
  EXPECT_EQ(tris, patch_tris);

  // Strings: size query, then the text.
  auto get_string = [&](mcon_entry_string which, size_t item) {
    size_t size = 0;
    EXPECT_EQ(mcon_library_get_entry_string(lib.get(), 0, which, item, nullptr, 0, &size), MCON_OK) << last_message();
    std::string s(size, '\0');
    EXPECT_EQ(mcon_library_get_entry_string(lib.get(), 0, which, item, s.data(), s.size(), &size), MCON_OK);
    EXPECT_EQ(s.back(), '\0');
    s.pop_back();
    return s;
  };
  EXPECT_EQ(get_string(MCON_ENTRY_NAME, 0), "nose_01");
  EXPECT_EQ(get_string(MCON_ENTRY_CLASS_LABEL, 0), "nose");
  EXPECT_EQ(get_string(MCON_ENTRY_AUTHOR, 0), "Vendor GmbH");
  EXPECT_EQ(get_string(MCON_ENTRY_LICENCE, 0), "CC-BY-4.0");
  EXPECT_EQ(get_string(MCON_ENTRY_TAG, 1), "symmetric");
  EXPECT_EQ(get_string(MCON_ENTRY_FIELD_NAME, 4), "region");

  // Polylines: guides first, then features.
  for (size_t i = 0; i < 2; ++i) {
    uint32_t kind = 0, closed = 7;
    size_t count = 0;
    ASSERT_EQ(mcon_library_get_entry_polyline(lib.get(), 0, i, &kind, &closed, &count, nullptr, 0), MCON_OK);
    const auto& expected = i == 0 ? c.guide : c.feature;
    EXPECT_EQ(kind, i == 0 ? static_cast<uint32_t>(MCON_POLYLINE_GUIDE) : static_cast<uint32_t>(MCON_POLYLINE_FEATURE));
    EXPECT_EQ(closed, i == 0 ? 0u : 1u);
    ASSERT_EQ(count, expected.size());
    std::vector<mcon_surface_point> points(count);
    ASSERT_EQ(mcon_library_get_entry_polyline(lib.get(), 0, i, nullptr, nullptr, nullptr, points.data(), count),
              MCON_OK);
    for (size_t j = 0; j < count; ++j) {
      EXPECT_EQ(points[j].face, expected[j].face);
      for (int k = 0; k < 3; ++k) EXPECT_EQ(points[j].barycentric[k], expected[j].barycentric[k]);
    }
  }
  std::vector<mcon_singularity> sing(2);
  ASSERT_EQ(mcon_library_get_entry_singularities(lib.get(), 0, sing.data(), sing.size()), MCON_OK);
  for (size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(sing[i].index_quarters, c.singularities[i].index_quarters);
    EXPECT_EQ(sing[i].location.face, c.singularities[i].location.face);
    EXPECT_EQ(sing[i].location.barycentric[2], c.singularities[i].location.barycentric[2]);
  }

  // Fields of every kind (values were chosen exactly representable in float).
  const std::vector<std::vector<double>*> reals = {&c.sizing, &c.direction, &c.normal, &c.uv};
  const uint32_t kinds[] = {MCON_FIELD_SCALAR, MCON_FIELD_TANGENT_VECTOR, MCON_FIELD_VECTOR3, MCON_FIELD_UV};
  for (size_t f = 0; f < 4; ++f) {
    uint32_t kind = 0, dim = 0;
    std::vector<double> values(reals[f]->size());
    ASSERT_EQ(mcon_library_get_entry_field(lib.get(), 0, f, &kind, &dim, values.data(), nullptr, values.size()),
              MCON_OK)
        << last_message();
    EXPECT_EQ(kind, kinds[f]);
    EXPECT_EQ(dim * pi.vertex_count, values.size());
    EXPECT_EQ(values, *reals[f]);
  }
  uint32_t kind = 0, dim = 0;
  std::vector<int32_t> labels(pi.vertex_count);
  ASSERT_EQ(mcon_library_get_entry_field(lib.get(), 0, 4, &kind, &dim, nullptr, labels.data(), labels.size()),
            MCON_OK);
  EXPECT_EQ(kind, static_cast<uint32_t>(MCON_FIELD_INTEGER_LABEL));
  EXPECT_EQ(dim, 1u);
  EXPECT_EQ(labels, c.region);

  // The stored CURV9 descriptors are those of the (float-rounded) patch; no histogram yet.
  std::vector<double> stored(9 * pi.vertex_count), direct(stored.size());
  ASSERT_EQ(mcon_library_get_entry_retrieval(lib.get(), 0, stored.data(), stored.size(), nullptr, 0), MCON_OK);
  ASSERT_EQ(mcon_patch_compute_descriptors(patches_[2].get(), MCON_DESCRIPTOR_CURV9, direct.data(), direct.size()),
            MCON_OK);
  double worst = 0;
  for (size_t i = 0; i < stored.size(); ++i)
    worst = std::max(worst, std::abs(stored[i] - direct[i]) / (1.0 + std::abs(direct[i])));
  EXPECT_LT(worst, 1e-3);
}

TEST_F(LibraryTest, QueriesFindEachEntryFirstAndSurviveSaveAndOpen) {
  LibraryPtr lib = make_library(ctx_.get());
  const std::vector<uint64_t> ids = add_all(lib.get());
  // No vocabulary yet: queries are refused.
  size_t count = 99;
  uint64_t one = 0;
  EXPECT_EQ(mcon_library_query(lib.get(), patches_[0].get(), 1, &one, nullptr, nullptr, 1, &count),
            MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(count, 0u);

  mcon_retrieval_options o = small_options();
  ASSERT_EQ(mcon_library_build_retrieval(lib.get(), &o), MCON_OK) << last_message();
  const mcon_library_info info = library_info(lib.get());
  EXPECT_EQ(info.rings, 1u);  // the default (kDefaultRetrievalRings)
  EXPECT_GE(info.vocabulary_size, 2u);
  EXPECT_LE(info.vocabulary_size, 16u);
  EXPECT_EQ(info.histogram_length, info.vocabulary_size * info.rings);
  EXPECT_GT(info.sigma_bof, 0);

  std::vector<QueryResult> before;
  for (size_t i = 0; i < patches_.size(); ++i) {
    QueryResult r = query(lib.get(), patches_[i].get(), 4);
    ASSERT_EQ(r.ids.size(), 4u);
    EXPECT_EQ(r.ids[0], ids[i]) << landmarks()[i].name;
    EXPECT_EQ(r.indices[0], i);
    EXPECT_EQ(r.distances[0], 0.0);  // the query is described exactly as its entry was
    for (size_t j = 1; j < r.distances.size(); ++j) EXPECT_GE(r.distances[j], r.distances[j - 1]);
    EXPECT_GT(r.distances[1], 0.0);
    before.push_back(r);
  }
  // n beyond the count gives every entry once.
  QueryResult all = query(lib.get(), patches_[0].get(), 100);
  EXPECT_EQ(all.ids.size(), patches_.size());

  // Save -> open: identical queries; re-saving gives the same bytes (file and memory).
  const std::string path = temp_path("roundtrip.mclb");
  ASSERT_EQ(mcon_library_save(lib.get(), path.c_str()), MCON_OK) << last_message();
  const std::vector<uint8_t> file = read_bytes(path);
  EXPECT_EQ(file, save_bytes(lib.get()));
  mcon_library opened_raw = nullptr;
  ASSERT_EQ(mcon_library_open(ctx_.get(), path.c_str(), &opened_raw), MCON_OK) << last_message();
  LibraryPtr opened(opened_raw);
  for (size_t i = 0; i < patches_.size(); ++i) EXPECT_EQ(query(opened.get(), patches_[i].get(), 4), before[i]);
  expect_same_entries(lib.get(), opened.get());
  EXPECT_EQ(save_bytes(opened.get()), file);
  const std::string path2 = temp_path("roundtrip2.mclb");
  ASSERT_EQ(mcon_library_save(opened.get(), path2.c_str()), MCON_OK);
  EXPECT_EQ(read_bytes(path2), file);
  mcon_library from_memory_raw = nullptr;
  ASSERT_EQ(mcon_library_open_memory(ctx_.get(), file.data(), file.size(), &from_memory_raw), MCON_OK);
  LibraryPtr from_memory(from_memory_raw);
  EXPECT_EQ(query(from_memory.get(), patches_[3].get(), 4), before[3]);

  // Rebuilding with the same options after the round trip gives the same library (entries are
  // described from what the file stores, ring distances included).
  ASSERT_EQ(mcon_library_build_retrieval(opened.get(), &o), MCON_OK) << last_message();
  EXPECT_EQ(save_bytes(opened.get()), file);
  std::remove(path.c_str());
  std::remove(path2.c_str());
}

TEST_F(LibraryTest, AddAfterBuildIsFoundAtOnceAndRemoveShiftsIndices) {
  LibraryPtr lib = built_library();
  const size_t n0 = library_count(lib.get());
  PatchPtr extra = make_patch(mesh_.get(), 11412, 0.6);  // the left foot, a new region
  EntryContent c;
  fill_entry(c, extra.get(), "foot_l", "foot");
  c.desc.id = 1000;
  uint64_t id = 0;
  ASSERT_EQ(mcon_library_add_entry(lib.get(), &c.desc, &id), MCON_OK) << last_message();
  EXPECT_EQ(id, 1000u);
  EXPECT_EQ(library_count(lib.get()), n0 + 1);
  QueryResult r = query(lib.get(), extra.get(), 2);
  EXPECT_EQ(r.ids[0], 1000u);
  EXPECT_EQ(r.distances[0], 0.0);
  // A taken id is refused and changes nothing.
  EXPECT_EQ(mcon_library_add_entry(lib.get(), &c.desc, &id), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(library_count(lib.get()), n0 + 1);
  // The next assigned id is the largest + 1.
  c.desc.id = 0;
  ASSERT_EQ(mcon_library_add_entry(lib.get(), &c.desc, &id), MCON_OK);
  EXPECT_EQ(id, 1001u);

  // Remove entry 1 (id 2): later entries move down, queries no longer return it.
  size_t index = 0;
  ASSERT_EQ(mcon_library_find_entry(lib.get(), 3, &index), MCON_OK);
  EXPECT_EQ(index, 2u);
  ASSERT_EQ(mcon_library_remove_entry(lib.get(), 2), MCON_OK) << last_message();
  EXPECT_EQ(mcon_library_find_entry(lib.get(), 2, &index), MCON_ERROR_NOT_FOUND);
  EXPECT_EQ(mcon_library_remove_entry(lib.get(), 2), MCON_ERROR_NOT_FOUND);
  ASSERT_EQ(mcon_library_find_entry(lib.get(), 3, &index), MCON_OK);
  EXPECT_EQ(index, 1u);
  QueryResult after = query(lib.get(), patches_[1].get(), 100);
  EXPECT_EQ(after.ids.size(), n0 + 1);
  for (uint64_t x : after.ids) EXPECT_NE(x, 2u);
  QueryResult nose = query(lib.get(), patches_[2].get(), 1);
  EXPECT_EQ(nose.ids[0], 3u);
  EXPECT_EQ(nose.indices[0], 1u);
}

// A library holding every class twice (merged with itself): the plain top 3 of the eye is both
// eyes and one more; the distinct top 3 is three classes, the eye's copy its alternative.
TEST_F(LibraryTest, DistinctSuggestionsCountACopyOnce) {
  LibraryPtr lib = built_library(0);
  ASSERT_EQ(mcon_library_merge(lib.get(), lib.get()), MCON_OK) << last_message();
  const size_t n = library_count(lib.get());
  ASSERT_EQ(n, 2 * landmarks().size());
  QueryResult plain = query(lib.get(), patches_[0].get(), 3);
  ASSERT_EQ(plain.ids.size(), 3u);
  EXPECT_EQ(plain.distances[0], 0.0);
  EXPECT_EQ(plain.distances[1], 0.0);  // the copy
  std::vector<uint32_t> idx(3), alt(3);
  std::vector<double> dist(3), conf(3);
  size_t count = 0;
  ASSERT_EQ(mcon_library_query_distinct(lib.get(), patches_[0].get(), 3, idx.data(), dist.data(), conf.data(),
                                        alt.data(), 3, &count),
            MCON_OK)
      << last_message();
  ASSERT_EQ(count, 3u);
  EXPECT_EQ(idx[0], 0u);
  EXPECT_EQ(alt[0], 1u);  // its copy
  EXPECT_EQ(conf[0], 1.0);  // an exact match
  EXPECT_GT(dist[1], 0.0);
  EXPECT_LE(dist[1], dist[2]);
  std::set<std::string> classes;
  for (size_t i = 0; i < count; ++i) {
    mcon_library_entry_info info;
    ASSERT_EQ(mcon_library_entry_info_init(&info), MCON_OK);
    ASSERT_EQ(mcon_library_get_entry_info(lib.get(), idx[i], &info), MCON_OK);
    classes.insert(landmarks()[idx[i] % landmarks().size()].class_label);
  }
  EXPECT_EQ(classes.size(), 3u);
  EXPECT_EQ(mcon_library_query_distinct(lib.get(), patches_[0].get(), 0, nullptr, nullptr, nullptr, nullptr, 0, &count),
            MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(mcon_library_query_distinct(lib.get(), patches_[0].get(), 3, idx.data(), nullptr, nullptr, nullptr, 2, &count),
            MCON_ERROR_BUFFER_TOO_SMALL);
  // NULL handles and a NULL count: NULL_POINTER naming the argument, no suggestion written.
  count = 77;
  EXPECT_EQ(mcon_library_query_distinct(nullptr, patches_[0].get(), 3, idx.data(), nullptr, nullptr, nullptr, 3, &count),
            MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(count, 77u);
  EXPECT_EQ(mcon_library_query_distinct(lib.get(), nullptr, 3, idx.data(), nullptr, nullptr, nullptr, 3, &count),
            MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(count, 0u);  // past the library check the count is reset first: an error reports none
  EXPECT_EQ(mcon_library_query_distinct(lib.get(), patches_[0].get(), 3, idx.data(), nullptr, nullptr, nullptr, 3, nullptr),
            MCON_ERROR_NULL_POINTER);
  EXPECT_NE(last_message().find("out_count"), std::string::npos) << last_message();
}

TEST_F(LibraryTest, InfoSaysWhetherAChecksumWasVerified) {
  LibraryPtr a = built_library(0);
  mcon_library_info info;
  ASSERT_EQ(mcon_library_info_init(&info), MCON_OK);
  ASSERT_EQ(mcon_library_get_info(a.get(), &info), MCON_OK);
  EXPECT_EQ(info.format_version, 0u);  // made in memory
  EXPECT_EQ(info.checksum_verified, 0u);
  std::vector<uint8_t> bytes = save_bytes(a.get());
  mcon_library b_raw = nullptr;
  ASSERT_EQ(mcon_library_open_memory(ctx_.get(), bytes.data(), bytes.size(), &b_raw), MCON_OK);
  LibraryPtr b(b_raw);
  ASSERT_EQ(mcon_library_get_info(b.get(), &info), MCON_OK);
  EXPECT_EQ(info.format_version, 2u);
  EXPECT_EQ(info.checksum_verified, 1u);
  bytes[bytes.size() / 2] ^= 0x10;  // one bit anywhere
  mcon_library c_raw = nullptr;
  EXPECT_EQ(mcon_library_open_memory(ctx_.get(), bytes.data(), bytes.size(), &c_raw), MCON_ERROR_INVALID_LIBRARY);
  EXPECT_EQ(c_raw, nullptr);
}

TEST_F(LibraryTest, MergeSameConfigIsReadyDifferentConfigNeedsABuild) {
  LibraryPtr a = built_library(0);
  const std::vector<uint8_t> bytes = save_bytes(a.get());
  mcon_library b_raw = nullptr;
  ASSERT_EQ(mcon_library_open_memory(ctx_.get(), bytes.data(), bytes.size(), &b_raw), MCON_OK);
  LibraryPtr b(b_raw);
  const size_t n = library_count(a.get());

  ASSERT_EQ(mcon_library_merge(a.get(), b.get()), MCON_OK) << last_message();
  EXPECT_EQ(library_count(a.get()), 2 * n);
  EXPECT_EQ(library_count(b.get()), n);  // the other library is not changed
  // Copies were renumbered after the largest id; both copies are at distance 0.
  QueryResult r = query(a.get(), patches_[0].get(), 2);
  ASSERT_EQ(r.ids.size(), 2u);
  EXPECT_EQ(r.ids[0], 1u);
  EXPECT_EQ(r.ids[1], n + 1);
  EXPECT_EQ(r.distances[1], 0.0);
  // Merging a library into itself doubles it again.
  ASSERT_EQ(mcon_library_merge(a.get(), a.get()), MCON_OK) << last_message();
  EXPECT_EQ(library_count(a.get()), 4 * n);

  // Different vocabularies (another seed): merged, but the vocabulary is dropped.
  LibraryPtr c = built_library(7);
  ASSERT_EQ(mcon_library_merge(c.get(), b.get()), MCON_OK) << last_message();
  EXPECT_EQ(library_count(c.get()), 2 * n);
  EXPECT_EQ(library_info(c.get()).vocabulary_size, 0u);
  size_t count = 0;
  EXPECT_EQ(mcon_library_query(c.get(), patches_[0].get(), 1, nullptr, nullptr, nullptr, 1, &count),
            MCON_ERROR_INVALID_ARGUMENT);
  mcon_retrieval_options o = small_options();
  ASSERT_EQ(mcon_library_build_retrieval(c.get(), &o), MCON_OK) << last_message();
  QueryResult rc = query(c.get(), patches_[4].get(), 2);
  EXPECT_EQ(rc.distances[0], 0.0);
  EXPECT_EQ(rc.distances[1], 0.0);

  // An empty library takes the other's configuration and is ready at once.
  LibraryPtr empty = make_library(ctx_.get());
  ASSERT_EQ(mcon_library_merge(empty.get(), b.get()), MCON_OK);
  EXPECT_EQ(query(empty.get(), patches_[5].get(), 3), query(b.get(), patches_[5].get(), 3));
}

TEST_F(LibraryTest, MergeRefusesAnotherDescriptor) {
  LibraryPtr a = built_library();
  LibraryPtr custom = make_library(ctx_.get());
  EntryContent c;
  fill_entry(c, patches_[0].get(), "eye", "eye", false);
  std::vector<double> d(2 * patch_info(patches_[0].get()).vertex_count, 0.5);
  c.desc.descriptors = d.data();
  c.desc.descriptor_dimension = 2;
  ASSERT_EQ(mcon_library_add_entry(custom.get(), &c.desc, nullptr), MCON_OK) << last_message();
  const std::vector<uint8_t> before = save_bytes(a.get());
  EXPECT_EQ(mcon_library_merge(a.get(), custom.get()), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(save_bytes(a.get()), before);  // unchanged
}

// Caller-supplied descriptors: here the patch's CURV9 computed by the host plus its uv (11 values
// per vertex), so retrieval still finds each patch's own entry.
TEST_F(LibraryTest, CustomDescriptors) {
  LibraryPtr lib = make_library(ctx_.get());
  std::vector<std::vector<double>> descriptors;
  const uint32_t d = 11;
  for (size_t i = 0; i < patches_.size(); ++i) {
    const size_t n = patch_info(patches_[i].get()).vertex_count;
    std::vector<double> curv(9 * n), uv(2 * n), rows;
    EXPECT_EQ(mcon_patch_compute_descriptors(patches_[i].get(), MCON_DESCRIPTOR_CURV9, curv.data(), curv.size()),
              MCON_OK);
    EXPECT_EQ(mcon_patch_get_uv(patches_[i].get(), uv.data(), uv.size()), MCON_OK);
    // A strided layout: 11 values and one unused double per row.
    for (size_t v = 0; v < n; ++v) {
      rows.insert(rows.end(), curv.begin() + static_cast<long>(9 * v), curv.begin() + static_cast<long>(9 * v + 9));
      rows.insert(rows.end(), {uv[2 * v], uv[2 * v + 1], -1.0});
    }
    descriptors.push_back(rows);
    EntryContent c;
    fill_entry(c, patches_[i].get(), landmarks()[i].name, landmarks()[i].class_label, false);
    c.desc.descriptors = descriptors.back().data();
    c.desc.descriptor_dimension = d;
    c.desc.descriptor_stride = 12 * sizeof(double);
    ASSERT_EQ(mcon_library_add_entry(lib.get(), &c.desc, nullptr), MCON_OK) << last_message();
  }
  mcon_library_info info = library_info(lib.get());
  EXPECT_EQ(info.descriptor, static_cast<uint32_t>(MCON_RETRIEVAL_DESCRIPTOR_CUSTOM));
  EXPECT_EQ(info.descriptor_dimension, d);
  // Stored as given (rounded to float).
  std::vector<double> stored(d * patch_info(patches_[1].get()).vertex_count);
  ASSERT_EQ(mcon_library_get_entry_retrieval(lib.get(), 1, stored.data(), stored.size(), nullptr, 0), MCON_OK);
  EXPECT_EQ(stored[9], static_cast<double>(static_cast<float>(descriptors[1][9])));
  EXPECT_EQ(stored[11], static_cast<double>(static_cast<float>(descriptors[1][12])));

  // A custom library refuses entries without descriptors, and building with a built-in one
  // recomputes; CUSTOM stays possible.
  EntryContent plain;
  fill_entry(plain, patches_[0].get(), "x", "x", false);
  EXPECT_EQ(mcon_library_add_entry(lib.get(), &plain.desc, nullptr), MCON_ERROR_INVALID_ARGUMENT);
  mcon_retrieval_options o = small_options();
  o.descriptor = MCON_RETRIEVAL_DESCRIPTOR_CUSTOM;
  o.rings = 2;
  ASSERT_EQ(mcon_library_build_retrieval(lib.get(), &o), MCON_OK) << last_message();
  info = library_info(lib.get());
  EXPECT_EQ(info.descriptor, static_cast<uint32_t>(MCON_RETRIEVAL_DESCRIPTOR_CUSTOM));
  EXPECT_EQ(info.rings, 2u);

  for (size_t i = 0; i < patches_.size(); ++i) {
    uint64_t ids[3];
    double dist[3];
    size_t count = 0;
    ASSERT_EQ(mcon_library_query_descriptors(lib.get(), patches_[i].get(), descriptors[i].data(), d,
                                             12 * sizeof(double), 3, ids, nullptr, dist, 3, &count),
              MCON_OK)
        << last_message();
    EXPECT_EQ(count, 3u);
    EXPECT_EQ(ids[0], i + 1);
    EXPECT_EQ(dist[0], 0.0);
  }
  // A custom library cannot compute the query's descriptors itself; wrong dimensions are refused.
  size_t count = 0;
  EXPECT_EQ(mcon_library_query(lib.get(), patches_[0].get(), 1, nullptr, nullptr, nullptr, 1, &count),
            MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(mcon_library_query_descriptors(lib.get(), patches_[0].get(), descriptors[0].data(), d - 1, 0, 1, nullptr,
                                           nullptr, nullptr, 1, &count),
            MCON_ERROR_INVALID_ARGUMENT);
  // Custom descriptors survive a round trip.
  const std::vector<uint8_t> bytes = save_bytes(lib.get());
  mcon_library reopened = nullptr;
  ASSERT_EQ(mcon_library_open_memory(ctx_.get(), bytes.data(), bytes.size(), &reopened), MCON_OK) << last_message();
  LibraryPtr again(reopened);
  EXPECT_EQ(library_info(again.get()).descriptor, static_cast<uint32_t>(MCON_RETRIEVAL_DESCRIPTOR_CUSTOM));
  EXPECT_EQ(save_bytes(again.get()), bytes);

  // Switching to a built-in descriptor recomputes every entry's descriptors from its mesh.
  o.descriptor = MCON_RETRIEVAL_DESCRIPTOR_CURV9;
  ASSERT_EQ(mcon_library_build_retrieval(lib.get(), &o), MCON_OK) << last_message();
  info = library_info(lib.get());
  EXPECT_EQ(info.descriptor, static_cast<uint32_t>(MCON_RETRIEVAL_DESCRIPTOR_CURV9));
  EXPECT_EQ(info.descriptor_dimension, 9u);
  EXPECT_EQ(query(lib.get(), patches_[3].get(), 1).ids[0], 4u);
  // ... and then CUSTOM is no longer possible.
  o.descriptor = MCON_RETRIEVAL_DESCRIPTOR_CUSTOM;
  EXPECT_EQ(mcon_library_build_retrieval(lib.get(), &o), MCON_ERROR_INVALID_ARGUMENT);
}

TEST_F(LibraryTest, ChangingTheDescriptorRecomputesDescriptors) {
  LibraryPtr lib = make_library(ctx_.get());
  add_all(lib.get(), false);
  mcon_retrieval_options o = small_options();
  o.descriptor = MCON_RETRIEVAL_DESCRIPTOR_WKS;
  o.rings = 1;
  ASSERT_EQ(mcon_library_build_retrieval(lib.get(), &o), MCON_OK) << last_message();
  const mcon_library_info info = library_info(lib.get());
  EXPECT_EQ(info.descriptor, static_cast<uint32_t>(MCON_RETRIEVAL_DESCRIPTOR_WKS));
  EXPECT_EQ(info.descriptor_dimension, 100u);
  EXPECT_EQ(info.rings, 1u);
  EXPECT_EQ(info.histogram_length, info.vocabulary_size);
  QueryResult r = query(lib.get(), patches_[2].get(), 2);
  EXPECT_EQ(r.ids[0], 3u);
  EXPECT_EQ(r.distances[0], 0.0);
}

// Choosing the descriptor of an empty library computes it from the first entry on; the file is
// the same as when the descriptor is changed by a build afterwards.
TEST_F(LibraryTest, SetDescriptorOnAnEmptyLibraryMatchesAChangeByBuild) {
  mcon_retrieval_options o = small_options();
  o.descriptor = MCON_RETRIEVAL_DESCRIPTOR_WKS;
  LibraryPtr chosen = make_library(ctx_.get());
  ASSERT_EQ(mcon_library_set_descriptor(chosen.get(), MCON_RETRIEVAL_DESCRIPTOR_WKS), MCON_OK) << last_message();
  add_all(chosen.get(), false);
  const mcon_library_info before_build = library_info(chosen.get());
  EXPECT_EQ(before_build.descriptor, static_cast<uint32_t>(MCON_RETRIEVAL_DESCRIPTOR_WKS));
  EXPECT_EQ(before_build.descriptor_dimension, 100u);
  ASSERT_EQ(mcon_library_build_retrieval(chosen.get(), &o), MCON_OK) << last_message();
  LibraryPtr changed = make_library(ctx_.get());
  add_all(changed.get(), false);
  ASSERT_EQ(mcon_library_build_retrieval(changed.get(), &o), MCON_OK) << last_message();
  EXPECT_EQ(save_bytes(chosen.get()), save_bytes(changed.get()));

  EXPECT_EQ(mcon_library_set_descriptor(chosen.get(), MCON_RETRIEVAL_DESCRIPTOR_HKS), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_message().find("mcon_library_build_retrieval"), std::string::npos) << last_message();
  LibraryPtr empty = make_library(ctx_.get());
  EXPECT_EQ(mcon_library_set_descriptor(empty.get(), MCON_RETRIEVAL_DESCRIPTOR_CUSTOM), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(mcon_library_set_descriptor(empty.get(), 2), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(library_info(empty.get()).descriptor, static_cast<uint32_t>(MCON_RETRIEVAL_DESCRIPTOR_CURV9));
}

std::string library_string(mcon_library l, mcon_library_string which) {
  size_t size = 0;
  EXPECT_EQ(mcon_library_get_string(l, which, nullptr, 0, &size), MCON_OK) << last_message();
  std::string s(size, '\0');
  EXPECT_EQ(mcon_library_get_string(l, which, &s[0], s.size(), &size), MCON_OK) << last_message();
  s.resize(size - 1);
  return s;
}

TEST_F(LibraryTest, NameDescriptionAndDescriptorNameSurviveSaveAndOpen) {
  LibraryPtr lib = make_library(ctx_.get());
  EXPECT_EQ(library_string(lib.get(), MCON_LIBRARY_NAME), "");
  EXPECT_EQ(library_string(lib.get(), MCON_LIBRARY_DESCRIPTOR), "curv9");
  ASSERT_EQ(mcon_library_set_descriptor(lib.get(), MCON_RETRIEVAL_DESCRIPTOR_HKS), MCON_OK) << last_message();
  ASSERT_EQ(mcon_library_set_string(lib.get(), MCON_LIBRARY_NAME, "faces \xc3\xa9t\xc3\xa9"), MCON_OK);
  ASSERT_EQ(mcon_library_set_string(lib.get(), MCON_LIBRARY_DESCRIPTION, "noses and ears"), MCON_OK);
  add_all(lib.get(), false);
  const std::vector<uint8_t> bytes = save_bytes(lib.get());
  mcon_library opened = nullptr;
  ASSERT_EQ(mcon_library_open_memory(ctx_.get(), bytes.data(), bytes.size(), &opened), MCON_OK) << last_message();
  LibraryPtr reopened(opened);
  EXPECT_EQ(library_string(opened, MCON_LIBRARY_NAME), "faces \xc3\xa9t\xc3\xa9");
  EXPECT_EQ(library_string(opened, MCON_LIBRARY_DESCRIPTION), "noses and ears");
  EXPECT_EQ(library_string(opened, MCON_LIBRARY_DESCRIPTOR), "hks");

  EXPECT_EQ(mcon_library_set_string(lib.get(), MCON_LIBRARY_NAME, "bad \xff"), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_message().find("UTF-8"), std::string::npos) << last_message();
  EXPECT_EQ(library_string(lib.get(), MCON_LIBRARY_NAME), "faces \xc3\xa9t\xc3\xa9");
  EXPECT_EQ(mcon_library_set_string(lib.get(), MCON_LIBRARY_DESCRIPTOR, "wks"), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(mcon_library_set_string(lib.get(), static_cast<mcon_library_string>(9), "x"), MCON_ERROR_INVALID_ARGUMENT);
  char small[2];
  EXPECT_NE(mcon_library_get_string(lib.get(), MCON_LIBRARY_NAME, small, sizeof small, nullptr), MCON_OK);
}

TEST_F(LibraryTest, AnEntryStoresItsUpDirectionThroughSaveOpenAndMerge) {
  LibraryPtr lib = make_library(ctx_.get());
  EntryContent plain, up;
  fill_entry(plain, patches_[0].get(), "plain", "nose", false);
  fill_entry(up, patches_[1].get(), "upright", "eye", false);
  up.desc.has_up = 1;
  up.desc.up[0] = 0;
  up.desc.up[1] = 2.5;  // any length: a direction
  up.desc.up[2] = -0.5;
  ASSERT_EQ(mcon_library_add_entry(lib.get(), &plain.desc, nullptr), MCON_OK) << last_message();
  ASSERT_EQ(mcon_library_add_entry(lib.get(), &up.desc, nullptr), MCON_OK) << last_message();
  // A desc of the size before has_up (an older caller) adds an entry without one.
  EntryContent older;
  fill_entry(older, patches_[2].get(), "older", "ear", false);
  older.desc.has_up = 1;  // beyond struct_size: never read
  older.desc.struct_size = static_cast<uint32_t>(offsetof(mcon_library_entry_desc, has_up));
  ASSERT_EQ(mcon_library_add_entry(lib.get(), &older.desc, nullptr), MCON_OK) << last_message();

  const std::vector<uint8_t> bytes = save_bytes(lib.get());
  mcon_library opened = nullptr;
  ASSERT_EQ(mcon_library_open_memory(ctx_.get(), bytes.data(), bytes.size(), &opened), MCON_OK) << last_message();
  LibraryPtr reopened(opened);
  LibraryPtr merged = make_library(ctx_.get());
  ASSERT_EQ(mcon_library_merge(merged.get(), opened), MCON_OK) << last_message();
  for (mcon_library l : {lib.get(), opened, merged.get()}) {
    mcon_library_entry_info e[3];
    for (size_t i = 0; i < 3; ++i) {
      ASSERT_EQ(mcon_library_entry_info_init(&e[i]), MCON_OK);
      ASSERT_EQ(mcon_library_get_entry_info(l, i, &e[i]), MCON_OK) << last_message();
    }
    EXPECT_EQ(e[0].has_up, 0u);
    EXPECT_EQ(e[2].has_up, 0u);
    ASSERT_EQ(e[1].has_up, 1u);
    EXPECT_EQ(e[1].up[0], 0.0);
    EXPECT_EQ(e[1].up[1], 2.5);
    EXPECT_EQ(e[1].up[2], -0.5);
  }
  // An info struct of the size before has_up (an older caller) is filled up to its size only.
  mcon_library_entry_info small;
  ASSERT_EQ(mcon_library_entry_info_init(&small), MCON_OK);
  small.struct_size = static_cast<uint32_t>(offsetof(mcon_library_entry_info, has_up));
  small.has_up = 7;
  ASSERT_EQ(mcon_library_get_entry_info(lib.get(), 1, &small), MCON_OK) << last_message();
  EXPECT_EQ(small.has_up, 7u);
  EXPECT_EQ(small.vertex_count, patch_info(patches_[1].get()).vertex_count);

  // Refused by name, the library unchanged: a zero vector and a non-finite one.
  up.desc.up[1] = 0;
  up.desc.up[2] = 0;
  EXPECT_EQ(mcon_library_add_entry(lib.get(), &up.desc, nullptr), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_message().find("desc.up is the zero vector"), std::string::npos) << last_message();
  up.desc.up[2] = std::nan("");
  EXPECT_EQ(mcon_library_add_entry(lib.get(), &up.desc, nullptr), MCON_ERROR_NON_FINITE);
  EXPECT_EQ(library_count(lib.get()), 3u);
}

TEST(RetrievalDescriptorNames, EveryBuiltInNameGivesItsCode) {
  uint32_t code = 0;
  ASSERT_EQ(mcon_retrieval_descriptor_from_name("curv9", &code), MCON_OK);
  EXPECT_EQ(code, static_cast<uint32_t>(MCON_RETRIEVAL_DESCRIPTOR_CURV9));
  ASSERT_EQ(mcon_retrieval_descriptor_from_name("hks", &code), MCON_OK);
  EXPECT_EQ(code, static_cast<uint32_t>(MCON_RETRIEVAL_DESCRIPTOR_HKS));
  ASSERT_EQ(mcon_retrieval_descriptor_from_name("wks", &code), MCON_OK);
  EXPECT_EQ(code, static_cast<uint32_t>(MCON_RETRIEVAL_DESCRIPTOR_WKS));
  EXPECT_EQ(mcon_retrieval_descriptor_from_name("HKS", &code), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_NE(last_message().find("curv9, hks or wks"), std::string::npos) << last_message();
  EXPECT_EQ(mcon_retrieval_descriptor_from_name(nullptr, &code), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(mcon_retrieval_descriptor_from_name("wks", nullptr), MCON_ERROR_NULL_POINTER);
}

TEST_F(LibraryTest, ResultsDoNotDependOnTheThreadCount) {
  std::vector<std::vector<uint8_t>> bytes;
  std::vector<std::vector<QueryResult>> results;
  for (uint32_t threads : {1u, 2u}) {
    ContextPtr ctx = make_context(threads);
    LibraryPtr lib = make_library(ctx.get());
    add_all(lib.get(), false);
    mcon_retrieval_options o = small_options();
    ASSERT_EQ(mcon_library_build_retrieval(lib.get(), &o), MCON_OK) << last_message();
    bytes.push_back(save_bytes(lib.get()));
    results.emplace_back();
    for (auto& p : patches_) results.back().push_back(query(lib.get(), p.get(), 6));
  }
  EXPECT_EQ(bytes[0], bytes[1]);
  ASSERT_EQ(results[0].size(), results[1].size());
  for (size_t i = 0; i < results[0].size(); ++i) EXPECT_EQ(results[0][i], results[1][i]);
}

struct ProgressLog {
  std::vector<double> fractions;
  int cancel_after = -1;  // calls before answering "cancel"; -1 never
};

int32_t on_progress(void* user, double fraction) {
  auto* log = static_cast<ProgressLog*>(user);
  log->fractions.push_back(fraction);
  return log->cancel_after >= 0 && static_cast<int>(log->fractions.size()) > log->cancel_after ? 0 : 1;
}

TEST_F(LibraryTest, ProgressAndCancelLeaveTheLibraryUnchanged) {
  LibraryPtr lib = built_library();
  const std::vector<uint8_t> before = save_bytes(lib.get());
  for (int cancel_after : {0, 3}) {
    ProgressLog log;
    log.cancel_after = cancel_after;
    mcon_retrieval_options o = small_options(8);
    o.rings = 2;
    o.progress = on_progress;
    o.progress_user_data = &log;
    EXPECT_EQ(mcon_library_build_retrieval(lib.get(), &o), MCON_ERROR_CANCELLED);
    EXPECT_FALSE(log.fractions.empty());
    EXPECT_EQ(save_bytes(lib.get()), before) << "cancel after " << cancel_after;
  }
  ProgressLog log;
  mcon_retrieval_options o = small_options(8);
  o.progress = on_progress;
  o.progress_user_data = &log;
  ASSERT_EQ(mcon_library_build_retrieval(lib.get(), &o), MCON_OK) << last_message();
  ASSERT_GE(log.fractions.size(), 3u);
  for (size_t i = 1; i < log.fractions.size(); ++i) EXPECT_GE(log.fractions[i], log.fractions[i - 1]);
  EXPECT_EQ(log.fractions.back(), 1.0);
  EXPECT_EQ(library_info(lib.get()).vocabulary_size, 8u);
}

}  // namespace

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include <tbb/task_arena.h>

#include "base/counter_rng.h"
#include "base/error.h"
#include "retrieval/retrieval_index.h"
#include "test_status.h"

using namespace mcon;
using mcon::test::status_of;

namespace {

std::vector<float> random_histograms(std::size_t count, std::size_t length, std::uint64_t seed) {
  std::vector<float> h(count * length);
  for (std::size_t i = 0; i < h.size(); ++i) h[i] = static_cast<float>(counter_uniform(seed, 0, i));
  return h;
}

// Reference: every distance in double, full sort by (distance, index).
std::vector<std::size_t> brute_force(const std::vector<float>& entries, std::size_t length, const float* query,
                                     std::size_t n, std::vector<double>* distances = nullptr) {
  const std::size_t count = entries.size() / length;
  std::vector<double> d(count);
  for (std::size_t e = 0; e < count; ++e)
    for (std::size_t i = 0; i < length; ++i) d[e] += std::abs(static_cast<double>(entries[e * length + i]) - query[i]);
  std::vector<std::size_t> order(count);
  for (std::size_t e = 0; e < count; ++e) order[e] = e;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return d[a] < d[b]; });
  order.resize(std::min(n, count));
  if (distances) *distances = d;
  return order;
}

}  // namespace

TEST(RetrievalIndex, L1DistanceMatchesDefinitionForAnyLength) {
  for (std::size_t length : {1u, 7u, 16u, 33u, 128u, 515u}) {
    const std::vector<float> a = random_histograms(1, length, 1), b = random_histograms(1, length, 2);
    double ref = 0;
    for (std::size_t i = 0; i < length; ++i) ref += std::abs(static_cast<double>(a[i]) - b[i]);
    EXPECT_NEAR(l1_distance(a.data(), b.data(), length), ref, 1e-5 * ref) << "length " << length;
    EXPECT_EQ(l1_distance(a.data(), a.data(), length), 0.0f);
  }
}

TEST(RetrievalIndex, TopNIsExactAgainstBruteForce) {
  // Several chunks (2048 entries each) plus a partial one.
  const std::size_t count = 5000, length = 128;
  const std::vector<float> entries = random_histograms(count, length, 11);
  for (std::uint64_t q = 0; q < 5; ++q) {
    const std::vector<float> query = random_histograms(1, length, 100 + q);
    for (std::size_t n : {1u, 10u, 100u}) {
      std::vector<double> ref_d;
      const std::vector<std::size_t> ref = brute_force(entries, length, query.data(), n, &ref_d);
      const std::vector<RetrievalHit> hits = top_n_l1(entries.data(), count, length, query.data(), n);
      ASSERT_EQ(hits.size(), n);
      for (std::size_t i = 0; i < n; ++i) {
        EXPECT_EQ(hits[i].entry, ref[i]) << "query " << q << " rank " << i;
        EXPECT_NEAR(hits[i].distance, ref_d[hits[i].entry], 1e-4);
        if (i > 0) {
          EXPECT_LE(hits[i - 1].distance, hits[i].distance);
        }
      }
    }
  }
  // n beyond the size: everything, sorted.
  const std::vector<float> query = random_histograms(1, length, 7);
  EXPECT_EQ(top_n_l1(entries.data(), 50, length, query.data(), 1000).size(), 50u);
  EXPECT_TRUE(top_n_l1(entries.data(), count, length, query.data(), 0).empty());
  EXPECT_TRUE(top_n_l1(nullptr, 0, length, query.data(), 5).empty());
}

TEST(RetrievalIndex, TiesGoToTheLowerEntryOnAnyThreadCount) {
  // 6000 entries in 6 repeated groups of 1000 distinct histograms: every distance occurs 6 times,
  // spread over different chunks.
  const std::size_t length = 32, distinct = 1000;
  const std::vector<float> base = random_histograms(distinct, length, 5);
  RetrievalIndex index(length);
  for (int copy = 0; copy < 6; ++copy)
    for (std::size_t e = 0; e < distinct; ++e)
      index.add(std::vector<float>(base.begin() + static_cast<std::ptrdiff_t>(e * length),
                                   base.begin() + static_cast<std::ptrdiff_t>((e + 1) * length)));
  ASSERT_EQ(index.size(), 6000u);
  const std::vector<float> query = random_histograms(1, length, 77);
  std::vector<RetrievalHit> r1, r2, r8;
  tbb::task_arena(1).execute([&] { r1 = index.query(query, 30); });
  tbb::task_arena(2).execute([&] { r2 = index.query(query, 30); });
  tbb::task_arena(8).execute([&] { r8 = index.query(query, 30); });
  ASSERT_EQ(r1.size(), 30u);
  for (std::size_t i = 0; i < 30; ++i) {
    // Groups of six equal distances, entries ascending within a group: e, e+1000, ..., e+5000.
    EXPECT_EQ(r1[i].entry % distinct, r1[i - i % 6].entry);
    EXPECT_EQ(r1[i].entry / distinct, i % 6);
    EXPECT_EQ(r1[i].distance, r1[i - i % 6].distance);
    EXPECT_EQ(r2[i].entry, r1[i].entry);
    EXPECT_EQ(r8[i].entry, r1[i].entry);
    EXPECT_EQ(r2[i].distance, r1[i].distance);
    EXPECT_EQ(r8[i].distance, r1[i].distance);
  }
}

TEST(RetrievalIndex, NaNEntriesRankLastAndBadInputIsRejected) {
  std::vector<float> entries = random_histograms(3, 4, 9);
  entries[5] = std::numeric_limits<float>::quiet_NaN();  // entry 1
  const std::vector<float> query(4, 0.5f);
  const auto hits = top_n_l1(entries.data(), 3, 4, query.data(), 3);
  ASSERT_EQ(hits.size(), 3u);
  EXPECT_EQ(hits[2].entry, 1u);
  EXPECT_TRUE(std::isinf(hits[2].distance));

  RetrievalIndex index(4);
  EXPECT_EQ(status_of([&] { index.add({1, 2, 3}); }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(status_of([&] { index.add({1, 2, 3, std::numeric_limits<float>::infinity()}); }), MCON_ERROR_NON_FINITE);
  EXPECT_EQ(index.size(), 0u);
  index.add({1, 2, 3, 4});
  EXPECT_EQ(status_of([&] { index.query({1, 2}, 1); }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(status_of([&] { index.query({1, 2, 3, std::nanf("")}, 1); }), MCON_ERROR_NON_FINITE);
  EXPECT_EQ(status_of([&] { top_n_l1(entries.data(), 3, 4, nullptr, 1); }), MCON_ERROR_NULL_POINTER);
  EXPECT_EQ(status_of([] { RetrievalIndex bad(0); }), MCON_ERROR_INVALID_ARGUMENT);
  EXPECT_EQ(index.query({1, 2, 3, 5}, 4).front().distance, 1.0f);
}

TEST(RetrievalIndex, ShortListsByInsertionEqualTheSelection) {
  // Up to 64 hits a chunk keeps its list by insertion, beyond by selection over every hit: the two
  // must give the same entries and distance bits, ties included (each histogram repeated 3 times).
  const std::size_t length = 128, distinct = 2500;
  const std::vector<float> base = random_histograms(distinct, length, 9);
  std::vector<float> entries;
  for (int copy = 0; copy < 3; ++copy) entries.insert(entries.end(), base.begin(), base.end());
  const std::size_t count = entries.size() / length;
  for (std::uint64_t q = 0; q < 3; ++q) {
    const std::vector<float> query = random_histograms(1, length, 300 + q);
    const std::vector<RetrievalHit> wide = top_n_l1(entries.data(), count, length, query.data(), 65);
    for (std::size_t n : {1u, 3u, 10u, 64u}) {
      const std::vector<RetrievalHit> shortlist = top_n_l1(entries.data(), count, length, query.data(), n);
      ASSERT_EQ(shortlist.size(), n);
      for (std::size_t i = 0; i < n; ++i) {
        EXPECT_EQ(shortlist[i].entry, wide[i].entry) << "n " << n << " rank " << i;
        EXPECT_EQ(std::memcmp(&shortlist[i].distance, &wide[i].distance, sizeof(float)), 0);
      }
    }
  }
}

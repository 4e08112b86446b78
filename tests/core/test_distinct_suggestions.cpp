#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "base/error.h"
#include "library/distinct_suggestions.h"

using namespace mcon;

namespace {

std::vector<MacroConstraint> labelled(const std::vector<std::string>& labels) {
  std::vector<MacroConstraint> out(labels.size());
  for (std::size_t i = 0; i < labels.size(); ++i) out[i].class_label = labels[i];
  return out;
}

}  // namespace

TEST(DistinctSuggestions, SideSuffixesAndCaseDoNotMakeANewGroup) {
  EXPECT_EQ(suggestion_group("eye_l"), "eye");
  EXPECT_EQ(suggestion_group("Eye_R"), "eye");
  EXPECT_EQ(suggestion_group("hand.left"), "hand");
  EXPECT_EQ(suggestion_group("foot right"), "foot");
  EXPECT_EQ(suggestion_group("nose"), "nose");
  EXPECT_EQ(suggestion_group("_l"), "_l");  // nothing left but the suffix: kept as it is
  EXPECT_EQ(suggestion_group(""), "");
}

// Five near-duplicate eyes (both sides) in front of a nose and an ear: the top 3 is eye, nose,
// ear, the other eyes are the first suggestion's alternatives, best first.
TEST(DistinctSuggestions, NearDuplicatesCountOnceAndStayAvailable) {
  const auto entries = labelled({"eye_l", "eye_r", "nose", "eye_l", "ear_r", "", "", "eye_r"});
  const std::vector<RetrievalHit> ranked = {{0, 1.0f}, {1, 1.1f}, {3, 1.2f}, {7, 1.3f}, {2, 2.0f},
                                            {5, 2.5f}, {6, 2.6f}, {4, 3.0f}};
  const auto s = distinct_suggestions(ranked, entries, 3);
  ASSERT_EQ(s.size(), 3u);
  EXPECT_EQ(s[0].entry, 0u);
  EXPECT_EQ(s[0].alternatives, (std::vector<std::size_t>{1, 3, 7}));
  EXPECT_EQ(s[1].entry, 2u);
  EXPECT_EQ(s[2].entry, 5u);  // unlabelled entries are their own groups
  EXPECT_TRUE(s[2].alternatives.empty());
  double sum = 0;
  for (const auto& x : s) sum += x.confidence;
  EXPECT_NEAR(sum, 1.0, 1e-12);
  EXPECT_GT(s[0].confidence, s[1].confidence);
  EXPECT_GT(s[1].confidence, s[2].confidence);
  // exp(-(d - d1) / d1): 1, e^-1, e^-1.5 normalized.
  const double z = 1 + std::exp(-1.0) + std::exp(-1.5);
  EXPECT_NEAR(s[0].confidence, 1 / z, 1e-6);
}

TEST(DistinctSuggestions, AnExactMatchIsCertainAndBadArgumentsAreRejected) {
  const auto entries = labelled({"nose", "ear"});
  const auto s = distinct_suggestions({{1, 0.0f}, {0, 0.4f}}, entries, 5);
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[0].confidence, 1.0);
  EXPECT_EQ(s[1].confidence, 0.0);
  EXPECT_THROW(distinct_suggestions({{0, 1.0f}}, entries, 0), Error);
  EXPECT_THROW(distinct_suggestions({{9, 1.0f}}, entries, 1), Error);
}

#include "bow/bow_database.h"

#include <gtest/gtest.h>

namespace semchain::bow {
namespace {

TEST(BowDatabaseTest, InvertedIndexListsEntriesPerWord) {
  BowDatabase database(6, 1);
  EXPECT_EQ(database.Add({{0, 1.0}, {2, 1.0}}), 0);
  EXPECT_EQ(database.Add({{2, 3.0}, {5, 1.0}}), 1);
  // Entries are stored L1-normalised.
  EXPECT_EQ(database.postings(2), (std::vector<std::pair<int, double>>{{0, 0.5}, {1, 0.75}}));
  EXPECT_TRUE(database.postings(1).empty());
  EXPECT_EQ(database.size(), 2);
}

TEST(BowDatabaseTest, QueryRanksByL1ScoreAndKeepsTopN) {
  BowDatabase database(10, 1);
  database.Add({{0, 0.5}, {1, 0.5}});              // s = 0.5 against the query below
  database.Add({{0, 0.25}, {1, 0.25}, {2, 0.5}});  // s = 1 (identical)
  database.Add({{7, 1.0}});                        // no common word: not returned
  database.Add({{2, 1.0}});                        // s = 0.5
  const BowVector query = {{0, 0.25}, {1, 0.25}, {2, 0.5}};
  const std::vector<BowMatch> all = database.Query(query, 10);
  ASSERT_EQ(all.size(), 3u);
  EXPECT_EQ(all[0].entry, 1);
  EXPECT_NEAR(all[0].score, 1.0, 1e-12);
  EXPECT_EQ(all[1].entry, 0);  // a tie with entry 3: the lower id first
  EXPECT_NEAR(all[1].score, 0.5, 1e-12);
  EXPECT_EQ(all[2].entry, 3);
  EXPECT_NEAR(all[2].score, 0.5, 1e-12);
  // The inverted-index score equals L1Score for every entry.
  for (const BowMatch& match : all) {
    EXPECT_NEAR(match.score, L1Score(query, database.vector(match.entry)), 1e-12);
  }
  const std::vector<BowMatch> top = database.Query(query, 1);
  ASSERT_EQ(top.size(), 1u);
  EXPECT_EQ(top[0].entry, 1);
}

TEST(BowDatabaseTest, KeepsTheDirectIndex) {
  BowDatabase database(4, 2);
  FeatureVector features = {{3, {0, 2}}, {5, {1}}};
  database.Add({{1, 1.0}}, features);
  EXPECT_EQ(database.features(0), features);
  EXPECT_EQ(database.direct_index_level(), 2);
}

}  // namespace
}  // namespace semchain::bow

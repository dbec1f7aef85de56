// `semchain bench reloc` in small (issue 5): map two_similar_rooms from a simulated mapping run
// (SLAM + semantic mapping), then relocalize from a few random starts in room A. The semantic
// methods must find the robot in every trial, and the first pre-localization must be close.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>

#include "eval/reloc_benchmark.h"

namespace semchain {
namespace {

namespace fs = std::filesystem;

TEST(RelocBenchmarkTest, SemanticMethodsRelocalizeInLookAlikeRooms) {
  const fs::path world = fs::path(SEMCHAIN_SOURCE_DIR) / "worlds" / "two_similar_rooms.yaml";
  eval::RelocBenchmarkOptions options;
  options.trials = 4;
  options.seed = 7;
  options.methods = {"semantic-amcl", "semantic-scanmatch"};
  options.work_dir =
      fs::temp_directory_path() / ("semchain_reloc_e2e_" + std::to_string(::getpid()));
  const Result<eval::RelocBenchmarkResult> result = eval::RunRelocBenchmark(world, world, options);
  ASSERT_TRUE(result.ok()) << result.status().message();
  EXPECT_LE(result->map_ate_m, 0.05);
  for (const std::string& method : options.methods) {
    const eval::RelocMethodStats& stats = result->methods.at(method);
    EXPECT_EQ(stats.trials, 4);
    EXPECT_EQ(stats.successes, 4) << method;
    EXPECT_LE(stats.mean_error_m, 0.1) << method;
    EXPECT_LE(stats.mean_time_s, 10.0) << method;
  }
  const eval::RelocMethodStats& amcl = result->methods.at("semantic-amcl");
  ASSERT_GT(amcl.prelocalized, 0);
  EXPECT_LE(amcl.prelocalization_error_x_m, 0.15);
  EXPECT_LE(amcl.prelocalization_error_y_m, 0.15);
  // The scan matcher searches only around the hypotheses: about one match per trial.
  EXPECT_LE(result->methods.at("semantic-scanmatch").mean_iterations, 2.0);
}

}  // namespace
}  // namespace semchain
